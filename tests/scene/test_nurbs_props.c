/* test_nurbs_props.c — sim/scene/nurbs.c by its claims (nurbs.h): the
 * defaults, the control net on a torus (tube radius 0.45, ring radius 1,
 * periodic indices), the radius bumps as the seeded sum of sinusoids the
 * file's comment states, the uniform cubic B-spline's value at a knot,
 * (c0 + 4 c1 + c2) / 6, and its continuity across spans, and the mesh:
 * counts, tags, one orientation for every strip triangle (all facing out
 * of the tube), the scene's view.  Found unchecked by make mutate
 * (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/core/rng.h"
#include "sim/scene/nurbs.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static void test_defaults_and_net(void **st)
{
    (void)st;
    SceneNurbsParams p = scene_nurbs_defaults();
    assert_true(p.patches_u == 6 && p.patches_v == 17 && p.tess == 24 &&
                p.bumps == 6 && p.amplitude == 0.25 && p.seed == 1);
    assert_true(p.color.r == 0.80f && p.color.g == 0.62f &&
                p.color.b == 0.45f);
    p.bumps = 0;
    p.patches_u = 2; /* 22 control points around the tube */
    p.patches_v = 3; /* 33 around the ring */
    Vec3 c = scene_nurbs_control(&p, 0, 0);
    NEAR(c.x, 1.45, 1e-12);
    NEAR(c.y, 0, 1e-12);
    NEAR(c.z, 0, 1e-12);
    double th = 2 * G_PI * 5 / 22, ph = 2 * G_PI * 7 / 33;
    c = scene_nurbs_control(&p, 5, 7);
    double ring = 1 + 0.45 * cos(th);
    NEAR(c.x, ring * cos(ph), 1e-12);
    NEAR(c.y, 0.45 * sin(th), 1e-12);
    NEAR(c.z, ring * sin(ph), 1e-12);
    Vec3 w = scene_nurbs_control(&p, 5 + 22, 7 + 33);
    assert_true(w.x == c.x && w.y == c.y && w.z == c.z);
}

/* r = 0.45 (1 + a / sqrt(n) sum_k sin(m_k th + n_k ph + phase_k)) with
 * m_k in 1..3, n_k in 1..5, phase_k uniform in [0, 2 pi), drawn in that
 * order from stream 7 of the seed. */
static void test_bumps(void **st)
{
    (void)st;
    SceneNurbsParams p = scene_nurbs_defaults();
    p.bumps = 3;
    p.amplitude = 0.5;
    p.seed = 9;
    SimRng r;
    sim_rng_init(&r, 9, 7);
    double m[3], n[3], ph0[3];
    for (int k = 0; k < 3; k++) {
        m[k] = 1 + (double)sim_rng_below(&r, 3);
        n[k] = 1 + (double)sim_rng_below(&r, 5);
        ph0[k] = 2 * G_PI * sim_rng_uniform(&r);
    }
    guint nu = 11 * 6, nv = 11 * 17;
    for (guint i = 0; i < nu; i += 13)
        for (guint j = 0; j < nv; j += 29) {
            double th = 2 * G_PI * i / nu, ph = 2 * G_PI * j / nv, f = 0;
            for (int k = 0; k < 3; k++)
                f += sin(m[k] * th + n[k] * ph + ph0[k]);
            double rad = 0.45 * (1 + 0.5 * f / sqrt(3.0));
            Vec3 c = scene_nurbs_control(&p, i, j);
            NEAR(c.y, rad * sin(th), 1e-12);
            NEAR(c.x, (1 + rad * cos(th)) * cos(ph), 1e-12);
        }
}

static void test_spline(void **st)
{
    (void)st;
    SceneNurbsParams p = scene_nurbs_defaults();
    p.patches_u = 2;
    p.patches_v = 2;
    for (guint a = 0; a < 2; a++)
        for (guint k = 0; k <= 11; k++) {
            /* at knot k of patch a (b = 1, t = 4): (c0 + 4 c1 + c2) / 6 */
            Vec3 want = vec3(0, 0, 0);
            const double wts[3] = {1, 4, 1};
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    Vec3 c = scene_nurbs_control(&p, 11 * a + k + i, 11 + 4 + j);
                    want = vec3_add(want, vec3_scale(c, wts[i] * wts[j] / 36));
                }
            Vec3 got = scene_nurbs_eval(&p, a, 1, k, 4);
            NEAR(got.x, want.x, 1e-12);
            NEAR(got.y, want.y, 1e-12);
            NEAR(got.z, want.z, 1e-12);
            /* continuous across the knot */
            if (k > 0 && k < 11) {
                Vec3 l = scene_nurbs_eval(&p, a, 1, k - 1e-9, 4.5);
                Vec3 r = scene_nurbs_eval(&p, a, 1, k + 1e-9, 4.5);
                NEAR(l.x, r.x, 1e-7);
                NEAR(l.y, r.y, 1e-7);
                NEAR(l.z, r.z, 1e-7);
            }
        }
    /* mid-span: (c0 + 23 c1 + 23 c2 + c3) / 48 in one direction */
    Vec3 want = vec3(0, 0, 0);
    const double w4[4] = {1, 23, 23, 1};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 3; j++) {
            Vec3 c = scene_nurbs_control(&p, 2 + i, 11 + 4 + j);
            want = vec3_add(want, vec3_scale(c, w4[i] / 48 * (j == 1 ? 4 : 1) / 6));
        }
    Vec3 got = scene_nurbs_eval(&p, 0, 1, 2.5, 4);
    NEAR(got.x, want.x, 1e-12);
    NEAR(got.z, want.z, 1e-12);
}

static void test_mesh(void **st)
{
    (void)st;
    SceneNurbsParams p = scene_nurbs_defaults();
    p.patches_u = 2;
    p.patches_v = 3;
    p.tess = 4;
    p.bumps = 0;
    SceneMesh *m = scene_nurbs_mesh(&p);
    assert_int_equal(scene_mesh_n_vertices(m), 6 * 25);
    assert_int_equal(scene_mesh_n_polys(m), 6 * 2 * 16);
    assert_int_equal(m->normals->len, 6 * 25);
    guint out = 0;
    for (guint t = 0; t < scene_mesh_n_polys(m); t++) {
        assert_int_equal(g_array_index(m->poly_tag, uint32_t, t), t / 32);
        const uint32_t *v = scene_mesh_poly(m, t);
        Vec3 a = scene_mesh_vertex(m, v[0]), b = scene_mesh_vertex(m, v[1]),
             c = scene_mesh_vertex(m, v[2]);
        Vec3 n = vec3_cross(vec3_sub(b, a), vec3_sub(c, a));
        assert_true(vec3_len(n) > 0);
        Vec3 q = vec3_scale(vec3_add(vec3_add(a, b), c), 1.0 / 3);
        Vec3 axis = vec3_norm(vec3(q.x, 0, q.z)); /* the ring's circle */
        out += vec3_dot(n, vec3_sub(q, axis)) > 0;
        SceneColor col = g_array_index(m->poly_color, SceneColor, t);
        assert_true(col.r == 0.80f);
    }
    /* one orientation everywhere */
    assert_true(out == 0 || out == scene_mesh_n_polys(m));
    /* the first strip: (a0 b0 a1), then (b0 a1 b1) flipped */
    const uint32_t *t0 = scene_mesh_poly(m, 0), *t1 = scene_mesh_poly(m, 1);
    assert_true(t0[0] == 0 && t0[1] == 5 && t0[2] == 1);
    assert_true(t1[0] == 1 && t1[1] == 5 && t1[2] == 6);
    /* patch (0, 0)'s first vertex is the spline at (0, 0) */
    Vec3 e = scene_nurbs_eval(&p, 0, 0, 0, 0), v0 = scene_mesh_vertex(m, 0);
    NEAR(e.x, v0.x, 1e-12);
    Vec3 last = scene_mesh_vertex(m, 24), e11 = scene_nurbs_eval(&p, 0, 0, 11, 11);
    NEAR(last.x, e11.x, 1e-12);
    NEAR(last.z, e11.z, 1e-12);
    scene_mesh_free(m);
    Scene *s = scene_nurbs_new(&p);
    assert_true(s->width == 1200 && s->height == 1000 && s->two_sided);
    assert_true(s->camera.aspect == 1.2);
    Vec3 d = vec3_norm(vec3_sub(s->camera.eye, s->camera.target));
    NEAR(d.y, sin(35 * G_PI / 180), 1e-9);
    NEAR(d.x / d.z, tan(20 * G_PI / 180), 1e-9);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_and_net),
        cmocka_unit_test(test_bumps),
        cmocka_unit_test(test_spline),
        cmocka_unit_test(test_mesh),
    };
    return cmocka_run_group_tests_name("nurbs_props", tests, NULL, NULL);
}
