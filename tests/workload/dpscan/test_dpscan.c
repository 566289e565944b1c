/* test_dpscan.c — the data-parallel renderer of seed 004: cost model
 * with exact times, a hand-checked frame schedule, pixel counts against
 * the raster library, determinism and model-file errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/isosurface.h"
#include "sim/workload/dpscan/dp_exec.h"
#include "sim/workload/dpscan/dp_model.h"
#include "sim/workload/workload.h"

static void test_vp_ratio(void **state)
{
    (void)state;
    WlDpMachine m = {.procs = 4};
    assert_int_equal(wl_dp_vp_ratio(&m, 0), 0);
    assert_int_equal(wl_dp_vp_ratio(&m, 1), 1);
    m.procs = 16384;
    assert_int_equal(wl_dp_vp_ratio(&m, 16384), 1);
    assert_int_equal(wl_dp_vp_ratio(&m, 228288), 14);
    m.vp_pow2 = TRUE;
    assert_int_equal(wl_dp_vp_ratio(&m, 228288), 16);
    m.procs = 65536, m.vp_pow2 = FALSE;
    assert_int_equal(wl_dp_vp_ratio(&m, 228288), 4);
}

static void test_simd_costs(void **state)
{
    (void)state;
    WlDpMachine m = {.arch = WL_DP_SIMD,
                     .procs = 4,
                     .op = 10,
                     .step = 100,
                     .scan_slice = 20,
                     .send_setup = 50,
                     .send_slice = 7,
                     .send_vp = 1};
    WlDpCoef k = {0};
    /* 10 elements on 4 lanes: VP ratio 3; 100 + 3 * 3 * 10. */
    assert_int_equal(wl_dp_step_cost(&m, 10, 3, &k), 190);
    /* Scan: 100 + 3 * 20. */
    assert_int_equal(wl_dp_scan_cost(&m, 10, &k), 160);
    /* Two arrays, load 5 from 10 elements (3 slices, 2 messages: 2
     * slices hold one): 2 * (100 + 50 + 2 * 1 + 5 * 7). */
    assert_int_equal(wl_dp_send_cost(&m, 2, 10, 2, 5, &k), 374);
    assert_int_equal(wl_dp_send_cost(&m, 2, 10, 0, 0, &k), 0);
    assert_true(k.op_slices == 9.0 && k.steps == 4.0);
    assert_true(k.scan_slices == 3.0 && k.sends == 2.0);
    assert_true(k.slices == 10.0 && k.vp_slices == 4.0);
}

static void test_spmd_costs(void **state)
{
    (void)state;
    WlDpMachine m = {.arch = WL_DP_SPMD,
                     .procs = 4,
                     .op = 1,
                     .step = 0,
                     .net_latency = 5,
                     .msg_overhead = 1000,
                     .msg_bytes = 20,
                     .arity = 4,
                     .levels = 1,
                     .level_bw = {20e6}};
    /* Load 2 on 4 nodes: 40 B, 3/4 leave the node at 20 MB/s: 1.5 us of
     * wire > 2 ns of software. */
    assert_int_equal(wl_dp_send_cost(&m, 1, 8, 8, 2, NULL), 5 + 1500000);
    m.msg_overhead = 2 * SIM_US;
    assert_int_equal(wl_dp_send_cost(&m, 1, 8, 8, 2, NULL), 5 + 4 * SIM_US);
    assert_true(wl_dp_fattree_escape(4, 64, 0) == 1.0 - 1.0 / 64);
    assert_true(wl_dp_fattree_escape(4, 64, 2) == 1.0 - 16.0 / 64);
    assert_true(wl_dp_fattree_escape(4, 64, 3) == 0.0);
}

static void test_layout(void **state)
{
    (void)state;
    WlDpLayout *l = wl_dp_layout_new(16384, 1280, 1024);
    assert_int_equal(l->px, 128);
    assert_int_equal(l->py, 128);
    assert_int_equal(l->bw, 10);
    assert_int_equal(l->bh, 8);
    assert_int_equal(wl_dp_layout_owner(l, 0, 0), 0);
    assert_int_equal(wl_dp_layout_owner(l, 19, 0), 1);
    assert_int_equal(wl_dp_layout_owner(l, 1279, 1023), 16383);
    wl_dp_layout_free(l);
    l = wl_dp_layout_new(32, 64, 48);
    assert_int_equal(l->px * l->py, 32);
    assert_int_equal(l->px, 8);
    wl_dp_layout_free(l);
}

/* Two visible polygons (rows of length 3, 1 and 2), one invisible;
 * polygon 0 at (0,0),(0,1), polygon 1 at (1,0). */
static WlDpGeom *tiny_geom(void)
{
    WlDpGeom *g = g_new0(WlDpGeom, 1);
    uint32_t start[] = {0, 2, 3}, len[] = {3, 1, 2}, x0[] = {0, 0, 1};
    uint32_t y0[] = {0, 0};
    g->seg_start = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g->seg_len = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g->seg_x0 = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g->poly_y0 = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g_array_append_vals(g->seg_start, start, 3);
    g_array_append_vals(g->seg_len, len, 3);
    g_array_append_vals(g->seg_x0, x0, 3);
    g_array_append_vals(g->poly_y0, y0, 2);
    g->width = 4, g->height = 2, g->n_polys = 3, g->n_visible = 2;
    g->max_rows = 2, g->max_len = 3, g->pixels = 6, g->seg_pixels = 6;
    return g;
}

static WlDpAlgo unit_algo(void)
{
    return (WlDpAlgo){.clear_ops = 1,
                      .transform_ops = 1,
                      .transform_steps = 1,
                      .scan_ops = 1,
                      .scan_steps = 1,
                      .scan_scans = 1,
                      .pixel_ops = 1,
                      .pixel_steps = 1,
                      .extract_ops = 1,
                      .segment_words = 1,
                      .pixel_words = 1,
                      .buffer_factor = 1.0};
}

static void test_frame_schedule(void **state)
{
    (void)state;
    WlDpGeom *g = tiny_geom();
    WlDpMachine m = {.arch = WL_DP_SIMD,
                     .procs = 2,
                     .op = 1,
                     .step = 0,
                     .scan_slice = 100,
                     .send_setup = 0,
                     .send_slice = 1};
    WlDpAlgo a = unit_algo();
    WlDpFrame f;
    wl_dp_frame_run(g, &m, &a, &f);
    /* Worked by hand (VP ratios: screen 4, polygons 2, buffer 2):
     * clear 4 + extract 4; transform 2; scan lines: 2 x (compute 2 +
     * enumerate 200); one flush: max 200 + 3 pixel iterations of 2;
     * sends: segments 2 then 1 (load 1 each), pixels: iteration 0 puts
     * (0,0) (1,0) (0,1) in the 2x1 grid of 2x2 blocks: all on processor
     * 0, load 3; iteration 1: (1,0) (2,0): load 1; iteration 2: load 1. */
    assert_int_equal(f.phase[WL_DP_PH_DISPLAY], 8);
    assert_int_equal(f.phase[WL_DP_PH_TRANSFORM], 2);
    assert_int_equal(f.phase[WL_DP_PH_SCAN], 404);
    assert_int_equal(f.phase[WL_DP_PH_PIXEL], 206);
    assert_int_equal(f.phase[WL_DP_PH_ROUTER], 2 + 3 + 1 + 1);
    assert_int_equal(f.total, 8 + 2 + 404 + 206 + 7);
    assert_int_equal(f.counts.scan_iters, 2);
    assert_int_equal(f.counts.flushes, 1);
    assert_int_equal(f.counts.pixel_iters, 3);
    assert_int_equal(f.counts.segments, 3);
    assert_int_equal(f.counts.messages, 3 + 6);
    /* The linear coefficients reproduce the total. */
    double t = f.coef.op_slices * m.op + f.coef.steps * m.step +
               f.coef.scan_slices * m.scan_slice + f.coef.sends * m.send_setup +
               f.coef.slices * m.send_slice;
    assert_true(t == (double)f.total);
    /* A buffer of one polygon's worth flushes before scan line 1. */
    a.buffer_factor = 1.0 / 3.0;
    wl_dp_frame_run(g, &m, &a, &f);
    assert_int_equal(f.counts.flushes, 2);
    assert_int_equal(f.counts.pixel_iters, 3 + 1);
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
    WlDpGeom *g = wl_dp_geom_new(s, 0.0, 160, 120, FALSE);
    assert_true(g->pixels > 0);
    assert_int_equal(g->pixels, g->counters.pixels);
    uint64_t sum = 0;
    for (guint i = 0; i < g->seg_len->len; i++)
        sum += g_array_index(g->seg_len, uint32_t, i);
    /* Convex polygons: one gap-free segment per row. */
    assert_int_equal(sum, g->pixels);
    assert_int_equal(g->seg_pixels, g->pixels);
    /* Inclusive end points: one more pixel per segment, one more row
     * per polygon. */
    WlDpGeom *gi = wl_dp_geom_new(s, 0.0, 160, 120, TRUE);
    assert_int_equal(gi->n_visible, g->n_visible);
    assert_int_equal(gi->seg_len->len, g->seg_len->len + g->n_visible);
    assert_true(gi->seg_pixels > g->pixels + g->seg_len->len);
    assert_int_equal(gi->pixels, g->pixels);
    wl_dp_geom_free(gi);
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
    WlDpMachine m = {.arch = WL_DP_SIMD,
                     .procs = 64,
                     .op = 7,
                     .step = 3,
                     .scan_slice = 5,
                     .send_setup = 11,
                     .send_slice = 13};
    WlDpAlgo a = wl_dp_algo_defaults();
    WlDpFrame f[2];
    for (int i = 0; i < 2; i++) {
        Scene *s = small_iso();
        WlDpGeom *g = wl_dp_geom_new(s, 0.0, 128, 128, TRUE);
        wl_dp_frame_run(g, &m, &a, &f[i]);
        wl_dp_geom_free(g);
        scene_free(s);
    }
    assert_true(f[0].total > 0);
    assert_memory_equal(&f[0], &f[1], sizeof(WlDpFrame));
}

/* The event-driven frame on the machine layer equals the closed form
 * on the SIMD machine, step by step (one event per step). */
static void test_exec_simd_equals_closed_form(void **state)
{
    (void)state;
    Scene *s = small_iso();
    WlDpGeom *g = wl_dp_geom_new(s, 0.0, 96, 64, TRUE);
    WlDpMachine m = {0};
    GError *err = NULL;
    assert_true(wl_dp_machine_load("models", "cm200", &m, &err));
    m.procs = 1024;
    WlDpAlgo a = wl_dp_algo_defaults();
    WlDpFrame cf, ev;
    wl_dp_frame_run(g, &m, &a, &cf);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *mach = wl_dp_exec_machine(eng, "cm200", &m, "analytic", &err);
    assert_non_null(mach);
    assert_true(wl_dp_exec_frame(mach, &m, g, &a, &ev, &err));
    assert_true(cf.total > 0);
    assert_int_equal(ev.total, cf.total);
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++)
        assert_int_equal(ev.phase[ph], cf.phase[ph]);
    assert_int_equal(ev.steps, cf.steps);
    assert_int_equal(sim_engine_events(eng), cf.steps + 1);
    assert_memory_equal(&ev.counts, &cf.counts, sizeof ev.counts);
    mach_free(mach);
    sim_engine_free(eng);
    wl_dp_geom_free(g);
    scene_free(s);
}

/* CM-5: the tiny frame on 2 nodes, every send one message per node pair:
 * no contention, so flow and packet give the analytic time; and the run
 * is deterministic.  Times worked by hand for the first send. */
static void test_exec_spmd_fidelities(void **state)
{
    (void)state;
    WlDpGeom *g = tiny_geom();
    WlDpMachine m = {0};
    GError *err = NULL;
    assert_true(wl_dp_machine_load("models", "cm5", &m, &err));
    m.procs = 2;
    WlDpAlgo a = unit_algo();
    const char *fid[] = {"analytic", "flow", "packet", "analytic"};
    SimTime t[4];
    for (int i = 0; i < 4; i++) {
        SimEngine *eng = sim_engine_new(1);
        MachMachine *mach = wl_dp_exec_machine(eng, "cm5", &m, fid[i], &err);
        assert_non_null(mach);
        WlDpFrame f;
        assert_true(wl_dp_exec_frame(mach, &m, g, &a, &f, &err));
        t[i] = f.total;
        assert_int_equal(f.counts.pixel_iters, 3);
        assert_true(f.phase[WL_DP_PH_ROUTER] > 0);
        mach_free(mach);
        sim_engine_free(eng);
    }
    assert_true(t[0] > 0);
    assert_int_equal(t[1], t[0]);
    assert_int_equal(t[3], t[0]);
    /* Packets of 20 B: a 1-word message is one packet, same time. */
    assert_int_equal(t[2], t[0]);
    wl_dp_geom_free(g);
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
                       "  scan_slice: {value: 5 us, assumption: y}\n"
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
    SimEngine *eng = sim_engine_new(1);
    WlContext ctx = {
        .eng = eng, .root = root, .frames = 2, .fidelity = "analytic"};
    SimResult *r = sim_result_new("dpscan", "cm200");
    assert_true(ops->run(&ctx, p, r, &err));
    assert_true(sim_engine_events(eng) > 10);
    assert_int_equal(r->frame_times->len, 2);
    double pps = 0;
    assert_true(sim_result_get_metric(r, "polygons_per_s", &pps));
    assert_true(pps > 0);
    sim_result_free(r);
    sim_engine_free(eng);
    ops->free_params(p);
    cfg_free(root);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vp_ratio),
        cmocka_unit_test(test_simd_costs),
        cmocka_unit_test(test_spmd_costs),
        cmocka_unit_test(test_layout),
        cmocka_unit_test(test_frame_schedule),
        cmocka_unit_test(test_pixels_match_raster),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_exec_simd_equals_closed_form),
        cmocka_unit_test(test_exec_spmd_fidelities),
        cmocka_unit_test(test_model_errors),
        cmocka_unit_test(test_workload_run),
    };
    return cmocka_run_group_tests_name("dpscan", tests, NULL, NULL);
}
