/* test_dpscan.c — the data-parallel renderer of seed 004: cost model
 * with exact times, a hand-checked frame schedule, pixel counts against
 * the raster library, determinism and model-file errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/isosurface.h"
#include "sim/workload/dpscan/dp_frame.h"
#include "sim/workload/dpscan/dp_model.h"
#include "sim/workload/workload.h"

static void test_vp_ratio(void **state)
{
    (void)state;
    assert_int_equal(wl_dp_vp_ratio(0, 4), 0);
    assert_int_equal(wl_dp_vp_ratio(1, 4), 1);
    assert_int_equal(wl_dp_vp_ratio(16384, 16384), 1);
    assert_int_equal(wl_dp_vp_ratio(228288, 16384), 14);
    assert_int_equal(wl_dp_vp_ratio(228288, 65536), 4);
}

static void test_simd_costs(void **state)
{
    (void)state;
    WlDpMachine m = {.arch = WL_DP_SIMD, .procs = 4, .op = 10, .step = 100,
                     .send_setup = 50, .send_slice = 7};
    WlDpCoef k = {0};
    /* 10 elements on 4 lanes: VP ratio 3; 100 + 3 * 3 * 10. */
    assert_int_equal(wl_dp_step_cost(&m, 10, 3, &k), 190);
    /* 9 messages: 3 slices; 50 + 3 * 7. */
    assert_int_equal(wl_dp_send_cost(&m, 9, &k), 71);
    assert_int_equal(wl_dp_send_cost(&m, 0, &k), 0);
    assert_true(k.op_slices == 9.0 && k.steps == 1.0);
    assert_true(k.sends == 1.0 && k.slices == 3.0);
}

static void test_spmd_costs(void **state)
{
    (void)state;
    WlDpMachine m = {.arch = WL_DP_SPMD, .procs = 4, .op = 1, .step = 0,
                     .net_latency = 5, .msg_overhead = 1000,
                     .msg_bytes = 20, .arity = 4, .levels = 1,
                     .level_bw = {20e6}};
    /* 8 messages on 4 nodes: 2 per node, 40 B; 3/4 leave the node at
     * 20 MB/s: 1.5 us of wire > 2 ns of software. */
    assert_int_equal(wl_dp_send_cost(&m, 8, NULL), 5 + 1500000);
    m.msg_overhead = 2 * SIM_US;
    assert_int_equal(wl_dp_send_cost(&m, 8, NULL), 5 + 4 * SIM_US);
    assert_true(wl_dp_fattree_escape(4, 64, 0) == 1.0 - 1.0 / 64);
    assert_true(wl_dp_fattree_escape(4, 64, 2) == 1.0 - 16.0 / 64);
    assert_true(wl_dp_fattree_escape(4, 64, 3) == 0.0);
}

/* Two visible polygons (rows of length 3, 1 and 2), one invisible. */
static WlDpGeom *tiny_geom(void)
{
    WlDpGeom *g = g_new0(WlDpGeom, 1);
    uint32_t start[] = {0, 2, 3}, len[] = {3, 1, 2};
    g->seg_start = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g->seg_len = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g_array_append_vals(g->seg_start, start, 3);
    g_array_append_vals(g->seg_len, len, 3);
    g->width = 4, g->height = 2, g->n_polys = 3, g->n_visible = 2;
    g->max_rows = 2, g->max_len = 3, g->pixels = 6;
    return g;
}

static void test_frame_schedule(void **state)
{
    (void)state;
    WlDpGeom *g = tiny_geom();
    WlDpMachine m = {.arch = WL_DP_SIMD, .procs = 2, .op = 1, .step = 0,
                     .send_setup = 0, .send_slice = 1};
    WlDpAlgo a = {1, 1, 1, 1, 1, 1, 1, 1, 1.0, 32, 8};
    WlDpFrame f;
    wl_dp_frame_run(g, &m, &a, &f);
    /* Worked by hand: clear 4 +
     * extract 4; transform 2; two scan iterations of 2; one flush of 3
     * pixel iterations of 2; sends 1 + 1 (segments) + 2 + 1 + 1. */
    assert_int_equal(f.phase[WL_DP_PH_DISPLAY], 8);
    assert_int_equal(f.phase[WL_DP_PH_TRANSFORM], 2);
    assert_int_equal(f.phase[WL_DP_PH_SCAN], 4);
    assert_int_equal(f.phase[WL_DP_PH_PIXEL], 6);
    assert_int_equal(f.phase[WL_DP_PH_ROUTER], 6);
    assert_int_equal(f.total, 26);
    assert_int_equal(f.scan_iters, 2);
    assert_int_equal(f.flushes, 1);
    assert_int_equal(f.pixel_iters, 3);
    assert_int_equal(f.segments, 3);
    assert_int_equal(f.messages, 3 + 6);
    /* The linear coefficients reproduce the total. */
    double t = f.coef.op_slices * m.op + f.coef.steps * m.step +
               f.coef.sends * m.send_setup + f.coef.slices * m.send_slice;
    assert_true(t == (double)f.total);
    /* A buffer of one polygon's worth flushes before scan line 1. */
    a.buffer_factor = 1.0 / 3.0;
    wl_dp_frame_run(g, &m, &a, &f);
    assert_int_equal(f.flushes, 2);
    assert_int_equal(f.pixel_iters, 3 + 1);
    wl_dp_geom_free(g);
}

static Scene *small_iso(void)
{
    SceneIsoParams p = scene_iso_defaults();
    p.grid = 12;
    return scene_iso_new(&p);
}

static void test_pixels_match_raster(void **state)
{
    (void)state;
    Scene *s = small_iso();
    WlDpGeom *g = wl_dp_geom_new(s, 0.0, 160, 120);
    assert_true(g->pixels > 0);
    assert_int_equal(g->pixels, g->counters.pixels);
    uint64_t sum = 0;
    for (guint i = 0; i < g->seg_len->len; i++)
        sum += g_array_index(g->seg_len, uint32_t, i);
    /* Convex polygons: one gap-free segment per row. */
    assert_int_equal(sum, g->pixels);
    assert_true(g->covered <= g->pixels);
    assert_true(g->covered <= 160 * 120);
    assert_true(g->n_visible <= g->n_polys);
    assert_int_equal(g->n_polys, scene_n_polys(s));
    wl_dp_geom_free(g);
    scene_free(s);
}

static void test_deterministic(void **state)
{
    (void)state;
    WlDpMachine m = {.arch = WL_DP_SIMD, .procs = 64, .op = 7, .step = 3,
                     .send_setup = 11, .send_slice = 13};
    WlDpAlgo a = wl_dp_algo_defaults();
    WlDpFrame f[2];
    for (int i = 0; i < 2; i++) {
        Scene *s = small_iso();
        WlDpGeom *g = wl_dp_geom_new(s, 0.0, 128, 128);
        wl_dp_frame_run(g, &m, &a, &f[i]);
        wl_dp_geom_free(g);
        scene_free(s);
    }
    assert_true(f[0].total > 0);
    assert_memory_equal(&f[0], &f[1], sizeof(WlDpFrame));
}

static void test_model_errors(void **state)
{
    (void)state;
    const char *bad = "dpscan:\n  arch: {value: simd, source: x}\n"
                      "  op: 2 us\n";
    GError *err = NULL;
    CfgNode *root = cfg_load_string(bad, "bad.yaml", &err);
    assert_non_null(root);
    WlDpMachine m = {0};
    assert_false(wl_dp_machine_from_cfg(cfg_get(root, "dpscan"), &m, &err));
    assert_non_null(strstr(err->message, "bad.yaml:3:"));
    assert_non_null(strstr(err->message, "expected {value"));
    g_clear_error(&err);
    cfg_free(root);
    const char *good = "dpscan:\n  arch: {value: simd, source: x}\n"
                       "  op: {value: 2 us, calibrated: [a]}\n"
                       "  step: {value: 1 us, assumption: y}\n"
                       "  send_setup: {value: 3 us, source: z}\n"
                       "  send_slice: {value: 4 ms, source: z}\n";
    root = cfg_load_string(good, "good.yaml", &err);
    assert_true(wl_dp_machine_from_cfg(cfg_get(root, "dpscan"), &m, &err));
    assert_int_equal(m.op, 2 * SIM_US);
    assert_int_equal(m.send_slice, 4 * SIM_MS);
    cfg_free(root);
}

static void test_workload_run(void **state)
{
    (void)state;
    const char *yml = "workload: {type: dpscan, model: cm200, "
                      "processors: 1024, width: 64, height: 48}\n"
                      "scene: {generator: isosurface, grid: 8}\n";
    GError *err = NULL;
    CfgNode *root = cfg_load_string(yml, "run.yaml", &err);
    const WlOps *ops = wl_find("dpscan");
    assert_non_null(ops);
    void *p = ops->parse(cfg_get(root, "workload"), &err);
    assert_non_null(p);
    WlContext ctx = {.root = root, .frames = 2};
    SimResult *r = sim_result_new("dpscan", "cm200");
    assert_true(ops->run(&ctx, p, r, &err));
    assert_int_equal(r->frame_times->len, 2);
    double pps = 0;
    assert_true(sim_result_get_metric(r, "polygons_per_s", &pps));
    assert_true(pps > 0);
    sim_result_free(r);
    ops->free_params(p);
    cfg_free(root);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vp_ratio),
        cmocka_unit_test(test_simd_costs),
        cmocka_unit_test(test_spmd_costs),
        cmocka_unit_test(test_frame_schedule),
        cmocka_unit_test(test_pixels_match_raster),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_model_errors),
        cmocka_unit_test(test_workload_run),
    };
    return cmocka_run_group_tests_name("dpscan", tests, NULL, NULL);
}
