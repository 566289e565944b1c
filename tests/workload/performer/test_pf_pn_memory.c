/* test_pf_pn_memory.c — the performer workload's `pn: {memory: ...}`
 * metrics (pf_pn.h, pn_memory.h): configs/pn-memory.yaml reports the
 * pre-tessellated store of levels 0..4 against the base mesh; the list
 * layout gives exactly sum (L + 1)^2 = 55, the indexed teapot a little
 * less (its open rims); without `memory:` there are no such metrics; a
 * bad layout is a located error.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/performer/pf_workload.h"
#include "tests/support.h"

static SimResult *run_memory(const char *const *overrides)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_file("configs/pn-memory.yaml", &err);
    if (!root)
        fail_msg("%s", err->message);
    SupportRun o = {.fidelity = "analytic", .frames = 1,
                    .overrides = overrides};
    SimResult *r = support_run_tree(root, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    return r;
}

static void test_memory_metrics(void **st)
{
    (void)st;
    double ratio = 0, lod = 0, base = 0;
    SimResult *r = run_memory(NULL);
    assert_true(sim_result_get_metric(r, "lod_memory_ratio", &ratio));
    assert_true(sim_result_get_metric(r, "lod_memory_bytes", &lod));
    assert_true(sim_result_get_metric(r, "pn_memory_bytes", &base));
    assert_float_equal(ratio, lod / base, 1e-9);
    assert_true(ratio > 50 && ratio < 55);
    sim_result_free(r);
    const char *list[] = {"workload.pn.memory.layout=list", NULL};
    r = run_memory(list);
    assert_true(sim_result_get_metric(r, "lod_memory_ratio", &ratio));
    assert_float_equal(ratio, 55, 1e-9);
    sim_result_free(r);
    const char *none[] = {"workload.pn.memory.to=0", NULL};
    r = run_memory(none);
    assert_true(sim_result_get_metric(r, "lod_memory_ratio", &ratio));
    assert_float_equal(ratio, 1, 1e-9);
    sim_result_free(r);
}

static void test_no_memory_no_metric(void **st)
{
    (void)st;
    GError *err = NULL;
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    SimResult *r = support_run_text(
        "machine: {model: sgi-onyx}\n"
        "scene: {generator: teapots, count: 1, polygons_per_teapot: 400}\n"
        "workload: {type: performer, pn: {level: 1}}\n",
        &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    double v;
    assert_false(sim_result_get_metric(r, "lod_memory_ratio", &v));
    sim_result_free(r);
}

static void test_bad_layout(void **st)
{
    (void)st;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "workload: {type: performer, pn: {memory: {layout: strips}}}\n",
        "b.yaml", &err);
    assert_non_null(root);
    assert_null(wl_pf_ops.parse(cfg_get(root, "workload"), &err));
    if (!g_str_has_prefix(err->message, "b.yaml:1:51: found 'strips', "
                                        "expected one of: list, grids"))
        fail_msg("got %s", err->message);
    g_error_free(err);
    cfg_free(root);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_memory_metrics),
        cmocka_unit_test(test_no_memory_no_metric),
        cmocka_unit_test(test_bad_layout),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
