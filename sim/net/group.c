/* group.c — two-level networks: endpoints in groups (the processes or
 * GPUs of one node) over an outer topology between the groups.
 *
 * Endpoint e belongs to group e / g.  Two endpoints of one group talk
 * through the group's own switch (NVSwitch in a DGX node; the node's
 * memory for the processes of one Blue Gene/P node): the route is e's
 * up-link into the switch, then the down-link to the other endpoint,
 * two hops at NetParams.node_bw per channel (0: bandwidth).  Endpoints
 * of different groups use the outer topology (a torus, a fat tree ...):
 *
 *   shared ports       the outer topology has one node per group and the
 *                      group's endpoints share its links (several MPI
 *                      processes on one Blue Gene/P node, one NIC per PC);
 *   per-endpoint ports the outer topology has one node per endpoint (a
 *                      DGX A100 has one InfiniBand adapter per GPU), so
 *                      the route is the outer route between the endpoints.
 *
 * Link ids: the outer topology's own ids (below 2^63), and inner links
 * 2^63 + 2e (e -> switch) and 2^63 + 2e + 1 (switch -> e).  Vertex ids:
 * the outer's, and 2^63 + e for an endpoint, 2^63 + 2^62 + group for a
 * group switch; only the shared form gives endpoints their own vertex.
 *
 * The last group may be partial (n endpoints need not fill every group:
 * a run on 4 GPUs of an 8-GPU node).
 *
 * Invariants: routes inside a group have 2 hops; others are the outer
 * route.  State: a few words plus the outer topology (owned); route()
 * costs what the outer route costs.
 */
#include "sim/net/topology.h"
#include <stdio.h>

#define INNER ((NetLinkId)1 << 63)
#define SWITCH ((uint64_t)1 << 62)

typedef struct {
    NetTopo *outer;
    uint32_t g, n;
    gboolean per_endpoint;
} NetGroup;

static uint32_t grp_nodes(const void *st)
{
    return ((const NetGroup *)st)->n;
}

static guint grp_max_hops(const void *st)
{
    const NetGroup *t = st;
    guint h = t->outer->ops->max_hops(t->outer->state);
    return h > 2 ? h : 2;
}

static guint grp_route(const void *st, uint32_t src, uint32_t dst,
                       NetLinkId *out)
{
    const NetGroup *t = st;
    if (src / t->g == dst / t->g) {
        out[0] = INNER + 2 * (NetLinkId)src;
        out[1] = INNER + 2 * (NetLinkId)dst + 1;
        return 2;
    }
    const NetTopo *o = t->outer;
    if (t->per_endpoint)
        return o->ops->route(o->state, src, dst, out);
    return o->ops->route(o->state, src / t->g, dst / t->g, out);
}

static void grp_link_ends(const void *st, NetLinkId l, uint64_t *from,
                          uint64_t *to)
{
    const NetGroup *t = st;
    if (l < INNER) {
        t->outer->ops->link_ends(t->outer->state, l, from, to);
        return;
    }
    uint64_t e = (l - INNER) / 2;
    uint64_t ev = INNER + e, sw = INNER + SWITCH + e / t->g;
    *from = l % 2 ? sw : ev;
    *to = l % 2 ? ev : sw;
}

static void grp_link_name(const void *st, NetLinkId l, char *buf, size_t n)
{
    const NetGroup *t = st;
    if (l < INNER) {
        t->outer->ops->link_name(t->outer->state, l, buf, n);
        return;
    }
    uint64_t e = (l - INNER) / 2;
    if (l % 2)
        snprintf(buf, n, "sw%" G_GUINT64_FORMAT "->e%" G_GUINT64_FORMAT,
                 e / t->g, e);
    else
        snprintf(buf, n, "e%" G_GUINT64_FORMAT "->sw%" G_GUINT64_FORMAT, e,
                 e / t->g);
}

static double grp_link_bw(const void *st, NetLinkId l, const NetParams *p)
{
    const NetGroup *t = st;
    if (l < INNER)
        return t->outer->ops->link_bw(t->outer->state, l, p);
    return p->node_bw > 0.0 ? p->node_bw : p->bandwidth;
}

static void grp_free(void *st)
{
    NetGroup *t = st;
    net_topo_free(t->outer);
    g_free(t);
}

const NetTopologyOps net_group_ops = {
    .name = "group",
    .nodes = grp_nodes,
    .max_hops = grp_max_hops,
    .route = grp_route,
    .link_ends = grp_link_ends,
    .link_name = grp_link_name,
    .link_bw = grp_link_bw,
    .free = grp_free,
};

NetTopo *net_group_new(NetTopo *outer, uint32_t group, gboolean per_endpoint,
                       uint32_t n)
{
    g_assert(outer && group >= 1 && n >= 1);
    uint64_t on = net_topo_nodes(outer);
    g_assert(per_endpoint ? n == on : (n - 1) / group + 1 == on);
    NetGroup *t = g_new0(NetGroup, 1);
    t->outer = outer;
    t->g = group;
    t->n = (uint32_t)n;
    t->per_endpoint = per_endpoint;
    return net_topo_wrap(&net_group_ops, t, sizeof *t + outer->state_bytes);
}

const NetTopo *net_group_outer(const NetTopo *t)
{
    g_assert(t->ops == &net_group_ops);
    return ((const NetGroup *)t->state)->outer;
}
