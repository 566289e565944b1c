/* hypercube.c — binary d-cube with e-cube routing.
 *
 * Node ids are d-bit addresses; the directed link from node n across
 * dimension k (to n ^ 2^k) has id n * d + k.  E-cube routing corrects the
 * bits in which source and destination differ in a fixed order, lowest
 * dimension first (Sullivan & Bashkow, "A large scale, homogeneous, fully
 * distributed parallel machine", ISCA 1977), as the iPSC/2 Direct-Connect
 * Modules do (Nugent, "The iPSC/2 direct-connect communications
 * technology", Proc. 3rd Conf. Hypercube Concurrent Computers, 1988).
 * Dimension-ordered routing is deadlock-free under hold-and-wait, which
 * the circuit transport relies on.
 *
 * Invariants: hops = popcount(src ^ dst); routes of the permutation
 * i -> i ^ k are link-disjoint for every k.  State: one word.  route() is
 * O(d); everything else O(1).
 */
#include "sim/net/topology.h"
#include <stdio.h>

typedef struct {
    unsigned dims;
} NetCube;

static uint32_t cube_nodes(const void *st)
{
    return (uint32_t)1 << ((const NetCube *)st)->dims;
}

static guint cube_max_hops(const void *st)
{
    const NetCube *c = st;
    return c->dims; /* 0 for one node: no route, no scratch */
}

static guint cube_route(const void *st, uint32_t src, uint32_t dst,
                        NetLinkId *out)
{
    const NetCube *c = st;
    uint32_t cur = src, diff = src ^ dst;
    guint h = 0;
    for (unsigned k = 0; k < c->dims; k++) {
        if (!(diff & ((uint32_t)1 << k)))
            continue;
        out[h++] = (NetLinkId)cur * c->dims + k;
        cur ^= (uint32_t)1 << k;
    }
    g_assert(cur == dst && h > 0);
    return h;
}

static void cube_link_ends(const void *st, NetLinkId l, uint64_t *from,
                           uint64_t *to)
{
    const NetCube *c = st;
    uint64_t n = l / c->dims;
    unsigned k = (unsigned)(l % c->dims);
    *from = n;
    *to = n ^ ((uint64_t)1 << k);
}

static void cube_link_name(const void *st, NetLinkId l, char *buf, size_t n)
{
    uint64_t a, b;
    cube_link_ends(st, l, &a, &b);
    snprintf(buf, n, "n%" G_GUINT64_FORMAT "->n%" G_GUINT64_FORMAT, a, b);
}

static double cube_link_bw(const void *st, NetLinkId l, const NetParams *p)
{
    (void)st;
    (void)l;
    return p->bandwidth;
}

const NetTopologyOps net_hypercube_ops = {
    .name = "hypercube",
    .nodes = cube_nodes,
    .max_hops = cube_max_hops,
    .route = cube_route,
    .link_ends = cube_link_ends,
    .link_name = cube_link_name,
    .link_bw = cube_link_bw,
    .free = g_free,
};

NetTopo *net_hypercube_new(unsigned dims)
{
    g_assert(dims <= 24);
    NetCube *c = g_new0(NetCube, 1);
    c->dims = dims;
    return net_topo_wrap(&net_hypercube_ops, c, sizeof *c);
}
