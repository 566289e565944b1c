/* test_sf_metrics.c — wl_sf_fill_metrics() on per-frame figures made up
 * so that every field of every frame differs: each steady-state metric
 * is the mean over the frames after the first (the first alone for a
 * one-frame run), maxima and the image verdict take every frame, ratios
 * divide the right sums, and the policy-dependent metrics appear only
 * under their policy. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "tests/workload/sortfirst/sf_testutil.h"

/* Field k of frame f. */
static double v(guint f, guint k)
{
    return (f + 1) * 100.0 + k;
}

static WlSfFrameStats frame(guint f)
{
    WlSfFrameStats s = {0};
    s.start = (SimTime)f * 10 * SIM_MS;
    s.end = s.start + (SimTime)(f + 1) * SIM_MS;
    s.migrated_chunks = v(f, 1), s.migrated_polys = v(f, 2);
    s.migrated_insts = v(f, 3), s.migrated_bytes = v(f, 4);
    s.messages = v(f, 5), s.master_boxes = v(f, 6), s.slave_boxes = v(f, 7);
    s.new_boxes = v(f, 8), s.deleted_chunks = v(f, 9);
    s.probe_boxes = v(f, 10), s.polys_rendered = v(f, 11);
    s.poly_imbalance = v(f, 12), s.imbalance = v(f, 13);
    s.estimate_bytes = v(f, 14), s.split_imbalance = v(f, 15);
    s.onscreen_insts = v(f, 16), s.region_insts = v(f, 17);
    s.box_side = v(f, 18), s.peak_memory = f == 0 ? 99 : v(f, 19);
    s.requests = v(f, 20), s.handovers = v(f, 21), s.held_polys = v(f, 22);
    s.master_imbalance = v(f, 23), s.offscreen_max = v(f, 24);
    s.offscreen_total = v(f, 25);
    s.trav = (WlSfTrav){v(f, 26), v(f, 27), v(f, 28), v(f, 29), v(f, 30),
                        v(f, 31)};
    s.edits = v(f, 32), s.edit_bytes = v(f, 33), s.nodes_created = v(f, 34);
    s.nodes_collected = v(f, 35), s.pointers_collected = v(f, 36);
    s.chunks_collected = v(f, 37), s.utilisation = v(f, 38);
    s.traverse_busy = (SimTime)v(f, 39) * SIM_MS;
    s.edit_busy = (SimTime)v(f, 40) * SIM_MS;
    s.image_checked = f < 2, s.image_ok = TRUE;
    return s;
}

static double metric(const SimResult *r, const char *name)
{
    double x = NAN;
    if (!sim_result_get_metric(r, name, &x))
        fail_msg("no metric %s", name);
    return x;
}

static void expect(const SimResult *r, const char *name, double want)
{
    double got = metric(r, name);
    if (!(fabs(got - want) <= 1e-9 * fabs(want)))
        fail_msg("%s: %.12g, expected %.12g", name, got, want);
}

/* The mean of field k over frames 1 and 2. */
static double mean(guint k)
{
    return (v(1, k) + v(2, k)) / 2;
}

static void test_three_frames(void **st)
{
    (void)st;
    SceneDb *src;
    WlSfDb *db = sf_test_tiny_db(&src, 4);
    GArray *stats = g_array_new(FALSE, FALSE, sizeof(WlSfFrameStats));
    for (guint f = 0; f < 3; f++) {
        WlSfFrameStats s = frame(f);
        g_array_append_val(stats, s);
    }
    WlSfSetup su = {.procs = 4, .resolution = 64, .adaptive = TRUE,
                    .mig = WL_SF_PULL, .ms = WL_SF_DYNAMIC, .edits = TRUE};
    SimResult *r = sim_result_new("sortfirst", "");
    wl_sf_fill_metrics(r, stats, db, &su);
    expect(r, "processors", 4);
    expect(r, "granularity", 2);
    expect(r, "resolution", 64);
    expect(r, "chunks", 2); /* 3 triangles, 2 a chunk */
    expect(r, "chunk_instances", 2);
    expect(r, "min_set_polygons", 3);
    expect(r, "max_set_polygons", 3);
    expect(r, "frame_ms", 2.5);
    expect(r, "migrated_chunks_per_frame", mean(1));
    expect(r, "migrated_polygons_per_frame", mean(2));
    expect(r, "migrated_pointers_per_frame", mean(3));
    expect(r, "migrated_bytes_per_frame", mean(4));
    expect(r, "initial_bytes", v(0, 4));
    expect(r, "messages_per_frame", mean(5));
    expect(r, "master_boxes_per_frame", mean(6));
    expect(r, "slave_boxes_per_frame", mean(7));
    expect(r, "new_boxes_per_frame", mean(8));
    expect(r, "slave_deletions_per_frame", mean(9));
    expect(r, "probe_boxes_per_frame", mean(10));
    expect(r, "polygons_rendered_per_frame", mean(11));
    expect(r, "transforms_per_frame",
           mean(6) + mean(7) + mean(8) + mean(10) + mean(11));
    expect(r, "polygon_imbalance", mean(12));
    expect(r, "load_imbalance", mean(13));
    expect(r, "load_imbalance_max", v(2, 13));
    expect(r, "estimate_bytes_per_frame", mean(14));
    expect(r, "split_imbalance", mean(15));
    expect(r, "chunk_overlap", mean(17) / mean(16));
    expect(r, "box_region_ratio", mean(18) / mean(16) / sqrt(64.0 * 64 / 4));
    expect(r, "peak_memory", v(2, 19));
    expect(r, "requests_per_frame", mean(20));
    expect(r, "handovers_per_frame", mean(21));
    expect(r, "copies", mean(22) / 3);
    expect(r, "master_polygon_imbalance", mean(23));
    expect(r, "offscreen_master_polygons_max", mean(24));
    expect(r, "offscreen_master_polygons", mean(25));
    expect(r, "traversal_nodes_per_frame", mean(26));
    expect(r, "traversal_nodes_flags", mean(27));
    expect(r, "traversal_nodes_culled", mean(28));
    expect(r, "traversal_nodes_flags_culled", mean(29));
    expect(r, "boxes_culled_per_frame", mean(30));
    expect(r, "volume_tests_per_frame", mean(31));
    expect(r, "edits_per_frame", mean(32));
    expect(r, "edit_bytes_per_frame", mean(33));
    expect(r, "maxset_nodes_created_per_frame", mean(34));
    expect(r, "maxset_nodes_collected_per_frame", mean(35));
    expect(r, "pointers_collected_per_frame", mean(36));
    expect(r, "chunks_collected_per_frame", mean(37));
    expect(r, "utilisation", mean(38));
    expect(r, "traversal_ms", mean(39) / 4);
    expect(r, "edit_ms", mean(40) / 4);
    expect(r, "image_matches_serial", 1);
    sim_result_free(r);
    /* one checked frame wrong, frame 0's peak the largest, push, fixed,
     * static, no edits: the policy metrics are absent */
    g_array_index(stats, WlSfFrameStats, 1).image_ok = FALSE;
    g_array_index(stats, WlSfFrameStats, 0).peak_memory = 5000;
    g_array_index(stats, WlSfFrameStats, 0).imbalance = 9999;
    su = (WlSfSetup){.procs = 4, .resolution = 64};
    r = sim_result_new("sortfirst", "");
    wl_sf_fill_metrics(r, stats, db, &su);
    expect(r, "image_matches_serial", 0);
    expect(r, "peak_memory", 5000);
    expect(r, "load_imbalance_max", v(2, 13));
    expect(r, "transforms_per_frame",
           mean(6) + mean(7) + mean(8) + mean(10) + mean(11));
    static const char *const absent[] = {
        "probe_boxes_per_frame", "estimate_bytes_per_frame", "split_imbalance",
        "requests_per_frame", "handovers_per_frame", "edits_per_frame",
        "edit_ms"};
    double x;
    for (guint i = 0; i < G_N_ELEMENTS(absent); i++)
        if (sim_result_get_metric(r, absent[i], &x))
            fail_msg("%s present", absent[i]);
    sim_result_free(r);
    /* a frame checked wrong before the steady state counts too; no frame
     * checked: no verdict */
    g_array_index(stats, WlSfFrameStats, 1).image_ok = TRUE;
    g_array_index(stats, WlSfFrameStats, 0).image_ok = FALSE;
    r = sim_result_new("sortfirst", "");
    wl_sf_fill_metrics(r, stats, db, &su);
    expect(r, "image_matches_serial", 0);
    sim_result_free(r);
    for (guint f = 0; f < 3; f++)
        g_array_index(stats, WlSfFrameStats, f).image_checked = FALSE;
    r = sim_result_new("sortfirst", "");
    wl_sf_fill_metrics(r, stats, db, &su);
    assert_false(sim_result_get_metric(r, "image_matches_serial", &x));
    sim_result_free(r);
    g_array_unref(stats);
    wl_sf_db_free(db);
    scene_db_free(src);
}

/* One frame: its own figures, n = 1; no instance on screen: ratios 0. */
static void test_one_frame(void **st)
{
    (void)st;
    SceneDb *src;
    WlSfDb *db = sf_test_tiny_db(&src, 4);
    GArray *stats = g_array_new(FALSE, FALSE, sizeof(WlSfFrameStats));
    WlSfFrameStats s = frame(0);
    g_array_append_val(stats, s);
    WlSfSetup su = {.procs = 2, .resolution = 32};
    SimResult *r = sim_result_new("sortfirst", "");
    wl_sf_fill_metrics(r, stats, db, &su);
    expect(r, "frame_ms", 1);
    expect(r, "migrated_chunks_per_frame", v(0, 1));
    expect(r, "load_imbalance_max", v(0, 13));
    expect(r, "traversal_ms", v(0, 39) / 2);
    expect(r, "copies", v(0, 22) / 3);
    expect(r, "peak_memory", 99);
    sim_result_free(r);
    g_array_index(stats, WlSfFrameStats, 0).onscreen_insts = 0;
    r = sim_result_new("sortfirst", "");
    wl_sf_fill_metrics(r, stats, db, &su);
    assert_true(metric(r, "chunk_overlap") == 0);
    assert_true(metric(r, "box_region_ratio") == 0);
    sim_result_free(r);
    /* two frames: the second alone is the steady state */
    s = frame(1);
    g_array_append_val(stats, s);
    r = sim_result_new("sortfirst", "");
    wl_sf_fill_metrics(r, stats, db, &su);
    expect(r, "frame_ms", 2);
    expect(r, "migrated_chunks_per_frame", v(1, 1));
    expect(r, "initial_bytes", v(0, 4));
    sim_result_free(r);
    g_array_unref(stats);
    wl_sf_db_free(db);
    scene_db_free(src);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_three_frames),
        cmocka_unit_test(test_one_frame),
    };
    return cmocka_run_group_tests_name("sf_metrics", tests, NULL, NULL);
}
