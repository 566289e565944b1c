/* test_mnet_params.c — every field of the NetParams that mach_net_params
 * fills from a network section (sim/machine/mnet.c), exactly: defaults of
 * absent keys, each bandwidth source in its order of preference down to
 * 1 B/s, the level lists (unused levels stay 0), the CM-200 level keys,
 * the switching word, and each refusal at its file:line:column. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/mnet.h"
#include "tests/support.h"

/* mach_net_params of the map `net: {...}` written on one line. */
static gboolean params(const char *net, NetParams *p, GError **err)
{
    char *text = g_strdup_printf("net: %s\n", net);
    CfgNode *root = cfg_load_string(text, "n.yaml", err);
    assert_non_null(root);
    memset(p, 0xab, sizeof *p); /* every field must be written */
    gboolean ok = mach_net_params(cfg_get(root, "net"), p, err);
    cfg_free(root);
    g_free(text);
    return ok;
}

static void params_ok(const char *net, NetParams *p)
{
    GError *err = NULL;
    if (!params(net, p, &err))
        fail_msg("%s: %s", net, err->message);
}

static void params_bad(const char *net, const char *want)
{
    GError *err = NULL;
    NetParams p;
    assert_false(params(net, &p, &err));
    assert_non_null(err);
    if (strcmp(err->message, want) != 0)
        fail_msg("%s:\n got '%s'\nwant '%s'", net, err->message, want);
    g_error_free(err);
}

static void levels_zero_from(const NetParams *p, guint from)
{
    for (guint i = from; i < NET_MAX_LEVELS; i++)
        if (p->level_bw[i] != 0.0)
            fail_msg("level_bw[%u] = %g, want 0", i, p->level_bw[i]);
}

static void test_defaults(void **state)
{
    (void)state;
    NetParams p;
    params_ok("{topology: hypercube, bandwidth: 1 B/s}", &p);
    assert_true(p.bandwidth == 1.0);
    assert_int_equal(p.channels, 1);
    assert_int_equal(p.startup, 0);
    assert_int_equal(p.startup_long, 0);
    assert_int_equal(p.long_threshold, 0);
    assert_int_equal(p.per_hop, 0);
    assert_int_equal(p.packet_bytes, 0);
    assert_int_equal(p.switching, NET_SW_CUT_THROUGH);
    assert_int_equal(p.ctrl_latency, 0);
    assert_true(p.ctrl_bandwidth == 0.0);
    levels_zero_from(&p, 0);
    params_ok("{topology: ring, bandwidth: 2 MB/s}", &p);
    assert_int_equal(p.switching, NET_SW_RING_SLOTS);
}

static void test_every_key(void **state)
{
    (void)state;
    NetParams p;
    params_ok("{topology: ring, bandwidth: 3 MB/s, channels: 4, startup: 5 us,"
              " startup_long: 7 us, long_threshold: 100 B, per_hop: 2 ns,"
              " packet_size: 64 B, switching: circuit}", &p);
    assert_true(p.bandwidth == 3e6);
    assert_int_equal(p.channels, 4);
    assert_int_equal(p.startup, 5 * SIM_US);
    assert_int_equal(p.startup_long, 7 * SIM_US);
    assert_int_equal(p.long_threshold, 100);
    assert_int_equal(p.per_hop, 2 * SIM_NS);
    assert_int_equal(p.packet_bytes, 64);
    assert_int_equal(p.switching, NET_SW_CIRCUIT);
    static const char *const words[] = {"circuit", "cut-through",
                                        "store-and-forward", "ring-slots"};
    static const NetSwitching vals[] = {NET_SW_CIRCUIT, NET_SW_CUT_THROUGH,
                                        NET_SW_STORE_FORWARD,
                                        NET_SW_RING_SLOTS};
    for (guint i = 0; i < 4; i++) {
        char *net = g_strdup_printf("{topology: ring, bandwidth: 1 MB/s, "
                                    "switching: %s}", words[i]);
        params_ok(net, &p);
        assert_int_equal(p.switching, vals[i]);
        g_free(net);
    }
    params_ok("{topology: bus, bandwidth: 1 MB/s, channels: 4294967295,"
              " packet_size: 4294967295 B}", &p);
    assert_int_equal(p.channels, UINT32_MAX);
    assert_int_equal(p.packet_bytes, UINT32_MAX);
}

/* bandwidth, else total_bandwidth / channels, else level_bandwidth[0] */
static void test_bandwidth_sources(void **state)
{
    (void)state;
    NetParams p;
    params_ok("{topology: ring, channels: 2, total_bandwidth: 2 B/s}", &p);
    assert_true(p.bandwidth == 1.0);
    params_ok("{topology: ring, channels: 4, total_bandwidth: 10 MB/s,"
              " bandwidth: 3 MB/s}", &p);
    assert_true(p.bandwidth == 3e6);
    params_ok("{topology: fat-tree, level_bandwidth: [1 B/s, 2 MB/s]}", &p);
    assert_true(p.bandwidth == 1.0);
    assert_true(p.level_bw[0] == 1.0 && p.level_bw[1] == 2e6);
    levels_zero_from(&p, 2);
    params_ok("{topology: fat-tree, bandwidth: 9 MB/s, level_bandwidth:"
              " [1 B/s, 2 B/s, 3 B/s, 4 B/s, 5 B/s, 6 B/s, 7 B/s, 8 B/s]}",
              &p);
    assert_true(p.bandwidth == 9e6);
    for (guint i = 0; i < NET_MAX_LEVELS; i++)
        assert_true(p.level_bw[i] == i + 1.0);
    params_ok("{topology: cm-router, bandwidth: 1 MB/s,"
              " router_link_bandwidth: 3 MB/s, news_bandwidth: 5 MB/s}", &p);
    assert_true(p.level_bw[0] == 3e6 && p.level_bw[1] == 5e6);
    levels_zero_from(&p, 2);
    params_ok("{topology: cm-router, bandwidth: 1 MB/s,"
              " news_bandwidth: 5 MB/s}", &p);
    assert_true(p.level_bw[0] == 0.0 && p.level_bw[1] == 5e6);
    params_ok("{topology: cm-router, router_link_bandwidth: 3 MB/s}", &p);
    assert_true(p.bandwidth == 3e6 && p.level_bw[0] == 3e6);
    levels_zero_from(&p, 1);
}

static void test_refusals(void **state)
{
    (void)state;
    params_bad("{topology: ring}",
               "n.yaml:1:6: found a network without a usable bandwidth, "
               "expected bandwidth:, total_bandwidth: or level_bandwidth: "
               "(> 0)");
    params_bad("{topology: ring, bandwidth: 0 B/s}",
               "n.yaml:1:6: found a network without a usable bandwidth, "
               "expected bandwidth:, total_bandwidth: or level_bandwidth: "
               "(> 0)");
    params_bad("{topology: ring, bandwidth: 1 MB/s, channels: 0}",
               "n.yaml:1:6: found zero channels, expected channels >= 1 and "
               "a packet size under 4 GB");
    params_bad("{topology: ring, bandwidth: 1 MB/s, channels: 4294967296}",
               "n.yaml:1:6: found an oversized channel/packet, expected "
               "channels >= 1 and a packet size under 4 GB");
    params_bad("{topology: ring, bandwidth: 1 MB/s, packet_size: 4294967296 B}",
               "n.yaml:1:6: found an oversized channel/packet, expected "
               "channels >= 1 and a packet size under 4 GB");
    params_bad("{topology: ring, bandwidth: 1 MB/s, switching: wormhole}",
               "n.yaml:1:53: found switching 'wormhole', expected circuit, "
               "cut-through, store-and-forward or ring-slots");
    params_bad("{topology: ring, bandwidth: 1 MB/s, startup_long: 5 us}",
               "n.yaml:1:56: found startup_long without long_threshold, "
               "expected both (messages above long_threshold pay "
               "startup_long)");
    params_bad("{topology: ring, bandwidth: 1 MB/s, long_threshold: 5 B}",
               "n.yaml:1:58: found long_threshold without startup_long, "
               "expected both (messages above long_threshold pay "
               "startup_long)");
    params_bad("{topology: fat-tree, level_bandwidth: [1 B/s, 2 B/s, 3 B/s,"
               " 4 B/s, 5 B/s, 6 B/s, 7 B/s, 8 B/s, 9 B/s]}",
               "n.yaml:1:44: found more levels than sim/net supports, "
               "expected at most 8 levels");
}

/* A bad value of each key is refused (and nothing after it is read). */
static void test_bad_values(void **state)
{
    (void)state;
    static const char *const keys[] = {
        "channels: x", "startup: x", "startup_long: x, long_threshold: 1 B",
        "startup_long: 1 us, long_threshold: x", "per_hop: x",
        "packet_size: x", "level_bandwidth: [x]",
        "router_link_bandwidth: x", "news_bandwidth: x", "total_bandwidth: x",
    };
    for (guint i = 0; i < G_N_ELEMENTS(keys); i++) {
        char *net = g_strdup_printf("{topology: ring, bandwidth: 1 MB/s, %s}",
                                    keys[i]);
        GError *err = NULL;
        NetParams p;
        assert_false(params(net, &p, &err));
        if (!err || !g_str_has_prefix(err->message, "n.yaml:1:") ||
            !strstr(err->message, "found 'x'"))
            fail_msg("%s: %s", net, err ? err->message : "no error");
        g_error_free(err);
        g_free(net);
    }
}

/* mach_topo_new on the map `net: {...}` for `endpoints` processors: the
 * topology (or NULL) and its error, whose location is checked by the
 * caller. */
static NetTopo *topo(const char *net, guint endpoints, char **msg)
{
    char *text = g_strdup_printf("net: %s\n", net);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "n.yaml", &err);
    assert_non_null(root);
    NetTopo *t = mach_topo_new(cfg_get(root, "net"), endpoints, NULL, &err);
    assert_true((t == NULL) == (err != NULL));
    *msg = err ? g_strdup(err->message) : NULL;
    g_clear_error(&err);
    cfg_free(root);
    g_free(text);
    return t;
}

/* A topology of `nodes` nodes, `hops` maximum hops and `name` ops. */
static void topo_ok(const char *net, guint endpoints, const char *name,
                    guint hops)
{
    char *msg = NULL;
    NetTopo *t = topo(net, endpoints, &msg);
    if (!t)
        fail_msg("%s on %u: %s", net, endpoints, msg);
    assert_string_equal(t->ops->name, name);
    assert_int_equal(net_topo_nodes(t), endpoints);
    if (t->ops->max_hops(t->state) != hops)
        fail_msg("%s on %u: %u hops, want %u", net, endpoints,
                 t->ops->max_hops(t->state), hops);
    net_topo_free(t);
}

static void topo_bad(const char *net, guint endpoints, const char *want)
{
    char *msg = NULL;
    NetTopo *t = topo(net, endpoints, &msg);
    if (t)
        fail_msg("%s on %u: accepted", net, endpoints);
    if (strcmp(msg, want) != 0)
        fail_msg("%s on %u:\n got '%s'\nwant '%s'", net, endpoints, msg, want);
    g_free(msg);
}

#define CUBE_EXP "expected a power of two up to 2^24 processors (= 2^dimension)"
#define FT_EXP "expected arity 2..64 and at least 2 processors"
#define CM_EXP                                                                 \
    "expected lanes = 2^d x procs_per_router (d <= 20) = router_nodes x "      \
    "procs_per_router"

static void test_topologies(void **state)
{
    (void)state;
    topo_ok("{topology: hypercube}", 8, "hypercube", 3);
    topo_ok("{topology: hypercube}", 1, "hypercube", 0);
    topo_ok("{topology: hypercube, dimension: 3}", 8, "hypercube", 3);
    topo_ok("{topology: hypercube}", 1u << 24, "hypercube", 24);
    topo_bad("{topology: hypercube}", 6,
             "n.yaml:1:6: found 6 processors on a hypercube, " CUBE_EXP);
    topo_bad("{topology: hypercube}", 1u << 25,
             "n.yaml:1:6: found 33554432 processors on a hypercube, " CUBE_EXP);
    topo_bad("{topology: hypercube, dimension: 2}", 8,
             "n.yaml:1:6: found 8 processors on a hypercube, " CUBE_EXP);
    topo_ok("{topology: ring}", 2, "ring", 1);
    topo_bad("{topology: ring}", 1,
             "n.yaml:1:6: found fewer than 2 stations on a ring, expected at "
             "least 2 processors");
    topo_ok("{topology: fat-tree, arity: 2}", 2, "fat-tree", 2);
    topo_ok("{topology: fat-tree, arity: 64}", 64, "fat-tree", 2);
    topo_bad("{topology: fat-tree, arity: 1}", 8,
             "n.yaml:1:34: found an unusable fat-tree arity, " FT_EXP);
    topo_bad("{topology: fat-tree, arity: 65}", 8,
             "n.yaml:1:34: found an unusable fat-tree arity, " FT_EXP);
    topo_bad("{topology: fat-tree, arity: 2}", 1,
             "n.yaml:1:6: found fewer than 2 leaves, " FT_EXP);
    topo_ok("{topology: crossbar}", 3, "crossbar", 2);
    topo_ok("{topology: bus}", 3, "bus", 1);
    /* a mesh's hop bound is the sum of its extents (mesh.c) */
    topo_ok("{topology: mesh, extents: [4, 2]}", 8, "mesh", 6);
    topo_ok("{topology: torus, extents: [4, 2]}", 8, "mesh", 6);
    /* 0 -> 3 on 4 x 2: three hops on the mesh, one round the torus */
    for (guint wrap = 0; wrap < 2; wrap++) {
        char *msg = NULL;
        NetTopo *t = topo(wrap ? "{topology: torus, extents: [4, 2]}"
                               : "{topology: mesh, extents: [4, 2]}", 8, &msg);
        NetLinkId r[8];
        assert_int_equal(t->ops->route(t->state, 0, 3, r), wrap ? 1 : 3);
        net_topo_free(t);
    }
    topo_ok("{topology: mesh, extents: [2, 1, 3]}", 6, "mesh", 6);
    topo_ok("{topology: mesh, extents: [16777216]}", 1u << 24, "mesh",
            1u << 24);
    topo_bad("{topology: mesh, extents: [4, 2]}", 9,
             "n.yaml:1:6: found 9 processors on a mesh of 8 nodes, expected "
             "the product of network.extents");
    static const char *const bad_ext[] = {"[]", "[1, 1, 1, 1]", "[0, 4]",
                                          "[16777217]"};
    for (guint i = 0; i < G_N_ELEMENTS(bad_ext); i++) {
        char *net = g_strdup_printf("{topology: torus, extents: %s}",
                                    bad_ext[i]);
        topo_bad(net, 4, "n.yaml:1:33: found unusable mesh extents, expected "
                         "1 to 3 extents of 1 .. 2^24");
        g_free(net);
    }
    topo_bad("{topology: star}", 4,
             "n.yaml:1:17: found topology 'star' (not built by the machine "
             "layer), expected hypercube, ring, fat-tree, cm-router, mesh, "
             "torus, crossbar or bus");
    assert_true(mach_topo_supported("torus"));
    assert_true(mach_topo_supported("bus"));
    assert_false(mach_topo_supported("star"));
}

/* CM-200: lanes = 2^d routers x procs_per_router on a NEWS grid of
 * 2^ceil(half) columns: 32 lanes are 8 x 4, so lane 8 is lane 0's +y
 * neighbour (one NEWS hop), 16 lanes are 4 x 4. */
static void test_cm_router(void **state)
{
    (void)state;
    char *msg = NULL;
    NetTopo *t = topo("{topology: cm-router, procs_per_router: 4}", 32, &msg);
    assert_non_null(t);
    assert_int_equal(t->ops->max_hops(t->state), 5);
    NetLinkId r[8];
    assert_int_equal(t->ops->route(t->state, 0, 8, r), 1);
    assert_int_equal(t->ops->route(t->state, 0, 4, r), 3); /* routers 0, 1 */
    net_topo_free(t);
    t = topo("{topology: cm-router, procs_per_router: 4, router_nodes: 4}",
             16, &msg);
    assert_non_null(t);
    assert_int_equal(t->ops->max_hops(t->state), 4);
    assert_int_equal(t->ops->route(t->state, 0, 4, r), 1);
    assert_int_equal(t->ops->route(t->state, 0, 8, r), 3); /* r0 -> r2 */
    net_topo_free(t);
    topo_ok("{topology: cm-router, procs_per_router: 1}", 1u << 20,
            "cm200", 22);
    topo_ok("{topology: cm-router, procs_per_router: 2}", 2, "cm200", 2);
    static const struct {
        const char *net;
        guint lanes;
    } bad[] = {
        {"{topology: cm-router, procs_per_router: 0}", 16},
        {"{topology: cm-router, procs_per_router: 3}", 16},
        {"{topology: cm-router, procs_per_router: 3}", 12},
        {"{topology: cm-router, procs_per_router: 4, router_nodes: 2}", 16},
        {"{topology: cm-router, procs_per_router: 1}", 1u << 21},
    };
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        char *want = g_strdup_printf("n.yaml:1:6: found %u lanes for "
                                     "router_nodes x procs_per_router, " CM_EXP,
                                     bad[i].lanes);
        topo_bad(bad[i].net, bad[i].lanes, want);
        g_free(want);
    }
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_every_key),
        cmocka_unit_test(test_bandwidth_sources),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_bad_values),
        cmocka_unit_test(test_topologies),
        cmocka_unit_test(test_cm_router),
    };
    return cmocka_run_group_tests_name("mnet_params", tests, NULL, NULL);
}
