/* test_pf_pnlod.c — PN triangles as a level of detail chosen by
 * Performer's LOD node and stress filter (pf_pnlod.h): as the eye
 * recedes the PN level and the triangles drawn fall (4 -> 0, 25x ->
 * 1x); held near, level 4 overloads a 30 Hz frame: without stress the
 * frame takes two frame times, with stress the level drops and the frame
 * holds 33.3 ms; bad `lod:` maps are located errors.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/performer/pf_workload.h"
#include "tests/support.h"

/* Runs the teapot (1,560 triangles) on the Onyx with the eye from
 * `from` to `to`; stress filter on or off; returns the result. */
static SimResult *run_lod(double from, double to, gboolean stress)
{
    char *yaml = g_strdup_printf(
        "machine: {model: sgi-onyx}\n"
        "scene: {generator: teapots, count: 1, polygons_per_teapot: 1000}\n"
        "workload:\n  type: performer\n  mode: appculldraw\n"
        "  frame_rate: 30\n%s"
        "  pn:\n    send: coarse\n    lod: {levels: [4, 3, 2, 1, 0],\n"
        "      ranges: [0, 5, 10, 20, 40, 1000], from: %g, to: %g}\n",
        stress ? "  stress: {gain: 0.5, low: 0.7, high: 0.9, max: 8}\n" : "",
        from, to);
    GError *err = NULL;
    SupportRun o = {.fidelity = "analytic", .frames = 40};
    SimResult *r = support_run_text(yaml, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    g_free(yaml);
    return r;
}

static void test_level_falls_with_distance(void **st)
{
    (void)st;
    SimResult *r = run_lod(2, 60, FALSE);
    assert_float_equal(support_metric(r, "level_first"), 4, 0);
    assert_float_equal(support_metric(r, "level_last"), 0, 0);
    double coarse = support_metric(r, "coarse_tris");
    assert_float_equal(support_metric(r, "fine_tris_first"), 25 * coarse, 0);
    assert_float_equal(support_metric(r, "fine_tris_last"), coarse, 0);
    sim_result_free(r);
    /* near all the way: level 4 every frame */
    r = run_lod(2, 2, FALSE);
    assert_float_equal(support_metric(r, "level"), 4, 0);
    sim_result_free(r);
}

static void test_stress_holds_the_rate(void **st)
{
    (void)st;
    double T = 1000.0 / 30;
    SimResult *off = run_lod(2, 2, FALSE), *on = run_lod(2, 2, TRUE);
    /* level 4 does not fit the frame: every frame takes two */
    assert_true(support_metric(off, "interval_ms_last") > 1.9 * T);
    assert_float_equal(support_metric(off, "stress_max"), 1, 0);
    /* stress raises the distance x stress past a range: a coarser level,
     * fewer triangles, and the frame rate held */
    assert_true(support_metric(on, "stress_max") > 1);
    assert_true(support_metric(on, "level_last") < 4);
    assert_true(support_metric(on, "fine_tris_last") < support_metric(off, "fine_tris_last"));
    assert_float_equal(support_metric(on, "interval_ms_last"), T, 1e-6);
    assert_true(support_metric(on, "frame_ms") < support_metric(off, "frame_ms"));
    sim_result_free(off);
    sim_result_free(on);
}

static const struct {
    const char *yaml, *message;
} bad[] = {
    {"workload: {type: performer, pn: {lod: {levels: [2, 1], ranges: [0, "
     "5]}}}\n",
     "b.yaml:1:64: found a list of another length, expected one more range"},
    {"workload: {type: performer, pn: {lod: {levels: [2, 1], ranges: [0, 5, "
     "5]}}}\n",
     "b.yaml:1:71: found an out-of-order or bad value, expected increasing"},
    {"workload: {type: performer, pn: {lod: {levels: [40], ranges: [0, 5]}}}\n",
     "b.yaml:1:49: found an out-of-order or bad value, expected a PN level"},
    {"workload: {type: performer, pn: {lod: 3}}\n",
     "b.yaml:1:39: found a non-map, expected lod: {levels"},
};

static void test_bad_lod(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        GError *err = NULL;
        CfgNode *root = cfg_load_string(bad[i].yaml, "b.yaml", &err);
        assert_non_null(root);
        assert_null(wl_pf_ops.parse(cfg_get(root, "workload"), &err));
        if (!g_str_has_prefix(err->message, bad[i].message))
            fail_msg("case %u: got %s", i, err->message);
        g_error_free(err);
        cfg_free(root);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_level_falls_with_distance),
        cmocka_unit_test(test_stress_holds_the_rate),
        cmocka_unit_test(test_bad_lod),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
