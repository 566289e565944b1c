/* ring.c — unidirectional ring of stations (Pixel-Planes 5).
 *
 * Stations 0 .. n-1; the directed segment from station i to i+1 (mod n)
 * has link id i.  A message goes downstream from src through every
 * station to dst, so hops = (dst - src) mod n.  Parallel channels are not
 * part of the topology: NetParams.channels says how many each segment
 * has, and the ring-slot transport (ringslot.c) assigns them.  Pixel-
 * Planes 5: host, Graphics Processors, Renderers and frame buffers are
 * stations on one ring of several channels, 640 MB/s in total (Fuchs et
 * al., SIGGRAPH 1989; Ellsworth, Good & Tebbs, seed 001).
 *
 * Invariants: routes never wrap past dst; link ends are (i, i+1 mod n).
 * State: one word; route() O(hops).
 */
#include "sim/net/topology.h"
#include <stdio.h>

typedef struct {
    uint32_t n;
} NetRing;

static uint32_t ring_nodes(const void *st)
{
    return ((const NetRing *)st)->n;
}

static guint ring_max_hops(const void *st)
{
    uint32_t n = ((const NetRing *)st)->n;
    return n - 1; /* net_ring_new asserts n >= 2 */
}

static guint ring_route(const void *st, uint32_t src, uint32_t dst,
                        NetLinkId *out)
{
    uint32_t n = ((const NetRing *)st)->n;
    guint h = 0;
    for (uint32_t s = src; s != dst; s = (s + 1) % n)
        out[h++] = s;
    return h;
}

static void ring_link_ends(const void *st, NetLinkId l, uint64_t *from,
                           uint64_t *to)
{
    uint32_t n = ((const NetRing *)st)->n;
    *from = l;
    *to = (l + 1) % n;
}

static void ring_link_name(const void *st, NetLinkId l, char *buf, size_t n)
{
    uint64_t a, b;
    ring_link_ends(st, l, &a, &b);
    snprintf(buf, n, "s%" G_GUINT64_FORMAT "->s%" G_GUINT64_FORMAT, a, b);
}

static double ring_link_bw(const void *st, NetLinkId l, const NetParams *p)
{
    (void)st;
    (void)l;
    return p->bandwidth;
}

const NetTopologyOps net_ring_ops = {
    .name = "ring",
    .nodes = ring_nodes,
    .max_hops = ring_max_hops,
    .route = ring_route,
    .link_ends = ring_link_ends,
    .link_name = ring_link_name,
    .link_bw = ring_link_bw,
    .free = g_free,
};

NetTopo *net_ring_new(uint32_t stations)
{
    g_assert(stations >= 2);
    NetRing *r = g_new0(NetRing, 1);
    r->n = stations;
    return net_topo_wrap(&net_ring_ops, r, sizeof *r);
}
