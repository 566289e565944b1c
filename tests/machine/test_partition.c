/* test_partition.c — machine models sized to N network endpoints
 * (sim/machine/partition.h): the counts chosen per topology, the
 * overrides being reported as overrides, and N that a topology refuses.
 */
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
    char *desc;
} Part;

/* Partitions `model` to n and builds it; NULL m with *err on failure. */
static gboolean part_open(Part *p, const char *model, guint n, GError **err)
{
    char *text = g_strdup_printf("machine: {model: %s}\n", model);
    *p = (Part){.root = cfg_load_string(text, "run.yaml", err)};
    g_free(text);
    assert_non_null(p->root);
    p->eng = sim_engine_new(1);
    if (!mach_partition(p->root, n, &p->desc, err))
        return FALSE;
    p->m = mach_new_from_cfg(p->eng, cfg_get(p->root, "machine"), "flow", err);
    return p->m != NULL;
}

static void part_close(Part *p)
{
    mach_free(p->m);
    sim_engine_free(p->eng);
    cfg_free(p->root);
    g_free(p->desc);
}

static void expect_ok(Part *p, const char *model, guint n)
{
    GError *err = NULL;
    if (!part_open(p, model, n, &err))
        fail_msg("%s --nodes %u: %s", model, n, err->message);
    assert_int_equal(net_nodes(mach_net(p->m)), n);
}

static void test_hypercube_and_fat_tree(void **state)
{
    (void)state;
    Part p;
    expect_ok(&p, "ipsc2", 256);
    assert_int_equal(mach_kind(p.m, "node")->count, 256);
    assert_string_equal(p.desc, "node 256");
    const CfgNode *kind = cfg_path(mach_model_cfg(p.m), "nodes.node");
    assert_int_equal(mach_param_provenance(kind, "count", NULL),
                     MACH_PROV_OVERRIDE);
    part_close(&p);
    expect_ok(&p, "cm5", 100); /* a fat tree takes any count */
    assert_int_equal(mach_proc_total(p.m), 100);
    part_close(&p);
    expect_ok(&p, "cluster-ib", 256);
    part_close(&p);
}

/* Pixel-Planes 5: host and frame buffer stay single; GPs and renderers
 * share the rest evenly (their model counts are equal). */
static void test_ring_split(void **state)
{
    (void)state;
    Part p;
    expect_ok(&p, "pixel-planes-5", 32);
    assert_string_equal(p.desc, "host 1, gp 15, renderer 15, frame_buffer 1");
    part_close(&p);
    expect_ok(&p, "pixel-planes-5", 33); /* the odd one goes to gp */
    assert_int_equal(mach_kind(p.m, "gp")->count, 16);
    assert_int_equal(mach_kind(p.m, "renderer")->count, 15);
    part_close(&p);
    /* the model's own size changes nothing: provenance stays a source */
    expect_ok(&p, "pixel-planes-5", 34);
    const CfgNode *gp = cfg_path(mach_model_cfg(p.m), "nodes.gp");
    assert_int_equal(mach_param_provenance(gp, "count", NULL),
                     MACH_PROV_SOURCE);
    part_close(&p);
    expect_ok(&p, "pixel-planes-5", 4);
    assert_string_equal(p.desc, "host 1, gp 1, renderer 1, frame_buffer 1");
    part_close(&p);
}

/* CM-200: lanes and router_nodes follow N. */
static void test_cm200_lanes(void **state)
{
    (void)state;
    Part p;
    expect_ok(&p, "cm200", 256);
    assert_int_equal(mach_kind(p.m, "array")->lanes, 256);
    uint64_t routers = 0;
    assert_true(mach_net_count(p.m, "router_nodes", &routers));
    assert_int_equal(routers, 16);
    assert_string_equal(p.desc, "array lanes 256 = 16 routers x 16");
    part_close(&p);
}

static void expect_refused(const char *model, guint n, const char *needle)
{
    Part p;
    GError *err = NULL;
    assert_false(part_open(&p, model, n, &err));
    assert_non_null(err);
    if (!strstr(err->message, needle))
        fail_msg("%s --nodes %u: got '%s', want '%s'", model, n, err->message,
                 needle);
    g_error_free(err);
    part_close(&p);
}

static void test_refused(void **state)
{
    (void)state;
    /* the hypercube refuses 12 where the override was made */
    expect_refused("ipsc2", 12, "--set machine.nodes.node.count=12");
    expect_refused("ipsc2", 12, "12 processors on a hypercube");
    expect_refused("pixel-planes-5", 3, "expected at least 4");
    expect_refused("cm200", 100, "procs_per_router x a power of two");
    expect_refused("cm200", 48, "procs_per_router x a power of two");
    expect_refused("mesh2d", 12, "the product of extents 4x4");
    expect_refused("no-such-model", 4, "no model 'no-such-model'");
}

static void test_mesh_keeps_shape(void **state)
{
    (void)state;
    Part p;
    expect_ok(&p, "mesh2d", 16);
    assert_string_equal(p.desc, "extents 4x4; node 16");
    part_close(&p);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hypercube_and_fat_tree),
        cmocka_unit_test(test_ring_split),
        cmocka_unit_test(test_cm200_lanes),
        cmocka_unit_test(test_refused),
        cmocka_unit_test(test_mesh_keeps_shape),
    };
    return cmocka_run_group_tests_name("machine_partition", tests, support_test_models,
                                       NULL);
}
