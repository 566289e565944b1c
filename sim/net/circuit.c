/* circuit.c — circuit switching: the iPSC/2 Direct-Connect Module, at the
 * packet rung and at the flow rung.
 *
 * Packet rung (net_circuit_transport).  After the software start-up, a
 * message's header sets up a circuit hop by hop along its route: it takes
 * a free channel of the next link, waits per_hop in the router, and goes
 * on.  When a link has no free channel the header waits there, holding
 * the part of the circuit already built, in a FIFO per link (ties in
 * arrival time resolve by event order, i.e. by (request time, send
 * sequence)).  Once the whole path is held, the data streams at the
 * path's channel bandwidth; at the end every link is released in path
 * order and each hands its channel to the head of its FIFO.  (Nugent,
 * "The iPSC/2 direct-connect communications technology", Proc. 3rd Conf.
 * Hypercube Concurrent Computers, 1988: "communication between
 * non-neighbouring processors is almost as fast as between neighbours if
 * the links are not used by other messages".)
 *
 * Flow rung (net_circuit_flow_transport).  Max-min sharing (flow.c) is the
 * wrong service discipline here: a DCM channel carries one circuit at a
 * time.  This rung keeps the channel discipline — one circuit per channel,
 * first come first served, the path held for the whole message — and drops
 * the header's per-hop events: the header takes every free link at once
 * at the end of the start-up and charges hops * per_hop with the data.  A
 * message costs 2 events (request, end) instead of hops + 1; links are
 * acquired up to hops * per_hop early, the rung's only approximation.
 * Whole-path reservation at request time (wait until every link is free,
 * holding none) was measured and rejected: +20 % against this rung's
 * +0.7 % on the 64-node iPSC/2 all-to-all (docs/net.md).
 *
 * Trace hook (sim/core/trace.h): when the engine's trace listens, a
 * message keeps the time it took each link of its path (m->tp, owned by
 * the net until tear-down); at tear-down each link reports its hold
 * [taken, released) with the message's bytes — a circuit holds every
 * link from set-up to tear-down, data or not — and a header that queued
 * for a channel reports its wait [reached, taken) on that link.  The
 * reports add no events and move nothing (docs/traces.md).
 *
 * Invariants: a lone message takes startup + hops * per_hop + bytes / bw,
 * the analytic time, at both rungs; hold-and-wait cannot deadlock under
 * e-cube (or any dimension-ordered) routing, whose channel dependency
 * graph is acyclic (Dally & Seitz, IEEE Trans. Comput. C-36(5), 1987).
 * Cost: O(1) per acquire and release.
 */
#include "sim/net/net_internal.h"
#include "sim/core/trace.h"

/* The flow rung builds the circuit without per-hop events. */
static gboolean instant_header(NetNet *n)
{
    return net_fidelity(n) == NET_FLOW;
}

static void circuit_try(SimEngine *eng, void *ctx, void *arg);
static void circuit_take(NetNet *n, NetMsg *m);
static void data_done(SimEngine *eng, void *ctx, void *arg);

/* Channel of l free for a newcomer, or -1.  A newcomer never jumps the
 * FIFO: a link has waiters only while all its channels are held, since a
 * header queues only when it finds none free and release() hands a freed
 * channel to the head waiter in the same step, so no test of the FIFO is
 * needed here (the one that stood here could never decide). */
static int free_channel(NetLink *l)
{
    if (!l->holder)
        l->holder = g_new0(NetMsg *, l->channels);
    for (uint32_t c = 0; c < l->channels; c++)
        if (!l->holder[c])
            return (int)c;
    return -1;
}

/* Time from the last link taken to delivery. */
static SimTime data_time(NetNet *n, const NetMsg *m)
{
    SimTime t = m->bytes ? sim_time_for_bytes((double)m->bytes, m->bw) : 0;
    if (instant_header(n))
        t += sim_time_mul_sat(net_par(n)->per_hop, m->hops);
    return t;
}

/* Trace: m->tp holds, per hop, the time the header reached the link
 * (taken: the time it took it); NULL when nobody listens. */
static SimTime *taken_at(const NetMsg *m)
{
    return m->tp;
}

static void trace_report(NetNet *n, const NetLink *l, SimTime from,
                         SimTime to, uint64_t bytes, gboolean hold)
{
    SimTrace *tr = sim_engine_trace(net_eng(n));
    char name[64];
    net_link_name(n, l->id, name, sizeof name);
    if (hold)
        sim_trace_hold(tr, l->id, name, bytes, from, to);
    else
        sim_trace_wait(tr, l->id, name, from, to);
}

/* The header reached path[m->step] at `reached` and takes it now. */
static void trace_take(NetNet *n, NetMsg *m)
{
    SimTime *t = taken_at(m), now = sim_now(net_eng(n));
    if (!t)
        return;
    if (now > t[m->step])
        trace_report(n, m->path[m->step], t[m->step], now, 0, FALSE);
    t[m->step] = now;
}

/* Tear-down: every link of the path was held from its take until now. */
static void trace_holds(NetNet *n, NetMsg *m)
{
    SimTime *t = taken_at(m), now = sim_now(net_eng(n));
    if (!t)
        return;
    for (guint i = 0; i < m->hops; i++)
        trace_report(n, m->path[i], t[i], now, m->bytes, TRUE);
    net_disown(n, t);
    g_free(t);
    m->tp = NULL;
}

/* m has just taken a channel on path[m->step]: go on from here. */
static void advance(NetNet *n, NetMsg *m, uint32_t c)
{
    NetLink *l = m->path[m->step];
    trace_take(n, m);
    l->holder[c] = m;
    m->chan[m->step] = c;
    m->step++;
    if (m->step == m->hops)
        sim_schedule_in(net_eng(n), data_time(n, m), data_done, n, m);
    else if (instant_header(n))
        circuit_take(n, m);
    else
        sim_schedule_in(net_eng(n), net_par(n)->per_hop, circuit_try, n, m);
}

static void circuit_take(NetNet *n, NetMsg *m)
{
    NetLink *l = m->path[m->step];
    if (taken_at(m))
        taken_at(m)[m->step] = sim_now(net_eng(n));
    int c = free_channel(l);
    if (c < 0) {
        g_queue_push_tail(&l->wait, m);
        return;
    }
    advance(n, m, (uint32_t)c);
}

static void circuit_try(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    circuit_take(ctx, arg);
}

static void release(NetNet *n, NetLink *l, uint32_t c)
{
    l->holder[c] = NULL;
    NetMsg *w = g_queue_pop_head(&l->wait);
    if (w)
        advance(n, w, c);
}

static void data_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    NetNet *n = ctx;
    NetMsg *m = arg;
    trace_holds(n, m);
    for (guint i = 0; i < m->hops; i++)
        release(n, m->path[i], m->chan[i]);
    net_account(n, -(gssize)(m->hops * sizeof(uint32_t)));
    net_msg_deliver(n, m);
}

static void circuit_start(NetNet *n, NetMsg *m)
{
    const NetParams *p = net_par(n);
    SimTime header = instant_header(n) ? 0 : p->per_hop;
    m->chan = g_new(uint32_t, m->hops);
    m->step = 0;
    net_account(n, (gssize)(m->hops * sizeof(uint32_t)));
    if (sim_trace_wants_holds(sim_engine_trace(net_eng(n)))) {
        m->tp = g_new0(SimTime, m->hops); /* freed at tear-down or net_free */
        net_own(n, m->tp, g_free);
    }
    sim_schedule_in(net_eng(n), net_startup(p, m->bytes) + header, circuit_try,
                    n, m);
}

const NetTransportOps net_circuit_transport = {
    .name = "circuit",
    .start = circuit_start,
    .free = NULL,
};

const NetTransportOps net_circuit_flow_transport = {
    .name = "circuit-flow",
    .start = circuit_start,
    .free = NULL,
};
