/* test_dpscan.c — seed 004's data-parallel machine: cost model with
 * exact times, the array layer (combiners, collisions, loads, NEWS,
 * masked ops), model-file errors and a workload run. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/isosurface.h"
#include "sim/workload/dpscan/dp_array.h"
#include "sim/raster/image.h"
#include <glib/gstdio.h>
#include <string.h>
#include "tests/workload/dpscan/dp_test_model.h"
#include "sim/workload/dpscan/dp_poly.h"
#include "sim/workload/workload.h"
#include "tests/support.h"

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
    /* Two arrays, load 5 from 10 elements (every one of the 3 VP slices
     * goes through the router; 2 messages on 4 lanes: 1 per processor
     * on average): 2 * (100 + 50 + 3 * 1 + 1 * 2 + 5 * 7). */
    m.send_msg = 2;
    assert_int_equal(wl_dp_send_cost(&m, 2, 10, 2, 5, &k), 380);
    assert_int_equal(wl_dp_send_cost(&m, 2, 10, 0, 0, &k), 0);
    assert_true(k.op_slices == 9.0 && k.steps == 4.0);
    assert_true(k.scan_slices == 3.0 && k.sends == 2.0);
    assert_true(k.slices == 10.0 && k.vp_slices == 6.0);
    assert_true(k.msg_slices == 2.0);
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

/* The array layer: real data movement, collisions and charged costs. */
static WlDpMachine unit_simd(uint64_t procs)
{
    return (WlDpMachine){.arch = WL_DP_SIMD,
                         .procs = procs,
                         .op = 10,
                         .step = 100,
                         .scan_slice = 20,
                         .send_setup = 50,
                         .send_slice = 7,
                         .news_slice = 3};
}

static void test_array_send_combiners(void **state)
{
    (void)state;
    WlDpMachine ms[2] = {unit_simd(2), unit_simd(4)};
    WlDpVm *vm = wl_dp_vm_new(ms, 2, 4, 2);
    assert_int_equal(wl_dp_vm_n_targets(vm), 2);
    for (int k = WL_DP_MODE_FLAT; k <= WL_DP_MODE_CONTOUR; k++) {
        WlDpMode back; /* every mode's name parses back to it */
        assert_true(wl_dp_mode_parse(wl_dp_mode_name((WlDpMode)k), &back));
        assert_int_equal(back, k);
    }
    WlDpMode none;
    assert_false(wl_dp_mode_parse("phong", &none));
    /* 4 messages from a 4-element array into a 4-element array: 3 land
     * on element 1 (2 collisions). */
    uint64_t dst[] = {1, 1, 3, 1}, val[] = {5, 9, 2, 7}, out[4] = {0};
    WlDpSend s = {.phase = WL_DP_PH_ROUTER, .n_src = 4, .n_dst = 4,
                  .lay = WL_DP_LAYOUT_LINEAR, .dst = dst, .val = val,
                  .count = 4, .dest = out, .words = 1,
                  .comb = WL_DP_COMBINE_MAX};
    assert_int_equal(wl_dp_send(vm, &s), 2);
    assert_int_equal(out[1], 9);
    assert_int_equal(out[3], 2);
    memset(out, 0, sizeof out);
    s.comb = WL_DP_COMBINE_ADD;
    wl_dp_send(vm, &s);
    assert_int_equal(out[1], 21);
    s.comb = WL_DP_COMBINE_OVERWRITE;
    wl_dp_send(vm, &s);
    assert_int_equal(out[1], 7);
    const WlDpVmCounts *c = wl_dp_vm_counts(vm);
    assert_int_equal(c->collisions, 6);
    assert_int_equal(c->max_depth, 3);
    /* 2 processors: VP ratio 2; processor 0 receives 3 (elements 0, 1):
     * 100 + 50 + 3 * 7 per send.  4 processors: element 1 alone is
     * processor 1, also 3. */
    assert_int_equal(wl_dp_vm_target(vm, 0)->total, 3 * 171);
    assert_int_equal(wl_dp_vm_target(vm, 1)->max_load, 3);
    /* Spread destinations: load falls to what one processor injects. */
    uint64_t spread[] = {0, 1, 2, 3};
    s.dst = spread;
    SimTime before = wl_dp_vm_target(vm, 1)->total;
    wl_dp_send(vm, &s);
    assert_int_equal(wl_dp_vm_target(vm, 1)->total - before, 100 + 50 + 7);
    wl_dp_vm_free(vm);
    /* Two processors per router node: processors 0 and 1 (elements 0, 1)
     * share a node, which now receives 2 of the spread messages. */
    ms[1].router_procs = 2;
    vm = wl_dp_vm_new(ms, 2, 4, 2);
    wl_dp_send(vm, &s);
    assert_int_equal(wl_dp_vm_target(vm, 1)->max_load, 2);
    assert_int_equal(wl_dp_vm_target(vm, 0)->max_load, 2);
    wl_dp_vm_free(vm);
}

static void test_array_masked_ops_cost_all(void **state)
{
    (void)state;
    WlDpMachine m = unit_simd(4);
    WlDpVm *vm = wl_dp_vm_new(&m, 1, 4, 2);
    /* 10 elements, 1 active: VP ratio 3, still 100 + 3 * 2 * 10. */
    wl_dp_ew(vm, WL_DP_PH_SCAN, 10, 1, 2);
    assert_int_equal(wl_dp_vm_target(vm, 0)->total, 160);
    uint32_t in[] = {2, 0, 3}, out[3];
    assert_int_equal(wl_dp_scan_add(vm, WL_DP_PH_SCAN, 10, in, out, 3), 5);
    assert_int_equal(out[1], 2);
    assert_int_equal(out[2], 2);
    assert_int_equal(wl_dp_reduce_max(vm, WL_DP_PH_SCAN, 10, in, 3), 3);
    assert_int_equal(wl_dp_vm_target(vm, 0)->total, 160 + 2 * 160);
    wl_dp_vm_free(vm);
}

static void test_array_news(void **state)
{
    (void)state;
    WlDpMachine m = unit_simd(2);
    WlDpVm *vm = wl_dp_vm_new(&m, 1, 3, 2);
    uint64_t in[] = {1, 2, 3, 4, 5, 6}, out[6];
    wl_dp_news(vm, WL_DP_PH_DISPLAY, in, out, 1, 0, 0);
    uint64_t east[] = {0, 1, 2, 0, 4, 5};
    assert_memory_equal(out, east, sizeof east);
    wl_dp_news(vm, WL_DP_PH_DISPLAY, in, out, 0, -1, 9);
    uint64_t north[] = {4, 5, 6, 9, 9, 9};
    assert_memory_equal(out, north, sizeof north);
    /* 6 elements on 2 processors: 100 + 3 * 3 each. */
    assert_int_equal(wl_dp_vm_target(vm, 0)->total, 2 * 109);
    wl_dp_vm_free(vm);
}

static void test_model_errors(void **state)
{
    (void)state;
    /* a bare value in the model's own file: refused by the machine layer
     * when the runner builds the machine */
    const char *bad = "machine:\n  name: t\n"
                      "  nodes: {array: {count: {value: 2, source: s}}}\n"
                      "  network: {topology: {value: ring, source: s},"
                      " bandwidth: {value: 1 MB/s, source: s}}\n"
                      "  dpscan:\n    arch: {value: simd, source: x}\n"
                      "    op: 2 us\n"
                      "workload: {type: dpscan}\n"
                      "scene: {generator: isosurface, grid: 4}\n";
    GError *err = NULL;
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    assert_null(support_run_text(bad, &o, &err));
    if (!strstr(err->message, "test.yaml:7:"))
        fail_msg("%s", err->message);
    assert_non_null(strstr(err->message, "expected {value"));
    g_clear_error(&err);
    WlDpMachine m = {0};
    CfgNode *root;
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
    char *dir = g_dir_make_tmp("dpscan-XXXXXX", NULL);
    SimTime now = 0;
    SupportRun o = {
        .fidelity = "analytic", .frames = 2, .out_dir = dir, .now = &now};
    SimResult *r = support_run_text(yml, &o, &err);
    assert_non_null(r);
    assert_int_equal(r->frame_times->len, 2);
    /* The clock ends where the two frames' counted work ends. */
    SimTime f0 = g_array_index(r->frame_times, SimTime, 0);
    assert_true(f0 > 0);
    assert_int_equal(now, 2 * f0);
    /* Only the last frame is written, through the generic hook. */
    char *first = g_build_filename(dir, "frame-0000.png", NULL);
    assert_false(g_file_test(first, G_FILE_TEST_EXISTS));
    g_free(first);
    char *png = g_build_filename(dir, "frame.png", NULL);
    RastImage *img = rast_image_read_png(png, &err);
    assert_non_null(img);
    assert_int_equal(img->width, 64);
    assert_true(rast_image_get(img, 32, 24) != rast_image_get(img, 0, 0));
    rast_image_free(img);
    g_unlink(png);
    g_free(png);
    g_rmdir(dir);
    g_free(dir);
    double pps = 0;
    assert_true(sim_result_get_metric(r, "polygons_per_s", &pps));
    assert_true(pps > 0);
    sim_result_free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vp_ratio),
        cmocka_unit_test(test_simd_costs),
        cmocka_unit_test(test_spmd_costs),
        cmocka_unit_test(test_layout),
        cmocka_unit_test(test_array_send_combiners),
        cmocka_unit_test(test_array_masked_ops_cost_all),
        cmocka_unit_test(test_array_news),
        cmocka_unit_test(test_model_errors),
        cmocka_unit_test(test_workload_run),
    };
    return cmocka_run_group_tests_name("dpscan", tests, NULL, NULL);
}
