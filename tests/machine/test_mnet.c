/* test_mnet.c — networks built from models: a mesh/torus machine described
 * in YAML (tests/data/models/mesh2d.yaml), the long-message keys, and a
 * 65,536-node hypercube built through the machine layer with --set
 * overrides that still costs kilobytes while it carries one message.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <malloc.h>
#include <string.h>

#include "sim/machine/machine.h"
#include "tests/support.h"

static void arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    *(SimTime *)ctx = d->arrived;
}

/* A run config with the given machine section text. */
static MachMachine *from_text(SimEngine *eng, const char *text, const char *fid,
                              CfgNode **root, GError **err)
{
    *root = cfg_load_string(text, "run.yaml", err);
    assert_non_null(*root);
    return mach_new_from_cfg(eng, cfg_get(*root, "machine"), fid, err);
}

static void expect_error(const char *text, const char *prefix,
                         const char *needle)
{
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    assert_null(from_text(eng, text, "flow", &root, &err));
    assert_non_null(err);
    if (!g_str_has_prefix(err->message, prefix) ||
        !strstr(err->message, needle))
        fail_msg("got '%s', want '%s...%s'", err->message, prefix, needle);
    g_error_free(err);
    cfg_free(root);
    sim_engine_free(eng);
}

/* The mesh model: 16 nodes, dimension-order routes (hops = Manhattan
 * distance), a lone message at the analytic time at every fidelity. */
static void test_mesh_model(void **state)
{
    (void)state;
    static const char *const fids[] = {"analytic", "flow", "packet"};
    for (guint f = 0; f < G_N_ELEMENTS(fids); f++) {
        SimEngine *eng = sim_engine_new(1);
        GError *err = NULL;
        MachMachine *m = mach_new_from_model(eng, "mesh2d", fids[f], &err);
        if (!m)
            fail_msg("%s", err->message);
        NetNet *net = mach_net(m);
        assert_int_equal(net_nodes(net), 16);
        assert_string_equal(net_topo(net)->ops->name, "mesh");
        SimTime at = 0;
        net_send(net, 0, 15, 1000, NULL, arrived, &at); /* (0,0)->(3,3) */
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        /* 20 us + 6 hops x 1 us + 1000 B at 10 MB/s (100 B packets) */
        assert_int_equal(at, 20 * SIM_US + 6 * SIM_US + 100 * SIM_US);
        assert_int_equal(net_ideal_time(net, 0, 15, 1000), at);
        mach_free(m);
        sim_engine_free(eng);
    }
}

/* The same machine as a torus, by override: (0,0)->(3,3) wraps, 2 hops;
 * and other extents for other node counts. */
static void test_torus_override(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    MachMachine *m = from_text(eng,
                               "machine:\n  model: mesh2d\n"
                               "  network: {topology: torus}\n",
                               "analytic", &root, &err);
    if (!m)
        fail_msg("%s", err->message);
    assert_int_equal(net_ideal_time(mach_net(m), 0, 15, 0),
                     20 * SIM_US + 2 * SIM_US);
    mach_free(m);
    cfg_free(root);
    m = from_text(eng,
                  "machine:\n  model: mesh2d\n"
                  "  nodes: {node: {count: 24}}\n"
                  "  network: {extents: [2, 3, 4]}\n",
                  "analytic", &root, &err);
    if (!m)
        fail_msg("%s", err->message);
    assert_int_equal(net_nodes(mach_net(m)), 24);
    /* (0,0,0) -> (1,2,3): 1 + 2 + 3 hops */
    assert_int_equal(net_ideal_time(mach_net(m), 0, 23, 0),
                     20 * SIM_US + 6 * SIM_US);
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
}

static void test_mesh_errors(void **state)
{
    (void)state;
    /* 12 processors do not fill 4 x 4: located at the count */
    expect_error("machine:\n  model: mesh2d\n  nodes: {node: {count: 12}}\n",
                 "run.yaml:3:", "12 processors on a mesh of 16 nodes");
    expect_error("machine:\n  model: mesh2d\n"
                 "  nodes: {node: {count: 16}}\n"
                 "  network: {extents: [2, 2, 2, 2]}\n",
                 "run.yaml:4:", "unusable mesh extents");
    expect_error("machine:\n  model: mesh2d\n"
                 "  network: {extents: [4, 4 us]}\n",
                 "run.yaml:3:", "4 us");
}

/* startup_long without long_threshold is refused where it is written. */
static void test_long_needs_threshold(void **state)
{
    (void)state;
    expect_error("machine:\n  model: mesh2d\n"
                 "  network: {startup_long: 700 us}\n",
                 "run.yaml:3:", "startup_long without long_threshold");
    expect_error("machine:\n  model: mesh2d\n"
                 "  network: {long_threshold: 100 B}\n",
                 "run.yaml:3:", "long_threshold without startup_long");
}

static size_t heap_in_use(void)
{
    return mallinfo2().uordblks;
}

/* "A 65,536-node hypercube carrying one message costs kilobytes, not
 * megabytes", built through the machine layer: models/ipsc2.yaml with the
 * node count and the cube's dimension overridden as `--set` does.  The
 * heap (glibc's count of bytes in use) grows by kilobytes for the whole
 * machine, model tree included; the network itself holds its 16 links. */
static void test_lazy_64k_through_model(void **state)
{
    (void)state;
    static const char *const fids[] = {"analytic", "flow", "packet"};
    for (guint f = 0; f < G_N_ELEMENTS(fids); f++) {
        GError *err = NULL;
        CfgNode *root =
            cfg_load_string("machine: {model: ipsc2}\n", "run.yaml", &err);
        assert_true(
            cfg_set_override(root, "machine.nodes.node.count=65536", &err));
        assert_true(
            cfg_set_override(root, "machine.network.dimension=16", &err));
        SimEngine *eng = sim_engine_new(1);
        size_t before = heap_in_use();
        MachMachine *m =
            mach_new_from_cfg(eng, cfg_get(root, "machine"), fids[f], &err);
        if (!m)
            fail_msg("%s", err->message);
        NetNet *net = mach_net(m);
        assert_int_equal(net_nodes(net), 65536);
        assert_int_equal(mach_proc_total(m), 65536);
        SimTime at = 0;
        net_send(net, 0, 65535, 4096, NULL, arrived, &at);
        assert_int_equal(net_links_touched(net), 16);
        assert_true(net_tracked_bytes(net) < 8192);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_true(at > 0);
        size_t grew = heap_in_use() - before;
        if (!g_getenv("PGSIM_SANITIZE") && grew > 256 * 1024)
            fail_msg("%s: the machine holds %zu bytes", fids[f], grew);
        mach_free(m);
        sim_engine_free(eng);
        cfg_free(root);
    }
}

/* A dimension that disagrees with the node count is a located error. */
static void test_dimension_mismatch(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root =
        cfg_load_string("machine: {model: ipsc2}\n", "run.yaml", &err);
    assert_true(cfg_set_override(root, "machine.network.dimension=16", &err));
    SimEngine *eng = sim_engine_new(1);
    assert_null(mach_new_from_cfg(eng, cfg_get(root, "machine"), "flow", &err));
    assert_non_null(strstr(err->message, "processors on a hypercube"));
    assert_non_null(strstr(err->message, "2^dimension"));
    g_error_free(err);
    sim_engine_free(eng);
    cfg_free(root);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mesh_model),
        cmocka_unit_test(test_torus_override),
        cmocka_unit_test(test_mesh_errors),
        cmocka_unit_test(test_long_needs_threshold),
        cmocka_unit_test(test_lazy_64k_through_model),
        cmocka_unit_test(test_dimension_mismatch),
    };
    return cmocka_run_group_tests_name("machine_mnet", tests, support_test_models,
                                       NULL);
}
