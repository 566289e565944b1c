/* mnet.c — NetParams and NetTopo from a model's network section.
 *
 * Channel bandwidth, in order of preference: `bandwidth`; else
 * `total_bandwidth` / `channels`; else the first `level_bandwidth`.
 * Start-up: `startup`, and `startup_long` above `long_threshold` (both or
 * neither; the iPSC/2's NX protocol).
 * Switching: the `switching` word, else ring slots for a ring and
 * cut-through packets otherwise (circuit switching is never guessed).
 * Topologies: one small builder per word in topo_table; a mesh or torus
 * takes `extents` or one of its `shapes` (flattened, one per partition
 * size) and is a mesh below `torus_min` nodes; `node_size` endpoints per
 * node (the last one possibly partly used) make it a two-level network
 * (sim/net/group.c) with
 * `node_bandwidth` inside a node and `node_ports` shared (one outer port
 * per node) or per-endpoint.
 * Every number comes from the model; the only defaults are "absent means
 * zero" for start-up and per-hop, and sim/net's own default packet size.
 * Cost: O(1).
 */
#include "sim/machine/mnet.h"
#include "sim/machine/model.h"
#include <string.h>

static const char *const switching_words[] = {
    "circuit", "cut-through", "store-and-forward", "ring-slots", NULL};
static const NetSwitching switching_vals[] = {
    NET_SW_CIRCUIT, NET_SW_CUT_THROUGH, NET_SW_STORE_FORWARD,
    NET_SW_RING_SLOTS};

static gboolean read_switching(const CfgNode *net, NetSwitching *out,
                               GError **err)
{
    const char *topo = mach_param_word(net, "topology");
    const CfgNode *v = mach_param_node(net, "switching");
    *out = topo && strcmp(topo, "ring") == 0 ? NET_SW_RING_SLOTS
                                             : NET_SW_CUT_THROUGH;
    if (!v)
        return TRUE;
    for (guint i = 0; switching_words[i]; i++) {
        if (g_strcmp0(cfg_scalar(v), switching_words[i]) == 0) {
            *out = switching_vals[i];
            return TRUE;
        }
    }
    char *found = g_strdup_printf("switching '%s'", cfg_scalar(v));
    cfg_error(err, v, found,
              "circuit, cut-through, store-and-forward or ring-slots");
    g_free(found);
    return FALSE;
}

static gboolean read_levels(const CfgNode *net, NetParams *out, GError **err)
{
    GArray *lv = NULL;
    if (!mach_param_bw_list(net, "level_bandwidth", FALSE, &lv, err))
        return FALSE;
    if (!lv)
        return TRUE;
    if (lv->len > NET_MAX_LEVELS) {
        cfg_error(err, mach_param_node(net, "level_bandwidth"),
                  "more levels than sim/net supports", "at most 8 levels");
        g_array_unref(lv);
        return FALSE;
    }
    for (guint i = 0; i < lv->len; i++)
        out->level_bw[i] = g_array_index(lv, double, i);
    g_array_unref(lv);
    return TRUE;
}

/* CM-200: level_bw[0] router cube links, level_bw[1] NEWS links. */
static gboolean read_cm_levels(const CfgNode *net, NetParams *out, GError **err)
{
    return mach_param_bandwidth(net, "router_link_bandwidth", FALSE,
                                &out->level_bw[0], err) &&
           mach_param_bandwidth(net, "news_bandwidth", FALSE, &out->level_bw[1],
                                err);
}

static gboolean read_bandwidth(const CfgNode *net, NetParams *out, GError **err)
{
    double total = 0.0;
    if (!mach_param_bandwidth(net, "bandwidth", FALSE, &out->bandwidth, err) ||
        !mach_param_bandwidth(net, "total_bandwidth", FALSE, &total, err))
        return FALSE;
    if (out->bandwidth <= 0.0) /* total 0 (absent) leaves it 0 */
        out->bandwidth = total / out->channels;
    if (out->bandwidth <= 0.0)
        out->bandwidth = out->level_bw[0];
    if (out->bandwidth > 0.0)
        return TRUE;
    cfg_error(err, net, "a network without a usable bandwidth",
              "bandwidth:, total_bandwidth: or level_bandwidth: (> 0)");
    return FALSE;
}

/* The long-message protocol: both keys or neither. */
static gboolean read_long(const CfgNode *net, NetParams *out, GError **err)
{
    const CfgNode *sl = mach_param_node(net, "startup_long");
    const CfgNode *th = mach_param_node(net, "long_threshold");
    if (!mach_param_time(net, "startup_long", FALSE, &out->startup_long, err) ||
        !mach_param_size(net, "long_threshold", FALSE, &out->long_threshold,
                         err))
        return FALSE;
    if (!sl == !th)
        return TRUE;
    cfg_error(err, sl ? sl : th,
              sl ? "startup_long without long_threshold"
                 : "long_threshold without startup_long",
              "both (messages above long_threshold pay startup_long)");
    return FALSE;
}

gboolean mach_net_params(const CfgNode *net, NetParams *out, GError **err)
{
    uint64_t channels = 1, packet = 0;
    *out = (NetParams){0};
    if (!mach_param_count(net, "channels", FALSE, &channels, err) ||
        !mach_param_time(net, "startup", FALSE, &out->startup, err) ||
        !read_long(net, out, err) ||
        !mach_param_time(net, "per_hop", FALSE, &out->per_hop, err) ||
        !mach_param_size(net, "packet_size", FALSE, &packet, err) ||
        !mach_param_bandwidth(net, "node_bandwidth", FALSE, &out->node_bw,
                              err) ||
        !read_switching(net, &out->switching, err) ||
        !read_levels(net, out, err) || !read_cm_levels(net, out, err))
        return FALSE;
    if (channels == 0 || channels > UINT32_MAX || packet > UINT32_MAX) {
        cfg_error(err, net,
                  channels == 0 ? "zero channels"
                                : "an oversized channel/packet",
                  "channels >= 1 and a packet size under 4 GB");
        return FALSE;
    }
    out->channels = (uint32_t)channels;
    out->packet_bytes = (uint32_t)packet;
    return read_bandwidth(net, out, err);
}

/* *out = ceil(log2 n) (0 for n <= 1); TRUE when n is a power of two.
 * n is a guint, so the loop ends at d <= 32 and the shift stays defined;
 * n = 0 gives d = 0 and 1 != 0. */
static gboolean log2_exact(guint n, unsigned *out)
{
    unsigned d = 0;
    while (((uint64_t)1 << d) < n)
        d++;
    *out = d;
    return ((uint64_t)1 << d) == n;
}

static NetTopo *hypercube_new(const CfgNode *net, guint endpoints,
                              const CfgNode *count_at, GError **err)
{
    unsigned d;
    uint64_t dim = 0;
    if (!mach_param_count(net, "dimension", FALSE, &dim, err))
        return NULL;
    if (!log2_exact(endpoints, &d) || d > 24 || (dim && dim != d)) {
        char *found =
            g_strdup_printf("%u processors on a hypercube", endpoints);
        cfg_error(err, count_at ? count_at : mach_param_node(net, "topology"),
                  found,
                  "a power of two up to 2^24 processors "
                  "(= 2^dimension)");
        g_free(found);
        return NULL;
    }
    return net_hypercube_new(d);
}

static NetTopo *ring_new(const CfgNode *net, guint endpoints,
                         const CfgNode *count_at, GError **err)
{
    (void)net;
    if (endpoints < 2) {
        cfg_error(err, count_at, "fewer than 2 stations on a ring",
                  "at least 2 processors");
        return NULL;
    }
    return net_ring_new(endpoints);
}

static NetTopo *fattree_new(const CfgNode *net, guint endpoints,
                            const CfgNode *count_at, GError **err)
{
    uint64_t arity = 0;
    if (!mach_param_count(net, "arity", TRUE, &arity, err))
        return NULL;
    if (arity < 2 || arity > 64 || endpoints < 2) {
        cfg_error(err,
                  arity < 2 || arity > 64 ? mach_param_node(net, "arity")
                                          : count_at,
                  arity < 2 || arity > 64 ? "an unusable fat-tree arity"
                                          : "fewer than 2 leaves",
                  "arity 2..64 and at least 2 processors");
        return NULL;
    }
    return net_fattree_new(endpoints, (unsigned)arity);
}

/* CM-200: endpoints are SIMD lanes, 2^d routers x procs_per_router, on a
 * NEWS grid as square as a power of two allows. */
static NetTopo *cm_new(const CfgNode *net, guint endpoints,
                       const CfgNode *count_at, GError **err)
{
    uint64_t group = 0, routers = 0;
    unsigned d, half;
    if (!mach_param_count(net, "procs_per_router", TRUE, &group, err) ||
        !mach_param_count(net, "router_nodes", FALSE, &routers, err))
        return NULL;
    if (group == 0 || endpoints % group || !log2_exact(endpoints, &half) ||
        !log2_exact(endpoints / group, &d) || d > 20 ||
        (routers && routers != endpoints / group)) {
        char *found = g_strdup_printf("%u lanes for router_nodes x "
                                      "procs_per_router",
                                      endpoints);
        cfg_error(err, count_at, found,
                  "lanes = 2^d x procs_per_router "
                  "(d <= 20) = router_nodes x procs_per_router");
        g_free(found);
        return NULL;
    }
    uint32_t nx = (uint32_t)1 << ((half + 1) / 2);
    return net_cm200_new(d, (uint32_t)group, nx, endpoints / nx);
}

/* TRUE when every count of a is in 1 .. 2^24. */
static gboolean extents_ok(const GArray *a)
{
    for (guint i = 0; i < a->len; i++) {
        uint64_t x = g_array_index(a, uint64_t, i);
        if (x < 1 || x > (1u << 24))
            return FALSE;
    }
    return TRUE;
}

/* The product of shape s (nd values) of a. */
static uint64_t shape_prod(const GArray *a, guint s, guint nd)
{
    uint64_t prod = 1;
    for (guint k = 0; k < nd; k++)
        prod *= g_array_index(a, uint64_t, s * nd + k);
    return prod;
}

/* Copies into e[] the first shape of a (nd values each) whose product
 * is nodes; FALSE if none. */
static gboolean pick_shape(const GArray *a, guint nd, guint nodes,
                           uint32_t e[3])
{
    for (guint s = 0; a && s < a->len / nd; s++) {
        if (shape_prod(a, s, nd) != nodes)
            continue;
        for (guint k = 0; k < nd; k++)
            e[k] = (uint32_t)g_array_index(a, uint64_t, s * nd + k);
        return TRUE;
    }
    return FALSE;
}

/* The shape for `nodes`: `extents` if their product is nodes, else the
 * first of the flattened `shapes` (as many values per shape as extents)
 * whose product is; e[] gets it.  Returns the dimension count, 0 with
 * *err on unusable values or no shape of that size. */
static guint grid_shape(const CfgNode *net, guint nodes, const CfgNode *count_at,
                        uint32_t e[3], GError **err)
{
    GArray *ext = NULL, *shapes = NULL;
    if (!mach_param_count_list(net, "extents", TRUE, &ext, err))
        return 0;
    if (!mach_param_count_list(net, "shapes", FALSE, &shapes, err)) {
        g_array_unref(ext);
        return 0;
    }
    guint nd = ext->len, found = 0;
    uint64_t prod = nd ? shape_prod(ext, 0, nd) : 0;
    if (nd < 1 || nd > 3 || !extents_ok(ext))
        cfg_error(err, mach_param_node(net, "extents"), "unusable mesh extents",
                  "1 to 3 extents of 1 .. 2^24");
    else if (shapes && (shapes->len % nd || !extents_ok(shapes)))
        cfg_error(err, mach_param_node(net, "shapes"), "unusable shapes",
                  "whole shapes of as many extents of 1 .. 2^24 as "
                  "network.extents has");
    else if (pick_shape(ext, nd, nodes, e) || pick_shape(shapes, nd, nodes, e))
        found = nd;
    else {
        char *f = shapes ? g_strdup_printf("%u processors on a mesh", nodes)
                         : g_strdup_printf("%u processors on a mesh of "
                                           "%" G_GUINT64_FORMAT " nodes",
                                           nodes, prod);
        cfg_error(err, count_at, f,
                  shapes ? "the product of network.extents or of one of "
                           "network.shapes"
                         : "the product of network.extents");
        g_free(f);
    }
    g_array_unref(ext);
    if (shapes)
        g_array_unref(shapes);
    return found;
}

/* Mesh / torus: `extents` (1 to 3 dimensions), or one of `shapes`, whose
 * product is the node count; a torus of fewer than `torus_min` nodes is
 * a mesh (Blue Gene/P blocks under a midplane). */
static NetTopo *grid_new(const CfgNode *net, guint endpoints,
                         const CfgNode *count_at, gboolean wrap, GError **err)
{
    uint32_t e[3];
    uint64_t torus_min = 0;
    if (!mach_param_count(net, "torus_min", FALSE, &torus_min, err))
        return NULL;
    guint nd = grid_shape(net, endpoints, count_at, e, err);
    if (!nd)
        return NULL;
    return net_mesh_new(nd, e, wrap && endpoints >= torus_min);
}

static NetTopo *mesh_new(const CfgNode *net, guint endpoints,
                         const CfgNode *count_at, GError **err)
{
    return grid_new(net, endpoints, count_at, FALSE, err);
}

static NetTopo *torus_new(const CfgNode *net, guint endpoints,
                          const CfgNode *count_at, GError **err)
{
    return grid_new(net, endpoints, count_at, TRUE, err);
}

static NetTopo *crossbar_new(const CfgNode *net, guint endpoints,
                             const CfgNode *count_at, GError **err)
{
    (void)net;
    (void)count_at;
    (void)err;
    return net_crossbar_new(endpoints);
}

static NetTopo *bus_new(const CfgNode *net, guint endpoints,
                        const CfgNode *count_at, GError **err)
{
    (void)net;
    (void)count_at;
    (void)err;
    return net_bus_new(endpoints);
}

typedef NetTopo *(*MachTopoFn)(const CfgNode *net, guint endpoints,
                               const CfgNode *count_at, GError **err);

static const struct {
    const char *word;
    MachTopoFn fn;
} topo_table[] = {
    {"hypercube", hypercube_new}, {"ring", ring_new},
    {"fat-tree", fattree_new},    {"cm-router", cm_new},
    {"crossbar", crossbar_new},   {"bus", bus_new},
    {"mesh", mesh_new},           {"torus", torus_new},
};

static MachTopoFn topo_fn(const char *word)
{
    for (guint i = 0; i < G_N_ELEMENTS(topo_table); i++)
        if (g_strcmp0(word, topo_table[i].word) == 0)
            return topo_table[i].fn;
    return NULL;
}

gboolean mach_topo_supported(const char *topology)
{
    return topo_fn(topology) != NULL;
}

/* Two-level networks (sim/net/group.c): `node_size` endpoints per node,
 * `node_ports` shared (the outer topology joins nodes) or per-endpoint
 * (it joins endpoints).  *outer_n: the outer topology's node count. */
static gboolean read_group(const CfgNode *net, guint endpoints,
                           uint64_t *size, gboolean *per_endpoint,
                           guint *outer_n, GError **err)
{
    const char *ports = mach_param_word(net, "node_ports");
    *size = 1;
    *per_endpoint = g_strcmp0(ports, "per-endpoint") == 0;
    if (!mach_param_count(net, "node_size", FALSE, size, err))
        return FALSE;
    if (ports && !*per_endpoint && strcmp(ports, "shared") != 0) {
        char *found = g_strdup_printf("node_ports '%s'", ports);
        cfg_error(err, mach_param_node(net, "node_ports"), found,
                  "shared or per-endpoint");
        g_free(found);
        return FALSE;
    }
    if (*size == 0 || *size > UINT32_MAX) {
        cfg_error(err, mach_param_node(net, "node_size"),
                  "an unusable node_size", "1 .. 2^32 - 1 endpoints a node");
        return FALSE;
    }
    /* The last node may be partly used (4 GPUs of a DGX). */
    *outer_n = *per_endpoint ? endpoints
                             : (guint)((endpoints + *size - 1) / *size);
    return TRUE;
}

NetTopo *mach_topo_new(const CfgNode *net, guint endpoints,
                       const CfgNode *count_at, GError **err)
{
    const char *topo = mach_param_word(net, "topology");
    MachTopoFn fn = topo_fn(topo);
    uint64_t size;
    gboolean per_endpoint;
    guint outer_n;
    if (!count_at)
        count_at = net;
    if (fn) {
        if (!read_group(net, endpoints, &size, &per_endpoint, &outer_n,
                        err))
            return NULL;
        NetTopo *t = fn(net, outer_n, count_at, err);
        if (t && size > 1)
            t = net_group_new(t, (uint32_t)size, per_endpoint, endpoints);
        return t;
    }
    char *found = g_strdup_printf("topology '%s' (not built by the machine "
                                  "layer)",
                                  topo ? topo : "");
    cfg_error(err, mach_param_node(net, "topology"), found,
              "hypercube, ring, fat-tree, cm-router, mesh, torus, "
              "crossbar or bus");
    g_free(found);
    return NULL;
}
