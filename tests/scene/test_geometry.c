/* test_geometry.c — meshes, bounding boxes, cameras, camera paths, scenes.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/scene.h"

#define NEAR(a, b) assert_true(fabs((a) - (b)) < 1e-9)

static Vec3 project(Mat4 m, Vec3 p)
{
    Vec4 h = mat4_apply_point(m, p);
    return vec3(h.x / h.w, h.y / h.w, h.z / h.w);
}

static void test_box(void **st)
{
    (void)st;
    SceneBox b = scene_box_empty();
    assert_true(scene_box_is_empty(b));
    b = scene_box_add_point(b, vec3(1, 2, 3));
    assert_false(scene_box_is_empty(b));
    b = scene_box_add_point(b, vec3(-1, 0, 5));
    NEAR(b.min.x, -1);
    NEAR(b.max.z, 5);
    NEAR(scene_box_radius(b), 0.5 * sqrt(4 + 4 + 4));
    assert_true(scene_box_contains(b, vec3(0, 1, 4)));
    assert_false(scene_box_contains(b, vec3(0, 1, 6)));
    SceneBox t = scene_box_transform(b, mat4_translate(10, 0, 0));
    NEAR(t.min.x, 9);
    NEAR(t.max.x, 11);
    assert_false(scene_box_overlaps(b, t));
    SceneBox r = scene_box_transform(b, mat4_rotate(vec3(0, 0, 1), G_PI / 2));
    NEAR(r.min.x, -2);
    NEAR(r.max.y, 1);
    /* 45 degrees about z: x' = (x - y) / sqrt 2, y' = (x + y) / sqrt 2;
     * the extremes come from the off-diagonal corners (-1, 2) and (1, 0)
     * as well as the diagonal ones, so every corner must be visited */
    double h = sqrt(0.5);
    SceneBox z = scene_box_transform(b, mat4_rotate(vec3(0, 0, 1), G_PI / 4));
    NEAR(z.min.x, -3 * h);
    NEAR(z.max.x, 1 * h);
    NEAR(z.min.y, -1 * h);
    NEAR(z.max.y, 3 * h);
    NEAR(z.min.z, 3);
    NEAR(z.max.z, 5);
    /* 45 degrees about x: y' = (y - z) / sqrt 2, z' = (y + z) / sqrt 2 */
    SceneBox x = scene_box_transform(b, mat4_rotate(vec3(1, 0, 0), G_PI / 4));
    NEAR(x.min.x, -1);
    NEAR(x.max.x, 1);
    NEAR(x.min.y, -5 * h);
    NEAR(x.max.y, -1 * h);
    NEAR(x.min.z, 3 * h);
    NEAR(x.max.z, 7 * h);
    SceneBox u = scene_box_union(scene_box_empty(), b);
    NEAR(u.max.y, 2);
    assert_true(scene_box_is_empty(
        scene_box_transform(scene_box_empty(), mat4_identity())));
}

static SceneMesh *unit_quad_mesh(void)
{
    SceneMesh *m = scene_mesh_new();
    scene_mesh_add_vertex(m, vec3(0, 0, 0));
    scene_mesh_add_vertex(m, vec3(1, 0, 0));
    scene_mesh_add_vertex(m, vec3(1, 1, 0));
    scene_mesh_add_vertex(m, vec3(0, 1, 0));
    scene_mesh_add_quad(m, 0, 1, 2, 3, scene_color(1, 0, 0), 7);
    scene_mesh_add_tri(m, 0, 2, 3, scene_color(0, 1, 0), 8);
    return m;
}

static void test_mesh(void **st)
{
    (void)st;
    SceneMesh *m = unit_quad_mesh();
    assert_int_equal(scene_mesh_n_polys(m), 2);
    assert_int_equal(scene_mesh_n_triangles(m), 3);
    assert_int_equal(scene_mesh_count_ngons(m, 4), 1);
    assert_int_equal(scene_mesh_poly_len(m, 1), 3);
    assert_int_equal(scene_mesh_poly(m, 1)[1], 2);
    Vec3 n = scene_mesh_poly_normal(m, 0);
    NEAR(n.z, 1);
    scene_mesh_compute_normals(m);
    NEAR(g_array_index(m->normals, Vec3, 1).z, 1);
    assert_true(scene_mesh_validate(m, "q", NULL));
    SceneMesh *c = scene_mesh_copy(m);
    scene_mesh_append(c, m, mat4_rotate(vec3(1, 0, 0), G_PI));
    assert_int_equal(scene_mesh_n_polys(c), 4);
    assert_int_equal(scene_mesh_poly(c, 3)[0], 4);
    NEAR(g_array_index(c->normals, Vec3, 5).z, -1);
    NEAR(scene_mesh_poly_normal(c, 2).z, -1);
    assert_int_equal(g_array_index(c->poly_tag, uint32_t, 3), 8);
    g_array_index(c->idx, uint32_t, 0) = 99;
    GError *err = NULL;
    assert_false(scene_mesh_validate(c, "bad", &err));
    assert_non_null(strstr(err->message, "bad: polygon 0"));
    g_error_free(err);
    scene_mesh_free(c);
    scene_mesh_free(m);
    scene_mesh_free(NULL);
}

/* Normals under non-uniform scaling and mirrors: the normal matrix maps
 * u x v to (A u) x (A v); scene_mesh_append keeps vertex normals
 * perpendicular to the transformed surface. */
static void test_normal_matrix(void **st)
{
    (void)st;
    Mat4 a =
        mat4_mul(mat4_rotate(vec3(0.3, 1, -0.2), 0.9),
                 mat4_mul(mat4_scale(2, -0.5, 7), mat4_translate(3, 1, 2)));
    Vec3 u = vec3(0.2, -1.1, 0.7), v = vec3(1.3, 0.4, -0.6);
    Vec4 au = mat4_apply(a, (Vec4){u.x, u.y, u.z, 0});
    Vec4 av = mat4_apply(a, (Vec4){v.x, v.y, v.z, 0});
    Vec3 want = vec3_cross(vec3(au.x, au.y, au.z), vec3(av.x, av.y, av.z));
    Vec3 n = vec3_cross(u, v);
    Vec4 got = mat4_apply(mat4_normal_matrix(a), (Vec4){n.x, n.y, n.z, 0});
    NEAR(got.x, want.x);
    NEAR(got.y, want.y);
    NEAR(got.z, want.z);
    /* the plane x + y = 0 (this winding: normal along -(1, 1, 0)) scaled
     * by (1, 3, 1): x + y / 3 = 0, normal along -(3, 1, 0) */
    SceneMesh *m = scene_mesh_new();
    scene_mesh_add_vertex(m, vec3(0, 0, 0));
    scene_mesh_add_vertex(m, vec3(1, -1, 0));
    scene_mesh_add_vertex(m, vec3(0, 0, 1));
    scene_mesh_add_tri(m, 0, 1, 2, scene_color(1, 1, 1), 0);
    scene_mesh_compute_normals(m);
    SceneMesh *w = scene_mesh_new();
    scene_mesh_append(w, m, mat4_scale(1, 3, 1));
    Vec3 wn = g_array_index(w->normals, Vec3, 0);
    Vec3 pn = scene_mesh_poly_normal(w, 0);
    NEAR(wn.x, -3 / sqrt(10.0));
    NEAR(wn.y, -1 / sqrt(10.0));
    NEAR(vec3_dot(wn, pn), 1); /* agrees with the world polygon */
    scene_mesh_free(w);
    /* a mirror flips the normal with the winding */
    w = scene_mesh_new();
    scene_mesh_append(w, m, mat4_scale(-1, 1, 1));
    NEAR(vec3_dot(g_array_index(w->normals, Vec3, 0),
                  scene_mesh_poly_normal(w, 0)),
         1);
    scene_mesh_free(w);
    scene_mesh_free(m);
}

static void test_view_matrix(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    c.eye = vec3(3, 4, 5);
    c.target = vec3(1, 1, 1);
    Mat4 v = scene_camera_view(&c);
    Vec3 e = project(v, c.eye);
    NEAR(vec3_len(e), 0);
    Vec3 t = project(v, c.target);
    NEAR(t.x, 0);
    NEAR(t.y, 0);
    NEAR(t.z, -vec3_len(vec3(2, 3, 4)));
    /* A point above the target along world up projects to +y. */
    Vec3 up = project(v, vec3(1, 2, 1));
    assert_true(up.y > 0);
}

static void test_perspective(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    c.eye = vec3(0, 0, 0);
    c.target = vec3(0, 0, -1);
    c.fov_deg = 90;
    c.near = 1;
    c.far = 10;
    c.aspect = 2;
    Mat4 vp = scene_camera_view_proj(&c);
    NEAR(project(vp, vec3(0, 0, -1)).z, -1);
    NEAR(project(vp, vec3(0, 0, -10)).z, 1);
    /* 90° vertical: y = -z is the top edge; x = -2z the right edge. */
    NEAR(project(vp, vec3(0, 3, -3)).y, 1);
    NEAR(project(vp, vec3(6, 0, -3)).x, 1);
    c.proj = SCENE_ORTHOGRAPHIC;
    c.height = 4;
    vp = scene_camera_view_proj(&c);
    NEAR(project(vp, vec3(4, 2, -5.5)).x, 1);
    NEAR(project(vp, vec3(4, 2, -5.5)).y, 1);
    NEAR(project(vp, vec3(4, 2, -5.5)).z, 0);
    NEAR(project(vp, vec3(0, 0, -10)).z, 1);
}

static void test_fit(void **st)
{
    (void)st;
    SceneBox b = {{-1, -1, -1}, {3, 1, 1}};
    SceneCamera c = scene_camera_default();
    c.aspect = 0.5;
    scene_camera_fit(&c, b, 1.0);
    Mat4 vp = scene_camera_view_proj(&c);
    double maxx = 0;
    for (int i = 0; i < 8; i++) {
        Vec3 p = vec3(i & 1 ? 3 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        Vec3 q = project(vp, p);
        assert_true(fabs(q.x) <= 1 && fabs(q.y) <= 1);
        assert_true(q.z >= -1 && q.z <= 1);
        maxx = fmax(maxx, fabs(q.x));
    }
    assert_true(maxx > 0.5); /* fills the narrow direction */
    c.proj = SCENE_ORTHOGRAPHIC;
    c.aspect = 1;
    scene_camera_fit(&c, b, 0.5);
    NEAR(c.height, 4 * scene_box_radius(b));
}

/* Box / point fits: every point inside [-fill, fill], one touching. */
static void test_fit_points(void **st)
{
    (void)st;
    Vec3 pts[6] = {{0, 0, 0},    {10, 0, -30}, {2, 3, 1},
                   {-1, -2, -4}, {12, 1, -31}, {5, 5, -10}};
    for (int proj = 0; proj < 2; proj++) {
        SceneCamera c = scene_camera_default();
        c.proj = proj ? SCENE_ORTHOGRAPHIC : SCENE_PERSPECTIVE;
        c.aspect = 1.5;
        c.eye = vec3(0, 3, 10);
        scene_camera_fit_points(&c, pts, 6, 0.8);
        Mat4 vp = scene_camera_view_proj(&c);
        double m = 0, lo[2] = {1, 1}, hi[2] = {-1, -1};
        for (int i = 0; i < 6; i++) {
            Vec3 q = project(vp, pts[i]);
            assert_true(fabs(q.x) <= 0.8 + 1e-9 && fabs(q.y) <= 0.8 + 1e-9);
            assert_true(q.z > -1 && q.z < 1);
            m = fmax(m, fmax(fabs(q.x), fabs(q.y)));
            lo[0] = fmin(lo[0], q.x), hi[0] = fmax(hi[0], q.x);
            lo[1] = fmin(lo[1], q.y), hi[1] = fmax(hi[1], q.y);
        }
        assert_true(m > 0.8 - 1e-6);
        /* perspective: the extent is re-centred on both axes (to within
         * the last distance step's shift, here 0.05 of the half-screen) */
        if (!proj)
            assert_true(fabs(lo[0] + hi[0]) < 0.15 &&
                        fabs(lo[1] + hi[1]) < 0.15);
    }
    SceneBox b = {{-1, -1, -1}, {1, 2, 3}};
    SceneCamera c = scene_camera_default();
    scene_camera_fit_box(&c, b, 1.0);
    Vec3 q = project(scene_camera_view_proj(&c), b.max);
    assert_true(fabs(q.x) <= 1 + 1e-9 && fabs(q.y) <= 1 + 1e-9);
}

/* A fixed path gives its camera at every frame; its length can change. */
static void test_fixed_path(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    c.eye = vec3(1, 2, 3);
    SceneCameraPath *p = scene_path_new_fixed(&c, 5);
    assert_int_equal(scene_path_kind(p), SCENE_PATH_FIXED);
    assert_int_equal(scene_path_n_frames(p), 5);
    NEAR(scene_path_camera(p, 3.5).eye.z, 3);
    scene_path_set_n_frames(p, 9);
    assert_int_equal(scene_path_n_frames(p), 9);
    scene_path_free(p);
}

static void test_orbit(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    c.eye = vec3(10, 2, 0);
    c.target = vec3(0, 2, 0);
    SceneCameraPath *p =
        scene_path_new_orbit(&c, vec3(0, 0, 0), vec3(0, 1, 0), 0, 90, 4);
    assert_int_equal(scene_path_n_frames(p), 4);
    SceneCamera f1 = scene_path_camera(p, 1);
    NEAR(f1.eye.x, 0);
    NEAR(f1.eye.z, -10);
    NEAR(f1.eye.y, 2);
    NEAR(f1.target.y, 2);
    NEAR(f1.up.y, 1);
    SceneCamera f4 = scene_path_camera(p, 4);
    NEAR(f4.eye.x, 10);
    NEAR(vec3_len(scene_path_camera(p, 0.5).eye), vec3_len(c.eye));
    scene_path_free(p);
}

static void test_keyframes(void **st)
{
    (void)st;
    SceneCamera a = scene_camera_default(), b = a, d = a;
    b.eye = vec3(10, 0, 5);
    b.fov_deg = 65;
    d.eye = vec3(10, 10, 5);
    SceneCameraPath *p = scene_path_new_keyframes(SCENE_INTERP_LINEAR);
    scene_path_add_key(p, 0, &a);
    scene_path_add_key(p, 10, &b);
    scene_path_add_key(p, 20, &d);
    assert_int_equal(scene_path_n_frames(p), 21);
    assert_int_equal(scene_path_n_keys(p), 3);
    SceneCamera m = scene_path_camera(p, 5);
    NEAR(m.eye.x, 5);
    NEAR(m.fov_deg, 55);
    NEAR(scene_path_camera(p, 15).eye.y, 5);
    NEAR(scene_path_camera(p, -3).eye.x, 0);
    NEAR(scene_path_camera(p, 99).eye.y, 10);
    scene_path_free(p);
    p = scene_path_new_keyframes(SCENE_INTERP_CATMULL_ROM);
    scene_path_add_key(p, 0, &a);
    scene_path_add_key(p, 10, &b);
    scene_path_add_key(p, 20, &d);
    NEAR(scene_path_camera(p, 10).eye.x, 10); /* interpolates keys */
    NEAR(scene_path_camera(p, 0).eye.x, 0);
    /* Curved: not the straight line between keys 0 and 1. */
    assert_true(scene_path_camera(p, 5).eye.y < -1e-3);
    scene_path_free(p);
}

static void test_scene(void **st)
{
    (void)st;
    Scene *s = scene_new("t");
    guint m = scene_add_mesh(s, unit_quad_mesh());
    scene_add_instance(s, m, mat4_identity(), scene_color(1, 1, 1), 0);
    scene_add_instance(s, m, mat4_translate(5, 0, 0), scene_color(.5, 1, 1), 1);
    assert_int_equal(scene_n_polys(s), 4);
    assert_int_equal(scene_n_triangles(s), 6);
    SceneBox b = scene_bbox(s);
    NEAR(b.max.x, 6);
    NEAR(scene_instance_bbox(s, 1).min.x, 5);
    SceneMesh *f = scene_flatten(s);
    assert_int_equal(scene_mesh_n_polys(f), 4);
    assert_true(fabs(g_array_index(f->poly_color, SceneColor, 2).r - .5) <
                1e-6);
    scene_mesh_free(f);
    SceneCamera c = scene_camera_at(s, 3);
    NEAR(c.eye.z, 5);
    scene_set_path(
        s, scene_path_new_orbit(&c, vec3(0, 0, 0), vec3(0, 1, 0), 0, 180, 2));
    NEAR(scene_camera_at(s, 1).eye.z, -5);
    assert_int_equal(scene_n_vertices(s), 8);
    /* looking straight down (and up): up turns to -z, the view stays
     * finite and the scene inside it */
    for (int sign = -1; sign <= 1; sign += 2) {
        SceneView v = scene_view_default();
        v.elevation_deg = 90 * sign;
        scene_apply_view(s, &v);
        NEAR(s->camera.up.z, -1);
        Vec3 q = project(scene_camera_view_proj(&s->camera), vec3(6, 1, 0));
        assert_true(fabs(q.x) <= 1 && fabs(q.y) <= 1 && fabs(q.z) <= 1);
        NEAR(s->camera.eye.y - s->camera.target.y,
             sign * vec3_len(vec3_sub(s->camera.eye, s->camera.target)));
    }
    scene_free(s);
    scene_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box),
        cmocka_unit_test(test_mesh),
        cmocka_unit_test(test_view_matrix),
        cmocka_unit_test(test_perspective),
        cmocka_unit_test(test_fit),
        cmocka_unit_test(test_fit_points),
        cmocka_unit_test(test_fixed_path),
        cmocka_unit_test(test_orbit),
        cmocka_unit_test(test_keyframes),
        cmocka_unit_test(test_scene),
        cmocka_unit_test(test_normal_matrix),
    };
    return cmocka_run_group_tests_name("geometry", tests, NULL, NULL);
}
