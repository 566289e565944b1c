/* test_dp_run.c — the dpscan workload (dp_workload.c) against the same
 * frame rendered directly on the array layer: every metric it reports
 * (per-phase seconds, steps, loop and message counts, the busiest load,
 * polygons per second) and its frame time equal what the layer counted,
 * the machine's array is busy exactly the frame's time in each phase;
 * the smallest CM-200 partition (16 processors: one router) runs; own
 * memory is 12 B a pixel and 12 B a processor.  Run from the repository
 * root (models/).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/scene_cfg.h"
#include "sim/workload/dpscan/dp_color.h"
#include "tests/workload/dpscan/dp_test_model.h"
#include "sim/workload/dpscan/dp_render.h"
#include "sim/workload/dpscan/dp_workload.h"
#include "tests/support.h"

static const char *scene_yaml = "scene: {generator: isosurface, grid: 6}\n";

static SimResult *run(const char *workload, GError **err)
{
    char *text = g_strconcat(workload, scene_yaml, NULL);
    CfgNode *root = cfg_load_string(text, "run.yaml", err);
    g_free(text);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    return support_run_tree(root, &o, err);
}

static double metric(const SimResult *r, const char *name)
{
    double v = NAN;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}

static void same(const SimResult *r, const char *name, double want)
{
    double got = metric(r, name);
    if (!(fabs(got - want) <= 1e-12 * fabs(want))) /* NaN fails */
        fail_msg("%s: %.17g, expected %.17g", name, got, want);
}

/* The frame rendered by hand: model `model` at `procs` processors. */
static void check_against_layer(const char *model, uint64_t procs,
                                const char *extra)
{
    char *w = g_strdup_printf(
        "workload: {type: dpscan, model: %s, processors: %" G_GUINT64_FORMAT
        ", width: 40, height: 30, mode: flat, wire: formula%s}\n",
        model, procs, extra);
    GError *err = NULL;
    SimResult *r = run(w, &err);
    if (!r)
        fail_msg("%s: %s", w, err->message);
    WlDpMachine m = {0};
    assert_true(dp_test_model(model, &m, &err));
    m.procs = procs;
    CfgNode *root = cfg_load_string(scene_yaml, "s.yaml", &err);
    Scene *s = scene_from_cfg(cfg_get(root, "scene"), &err);
    assert_non_null(s);
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 40, 30, WL_DP_MODE_FLAT, pal);
    WlDpVm *vm = wl_dp_vm_new(&m, 1, 40, 30);
    WlDpRenderOpts o = {.mode = WL_DP_MODE_FLAT,
                        .buffer_factor = 0.25,
                        .ops = wl_dp_ops_defaults()};
    WlDpImage *img = wl_dp_render(vm, p, 40, 30, &o);
    const WlDpTarget *t = wl_dp_vm_target(vm, 0);
    const WlDpVmCounts *c = wl_dp_vm_counts(vm);
    assert_true(t->total > 0 && c->messages > 0 && img->flushes > 0);
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++) {
        char *name = g_strdup_printf("%s_s", wl_dp_phase_name(ph));
        same(r, name, sim_time_to_s(t->phase[ph]));
        g_free(name);
    }
    same(r, "polygons_per_s", (double)p->n / sim_time_to_s(t->total));
    same(r, "steps", (double)c->steps);
    same(r, "scan_iters", (double)img->scan_iters);
    same(r, "pixel_iters", (double)img->pixel_iters);
    same(r, "flushes", (double)img->flushes);
    same(r, "segments", (double)img->segments);
    same(r, "pixels", (double)img->pixels);
    same(r, "collisions", (double)c->collisions);
    same(r, "messages", (double)c->messages);
    same(r, "max_load", (double)t->max_load);
    assert_int_equal(r->frame_times->len, 1);
    assert_int_equal(g_array_index(r->frame_times, SimTime, 0), t->total);
    assert_int_equal(r->elapsed, t->total);
    double v;
    if (m.arch == WL_DP_SPMD) {
        same(r, "router_wire_s", sim_time_to_s(t->wire_total));
        same(r, "router_soft_s", sim_time_to_s(t->soft_total));
    } else {
        assert_false(sim_result_get_metric(r, "router_wire_s", &v));
    }
    /* every processor that plays the frame is busy all of it, each
     * phase's time in that phase */
    const SimNodeResult *n0 = g_ptr_array_index(r->nodes, 0);
    assert_int_equal(n0->busy.total, t->total);
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++) {
        guint id = G_MAXUINT;
        for (guint k = 0; k < r->phases->len; k++)
            if (!strcmp(g_ptr_array_index(r->phases, k), wl_dp_phase_name(ph)))
                id = k;
        assert_true(id != G_MAXUINT);
        assert_int_equal(sim_busy_phase(&n0->busy, id), t->phase[ph]);
    }
    wl_dp_image_free(img);
    wl_dp_vm_free(vm);
    wl_dp_polys_free(p);
    scene_free(s);
    cfg_free(root);
    sim_result_free(r);
    g_free(w);
}

static void test_simd_metrics(void **state)
{
    (void)state;
    check_against_layer("cm200", 1024, "");
    check_against_layer("cm200", 16, ""); /* one router */
}

static void test_spmd_metrics(void **state)
{
    (void)state;
    check_against_layer("cm5", 32, "");
}

static void test_mem_bytes(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root =
        cfg_load_string("{type: dpscan, processors: 64, width: 30, height: 20}",
                        "w.yaml", &err);
    const WlOps *ops = wl_find("dpscan");
    void *p = ops->parse(root, &err);
    assert_non_null(p);
    GString *what = g_string_new("");
    assert_true(ops->mem_bytes(p, what) == 30.0 * 20 * 12 + 64 * 12.0);
    assert_string_equal(what->str, "64 processors, 30 x 20 pixels");
    g_string_free(what, TRUE);
    ops->free_params(p);
    cfg_free(root);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_simd_metrics),
        cmocka_unit_test(test_spmd_metrics),
        cmocka_unit_test(test_mem_bytes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
