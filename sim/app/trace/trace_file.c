/* trace_file.c — opening, capping and closing trace files, and the one
 * SimTraceOps every format shares.
 *
 * Invariants: at most `cap` events are recorded; after the cap the note
 * is written exactly once and every hook is a no-op.  The file is written
 * as <path>.tmp and renamed to <path> on a successful close, so a reader
 * never sees half a trace under the final name.  O(1) per event; the
 * counters derived from flows (messages and bytes in flight) are sorted
 * on close: O(f log f) for f recorded flows.  Link load: a message adds
 * its mean rate, bytes / (arrival - send), to every link of its route
 * while in flight (SimGrid's "bandwidth_used" for a flow at a constant
 * rate); links are recorded only for messages within the cap, so memory
 * stays within cap x route length; sorted on close per link.  At the
 * packet rung the transport reports each hop's holds instead (each
 * packet's [take, release) on a link, sim/core/trace.h): a link that
 * reports holds gets its use from them, bytes / (release - take) while
 * held, and ignores the route average; contiguous holds at one rate are
 * merged as they come (holds of a link arrive in time order), so a long
 * message costs one step per link, not one per packet.  Queue depth: a
 * message whose head waits for a link counts 1 on the link's queue track
 * over the wait.
 */
#include "sim/app/trace/trace_impl.h"
#include "sim/core/memlimit.h"
#include <errno.h>
#include <stdio.h>
#include <string.h>

static const TrcFormat *format_for(const char *path)
{
    if (g_str_has_suffix(path, ".json"))
        return &trc_chrome;
    if (g_str_has_suffix(path, ".paje") || g_str_has_suffix(path, ".trace"))
        return &trc_paje;
    return NULL;
}

typedef struct {
    SimTime t;
    uint64_t seq;
    int64_t bytes; /* +bytes at a send, -bytes at an arrival */
} TrcDelta;

typedef struct {
    SimTime t;
    uint64_t seq;
    guint link;
    int which; /* TRC_LINK_BW or TRC_LINK_QUEUE */
    int sign;  /* +1 when it starts, -1 when it ends */
    double rate; /* B/s (TRC_LINK_BW) */
} TrcLinkDelta;

static const SimTraceOps trc_ops; /* below: the hooks every format shares */

/* Memory one recorded event keeps until the file is closed, about: a
 * buffered Paje line, or a message's in-flight deltas and its links'. */
#define TRC_EVENT_BYTES 256.0

/* A --trace-cap whose events would not fit the memory limit is an input
 * error now, not an abort part way through the run. */
static gboolean cap_fits(uint64_t cap, GError **err)
{
    char *what = g_strdup_printf("a cap of %" G_GUINT64_FORMAT " events", cap);
    gboolean ok = sim_mem_check((double)cap * TRC_EVENT_BYTES, "--trace-cap",
                                what, err);
    g_free(what);
    return ok;
}

SimTrace *trc_open(const char *path, uint64_t max_events, GError **err)
{
    const TrcFormat *fmt = format_for(path);
    if (!fmt) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "--trace: found '%s', expected a file ending in .json "
                    "(Chrome/Perfetto) or .paje (ViTE)",
                    path);
        return NULL;
    }
    if (max_events && !cap_fits(max_events, err))
        return NULL; /* before the .tmp file exists */
    TrcWriter *w = g_new0(TrcWriter, 1);
    w->tmp = g_strconcat(path, ".tmp", NULL);
    w->f = fopen(w->tmp, "w");
    if (!w->f) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot write: %s",
                    w->tmp, g_strerror(errno));
        g_free(w->tmp);
        g_free(w);
        return NULL;
    }
    w->fmt = fmt;
    w->path = g_strdup(path);
    w->cap = max_events ? max_events : TRC_DEFAULT_CAP;
    w->nodes = g_hash_table_new_full(NULL, NULL, NULL, g_free);
    w->default_named = g_hash_table_new(NULL, NULL);
    w->deltas = g_array_new(FALSE, FALSE, sizeof(TrcDelta));
    w->link_index = g_hash_table_new_full(g_int64_hash, g_int64_equal,
                                          g_free, NULL);
    w->link_names = g_ptr_array_new_with_free_func(g_free);
    w->link_deltas = g_array_new(FALSE, FALSE, sizeof(TrcLinkDelta));
    w->link_holds = g_array_new(FALSE, TRUE, sizeof(TrcHold));
    w->trace.ops = &trc_ops;
    w->trace.state = w;
    fmt->begin(w);
    return &w->trace;
}

const char *const trc_counter_names[TRC_N_COUNTERS] = {"messages in flight",
                                                       "bytes in flight"};
const char *const trc_counter_units[TRC_N_COUNTERS] = {"messages", "B"};

/* Counts one event; FALSE once the cap is reached (then the note is
 * written once). */
static gboolean trc_admit(TrcWriter *w, SimTime t)
{
    if (w->truncated)
        return FALSE;
    if (w->events < w->cap) {
        w->events++;
        return TRUE;
    }
    w->truncated = TRUE;
    char *msg = g_strdup_printf("trace truncated: cap of %" G_GUINT64_FORMAT
                                " events reached; later events are not "
                                "recorded",
                                w->cap);
    w->fmt->mark(w, msg, t);
    g_free(msg);
    fprintf(stderr,
            "pgsim: trace %s: cap of %" G_GUINT64_FORMAT
            " events reached at %.6f ms; later events are not "
            "recorded\n",
            w->path, w->cap, sim_time_to_ms(t));
    return FALSE;
}

/* TRUE the first time a node id is seen, and when a node first seen
 * without a name (NULL: "node<id>") gets one; the name is remembered. */
static gboolean trc_new_node(TrcWriter *w, uint32_t node, const char *name)
{
    gpointer key = GUINT_TO_POINTER(node + 1);
    const char *old = g_hash_table_lookup(w->nodes, key);
    /* a flow knows only the id; a later span may bring the real name */
    if (old && (!name || strcmp(old, name) == 0 ||
                !g_hash_table_contains(w->default_named, key)))
        return FALSE;
    g_hash_table_insert(
        w->nodes, key, name ? g_strdup(name) : g_strdup_printf("node%u", node));
    if (name)
        g_hash_table_remove(w->default_named, key);
    else
        g_hash_table_add(w->default_named, key);
    return TRUE;
}

static void see_node(TrcWriter *w, uint32_t node, const char *name)
{
    if (trc_new_node(w, node, name))
        w->fmt->node(w, node);
}

static void on_span(SimTrace *tr, uint32_t node, const char *node_name,
                    const char *phase, SimTime start, SimTime end)
{
    TrcWriter *w = tr->state;
    if (!trc_admit(w, end))
        return;
    see_node(w, node, node_name);
    w->fmt->span(w, node, phase, start, end);
}

static void add_delta(TrcWriter *w, SimTime t, int64_t bytes)
{
    TrcDelta d = {t, w->deltas->len, bytes};
    g_array_append_val(w->deltas, d);
}

static void on_flow(SimTrace *tr, uint32_t src, const char *src_name,
                    uint32_t dst, const char *dst_name, uint64_t bytes,
                    SimTime sent, SimTime arrived)
{
    TrcWriter *w = tr->state;
    if (!trc_admit(w, arrived))
        return;
    see_node(w, src, src_name);
    see_node(w, dst, dst_name);
    w->fmt->flow(w, src, dst, bytes, sent, arrived, ++w->next_flow);
    add_delta(w, sent, (int64_t)bytes);
    add_delta(w, arrived, -(int64_t)bytes);
}

static void on_mark(SimTrace *tr, const char *name, SimTime t)
{
    TrcWriter *w = tr->state;
    if (trc_admit(w, t))
        w->fmt->mark(w, name, t);
}

/* The link's index, given on first sight. */
static guint link_index(TrcWriter *w, uint64_t id, const char *name)
{
    gpointer v = g_hash_table_lookup(w->link_index, &id);
    if (v)
        return GPOINTER_TO_UINT(v) - 1;
    guint i = w->link_names->len;
    uint64_t *key = g_new(uint64_t, 1);
    *key = id;
    g_hash_table_insert(w->link_index, key, GUINT_TO_POINTER(i + 1));
    g_ptr_array_add(w->link_names, g_strdup(name));
    g_array_set_size(w->link_holds, i + 1);
    return i;
}

static void add_link_delta(TrcWriter *w, SimTime t, guint link, int which,
                           int sign, double rate)
{
    TrcLinkDelta d = {t, w->link_deltas->len, link, which, sign, rate};
    g_array_append_val(w->link_deltas, d);
}

/* Adds a use of `rate` over [from, to) to the link's bandwidth track. */
static void add_use(TrcWriter *w, guint link, SimTime from, SimTime to,
                    double rate)
{
    add_link_delta(w, from, link, TRC_LINK_BW, 1, rate);
    add_link_delta(w, to, link, TRC_LINK_BW, -1, rate);
}

static TrcHold *hold_of(TrcWriter *w, guint link)
{
    return &g_array_index(w->link_holds, TrcHold, link);
}

/* Turns the link's open hold, if any, into deltas. */
static void flush_hold(TrcWriter *w, guint link)
{
    TrcHold *h = hold_of(w, link);
    if (h->end > h->start)
        add_use(w, link, h->start, h->end, h->rate);
    h->start = h->end = 0;
}

/* The index of a link seen over [from, to), FALSE for an empty interval
 * or past the cap: link reports are not events of their own, kept while
 * their messages are. */
static gboolean link_at(TrcWriter *w, uint64_t link, const char *name,
                        SimTime from, SimTime to, guint *i)
{
    if (w->truncated || to <= from)
        return FALSE;
    *i = link_index(w, link, name);
    return TRUE;
}

static void on_link(SimTrace *tr, uint64_t link, const char *name,
                    uint64_t bytes, SimTime sent, SimTime arrived)
{
    guint i;
    TrcWriter *w = tr->state;
    if (!link_at(w, link, name, sent, arrived, &i) || hold_of(w, i)->held)
        return; /* its holds tell the truth */
    add_use(w, i, sent, arrived, (double)bytes / sim_time_to_s(arrived - sent));
}

/* A packet holds the link over [start, end): merged with the open hold
 * when it continues it at the same rate. */
static void on_hold(SimTrace *tr, uint64_t link, const char *name,
                    uint64_t bytes, SimTime start, SimTime end)
{
    guint i;
    TrcWriter *w = tr->state;
    if (!link_at(w, link, name, start, end, &i))
        return;
    TrcHold *h = hold_of(w, i);
    double rate = (double)bytes / sim_time_to_s(end - start);
    h->held = TRUE;
    if (h->end > h->start && h->end == start && h->rate == rate) {
        h->end = end;
        return;
    }
    flush_hold(w, i);
    *h = (TrcHold){start, end, rate, TRUE};
}

static void on_wait(SimTrace *tr, uint64_t link, const char *name,
                    SimTime from, SimTime to)
{
    guint i;
    TrcWriter *w = tr->state;
    if (!link_at(w, link, name, from, to, &i))
        return;
    add_link_delta(w, from, i, TRC_LINK_QUEUE, 1, 0.0);
    add_link_delta(w, to, i, TRC_LINK_QUEUE, -1, 0.0);
}

static const SimTraceOps trc_ops = {on_span, on_flow, on_mark,
                                    on_link, on_hold, on_wait};

static gint by_time(gconstpointer a, gconstpointer b)
{
    const TrcDelta *x = a, *y = b;
    if (x->t != y->t)
        return x->t < y->t ? -1 : 1;
    return x->seq < y->seq ? -1 : x->seq > y->seq;
}

/* One sample per counter at every time the flows change them (after all
 * the changes at that time), starting from 0 at time 0. */
static void write_counters(TrcWriter *w)
{
    if (!w->deltas->len)
        return;
    g_array_sort(w->deltas, by_time);
    for (int c = 0; c < TRC_N_COUNTERS; c++)
        w->fmt->counter(w, c, 0, 0.0);
    int64_t msgs = 0, bytes = 0;
    for (guint i = 0; i < w->deltas->len; i++) {
        const TrcDelta *d = &g_array_index(w->deltas, TrcDelta, i);
        msgs += d->bytes >= 0 ? 1 : -1;
        bytes += d->bytes;
        if (i + 1 < w->deltas->len &&
            g_array_index(w->deltas, TrcDelta, i + 1).t == d->t)
            continue;
        w->fmt->counter(w, TRC_MSGS_IN_FLIGHT, d->t, (double)msgs);
        w->fmt->counter(w, TRC_BYTES_IN_FLIGHT, d->t, (double)bytes);
    }
}

static gint by_link_time(gconstpointer a, gconstpointer b)
{
    const TrcLinkDelta *x = a, *y = b;
    if (x->link != y->link)
        return x->link < y->link ? -1 : 1;
    if (x->which != y->which)
        return x->which < y->which ? -1 : 1;
    if (x->t != y->t)
        return x->t < y->t ? -1 : 1;
    return x->seq < y->seq ? -1 : x->seq > y->seq;
}

static gboolean same_track(const TrcLinkDelta *x, const TrcLinkDelta *y)
{
    return x->link == y->link && x->which == y->which;
}

/* Per link and track: 0 at time 0, then one sample at every time its
 * messages change it (the use is exactly 0 when nothing holds the link,
 * free of rounding; the queue is a count of waiting messages). */
static void write_link_counters(TrcWriter *w)
{
    GArray *d = w->link_deltas;
    for (guint l = 0; l < w->link_holds->len; l++)
        flush_hold(w, l);
    g_array_sort(d, by_link_time);
    double sum = 0;
    int n = 0;
    for (guint i = 0; i < d->len; i++) {
        const TrcLinkDelta *x = &g_array_index(d, TrcLinkDelta, i);
        if (i == 0 || !same_track(x - 1, x)) {
            sum = 0;
            n = 0;
            w->fmt->link_counter(w, x->link, x->which, 0, 0.0);
        }
        sum += x->sign * x->rate;
        n += x->sign;
        if (i + 1 < d->len && same_track(x + 1, x) && x[1].t == x->t)
            continue;
        double v = x->which == TRC_LINK_QUEUE ? n : n ? sum : 0.0;
        w->fmt->link_counter(w, x->link, x->which, x->t, v);
    }
}

uint64_t trc_events(const SimTrace *tr)
{
    return ((const TrcWriter *)tr->state)->events;
}

gboolean trc_truncated(const SimTrace *tr)
{
    return ((const TrcWriter *)tr->state)->truncated;
}

static void writer_free(TrcWriter *w);

gboolean trc_close(SimTrace *tr, GError **err)
{
    if (!tr)
        return TRUE;
    TrcWriter *w = tr->state;
    write_counters(w);
    write_link_counters(w);
    w->fmt->end(w);
    gboolean ok = !ferror(w->f);
    ok = fclose(w->f) == 0 && ok;
    if (ok && rename(w->tmp, w->path) != 0)
        ok = FALSE;
    if (!ok) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot write: %s",
                    w->path, g_strerror(errno));
        remove(w->tmp);
    }
    writer_free(w);
    return ok;
}

void trc_discard(SimTrace *tr)
{
    if (!tr)
        return;
    TrcWriter *w = tr->state;
    fclose(w->f);
    remove(w->tmp);
    writer_free(w);
}

static void writer_free(TrcWriter *w)
{
    g_hash_table_destroy(w->nodes);
    g_hash_table_destroy(w->default_named);
    g_array_free(w->deltas, TRUE);
    g_hash_table_destroy(w->link_index);
    g_ptr_array_free(w->link_names, TRUE);
    g_array_free(w->link_deltas, TRUE);
    g_array_free(w->link_holds, TRUE);
    if (w->buffer)
        g_ptr_array_free(w->buffer, TRUE);
    g_free(w->path);
    g_free(w->tmp);
    g_free(w);
}
