/* trace.h — trace hooks.
 *
 * A SimTrace is a small table of callbacks plus its state; writers
 * (Chrome Trace Event JSON, Paje) live in sim/app/.  The model layers call
 * the sim_trace_* helpers, which are no-ops when no trace is attached, so
 * tracing costs one NULL test when off.
 */
#ifndef PGSIM_CORE_TRACE_H
#define PGSIM_CORE_TRACE_H

#include "sim/core/time.h"

typedef struct SimTrace SimTrace;

typedef struct {
    /* A processor was busy in a phase over [start, end). */
    void (*span)(SimTrace *tr, uint32_t node, const char *node_name,
                 const char *phase, SimTime start, SimTime end);
    /* A message went from src to dst over [sent, arrived).  Node ids are
     * the same numbers spans use (processor ids on a machine); the names
     * are the nodes' (NULL when nobody named them). */
    void (*flow)(SimTrace *tr, uint32_t src, const char *src_name,
                 uint32_t dst, const char *dst_name, uint64_t bytes,
                 SimTime sent, SimTime arrived);
    /* A named instant (frame boundary ...). */
    void (*mark)(SimTrace *tr, const char *name, SimTime t);
    /* A message of `bytes` crossed a network link on its route while in
     * flight over [sent, arrived): one call per link of the route, after
     * its flow.  link is the network's link id, link_name its name. */
    void (*link)(SimTrace *tr, uint64_t link, const char *link_name,
                 uint64_t bytes, SimTime sent, SimTime arrived);
    /* The link is taken at `start` and released at `end` while it
     * carries `bytes` of one packet (packet rung), of one message's
     * circuit (circuit switching: from the header's take to the
     * tear-down) or of one message's ring-slot claim.  A transport
     * reports each hold when it reserves the link (so possibly ahead of
     * `start`) or, for circuits, at the tear-down, and always before the
     * message's delivery; holds of one channel of a link come in time
     * order and never overlap (a link's channels may overlap).  A link
     * that reports holds is not also given the per-message `link`
     * average by a writer. */
    void (*hold)(SimTrace *tr, uint64_t link, const char *link_name,
                 uint64_t bytes, SimTime start, SimTime end);
    /* A message's head (a packet, a circuit's header, a ring message)
     * waited for the link over [from, to) while others held it. */
    void (*wait)(SimTrace *tr, uint64_t link, const char *link_name,
                 SimTime from, SimTime to);
} SimTraceOps;

struct SimTrace {
    const SimTraceOps *ops;
    void *state;
};

static inline void sim_trace_span(SimTrace *tr, uint32_t node,
                                  const char *node_name, const char *phase,
                                  SimTime start, SimTime end)
{
    if (tr && tr->ops->span)
        tr->ops->span(tr, node, node_name, phase, start, end);
}

static inline void sim_trace_flow(SimTrace *tr, uint32_t src,
                                  const char *src_name, uint32_t dst,
                                  const char *dst_name, uint64_t bytes,
                                  SimTime sent, SimTime arrived)
{
    if (tr && tr->ops->flow)
        tr->ops->flow(tr, src, src_name, dst, dst_name, bytes, sent, arrived);
}

static inline void sim_trace_mark(SimTrace *tr, const char *name, SimTime t)
{
    if (tr && tr->ops->mark)
        tr->ops->mark(tr, name, t);
}

static inline gboolean sim_trace_wants_links(const SimTrace *tr)
{
    return tr && tr->ops->link;
}

static inline void sim_trace_link(SimTrace *tr, uint64_t link,
                                  const char *link_name, uint64_t bytes,
                                  SimTime sent, SimTime arrived)
{
    if (tr && tr->ops->link)
        tr->ops->link(tr, link, link_name, bytes, sent, arrived);
}

/* TRUE when the trace listens to holds and waits (then a transport
 * builds link names for them). */
static inline gboolean sim_trace_wants_holds(const SimTrace *tr)
{
    return tr && (tr->ops->hold || tr->ops->wait);
}

static inline void sim_trace_hold(SimTrace *tr, uint64_t link,
                                  const char *link_name, uint64_t bytes,
                                  SimTime start, SimTime end)
{
    if (tr && tr->ops->hold)
        tr->ops->hold(tr, link, link_name, bytes, start, end);
}

static inline void sim_trace_wait(SimTrace *tr, uint64_t link,
                                  const char *link_name, SimTime from,
                                  SimTime to)
{
    if (tr && tr->ops->wait)
        tr->ops->wait(tr, link, link_name, from, to);
}

#endif
