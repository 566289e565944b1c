/* trace_chrome.c — Chrome Trace Event JSON (the "JSON Object Format" of
 * the Trace Event Format document; Perfetto and chrome://tracing read it).
 *
 * One process (pid 0, "pgsim"); one thread per node (tid = node id, the
 * processor id on a machine, named with an "M" thread_name event and
 * sorted by id with thread_sort_index on first sight).  A span is an "X"
 * complete event; a message is a flow: a zero-length "X" slice "send" on
 * the source with an "s" event, and "recv" on the destination with an "f"
 * event (binding point "e"), both carrying the same id; a mark (frame
 * boundary) is a global instant "i"; the counters derived from flows
 * ("messages in flight", "bytes in flight") are "C" counter tracks; each
 * network link that carried a message is a counter track "link NAME"
 * (series "B/s": its bandwidth use) of a second process, "network links"
 * (pid 1), and a link a message waited for at the packet rung also has
 * a track "queue NAME" (series "messages": messages waiting for it).
 * Timestamps are microseconds (doubles).  Events
 * are written as they come (the format needs no order), each one built
 * and printed by json-glib; only the fixed envelope around the event
 * array is literal text.
 */
#include "sim/output/json.h"
#include "sim/app/trace/trace_impl.h"

static void set_us(JsonBuilder *b, const char *key, SimTime t)
{
    js_set_num(b, key, (double)t / (double)SIM_US);
}

/* Opens an event object with its name, category, phase and thread. */
static JsonBuilder *event(const char *name, const char *cat, const char *ph,
                          uint32_t tid)
{
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "name", name);
    if (cat)
        js_set_str(b, "cat", cat);
    js_set_str(b, "ph", ph);
    js_set_int(b, "pid", 0);
    js_set_int(b, "tid", tid);
    return b;
}

/* Closes the event and appends it to the array in the file. */
static void emit(TrcWriter *w, JsonBuilder *b)
{
    json_builder_end_object(b);
    char *text = js_finish(b, FALSE);
    fprintf(w->f, ",\n%s", text);
    g_free(text);
}

/* A metadata event: args {key: string value} or {key: int value}. */
static void meta(TrcWriter *w, const char *what, uint32_t tid,
                 const char *key, const char *s, gint64 i)
{
    JsonBuilder *b = event(what, NULL, "M", tid);
    json_builder_set_member_name(b, "args");
    json_builder_begin_object(b);
    if (s)
        js_set_str(b, key, s);
    else
        js_set_int(b, key, i);
    json_builder_end_object(b);
    emit(w, b);
}

static void on_node(TrcWriter *w, uint32_t node)
{
    meta(w, "thread_name", node, "name",
         g_hash_table_lookup(w->nodes, GUINT_TO_POINTER(node + 1)), 0);
    meta(w, "thread_sort_index", node, "sort_index", NULL, node);
}

static void on_span(TrcWriter *w, uint32_t node, const char *phase,
                    SimTime start, SimTime end)
{
    JsonBuilder *b = event(phase, "phase", "X", node);
    set_us(b, "ts", start);
    set_us(b, "dur", end - start);
    emit(w, b);
}

static void flow_end(TrcWriter *w, const char *ph, uint32_t node, SimTime t,
                     uint64_t id, uint64_t bytes)
{
    gboolean send = ph[0] == 's';
    JsonBuilder *b = event(send ? "send" : "recv", "msg", "X", node);
    set_us(b, "ts", t);
    js_set_int(b, "dur", 0);
    json_builder_set_member_name(b, "args");
    json_builder_begin_object(b);
    js_set_int(b, "bytes", (gint64)bytes);
    json_builder_end_object(b);
    emit(w, b);
    b = event("message", "msg", ph, node);
    js_set_int(b, "id", (gint64)id);
    if (!send)
        js_set_str(b, "bp", "e");
    set_us(b, "ts", t);
    emit(w, b);
}

static void on_flow(TrcWriter *w, uint32_t src, uint32_t dst, uint64_t bytes,
                    SimTime sent, SimTime arrived, uint64_t id)
{
    flow_end(w, "s", src, sent, id, bytes);
    flow_end(w, "f", dst, arrived, id, bytes);
}

static void on_mark(TrcWriter *w, const char *name, SimTime t)
{
    JsonBuilder *b = event(name, "mark", "i", 0);
    js_set_str(b, "s", "g");
    set_us(b, "ts", t);
    emit(w, b);
}

/* A "C" event: the track is the counter's name, the series its unit. */
static void on_counter(TrcWriter *w, int which, SimTime t, double value)
{
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "name", trc_counter_names[which]);
    js_set_str(b, "ph", "C");
    js_set_int(b, "pid", 0);
    set_us(b, "ts", t);
    json_builder_set_member_name(b, "args");
    json_builder_begin_object(b);
    js_set_num(b, trc_counter_units[which], value);
    json_builder_end_object(b);
    emit(w, b);
}

/* The process_name metadata event of process pid. */
static char *process_name(int pid, const char *name)
{
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "name", "process_name");
    js_set_str(b, "ph", "M");
    js_set_int(b, "pid", pid);
    json_builder_set_member_name(b, "args");
    json_builder_begin_object(b);
    js_set_str(b, "name", name);
    json_builder_end_object(b);
    json_builder_end_object(b);
    return js_finish(b, FALSE);
}

static void on_link_counter(TrcWriter *w, guint link, int which, SimTime t,
                            double value)
{
    gboolean bw = which == TRC_LINK_BW;
    if (!w->links_begun) {
        char *text = process_name(1, "network links");
        fprintf(w->f, ",\n%s", text);
        g_free(text);
        w->links_begun = TRUE;
    }
    char *name = g_strconcat(bw ? "link " : "queue ",
                             w->link_names->pdata[link], NULL);
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "name", name);
    js_set_str(b, "ph", "C");
    js_set_int(b, "pid", 1);
    set_us(b, "ts", t);
    json_builder_set_member_name(b, "args");
    json_builder_begin_object(b);
    js_set_num(b, bw ? "B/s" : "messages", value);
    json_builder_end_object(b);
    emit(w, b);
    g_free(name);
}

static void begin(TrcWriter *w)
{
    char *text = process_name(0, "pgsim");
    fprintf(w->f, "{\"traceEvents\":[\n%s", text);
    g_free(text);
}

static void end(TrcWriter *w)
{
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "generator", "pgsim");
    js_set_int(b, "events", (gint64)w->events);
    js_set_int(b, "cap", (gint64)w->cap);
    js_set_bool(b, "truncated", w->truncated);
    json_builder_end_object(b);
    char *other = js_finish(b, FALSE);
    fprintf(w->f, "\n],\"displayTimeUnit\":\"ns\",\"otherData\":%s}\n",
            other);
    g_free(other);
}

const TrcFormat trc_chrome = {begin,   on_node,    on_span,         on_flow,
                              on_mark, on_counter, on_link_counter, end};
