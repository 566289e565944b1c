/* test_sf_mutants.c — claims of the sort-first adaptive grid (sf_adapt.h)
 * that mutation testing (make mutate, docs/testing.md) found unchecked:
 * calibration sets each cell's factor to its owner's work per estimated
 * polygon, the mean of those for a region without polygons, and leaves
 * the factor at 1 when no region has any; sorted chunking's median
 * split. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

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

/* One posted structure of n triangles, the i-th with its right-angle
 * corner at c[i] and legs of 1 along x and y: centroid c[i] + (1/3,
 * 1/3, 0). */
static SceneDb *triangles_at(const Vec3 *c, guint n)
{
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    for (guint i = 0; i < n; i++) {
        Vec3 v[3] = {c[i], vec3_add(c[i], vec3(1, 0, 0)),
                     vec3_add(c[i], vec3(0, 1, 0))};
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(scene_db_append(db, root, &e, NULL));
    }
    scene_db_post(db, root);
    return db;
}

/* Sorted chunking splits at the median along the longest axis of the
 * centroids' box (sf_db.h): 16 triangles stacked along z, stored in a
 * scrambled order, make chunks of 4 consecutive depths. */
static void test_sorted_chunks_longest_axis(void **state)
{
    (void)state;
    Vec3 c[16];
    for (guint i = 0; i < 16; i++)
        c[i] = vec3(0, 0, (7 * i) % 16);
    SceneDb *db = triangles_at(c, 16);
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

/* Sorted chunking with granularity 2 splits 5 primitives into
 * ceil(ceil(5/2) / 2) x 2 = 4 and 1 (sf_db.c split_sorted), then splits
 * the 4 along their own longest axis.  Centroids (x, y) of primitives
 * 0..4: (0, 0) (1, 3.5) (2, 0.2) (3, 3.4) (4, 1): x is the longest axis
 * of all five (4 > 3.5), y of the first four (3.5 > 3), so the chunks
 * are {0, 2} {3, 1} (by y) {4}.  A split of 2 and 3 would give {0, 1}
 * {2, 4} {3} instead. */
static void test_sorted_split_sizes(void **state)
{
    (void)state;
    static const double at[5][2] = {{0, 0}, {1, 3.5}, {2, 0.2}, {3, 3.4},
                                    {4, 1}};
    Vec3 c[5];
    for (guint i = 0; i < 5; i++)
        c[i] = vec3(at[i][0] - 1.0 / 3, at[i][1] - 1.0 / 3, 0);
    SceneDb *db = triangles_at(c, 5);
    GError *err = NULL;
    WlSfDb *d = wl_sf_db_new(db, 1, 2, WL_SF_CHUNK_SORTED, &err);
    assert_non_null(d);
    assert_int_equal(wl_sf_n_chunks(d), 3);
    static const guint sizes[3] = {2, 2, 1}, order[5] = {0, 2, 3, 1, 4};
    for (guint c = 0; c < 3; c++)
        assert_int_equal(wl_sf_chunk(d, c)->n_prims, sizes[c]);
    assert_int_equal(d->prims->len, 5);
    for (guint i = 0; i < 5; i++)
        assert_int_equal(g_array_index(d->prims, guint, i), order[i]);
    wl_sf_db_free(d);
    scene_db_free(db);
}

/* One posted structure of triangles whose centroids are exactly c[i]:
 * corners (x - 1, y - 1), (x + 1, y - 1), (x, y + 2) at z, so the sum of
 * the corners is 3 c[i] and equal coordinates give equal centroids. */
static SceneDb *centroids_at(const Vec3 *c, guint n)
{
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    for (guint i = 0; i < n; i++) {
        Vec3 v[3] = {vec3(c[i].x - 1, c[i].y - 1, c[i].z),
                     vec3(c[i].x + 1, c[i].y - 1, c[i].z),
                     vec3(c[i].x, c[i].y + 2, c[i].z)};
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(scene_db_append(db, root, &e, NULL));
    }
    scene_db_post(db, root);
    return db;
}

/* Sorted chunking of 4 primitives in chunks of 2: the element positions
 * of the chunks, in order. */
static void sorted_order(const Vec3 *c, guint out[4])
{
    SceneDb *db = centroids_at(c, 4);
    WlSfDb *d = wl_sf_db_new(db, 1, 2, WL_SF_CHUNK_SORTED, NULL);
    assert_non_null(d);
    assert_int_equal(wl_sf_n_chunks(d), 2);
    assert_int_equal(d->prims->len, 4);
    for (guint i = 0; i < 4; i++)
        out[i] = g_array_index(d->prims, guint, i);
    wl_sf_db_free(d);
    scene_db_free(db);
}

/* The longest axis on ties (sf_db.c longest_axis): x before y before z.
 * Centroid coordinates a = {0, 3, 1, 2} and b = {0, 1, 3, 2} (extent 3
 * each) on two axes, 0 on the third: sorted along a the order is 0 2 3 1,
 * along b 0 1 3 2. */
static void test_sorted_axis_ties(void **state)
{
    (void)state;
    static const double a[4] = {0, 3, 1, 2}, b[4] = {0, 1, 3, 2};
    static const guint along_a[4] = {0, 2, 3, 1};
    Vec3 xy[4], xz[4], yz[4];
    for (guint i = 0; i < 4; i++) {
        xy[i] = vec3(a[i], b[i], 0);
        xz[i] = vec3(a[i], 0, b[i]);
        yz[i] = vec3(0, a[i], b[i]);
    }
    guint got[4];
    sorted_order(xy, got); /* x, not y */
    assert_memory_equal(got, along_a, sizeof got);
    sorted_order(xz, got); /* x, not z */
    assert_memory_equal(got, along_a, sizeof got);
    sorted_order(yz, got); /* y, not z */
    assert_memory_equal(got, along_a, sizeof got);
}

/* Equal centroids along the sorting axis keep their file order
 * (cmp_prim breaks ties by position): x = {1, 0, 0, 1} with y and z
 * spread less gives chunks {1, 2} {0, 3}, each in file order. */
static void test_sorted_ties_file_order(void **state)
{
    (void)state;
    Vec3 c[4] = {vec3(1, 0.5, 0), vec3(0, 0.25, 0), vec3(0, 0, 0),
                 vec3(1, 0.75, 0)};
    static const guint want[4] = {1, 2, 0, 3};
    guint got[4];
    sorted_order(c, got);
    assert_memory_equal(got, want, sizeof got);
}

/* The partial sort's octree is 21 levels deep (WL_SF_OCTREE_MAX_DEPTH):
 * in the unit box, c = 1 - 1.5 x 2^-21 and b = 1 share every cell down to
 * side 2^-20 and are told apart by the 21st split (c in the lower half),
 * so c comes first; one level fewer would keep file order (b first). */
static void test_octree_last_level(void **state)
{
    (void)state;
    Vec3 p[3] = {vec3(0, 0, 0), vec3(1, 0, 0),
                 vec3(1 - 1.5 * ldexp(1, -21), 0, 0)};
    guint order[3], want[3] = {0, 2, 1};
    wl_sf_octree_order(p, 3, order);
    assert_memory_equal(order, want, sizeof order);
}

/* A point on the centre plane of y, or of z, goes to the upper half, as
 * on x (test_sf_db.c): p (on the plane) after s = (0.4, 0.4, 0.4) and the
 * origin, whose octant 0 it would otherwise join (between them, since
 * its octant there would be below s's 7). */
static void test_octant_centre_planes(void **state)
{
    (void)state;
    for (int axis = 0; axis < 3; axis++) {
        Vec3 p[4] = {vec3(axis == 0 ? 0.5 : 0, axis == 1 ? 0.5 : 0,
                          axis == 2 ? 0.5 : 0),
                     vec3(0.4, 0.4, 0.4), vec3(1, 1, 1), vec3(0, 0, 0)};
        guint order[4], want[4] = {3, 1, 0, 2};
        wl_sf_octree_order(p, 4, order);
        assert_memory_equal(order, want, sizeof order);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_calibrate),
        cmocka_unit_test(test_regions_grid),
        cmocka_unit_test(test_sorted_chunks_longest_axis),
        cmocka_unit_test(test_sorted_split_sizes),
        cmocka_unit_test(test_sorted_axis_ties),
        cmocka_unit_test(test_sorted_ties_file_order),
        cmocka_unit_test(test_octree_last_level),
        cmocka_unit_test(test_octant_centre_planes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
