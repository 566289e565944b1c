/* test_sf_mutants.c — claims of the sort-first adaptive grid (sf_adapt.h)
 * that mutation testing (make mutate, docs/testing.md) found unchecked:
 * calibration sets each cell's factor to its owner's work per estimated
 * polygon, the mean of those for a region without polygons, and leaves
 * the factor at 1 when no region has any. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/sortfirst/sf_adapt.h"
#include "sim/workload/sortfirst/sf_db.h"

static void test_calibrate(void **state)
{
    (void)state;
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 64, 64);
    WlSfAdapt *a = wl_sf_adapt_new(8, 2);
    double work[2] = {50, 7};
    wl_sf_adapt_calibrate(a, &r, work); /* no polygons anywhere */
    for (guint i = 0; i < 64; i++)
        assert_true(a->factor[i] == 1);
    /* 10 polygons in region 0's first cell: 50 / 10 = 5 there; region 1
     * has none and takes the mean over regions with polygons, 5 */
    a->weight[0] = 10;
    assert_int_equal(wl_sf_adapt_weight_in(a, &r, r.rect[0]), 10);
    assert_int_equal(wl_sf_adapt_weight_in(a, &r, r.rect[1]), 0);
    wl_sf_adapt_calibrate(a, &r, work);
    for (guint i = 0; i < 64; i++)
        assert_true(a->factor[i] == 5);
    wl_sf_adapt_free(a);
}

/* The static regions are the squarest grid: cols the least divisor of P
 * that is at least sqrt(P), so a square P gets sqrt(P) x sqrt(P). */
static void test_regions_grid(void **state)
{
    (void)state;
    static const guint cases[][3] = {{1, 1, 1}, {4, 2, 2},  {8, 4, 2},
                                     {9, 3, 3}, {16, 4, 4}, {12, 4, 3},
                                     {7, 7, 1}, {64, 8, 8}};
    for (size_t i = 0; i < G_N_ELEMENTS(cases); i++) {
        WlSfRegions r;
        wl_sf_regions_init(&r, cases[i][0], 256, 256);
        if (r.cols != cases[i][1] || r.rows != cases[i][2])
            fail_msg("P = %u: %u x %u, expected %u x %u", cases[i][0], r.cols,
                     r.rows, cases[i][1], cases[i][2]);
    }
}

/* Sorted chunking splits at the median along the longest axis of the
 * centroids' box (sf_db.h): 16 triangles stacked along z, stored in a
 * scrambled order, make chunks of 4 consecutive depths. */
static void test_sorted_chunks_longest_axis(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    for (guint i = 0; i < 16; i++) {
        double z = (7 * i) % 16;
        Vec3 v[3] = {vec3(0, 0, z), vec3(1, 0, z), vec3(0, 1, z)};
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(scene_db_append(db, root, &e, NULL));
    }
    scene_db_post(db, root);
    GError *err = NULL;
    WlSfDb *d = wl_sf_db_new(db, 4, 4, WL_SF_CHUNK_SORTED, &err);
    assert_non_null(d);
    assert_int_equal(wl_sf_n_chunks(d), 4);
    for (guint c = 0; c < 4; c++) {
        SceneBox b = wl_sf_chunk(d, c)->box;
        assert_true(b.max.z - b.min.z == 3);
    }
    wl_sf_db_free(d);
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_calibrate),
        cmocka_unit_test(test_regions_grid),
        cmocka_unit_test(test_sorted_chunks_longest_axis),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
