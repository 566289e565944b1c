/* fattree.c — k-ary fat tree with up/down routing (CM-5 data network).
 *
 * n leaves (nodes) under L = ceil(log_k n) levels of switches.  The
 * parallel up-links of a subtree are aggregated into one "fat" link per
 * direction: the subtree rooted at level l with index j (it covers nodes
 * j * k^l .. (j+1) * k^l - 1) has an up link to its parent and a down link
 * from it.  Link id = (2 * l + dir) * n + j, dir 0 up, 1 down.  A message
 * climbs from src to the least common ancestor of src and dst (the lowest
 * level m where src / k^m == dst / k^m) and descends: hops = 2m
 * (Leiserson, "Fat-trees: universal networks for hardware-efficient
 * supercomputing", IEEE Trans. Comput. C-34(10), 1985).
 *
 * Bandwidth: NetParams.level_bw[l] is the bandwidth per node at level l
 * (CM-5: about 20 MB/s at the leaves, 10 and 5 MB/s higher: Leiserson et
 * al., "The network architecture of the Connection Machine CM-5", SPAA
 * 1992), so the fat link at level l carries k^l * level_bw[l].  The CM-5
 * chooses among parallel up-links at random; aggregation replaces that
 * choice by perfect load balance (documented in docs/net.md).
 *
 * Invariants: hops are even; up links precede down links.  State: three
 * words; route() O(L).
 */
#include "sim/net/topology.h"
#include <math.h>
#include <stdio.h>

typedef struct {
    uint32_t n;
    unsigned k, levels;
} NetFatTree;

static uint32_t ft_nodes(const void *st)
{
    return ((const NetFatTree *)st)->n;
}

static guint ft_max_hops(const void *st)
{
    const NetFatTree *t = st;
    return 2 * t->levels; /* levels >= 1: net_fattree_new asserts n >= 2 */
}

static guint ft_route(const void *st, uint32_t src, uint32_t dst,
                      NetLinkId *out)
{
    const NetFatTree *t = st;
    unsigned m = 0;
    uint64_t span = 1;
    while (src / span != dst / span) {
        span *= t->k;
        m++;
    }
    uint64_t w = 1;
    for (unsigned l = 0; l < m; l++, w *= t->k)
        out[l] = (uint64_t)(2 * l) * t->n + src / w;
    for (unsigned l = m; l-- > 0;) {
        w /= t->k;
        out[2 * m - 1 - l] = (uint64_t)(2 * l + 1) * t->n + dst / w;
    }
    return 2 * m;
}

static void ft_decode(const NetFatTree *t, NetLinkId id, unsigned *l,
                      unsigned *dir, uint64_t *j)
{
    uint64_t c = id / t->n;
    *l = (unsigned)(c / 2);
    *dir = (unsigned)(c % 2);
    *j = id % t->n;
}

static void ft_link_ends(const void *st, NetLinkId id, uint64_t *from,
                         uint64_t *to)
{
    const NetFatTree *t = st;
    unsigned l, dir;
    uint64_t j;
    ft_decode(t, id, &l, &dir, &j);
    uint64_t child = (uint64_t)l * t->n + j;
    uint64_t parent = (uint64_t)(l + 1) * t->n + j / t->k;
    *from = dir ? parent : child;
    *to = dir ? child : parent;
}

static void ft_link_name(const void *st, NetLinkId id, char *buf, size_t n)
{
    unsigned l, dir;
    uint64_t j;
    ft_decode(st, id, &l, &dir, &j);
    snprintf(buf, n, "%s%u.%" G_GUINT64_FORMAT, dir ? "down" : "up", l, j);
}

static double ft_link_bw(const void *st, NetLinkId id, const NetParams *p)
{
    const NetFatTree *t = st;
    unsigned l, dir;
    uint64_t j;
    ft_decode(t, id, &l, &dir, &j);
    double per_node = p->bandwidth;
    if (l < NET_MAX_LEVELS && p->level_bw[l] > 0.0)
        per_node = p->level_bw[l];
    else if (l >= NET_MAX_LEVELS && p->level_bw[NET_MAX_LEVELS - 1] > 0.0)
        per_node = p->level_bw[NET_MAX_LEVELS - 1];
    return per_node * pow((double)t->k, (double)l);
}

const NetTopologyOps net_fattree_ops = {
    .name = "fat-tree",
    .nodes = ft_nodes,
    .max_hops = ft_max_hops,
    .route = ft_route,
    .link_ends = ft_link_ends,
    .link_name = ft_link_name,
    .link_bw = ft_link_bw,
    .free = g_free,
};

NetTopo *net_fattree_new(uint32_t nodes, unsigned arity)
{
    g_assert(nodes >= 2 && arity >= 2);
    NetFatTree *t = g_new0(NetFatTree, 1);
    t->n = nodes;
    t->k = arity;
    for (uint64_t span = 1; span < nodes; span *= arity)
        t->levels++;
    return net_topo_wrap(&net_fattree_ops, t, sizeof *t);
}
