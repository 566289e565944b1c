/* test_scene_cfg_values.c — the defaults and edge values of a `scene:`
 * section (sim/scene/scene_cfg.c) pinned by what they produce: seed 0
 * accepted by every seeded generator and a PPHIGS database's default
 * seed being 1; a placement without `at` at the origin; a view's default
 * fit being the sphere (box and vertices differ from it); a camera one
 * unit from its target accepted; keyframes interpolated linearly unless
 * asked; the scene camera set to a new path's frame 0.  Run from the
 * repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/scene_cfg.h"
#include "tests/support.h"

static Scene *from_text(const char *yaml)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(yaml, "v.yaml", &err);
    assert_non_null(root);
    Scene *s = scene_from_cfg(cfg_get(root, "scene"), &err);
    if (!s)
        print_error("%s\n%s", err->message, yaml);
    assert_non_null(s);
    cfg_free(root);
    return s;
}

static gboolean same_cam(SceneCamera a, SceneCamera b)
{
    return memcmp(&a.eye, &b.eye, sizeof a.eye) == 0 &&
           memcmp(&a.target, &b.target, sizeof a.target) == 0 &&
           a.near == b.near && a.far == b.far && a.height == b.height;
}

/* Seed 0 is a seed like any other for every seeded generator. */
static void test_seed_zero(void **st)
{
    (void)st;
    const char *y[] = {
        "scene: {generator: isosurface, grid: 8, seed: 0}\n",
        "scene: {generator: nurbs, patches_u: 1, patches_v: 1, seed: 0}\n",
        "scene: {generator: march, grid: 8, cell: 4, seed: 0}\n",
        "scene: {generator: space_station, size: 10, polygons: 4, "
        "attributes: 2, seed: 0}\n",
    };
    for (guint i = 0; i < G_N_ELEMENTS(y); i++)
        scene_free(from_text(y[i]));
}

/* A PPHIGS database without `seed` is the one of seed 1. */
static void test_pphigs_default_seed(void **st)
{
    (void)st;
    const char *fmt = "scene: {generator: space_station, size: 10, "
                      "polygons: 6, attributes: 3%s}\n";
    const char *seeds[] = {"", ", seed: 1", ", seed: 2"};
    Vec3 first[3];
    for (guint i = 0; i < 3; i++) {
        char *t = g_strdup_printf(fmt, seeds[i]);
        Scene *s = from_text(t);
        first[i] = scene_mesh_vertex(scene_instance_mesh(s, 0), 0);
        scene_free(s);
        g_free(t);
    }
    assert_memory_equal(&first[0], &first[1], sizeof(Vec3));
    assert_memory_not_equal(&first[0], &first[2], sizeof(Vec3));
}

/* A placement without `at` stands at the origin, like at: [0, 0, 0]. */
static void test_placement_default_at(void **st)
{
    (void)st;
    Scene *a = from_text("scene: {generator: teapots, placements: "
                         "[{yaw: 30}]}\n");
    Scene *b = from_text("scene: {generator: teapots, placements: "
                         "[{at: [0, 0, 0], yaw: 30}]}\n");
    SceneBox ba = scene_instance_bbox(a, 0), bb = scene_instance_bbox(b, 0);
    assert_memory_equal(&ba, &bb, sizeof ba);
    scene_free(a);
    scene_free(b);
}

/* view: the default fit is the bounding sphere; box and vertices give
 * other (closer) cameras. */
static void test_view_fits(void **st)
{
    (void)st;
    const char *fmt = "scene: {generator: teapots, count: 2, "
                      "view: {azimuth: 30, elevation: 20%s}}\n";
    const char *fit[] = {"", ", fit: sphere", ", fit: box", ", fit: vertices"};
    SceneCamera c[4];
    for (guint i = 0; i < 4; i++) {
        char *t = g_strdup_printf(fmt, fit[i]);
        Scene *s = from_text(t);
        c[i] = s->camera;
        scene_free(s);
        g_free(t);
    }
    assert_true(same_cam(c[0], c[1]));
    assert_false(same_cam(c[0], c[2]));
    assert_false(same_cam(c[0], c[3]));
    assert_false(same_cam(c[2], c[3]));
    /* the tighter fits bring the eye closer */
    double d[4];
    for (guint i = 0; i < 4; i++)
        d[i] = vec3_len(vec3_sub(c[i].eye, c[i].target));
    assert_true(d[2] < d[0] && d[3] < d[0]);
}

/* Large polygons of one size (min_size = max_size) are allowed; a
 * missing or non-map section is refused once (warnings are fatal). */
static void test_sizes_and_sections(void **st)
{
    (void)st;
    scene_free(from_text("scene: {generator: large_polygons, count: 4, "
                         "min_size: 0.5, max_size: 0.5}\n"));
    GError *err = NULL;
    assert_null(scene_from_cfg(NULL, &err));
    CfgNode *root = cfg_load_string("scene: [1, 2]\n", "v.yaml", &err);
    assert_null(scene_from_cfg(cfg_get(root, "scene"), &err));
    assert_string_equal(err->message, "v.yaml:1:8: found a non-map, expected "
                                      "a scene map {generator | file ...}");
    g_clear_error(&err);
    cfg_free(root);
}

/* An eye one unit from the target is a camera like any other. */
static void test_unit_camera(void **st)
{
    (void)st;
    Scene *s = from_text("scene: {generator: teapots, camera: {eye: [0, 0, 1],"
                         " target: [0, 0, 0]}}\n");
    assert_true(s->camera.eye.z == 1 && s->camera.target.z == 0);
    scene_free(s);
    /* and an up of length 1 across the view */
    s = from_text("scene: {generator: teapots, camera: {eye: [0, 0, 3],"
                  " target: [0, 0, 2], up: [1, 0, 0]}}\n");
    assert_true(s->camera.up.x == 1);
    scene_free(s);
}

/* Keys are interpolated linearly unless `interp: catmull_rom`: a quarter
 * of the way between two keys is a quarter of the way for linear. */
static void test_keyframe_interp(void **st)
{
    (void)st;
    const char *fmt = "scene: {generator: teapots, path: {kind: keyframes,%s"
                      " keys: [{frame: 0, eye: [0, 0, 5]}, "
                      "{frame: 4, eye: [4, 0, 5]}]}}\n";
    const char *in[] = {"", " interp: linear,", " interp: catmull_rom,"};
    double x[3];
    for (guint i = 0; i < 3; i++) {
        char *t = g_strdup_printf(fmt, in[i]);
        Scene *s = from_text(t);
        x[i] = scene_camera_at(s, 1).eye.x;
        scene_free(s);
        g_free(t);
    }
    assert_true(fabs(x[0] - 1) < 1e-12 && fabs(x[1] - 1) < 1e-12);
    assert_true(fabs(x[2] - 1) > 1e-3);
}

/* A path sets the scene camera to its frame 0. */
static void test_path_sets_camera(void **st)
{
    (void)st;
    Scene *s = from_text("scene: {generator: teapots, camera: {eye: [0, 0, 9],"
                         " target: [0, 0, 0]}, path: {kind: orbit, start: 90,"
                         " frames: 4}}\n");
    SceneCamera c0 = scene_camera_at(s, 0), c1 = scene_camera_at(s, 1);
    assert_true(same_cam(s->camera, c0));
    assert_false(same_cam(s->camera, c1));
    assert_true(fabs(s->camera.eye.x - 9) < 1e-9);
    scene_free(s);
    /* an orbit given no frames: one frame, a whole turn per frame, frame
     * 0 the section's camera */
    s = from_text("scene: {generator: teapots, camera: {eye: [0, 0, 9],"
                  " target: [0, 0, 0]}, path: {kind: orbit}}\n");
    assert_int_equal(scene_path_n_frames(s->path), 1);
    c0 = scene_camera_at(s, 0);
    assert_true(fabs(c0.eye.z - 9) < 1e-9 && fabs(c0.eye.x) < 1e-9);
    c1 = scene_camera_at(s, 0.25); /* a quarter turn a quarter frame on */
    assert_true(fabs(c1.eye.x - 9) < 1e-9 || fabs(c1.eye.x + 9) < 1e-9);
    scene_free(s);
}

int main(void)
{
    /* a reader that goes on after its error sets a GError over another,
     * and GLib warns: that is a failure here */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_seed_zero),
        cmocka_unit_test(test_pphigs_default_seed),
        cmocka_unit_test(test_placement_default_at),
        cmocka_unit_test(test_view_fits),
        cmocka_unit_test(test_sizes_and_sections),
        cmocka_unit_test(test_unit_camera),
        cmocka_unit_test(test_keyframe_interp),
        cmocka_unit_test(test_path_sets_camera),
    };
    return cmocka_run_group_tests_name("scene_cfg_values", tests, NULL, NULL);
}
