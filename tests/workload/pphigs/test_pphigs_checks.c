/* test_pphigs_checks.c — the pphigs YAML readers and metric formulas
 * against values the test computes itself (issue 21): every field of a
 * database spec and of frame.yaml read, each located error (no kind, an
 * unknown kind or database, a bare or unsourced cluster_scale, an unknown
 * key), the clustering factor max(1, scale / GPs) at its edge, and the
 * metrics of pphigs_metrics.h with all GPs idle. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <math.h>
#include <string.h>

#include "sim/workload/pphigs/pphigs_cfg.h"
#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/pphigs_distrib.h"
#include "sim/workload/pphigs/pphigs_metrics.h"
#include "sim/workload/pphigs/pphigs_pixels.h"

static gboolean spec(const char *yaml, ScenePphigsSpec *s, GError **err)
{
    CfgNode *root = cfg_load_string(yaml, "db.yaml", err);
    assert_non_null(root);
    gboolean ok = wl_pphigs_spec_from_cfg(root, s, err);
    cfg_free(root);
    return ok;
}

static void spec_fails(const char *yaml, const char *message)
{
    ScenePphigsSpec s;
    GError *err = NULL;
    assert_false(spec(yaml, &s, &err));
    if (strcmp(err->message, message))
        fail_msg("%s: '%s', expected '%s'", yaml, err->message, message);
    g_error_free(err);
}

static void test_spec_fields(void **state)
{
    (void)state;
    ScenePphigsSpec s;
    GError *err = NULL;
    if (!spec("{kind: flock_old_well, seed: 7, size: 2.5, fov_deg: 179,\n"
              " polygons: 1, attributes: 2, verts: 3, boids: 4,\n"
              " boid_polygons: 5, boid_colors: 6, well_structs: 7,\n"
              " well_polygons: 8, well_attributes: 9, figures: 10,\n"
              " structures: 11, levels: 12, overlays: 1073741824}",
              &s, &err))
        fail_msg("%s", err->message);
    ScenePphigsKind k;
    assert_true(scene_pphigs_kind_parse("flock_old_well", &k));
    assert_int_equal(s.kind, k);
    assert_int_equal(s.seed, 7);
    assert_true(s.size == 2.5 && s.fov_deg == 179);
    const guint want[] = {s.polygons,      s.attributes,   s.verts,
                          s.boids,         s.boid_polygons, s.boid_colors,
                          s.well_structs,  s.well_polygons, s.well_attributes,
                          s.figures,       s.structures,   s.levels};
    for (guint i = 0; i < G_N_ELEMENTS(want); i++)
        assert_int_equal(want[i], i + 1);
    assert_int_equal(s.overlays, 1u << 30);
    spec_fails("{seed: 1}",
               "db.yaml:1:1: found no key 'kind' in this map, expected "
               "'kind': a string");
    spec_fails("{kind: castle}",
               "db.yaml:1:8: found kind 'castle', expected space_station, "
               "building_lobby, flock_old_well or two_human_figures");
    spec_fails("[1, 2]", "db.yaml:1:1: found a non-map, expected a map of "
                         "generator parameters");
    spec_fails("{kind: space_station, overlays: 1073741825}",
               "db.yaml:1:33: found '1073741825', expected a count in [0, "
               "1073741824]");
    spec_fails("{kind: space_station, fov_deg: 180}",
               "db.yaml:1:32: found '180', expected a number in [1, 179]");
    spec_fails("{kind: space_station, colour: red}",
               "db.yaml:1:23: found unknown key 'colour', expected one of: "
               "kind, seed, size, fov_deg, polygons, attributes, verts, "
               "boids, boid_polygons, boid_colors, well_structs, "
               "well_polygons, well_attributes, figures, structures, levels, "
               "overlays");
}

static void test_spec_load(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pphigs-XXXXXX", NULL);
    char *path = g_build_filename(dir, "dbs.yaml", NULL);
    assert_true(g_file_set_contents(
        path, "lobby: {kind: building_lobby, polygons: 40}\n"
              "well: {kind: flock_old_well}\n", -1, NULL));
    ScenePphigsSpec s;
    GError *err = NULL;
    assert_true(wl_pphigs_spec_load(path, "lobby", NULL, &s, &err));
    assert_int_equal(s.polygons, 40);
    assert_false(wl_pphigs_spec_load(path, "attic", NULL, &s, &err));
    char *want = g_strdup_printf("%s:1:1: found database 'attic', expected "
                                 "one of the databases of %s: lobby, well, "
                                 "or a structure database file (*.yaml)",
                                 path, path);
    assert_string_equal(err->message, want);
    g_clear_error(&err);
    g_free(want);
    /* the error at the caller's key when given */
    CfgNode *at = cfg_load_string("database: attic\n", "w.yaml", &err);
    assert_false(
        wl_pphigs_spec_load(path, "attic", cfg_get(at, "database"), &s, &err));
    assert_true(g_str_has_prefix(err->message, "w.yaml:1:11: found database "
                                               "'attic'"));
    g_clear_error(&err);
    cfg_free(at);
    assert_false(wl_pphigs_spec_load("/nonexistent/dbs.yaml", "lobby", NULL,
                                     &s, &err));
    g_clear_error(&err);
    g_remove(path);
    g_rmdir(dir);
    g_free(path);
    g_free(dir);
}

static const char *frame_keys =
    "width: 1280\nheight: 1024\nregion: 128\ncmd_bytes: 20\nend_bytes: 4\n"
    "batch: 16\npixel_bytes: 3\nelement_bytes: 24\n";

static gboolean setup(const char *extra, WlPphigsSetup *s, GError **err)
{
    char *y = g_strconcat(frame_keys, extra, NULL);
    CfgNode *root = cfg_load_string(y, "frame.yaml", err);
    g_free(y);
    assert_non_null(root);
    gboolean ok = wl_pphigs_setup_from_cfg(root, s, err);
    cfg_free(root);
    return ok;
}

static void setup_fails(const char *extra, const char *message)
{
    WlPphigsSetup s;
    GError *err = NULL;
    assert_false(setup(extra, &s, &err));
    if (strcmp(err->message, message))
        fail_msg("%s: '%s', expected '%s'", extra, err->message, message);
    g_error_free(err);
}

static void test_setup(void **state)
{
    (void)state;
    WlPphigsSetup s;
    GError *err = NULL;
    if (!setup("cluster_scale: {value: 32, calibrated: x}\nstrip_split: 6\n",
               &s, &err))
        fail_msg("%s", err->message);
    assert_int_equal(s.frame.width, 1280);
    assert_int_equal(s.frame.height, 1024);
    assert_int_equal(s.frame.region, 128);
    assert_int_equal(s.frame.cmd_bytes, 20);
    assert_int_equal(s.frame.end_bytes, 4);
    assert_int_equal(s.frame.batch, 16);
    assert_int_equal(s.frame.pixel_bytes, 3);
    assert_int_equal(s.frame.element_bytes, 24);
    assert_true(s.cluster_scale == 32);
    assert_int_equal(s.strip_split, 6);
    assert_true(setup("cluster_scale: {value: 1, source: y}\n", &s, &err));
    assert_int_equal(s.strip_split, 0);
    assert_true(setup("cluster_scale: {value: 1, assumption: y}\n", &s, &err));
    setup_fails("", "frame.yaml:1:1: found no key 'cluster_scale' in this "
                    "map, expected cluster_scale: {value: <number>, "
                    "calibrated: <cells>}");
    setup_fails("cluster_scale: 32\n",
                "frame.yaml:9:16: found a bare cluster_scale, expected "
                "cluster_scale: {value: <number>, calibrated: <cells>}");
    setup_fails("cluster_scale: {value: 32}\n",
                "frame.yaml:9:16: found cluster_scale without a provenance, "
                "expected one of calibrated:, assumption: or source:");
    setup_fails("cluster_scale: {value: 0, source: y}\n",
                "frame.yaml:9:24: found '0', expected a number in [1e-06, "
                "1e+06]");
    setup_fails("cluster_scale: {value: 2, source: y}\nwidth2: 5\n",
                "frame.yaml:10:1: found unknown key 'width2', expected one "
                "of: width, height, region, cmd_bytes, end_bytes, batch, "
                "pixel_bytes, element_bytes, cluster_scale, strip_split");
    /* every size is a count of at least 1 */
    static const char *const sizes[][2] = {
        {"width: 1280", "1:8"},   {"height: 1024", "2:9"},
        {"region: 128", "3:9"},   {"cmd_bytes: 20", "4:12"},
        {"end_bytes: 4", "5:12"}, {"batch: 16", "6:8"},
        {"pixel_bytes: 3", "7:14"}, {"element_bytes: 24", "8:16"}};
    for (guint i = 0; i < G_N_ELEMENTS(sizes); i++) {
        GString *y = g_string_new(frame_keys);
        char *zero = g_strdup(sizes[i][0]);
        strcpy(strchr(zero, ':'), ": 0");
        g_string_replace(y, sizes[i][0], zero, 1);
        g_string_append(y, "cluster_scale: {value: 1, source: y}\n");
        CfgNode *root = cfg_load_string(y->str, "frame.yaml", &err);
        assert_non_null(root);
        assert_false(wl_pphigs_setup_from_cfg(root, &s, &err));
        char *want = g_strdup_printf("frame.yaml:%s: found '0', expected a "
                                     "count in [1, 16777216]", sizes[i][1]);
        assert_string_equal(err->message, want);
        g_clear_error(&err);
        g_free(want);
        g_free(zero);
        cfg_free(root);
        g_string_free(y, TRUE);
    }
    CfgNode *seq = cfg_load_string("[1]", "frame.yaml", &err);
    assert_false(wl_pphigs_setup_from_cfg(seq, &s, &err));
    assert_string_equal(err->message, "frame.yaml:1:1: found a non-map, "
                                      "expected a map of frame sizes");
    g_clear_error(&err);
    cfg_free(seq);
}

static void test_cluster_factor(void **state)
{
    (void)state;
    assert_true(wl_pphigs_cluster_factor(32, 8) == 4);
    assert_true(wl_pphigs_cluster_factor(32, 32) == 1);
    assert_true(wl_pphigs_cluster_factor(32, 64) == 1);
    assert_true(wl_pphigs_cluster_factor(12, 8) == 1.5);
}

static void test_metrics_idle_and_busy(void **state)
{
    (void)state;
    WlPphigsMetrics m;
    const double idle[3] = {0, 0, 0};
    wl_pphigs_metrics_from(0, idle, 3, &m);
    assert_true(m.sum == 0 && m.max == 0);
    assert_true(m.efficiency == 0 && m.utilisation == 0 && m.speedup == 0);
    const double busy[3] = {2, 4, 6};
    wl_pphigs_metrics_from(10, busy, 3, &m);
    assert_true(m.t1 == 10 && m.sum == 12 && m.max == 6);
    assert_true(m.efficiency == 10.0 / 12);
    assert_true(m.utilisation == 12.0 / 18);
    assert_true(m.speedup == 3 * (10.0 / 12) * (12.0 / 18));
    /* times under 1 us: the guards compare with 0, not 1 */
    const double small[2] = {0.25, 0.5};
    wl_pphigs_metrics_from(0.5, small, 2, &m);
    assert_true(m.efficiency == 0.5 / 0.75);
    assert_true(m.utilisation == 0.75);
    const double one[1] = {5};
    wl_pphigs_metrics_from(5, one, 1, &m);
    assert_true(m.efficiency == 1 && m.utilisation == 1 && m.speedup == 1);
}

/* A move takes its weight off the old GP: after every primitive of GP 1
 * moved to GP 0, GP 1 is the least loaded, so the next appended
 * primitive is dealt to it (simple dealing: always the least loaded). */
static void test_move_unloads_the_old_gp(void **state)
{
    (void)state;
    ScenePphigsSpec sp = {.kind = SCENE_PPHIGS_STATION, .seed = 5,
                          .polygons = 200, .attributes = 10, .verts = 4,
                          .size = 100, .fov_deg = 51};
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&sp, &db, NULL));
    const WlPphigsCosts c = {.poly = 600 * SIM_NS, .vertex = 100 * SIM_NS,
                             .color = 100 * SIM_NS, .matrix = 300 * SIM_NS,
                             .execute = 500 * SIM_NS};
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(&c, 1, &w);
    WlPphigsDist *d = wl_pphigs_dist_new(db.db, 4, WL_PPHIGS_SIMPLE, &w);
    const SceneDb *h = wl_pphigs_dist_host(d);
    guint moved = 0, prim = G_MAXUINT;
    for (guint i = 0; i < scene_db_len(h, 0); i++)
        if (wl_pphigs_dist_owner(d, 0, i) == 1) {
            assert_true(wl_pphigs_dist_move(d, 0, i, 0));
            assert_int_equal(wl_pphigs_dist_owner(d, 0, i), 0);
            moved++;
            prim = i;
        }
    assert_true(moved > 1 && prim != G_MAXUINT);
    /* moving to the owner itself is refused */
    assert_false(wl_pphigs_dist_move(d, 0, prim, 0));
    double load[4];
    wl_pphigs_dist_loads(d, load);
    assert_true(load[0] > 0 && load[2] > 0 && load[3] > 0);
    SceneElem e = *scene_db_elem(h, 0, prim);
    e.verts = g_memdup2(e.verts, e.nverts * sizeof *e.verts);
    GError *err = NULL;
    assert_true(wl_pphigs_dist_append(d, 0, &e, &err));
    g_free(e.verts);
    wl_pphigs_dist_finish(d);
    assert_int_equal(wl_pphigs_dist_owner(d, 0, scene_db_len(h, 0) - 1), 1);
    wl_pphigs_dist_free(d);
    scene_pphigs_db_clear(&db);
}

/* Pixels a whole-screen command of constant depth z wins in a fresh
 * 2 x 2 region (its box 3 x 3 from (-1, -1): clipped to the region). */
static uint64_t won_at(double z, uint64_t *key)
{
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, 2, 2, 0);
    WlPphigsCmd c = {.z = {0, 0, z}, .nedges = 0, .x0 = -1, .y0 = -1,
                     .x1 = 1, .y1 = 1, .rgba = 0xff00ff00u, .tag = 5};
    uint64_t won = wl_pphigs_region_draw(r, &c);
    *key = r->key[3];
    /* the same command again wins nothing: equal keys keep the first */
    assert_int_equal(wl_pphigs_region_draw(r, &c), 0);
    wl_pphigs_region_free(r);
    return won;
}

/* pixel_key: a pixel draws when its NDC z is in [-1, 1], both ends
 * included; its key is the depth (1 - z) / 2 scaled to 32 bits, above
 * the tag. */
static void test_depth_range_ends(void **state)
{
    (void)state;
    const double z[] = {-1.5, -1.0000001, -1, -0.5, 0, 0.5, 1, 1.0000001, 1.5};
    const uint64_t want[] = {0, 0, 4, 4, 4, 4, 4, 0, 0};
    for (guint i = 0; i < G_N_ELEMENTS(z); i++) {
        uint64_t key = 0, won = won_at(z[i], &key);
        if (won != want[i])
            fail_msg("z %.7f: %" G_GUINT64_FORMAT " pixels, expected %"
                     G_GUINT64_FORMAT, z[i], won, want[i]);
        uint64_t k = want[i] ? (uint64_t)llrint((1 - z[i]) / 2 *
                                                (double)UINT32_MAX)
                                       << 31 |
                                   5
                             : 0;
        assert_true(key == k);
    }
    /* nearer (smaller z) wins over farther */
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, 2, 2, 7);
    assert_int_equal(r->rgba[0], 7);
    WlPphigsCmd far = {.z = {0, 0, 0.5}, .x1 = 1, .y1 = 1, .rgba = 1};
    WlPphigsCmd near = far;
    near.z.c = -0.5;
    near.rgba = 2;
    assert_int_equal(wl_pphigs_region_draw(r, &near), 4);
    assert_int_equal(wl_pphigs_region_draw(r, &far), 0);
    assert_int_equal(r->rgba[3], 2);
    wl_pphigs_region_free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spec_fields),
        cmocka_unit_test(test_spec_load),
        cmocka_unit_test(test_setup),
        cmocka_unit_test(test_cluster_factor),
        cmocka_unit_test(test_metrics_idle_and_busy),
        cmocka_unit_test(test_move_unloads_the_old_gp),
        cmocka_unit_test(test_depth_range_ends),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
