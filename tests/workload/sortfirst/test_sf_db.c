/* test_sf_db.c — the partial sort of seed 000 §4.1 (sf_db.h) by its
 * properties: wl_sf_octree_order is a permutation; it is the depth-first
 * order of an octree over the points' bounding cube (at every level the
 * points of a cell are contiguous, cells in octant order); the octree is
 * adaptive (two points 10^-5 apart in a unit box are still told apart),
 * a point on a centre plane is in the upper half, and coincident points
 * keep their file order.  On a long strip of
 * triangles written row by row along its length, as a modelling tool
 * writes it, partially sorted chunks hold every primitive once and have
 * smaller boxes (mean sum of extents) than unsorted ones at 5, 12 and
 * 26 primitives a chunk. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/workload/sortfirst/sf_db.h"

static Vec3 *random_points(guint n, GRand *g)
{
    Vec3 *p = g_new(Vec3, n);
    for (guint i = 0; i < n; i++) /* a box 4 x 1 x 0.5 at (-1, 2, 3) */
        p[i] = vec3(-1 + 4 * g_rand_double(g), 2 + g_rand_double(g),
                    3 + 0.5 * g_rand_double(g));
    return p;
}

static void assert_permutation(const guint *order, guint n)
{
    gboolean *seen = g_new0(gboolean, n ? n : 1);
    for (guint i = 0; i < n; i++) {
        assert_true(order[i] < n);
        assert_false(seen[order[i]]);
        seen[order[i]] = TRUE;
    }
    g_free(seen);
}

/* Morton code of the level-`level` cell of p in the cube at lo, side s
 * (bit interleave: x lowest, as the octant numbering). */
static uint64_t cell_code(Vec3 p, Vec3 lo, double s, guint level)
{
    double t[3] = {(p.x - lo.x) / s, (p.y - lo.y) / s, (p.z - lo.z) / s};
    guint side = 1u << level;
    uint64_t q[3], code = 0;
    for (int a = 0; a < 3; a++)
        q[a] = MIN((guint)(t[a] * side), side - 1);
    for (int l = (int)level - 1; l >= 0; l--)
        for (int a = 2; a >= 0; a--)
            code = code << 1 | ((q[a] >> l) & 1);
    return code;
}

/* At every level the cells' codes never decrease along the order: each
 * cell's points are contiguous and cells come in octant order. */
static void test_depth_first_over_cube(void **state)
{
    (void)state;
    GRand *g = g_rand_new_with_seed(7);
    guint n = 2000, *order = g_new(guint, n);
    Vec3 *p = random_points(n, g);
    wl_sf_octree_order(p, n, order);
    assert_permutation(order, n);
    SceneBox box = scene_box_empty();
    for (guint i = 0; i < n; i++)
        box = scene_box_add_point(box, p[i]);
    double side = scene_box_size(box).x; /* the longest: a cube's side */
    gboolean moved = FALSE;
    for (guint level = 1; level <= 6; level++)
        for (guint i = 1; i < n; i++) {
            assert_true(cell_code(p[order[i - 1]], box.min, side, level) <=
                        cell_code(p[order[i]], box.min, side, level));
            moved |= order[i] < order[i - 1];
        }
    assert_true(moved);
    g_free(p);
    g_free(order);
    g_rand_free(g);
}

/* Subdivision goes as deep as the points need: b and c, 10^-5 apart near
 * the box's upper x end, are split at depth 17 and come in octant order
 * (c before b), not file order; a depth-3 grid would keep them in one
 * cell.  A point on a cell's centre plane goes to the upper half. */
static void test_adaptive_depth(void **state)
{
    (void)state;
    Vec3 p[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1 - 1e-5, 0, 0)};
    guint order[3];
    wl_sf_octree_order(p, 3, order);
    assert_int_equal(order[0], 0);
    assert_int_equal(order[1], 2);
    assert_int_equal(order[2], 1);
    /* a centroid on a centre plane is in the upper half: p (x = 0.5) in
     * octant 1 after s and q in octant 0; in the lower half p would join
     * them and come between s (octant 0) and q (octant 3) a level down */
    Vec3 b[4] = {vec3(0.5, 0, 0), vec3(0.4, 0.4, 0), vec3(1, 1, 1),
                 vec3(0, 0, 0)};
    guint ob[4], expect[4] = {3, 1, 0, 2};
    wl_sf_octree_order(b, 4, ob);
    assert_memory_equal(ob, expect, sizeof ob);
}

/* Coincident points stay in file order (leaves at the depth limit), and
 * the empty, single and all-equal cases are the identity. */
static void test_coincident_file_order(void **state)
{
    (void)state;
    Vec3 a = vec3(1, 1, 1), b = vec3(0, 0, 0), c = vec3(1, 0, 1);
    Vec3 p[7] = {a, b, a, c, b, a, c};
    guint order[7], expect[7] = {1, 4, 3, 6, 0, 2, 5}; /* b, c, a */
    wl_sf_octree_order(p, 7, order);
    assert_memory_equal(order, expect, sizeof order);
    Vec3 same[4] = {a, a, a, a};
    wl_sf_octree_order(same, 4, order);
    for (guint i = 0; i < 4; i++)
        assert_int_equal(order[i], i);
    wl_sf_octree_order(p, 1, order);
    assert_int_equal(order[0], 0);
    wl_sf_octree_order(NULL, 0, order);
}

/* ---- a long strip, chunked -------------------------------------------- */

enum { STRIP_LEN = 96, STRIP_ROWS = 6 };

/* STRIP_LEN x STRIP_ROWS unit quads in z = 0, two triangles each,
 * written row by row along x (the long side). */
static SceneDb *strip_db(void)
{
    SceneDb *db = scene_db_new();
    guint sid = scene_db_add_struct(db, "strip");
    for (int j = 0; j < STRIP_ROWS; j++)
        for (int i = 0; i < STRIP_LEN; i++) {
            Vec3 q[4] = {vec3(i, j, 0), vec3(i + 1, j, 0),
                         vec3(i + 1, j + 1, 0), vec3(i, j + 1, 0)};
            Vec3 t1[3] = {q[0], q[1], q[2]}, t2[3] = {q[0], q[2], q[3]};
            SceneElem e1 = scene_elem_prim(SCENE_EL_TRIANGLE, t1, 3);
            SceneElem e2 = scene_elem_prim(SCENE_EL_TRIANGLE, t2, 3);
            assert_true(scene_db_append(db, sid, &e1, NULL));
            assert_true(scene_db_append(db, sid, &e2, NULL));
        }
    scene_db_post(db, sid);
    return db;
}

/* Mean over the chunks of the sum of the box's extents; checks that the
 * chunks hold every primitive exactly once, N to a chunk but the last. */
static double mean_extent(const SceneDb *db, WlSfChunking how, guint n)
{
    WlSfDb *d = wl_sf_db_new(db, 4, n, how, NULL);
    assert_non_null(d);
    guint total = 2 * STRIP_LEN * STRIP_ROWS;
    gboolean *seen = g_new0(gboolean, total);
    double sum = 0;
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        if (how != WL_SF_CHUNK_SORTED && c + 1 < wl_sf_n_chunks(d))
            assert_int_equal(ch->n_prims, n);
        assert_true(ch->n_prims >= 1 && ch->n_prims <= n);
        for (guint i = 0; i < ch->n_prims; i++) {
            guint pos = g_array_index(d->prims, guint, ch->prim_first + i);
            assert_true(pos < total);
            assert_false(seen[pos]);
            seen[pos] = TRUE;
        }
        Vec3 s = scene_box_size(ch->box);
        sum += s.x + s.y + s.z;
    }
    assert_int_equal(d->prims->len, total);
    double mean = sum / wl_sf_n_chunks(d);
    g_free(seen);
    wl_sf_db_free(d);
    return mean;
}

static void test_strip_chunks(void **state)
{
    (void)state;
    SceneDb *db = strip_db();
    const guint sizes[] = {5, 12, 26};
    for (guint k = 0; k < G_N_ELEMENTS(sizes); k++) {
        double u = mean_extent(db, WL_SF_CHUNK_UNSORTED, sizes[k]);
        double p = mean_extent(db, WL_SF_CHUNK_PARTIAL, sizes[k]);
        double s = mean_extent(db, WL_SF_CHUNK_SORTED, sizes[k]);
        print_message("strip N=%u mean extent: unsorted %.3f, partially "
                      "sorted %.3f, sorted %.3f\n",
                      sizes[k], u, p, s);
        assert_true(p < u);
    }
    scene_db_free(db);
}

/* ---- polygon counts of every primitive kind --------------------------- */

/* Structure "part": a triangle (1 polygon), a 5-vertex strip (3), a
 * 2-vertex polygon (no area: 0, left out of the chunks), a quad (1) and
 * a 4-vertex strip (2); executed twice by the posted root under two
 * translations.  Unsorted chunks of 2 primitives for 3 masters. */
static SceneDb *kinds_db(void)
{
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    guint part = scene_db_add_struct(db, "part");
    Vec3 v[5] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(1, 1, 2),
                 vec3(0, 2, -1)};
    const SceneElemKind kind[5] = {SCENE_EL_TRIANGLE, SCENE_EL_TRISTRIP,
                                   SCENE_EL_POLYGON, SCENE_EL_POLYGON,
                                   SCENE_EL_TRISTRIP};
    const guint nv[5] = {3, 5, 2, 4, 4};
    for (guint k = 0; k < 5; k++) {
        SceneElem e = scene_elem_prim(kind[k], v, nv[k]);
        assert_true(scene_db_append(db, part, &e, NULL));
    }
    for (int k = 0; k < 2; k++) {
        SceneElem m = scene_elem_matrix(mat4_translate(10 * (k + 1), 0, 0),
                                        SCENE_MAT_REPLACE);
        SceneElem x = scene_elem_execute(part);
        assert_true(scene_db_append(db, root, &m, NULL));
        assert_true(scene_db_append(db, root, &x, NULL));
    }
    scene_db_post(db, root);
    return db;
}

/* Chunk 0 holds positions 0 and 1 (1 + 3 polygons), chunk 1 positions 3
 * and 4 (1 + 2); each has the two instances (max-set nodes 1 and 2),
 * whose polygons are those of `flat` in traversal order: node 1 owns
 * polygons 0..6 (triangle 0, strip 1-3, quad 4, strip 5-6), node 2 the
 * same shifted by 7.  The boxes are of the chunks' own vertices: chunk 0
 * (the 5-vertex strip) reaches y = 2 and z = -1, chunk 1 does not. */
static void test_polygon_counts(void **state)
{
    (void)state;
    SceneDb *src = kinds_db();
    WlSfDb *d = wl_sf_db_new(src, 3, 2, WL_SF_CHUNK_UNSORTED, NULL);
    assert_non_null(d);
    assert_int_equal(scene_mesh_n_polys(d->flat), 14);
    assert_int_equal(d->min_prims, 4);
    assert_int_equal(d->n_structs, 2);
    assert_int_equal(wl_sf_n_chunks(d), 2);
    assert_int_equal(wl_sf_n_insts(d), 4);
    const guint polys[2] = {4, 3}, pos[2][2] = {{0, 1}, {3, 4}};
    const uint32_t want[4][4] = {{0, 1, 2, 3}, {7, 8, 9, 10}, {4, 5, 6},
                                 {11, 12, 13}};
    for (guint c = 0; c < 2; c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        assert_int_equal(ch->sid, 1);
        assert_int_equal(ch->polys, polys[c]);
        assert_int_equal(ch->n_prims, 2);
        assert_int_equal(ch->prim_first, 2 * c);
        assert_int_equal(ch->master, c);
        assert_int_equal(ch->inst_first, 2 * c);
        assert_int_equal(ch->n_inst, 2);
        for (guint i = 0; i < 2; i++)
            assert_int_equal(g_array_index(d->prims, guint, 2 * c + i),
                             pos[c][i]);
        assert_true(ch->box.min.x == 0 && ch->box.max.x == 1);
        assert_true(ch->box.min.y == 0 && ch->box.max.y == (c ? 1 : 2));
        assert_true(ch->box.min.z == (c ? 0 : -1) && ch->box.max.z == 2);
        for (guint k = 0; k < 2; k++) {
            guint i = 2 * c + k;
            const WlSfInst *in = wl_sf_inst(d, i);
            assert_int_equal(in->chunk, c);
            assert_int_equal(in->node, k + 1);
            assert_true(in->matrix.m[0][3] == 10.0 * (k + 1));
            assert_memory_equal(wl_sf_inst_polys(d, i), want[i],
                                polys[c] * sizeof(uint32_t));
        }
    }
    wl_sf_db_set_procs(d, 1);
    assert_int_equal(wl_sf_chunk(d, 0)->master, 0);
    assert_int_equal(wl_sf_chunk(d, 1)->master, 0);
    wl_sf_db_free(d);
    scene_db_free(src);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_depth_first_over_cube),
        cmocka_unit_test(test_adaptive_depth),
        cmocka_unit_test(test_coincident_file_order),
        cmocka_unit_test(test_strip_chunks),
        cmocka_unit_test(test_polygon_counts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
