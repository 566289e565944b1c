/* test_machine_mutants.c — claims of sim/machine that mutation testing
 * (make mutate, docs/testing.md) found unchecked: partitioning a
 * hypercube whose config states its dimension to one node sets the
 * dimension to 0 (2^0 = 1 node), so the machine builds; a model's
 * schema_version must be exactly 1; a machine of exactly 16M processors
 * builds. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/machine/machine.h"
#include "sim/machine/model.h"
#include "sim/machine/partition.h"
#include "tests/support.h"
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

/* The message mach_model_check gives a model whose node kind has the
 * extra line `kind` and whose network has the extra line `net` (each at
 * two spaces deeper than its section; "" for none), or NULL if it
 * passes.  The node line is line 6, the network line line 10. */
static char *model_error(const char *kind, const char *net)
{
    char *text = g_strdup_printf(
        "schema_version: 1\nname: t\nnodes:\n  node:\n"
        "    count: {value: 2, source: s}\n    %s\n"
        "network:\n  topology: {value: ring, source: s}\n"
        "  bandwidth: {value: 1 MB/s, source: s}\n  %s\n",
        kind, net);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "m.yaml", &err);
    if (!root)
        fail_msg("'%s' does not parse: %s", text, err->message);
    char *msg = NULL;
    if (!mach_model_check(root, "m.yaml", &err)) {
        msg = g_strdup(err->message);
        g_error_free(err);
    }
    cfg_free(root);
    g_free(text);
    return msg;
}

typedef struct {
    const char *kind, *net, *want; /* want NULL: accepted */
} ModelCase;

/* Each type's value without its unit, or of the wrong shape, names the
 * type's own example; lists are checked item by item. */
static const ModelCase model_cases[] = {
    {"", "startup: {value: 350, source: s}",
     "m.yaml:10:20: found '350' without a unit, expected a time with its "
     "unit, e.g. '350 us'"},
    {"", "per_hop: {value: [1 us], source: s}",
     "m.yaml:10:20: found a non-scalar value, expected a time with its "
     "unit, e.g. '350 us'"},
    {"", "total_bandwidth: {value: '2.8 ', source: s}",
     "m.yaml:10:28: found '2.8 ' without a unit, expected a bandwidth with "
     "its unit, e.g. '2.8 MB/s'"},
    {"clock: {value: 16., source: s}", "",
     "m.yaml:6:20: found '16.' without a unit, expected a frequency with "
     "its unit, e.g. '16 MHz'"},
    {"memory: {value: 4, source: s}", "",
     "m.yaml:6:21: found '4' without a unit, expected a size with its "
     "unit, e.g. '4 MB'"},
    {"", "level_bandwidth: {value: 20 MB/s, source: s}",
     "m.yaml:10:28: found a non-list value, expected a list of bandwidths, "
     "e.g. [20 MB/s, 10 MB/s]"},
    {"", "level_bandwidth: {value: [], source: s}",
     "m.yaml:10:28: found a non-list value, expected a list of bandwidths, "
     "e.g. [20 MB/s, 10 MB/s]"},
    {"", "level_bandwidth: {value: [20 MB/s, 10], source: s}",
     "m.yaml:10:38: found '10' without a unit, expected a bandwidth with "
     "its unit, e.g. '2.8 MB/s'"},
    {"", "extents: {value: 8, source: s}",
     "m.yaml:10:20: found a non-list value, expected a list of counts, "
     "e.g. [8, 8]"},
    {"", "level_bandwidth: {value: [20 MB/s, 10 MB/s], source: s}", NULL},
    {"", "extents: {value: [2, 1], source: s}", NULL},
    {"cores: {value: 4, source: s}", "arity: {value: 2, source: s}", NULL},
    {"lanes: 4", "",
     "m.yaml:6:12: found bare value for 'lanes', expected {value: ..., "
     "source|calibrated|assumption: ...} (or provenance: assumption at the "
     "top of your own model)"},
    {"colour: {value: 1, source: s}", "",
     "m.yaml:6:13: found unknown key 'colour', expected one of: count, "
     "processor, clock, memory, lanes, lane_memory, fpa_lanes, cores, "
     "peak_flops, memory_bandwidth, costs, cycles"},
};

static void test_model_errors_name_the_type(void **state)
{
    (void)state;
    for (size_t i = 0; i < G_N_ELEMENTS(model_cases); i++) {
        const ModelCase *c = &model_cases[i];
        char *got = model_error(c->kind, c->net);
        if (g_strcmp0(got, c->want) != 0)
            fail_msg("case %zu: got '%s', want '%s'", i, got ? got : "(ok)",
                     c->want ? c->want : "(ok)");
        g_free(got);
    }
}

/* The 16M bound on processors in all is inclusive: two kinds of 8M make
 * exactly 2^24 processors and build (one more is refused: test_machine.c,
 * too-many); processors are paged in lazily, so this allocates little. */
static void test_exactly_16m_processors(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "machine:\n  provenance: assumption\n  name: t\n"
        "  nodes: {a: {count: 8388608}, b: {count: 8388608}}\n"
        "  network: {topology: hypercube, bandwidth: 1 MB/s}\n",
        "run.yaml", &err);
    assert_non_null(root);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    if (!m)
        fail_msg("2^24 processors: %s", err->message);
    assert_int_equal(mach_proc_total(m), 1u << 24);
    assert_int_equal(mach_kind_count(m), 2);
    mach_free(m);
    sim_engine_free(eng);
    cfg_free(root);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_node_hypercube),
        cmocka_unit_test(test_unknown_key_list),
        cmocka_unit_test(test_model_schema_version_exact),
        cmocka_unit_test(test_model_errors_name_the_type),
        cmocka_unit_test(test_exactly_16m_processors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
