/* trace_chrome.c — Chrome Trace Event JSON (the "JSON Object Format" of
 * the Trace Event Format document; Perfetto and chrome://tracing read it).
 *
 * One process (pid 0, "pgsim"); one thread per node (tid = node id, the
 * processor id on a machine, named with an "M" thread_name event and
 * sorted by id with thread_sort_index on first sight).  A span is an "X"
 * complete event; a message is a flow: a zero-length "X" slice "send" on
 * the source with an "s" event, and "recv" on the destination with an "f"
 * event (binding point "e"), both carrying the same id; a mark is a
 * global instant "i".  Timestamps are microseconds with picosecond
 * digits.  Events are written as they come (the format needs no order).
 */
#include "sim/output/json.h"
#include "sim/app/trace/trace_impl.h"

static void put_us(FILE *f, const char *key, SimTime t)
{
    fprintf(f, ",\"%s\":%" G_GUINT64_FORMAT ".%06u", key, t / SIM_US,
            (unsigned)(t % SIM_US));
}

static void put_name(FILE *f, const char *name)
{
    GString *s = g_string_new(NULL);
    json_put_str(s, name);
    fputs(s->str, f);
    g_string_free(s, TRUE);
}

static void node_meta(TrcWriter *w, uint32_t node, const char *name)
{
    if (!trc_new_node(w, node, name))
        return;
    fprintf(w->f,
            ",\n{\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":0,"
            "\"tid\":%u,\"args\":{\"name\":",
            node);
    put_name(w->f, g_hash_table_lookup(w->nodes, GUINT_TO_POINTER(node + 1)));
    fprintf(w->f,
            "}},\n{\"name\":\"thread_sort_index\",\"ph\":\"M\",\"pid\":0,"
            "\"tid\":%u,\"args\":{\"sort_index\":%u}}",
            node, node);
}

static void on_span(SimTrace *tr, uint32_t node, const char *node_name,
                    const char *phase, SimTime start, SimTime end)
{
    TrcWriter *w = tr->state;
    if (!trc_admit(w, end))
        return;
    node_meta(w, node, node_name);
    fputs(",\n{\"name\":", w->f);
    put_name(w->f, phase);
    fprintf(w->f, ",\"cat\":\"phase\",\"ph\":\"X\",\"pid\":0,\"tid\":%u", node);
    put_us(w->f, "ts", start);
    put_us(w->f, "dur", end - start);
    fputc('}', w->f);
}

static void flow_end(TrcWriter *w, const char *ph, uint32_t node, SimTime t,
                     uint64_t id, uint64_t bytes)
{
    gboolean send = ph[0] == 's';
    fprintf(w->f,
            ",\n{\"name\":\"%s\",\"cat\":\"msg\",\"ph\":\"X\","
            "\"pid\":0,\"tid\":%u",
            send ? "send" : "recv", node);
    put_us(w->f, "ts", t);
    fprintf(w->f, ",\"dur\":0,\"args\":{\"bytes\":%" G_GUINT64_FORMAT "}}",
            bytes);
    fprintf(w->f,
            ",\n{\"name\":\"message\",\"cat\":\"msg\",\"ph\":\"%s\","
            "\"pid\":0,\"tid\":%u,\"id\":%" G_GUINT64_FORMAT "%s",
            ph, node, id, send ? "" : ",\"bp\":\"e\"");
    put_us(w->f, "ts", t);
    fputc('}', w->f);
}

static void on_flow(SimTrace *tr, uint32_t src, const char *src_name,
                    uint32_t dst, const char *dst_name, uint64_t bytes,
                    SimTime sent, SimTime arrived)
{
    TrcWriter *w = tr->state;
    if (!trc_admit(w, arrived))
        return;
    node_meta(w, src, src_name);
    node_meta(w, dst, dst_name);
    uint64_t id = ++w->next_flow;
    flow_end(w, "s", src, sent, id, bytes);
    flow_end(w, "f", dst, arrived, id, bytes);
}

static void instant(TrcWriter *w, const char *name, SimTime t)
{
    fputs(",\n{\"name\":", w->f);
    put_name(w->f, name);
    fputs(",\"cat\":\"mark\",\"ph\":\"i\",\"s\":\"g\",\"pid\":0,\"tid\":0",
          w->f);
    put_us(w->f, "ts", t);
    fputc('}', w->f);
}

static void on_mark(SimTrace *tr, const char *name, SimTime t)
{
    TrcWriter *w = tr->state;
    if (trc_admit(w, t))
        instant(w, name, t);
}

static void begin(TrcWriter *w)
{
    fputs("{\"traceEvents\":[\n{\"name\":\"process_name\",\"ph\":\"M\","
          "\"pid\":0,\"args\":{\"name\":\"pgsim\"}}",
          w->f);
}

static void cap_note(TrcWriter *w, SimTime t)
{
    char *msg = g_strdup_printf("trace truncated: cap of %" G_GUINT64_FORMAT
                                " events reached; later events are not "
                                "recorded",
                                w->cap);
    instant(w, msg, t);
    g_free(msg);
}

static void end(TrcWriter *w)
{
    fprintf(w->f,
            "\n],\"displayTimeUnit\":\"ns\",\"otherData\":{"
            "\"generator\":\"pgsim\",\"events\":%" G_GUINT64_FORMAT
            ",\"cap\":%" G_GUINT64_FORMAT ",\"truncated\":%s}}\n",
            w->events, w->cap, w->truncated ? "true" : "false");
}

static const SimTraceOps chrome_ops = {on_span, on_flow, on_mark};

const TrcFormat trc_chrome = {begin, cap_note, end, &chrome_ops};
