/* test_pphigs_ties.c — the PPHIGS workload at its exact edges (issue 21,
 * seed-7 survivors): a polygon whose screen area2 is exactly the
 * degeneracy bound 1e-12 draws nothing while one a rounding step larger
 * draws; an edit finds its element when the list holds exactly one
 * candidate; an element appended at the attribute cache's front is
 * walked by the next scan that needs it; a run on all 64 GPs reports
 * per-GP traffic.  Run from the repository root (make test does).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <math.h>
#include <unistd.h>

#include "sim/run/run.h"
#include "sim/workload/pphigs/pphigs_distrib.h"
#include "sim/workload/pphigs/pphigs_pixels.h"
#include "sim/workload/pphigs/pphigs_rebalance.h"

/* Commands of the triangle v (object = clip space, w = 1) on a 2 x 2
 * screen: screen x = v.x + 1 and y = 1 - v.y, both exact here. */
static guint cmds_of(const Vec3 *v)
{
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 3);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1), .depth = 1};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    guint n = wl_pphigs_cmds(&pi, mat4_identity(), 2, 2, out);
    assert_int_equal(n, out->len);
    g_array_free(out, TRUE);
    return n;
}

/* Screen points (0, 0.5), (X, 0.5), (0, 0.5 + 2^-40): area2 = X 2^-40,
 * exactly the double 1e-12 for X = 1e-12 2^40 (in [1, 2), so X - 1 and
 * back are exact).  The box covers pixel (0, 0)'s centre either way. */
static void test_area_bound_exact(void **st)
{
    (void)st;
    double eps = ldexp(1, -40), x = ldexp(1e-12, 40);
    assert_true(x * eps == 1e-12);
    Vec3 at[3] = {vec3(-1, 0.5, 0), vec3(x - 1, 0.5, 0),
                  vec3(-1, 0.5 - eps, 0)};
    assert_int_equal(cmds_of(at), 0); /* |d| > 1e-12 fails: degenerate */
    double up = nextafter(x, 2);
    Vec3 above[3] = {vec3(-1, 0.5, 0), vec3(up - 1, 0.5, 0),
                     vec3(-1, 0.5 - eps, 0)};
    assert_int_equal(cmds_of(above), 1);
}

/* ---- through the workload --------------------------------------------- */

static const char *const ONE_TRIANGLE =
    "structure_database: 1\n"
    "structures:\n"
    "  - name: root\n"
    "    elements:\n"
    "      - matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n"
    "      - triangle: [[-1, -1, 0], [1, -1, 0], [0, 1, 0]]\n"
    "posted: [root]\n";

static char *db_file(void)
{
    char *path = NULL;
    int fd = g_file_open_tmp("pphigs-ties-XXXXXX.yaml", &path, NULL);
    assert_true(fd >= 0);
    close(fd);
    assert_true(g_file_set_contents(path, ONE_TRIANGLE, -1, NULL));
    return path;
}

/* A run of the one-triangle file: run.frames, edits_per_frame and
 * fidelity as given, then the settings `more` (NULL-terminated). */
static SimResult *run_with(const char *path, const char *frames,
                           const char *edits, const char *const *more)
{
    char *db = g_strdup_printf("workload.database=%s", path);
    const char *sets[8] = {frames, edits, "run.fidelity=analytic", db};
    for (guint i = 0; more && more[i]; i++) {
        g_assert(i < 3);
        sets[4 + i] = more[i];
    }
    GError *err = NULL;
    CfgRun *r = cfg_run_load("configs/pphigs-flock.yaml", sets, &err);
    if (!r)
        fail_msg("%s", err->message);
    SimResult *res = cfg_run_exec(r, NULL, &err);
    if (!res)
        fail_msg("%s", err->message);
    cfg_run_free(r);
    g_free(db);
    return res;
}

static double metric(const SimResult *r, const char *name)
{
    double v = -1;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}

/* One triangle: frame 1 appends a copy (the one candidate picked), then
 * deletes both; frame 2 finds no primitive for any edit. */
static void test_single_candidate(void **st)
{
    (void)st;
    char *path = db_file();
    const char *ed[] = {"workload.edits={append: 1, delete: 2}", NULL};
    SimResult *r = run_with(path, "run.frames=2", "workload.edits_per_frame=0",
                            ed);
    assert_true(metric(r, "edits_append") == 1);
    assert_true(metric(r, "edits_delete") == 2);
    assert_true(metric(r, "image_matches_serial") == 1);
    sim_result_free(r);
    g_unlink(path);
    g_free(path);
}

/* All 64 GPs (the traffic arrays' size): the run completes with every
 * frame equal to the serial render. */
static void test_all_gps(void **st)
{
    (void)st;
    char *path = db_file();
    const char *gps[] = {"workload.gps=64", NULL};
    SimResult *r = run_with(path, "run.frames=2", "workload.edits_per_frame=0",
                            gps);
    assert_true(metric(r, "gps") == 64);
    assert_true(metric(r, "image_matches_serial") == 1);
    sim_result_free(r);
    g_unlink(path);
    g_free(path);
}

/* A modify turns its matrix about y by edit_angle_deg (§3.1), before the
 * frame draws: the triangle in the z = 0 plane, turned by 90 degrees, is
 * seen edge-on and draws no command; unturned it draws. */
static void test_modify_turns_about_y(void **st)
{
    (void)st;
    char *path = db_file();
    static const char *const angle[] = {"workload.edit_angle_deg=90",
                                        "workload.edit_angle_deg=0"};
    for (guint i = 0; i < 2; i++) {
        const char *more[] = {angle[i], NULL};
        SimResult *r = run_with(path, "run.frames=1",
                                "workload.edits_per_frame=1", more);
        assert_true(metric(r, "edits") == 1);
        if (i == 0)
            assert_true(metric(r, "commands_per_frame") == 0);
        else
            assert_true(metric(r, "commands_per_frame") > 0);
        sim_result_free(r);
    }
    g_unlink(path);
    g_free(path);
}

/* ---- the attribute cache's front --------------------------------------- */

static const WlPphigsWeights W = {
    .w = {[SCENE_EL_TRIANGLE] = 1, [SCENE_EL_COLOR] = 0.1},
    .cluster = 2,
    .attr_cache = 2,
};

/* colour, 10 triangles: the cache is built to the end (front at 11). */
static SceneDb *colour_db(void)
{
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "s");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (guint i = 0; i < 11; i++) {
        SceneElem e = i == 0 ? scene_elem_color(vec3(1, 0, 0))
                             : scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(scene_db_append(db, s, &e, NULL));
    }
    scene_db_post(db, s);
    return db;
}

/* A triangle appended at the front's position (11) is not yet walked;
 * the next append's scan (from 12) walks exactly it: cache_walk + 1.
 * Deleting an element at the front (after a truncation left it there)
 * is the same: the front does not move. */
static void test_cache_front_append(void **st)
{
    (void)st;
    SceneDb *db = colour_db();
    WlPphigsDist *d = wl_pphigs_dist_new(db, 4, WL_PPHIGS_COMPLEX, &W);
    uint64_t w0 = wl_pphigs_dist_traffic(d)->cache_walk;
    assert_int_equal(w0, 11);
    Vec3 v[3] = {vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    assert_true(wl_pphigs_dist_append(d, 0, &e, NULL));
    assert_int_equal(wl_pphigs_dist_traffic(d)->cache_walk, w0);
    assert_true(wl_pphigs_dist_append(d, 0, &e, NULL));
    assert_int_equal(wl_pphigs_dist_traffic(d)->cache_walk, w0 + 1);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* ---- the rebalancer's budget at a tie ---------------------------------- */

/* §5.1 on 2 GPs: 8 triangles of nominal weight 1, all on GP 0, measured
 * 8 us and 0 us: budget = fraction (max - mean) = 0.5 (8 - 4) = 2, so
 * moving stops once exactly 2 have moved (moved < budget fails at the
 * tie): 2 moves, not 3. */
static void test_imperfect_budget_tie(void **st)
{
    (void)st;
    SceneDb *db = colour_db();
    WlPphigsWeights w = W;
    w.w[SCENE_EL_COLOR] = 0; /* on every GP: no load */
    w.attr_cache = 0;
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
    for (guint i = 1; i < 9; i++)
        if (wl_pphigs_dist_owner(d, 0, i) != 0)
            assert_true(wl_pphigs_dist_move(d, 0, i, 0));
    for (guint i = 9; i < 11; i++) /* the last two go: 8 stay */
        wl_pphigs_dist_delete(d, 0, 9);
    wl_pphigs_dist_finish(d);
    double load[2];
    wl_pphigs_dist_loads(d, load);
    assert_true(load[0] == 8 && load[1] == 0);
    WlPphigsRebalParams p = {.threshold = 0.1, .frames = 1, .fraction = 0.5,
                             .max_moves = 16, .seed = 3};
    WlPphigsRebal *rb = wl_pphigs_rebal_new(&p);
    WlPphigsCosts c = {.poly = SIM_US};
    const double us[2] = {8, 0};
    WlPphigsRebalStep out;
    wl_pphigs_rebal_frame(rb, d, mat4_identity(), &c, us, &out);
    assert_int_equal(out.cause, WL_PPHIGS_REBAL_IMPERFECT);
    assert_int_equal(out.moves, 2);
    wl_pphigs_dist_loads(d, load);
    assert_true(load[0] == 6 && load[1] == 2);
    wl_pphigs_rebal_free(rb);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* The one command of triangle v (clip = object space) coloured col on a
 * 100 x 80 screen. */
static uint32_t rgba_of_tri(const Vec3 *v, Vec3 col)
{
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 3);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(), .color = col,
                        .depth = 1};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 100, 80, out), 1);
    uint32_t rgba = g_array_index(out, WlPphigsCmd, 0).rgba;
    g_array_free(out, TRUE);
    return rgba;
}

/* Shading of a small tilted triangle (its NDC normal shorter than 1) is
 * the same 0.3 + 0.7 |n_z| / |n| as a large one's; channels clamp to
 * [0, 1] (a negative one to 0, one above 1 to 255). */
static void test_shading_edges(void **st)
{
    (void)st;
    /* u = (0.5, 0, 0), v = (0.25, 0.5, 0.25): n = (0, -0.125, 0.25) */
    Vec3 small[3] = {vec3(-0.25, -0.25, 0), vec3(0.25, -0.25, 0),
                     vec3(0, 0.25, 0.25)};
    double s = 0.3 + 0.7 / sqrt(1.25);
    uint32_t want = 0xff000000u | (uint32_t)lrint(255 * s) |
                    (uint32_t)lrint(255 * 0.5 * s) << 8;
    assert_int_equal(rgba_of_tri(small, vec3(1, 0.5, 0)), want);
    Vec3 flat[3] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0, 0.5, 0)};
    assert_int_equal(rgba_of_tri(flat, vec3(-0.5, 2, 0.25)),
                     0xff000000u | 255u << 8 | (uint32_t)lrint(63.75) << 16);
}

/* Two posted structures, each a colour and 10 triangles; an insert into
 * the first: finishing scans back once, in the edited structure only
 * (the other has no edited region), so all the scanning done is that
 * one scan. */
static void test_finish_scans_edited_only(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (guint t = 0; t < 2; t++) {
        guint s = scene_db_add_struct(db, t ? "b" : "a");
        for (guint i = 0; i < 11; i++) {
            SceneElem e = i == 0 ? scene_elem_color(vec3(1, 0, 0))
                                 : scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
            assert_true(scene_db_append(db, s, &e, NULL));
        }
        scene_db_post(db, s);
    }
    WlPphigsWeights w = W;
    w.attr_cache = 0;
    WlPphigsDist *d = wl_pphigs_dist_new(db, 4, WL_PPHIGS_COMPLEX, &w);
    uint64_t before = wl_pphigs_dist_traffic(d)->total_scan;
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    assert_true(wl_pphigs_dist_insert(d, 0, 6, &e, NULL));
    wl_pphigs_dist_finish(d);
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(d);
    assert_true(t->last_scan > 0);
    assert_int_equal(t->total_scan - before, t->last_scan);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* A modify that makes a dealt polygon heavier (more vertices, w_vertex
 * 1; by 1 or by 3) adds the difference to its GP's load: of two GPs with one triangle
 * each, the one whose triangle became a hexagon is no longer the least
 * loaded, so the next polygon goes to the other (GP 0 would win the
 * tie of equal loads). */
static void test_modify_moves_load(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "s");
    Vec3 v[6] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(2, 1, 0),
                 vec3(1, 2, 0), vec3(0, 2, 0), vec3(-1, 1, 0)};
    SceneElem col = scene_elem_color(vec3(1, 0, 0));
    assert_true(scene_db_append(db, s, &col, NULL));
    for (guint i = 0; i < 2; i++) {
        SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 3);
        assert_true(scene_db_append(db, s, &e, NULL));
    }
    scene_db_post(db, s);
    WlPphigsWeights w = {.w = {[SCENE_EL_POLYGON] = 1}, .w_vertex = 1,
                         .cluster = 0};
    for (guint nv = 4; nv <= 6; nv += 2) { /* heavier by 1 and by 3 */
        WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
        guint on0 = wl_pphigs_dist_owner(d, s, 1) == 0 ? 1 : 2;
        assert_int_equal(wl_pphigs_dist_owner(d, s, on0), 0);
        assert_int_equal(wl_pphigs_dist_owner(d, s, 3 - on0), 1);
        SceneElem hex = scene_elem_prim(SCENE_EL_POLYGON, v, nv);
        assert_true(wl_pphigs_dist_modify(d, s, on0, &hex, NULL));
        SceneElem tri = scene_elem_prim(SCENE_EL_POLYGON, v, 3);
        assert_true(wl_pphigs_dist_insert(d, s, 3, &tri, NULL));
        wl_pphigs_dist_finish(d);
        assert_int_equal(wl_pphigs_dist_owner(d, s, 3), 1);
        wl_pphigs_dist_free(d);
    }
    scene_db_free(db);
}

/* The other signs: of two GPs with one quad each (loads 5, 5; w_vertex
 * 1), the one whose quad became a triangle (lighter by 1) is the least
 * loaded and takes the next polygon; a modified colour (not dealt)
 * moves no load, so the next polygon goes by the tie to GP 0. */
static void test_modify_lighter_and_colour(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "s");
    Vec3 v[4] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(0, 1, 0)};
    SceneElem col = scene_elem_color(vec3(1, 0, 0));
    assert_true(scene_db_append(db, s, &col, NULL));
    for (guint i = 0; i < 2; i++) {
        SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 4);
        assert_true(scene_db_append(db, s, &e, NULL));
    }
    scene_db_post(db, s);
    WlPphigsWeights w = {.w = {[SCENE_EL_POLYGON] = 1}, .w_vertex = 1,
                         .cluster = 0};
    for (int colour = 0; colour < 2; colour++) {
        WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
        guint on1 = wl_pphigs_dist_owner(d, s, 1) == 1 ? 1 : 2;
        assert_int_equal(wl_pphigs_dist_owner(d, s, on1), 1);
        SceneElem tri = scene_elem_prim(SCENE_EL_POLYGON, v, 3);
        SceneElem blue = scene_elem_color(vec3(0, 0, 1));
        assert_true(wl_pphigs_dist_modify(d, s, colour ? 0 : on1,
                                          colour ? &blue : &tri, NULL));
        assert_true(wl_pphigs_dist_insert(d, s, 3, &tri, NULL));
        wl_pphigs_dist_finish(d);
        assert_int_equal(wl_pphigs_dist_owner(d, s, 3), colour ? 0 : 1);
        wl_pphigs_dist_free(d);
    }
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_area_bound_exact),
        cmocka_unit_test(test_shading_edges),
        cmocka_unit_test(test_single_candidate),
        cmocka_unit_test(test_all_gps),
        cmocka_unit_test(test_modify_turns_about_y),
        cmocka_unit_test(test_cache_front_append),
        cmocka_unit_test(test_imperfect_budget_tie),
        cmocka_unit_test(test_finish_scans_edited_only),
        cmocka_unit_test(test_modify_moves_load),
        cmocka_unit_test(test_modify_lighter_and_colour),
    };
    return cmocka_run_group_tests_name("pphigs_ties", tests, NULL, NULL);
}
