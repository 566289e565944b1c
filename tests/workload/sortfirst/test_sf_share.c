/* test_sf_share.c — sort-first runs handed one share (WlContext.share,
 * sim/workload/share.h), as `pgsim reproduce mueller97` hands its cases:
 * each case gives exactly what it gives alone (the frames rasterised
 * once, the chunk database kept for the next case of its chunking and
 * chunk size with the masters re-dealt for P), and a run that checks its
 * image keeps nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/run/run.h"

static const char *text =
    "schema_version: 1\n"
    "machine: {model: cluster-ib}\n"
    "workload: {type: sortfirst, regions: static, check_image: false,\n"
    "  resolution: 64}\n"
    "scene: {generator: vehicle, structures: 40, triangles: 3000,\n"
    "  instances: 3, circle_radius: 6, camera_radius: 15,\n"
    "  camera_height: 5, fov: 30, degrees_per_frame: 12}\n"
    "run: {frames: 3, fidelity: analytic}\n";

static SimResult *run(const char *const *sets, WlShare *share)
{
    CfgNode *root = cfg_load_string(text, "share.yaml", NULL);
    assert_non_null(root);
    GError *e = NULL;
    CfgRun *r = cfg_run_from_tree(root, sets, &e);
    CfgRunOpts o = {.quiet = TRUE, .share = share};
    SimResult *res = r ? cfg_run_exec(r, &o, &e) : NULL;
    if (!res)
        fail_msg("%s", e->message);
    cfg_run_free(r);
    return res;
}

static void assert_same(const SimResult *a, const SimResult *b)
{
    assert_int_equal(a->metrics->len, b->metrics->len);
    for (guint i = 0; i < a->metrics->len; i++) {
        const SimMetric *x = g_ptr_array_index(a->metrics, i);
        const SimMetric *y = g_ptr_array_index(b->metrics, i);
        assert_string_equal(x->name, y->name);
        if (x->value != y->value)
            fail_msg("%s: %.17g shared, %.17g alone", x->name, x->value,
                     y->value);
    }
    assert_int_equal(a->frame_times->len, b->frame_times->len);
    assert_memory_equal(a->frame_times->data, b->frame_times->data,
                        a->frame_times->len * sizeof(SimTime));
}

static void test_shared_cases_equal_alone(void **st)
{
    (void)st;
    /* P changes with the database kept; then a new chunk size and a new
     * chunking each build their own */
    const char *cases[][4] = {
        {"workload.processors=4", "workload.granularity=5",
         "workload.bookkeeping=minset", NULL},
        {"workload.processors=8", "workload.granularity=5",
         "workload.bookkeeping=maxset", NULL},
        {"workload.processors=2", "workload.granularity=5",
         "workload.bookkeeping=minset", NULL},
        {"workload.processors=4", "workload.granularity=1",
         "workload.bookkeeping=maxset", NULL},
        {"workload.processors=4", "workload.chunking=unsorted",
         "workload.bookkeeping=maxset", NULL},
    };
    WlShare *share = wl_share_new();
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++) {
        SimResult *a = run(cases[i], share), *b = run(cases[i], NULL);
        assert_non_null(wl_share_get(share, "sortfirst db")); /* kept */
        assert_same(a, b);
        sim_result_free(a);
        sim_result_free(b);
    }
    wl_share_free(share);
}

/* The image check (and edits, and frame output) render for real: such a
 * run neither uses nor fills the share. */
static void test_checked_run_keeps_nothing(void **st)
{
    (void)st;
    const char *check[] = {"workload.check_image=true", NULL};
    WlShare *share = wl_share_new();
    SimResult *a = run(check, share);
    assert_null(wl_share_get(share, "sortfirst db"));
    sim_result_free(a);
    wl_share_free(share);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shared_cases_equal_alone),
        cmocka_unit_test(test_checked_run_keeps_nothing),
    };
    return cmocka_run_group_tests_name("sf_share", tests, NULL, NULL);
}
