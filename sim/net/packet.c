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
 * arrive in order.  Cost: packets * hops events per message, O(1) each.
 */
#include "sim/net/net_internal.h"

typedef struct {
    NetMsg *m;
    uint32_t bytes;
    guint hop;
    SimTime prev_end; /* when the packet's tail left the previous link */
} NetPkt;

static void pkt_hop(SimEngine *eng, void *ctx, void *arg);

static void pkt_arrive(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    NetNet *n = ctx;
    NetPkt *p = arg;
    NetMsg *m = p->m;
    net_account(n, -(gssize)sizeof *p);
    g_free(p);
    if (--m->step == 0)
        net_msg_deliver(n, m);
}

static void pkt_hop(SimEngine *eng, void *ctx, void *arg)
{
    NetNet *n = ctx;
    NetPkt *p = arg;
    const NetParams *par = net_par(n);
    NetLink *l = p->m->path[p->hop];
    SimTime now = sim_now(eng);
    SimTime start = now > l->free_at ? now : l->free_at;
    SimTime end = start + sim_time_for_bytes((double)p->bytes, l->bw);
    gboolean cut = par->switching != NET_SW_STORE_FORWARD;
    if (cut && end < p->prev_end)
        end = p->prev_end;
    l->free_at = end;
    p->prev_end = end;
    if (++p->hop == p->m->hops) {
        sim_schedule_at(eng, end, pkt_arrive, n, p);
        return;
    }
    SimTime next = (cut ? start : end) + par->per_hop;
    sim_schedule_at(eng, next, pkt_hop, n, p);
}

static void packet_start(NetNet *n, NetMsg *m)
{
    const NetParams *par = net_par(n);
    uint64_t pb = par->packet_bytes;
    uint64_t np = m->bytes ? (m->bytes + pb - 1) / pb : 1;
    SimTime at = net_startup(par, m->bytes) + par->per_hop;
    m->step = (guint)np;
    for (uint64_t i = 0; i < np; i++) {
        NetPkt *p = g_new0(NetPkt, 1);
        p->m = m;
        p->bytes = (uint32_t)(i + 1 < np ? pb : m->bytes - i * pb);
        net_account(n, (gssize)sizeof *p);
        sim_schedule_in(net_eng(n), at, pkt_hop, n, p);
    }
}

const NetTransportOps net_packet_transport = {
    .name = "packet",
    .start = packet_start,
    .free = NULL,
};
