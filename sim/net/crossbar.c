/* crossbar.c — single-stage networks: crossbar and bus.
 *
 * Crossbar: every node has an input port (link 2i, node -> switch) and an
 * output port (link 2j + 1, switch -> node); a message crosses its
 * source's input and its destination's output, so only messages sharing
 * a source or a destination contend.  Bus: one shared link (id 0) that
 * every message crosses, so all messages contend.  Both are generic
 * building blocks for user-described machines (Hwang & Briggs, Computer
 * Architecture and Parallel Processing, 1984, ch. 7).
 *
 * Vertex ids: nodes 0 .. n-1, the switch or bus is vertex n.
 * State: one word; everything O(1).
 */
#include "sim/net/topology.h"
#include <stdio.h>

typedef struct {
    uint32_t n;
} NetSingle;

static uint32_t single_nodes(const void *st)
{
    return ((const NetSingle *)st)->n;
}

static double single_link_bw(const void *st, NetLinkId l, const NetParams *p)
{
    (void)st;
    (void)l;
    return p->bandwidth;
}

static guint xbar_max_hops(const void *st)
{
    (void)st;
    return 2;
}

static guint xbar_route(const void *st, uint32_t src, uint32_t dst,
                        NetLinkId *out)
{
    (void)st;
    out[0] = 2 * (NetLinkId)src;
    out[1] = 2 * (NetLinkId)dst + 1;
    return 2;
}

static void xbar_link_ends(const void *st, NetLinkId l, uint64_t *from,
                           uint64_t *to)
{
    uint64_t sw = ((const NetSingle *)st)->n;
    *from = l % 2 ? sw : l / 2;
    *to = l % 2 ? l / 2 : sw;
}

static void xbar_link_name(const void *st, NetLinkId l, char *buf, size_t n)
{
    (void)st;
    snprintf(buf, n, "%s%" G_GUINT64_FORMAT, l % 2 ? "out" : "in", l / 2);
}

const NetTopologyOps net_crossbar_ops = {
    .name = "crossbar",
    .nodes = single_nodes,
    .max_hops = xbar_max_hops,
    .route = xbar_route,
    .link_ends = xbar_link_ends,
    .link_name = xbar_link_name,
    .link_bw = single_link_bw,
    .free = g_free,
};

static guint bus_max_hops(const void *st)
{
    (void)st;
    return 1;
}

static guint bus_route(const void *st, uint32_t src, uint32_t dst,
                       NetLinkId *out)
{
    (void)st;
    (void)src;
    (void)dst;
    out[0] = 0;
    return 1;
}

static void bus_link_ends(const void *st, NetLinkId l, uint64_t *from,
                          uint64_t *to)
{
    (void)l;
    *from = *to = ((const NetSingle *)st)->n;
}

static void bus_link_name(const void *st, NetLinkId l, char *buf, size_t n)
{
    (void)st;
    (void)l;
    snprintf(buf, n, "bus");
}

const NetTopologyOps net_bus_ops = {
    .name = "bus",
    .nodes = single_nodes,
    .max_hops = bus_max_hops,
    .route = bus_route,
    .link_ends = bus_link_ends,
    .link_name = bus_link_name,
    .link_bw = single_link_bw,
    .free = g_free,
};

static NetTopo *single_new(const NetTopologyOps *ops, uint32_t nodes)
{
    g_assert(nodes >= 1);
    NetSingle *s = g_new0(NetSingle, 1);
    s->n = nodes;
    return net_topo_wrap(ops, s, sizeof *s);
}

NetTopo *net_crossbar_new(uint32_t nodes)
{
    return single_new(&net_crossbar_ops, nodes);
}

NetTopo *net_bus_new(uint32_t nodes)
{
    return single_new(&net_bus_ops, nodes);
}
