/* test_pphigs_metrics.c — seed 001's metrics on generated databases:
 * one GP is the serial traversal; the speed-up identity; the complex
 * algorithm beats the simple one where attributes are dense; the table
 * rows of the reproduction.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/reproduce/reproduce.h"
#include "sim/reproduce/ellsworth90.h"

/* Test costs: a 4-vertex polygon 1 us on-screen, 0.3 us rejected. */
static const WlPphigsCosts C = {.poly = 600 * SIM_NS,
                                .vertex = 100 * SIM_NS,
                                .reject_vertex = 75 * SIM_NS,
                                .color = 100 * SIM_NS,
                                .matrix = 300 * SIM_NS,
                                .concat = SIM_US,
                                .execute = 500 * SIM_NS};

static ScenePphigsSpec flock(void)
{
    ScenePphigsSpec s = {.kind = SCENE_PPHIGS_FLOCK,
                         .seed = 9,
                         .verts = 4,
                         .size = 10,
                         .boids = 30,
                         .boid_polygons = 5,
                         .boid_colors = 4,
                         .well_structs = 10,
                         .well_polygons = 60,
                         .well_attributes = 5};
    return s;
}

static void test_one_gp_is_serial(void **st)
{
    (void)st;
    ScenePphigsSpec s = flock();
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    WlPphigsMetrics a, b;
    wl_pphigs_run_db_analytic(&db, 1, &C, 8, &a, &b);
    assert_true(fabs(a.efficiency - 1) < 1e-12);
    assert_true(fabs(b.efficiency - 1) < 1e-12);
    assert_true(fabs(b.utilisation - 1) < 1e-12);
    wl_pphigs_run_db_analytic(&db, 4, &C, 8, &a, &b);
    assert_true(fabs(b.speedup - b.t1 / b.max) < 1e-9);
    assert_true(a.efficiency < 0.9); /* attributes copied to every GP */
    assert_true(b.efficiency > a.efficiency + 0.1);
    scene_pphigs_db_clear(&db);
}

static void test_offscreen_is_cheaper(void **st)
{
    (void)st;
    ScenePphigsSpec s = {.kind = SCENE_PPHIGS_LOBBY,
                         .seed = 2,
                         .polygons = 400,
                         .attributes = 50,
                         .verts = 4,
                         .size = 100,
                         .fov_deg = 51};
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    Mat4 vp = scene_camera_view_proj(&db.camera);
    WlPphigsCosts full = C; /* rejected costs as much as on-screen */
    full.reject_vertex = (C.poly + 4 * C.vertex) / 4;
    SimTime t = wl_pphigs_traversal_cost(db.db, vp, &C);
    SimTime tf = wl_pphigs_traversal_cost(db.db, vp, &full);
    double off = scene_pphigs_offscreen_share(db.db, vp);
    assert_true(off > 0.3 && off < 0.8);
    uint64_t n_off = (uint64_t)llround(400 * off);
    assert_int_equal(tf - t,
                     n_off * (C.poly + 4 * C.vertex - 4 * C.reject_vertex));
    scene_pphigs_db_clear(&db);
}

static void test_table_rows(void **st)
{
    (void)st;
    ScenePphigsSpec s[2] = {flock(), flock()};
    s[1].kind = SCENE_PPHIGS_HUMANS;
    s[1].figures = 2, s[1].structures = 20, s[1].polygons = 200;
    s[1].levels = 5;
    WlPphigsRig rig = {"pixel-planes-5", "analytic", {{0}, 64, 0}};
    const guint gps[] = {4, 16};
    rig.setup.frame = (WlPphigsFrameSpec){100, 16, 16, 4, 640, 512, 128, 80};
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    assert_true(rp_ellsworth90_table1(s, 2, gps, 2, &rig, rows, NULL));
    assert_int_equal(rows->len, 2 * (8 + 6 + 5)); /* + by-structure */
    guint table1 = 0;
    for (guint i = 0; i < rows->len; i++) {
        RpRow *r = g_ptr_array_index(rows, i);
        if (g_strcmp0(r->table, "1") == 0)
            table1++;
        if (g_strcmp0(r->column, "depth") == 0)
            assert_true(r->sim == (i < 19 ? 2 : 5));
    }
    assert_int_equal(table1, 28);
    g_ptr_array_unref(rows);
    s[1].levels = 50; /* cannot be met */
    GError *err = NULL;
    rows = g_ptr_array_new_with_free_func(rp_row_free);
    assert_false(rp_ellsworth90_table1(s, 2, gps, 2, &rig, rows, &err));
    assert_non_null(err);
    g_clear_error(&err);
    g_ptr_array_unref(rows);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_gp_is_serial),
        cmocka_unit_test(test_offscreen_is_cheaper),
        cmocka_unit_test(test_table_rows),
    };
    return cmocka_run_group_tests_name("pphigs_metrics", tests, NULL, NULL);
}
