/* mesh.c — meshes and tori of up to three dimensions, dimension-order
 * routing.
 *
 * Node id = x0 + e0 * (x1 + e1 * x2).  The directed link leaving node v
 * along dimension k in direction dir (0: +, 1: -) has id
 * v * 2 * ndims + 2 * k + dir.  Routes correct dimension 0 first, then 1,
 * then 2 (dimension-order routing, deadlock-free on meshes: Dally & Seitz,
 * IEEE Trans. Comput. C-36(5), 1987); on a torus each dimension takes the
 * shorter way round, the + direction on ties.  Generic: users describe
 * other machines with it, and the CM-200 NEWS grid is a 2-D torus.
 *
 * Invariants: hops = sum over dimensions of the (wrapped) coordinate
 * distance.  State: a few words; route() O(hops).
 */
#include "sim/net/topology.h"
#include <stdio.h>

typedef struct {
    unsigned nd;
    uint32_t e[3];
    gboolean wrap;
} NetMesh;

static uint32_t mesh_nodes(const void *st)
{
    const NetMesh *m = st;
    uint32_t n = 1;
    for (unsigned k = 0; k < m->nd; k++)
        n *= m->e[k];
    return n;
}

static guint mesh_max_hops(const void *st)
{
    const NetMesh *m = st;
    guint h = 0;
    for (unsigned k = 0; k < m->nd; k++)
        h += m->e[k];
    return h;
}

static uint32_t stride(const NetMesh *m, unsigned k)
{
    uint32_t s = 1;
    for (unsigned i = 0; i < k; i++)
        s *= m->e[i];
    return s;
}

/* Steps along dimension k from coordinate a to b: count and direction. */
static uint32_t mesh_steps(const NetMesh *m, unsigned k, uint32_t a, uint32_t b,
                           unsigned *dir)
{
    uint32_t fwd = (b + m->e[k] - a) % m->e[k];
    if (!m->wrap) {
        *dir = b >= a ? 0 : 1;
        return b >= a ? b - a : a - b;
    }
    uint32_t back = m->e[k] - fwd;
    *dir = fwd <= back ? 0 : 1;
    return fwd <= back ? fwd : back;
}

static guint mesh_route(const void *st, uint32_t src, uint32_t dst,
                        NetLinkId *out)
{
    const NetMesh *m = st;
    uint32_t cur = src;
    guint h = 0;
    for (unsigned k = 0; k < m->nd; k++) {
        uint32_t s = stride(m, k), e = m->e[k];
        unsigned dir;
        uint32_t a = cur / s % e, b = dst / s % e;
        uint32_t n = mesh_steps(m, k, a, b, &dir);
        for (uint32_t i = 0; i < n; i++) {
            out[h++] = (NetLinkId)cur * 2 * m->nd + 2 * k + dir;
            uint32_t na = dir ? (a + e - 1) % e : (a + 1) % e;
            cur = cur - a * s + na * s;
            a = na;
        }
    }
    g_assert(cur == dst);
    return h;
}

static void mesh_link_ends(const void *st, NetLinkId l, uint64_t *from,
                           uint64_t *to)
{
    const NetMesh *m = st;
    uint64_t v = l / (2 * m->nd);
    unsigned k = (unsigned)(l % (2 * m->nd)) / 2, dir = (unsigned)(l % 2);
    uint32_t s = stride(m, k), e = m->e[k];
    uint32_t a = (uint32_t)(v / s % e);
    uint32_t na = dir ? (a + e - 1) % e : (a + 1) % e;
    *from = v;
    *to = v - (uint64_t)a * s + (uint64_t)na * s;
}

static void mesh_link_name(const void *st, NetLinkId l, char *buf, size_t n)
{
    uint64_t a, b;
    mesh_link_ends(st, l, &a, &b);
    snprintf(buf, n, "n%" G_GUINT64_FORMAT "->n%" G_GUINT64_FORMAT, a, b);
}

static double mesh_link_bw(const void *st, NetLinkId l, const NetParams *p)
{
    (void)st;
    (void)l;
    return p->bandwidth;
}

const NetTopologyOps net_mesh_ops = {
    .name = "mesh",
    .nodes = mesh_nodes,
    .max_hops = mesh_max_hops,
    .route = mesh_route,
    .link_ends = mesh_link_ends,
    .link_name = mesh_link_name,
    .link_bw = mesh_link_bw,
    .free = g_free,
};

NetTopo *net_mesh_new(unsigned ndims, const uint32_t *extent, gboolean wrap)
{
    g_assert(ndims >= 1 && ndims <= 3);
    NetMesh *m = g_new0(NetMesh, 1);
    m->nd = ndims;
    m->wrap = wrap;
    for (unsigned k = 0; k < ndims; k++) {
        g_assert(extent[k] >= 1);
        m->e[k] = extent[k];
    }
    return net_topo_wrap(&net_mesh_ops, m, sizeof *m);
}
