/* test_pphigs_regions.c — how the renderers get their 128x128 regions
 * (workload.region_assignment, pphigs_frame.h).  Static: region k is
 * renderer k mod R's; dynamic: a renderer takes the next region when it
 * has rasterised one, as Pixel-Planes 5's renderers "can be
 * independently reassigned to any part of the screen" (fuchs89).  On
 * the flock with 4 renderers, static leaves the busiest renderer far
 * busier than the least (its regions hold the boids); dynamic brings the
 * range within a few points, draws the same image as the serial painter
 * and does the same work (expressions, commands).  An unknown value is
 * a located error.  Run from the repository root (make test does).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/run/run.h"

static SimResult *flock(const char *assign, const char *renderers,
                        GError **err)
{
    char *a = g_strdup_printf("workload.region_assignment=%s", assign);
    char *r = g_strdup_printf("machine.nodes.renderer.count=%s", renderers);
    const char *sets[] = {a, r, "run.frames=1", "workload.edits_per_frame=0",
                          NULL};
    CfgRun *run = cfg_run_load("configs/pphigs-flock.yaml", sets, err);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = run ? cfg_run_exec(run, &o, err) : NULL;
    cfg_run_free(run);
    g_free(a);
    g_free(r);
    return res;
}

static double metric(const SimResult *r, const char *name)
{
    double v = -1;
    assert_true(sim_result_get_metric(r, name, &v));
    return v;
}

static double spread(const SimResult *r)
{
    return metric(r, "renderer_util_max_pct") -
           metric(r, "renderer_util_min_pct");
}

static void test_dynamic_balances(void **st)
{
    (void)st;
    SimResult *s = flock("static", "4", NULL), *d = flock("dynamic", "4", NULL);
    assert_non_null(s);
    assert_non_null(d);
    /* measured: static 51.5 .. 80.6 %, dynamic 68.7 .. 70.7 % */
    assert_true(spread(s) > 20);
    assert_true(spread(d) < 5);
    assert_true(spread(d) < spread(s) / 4);
    assert_true(metric(d, "frame_ms") < metric(s, "frame_ms"));
    for (int i = 0; i < 2; i++)
        assert_true(metric(i ? d : s, "image_matches_serial") == 1);
    assert_true(metric(d, "expressions_per_frame") ==
                metric(s, "expressions_per_frame"));
    assert_true(metric(d, "commands_per_frame") ==
                metric(s, "commands_per_frame"));
    /* the GPs' figures (seed 001 §6) do not depend on the renderers */
    assert_true(metric(d, "distribution_efficiency_pct") ==
                metric(s, "distribution_efficiency_pct"));
    sim_result_free(s);
    sim_result_free(d);
}

/* More renderers (100) than regions (80): the idle ones take nothing,
 * the image is still whole. */
static void test_more_renderers_than_regions(void **st)
{
    (void)st;
    for (int i = 0; i < 2; i++) {
        SimResult *r = flock(i ? "dynamic" : "static", "100", NULL);
        assert_non_null(r);
        assert_true(metric(r, "image_matches_serial") == 1);
        assert_true(metric(r, "renderer_util_min_pct") == 0);
        sim_result_free(r);
    }
}

static void test_unknown_value(void **st)
{
    (void)st;
    GError *err = NULL;
    assert_null(flock("round_robin", "16", &err));
    assert_non_null(err);
    assert_non_null(strstr(err->message, "round_robin"));
    assert_non_null(strstr(err->message, "dynamic, static"));
    g_error_free(err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dynamic_balances),
        cmocka_unit_test(test_more_renderers_than_regions),
        cmocka_unit_test(test_unknown_value),
    };
    return cmocka_run_group_tests_name("pphigs_regions", tests, NULL, NULL);
}
