/* test_dp_parse.c — the dpscan section (dp_workload.c's parser, issue 21):
 * the defaults (model cm200, 16384 processors, 1280 x 1024, mode
 * gouraud, buffer_factor 0.25, wire network) shown by mem_bytes and by a
 * run equal to one with the values written out (and different from one
 * with other values), each range's ends accepted and one past them
 * refused at the value's file:line:column.  Run from the repository root
 * (models/). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/raster/scan.h"
#include "sim/workload/dpscan/dp_workload.h"
#include "sim/workload/metrics.h"
#include "tests/support.h"

static const char *scene_yaml = "scene: {generator: isosurface, grid: 5}\n";

/* Parses "{type: dpscan<extra>}"; NULL with *err on a refusal. */
static void *parse(const char *extra, GError **err)
{
    char *text = g_strdup_printf("workload: {type: dpscan%s}\n", extra);
    CfgNode *root = cfg_load_string(text, "dp.yaml", err);
    g_free(text);
    assert_non_null(root);
    void *p = wl_dpscan_ops.parse(cfg_get(root, "workload"), err);
    cfg_free(root);
    return p;
}

static void test_default_sizes(void **state)
{
    (void)state;
    GError *err = NULL;
    void *p = parse("", &err);
    assert_non_null(p);
    GString *what = g_string_new("");
    assert_true(wl_dpscan_ops.mem_bytes(p, what) ==
                1280.0 * 1024 * 12 + 16384.0 * 12);
    assert_string_equal(what->str, "16384 processors, 1280 x 1024 pixels");
    wl_dpscan_ops.free_params(p);
    g_string_free(what, TRUE);
}

/* Every metric of a one-frame run of "{type: dpscan, processors: 64,
 * width: 24, height: 20<extra>}" on the small isosurface. */
static SimResult *run(const char *extra)
{
    char *text = g_strdup_printf("workload: {type: dpscan, processors: 64, "
                                 "width: 24, height: 20%s}\n%s",
                                 extra, scene_yaml);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "dp.yaml", &err);
    g_free(text);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    SimResult *r = support_run_tree(root, &o, &err);
    if (!r)
        fail_msg("%s: %s", extra, err->message);
    return r;
}

/* Do two runs give the same metrics, value for value? */
static gboolean same_metrics(const SimResult *a, const SimResult *b)
{
    static const char *const names[] = {
        "transform_s", "scan_s", "pixel_s", "router_s", "display_s",
        "steps", "scan_iters", "pixel_iters", "flushes", "segments",
        "pixels", "collisions", "messages", "max_load"};
    for (guint i = 0; i < G_N_ELEMENTS(names); i++) {
        double x = -1, y = -2;
        assert_true(sim_result_get_metric(a, names[i], &x));
        assert_true(sim_result_get_metric(b, names[i], &y));
        if (x != y)
            return FALSE;
    }
    return TRUE;
}

static void test_default_words(void **state)
{
    (void)state;
    SimResult *d = run("");
    SimResult *e = run(", model: cm200, mode: gouraud, buffer_factor: 0.25, "
                       "wire: network");
    assert_true(same_metrics(d, e));
    assert_string_equal(d->machine, "cm200");
    static const char *const other[] = {
        ", mode: flat", ", mode: wireframe", ", buffer_factor: 0.5",
        ", model: cm5"};
    for (guint i = 0; i < G_N_ELEMENTS(other); i++) {
        SimResult *o = run(other[i]);
        if (same_metrics(d, o))
            fail_msg("'%s' changes nothing", other[i]);
        sim_result_free(o);
    }
    sim_result_free(d);
    sim_result_free(e);
}

/* "dp.yaml:1:<col>:" where col is the value's column. */
static void expect_refused(const char *key, const char *value)
{
    char *extra = g_strdup_printf(", %s: %s", key, value);
    GError *err = NULL;
    assert_null(parse(extra, &err));
    assert_non_null(err);
    char *at = g_strdup_printf(
        "dp.yaml:1:%d: found ",
        (int)(strlen("workload: {type: dpscan, ") + strlen(key) + 3));
    if (strncmp(err->message, at, strlen(at)) != 0)
        fail_msg("%s: '%s' does not start '%s'", extra, err->message, at);
    g_free(at);
    g_clear_error(&err);
    g_free(extra);
}

static void expect_accepted(const char *key, const char *value)
{
    char *extra = g_strdup_printf(", %s: %s", key, value);
    GError *err = NULL;
    void *p = parse(extra, &err);
    if (!p)
        fail_msg("%s: %s", extra, err->message);
    wl_dpscan_ops.free_params(p);
    g_free(extra);
}

static void test_ranges(void **state)
{
    (void)state;
    char max_side[16], past_side[16];
    g_snprintf(max_side, sizeof max_side, "%d", RAST_MAX_SIDE);
    g_snprintf(past_side, sizeof past_side, "%d", RAST_MAX_SIDE + 1);
    expect_accepted("processors", "1");
    expect_accepted("processors", "4294967295");
    expect_refused("processors", "0");
    expect_refused("processors", "4294967296");
    static const char *const sides[] = {"width", "height"};
    for (guint i = 0; i < 2; i++) {
        expect_accepted(sides[i], "1");
        expect_accepted(sides[i], max_side);
        expect_refused(sides[i], "0");
        expect_refused(sides[i], past_side);
    }
    expect_accepted("buffer_factor", "1e-6");
    expect_accepted("buffer_factor", "1e6");
    expect_refused("buffer_factor", "0");
    expect_refused("buffer_factor", "1.1e6");
    expect_refused("mode", "shaded");
    expect_refused("wire", "cable");
    GError *err = NULL;
    void *p = parse(", mode: flat, wire: formula, model: cm5", &err);
    assert_non_null(p);
    wl_dpscan_ops.free_params(p);
}

/* A run refused: `yaml` parses but names a scene or model that does not
 * exist; the run (through the runner) fails with an error holding `want`
 * and gives no result, so no frame. */
static void refused(const char *yaml, const char *want)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(yaml, "dp.yaml", &err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    SimResult *r = support_run_tree(root, &o, &err);
    assert_null(r);
    assert_non_null(err);
    if (!strstr(err->message, want))
        fail_msg("'%s' lacks '%s'", err->message, want);
    g_error_free(err);
}

static void test_run_refusals(void **state)
{
    (void)state;
    refused("workload: {type: dpscan, processors: 16, width: 8, height: 8}\n"
            "scene: {generator: nosuch}\n",
            "dp.yaml:2:");
    refused("workload: {type: dpscan, model: nosuch, processors: 16}\n"
            "scene: {generator: isosurface, grid: 4}\n",
            "nosuch.yaml");
}

/* workload.partitions: the frame costed at each P (time_s@P): at the
 * machine's own partition the frame's time, at four times as many
 * processors less; the counts are declared (the runner checks them);
 * an SPMD machine pricing its sends on its own network refuses them. */
static void test_partitions(void **state)
{
    (void)state;
    SimResult *r = run(", partitions: [64, 256]");
    double own = wl_metric(r, "time_s@64"), big = wl_metric(r, "time_s@256");
    assert_true(own == sim_time_to_s(g_array_index(r->frame_times, SimTime,
                                                   0)));
    assert_true(big > 0 && big < own);
    assert_true(wl_metric(r, "send_slice_count@256") > 0);
    assert_true(wl_metric(r, "polygons") > 0);
    sim_result_free(r);
    refused("workload: {type: dpscan, model: cm5, processors: 16, "
            "partitions: [16, 32]}\n"
            "scene: {generator: isosurface, grid: 4}\n",
            "dp.yaml:1:66: found partitions with SPMD sends on the "
            "machine's network, expected wire: formula");
    refused("workload: {type: dpscan, partitions: [16, 0]}\n"
            "scene: {generator: isosurface, grid: 4}\n",
            "dp.yaml:1:43: found 0, expected a processor count");
}

int main(void)
{
    g_log_set_always_fatal(G_LOG_LEVEL_WARNING | G_LOG_LEVEL_CRITICAL);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_sizes),
        cmocka_unit_test(test_default_words),
        cmocka_unit_test(test_ranges),
        cmocka_unit_test(test_run_refusals),
        cmocka_unit_test(test_partitions),
    };
    return cmocka_run_group_tests_name("dp_parse", tests, NULL, NULL);
}
