/* packet.c — packet switching with a FIFO per link.
 *
 * A message becomes ceil(bytes / packet_bytes) packets (at least one),
 * injected together after the start-up.  Each packet visits its path's
 * links in order; at each link it waits until the link is free (FIFO in
 * arrival order, ties by event order), then occupies it for
 * packet_bytes / bw.  Two switching disciplines (Kermani & Kleinrock,
 * "Virtual cut-through", Computer Networks 3, 1979):
 *   cut-through       the header moves on after per_hop, so a packet is
 *                     pipelined across links (its tail cannot leave a link
 *                     before it has arrived through the previous one);
 *   store-and-forward the next hop starts per_hop after the whole packet
 *                     has arrived.
 * Wormhole routing is approximated by cut-through with unbounded buffers:
 * a blocked packet does not hold upstream links (documented in docs/net.md).
 *
 * Invariants: with cut-through, a lone message whose size is a multiple of
 * packet_bytes takes exactly the analytic time; packets of one message
 * arrive in order.  Cost: packets * hops events per message, O(1) each;
 * the first link is reserved for all of a message's packets in one event,
 * and each packet schedules its successor's next event, so packets enter
 * the event queue one after another as they leave the first link rather
 * than all at injection (a 10 KB message in 20-byte CM-5 packets is 512
 * packets).  A message's packets are one block (m->tp), held by the net
 * (net_own) until its last packet arrives, so a net freed mid-run (a run
 * stopped early) frees the packets still queued on links.
 *
 * Trace hook (sim/core/trace.h): when the engine's trace listens, each
 * reservation reports the link's hold [start, end) by that packet, and a
 * message's head packet that finds the link busy reports its wait [now,
 * start), so the trace layer draws each hop's real occupancy and queue
 * (docs/traces.md).  Reporting adds no events: a run with and without a
 * trace makes the same events.
 */
#include "sim/net/net_internal.h"
#include "sim/core/trace.h"

typedef struct NetPkt NetPkt;
struct NetPkt {
    NetMsg *m;
    uint32_t bytes;
    guint hop;        /* next link to cross */
    SimTime prev_end; /* when the packet's tail left the previous link */
    SimTime due;      /* its first event after injection */
    NetPkt *chain;    /* the message's next packet, not yet scheduled */
    gboolean head;    /* the message's first packet */
};

static void pkt_hop(SimEngine *eng, void *ctx, void *arg);
static void pkt_arrive(SimEngine *eng, void *ctx, void *arg);

/* ceil(bytes / packet_bytes) packets, at least one. */
static guint pkt_count(NetNet *n, const NetMsg *m)
{
    uint64_t pb = net_par(n)->packet_bytes;
    return (guint)(m->bytes ? (m->bytes + pb - 1) / pb : 1);
}

/* Tells the trace that p holds l over [start, end), and that a head
 * packet reaching it at `now` waited until `start`. */
static void pkt_trace(NetNet *n, const NetPkt *p, const NetLink *l,
                      SimTime now, SimTime start, SimTime end)
{
    SimTrace *tr = sim_engine_trace(net_eng(n));
    if (!sim_trace_wants_holds(tr))
        return;
    char name[64];
    net_link_name(n, l->id, name, sizeof name);
    if (p->head && start > now)
        sim_trace_wait(tr, l->id, name, now, start);
    sim_trace_hold(tr, l->id, name, p->bytes, start, end);
}

/* p crosses link p->hop, entering at `now`: reserves it in FIFO order and
 * returns when p's next event is due (the next hop, or its arrival). */
static SimTime pkt_cross(NetNet *n, NetPkt *p, SimTime now)
{
    const NetParams *par = net_par(n);
    NetLink *l = p->m->path[p->hop];
    SimTime start = now > l->free_at ? now : l->free_at;
    SimTime end = start + sim_time_for_bytes((double)p->bytes, l->bw);
    gboolean cut = par->switching != NET_SW_STORE_FORWARD;
    if (cut && end < p->prev_end)
        end = p->prev_end;
    pkt_trace(n, p, l, now, start, end);
    l->free_at = end;
    p->prev_end = end;
    if (++p->hop == p->m->hops)
        return end;
    return (cut ? start : end) + par->per_hop;
}

static void pkt_schedule(NetNet *n, NetPkt *p, SimTime t)
{
    sim_schedule_at(net_eng(n), t, p->hop == p->m->hops ? pkt_arrive : pkt_hop,
                    n, p);
}

/* A packet's first event after injection schedules its successor's, so a
 * message has one pending event per packet in flight beyond the first
 * link, not one per packet. */
static void pkt_release_chain(NetNet *n, NetPkt *p)
{
    NetPkt *q = p->chain;
    if (!q)
        return;
    p->chain = NULL;
    pkt_schedule(n, q, q->due);
}

static void pkt_arrive(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    NetNet *n = ctx;
    NetPkt *p = arg;
    NetMsg *m = p->m;
    pkt_release_chain(n, p);
    if (--m->step > 0)
        return;
    net_account(n, -(gssize)(pkt_count(n, m) * sizeof *p));
    net_disown(n, m->tp);
    g_free(m->tp);
    m->tp = NULL;
    net_msg_deliver(n, m);
}

static void pkt_hop(SimEngine *eng, void *ctx, void *arg)
{
    NetNet *n = ctx;
    NetPkt *p = arg;
    pkt_release_chain(n, p);
    pkt_schedule(n, p, pkt_cross(n, p, sim_now(eng)));
}

/* All packets of a message enter the first link at once, back to back in
 * FIFO order; only the first one's next event is scheduled now. */
static void pkt_inject(SimEngine *eng, void *ctx, void *arg)
{
    NetNet *n = ctx;
    NetMsg *m = arg;
    uint64_t pb = net_par(n)->packet_bytes, np = m->step;
    NetPkt *pk = g_new0(NetPkt, np);
    m->tp = pk;
    net_own(n, pk, g_free); /* freed by net_free if the run stops early */
    net_account(n, (gssize)(np * sizeof *pk));
    for (uint64_t i = 0; i < np; i++) {
        NetPkt *p = &pk[i];
        p->m = m;
        p->head = i == 0;
        p->bytes = (uint32_t)(i + 1 < np ? pb : m->bytes - i * pb);
        p->due = pkt_cross(n, p, sim_now(eng));
        if (i > 0)
            pk[i - 1].chain = p;
    }
    pkt_schedule(n, pk, pk->due);
}

static void packet_start(NetNet *n, NetMsg *m)
{
    const NetParams *par = net_par(n);
    m->step = pkt_count(n, m);
    sim_schedule_in(net_eng(n), net_startup(par, m->bytes) + par->per_hop,
                    pkt_inject, n, m);
}

const NetTransportOps net_packet_transport = {
    .name = "packet",
    .start = packet_start,
    .free = NULL,
};
