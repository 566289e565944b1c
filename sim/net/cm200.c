/* cm200.c — the CM-200 router network plus the NEWS grid.
 *
 * P = 2^d * g processors; processor p is served by router p / g, and the
 * routers form a d-cube (Thinking Machines, "Connection Machine CM-200
 * Series Technical Summary", 1991: 16 processors per router chip, a
 * 12-cube of routers for 64K processors).  A general message goes
 * p -> router (injection), e-cube across routers (lowest dimension
 * first), router -> q (ejection); processors sharing a router use only
 * injection and ejection.  Nearest-neighbour moves use the NEWS grid
 * instead: the processors also form an nx x ny torus (p = y * nx + x), and
 * a message to one of p's four NEWS neighbours takes one NEWS link.
 *
 * Link ids (P processors, R = 2^d routers):
 *   [0, P)               injection of processor p
 *   [P, 2P)              ejection to processor p
 *   [2P, 2P + R d)       cube link of router r across dimension k
 *   [2P + R d, ... + 4P) NEWS link of p towards +x, -x, +y, -y
 * Bandwidths: level_bw[0] cube links, level_bw[1] NEWS links (0 means
 * NetParams.bandwidth), injection and ejection at NetParams.bandwidth.
 * Vertex ids: processors 0 .. P-1, routers P .. P+R-1.
 *
 * Invariants: router hops = popcount(router(p) ^ router(q)).  State: a
 * few words; route() O(d).
 */
#include "sim/net/topology.h"
#include <stdio.h>

typedef struct {
    unsigned d;
    uint32_t g, nx, ny, p, r;
} NetCm200;

static uint32_t cm_nodes(const void *st)
{
    return ((const NetCm200 *)st)->p;
}

static guint cm_max_hops(const void *st)
{
    return ((const NetCm200 *)st)->d + 2;
}

/* NEWS direction from a to its neighbour b, or -1. */
static int news_dir(const NetCm200 *c, uint32_t a, uint32_t b)
{
    uint32_t ax = a % c->nx, ay = a / c->nx, bx = b % c->nx, by = b / c->nx;
    if (ay == by && bx == (ax + 1) % c->nx)
        return 0;
    if (ay == by && ax == (bx + 1) % c->nx)
        return 1;
    if (ax == bx && by == (ay + 1) % c->ny)
        return 2;
    if (ax == bx && ay == (by + 1) % c->ny)
        return 3;
    return -1;
}

static uint64_t news_base(const NetCm200 *c)
{
    return 2 * (uint64_t)c->p + (uint64_t)c->r * c->d;
}

static guint cm_route(const void *st, uint32_t src, uint32_t dst,
                      NetLinkId *out)
{
    const NetCm200 *c = st;
    int nd = news_dir(c, src, dst);
    if (nd >= 0) {
        out[0] = news_base(c) + 4 * (uint64_t)src + (unsigned)nd;
        return 1;
    }
    guint h = 0;
    uint32_t cur = src / c->g, to = dst / c->g;
    out[h++] = src;
    for (unsigned k = 0; k < c->d; k++) {
        if (!((cur ^ to) & ((uint32_t)1 << k)))
            continue;
        out[h++] = 2 * (uint64_t)c->p + (uint64_t)cur * c->d + k;
        cur ^= (uint32_t)1 << k;
    }
    out[h++] = (uint64_t)c->p + dst;
    return h;
}

static void cm_link_ends(const void *st, NetLinkId l, uint64_t *from,
                         uint64_t *to)
{
    const NetCm200 *c = st;
    uint64_t p = c->p;
    if (l < p) {
        *from = l;
        *to = p + l / c->g;
    } else if (l < 2 * p) {
        *from = p + (l - p) / c->g;
        *to = l - p;
    } else if (l < news_base(c)) {
        uint64_t r = (l - 2 * p) / c->d, k = (l - 2 * p) % c->d;
        *from = p + r;
        *to = p + (r ^ ((uint64_t)1 << k));
    } else {
        uint64_t q = (l - news_base(c)) / 4, x = q % c->nx, y = q / c->nx;
        unsigned dir = (unsigned)((l - news_base(c)) % 4);
        x = dir == 0 ? (x + 1) % c->nx : dir == 1 ? (x + c->nx - 1) % c->nx : x;
        y = dir == 2 ? (y + 1) % c->ny : dir == 3 ? (y + c->ny - 1) % c->ny : y;
        *from = q;
        *to = y * c->nx + x;
    }
}

static void cm_link_name(const void *st, NetLinkId l, char *buf, size_t n)
{
    const NetCm200 *c = st;
    uint64_t a, b;
    cm_link_ends(st, l, &a, &b);
    const char *kind = l < 2 * (uint64_t)c->p ? "port"
                       : l < news_base(c)     ? "cube"
                                              : "news";
    snprintf(buf, n, "%s:%s%" G_GUINT64_FORMAT "->%s%" G_GUINT64_FORMAT, kind,
             a < c->p ? "p" : "r", a < c->p ? a : a - c->p,
             b < c->p ? "p" : "r", b < c->p ? b : b - c->p);
}

static double cm_link_bw(const void *st, NetLinkId l, const NetParams *p)
{
    const NetCm200 *c = st;
    if (l < 2 * (uint64_t)c->p)
        return p->bandwidth;
    unsigned cls = l < news_base(c) ? 0 : 1;
    return p->level_bw[cls] > 0.0 ? p->level_bw[cls] : p->bandwidth;
}

const NetTopologyOps net_cm200_ops = {
    .name = "cm200",
    .nodes = cm_nodes,
    .max_hops = cm_max_hops,
    .route = cm_route,
    .link_ends = cm_link_ends,
    .link_name = cm_link_name,
    .link_bw = cm_link_bw,
    .free = g_free,
};

NetTopo *net_cm200_new(unsigned cube_dims, uint32_t group, uint32_t news_x,
                       uint32_t news_y)
{
    g_assert(cube_dims <= 20 && group >= 1);
    NetCm200 *c = g_new0(NetCm200, 1);
    c->d = cube_dims;
    c->g = group;
    c->r = (uint32_t)1 << cube_dims;
    c->p = c->r * group;
    c->nx = news_x;
    c->ny = news_y;
    g_assert((uint64_t)news_x * news_y == c->p);
    return net_topo_wrap(&net_cm200_ops, c, sizeof *c);
}
