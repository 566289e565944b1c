/* test_pn_props.c — sim/scene/pn_triangles.c: every grid vertex of a
 * tessellated triangle, edges included (which are computed from the edge
 * alone, pn_triangles.c), equals the patch's cubic point and its linear
 * or quadratic normal at the vertex's barycentric (u, v); corners are
 * the inputs; the mid-edge normal is the reflection formula of Vlachos et
 * al.; the grid's triangles keep the input's winding.  Found unchecked by
 * make mutate (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/pn_triangles.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static SceneMesh *curved_tri(void)
{
    SceneMesh *m = scene_mesh_new();
    Vec3 P[3] = {{0, 0, 0}, {2, 0.5, 0}, {0.25, 2, 0.5}};
    Vec3 N[3] = {{-0.3, -0.2, 1}, {0.4, 0, 1}, {0, 0.5, 1}};
    for (int i = 0; i < 3; i++) {
        scene_mesh_add_vertex(m, P[i]);
        Vec3 n = vec3_norm(N[i]);
        g_array_append_val(m->normals, n);
    }
    scene_mesh_add_tri(m, 0, 1, 2, scene_color(0.5f, 1, 1), 3);
    return m;
}

static void test_grid_matches_patch(void **st)
{
    (void)st;
    SceneMesh *m = curved_tri();
    ScenePnPatch pt;
    Vec3 P[3], N[3];
    for (int i = 0; i < 3; i++) {
        P[i] = scene_mesh_vertex(m, i);
        N[i] = g_array_index(m->normals, Vec3, i);
    }
    scene_pn_patch(&pt, P, N);
    for (int kind = 0; kind < 2; kind++) {
        ScenePnParams p = {.level = 3,
                           .normals = kind ? SCENE_PN_QUADRATIC
                                           : SCENE_PN_LINEAR};
        SceneMesh *t = scene_pn_tessellate(m, &p);
        guint n = 4, idx = 0;
        assert_int_equal(scene_mesh_n_vertices(t), 15);
        assert_int_equal(scene_mesh_n_polys(t), 16);
        for (guint k = 0; k <= n; k++)
            for (guint j = 0; j + k <= n; j++, idx++) {
                double u = (double)j / n, v = (double)k / n;
                Vec3 want = scene_pn_point(&pt, u, v);
                Vec3 wn = scene_pn_normal(&pt, p.normals, u, v);
                Vec3 got = scene_mesh_vertex(t, idx);
                Vec3 gn = g_array_index(t->normals, Vec3, idx);
                NEAR(got.x, want.x, 1e-12);
                NEAR(got.y, want.y, 1e-12);
                NEAR(got.z, want.z, 1e-12);
                NEAR(gn.x, wn.x, 1e-12);
                NEAR(gn.y, wn.y, 1e-12);
                NEAR(gn.z, wn.z, 1e-12);
            }
        /* corners are the inputs */
        Vec3 c1 = scene_mesh_vertex(t, 4), c2 = scene_mesh_vertex(t, 14);
        assert_true(c1.x == 2 && c1.y == 0.5 && c2.z == 0.5);
        /* every small triangle wound like the input (normal along +z) */
        for (guint i = 0; i < scene_mesh_n_polys(t); i++) {
            assert_true(scene_mesh_poly_normal(t, i).z > 0);
            assert_int_equal(g_array_index(t->poly_tag, uint32_t, i), 3);
            assert_true(g_array_index(t->poly_color, SceneColor, i).r == 0.5f);
        }
        scene_mesh_free(t);
    }
    /* the two normal kinds differ inside an edge */
    Vec3 a = scene_pn_normal(&pt, SCENE_PN_LINEAR, 0.5, 0);
    Vec3 b = scene_pn_normal(&pt, SCENE_PN_QUADRATIC, 0.5, 0);
    assert_true(vec3_len(vec3_sub(a, b)) > 1e-6);
    /* n110: (N0 + N1 - v d) normalised, v = 2 d.(N0 + N1) / d.d */
    Vec3 d = vec3_sub(P[1], P[0]), s = vec3_add(pt.n[0], pt.n[1]);
    Vec3 h = vec3_norm(vec3_sub(s, vec3_scale(d, 2 * vec3_dot(d, s) /
                                                    vec3_dot(d, d))));
    NEAR(pt.n110.x, h.x, 1e-12);
    NEAR(pt.n110.z, h.z, 1e-12);
    /* b210 = (2 P0 + P1 - ((P1 - P0).N0) N0) / 3 */
    double w = vec3_dot(d, pt.n[0]);
    Vec3 b210 = vec3_scale(vec3_sub(vec3_add(vec3_scale(P[0], 2), P[1]),
                                    vec3_scale(pt.n[0], w)),
                           1.0 / 3);
    NEAR(pt.b210.x, b210.x, 1e-12);
    NEAR(pt.b210.z, b210.z, 1e-12);
    scene_mesh_free(m);
}

/* A quad without normals: normals computed, split into a fan of two
 * patches; level 0 keeps the triangles. */
static void test_quad_level0(void **st)
{
    (void)st;
    SceneMesh *m = scene_mesh_new();
    for (int i = 0; i < 4; i++)
        scene_mesh_add_vertex(m, vec3(i == 1 || i == 2, i >= 2, 0));
    scene_mesh_add_quad(m, 0, 1, 2, 3, scene_color(1, 1, 1), 5);
    ScenePnParams p = {.level = 0, .normals = SCENE_PN_LINEAR};
    SceneMesh *t = scene_pn_tessellate(m, &p);
    assert_int_equal(scene_mesh_n_polys(t), 2);
    assert_int_equal(scene_mesh_n_vertices(t), 6);
    assert_int_equal(m->normals->len, 0); /* the input is not changed */
    for (guint i = 0; i < 6; i++) {
        Vec3 n = g_array_index(t->normals, Vec3, i);
        assert_true(n.z == 1);
    }
    scene_mesh_free(t);
    scene_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grid_matches_patch),
        cmocka_unit_test(test_quad_level0),
    };
    return cmocka_run_group_tests_name("pn_props", tests, NULL, NULL);
}
