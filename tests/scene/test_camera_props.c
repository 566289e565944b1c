/* test_camera_props.c — sim/scene/camera.c by its properties: the default
 * camera of camera.h, the view and projection matrices of gluLookAt /
 * glFrustum / glOrtho checked on points (eye to the origin, near and far
 * planes to z = -1 and +1, the frustum's edges to x, y = +-1), the fits
 * (the bounding sphere tangent to the narrower half-angle, every point
 * inside +-fill and the extent centred in x and in y, near and far
 * bracketing the scene), and the paths (orbits, linear and Catmull-Rom
 * keyframes against the spline's matrix form, clamping at the ends, frame
 * counts).  Found unchecked by make mutate (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/camera.h"
#include "tests/support.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static Vec3 ndc(Mat4 vp, Vec3 p)
{
    Vec4 h = mat4_apply_point(vp, p);
    return vec3(h.x / h.w, h.y / h.w, h.z / h.w);
}

static void test_default(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    assert_int_equal(c.proj, SCENE_PERSPECTIVE);
    assert_true(c.eye.x == 0 && c.eye.y == 0 && c.eye.z == 5);
    assert_true(c.target.x == 0 && c.target.y == 0 && c.target.z == 0);
    assert_true(c.up.x == 0 && c.up.y == 1 && c.up.z == 0);
    assert_true(c.fov_deg == 45 && c.height == 2 && c.near == 0.1 &&
                c.far == 100 && c.aspect == 1);
}

/* The view matrix takes the eye to the origin, the target onto -z at its
 * distance, up to +y and the right-hand side to +x. */
static void test_view(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    c.eye = vec3(3, -2, 7);
    c.target = vec3(3, -2, 1); /* looking along -z from 6 away */
    c.up = vec3(0, 2, 0);
    Mat4 v = scene_camera_view(&c);
    Vec4 e = mat4_apply_point(v, c.eye), t = mat4_apply_point(v, c.target);
    NEAR(e.x, 0, 1e-12);
    NEAR(e.y, 0, 1e-12);
    NEAR(e.z, 0, 1e-12);
    NEAR(t.x, 0, 1e-12);
    NEAR(t.y, 0, 1e-12);
    NEAR(t.z, -6, 1e-12);
    Vec4 r = mat4_apply_point(v, vec3(4, 0, 1)); /* right of and above */
    NEAR(r.x, 1, 1e-12);
    NEAR(r.y, 2, 1e-12);
    NEAR(r.z, -6, 1e-12);
    /* a sideways view: eye on +x looking at the origin, up +y */
    c.eye = vec3(5, 0, 0);
    c.target = vec3(0, 0, 0);
    c.up = vec3(0, 1, 0);
    v = scene_camera_view(&c);
    Vec4 p = mat4_apply_point(v, vec3(0, 1, -1)); /* -z is screen right */
    NEAR(p.x, 1, 1e-12);
    NEAR(p.y, 1, 1e-12);
    NEAR(p.z, -5, 1e-12);
}

/* Perspective: the near plane maps to z = -1, the far one to +1, a point
 * on the frustum's top edge to y = 1 and on its right edge to x = 1. */
static void test_perspective(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    c.fov_deg = 60;
    c.aspect = 2;
    c.near = 1;
    c.far = 11;
    Mat4 vp = scene_camera_view_proj(&c);
    double t = tan(30 * G_PI / 180);
    Vec3 n = ndc(vp, vec3(0, 0, 4)), f = ndc(vp, vec3(0, 0, -6));
    NEAR(n.z, -1, 1e-12);
    NEAR(f.z, 1, 1e-12);
    Vec3 top = ndc(vp, vec3(0, 3 * t, 2)); /* depth 3 */
    NEAR(top.y, 1, 1e-12);
    NEAR(top.x, 0, 1e-12);
    Vec3 right = ndc(vp, vec3(2 * 3 * t, 0, 2));
    NEAR(right.x, 1, 1e-12);
    Vec3 left = ndc(vp, vec3(-2 * 5 * t, -5 * t, 0)); /* depth 5 */
    NEAR(left.x, -1, 1e-12);
    NEAR(left.y, -1, 1e-12);
    Vec4 h = mat4_apply_point(vp, vec3(0, 0, 2));
    NEAR(h.w, 3, 1e-12); /* w is the depth */
}

static void test_orthographic(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    c.proj = SCENE_ORTHOGRAPHIC;
    c.height = 4;
    c.aspect = 1.5;
    c.near = 2;
    c.far = 8;
    Mat4 vp = scene_camera_view_proj(&c);
    Vec3 n = ndc(vp, vec3(0, 0, 3)), f = ndc(vp, vec3(0, 0, -3));
    NEAR(n.z, -1, 1e-12);
    NEAR(f.z, 1, 1e-12);
    Vec3 corner = ndc(vp, vec3(3, -2, 0));
    NEAR(corner.x, 1, 1e-12);
    NEAR(corner.y, -1, 1e-12);
    Vec4 h = mat4_apply_point(vp, vec3(1, 1, -1));
    NEAR(h.w, 1, 1e-12);
}

static SceneBox box(Vec3 lo, Vec3 hi)
{
    return scene_box_add_point(scene_box_add_point(scene_box_empty(), lo), hi);
}

/* scene_camera_fit: the bounding sphere is tangent to the narrower
 * half-angle at fill 1 (sin = r / d), centred on the box, with near and
 * far 1 % beyond the sphere; the direction of the eye is kept. */
static void test_fit_sphere(void **st)
{
    (void)st;
    SceneBox b = box(vec3(1, 2, 3), vec3(3, 6, 7)); /* centre (2, 4, 5) */
    double r = scene_box_radius(b);
    for (int k = 0; k < 2; k++) {
        SceneCamera c = scene_camera_default();
        c.eye = vec3(0, 0, 10);
        c.target = vec3(0, 0, 9); /* direction +z */
        c.fov_deg = 40;
        c.aspect = k ? 0.5 : 2; /* the horizontal half-angle is narrower */
        scene_camera_fit(&c, b, 0.5);
        double half = 20 * G_PI / 180;
        double hx = atan(tan(half) * c.aspect);
        double d = vec3_len(vec3_sub(c.eye, c.target));
        NEAR(r / d, 0.5 * sin(k ? hx : half), 1e-12);
        assert_true(c.target.x == 2 && c.target.y == 4 && c.target.z == 5);
        NEAR(c.eye.x, 2, 1e-12);
        NEAR(c.eye.y, 4, 1e-12);
        assert_true(c.eye.z > 5);
        NEAR(c.far, d + 1.01 * r, 1e-9);
        NEAR(c.near, d - 1.01 * r, 1e-9);
    }
    /* eye = target: the eye goes to +z; a close fit clamps near at
     * far / 1000 */
    SceneCamera c = scene_camera_default();
    c.eye = c.target = vec3(0, 0, 0);
    c.fov_deg = 170;
    scene_camera_fit(&c, b, 4);
    NEAR(c.eye.x, 2, 1e-12);
    NEAR(c.eye.y, 4, 1e-12);
    assert_true(c.eye.z > 5);
    assert_true(c.near == c.far * 1e-3);
    /* orthographic: height 2 r / fill, over the aspect when below 1; the
     * eye 2 r away */
    for (int k = 0; k < 2; k++) {
        c = scene_camera_default();
        c.proj = SCENE_ORTHOGRAPHIC;
        c.aspect = k ? 0.5 : 1;
        scene_camera_fit(&c, b, 0.8);
        NEAR(c.height, 2 * r / 0.8 / (k ? 0.5 : 1), 1e-9);
        NEAR(vec3_len(vec3_sub(c.eye, c.target)), 2 * r, 1e-9);
        NEAR(c.far, 3.01 * r, 1e-9);
        NEAR(c.near, 0.99 * r, 1e-9);
    }
}

/* Points projected through a fitted camera: all inside +-fill, touching
 * it on one axis, the extent centred in x and in y. */
static void check_fit(const SceneCamera *c, const Vec3 *p, guint n,
                      double fill)
{
    Mat4 vp = scene_camera_view_proj(c);
    double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
    for (guint i = 0; i < n; i++) {
        Vec3 q = ndc(vp, p[i]);
        assert_true(q.z > -1 && q.z < 1); /* between near and far */
        lo[0] = fmin(lo[0], q.x), hi[0] = fmax(hi[0], q.x);
        lo[1] = fmin(lo[1], q.y), hi[1] = fmax(hi[1], q.y);
    }
    NEAR(lo[0] + hi[0], 0, 1e-6);
    NEAR(lo[1] + hi[1], 0, 1e-6);
    assert_true(hi[0] <= fill + 1e-9 && hi[1] <= fill + 1e-9);
    assert_true(fabs(hi[0] - fill) < 1e-6 || fabs(hi[1] - fill) < 1e-6);
}

static void test_fit_points(void **st)
{
    (void)st;
    /* tall (y bounds) and wide (x bounds) point sets, off-centre, with
     * depth; perspective and orthographic */
    const Vec3 tall[] = {{0, 0, 0}, {1, 9, 0}, {0.5, -3, 2}, {2, 1, -1}};
    const Vec3 wide[] = {{-7, 0, 0}, {9, 1, 1}, {0, -1, -2}, {3, 2, 0}};
    const Vec3 *sets[] = {tall, wide};
    for (int s = 0; s < 2; s++)
        for (int proj = 0; proj < 2; proj++) {
            SceneCamera c = scene_camera_default();
            c.proj = proj ? SCENE_ORTHOGRAPHIC : SCENE_PERSPECTIVE;
            c.eye = vec3(1, 2, 30);
            c.target = vec3(1, 2, 0);
            c.aspect = 1.25;
            scene_camera_fit_points(&c, sets[s], 4, 0.75);
            check_fit(&c, sets[s], 4, 0.75);
            Vec3 d = vec3_norm(vec3_sub(c.eye, c.target));
            NEAR(d.z, 1, 1e-12); /* the view direction is kept */
        }
    /* eye = target: looks along -z from +z */
    SceneCamera c = scene_camera_default();
    c.eye = c.target = vec3(4, 4, 4);
    scene_camera_fit_points(&c, tall, 4, 1);
    check_fit(&c, tall, 4, 1);
    assert_true(c.eye.z > c.target.z);
    NEAR(c.eye.x, c.target.x, 1e-12);
    /* a box's eight corners */
    SceneBox b = box(vec3(-1, 0, 2), vec3(3, 1, 4));
    c = scene_camera_default();
    c.eye = vec3(5, 5, 5);
    scene_camera_fit_box(&c, b, 0.5);
    Vec3 k[8];
    for (int i = 0; i < 8; i++)
        k[i] = vec3(i & 1 ? 3 : -1, i & 2 ? 1 : 0, i & 4 ? 4 : 2);
    check_fit(&c, k, 8, 0.5);
    /* one point: a distance of at least 1e-9, the point in the centre */
    c = scene_camera_default();
    Vec3 one = vec3(2, 3, 4);
    scene_camera_fit_points(&c, &one, 1, 1);
    assert_true(c.target.x == 2 && c.target.y == 3 && c.target.z == 4);
    assert_true(c.far > c.near && c.near > 0);
}

/* fit_box is fit_points on the box's 8 corners, whichever corner is on
 * the silhouette: seen from -z the near face (z = min, corner 0 among
 * them) bounds the view, seen from +z the far one does not. */
static void test_fit_box_corners(void **st)
{
    (void)st;
    SceneBox b = box(vec3(-1, 0, 2), vec3(3, 1, 4));
    Vec3 k[8];
    for (int i = 0; i < 8; i++)
        k[i] = vec3(i & 1 ? 3 : -1, i & 2 ? 1 : 0, i & 4 ? 4 : 2);
    const Vec3 eyes[] = {{1, 0.5, -20}, {1, 0.5, 20}, {-9, -8, -7}};
    for (int proj = 0; proj < 2; proj++)
        for (guint e = 0; e < 3; e++) {
            SceneCamera a = scene_camera_default(), p;
            a.proj = proj ? SCENE_ORTHOGRAPHIC : SCENE_PERSPECTIVE;
            a.eye = eyes[e];
            a.target = vec3(1, 0.5, 3);
            p = a;
            scene_camera_fit_box(&a, b, 0.6);
            scene_camera_fit_points(&p, k, 8, 0.6);
            assert_true(support_camera_equal(&a, &p));
            if (!proj)
                check_fit(&a, k, 8, 0.6);
        }
}

/* The orthographic point fit weighs every point, the first too: the eye
 * goes 2 r from the box centre, r the largest distance from it, here the
 * first point's alone (sqrt 75 from (5, 5, 5); the others sqrt 50). */
static void test_fit_ortho_first_point(void **st)
{
    (void)st;
    const Vec3 pts[] = {{10, 10, 10}, {0, 0, 5}, {5, 0, 0}, {0, 5, 0}};
    SceneCamera c = scene_camera_default();
    c.proj = SCENE_ORTHOGRAPHIC;
    c.aspect = 2;
    scene_camera_fit_points(&c, pts, 4, 0.5);
    double r = sqrt(75.0);
    NEAR(vec3_len(vec3_sub(c.eye, c.target)), 2 * r, 1e-12);
    NEAR(c.far, 2 * r + 1.01 * r, 1e-9);
    NEAR(c.height, 2 * 5 / 0.5, 1e-12); /* 5 up and down, 5 / 2 across */
}

/* Orbits: frame f turns the base camera by deg0 + f * step about the
 * axis through the centre, eye, target and up alike. */
static void test_orbit(void **st)
{
    (void)st;
    SceneCamera b = scene_camera_default();
    b.eye = vec3(1, 0, 4);
    b.target = vec3(1, 0, 0);
    SceneCameraPath *p =
        scene_path_new_orbit(&b, vec3(1, 0, 0), vec3(0, 2, 0), 90, 45, 8);
    assert_int_equal(scene_path_kind(p), SCENE_PATH_ORBIT);
    assert_int_equal(scene_path_n_frames(p), 8);
    SceneCamera c0 = scene_path_camera(p, 0), c2 = scene_path_camera(p, 2);
    NEAR(c0.eye.x, 5, 1e-12); /* +z turned 90 degrees about +y: +x */
    NEAR(c0.eye.z, 0, 1e-12);
    NEAR(c2.eye.x, 1, 1e-12); /* 180 degrees */
    NEAR(c2.eye.z, -4, 1e-12);
    NEAR(c2.target.x, 1, 1e-12);
    NEAR(c2.up.y, 1, 1e-12);
    /* re-based: frame 0 becomes the camera given */
    SceneCamera want = b;
    want.eye = vec3(1, 3, 4);
    want.fov_deg = 30;
    scene_path_set_base(p, &want);
    c0 = scene_path_camera(p, 0);
    NEAR(c0.eye.x, 1, 1e-12);
    NEAR(c0.eye.y, 3, 1e-12);
    NEAR(c0.eye.z, 4, 1e-12);
    assert_true(c0.fov_deg == 30);
    SceneCamera c1 = scene_path_camera(p, 1); /* 45 degrees on */
    NEAR(c1.eye.x, 1 + 4 * sin(G_PI / 4), 1e-12);
    NEAR(c1.eye.z, 4 * cos(G_PI / 4), 1e-12);
    scene_path_free(p);
    /* fixed: the same camera every frame, frames at least 1 */
    p = scene_path_new_fixed(&b, 0);
    assert_int_equal(scene_path_n_frames(p), 1);
    scene_path_set_n_frames(p, 0);
    assert_int_equal(scene_path_n_frames(p), 1);
    scene_path_set_n_frames(p, 9);
    assert_int_equal(scene_path_n_frames(p), 9);
    scene_path_set_base(p, &want);
    c1 = scene_path_camera(p, 5);
    assert_true(c1.eye.y == 3 && c1.fov_deg == 30);
    assert_int_equal(scene_path_n_keys(p), 0);
    scene_path_free(p);
}

/* The uniform Catmull-Rom spline in its matrix form (Catmull & Rom 1974):
 * 0.5 [1 t t^2 t^3] M [p0 p1 p2 p3]. */
static double cr(double p0, double p1, double p2, double p3, double t)
{
    return 0.5 * (2 * p1 + (-p0 + p2) * t +
                  (2 * p0 - 5 * p1 + 4 * p2 - p3) * t * t +
                  (-p0 + 3 * p1 - 3 * p2 + p3) * t * t * t);
}

static SceneCameraPath *keys(SceneInterp interp, const double *xs,
                             const double *frames, guint n)
{
    SceneCameraPath *p = scene_path_new_keyframes(interp);
    for (guint i = 0; i < n; i++) {
        SceneCamera c = scene_camera_default();
        c.eye = vec3(xs[i], 2 * xs[i], 5);
        c.target = vec3(xs[i], 0, -xs[i]);
        c.fov_deg = 10 + xs[i];
        c.height = 1 + xs[i];
        c.near = 0.5 + xs[i];
        c.far = 100 + xs[i];
        c.aspect = 1 + xs[i];
        c.up = vec3(0, 1, xs[i]);
        scene_path_add_key(p, frames[i], &c);
    }
    return p;
}

static void test_keyframes(void **st)
{
    (void)st;
    const double xs[] = {0, 1, 3, 6, 7};
    const double fr[] = {0, 2, 4, 6, 8.5};
    SceneCameraPath *p = keys(SCENE_INTERP_CATMULL_ROM, xs, fr, 5);
    assert_int_equal(scene_path_n_keys(p), 5);
    assert_int_equal(scene_path_n_frames(p), 10); /* ceil(8.5) + 1 */
    for (guint seg = 0; seg < 4; seg++)
        for (int q = 0; q <= 3; q++) {
            double t = q / 4.0;
            double f = fr[seg] + t * (fr[seg + 1] - fr[seg]);
            SceneCamera c = scene_path_camera(p, f);
            double p0 = xs[seg ? seg - 1 : 0], p3 = xs[seg + 2 < 5 ? seg + 2 : 4];
            double want = cr(p0, xs[seg], xs[seg + 1], p3, t);
            NEAR(c.eye.x, want, 1e-12);
            NEAR(c.eye.y, 2 * want, 1e-12);
            NEAR(c.target.z, -want, 1e-12);
            double lin = xs[seg] + t * (xs[seg + 1] - xs[seg]);
            NEAR(c.fov_deg, 10 + lin, 1e-12); /* the rest is linear */
            NEAR(c.height, 1 + lin, 1e-12);
            NEAR(c.near, 0.5 + lin, 1e-12);
            NEAR(c.far, 100 + lin, 1e-12);
            NEAR(c.aspect, 1 + lin, 1e-12);
            NEAR(c.up.z, lin, 1e-12);
        }
    /* before the first key and after the last: the end keys */
    SceneCamera a = scene_path_camera(p, -3), z = scene_path_camera(p, 99);
    assert_true(a.eye.x == 0 && z.eye.x == 7 && z.fov_deg == 17);
    scene_path_free(p);
    p = keys(SCENE_INTERP_LINEAR, xs, fr, 5);
    for (guint seg = 0; seg < 4; seg++)
        for (int q = 0; q <= 3; q++) {
            double t = q / 4.0;
            double f = fr[seg] + t * (fr[seg + 1] - fr[seg]);
            SceneCamera c = scene_path_camera(p, f);
            double lin = xs[seg] + t * (xs[seg + 1] - xs[seg]);
            NEAR(c.eye.x, lin, 1e-12);
            NEAR(c.target.z, -lin, 1e-12);
        }
    scene_path_free(p);
    /* one key: that camera everywhere; frames from the key's frame */
    const double one[] = {4}, at[] = {3};
    p = keys(SCENE_INTERP_CATMULL_ROM, one, at, 1);
    assert_int_equal(scene_path_n_frames(p), 4);
    assert_true(scene_path_camera(p, 7).eye.x == 4);
    assert_true(scene_path_camera(p, 0).eye.x == 4);
    scene_path_free(p);
    /* a whole last frame: frame 2 needs 3 frames, 2.01 needs 4 */
    const double two[] = {0, 1}, f2[] = {0, 2};
    p = keys(SCENE_INTERP_LINEAR, two, f2, 2);
    assert_int_equal(scene_path_n_frames(p), 3);
    scene_path_set_n_frames(p, 2); /* lowering is allowed explicitly */
    assert_int_equal(scene_path_n_frames(p), 2);
    scene_path_free(p);
    const double f3[] = {0, 2.01};
    p = keys(SCENE_INTERP_LINEAR, two, f3, 2);
    assert_int_equal(scene_path_n_frames(p), 4);
    scene_path_free(p);
}

/* Exactly at a key's frame the path gives that key, down to the fields
 * it does not interpolate (the projection, which alternates here): the
 * segment starting there, or the last key at the last frame.  Two keys
 * interpolate like more. */
static void test_key_edges(void **st)
{
    (void)st;
    const double xs[] = {0, 1, 3, 6, 7};
    const double fr[] = {0, 2, 4, 6, 8.5};
    for (int interp = 0; interp < 2; interp++) {
        SceneCameraPath *p = scene_path_new_keyframes(
            interp ? SCENE_INTERP_CATMULL_ROM : SCENE_INTERP_LINEAR);
        for (guint i = 0; i < 5; i++) {
            SceneCamera c = scene_camera_default();
            c.proj = i % 2 ? SCENE_ORTHOGRAPHIC : SCENE_PERSPECTIVE;
            c.eye = vec3(xs[i], 1, 5);
            scene_path_add_key(p, fr[i], &c);
        }
        for (guint i = 0; i < 5; i++) {
            SceneCamera c = scene_path_camera(p, fr[i]);
            assert_int_equal(c.proj, i % 2 ? SCENE_ORTHOGRAPHIC
                                           : SCENE_PERSPECTIVE);
            assert_true(c.eye.x == xs[i]);
            /* just before the key: still the segment before it */
            if (i > 0)
                assert_int_equal(scene_path_camera(p, fr[i] - 1e-9).proj,
                                 (i - 1) % 2 ? SCENE_ORTHOGRAPHIC
                                             : SCENE_PERSPECTIVE);
        }
        scene_path_free(p);
    }
    /* a keyframed path starts at 1 frame: no keys, or one at frame 0 */
    SceneCameraPath *none = scene_path_new_keyframes(SCENE_INTERP_LINEAR);
    assert_int_equal(scene_path_n_frames(none), 1);
    SceneCamera k0 = scene_camera_default();
    scene_path_add_key(none, 0, &k0);
    assert_int_equal(scene_path_n_frames(none), 1);
    scene_path_free(none);
    const double two[] = {0, 4}, f2[] = {1, 3};
    SceneCameraPath *p = keys(SCENE_INTERP_LINEAR, two, f2, 2);
    SceneCamera mid = scene_path_camera(p, 2);
    NEAR(mid.eye.x, 2, 1e-12);
    NEAR(mid.fov_deg, 12, 1e-12);
    scene_path_free(p);
    p = keys(SCENE_INTERP_CATMULL_ROM, two, f2, 2);
    mid = scene_path_camera(p, 1.5); /* ends doubled: p0 = p1, p3 = p2 */
    NEAR(mid.eye.x, cr(0, 0, 4, 4, 0.25), 1e-12);
    scene_path_free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default),
        cmocka_unit_test(test_view),
        cmocka_unit_test(test_perspective),
        cmocka_unit_test(test_orthographic),
        cmocka_unit_test(test_fit_sphere),
        cmocka_unit_test(test_fit_points),
        cmocka_unit_test(test_fit_box_corners),
        cmocka_unit_test(test_fit_ortho_first_point),
        cmocka_unit_test(test_orbit),
        cmocka_unit_test(test_keyframes),
        cmocka_unit_test(test_key_edges),
    };
    return cmocka_run_group_tests_name("camera_props", tests, NULL, NULL);
}
