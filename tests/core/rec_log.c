/* rec_log.c — the logging test recorder (rec_log.h). */
#include "tests/core/rec_log.h"

void rec_log_note(RecLog *log, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    g_string_append_vprintf(log->text, fmt, ap);
    va_end(ap);
    g_string_append_c(log->text, '\n');
}

static uint64_t next(RecLog *log)
{
    return ++log->next_id;
}

static uint64_t on_compute(SimRecorder *r, SimTime now, uint32_t node,
                           unsigned phase, SimTime cost, SimTime end,
                           const SimWork *w, gboolean handled)
{
    const SimOp *ops = w->ops;
    unsigned n_ops = w->n_ops;
    const SimOpTerm *terms = w->terms;
    unsigned n_terms = w->n_terms;
    RecLog *log = (RecLog *)r;
    GString *o = g_string_new("");
    for (unsigned i = 0; i < n_ops; i++)
        g_string_append_printf(o, " %s*%" G_GUINT64_FORMAT, ops[i].name,
                               ops[i].count);
    for (unsigned i = 0; i < n_terms; i++)
        g_string_append_printf(o, " [n%u%s %" G_GUINT64_FORMAT " B %u ops]",
                               terms[i].node, terms[i].bus ? " bus" : "",
                               terms[i].bytes, terms[i].n_ops);
    uint64_t id = next(log);
    rec_log_note(log,
                 "compute @%" G_GUINT64_FORMAT " n%u p%u cost=%" G_GUINT64_FORMAT
                 " end=%" G_GUINT64_FORMAT "%s h=%d -> %" G_GUINT64_FORMAT,
                 now, node, phase, cost, end, o->str, handled, id);
    g_string_free(o, TRUE);
    return id;
}

static uint64_t on_send(SimRecorder *r, SimTime now, uint32_t src,
                        uint32_t dst, uint64_t bytes, gboolean handled)
{
    RecLog *log = (RecLog *)r;
    uint64_t id = next(log);
    rec_log_note(log,
                 "send @%" G_GUINT64_FORMAT " %u->%u %" G_GUINT64_FORMAT
                 " B h=%d -> %" G_GUINT64_FORMAT,
                 now, src, dst, bytes, handled, id);
    return id;
}

static uint64_t on_transfer(SimRecorder *r, SimTime now, uint32_t src,
                            uint32_t dst, uint64_t bytes, SimTime end)
{
    RecLog *log = (RecLog *)r;
    uint64_t id = next(log);
    rec_log_note(log,
                 "transfer @%" G_GUINT64_FORMAT " %u->%u %" G_GUINT64_FORMAT
                 " B end=%" G_GUINT64_FORMAT " -> %" G_GUINT64_FORMAT,
                 now, src, dst, bytes, end, id);
    return id;
}

static uint64_t on_refresh(SimRecorder *r, SimTime now, uint32_t node,
                           SimTime period)
{
    RecLog *log = (RecLog *)r;
    uint64_t id = next(log);
    rec_log_note(log,
                 "refresh @%" G_GUINT64_FORMAT " n%u every %" G_GUINT64_FORMAT
                 " -> %" G_GUINT64_FORMAT,
                 now, node, period, id);
    return id;
}

static void on_begin(SimRecorder *r, uint64_t id, SimTime t)
{
    rec_log_note((RecLog *)r, "begin %" G_GUINT64_FORMAT " @%" G_GUINT64_FORMAT,
                 id, t);
}

static void on_end(SimRecorder *r, uint64_t id)
{
    rec_log_note((RecLog *)r, "end %" G_GUINT64_FORMAT, id);
}

static const SimRecorderOps rec_log_ops = {
    .compute = on_compute,
    .send = on_send,
    .transfer = on_transfer,
    .refresh = on_refresh,
    .begin = on_begin,
    .end = on_end,
};

/* ---- the trace ---- */

static void tr_span(SimTrace *tr, uint32_t node, const char *node_name,
                    const char *phase, SimTime start, SimTime end)
{
    rec_log_note(tr->state,
                 "span n%u %s %s [%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT ")",
                 node, node_name, phase, start, end);
}

static void tr_flow(SimTrace *tr, uint32_t src, const char *src_name,
                    uint32_t dst, const char *dst_name, uint64_t bytes,
                    SimTime sent, SimTime arrived)
{
    rec_log_note(tr->state,
                 "flow %u(%s)->%u(%s) %" G_GUINT64_FORMAT
                 " B [%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT ")",
                 src, src_name ? src_name : "-", dst,
                 dst_name ? dst_name : "-", bytes, sent, arrived);
}

static void tr_mark(SimTrace *tr, const char *name, SimTime t)
{
    rec_log_note(tr->state, "mark %s @%" G_GUINT64_FORMAT, name, t);
}

static void tr_link(SimTrace *tr, uint64_t link, const char *link_name,
                    uint64_t bytes, SimTime sent, SimTime arrived)
{
    rec_log_note(tr->state,
                 "link L%" G_GUINT64_FORMAT " %s %" G_GUINT64_FORMAT
                 " B [%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT ")",
                 link, link_name, bytes, sent, arrived);
}

static void tr_hold(SimTrace *tr, uint64_t link, const char *link_name,
                    uint64_t bytes, SimTime start, SimTime end)
{
    rec_log_note(tr->state,
                 "hold L%" G_GUINT64_FORMAT " %s %" G_GUINT64_FORMAT
                 " B [%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT ")",
                 link, link_name, bytes, start, end);
}

static void tr_wait(SimTrace *tr, uint64_t link, const char *link_name,
                    SimTime from, SimTime to)
{
    rec_log_note(tr->state,
                 "wait L%" G_GUINT64_FORMAT " %s [%" G_GUINT64_FORMAT
                 ",%" G_GUINT64_FORMAT ")",
                 link, link_name, from, to);
}

static const SimTraceOps rec_log_trace_ops = {
    .span = tr_span,
    .flow = tr_flow,
    .mark = tr_mark,
    .link = tr_link,
    .hold = tr_hold,
    .wait = tr_wait,
};

void rec_log_init(RecLog *log)
{
    *log = (RecLog){.rec = {.ops = &rec_log_ops, .state = log},
                    .tr = {.ops = &rec_log_trace_ops, .state = log},
                    .text = g_string_new("")};
}

void rec_log_clear(RecLog *log)
{
    g_string_free(log->text, TRUE);
    log->text = NULL;
}
