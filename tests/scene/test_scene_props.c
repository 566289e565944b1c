/* test_scene_props.c — sim/scene/scene.c by its claims: a new scene's
 * defaults, instance bookkeeping, the view rule (azimuth about +y from
 * +z, elevation towards +y, up switched to -z looking straight down or
 * up; the three fits), counts and boxes over instances, and flattening
 * (each instance's colour multiplies its polygons').  Found unchecked by
 * make mutate (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/scene.h"
#include "tests/support.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

/* A unit square (a quad) and a triangle, in one mesh. */
static SceneMesh *mesh(void)
{
    SceneMesh *m = scene_mesh_new();
    scene_mesh_add_vertex(m, vec3(0, 0, 0));
    scene_mesh_add_vertex(m, vec3(1, 0, 0));
    scene_mesh_add_vertex(m, vec3(1, 1, 0));
    scene_mesh_add_vertex(m, vec3(0, 1, 0));
    scene_mesh_add_vertex(m, vec3(0, 0, 1));
    scene_mesh_add_quad(m, 0, 1, 2, 3, scene_color(0.5f, 1, 0.25f), 1);
    scene_mesh_add_tri(m, 0, 1, 4, scene_color(1, 1, 1), 2);
    return m;
}

static void test_new_and_counts(void **st)
{
    (void)st;
    Scene *s = scene_new(NULL);
    assert_string_equal(s->name, "scene");
    assert_true(s->background.r == 0 && s->background.g == 0 &&
                s->background.b == 0);
    assert_true(s->camera.eye.z == 5 && s->camera.fov_deg == 45);
    assert_null(s->path);
    assert_null(s->db);
    assert_true(scene_box_is_empty(scene_bbox(s)));
    assert_int_equal(scene_n_polys(s), 0);
    SceneCamera c = scene_camera_at(s, 3);
    assert_true(c.eye.z == 5);
    assert_int_equal(scene_add_mesh(s, mesh()), 0);
    assert_int_equal(scene_add_mesh(s, mesh()), 1);
    assert_int_equal(scene_add_instance(s, 1, mat4_translate(10, 0, 0),
                                        scene_color(1, 0.5f, 1), 4),
                     0);
    assert_int_equal(scene_add_instance(s, 0, mat4_scale(2, 3, 4),
                                        scene_color(0.5f, 1, 1), 5),
                     1);
    assert_int_equal(scene_add_instance(s, 0, mat4_identity(),
                                        scene_color(1, 1, 1), 6),
                     2);
    assert_int_equal(scene_n_instances(s), 3);
    assert_ptr_equal(scene_instance_mesh(s, 0), g_ptr_array_index(s->meshes, 1));
    assert_int_equal(scene_instance(s, 1)->tag, 5);
    assert_int_equal(scene_n_polys(s), 6);
    assert_int_equal(scene_n_triangles(s), 9);
    assert_int_equal(scene_n_vertices(s), 15);
    SceneBox b = scene_bbox(s);
    assert_true(b.min.x == 0 && b.min.y == 0 && b.min.z == 0);
    assert_true(b.max.x == 11 && b.max.y == 3 && b.max.z == 4);
    SceneBox i0 = scene_instance_bbox(s, 0), i1 = scene_instance_bbox(s, 1);
    assert_true(i0.min.x == 10 && i0.max.x == 11 && i0.max.z == 1);
    assert_true(i1.max.x == 2 && i1.max.y == 3 && i1.max.z == 4);
    scene_free(s);
    s = scene_new("named");
    assert_string_equal(s->name, "named");
    scene_add_mesh(s, mesh());
    Mat4 h = mat4_identity();
    h.m[3][3] = 2;
    scene_add_instance(s, 0, h, scene_color(1, 1, 1), 0);
    SceneBox hb = scene_instance_bbox(s, 0); /* w = 2 halves */
    assert_true(hb.max.x == 0.5 && hb.max.z == 0.5);
    h.m[3][3] = 0; /* w = 0: as they are */
    scene_add_instance(s, 0, h, scene_color(1, 1, 1), 0);
    hb = scene_instance_bbox(s, 1);
    assert_true(hb.max.x == 1 && hb.max.z == 1);
    scene_free(s);
}

static void test_flatten(void **st)
{
    (void)st;
    Scene *s = scene_new("f");
    scene_add_mesh(s, mesh());
    scene_add_instance(s, 0, mat4_identity(), scene_color(1, 0.5f, 0), 0);
    scene_add_instance(s, 0, mat4_translate(0, 0, 5),
                       scene_color(0.5f, 1, 1), 0);
    SceneMesh *f = scene_flatten(s);
    assert_int_equal(scene_mesh_n_polys(f), 4);
    assert_int_equal(scene_mesh_n_vertices(f), 10);
    SceneColor c0 = g_array_index(f->poly_color, SceneColor, 0),
               c1 = g_array_index(f->poly_color, SceneColor, 1),
               c2 = g_array_index(f->poly_color, SceneColor, 2);
    assert_true(c0.r == 0.5f && c0.g == 0.5f && c0.b == 0);
    assert_true(c1.r == 1 && c1.g == 0.5f && c1.b == 0);
    assert_true(c2.r == 0.25f && c2.g == 1 && c2.b == 0.25f);
    assert_true(scene_mesh_vertex(f, 9).z == 6);
    assert_int_equal(scene_mesh_poly(f, 3)[2], 9);
    scene_mesh_free(f);
    /* set_db / set_path keep a pointer set twice */
    SceneDb *db = scene_db_new();
    scene_set_db(s, db);
    scene_set_db(s, db);
    assert_ptr_equal(s->db, db);
    SceneCameraPath *p = scene_path_new_fixed(&s->camera, 3);
    scene_set_path(s, p);
    scene_set_path(s, p);
    assert_ptr_equal(s->path, p);
    scene_set_db(s, scene_db_new()); /* the old one freed (ASan) */
    scene_set_path(s, scene_path_new_fixed(&s->camera, 2));
    assert_int_equal(scene_path_n_frames(s->path), 2);
    scene_free(s);
}

static void test_view_directions(void **st)
{
    (void)st;
    SceneView v = scene_view_default();
    assert_int_equal(v.proj, SCENE_PERSPECTIVE);
    assert_true(v.azimuth_deg == 0 && v.elevation_deg == 0 && v.fov_deg == 45 &&
                v.fill == 1 && v.aspect == 1 && !v.fit_box && !v.fit_vertices);
    Scene *s = scene_new("v");
    scene_add_mesh(s, mesh());
    scene_add_instance(s, 0, mat4_identity(), scene_color(1, 1, 1), 0);
    const double az[] = {0, 90, 180, 0, 0, 30};
    const double el[] = {0, 0, 0, 90, -90, 45};
    for (guint i = 0; i < 6; i++) {
        v.azimuth_deg = az[i];
        v.elevation_deg = el[i];
        scene_apply_view(s, &v);
        Vec3 d = vec3_norm(vec3_sub(s->camera.eye, s->camera.target));
        double a = az[i] * G_PI / 180, e = el[i] * G_PI / 180;
        NEAR(d.x, cos(e) * sin(a), 1e-9);
        NEAR(d.y, sin(e), 1e-9);
        NEAR(d.z, cos(e) * cos(a), 1e-9);
        if (fabs(el[i]) == 90)
            assert_true(s->camera.up.x == 0 && s->camera.up.y == 0 &&
                        s->camera.up.z == -1);
        else
            assert_true(s->camera.up.y == 1 && s->camera.up.z == 0);
        /* the whole box in view */
        Mat4 vp = scene_camera_view_proj(&s->camera);
        SceneBox n = scene_box_transform(scene_bbox(s), vp);
        assert_true(n.min.x >= -1 && n.max.x <= 1 && n.min.y >= -1 &&
                    n.max.y <= 1 && n.min.z >= -1 && n.max.z <= 1);
    }
    /* up switches to -z once |dir.y| > 0.999: sin 87 deg = 0.9986 keeps
     * +y, sin 88 deg = 0.9994 does not */
    v.elevation_deg = 87;
    scene_apply_view(s, &v);
    assert_true(s->camera.up.y == 1);
    v.elevation_deg = 88;
    scene_apply_view(s, &v);
    assert_true(s->camera.up.z == -1);
    /* at this elevation sin(el) is 0.999 exactly, not above: +y stays */
    const double at[] = {87.43744126687686, -87.43744126687686};
    for (guint i = 0; i < 2; i++) {
        v.elevation_deg = at[i];
        assert_true(fabs(sin(at[i] * G_PI / 180)) == 0.999);
        scene_apply_view(s, &v);
        assert_true(s->camera.up.y == 1 && s->camera.up.z == 0);
    }
    scene_free(s);
}

/* The three fits, tightest last: sphere (distance from the box radius),
 * box corners, vertices; all keep the direction. */
static void test_view_fits(void **st)
{
    (void)st;
    Scene *s = scene_new("fit");
    scene_add_mesh(s, mesh());
    scene_add_instance(s, 0, mat4_identity(), scene_color(1, 1, 1), 0);
    scene_add_instance(s, 0, mat4_translate(3, 3, 0), scene_color(1, 1, 1), 0);
    SceneView v = scene_view_default();
    v.azimuth_deg = 20;
    v.elevation_deg = 10;
    v.fill = 0.8;
    double d[3];
    for (int k = 0; k < 3; k++) {
        v.fit_box = k == 1;
        v.fit_vertices = k == 2;
        scene_apply_view(s, &v);
        d[k] = vec3_len(vec3_sub(s->camera.eye, s->camera.target));
        Mat4 vp = scene_camera_view_proj(&s->camera);
        double hi = 0;
        for (guint i = 0; i < 2; i++) {
            const SceneMesh *m = scene_instance_mesh(s, i);
            for (guint q = 0; q < scene_mesh_n_vertices(m); q++) {
                Vec4 w = mat4_apply_point(scene_instance(s, i)->xform,
                                          scene_mesh_vertex(m, q));
                Vec4 c = mat4_apply_point(vp, vec3(w.x, w.y, w.z));
                hi = fmax(hi, fmax(fabs(c.x / c.w), fabs(c.y / c.w)));
            }
        }
        assert_true(hi <= 0.8 + 1e-9);
        if (k == 2)
            NEAR(hi, 0.8, 1e-6); /* the silhouette touches the frame */
        else
            assert_true(hi < 0.8 - 1e-3);
    }
    assert_true(d[0] > d[1] && d[1] > d[2]);
    /* an orthographic view, and an empty scene's (a unit-ish default) */
    v.proj = SCENE_ORTHOGRAPHIC;
    v.fit_vertices = FALSE;
    v.fit_box = FALSE;
    v.aspect = 2;
    scene_apply_view(s, &v);
    assert_int_equal(s->camera.proj, SCENE_ORTHOGRAPHIC);
    assert_true(s->camera.aspect == 2);
    scene_free(s);
    s = scene_new("empty");
    v = scene_view_default();
    v.fit_vertices = TRUE;
    scene_apply_view(s, &v);
    assert_true(s->camera.far > s->camera.near && s->camera.near > 0);
    SceneCamera fit_v = s->camera;
    v.fit_vertices = FALSE;
    v.fit_box = TRUE;
    scene_apply_view(s, &v);
    assert_true(s->camera.far > s->camera.near && s->camera.near > 0);
    SceneCamera fit_b = s->camera;
    /* with nothing to fit both fall back to the sphere fit of the box */
    v.fit_box = FALSE;
    scene_apply_view(s, &v);
    assert_true(support_camera_equal(&fit_v, &s->camera));
    assert_true(support_camera_equal(&fit_b, &s->camera));
    /* instances of a mesh without vertices: the vertex fit leaves the
     * unit-distance camera the view rule starts from */
    scene_add_instance(s, scene_add_mesh(s, scene_mesh_new()),
                       mat4_identity(), scene_color(1, 1, 1), 0);
    v.fit_vertices = TRUE;
    scene_apply_view(s, &v);
    assert_true(s->camera.eye.z == 1 && s->camera.target.z == 0);
    assert_true(s->camera.near == 0.1 && s->camera.far == 100);
    scene_free(s);
}

/* The box fit takes all 8 corners of every instance's box, the corners
 * at each box's minimum too: seen from -z and from below (the minimum
 * corners nearest the eye, on the silhouette; the boxes away from the
 * origin) every corner projects
 * inside +-fill, one touches it, and the extent is centred. */
static void test_fit_box_corners(void **st)
{
    (void)st;
    Scene *s = scene_new("fit");
    scene_add_mesh(s, mesh());
    scene_add_instance(s, 0, mat4_translate(4, 5, 6), scene_color(1, 1, 1), 0);
    scene_add_instance(s, 0, mat4_translate(7, 7, 7), scene_color(1, 1, 1), 0);
    SceneView v = scene_view_default();
    v.fit_box = TRUE;
    v.fill = 0.7;
    const double az[] = {180, 200, 200}, el[] = {0, -30, -30};
    for (guint k = 0; k < 3; k++) {
        v.azimuth_deg = az[k];
        v.elevation_deg = el[k];
        if (k == 2) /* one instance: fitted by its box too */
            g_array_set_size(s->instances, 1);
        scene_apply_view(s, &v);
        Mat4 vp = scene_camera_view_proj(&s->camera);
        double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
        for (guint i = 0; i < scene_n_instances(s); i++)
            for (int c = 0; c < 8; c++) {
                Vec3 off = i ? vec3(7, 7, 7) : vec3(4, 5, 6);
                Vec3 p = vec3_add(off, vec3(c & 1, (c & 2) / 2, (c & 4) / 4));
                Vec4 h = mat4_apply_point(vp, p);
                double q[2] = {h.x / h.w, h.y / h.w};
                for (int a = 0; a < 2; a++) {
                    lo[a] = fmin(lo[a], q[a]);
                    hi[a] = fmax(hi[a], q[a]);
                }
            }
        NEAR(lo[0] + hi[0], 0, 1e-6);
        NEAR(lo[1] + hi[1], 0, 1e-6);
        assert_true(hi[0] <= 0.7 + 1e-9 && hi[1] <= 0.7 + 1e-9);
        assert_true(fabs(hi[0] - 0.7) < 1e-6 || fabs(hi[1] - 0.7) < 1e-6);
    }
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_new_and_counts),
        cmocka_unit_test(test_flatten),
        cmocka_unit_test(test_view_directions),
        cmocka_unit_test(test_view_fits),
        cmocka_unit_test(test_fit_box_corners),
    };
    return cmocka_run_group_tests_name("scene_props", tests, NULL, NULL);
}
