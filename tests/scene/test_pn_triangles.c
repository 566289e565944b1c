/* test_pn_triangles.c — curved PN triangles (seed 002, "Curved PN
 * Triangles"): the corners reproduce the input positions and normals;
 * two triangles sharing an edge and its vertex normals but with
 * different opposite vertices produce bit-identical edge points (no
 * cracks), while changing a shared normal on one side does open a crack;
 * a triangle whose vertex normals equal its face normal stays flat,
 * while a tilted normal bends it; each triangle becomes (L + 1)^2;
 * the scene option tessellates every mesh.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/pn_triangles.h"
#include "sim/scene/scene_cfg.h"

static const ScenePnNormals kinds[] = {SCENE_PN_LINEAR, SCENE_PN_QUADRATIC};

/* A one-triangle mesh (P, N). */
static SceneMesh *tri_mesh(const Vec3 P[3], const Vec3 N[3])
{
    SceneMesh *m = scene_mesh_new();
    for (int i = 0; i < 3; i++) {
        scene_mesh_add_vertex(m, P[i]);
        g_array_append_val(m->normals, N[i]);
    }
    scene_mesh_add_tri(m, 0, 1, 2, scene_color(1, 1, 1), 0);
    return m;
}

static gboolean vec_eq(Vec3 a, Vec3 b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static gboolean vec_near(Vec3 a, Vec3 b, double eps)
{
    return vec3_len(vec3_sub(a, b)) <= eps;
}

static void test_corners(void **st)
{
    (void)st;
    Vec3 P[3] = {{0, 0, 0}, {2, 0.3, 0}, {0.4, 1.7, 0.2}};
    Vec3 N[3] = {{-0.3, -0.2, 1}, {0.4, 0, 1}, {0, 0.5, 1}};
    ScenePnPatch pt;
    scene_pn_patch(&pt, P, N);
    const double uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    for (int c = 0; c < 3; c++) {
        assert_true(
            vec_near(scene_pn_point(&pt, uv[c][0], uv[c][1]), P[c], 1e-12));
        for (int k = 0; k < 2; k++)
            assert_true(
                vec_near(scene_pn_normal(&pt, kinds[k], uv[c][0], uv[c][1]),
                         vec3_norm(N[c]), 1e-12));
    }
    /* the tessellated mesh holds the corners among its vertices */
    for (guint L = 0; L < 4; L++) {
        ScenePnParams p = {L, SCENE_PN_QUADRATIC, FALSE};
        SceneMesh *in = tri_mesh(P, N), *out = scene_pn_tessellate(in, &p);
        guint last = scene_mesh_n_vertices(out) - 1;
        assert_true(vec_eq(scene_mesh_vertex(out, 0), P[0]));
        assert_true(vec_eq(scene_mesh_vertex(out, L + 1), P[1]));
        assert_true(vec_eq(scene_mesh_vertex(out, last), P[2]));
        scene_mesh_free(in);
        scene_mesh_free(out);
    }
}

/* Every vertex of `a` that lies on segment (p, q)'s curve, i.e. whose
 * flat projection is on the segment: collected in `pts`. */
static void edge_points(const SceneMesh *m, guint level, guint corner_a,
                        guint corner_b, GArray *pts, GArray *nrms)
{
    /* the grid rows are by k (weight of P3); corner indices in the block */
    guint n = level + 1;
    for (guint s = 0; s <= n; s++) {
        guint j, k;
        if (corner_a == 0 && corner_b == 1)
            j = s, k = 0; /* P1 -> P2 */
        else
            g_assert_not_reached();
        guint idx = k * (n + 1) - k * (k - 1) / 2 + j;
        Vec3 v = scene_mesh_vertex(m, idx);
        Vec3 nn = g_array_index(m->normals, Vec3, idx);
        g_array_append_val(pts, v);
        g_array_append_val(nrms, nn);
    }
}

/* Triangle A = (X, Y, C) and B = (Y, X, D): the shared edge runs X -> Y
 * in A and Y -> X in B; C and D (and their normals) differ. */
static void shared_edge(guint L, ScenePnNormals kind, Vec3 Y, Vec3 ny_b,
                        GArray *pa, GArray *pb, GArray *na, GArray *nb)
{
    Vec3 X = {0.1, 0, 0}, C = {0.5, 1, 0.3}, D = {0.7, -1.1, -0.2};
    Vec3 nx = {-0.3, 0.1, 1}, ny = {0.4, -0.2, 1}, nc = {0, 0.6, 1},
         nd = {0.2, -0.7, 0.9};
    Vec3 PA[3] = {X, Y, C}, NA[3] = {nx, ny, nc};
    Vec3 PB[3] = {Y, X, D}, NB[3] = {ny_b, nx, nd};
    (void)ny;
    ScenePnParams p = {L, kind, FALSE};
    SceneMesh *ma = tri_mesh(PA, NA), *mb = tri_mesh(PB, NB);
    SceneMesh *ta = scene_pn_tessellate(ma, &p);
    SceneMesh *tb = scene_pn_tessellate(mb, &p);
    edge_points(ta, L, 0, 1, pa, na);
    edge_points(tb, L, 0, 1, pb, nb);
    scene_mesh_free(ma);
    scene_mesh_free(mb);
    scene_mesh_free(ta);
    scene_mesh_free(tb);
}

static guint n_mismatch(guint L, ScenePnNormals kind, Vec3 Y, Vec3 ny_b)
{
    GArray *pa = g_array_new(FALSE, FALSE, sizeof(Vec3));
    GArray *pb = g_array_new(FALSE, FALSE, sizeof(Vec3));
    GArray *na = g_array_new(FALSE, FALSE, sizeof(Vec3));
    GArray *nb = g_array_new(FALSE, FALSE, sizeof(Vec3));
    shared_edge(L, kind, Y, ny_b, pa, pb, na, nb);
    guint bad = 0, n = pa->len;
    for (guint s = 0; s < n; s++) /* B walks the edge backwards */
        bad += !vec_eq(g_array_index(pa, Vec3, s),
                       g_array_index(pb, Vec3, n - 1 - s)) ||
               !vec_eq(g_array_index(na, Vec3, s),
                       g_array_index(nb, Vec3, n - 1 - s));
    g_array_free(pa, TRUE);
    g_array_free(pb, TRUE);
    g_array_free(na, TRUE);
    g_array_free(nb, TRUE);
    return bad;
}

/* The patch does not depend on which vertex is called first: the patch
 * of (P2, P3, P1) at barycentric (u, v) = (v0, 1 - u0 - v0) is the
 * patch of (P1, P2, P3) at (u0, v0), positions and normals alike (every
 * control point takes part). */
static void test_rotation_invariant(void **st)
{
    (void)st;
    Vec3 P[3] = {{0, 0, 0}, {2, 0.3, 0}, {0.4, 1.7, 0.2}};
    Vec3 N[3] = {{-0.3, -0.2, 1}, {0.4, 0, 1}, {0, 0.5, 1}};
    Vec3 Q[3] = {P[1], P[2], P[0]}, M[3] = {N[1], N[2], N[0]};
    ScenePnPatch a, b;
    scene_pn_patch(&a, P, N);
    scene_pn_patch(&b, Q, M);
    const double uv[4][2] = {{0.2, 0.3}, {0.5, 0}, {0, 0.5}, {0.5, 0.5}};
    for (int i = 0; i < 4; i++) {
        double u = uv[i][0], v = uv[i][1];
        assert_true(vec_near(scene_pn_point(&a, u, v),
                             scene_pn_point(&b, v, 1 - u - v), 1e-12));
        for (int k = 0; k < 2; k++)
            assert_true(vec_near(scene_pn_normal(&a, kinds[k], u, v),
                                 scene_pn_normal(&b, kinds[k], v, 1 - u - v),
                                 1e-12));
    }
}

/* Y apart from X = (0.1, 0, 0) in x, then only in y, then only in z,
 * then only in x, then only in y: each coordinate in turn decides which
 * end an edge is computed from (and the order must not look past the
 * first coordinate that differs). */
static void test_no_cracks(void **st)
{
    (void)st;
    Vec3 ny = {0.4, -0.2, 1}, other = {0.1, 0.3, 1};
    const Vec3 Y[5] = {{1.3, 0.2, 0.1}, {0.1, 1.2, 0.1}, {0.1, 0, 0.9},
                       {1.3, 0, 0},     {0.1, 1.2, 0}};
    for (int y = 0; y < 5; y++)
        for (guint L = 1; L < 7; L++)
            for (int k = 0; k < 2; k++) {
                /* same edge and normals, different opposite vertices */
                if (n_mismatch(L, kinds[k], Y[y], ny))
                    fail_msg("Y %d level %u normals %d: a crack", y, L, k);
                /* a different normal at Y on one side opens a crack: the
                 * edge's shape does come from its vertex normals */
                assert_true(n_mismatch(L, kinds[k], Y[y], other) > 0);
            }
}

/* Largest distance of any vertex from the plane of P. */
static double off_plane(const SceneMesh *m, const Vec3 P[3], Vec3 *face)
{
    *face = vec3_norm(vec3_cross(vec3_sub(P[1], P[0]), vec3_sub(P[2], P[0])));
    double worst = 0;
    for (guint i = 0; i < scene_mesh_n_vertices(m); i++)
        worst = fmax(
            worst,
            fabs(vec3_dot(vec3_sub(scene_mesh_vertex(m, i), P[0]), *face)));
    return worst;
}

static void test_flat_stays_flat(void **st)
{
    (void)st;
    Vec3 P[3] = {{0, 0, 0}, {2, 0.5, 1}, {-0.3, 1.5, 0.4}};
    Vec3 f = vec3_norm(vec3_cross(vec3_sub(P[1], P[0]), vec3_sub(P[2], P[0])));
    for (int k = 0; k < 2; k++) {
        Vec3 N[3] = {f, f, f}, face;
        ScenePnParams p = {5, kinds[k], FALSE};
        SceneMesh *in = tri_mesh(P, N), *out = scene_pn_tessellate(in, &p);
        assert_true(off_plane(out, P, &face) < 1e-12);
        for (guint i = 0; i < out->normals->len; i++)
            assert_true(
                vec_near(g_array_index(out->normals, Vec3, i), face, 1e-12));
        scene_mesh_free(out);
        scene_mesh_free(in);
        /* the same triangle with one tilted normal bulges */
        N[1] = vec3_norm(vec3_add(f, vec3(0.5, 0, 0)));
        in = tri_mesh(P, N);
        out = scene_pn_tessellate(in, &p);
        assert_true(off_plane(out, P, &face) > 1e-3);
        scene_mesh_free(out);
        scene_mesh_free(in);
    }
}

/* The quadratic normal sees an inflection the linear one ignores: on an
 * S-shaped edge (normals tilted the same way at both ends, as in the
 * slides' picture) the linear mid-edge normal is the average, the
 * mid-edge coefficient n110 is that average reflected across the plane
 * perpendicular to the edge, and the quadratic normal at mid-edge leans
 * towards it (the true S-curve's normal there leans past the vertical). */
static void test_quadratic_vs_linear(void **st)
{
    (void)st;
    Vec3 P[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    Vec3 t = vec3_norm(vec3(0.5, 0, 1));
    Vec3 N[3] = {t, t, vec3(0, 0, 1)};
    ScenePnPatch pt;
    scene_pn_patch(&pt, P, N);
    Vec3 lin = scene_pn_normal(&pt, SCENE_PN_LINEAR, 0.5, 0);
    Vec3 quad = scene_pn_normal(&pt, SCENE_PN_QUADRATIC, 0.5, 0);
    assert_true(vec_near(lin, t, 1e-12));
    assert_true(pt.n110.x < 0 && fabs(pt.n110.x + t.x) < 1e-12);
    assert_true(quad.x < lin.x - 0.1);
    assert_true(fabs(vec3_len(quad) - 1) < 1e-12);
}

static void test_counts(void **st)
{
    (void)st;
    SceneMesh *m = scene_mesh_new();
    for (int i = 0; i < 5; i++)
        scene_mesh_add_vertex(m,
                              vec3(cos(i * 1.2566), sin(i * 1.2566), 0.1 * i));
    uint32_t pent[5] = {0, 1, 2, 3, 4};
    scene_mesh_add_poly(m, pent, 5, scene_color(1, 0, 0), 7);
    scene_mesh_add_tri(m, 0, 2, 4, scene_color(0, 1, 0), 8);
    for (guint L = 0; L < 9; L++) {
        ScenePnParams p = {L, SCENE_PN_LINEAR, FALSE};
        SceneMesh *out = scene_pn_tessellate(m, &p);
        assert_int_equal(scene_mesh_n_triangles(out), 4 * (L + 1) * (L + 1));
        assert_int_equal(scene_mesh_n_polys(out), 4 * scene_pn_tris_per_tri(L));
        assert_int_equal(scene_mesh_n_vertices(out),
                         4 * scene_pn_verts_per_tri(L));
        assert_int_equal(out->normals->len, scene_mesh_n_vertices(out));
        GError *err = NULL;
        assert_true(scene_mesh_validate(out, "pn", &err));
        /* every small triangle keeps its source's colour and tag, and
         * faces the same way as its flat source */
        guint last = scene_mesh_n_polys(out) - 1;
        assert_int_equal(g_array_index(out->poly_tag, uint32_t, last), 8);
        assert_true(vec3_dot(scene_mesh_poly_normal(out, last),
                             scene_mesh_poly_normal(m, 1)) > 0.5);
        scene_mesh_free(out);
    }
    scene_mesh_free(m);
}

static void test_scene_option(void **st)
{
    (void)st;
    GError *err = NULL;
    const char *flat = "scene: {generator: teapots, count: 2,"
                       " polygons_per_teapot: 300}\n";
    const char *pn = "scene: {generator: teapots, count: 2,"
                     " polygons_per_teapot: 300,\n"
                     "        pn_triangles: {level: 3, normals: quadratic}}\n";
    CfgNode *a = cfg_load_string(flat, "a.yaml", &err);
    CfgNode *b = cfg_load_string(pn, "b.yaml", &err);
    Scene *sa = scene_from_cfg(cfg_get(a, "scene"), &err);
    Scene *sb = scene_from_cfg(cfg_get(b, "scene"), &err);
    assert_non_null(sa);
    assert_non_null(sb);
    assert_int_equal(scene_n_triangles(sb), 16 * scene_n_triangles(sa));
    scene_free(sa);
    scene_free(sb);
    cfg_free(a);
    cfg_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_corners),
        cmocka_unit_test(test_rotation_invariant),
        cmocka_unit_test(test_no_cracks),
        cmocka_unit_test(test_flat_stays_flat),
        cmocka_unit_test(test_quadratic_vs_linear),
        cmocka_unit_test(test_counts),
        cmocka_unit_test(test_scene_option),
    };
    return cmocka_run_group_tests_name("pn_triangles", tests, NULL, NULL);
}
