/* test_machine_mutants.c — claims of sim/machine that mutation testing
 * (make mutate, docs/testing.md) found unchecked: partitioning a
 * hypercube whose config states its dimension to one node sets the
 * dimension to 0 (2^0 = 1 node), so the machine builds; a model's
 * schema_version must be exactly 1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/machine/machine.h"
#include "sim/machine/model.h"
#include "sim/machine/partition.h"
#include <string.h>

static void test_one_node_hypercube(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string("machine: {model: ipsc2, network: {dimension: 4}}\n", "run.yaml", &err);
    assert_non_null(root);
    char *desc = NULL;
    assert_true(mach_partition(root, 1, &desc, &err));
    const char *dim = cfg_scalar(cfg_path(root, "machine.network.dimension"));
    assert_non_null(dim);
    assert_string_equal(dim, "0");
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "flow", &err);
    if (!m)
        fail_msg("ipsc2 on one node: %s", err->message);
    assert_int_equal(net_nodes(mach_net(m)), 1);
    mach_free(m);
    sim_engine_free(eng);
    cfg_free(root);
    g_free(desc);
}

/* An unknown key of a machine's network section lists the known ones as
 * "one of: a, b, c": comma-separated, no comma first or last. */
static void test_unknown_key_list(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "machine: {model: ipsc2, network: {bogus: 1}}\n", "run.yaml", &err);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "flow", &err);
    assert_null(m);
    const char *l = strstr(err->message, "one of: ");
    if (!l || l[8] == ',' || strstr(l, ", ,") || strstr(l, ",,"))
        fail_msg("'%s'", err->message);
    assert_non_null(strstr(l, ", ")); /* several keys, separated */
    g_clear_error(&err);
    sim_engine_free(eng);
    cfg_free(root);
}

/* A model file states schema_version 1 exactly: 0 and 2 are rejected at
 * the value's line and column, 1 passes. */
static void test_model_schema_version_exact(void **state)
{
    (void)state;
    const char *want[] = {"m.yaml:1:17: ", NULL, "m.yaml:1:17: "};
    for (int v = 0; v <= 2; v++) {
        char *text = g_strdup_printf(
            "schema_version: %d\nname: t\n"
            "nodes: {node: {count: {value: 2, source: s}}}\n"
            "network: {topology: {value: ring, source: s},\n"
            "          bandwidth: {value: 1 MB/s, source: s}}\n", v);
        GError *err = NULL;
        CfgNode *root = cfg_load_string(text, "m.yaml", &err);
        assert_non_null(root);
        gboolean ok = mach_model_check(root, "m.yaml", &err);
        assert_int_equal(ok, want[v] == NULL);
        if (want[v] && !g_str_has_prefix(err->message, want[v]))
            fail_msg("version %d: '%s'", v, err->message);
        g_clear_error(&err);
        cfg_free(root);
        g_free(text);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_node_hypercube),
        cmocka_unit_test(test_unknown_key_list),
        cmocka_unit_test(test_model_schema_version_exact),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
