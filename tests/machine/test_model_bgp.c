/* test_model_bgp.c — the shipped Blue Gene/P model (models/bgp-intrepid.yaml)
 * as loaded: its documented figures, the torus of a 32,768-node partition
 * (diameter 48 hops, 100 ns per hop, 425 MB/s links), a 256-node block
 * being a mesh (no wrap below a midplane), four processes per node, and
 * partition sizes the model has no shape for being refused, located. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/machine.h"
#include "sim/machine/model.h"
#include "sim/machine/partition.h"
#include "tests/support.h"

typedef struct {
    CfgNode *root;
    SimEngine *eng;
    MachMachine *m;
} Bgp;

/* The model partitioned to n endpoints with `sets` (NULL-terminated). */
static gboolean bgp_open(Bgp *b, guint n, const char *const *sets,
                         GError **err)
{
    *b = (Bgp){.eng = sim_engine_new(1)};
    b->root = mach_partition_root("test", "bgp-intrepid", sets, n, NULL, err);
    if (!b->root)
        return FALSE;
    b->m = mach_new_from_cfg(b->eng, cfg_get(b->root, "machine"), "analytic",
                             err);
    return b->m != NULL;
}

static void bgp_close(Bgp *b)
{
    mach_free(b->m);
    sim_engine_free(b->eng);
    cfg_free(b->root);
}

static NetNet *open_ok(Bgp *b, guint n, const char *const *sets)
{
    GError *err = NULL;
    if (!bgp_open(b, n, sets, &err))
        fail_msg("bgp-intrepid --nodes %u: %s", n, err->message);
    NetNet *net = mach_net(b->m);
    assert_int_equal(net_nodes(net), n);
    return net;
}

static guint hops(NetNet *net, uint32_t a, uint32_t b)
{
    const NetTopo *t = net_topo(net);
    NetLinkId r[256];
    g_assert(t->ops->max_hops(t->state) <= G_N_ELEMENTS(r));
    return t->ops->route(t->state, a, b, r);
}

/* Node id of (x, y, z) on an ex x ey grid (mesh.c: x fastest). */
static uint32_t at(uint32_t ex, uint32_t ey, uint32_t x, uint32_t y,
                   uint32_t z)
{
    return x + ex * (y + ey * z);
}

static void test_node_figures(void **state)
{
    (void)state;
    Bgp b;
    open_ok(&b, 32768, NULL);
    const MachKindInfo *k = mach_kind(b.m, "node");
    assert_int_equal(k->count, 32768);
    const CfgNode *kind = cfg_path(mach_model_cfg(b.m), "nodes.node");
    double clock = 0;
    uint64_t cores = 0, flops = 0;
    assert_true(mach_param_freq(kind, "clock", TRUE, &clock, NULL));
    assert_true(mach_param_count(kind, "cores", TRUE, &cores, NULL));
    assert_true(mach_param_count(kind, "peak_flops", TRUE, &flops, NULL));
    assert_true(clock == 850e6);
    assert_int_equal(cores, 4);
    /* 13.6 Gflop/s = 4 cores x 850 MHz x 4 flops (two FMA pipes). */
    assert_int_equal(flops, cores * 850000000ull * 4);
    const CfgNode *net = cfg_path(mach_model_cfg(b.m), "network");
    double node_bw = 0;
    assert_true(mach_param_bandwidth(net, "node_bandwidth", TRUE, &node_bw,
                                     NULL));
    assert_true(node_bw == 13.6e9);
    /* Every value carries a source or an assumption. */
    for (guint i = 0; i < cfg_map_len(net); i++)
        assert_int_not_equal(
            mach_param_provenance(net, cfg_map_key(net, i), NULL),
            MACH_PROV_NONE);
    bgp_close(&b);
}

/* 32,768 nodes = 32 x 32 x 32 torus: the farthest node is 16 + 16 + 16 =
 * 48 hops away; a message there pays 3 us + 48 x 100 ns + bytes at
 * 425 MB/s; a neighbour across the wrap is 1 hop. */
static void test_torus_32k(void **state)
{
    (void)state;
    Bgp b;
    NetNet *net = open_ok(&b, 32768, NULL);
    assert_string_equal(net_topo(net)->ops->name, "mesh");
    assert_int_equal(hops(net, 0, at(32, 32, 16, 16, 16)), 48);
    assert_int_equal(hops(net, 0, at(32, 32, 31, 31, 31)), 3); /* wraps */
    const NetParams *p = net_params(net);
    assert_true(p->bandwidth == 425e6);
    assert_int_equal(p->per_hop, (100 * SIM_NS));
    SimTime want = (3 * SIM_US) + 48 * (100 * SIM_NS) +
                   sim_time_for_bytes(425e3, 425e6);
    assert_int_equal(net_ideal_time(net, 0, at(32, 32, 16, 16, 16), 425000),
                     want);
    /* The topology's state does not grow with the partition. */
    assert_true(net_topo(net)->state_bytes < 64);
    bgp_close(&b);
}

/* Below a 512-node midplane a block is a mesh: 256 nodes = 4 x 8 x 8,
 * corner to corner 3 + 7 + 7 hops (a torus would take 2 + 4 + 4 = 10);
 * at 512 = 8 x 8 x 8 the wrap is back: corner to corner 3 hops. */
static void test_mesh_below_midplane(void **state)
{
    (void)state;
    Bgp b;
    NetNet *net = open_ok(&b, 256, NULL);
    assert_int_equal(hops(net, 0, 255), 17);
    bgp_close(&b);
    net = open_ok(&b, 512, NULL);
    assert_int_equal(hops(net, 0, 511), 3);
    bgp_close(&b);
    net = open_ok(&b, 32, NULL);
    assert_int_equal(hops(net, 0, 31), 3 + 3 + 1);
    bgp_close(&b);
    open_ok(&b, 40960, NULL); /* the whole machine, 40 x 32 x 32 */
    bgp_close(&b);
    net = open_ok(&b, 4, NULL); /* 2 x 2 x 1, for small runs */
    assert_int_equal(hops(net, 0, 3), 2);
    bgp_close(&b);
}

/* Virtual Node mode: 4 processes per node, 2,048 processes on a 512-node
 * torus; processes 0..3 share node 0 (two hops through its memory at
 * 13.6 GB/s), process 4 is on the next node (one torus hop). */
static void test_four_per_node(void **state)
{
    (void)state;
    const char *sets[] = {"machine.network.node_size=4", NULL};
    Bgp b;
    NetNet *net = open_ok(&b, 2048, sets);
    assert_string_equal(net_topo(net)->ops->name, "group");
    assert_int_equal(hops(net, 0, 3), 2);
    assert_int_equal(hops(net, 0, 4), 1);
    SimTime in = net_ideal_time(net, 0, 3, 1 << 20);
    SimTime out = net_ideal_time(net, 0, 4, 1 << 20);
    assert_true(in < out); /* memory beats a torus link */
    assert_int_equal(in, (3 * SIM_US) + 2 * (100 * SIM_NS) +
                             sim_time_for_bytes(1 << 20, 13.6e9));
    bgp_close(&b);
}

static void expect_refused(guint n, const char *const *sets, const char *what)
{
    GError *err = NULL;
    Bgp b;
    assert_false(bgp_open(&b, n, sets, &err));
    if (!strstr(err->message, what))
        fail_msg("--nodes %u: '%s' lacks '%s'", n, err->message, what);
    g_error_free(err);
    bgp_close(&b);
}

static void test_refused(void **state)
{
    (void)state;
    expect_refused(1000, NULL, "found 1000 processors on a mesh, expected");
    expect_refused(48, NULL, "one of network.shapes");
    const char *vn[] = {"machine.network.node_size=4", NULL};
    expect_refused(2050, vn, "found 513 processors on a mesh"); /* 512 + 1 */
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_node_figures),
        cmocka_unit_test(test_torus_32k),
        cmocka_unit_test(test_mesh_below_midplane),
        cmocka_unit_test(test_four_per_node),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests_name("model_bgp", tests, NULL, NULL);
}
