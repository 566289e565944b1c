/* test_ellsworth90_claims.c — seed 001's worked examples and its one
 * million polygons per second as computed rows
 * (sim/reproduce/ellsworth90_claims.c) decide from the simulated figures
 * and can come out false: figures made so that each claim holds, then
 * each broken in turn (no idle GP, a GP without a strip, a traversal
 * below the goal), a missing figure gives NaN, not a verdict; the strip
 * count is 16 on the shipped mesh and falls on the same quads in another
 * order.  Run from the repository root (make test does). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/reproduce/ellsworth90.h"
#include "sim/scene/structdb_file.h"

static const RpEllClaims cl = {"cube.yaml", 8, 2, "simple", "mesh.yaml", 16,
                               1e6};

static void figure(GPtrArray *rows, const char *row, const char *col,
                   double v)
{
    g_ptr_array_add(rows, rp_row_new("claims", row, col, v, NULL));
}

/* Figures under which every claim holds but the frame one, then one
 * change (which, value). */
static GPtrArray *figures(int which, double v)
{
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    figure(rows, "cube", "gps_without_primitives", which == 0 ? v : 2);
    figure(rows, "mesh", "gps_with_one_strip", which == 1 ? v : 16);
    figure(rows, "million a 16 GPs", "gp_polygons_per_s",
           which == 2 ? v : 1.2e6);
    figure(rows, "million a 16 GPs", "frame_polygons_per_s", 3e5);
    figure(rows, "million b 16 GPs", "gp_polygons_per_s", 5e5);
    figure(rows, "million b 16 GPs", "frame_polygons_per_s", 2e5);
    rp_ellsworth90_claims(rows, &cl);
    return rows;
}

static double holds(const GPtrArray *rows, const char *id, const char **note)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        if (!strcmp(r->table, "claims") && !strcmp(r->row, id) &&
            !strcmp(r->column, "holds")) {
            if (note)
                *note = r->note;
            return r->sim;
        }
    }
    fail_msg("no holds row for %s", id);
    return NAN;
}

static void test_all_hold(void **st)
{
    (void)st;
    GPtrArray *rows = figures(-1, 0);
    const char *note = NULL;
    assert_true(holds(rows, "cube", NULL) == 1);
    assert_true(holds(rows, "mesh", NULL) == 1);
    assert_true(holds(rows, "million", &note) == 1);
    assert_non_null(strstr(note, "a 16 GPs")); /* names the configuration */
    assert_true(holds(rows, "million frame", &note) == 0);
    assert_non_null(strstr(note, "does not hold, because"));
    g_ptr_array_free(rows, TRUE);
}

static void test_each_can_fail(void **st)
{
    (void)st;
    static const char *const id[] = {"cube", "mesh", "million"};
    static const double bad[] = {0, 15, 9.9e5};
    for (int k = 0; k < 3; k++) {
        GPtrArray *rows = figures(k, bad[k]);
        const char *note = NULL;
        assert_true(holds(rows, id[k], &note) == 0);
        assert_non_null(strstr(note, "does not hold, because"));
        for (int j = 0; j < 3; j++)
            if (j != k)
                assert_true(holds(rows, id[j], NULL) == 1);
        g_ptr_array_free(rows, TRUE);
    }
    GPtrArray *rows = figures(0, NAN);
    assert_true(isnan(holds(rows, "cube", NULL)));
    g_ptr_array_free(rows, TRUE);
}

/* The shipped mesh gives every GP a strip; the same 256 quads shuffled
 * (a fixed seed; any order i -> a i + b keeps columns together) give
 * none a whole one. */
static void test_strips(void **st)
{
    (void)st;
    SceneDb *db = scene_db_load("configs/pphigs/mesh16.yaml", NULL);
    assert_non_null(db);
    assert_int_equal(rp_ellsworth90_strips(db, 16), 16);
    SceneDb *mix = scene_db_new();
    guint sid = scene_db_add_struct(mix, "mesh");
    guint order[256];
    for (guint i = 0; i < 256; i++)
        order[i] = i;
    GRand *rng = g_rand_new_with_seed(37);
    for (guint i = 255; i > 0; i--) {
        guint j = (guint)g_rand_int_range(rng, 0, (gint32)i + 1), t = order[i];
        order[i] = order[j], order[j] = t;
    }
    g_rand_free(rng);
    for (guint i = 0; i < 256; i++) {
        const SceneElem *e = scene_db_elem(db, 0, 1 + order[i]);
        assert_true(scene_db_append(mix, sid, e, NULL));
    }
    scene_db_post(mix, sid);
    assert_int_equal(rp_ellsworth90_strips(mix, 16), 0);
    scene_db_free(mix);
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_hold),
        cmocka_unit_test(test_each_can_fail),
        cmocka_unit_test(test_strips),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
