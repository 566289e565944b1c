/* test_pm_run.c — the pixelmerge run through the runner (issue 21):
 * every metric it prints equals the value recomputed from one frame run
 * by the test on a fresh machine (wl_pm_frame_run_procs with the same
 * setup and costs): phase times, speed-up and utilisation from their
 * definitions, the counts (themselves rebuilt from the local renders,
 * the partition, the merge and its replay), and the peak memory as the largest
 * node's wl_pm_memory_use() (P = 1 included); frames and elapsed time; a
 * machine without a "node" kind refused with the exact message; and the
 * image written under an output directory. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <string.h>

#include "sim/raster/image.h"
#include "sim/scene/scene_cfg.h"
#include "sim/workload/pixelmerge/pm_workload.h"
#include "tests/support.h"

static const char *cfg_text =
    "machine: {model: ipsc2}\n"
    "workload: {type: pixelmerge, scheme: %s,\n"
    "           processors: %u, resolution: 24%s}\n"
    "scene: {generator: teapots, count: 2, polygons_per_teapot: 300,\n"
    "        layout: spread}\n";

typedef struct {
    CfgNode *root;
    WlPmParams *p;
    Scene *sc;
} Setup;

static Setup setup(const char *scheme, guint procs, const char *extra)
{
    char *text = g_strdup_printf(cfg_text, scheme, procs, extra);
    GError *err = NULL;
    Setup s = {cfg_load_string(text, "pm.yaml", &err), NULL, NULL};
    g_free(text);
    assert_non_null(s.root);
    s.p = wl_pixelmerge_ops.parse(cfg_get(s.root, "workload"), &err);
    assert_non_null(s.p);
    s.sc = scene_from_cfg(cfg_get(s.root, "scene"), &err);
    assert_non_null(s.sc);
    return s;
}

static void setup_clear(Setup *s)
{
    scene_free(s->sc);
    wl_pixelmerge_ops.free_params(s->p);
    cfg_free(s->root);
}

static MachMachine *machine(const Setup *s, SimEngine *eng, WlPmCosts *c)
{
    GError *err = NULL;
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(s->root, "machine"), "analytic", &err);
    assert_non_null(m);
    assert_true(wl_pm_costs_from_machine(m, s->p->count_bytes, c, &err));
    return m;
}

static double metric(const SimResult *r, const char *name)
{
    double v = -1;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}

/* The largest node's footprint, by the test's own loop over nodes. */
static WlPmMemUse largest(const Setup *s, const WlPmFrameOut *fo)
{
    WlPmMemUse best = {0};
    for (guint q = 0; q < s->p->setup.procs; q++) {
        WlPmMemUse u =
            wl_pm_memory_use(&s->p->mem, &s->p->setup, fo->counts[q].polygons,
                             fo->counts[q].rc.spans, fo->active[q]);
        assert_true(u.total > 0);
        if (u.total > best.total)
            best = u;
    }
    return best;
}

static void check_memory(const SimResult *r, const WlPmMemUse *u)
{
    assert_true(metric(r, "peak_memory") == (double)u->total);
    assert_true(metric(r, "memory_base") == (double)u->base);
    assert_true(metric(r, "memory_polygons") == (double)u->polygons);
    assert_true(metric(r, "memory_spans") == (double)u->spans);
    assert_true(metric(r, "memory_zbuffer") == (double)u->zbuffer);
    assert_true(metric(r, "memory_buffers") == (double)u->buffers);
}

static void check_frame_metrics(const SimResult *r, const WlPmFrameOut *fo,
                                guint P, double serial)
{
    SimTime busy = 0;
    for (guint q = 0; q < P; q++)
        busy += fo->busy[q].total;
    assert_true(metric(r, "processors") == P);
    assert_true(metric(r, "resolution") == 24);
    assert_true(metric(r, "span_ms") == fo->span_ms);
    assert_true(metric(r, "zbuf_ms") == fo->zbuf_ms);
    assert_true(metric(r, "merge_ms") == fo->merge_ms);
    assert_true(metric(r, "frame_ms") == fo->frame_ms);
    assert_true(metric(r, "serial_ms") == serial);
    assert_true(metric(r, "speedup") == serial / fo->frame_ms);
    assert_true(metric(r, "utilisation") ==
                sim_time_to_ms(busy) / (P * fo->frame_ms));
    assert_true(metric(r, "concurrent_volume") == fo->concurrent_volume);
    assert_true(metric(r, "merge_bytes") == fo->merge_bytes);
    assert_true(metric(r, "load_imbalance") == fo->load_imbalance);
    assert_true(metric(r, "partition_imbalance") == fo->partition_imbalance);
    assert_true(metric(r, "polygons") == 600);
    assert_true(metric(r, "tpg") == fo->tpg);
    assert_true(metric(r, "tpf") == fo->tpf);
    assert_true(metric(r, "image_matches_serial") == 1);
}

/* The frame's counts rebuilt from the public pieces: each processor's
 * local render (its share, active pixels, row counts), the partition by
 * the setup's balancing, the merge by its scheme, and the merge replayed
 * alone on a fresh machine (ZBUF-EXC without a global sum: strips). */
static void check_glue(const Setup *s, const WlPmFrameOut *fo,
                       const WlPmCosts *c)
{
    const WlPmSetup *su = &s->p->setup;
    guint P = su->procs, N = su->resolution;
    SceneMesh *flat = scene_flatten(s->sc);
    SceneCamera cam = scene_camera_at(s->sc, 0);
    RastView v = rast_view_for_camera(&cam, N, N);
    v.cull_back = su->cull_back;
    v.span_rule = su->span_rule;
    WlPmWpa *local[8];
    uint64_t rows[24] = {0}, tpg = 0, polys = 0;
    for (guint q = 0; q < P; q++) {
        WlPmCounts k;
        local[q] = wl_pm_render_local(&v, flat, q, P, su->split, &k);
        assert_memory_equal(&fo->counts[q], &k, sizeof k);
        assert_int_equal(fo->active[q], wl_pm_wpa_len(local[q]));
        wl_pm_wpa_add_row_counts(local[q], rows);
        tpg += k.rc.pixels;
        polys += k.polygons;
    }
    assert_int_equal(fo->tpg, tpg);
    assert_int_equal(polys, 600);
    WlPmPartition *part = wl_pm_partition_new(su->balance, P, rows, N);
    uint64_t load[8];
    wl_pm_partition_loads(part, rows, load);
    assert_true(fo->partition_imbalance == wl_pm_load_imbalance(load, P));
    WlPmMerge *m = wl_pm_merge_run(su->scheme, local, P, part, &su->fmt);
    assert_int_equal(fo->tpf, wl_pm_frame_count(m->image));
    assert_int_equal(fo->concurrent_volume, m->concurrent_volume);
    assert_int_equal(fo->merge_bytes, m->total_bytes);
    assert_true(fo->load_imbalance == wl_pm_load_imbalance(m->merge_ops, P));
    SimEngine *eng = sim_engine_new(1);
    WlPmCosts c2;
    MachMachine *mm = machine(s, eng, &c2);
    SimBusy busy[8];
    SimTime ready[8] = {0};
    for (guint q = 0; q < P; q++)
        sim_busy_init(&busy[q]);
    WlPmReplayOut ro = {0};
    WlPmReplayRig rig = {.net = mach_net(mm),
                         .costs = &c->merge,
                         .ready = ready,
                         .busy = busy,
                         .bal = su->scheme == WL_PM_ZBUF_EXC ? WL_PM_BAL_STRIPS
                                                             : su->balance,
                         .height = N};
    assert_true(wl_pm_replay(&rig, m, &ro, NULL));
    assert_true(fo->merge_ms == sim_time_to_ms(ro.end));
    wl_pm_replay_out_clear(&ro);
    for (guint q = 0; q < P; q++) {
        sim_busy_clear(&busy[q]);
        wl_pm_wpa_free(local[q]);
    }
    mach_free(mm);
    sim_engine_free(eng);
    wl_pm_merge_free(m);
    wl_pm_partition_free(part);
    scene_mesh_free(flat);
}

/* Runs `frames` frames through the runner and checks the result against
 * one frame the test runs itself on a fresh machine. */
static void check_run(const char *scheme, guint P, int frames,
                      const char *extra)
{
    Setup s = setup(scheme, P, extra);
    SimTime now = 0;
    SupportRun o = {.fidelity = "analytic", .frames = frames, .now = &now};
    GError *err = NULL;
    SimResult *r = support_run_tree(cfg_copy(s.root), &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    assert_int_equal(r->frame_times->len, frames);
    assert_true(r->elapsed == now && r->elapsed > 0);

    SimEngine *eng = sim_engine_new(1);
    WlPmCosts c;
    MachMachine *m = machine(&s, eng, &c);
    MachProc *procs[8];
    for (guint q = 0; q < P; q++)
        procs[q] = mach_proc(m, "node", q);
    WlPmFrameOut fo;
    if (!wl_pm_frame_run_procs(mach_net(m), procs, 0, s.sc, &s.p->setup, &c,
                               &fo, &err))
        fail_msg("%s", err->message);
    /* every frame takes as long (one camera); the run ends after them all */
    for (int f = 0; f < frames; f++)
        assert_true(g_array_index(r->frame_times, SimTime, f) ==
                    sim_now(mach_engine(m)));
    assert_true(r->elapsed == (SimTime)frames * sim_now(mach_engine(m)));
    double ins = -1;
    double serial = wl_pm_serial_ms(s.sc, &s.p->setup, &c, &ins);
    check_frame_metrics(r, &fo, P, serial);
    check_glue(&s, &fo, &c);
    assert_true(metric(r, "serial_insert_ms") == ins && ins > 0);
    WlPmMemUse u = largest(&s, &fo);
    check_memory(r, &u);
    wl_pm_frame_out_clear(&fo, P);
    sim_result_free(r);
    mach_free(m);
    sim_engine_free(eng);
    setup_clear(&s);
}

static void test_metrics_recomputed(void **state)
{
    (void)state;
    check_run("pair", 4, 1, ", balance: hbp");
    check_run("aapc", 8, 2, ", cull_back: true, polygon_split: block");
    check_run("zbuf-exc", 2, 1, ", span_rule: endpoints, balance: hbp");
    check_run("pair", 2, 1, ", balance: strips, cull_back: true");
    check_run("pair", 1, 1, ""); /* the only node is the peak */
}

/* A machine with no node kind "node" (the CM-200: front_end and array)
 * and processors left to the machine: 0 processors, refused before any
 * cost is asked for. */
static void test_machine_without_nodes(void **state)
{
    (void)state;
    GError *err = NULL;
    SupportRun o = {.fidelity = "analytic"};
    SimResult *r = support_run_text(
        "machine: {model: cm200}\n"
        "workload: {type: pixelmerge, scheme: pair, resolution: 24}\n"
        "scene: {generator: teapots, count: 1, polygons_per_teapot: 300}\n",
        &o, &err);
    assert_null(r);
    assert_string_equal(err->message,
                        "pixelmerge: found '0' processors, expected at most "
                        "the 0 nodes of kind 'node' of machine 'cm200'");
    g_error_free(err);
}

/* With an output directory the run writes the last frame's merged image
 * (DIR/frame.png, no per-frame files): the raster library's image of the
 * scene, every channel in its place. */
static void test_frame_png(void **state)
{
    (void)state;
    Setup s = setup("aapc", 4, "");
    char *dir = g_dir_make_tmp("pm-run-XXXXXX", NULL);
    SupportRun o = {.fidelity = "analytic", .frames = 2, .out_dir = dir};
    GError *err = NULL;
    SimResult *r = support_run_tree(cfg_copy(s.root), &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    char *first = g_build_filename(dir, "frame-0000.png", NULL);
    assert_false(g_file_test(first, G_FILE_TEST_EXISTS));
    char *png = g_build_filename(dir, "frame.png", NULL);
    RastImage *got = rast_image_read_png(png, &err);
    assert_non_null(got);
    SceneMesh *flat = scene_flatten(s.sc);
    SceneCamera cam = scene_camera_at(s.sc, 1);
    RastView v = rast_view_for_camera(&cam, 24, 24);
    v.cull_back = FALSE;
    RastSpanList *sl = rast_spanlist_new(24, 24);
    RastCounters rc = {0};
    rast_draw_mesh(&v, flat, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   rast_spanlist_sink(sl), &rc);
    rast_spanlist_sort(sl);
    RastActive *a = rast_active_new(24, 24);
    rast_scanline_zbuffer(a, sl, &rc);
    RastImage *want = rast_image_new(24, 24);
    rast_image_from_active(want, a, (RastColor){0, 0, 0});
    assert_true(rast_active_count(a) > 30); /* the teapots show */
    assert_int_equal(rast_image_diff(got, want), 0);
    rast_image_free(want);
    rast_active_free(a);
    rast_spanlist_free(sl);
    scene_mesh_free(flat);
    rast_image_free(got);
    g_unlink(png);
    g_rmdir(dir);
    g_free(png);
    g_free(first);
    g_free(dir);
    sim_result_free(r);
    setup_clear(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_metrics_recomputed),
        cmocka_unit_test(test_machine_without_nodes),
        cmocka_unit_test(test_frame_png),
    };
    return cmocka_run_group_tests_name("pm_run", tests, NULL, NULL);
}
