/* test_teapot_props.c — sim/scene/teapot.c and teapots.c by their
 * claims: the tessellation rule of teapot.h (n the largest with 32 n^2 <=
 * P, the rest split quads; exactly P polygons), Bézier evaluation against
 * de Casteljau's construction and the control points at the corners,
 * z-up to y-up, snapped coordinates, welded vertices, outward winding
 * (positive volume), unit normals; the teapots' layouts (spread rows
 * centred, the last one short; depth rows shifted and receding), yaw
 * steps, colours and tags, and the count and memory checks at their
 * limits.  Found unchecked by make mutate (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/core/memlimit.h"
#include "sim/scene/teapot.h"
#include "sim/scene/teapots.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static void test_tess_rule(void **st)
{
    (void)st;
    const uint64_t polys[] = {288, 289, 511, 512, 513, 3200, 1u << 26};
    const guint n[] = {3, 3, 3, 4, 4, 10, 1448};
    const guint split[] = {0, 1, 223, 0, 1, 0, 67108864 - 32 * 1448 * 1448};
    for (guint i = 0; i < G_N_ELEMENTS(polys); i++) {
        SceneTeapotTess t;
        assert_true(scene_teapot_tess_for(polys[i], "w", &t, NULL));
        assert_int_equal(t.n, n[i]);
        assert_int_equal(t.split, split[i]);
    }
    GError *err = NULL;
    SceneTeapotTess t;
    assert_false(scene_teapot_tess_for(287, "w", &t, &err));
    assert_string_equal(err->message, "w: found 287 polygons per teapot, "
                                      "expected 288 to 67108864");
    g_clear_error(&err);
    assert_false(scene_teapot_tess_for((1u << 26) + 1, "w", &t, &err));
    assert_string_equal(err->message, "w: found 67108865 polygons per teapot,"
                                      " expected 288 to 67108864");
    g_clear_error(&err);
}

static Vec3 control(guint patch, int k)
{
    const double *c = scene_teapot_points[scene_teapot_patches[patch][k] - 1];
    return vec3(c[0], c[2], -c[1]); /* z-up to y-up */
}

static Vec3 lerp3(Vec3 a, Vec3 b, double t)
{
    return vec3_add(a, vec3_scale(vec3_sub(b, a), t));
}

/* de Casteljau on four points. */
static Vec3 casteljau(Vec3 p[4], double t)
{
    Vec3 q[4];
    memcpy(q, p, sizeof q);
    for (int r = 3; r > 0; r--)
        for (int i = 0; i < r; i++)
            q[i] = lerp3(q[i], q[i + 1], t);
    return q[0];
}

static void test_eval(void **st)
{
    (void)st;
    for (guint patch = 0; patch < SCENE_TEAPOT_PATCHES; patch += 5) {
        const double uv[][2] = {{0, 0}, {0, 1}, {1, 0}, {1, 1},
                                {0.5, 0.25}, {0.3, 0.9}};
        for (guint s = 0; s < G_N_ELEMENTS(uv); s++) {
            double u = uv[s][0], v = uv[s][1];
            Vec3 rows[4];
            for (int i = 0; i < 4; i++) {
                Vec3 r[4];
                for (int j = 0; j < 4; j++)
                    r[j] = control(patch, 4 * i + j);
                rows[i] = casteljau(r, v);
            }
            Vec3 want = casteljau(rows, u), got = scene_teapot_eval(patch, u, v);
            NEAR(got.x, want.x, 1e-7);
            NEAR(got.y, want.y, 1e-7);
            NEAR(got.z, want.z, 1e-7);
            /* snapped to 2^-24 */
            assert_true(got.x * 16777216.0 == nearbyint(got.x * 16777216.0));
            assert_true(got.z * 16777216.0 == nearbyint(got.z * 16777216.0));
        }
        Vec3 c0 = control(patch, 0), c15 = control(patch, 15);
        Vec3 e0 = scene_teapot_eval(patch, 0, 0),
             e15 = scene_teapot_eval(patch, 1, 1);
        NEAR(e0.x, c0.x, 1e-7);
        NEAR(e0.y, c0.y, 1e-7);
        NEAR(e15.z, c15.z, 1e-7);
    }
    Vec3 z = scene_teapot_eval(0, 0, 0);
    assert_true(signbit(z.x) == 0 || z.x != 0); /* no -0 */
}

static void test_mesh(void **st)
{
    (void)st;
    const uint64_t polys[] = {288, 300, 800, 1000};
    for (guint k = 0; k < G_N_ELEMENTS(polys); k++) {
        SceneTeapotTess t;
        assert_true(scene_teapot_tess_for(polys[k], "w", &t, NULL));
        SceneMesh *m = scene_teapot_mesh(t, scene_color(0.5f, 0.25f, 1));
        assert_int_equal(scene_mesh_n_polys(m), polys[k]);
        /* every polygon a triangle or a quad, tagged with its patch */
        double vol = 0;
        for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
            guint n = scene_mesh_poly_len(m, i);
            assert_true(n == 3 || n == 4);
            assert_true(g_array_index(m->poly_tag, uint32_t, i) < 32);
            SceneColor c = g_array_index(m->poly_color, SceneColor, i);
            assert_true(c.r == 0.5f && c.g == 0.25f && c.b == 1);
            const uint32_t *v = scene_mesh_poly(m, i);
            Vec3 a = scene_mesh_vertex(m, v[0]);
            for (guint j = 1; j + 1 < n; j++)
                vol += vec3_dot(a, vec3_cross(scene_mesh_vertex(m, v[j]),
                                              scene_mesh_vertex(m, v[j + 1]))) /
                       6;
        }
        assert_true(vol > 0); /* wound counter-clockwise from outside */
        /* tags: every patch appears, in order */
        assert_int_equal(g_array_index(m->poly_tag, uint32_t, 0), 0);
        assert_int_equal(
            g_array_index(m->poly_tag, uint32_t, scene_mesh_n_polys(m) - 1), 31);
        /* welded: no two vertices equal; unit normals, one a vertex */
        GHashTable *seen = g_hash_table_new_full(
            g_bytes_hash, g_bytes_equal, (GDestroyNotify)g_bytes_unref, NULL);
        for (guint i = 0; i < scene_mesh_n_vertices(m); i++) {
            Vec3 p = scene_mesh_vertex(m, i);
            GBytes *b = g_bytes_new(&p, sizeof p);
            assert_false(g_hash_table_contains(seen, b));
            g_hash_table_add(seen, b);
        }
        g_hash_table_destroy(seen);
        assert_int_equal(m->normals->len, scene_mesh_n_vertices(m));
        for (guint i = 0; i < m->normals->len; i++)
            NEAR(vec3_len(g_array_index(m->normals, Vec3, i)), 1, 1e-9);
        /* no -0 coordinate (snap adds +0.0), so +0 and -0 never split
         * a welded vertex; Newell's y = 0 points give z = -0 before it */
        guint zeros = 0;
        for (guint i = 0; i < scene_mesh_n_vertices(m); i++) {
            Vec3 p = scene_mesh_vertex(m, i);
            const double c[3] = {p.x, p.y, p.z};
            for (int k = 0; k < 3; k++) {
                assert_false(c[k] == 0 && signbit(c[k]));
                zeros += c[k] == 0;
            }
        }
        assert_true(zeros > 0);
        /* y-up: taller in y than deep, wider in x than deep */
        Vec3 sz = scene_box_size(scene_mesh_bbox(m));
        assert_true(sz.x > sz.y && sz.z < sz.x);
        scene_mesh_free(m);
    }
}

static double dist(const SceneMesh *m, uint32_t a, uint32_t b)
{
    return vec3_len(vec3_sub(scene_mesh_vertex(m, a), scene_mesh_vertex(m, b)));
}

/* A split quad a b c d becomes two consecutive triangles across its
 * shorter diagonal: (a, b, c) (a, c, d) when |ac| <= |bd|, else (a, b, d)
 * (b, c, d).  The pole triangles of collapsed cells match neither. */
static void test_split_diagonals(void **st)
{
    (void)st;
    SceneTeapotTess t;
    assert_true(scene_teapot_tess_for(32 * 100 + 600, "w", &t, NULL));
    assert_true(t.n == 10 && t.split == 600); /* 32 x 11^2 > 3800 */
    SceneMesh *m = scene_teapot_mesh(t, scene_color(1, 1, 1));
    guint ac = 0, bd = 0;
    for (guint i = 0; i + 1 < scene_mesh_n_polys(m); i++) {
        if (scene_mesh_poly_len(m, i) != 3 || scene_mesh_poly_len(m, i + 1) != 3)
            continue;
        const uint32_t *p = scene_mesh_poly(m, i), *q = scene_mesh_poly(m, i + 1);
        if (q[0] == p[0] && q[1] == p[2]) { /* a b c, a c d */
            assert_true(dist(m, p[0], p[2]) <= dist(m, p[1], q[2]));
            ac++;
            i++;
        } else if (q[0] == p[1] && q[2] == p[2]) { /* a b d, b c d */
            assert_true(dist(m, p[0], q[1]) > dist(m, p[1], p[2]));
            bd++;
            i++;
        }
    }
    assert_int_equal(ac + bd, 600);
    assert_true(ac > 100 && bd > 100);
    scene_mesh_free(m);
}

static Vec3 instance_centre(const Scene *s, guint i)
{
    return scene_box_center(scene_instance_bbox(s, i));
}

static void test_layouts(void **st)
{
    (void)st;
    SceneTeapotsParams p = scene_teapots_defaults();
    assert_true(p.polygons_per_teapot == 3200 && p.count == 1 &&
                p.layout == SCENE_TEAPOTS_SPREAD && p.spacing == 1.1 &&
                p.shift == 0.5 && p.vary_color && p.columns == 1 &&
                p.across == 1.1 && p.yaw == 0 && p.yaw_step == 0);
    p.polygons_per_teapot = 288;
    p.count = 5; /* 3 columns, 2 rows, the last of 2 */
    p.spacing = 2;
    Scene *s = scene_teapots_new(&p, "w", NULL);
    Vec3 size = scene_box_size(scene_mesh_bbox(scene_instance_mesh(s, 0)));
    const double cx[] = {-1, 0, 1, -0.5, 0.5}, cy[] = {0.5, 0.5, 0.5, -0.5, -0.5};
    for (guint i = 0; i < 5; i++) {
        Vec3 c = instance_centre(s, i);
        NEAR(c.x, cx[i] * 2 * size.x, 1e-6);
        NEAR(c.y, cy[i] * 2 * size.y, 1e-6);
        NEAR(c.z, 0, 1e-6);
        assert_int_equal(scene_instance(s, i)->tag, i);
    }
    assert_true(scene_instance(s, 0)->color.r == 0.90f);
    assert_true(scene_instance(s, 1)->color.g == 0.70f);
    assert_true(scene_instance(s, 4)->color.b == 0.85f);
    scene_free(s);
    /* counts whose rows are not the count rounded up (ceil(count / cols)
     * with cols = ceil(sqrt(count))): 3 = 2 + 1 and 7 = 3 + 3 + 1 */
    p.count = 3;
    s = scene_teapots_new(&p, "w", NULL);
    const double x3[] = {-0.5, 0.5, 0}, y3[] = {0.5, 0.5, -0.5};
    for (guint i = 0; i < 3; i++) {
        NEAR(instance_centre(s, i).x, x3[i] * 2 * size.x, 1e-6);
        NEAR(instance_centre(s, i).y, y3[i] * 2 * size.y, 1e-6);
    }
    scene_free(s);
    p.count = 7;
    s = scene_teapots_new(&p, "w", NULL);
    const double x7[] = {-1, 0, 1, -1, 0, 1, 0}, y7[] = {1, 1, 1, 0, 0, 0, -1};
    for (guint i = 0; i < 7; i++) {
        NEAR(instance_centre(s, i).x, x7[i] * 2 * size.x, 1e-6);
        NEAR(instance_centre(s, i).y, y7[i] * 2 * size.y, 1e-6);
    }
    scene_free(s);
    p.count = 5;
    /* depth: 2 columns, 3 rows about the middle one, each row shifted
     * right by shift x width and moved back by spacing x depth */
    p.layout = SCENE_TEAPOTS_DEPTH;
    p.columns = 2;
    p.across = 1.5;
    p.shift = 0.25;
    p.spacing = 3;
    p.vary_color = FALSE;
    p.color = scene_color(0.5f, 0.5f, 0);
    s = scene_teapots_new(&p, "w", NULL);
    for (guint i = 0; i < 5; i++) {
        double r = i / 2, c = i % 2;
        Vec3 at = instance_centre(s, i);
        NEAR(at.x, (c - 0.5) * 1.5 * size.x + (r - 1) * 0.25 * size.x, 1e-6);
        NEAR(at.z, -(r - 1) * 3 * size.z, 1e-6);
        NEAR(at.y, 0, 1e-6);
        SceneColor col = scene_instance(s, i)->color;
        assert_true(col.r == 0.5f && col.b == 0);
    }
    scene_free(s);
    /* columns 0 counts as 1: one diagonal row, as with 1 */
    p.columns = 0;
    Scene *zero = scene_teapots_new(&p, "w", NULL);
    p.columns = 1;
    Scene *one = scene_teapots_new(&p, "w", NULL);
    for (guint i = 0; i < 5; i++) {
        Mat4 a = scene_instance(zero, i)->xform, b = scene_instance(one, i)->xform;
        assert_memory_equal(&a, &b, sizeof a);
    }
    scene_free(zero);
    scene_free(one);
    /* one column more than teapots: clamped to the count */
    p.columns = 9;
    p.count = 3;
    s = scene_teapots_new(&p, "w", NULL);
    for (guint i = 0; i < 3; i++)
        NEAR(instance_centre(s, i).x, (i - 1.0) * 1.5 * size.x, 1e-6);
    scene_free(s);
    /* yaw: the first instance turned by yaw, each next by yaw_step more */
    p.layout = SCENE_TEAPOTS_SPREAD;
    p.yaw = 90;
    p.yaw_step = 90;
    s = scene_teapots_new(&p, "w", NULL);
    const double want_x[] = {0, -1, 0}, want_z[] = {-1, 0, 1};
    for (guint i = 0; i < 3; i++) {
        Vec4 d = mat4_apply(scene_instance(s, i)->xform, (Vec4){1, 0, 0, 0});
        NEAR(d.x, want_x[i], 1e-12);
        NEAR(d.z, want_z[i], 1e-12);
    }
    scene_free(s);
}

static void test_checks(void **st)
{
    (void)st;
    SceneTeapotsParams p = scene_teapots_defaults();
    GError *err = NULL;
    p.count = 0;
    assert_false(scene_teapots_check(&p, "w", &err));
    assert_string_equal(err->message, "w: found 0 teapots, expected 1 to 4096");
    g_clear_error(&err);
    p.count = 4097;
    assert_false(scene_teapots_check(&p, "w", &err));
    assert_string_equal(err->message, "w: found 4097 teapots, expected 1 to "
                                      "4096");
    g_clear_error(&err);
    p.count = 4096;
    p.polygons_per_teapot = 1000;
    sim_mem_set_limit(4096ull * 1000 * 512);
    assert_true(scene_teapots_check(&p, "w", NULL));
    sim_mem_set_limit(4096ull * 1000 * 512 - 1);
    assert_false(scene_teapots_check(&p, "w", &err));
    assert_true(g_str_has_prefix(err->message, "w: found 4096 teapots x 1000 "
                                               "polygons needing"));
    g_clear_error(&err);
    sim_mem_set_limit(0);
    p.count = 1;
    assert_true(scene_teapots_check(&p, "w", NULL));
    p.polygons_per_teapot = 100;
    assert_null(scene_teapots_new(&p, "w", &err));
    assert_true(g_str_has_prefix(err->message, "w: found 100 polygons"));
    g_clear_error(&err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tess_rule),
        cmocka_unit_test(test_eval),
        cmocka_unit_test(test_mesh),
        cmocka_unit_test(test_split_diagonals),
        cmocka_unit_test(test_layouts),
        cmocka_unit_test(test_checks),
    };
    return cmocka_run_group_tests_name("teapot_props", tests, NULL, NULL);
}
