/* test_scene_cfg_limits.c — the range of every key a `scene:` section
 * reads (sim/scene/scene_cfg.c), pinned through its error message: a
 * value outside the range fails at the value's line:column and the
 * message states the range, so a changed bound shows.  Then the paths of
 * scene_cfg.c no other suite ran (make coverage): teapot placements and
 * arrangements, march cells, large-polygon sizes, orbit axes, keyframe
 * lists, fixed paths and the frame counts of keyframed ones.  Run from
 * the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include <glib/gstdio.h>

#include "sim/scene/scene_cfg.h"
#include "tests/support.h"

static Scene *from_text(const char *yaml, GError **err)
{
    CfgNode *root = cfg_load_string(yaml, "t.yaml", err);
    assert_non_null(root);
    Scene *s = scene_from_cfg(cfg_get(root, "scene"), err);
    cfg_free(root);
    return s;
}

/* yaml must fail with "t.yaml:1:C: found 'BAD', expected WANT", C the
 * column of the first `bad` in the text after a blank or a '['. */
static void fails_at_value(const char *yaml, const char *bad,
                           const char *want)
{
    GError *err = NULL;
    Scene *s = from_text(yaml, &err);
    if (s)
        print_error("accepted: %s", yaml);
    assert_null(s);
    const char *at = yaml;
    while ((at = strstr(at + 1, bad)) && at[-1] != ' ' && at[-1] != '[')
        ;
    assert_non_null(at);
    char *full = g_strdup_printf("t.yaml:1:%d: found '%s', expected %s",
                                 (int)(at - yaml) + 1, bad, want);
    if (strcmp(err->message, full))
        print_error("got  %s\nwant %s\n", err->message, full);
    assert_string_equal(err->message, full);
    g_free(full);
    g_error_free(err);
}

typedef struct {
    const char *prefix; /* the section up to the key, generator included */
    const char *key, *range;
} Range;


#define LOBBY "generator: building_lobby, size: 1, fov_deg: 45"
#define FLOCK                                                                  \
    "generator: flock_old_well, size: 1, boids: 1, boid_polygons: 1, "         \
    "boid_colors: 1, well_structs: 1, well_polygons: 1"
#define HUMANS "generator: two_human_figures, size: 1, figures: 1"
#define CAM "generator: teapots, camera: {eye: [0, 0, 5], target: [0, 0, 0]"

/* Counts: a value past every range gives "a count in [min, max]". */
static const Range counts[] = {
    {"generator: teapots", "teapots", "[1, 4096]"},
    {"generator: teapots", "count", "[1, 4096]"},
    {"generator: teapots", "polygons_per_teapot", "[1, 67108864]"},
    {"generator: teapots", "columns", "[1, 4096]"},
    {"generator: vehicle", "structures", "[10, 16777216]"},
    {"generator: vehicle", "triangles", "[8, 268435456]"},
    {"generator: vehicle", "instances", "[1, 1024]"},
    {"generator: vehicle", "frames", "[1, 16777216]"},
    {"generator: isosurface", "grid", "[2, 1024]"},
    {"generator: isosurface", "balls", "[1, 4096]"},
    {"generator: nurbs", "patches_u", "[1, 256]"},
    {"generator: nurbs", "patches_v", "[1, 256]"},
    {"generator: nurbs", "tess", "[1, 256]"},
    {"generator: nurbs", "bumps", "[0, 64]"},
    {"generator: march", "grid", "[2, 1024]"},
    {"generator: march", "cell", "[1, 1024]"},
    {"generator: march", "balls", "[1, 4096]"},
    {"generator: large_polygons", "count", "[1, 67108864]"},
    {"generator: large_polygons", "max_sides", "[3, 16]"},
    {"generator: space_station", "verts", "[3, 64]"},
    {"generator: space_station, size: 1", "polygons", "[0, 16777216]"},
    {"generator: space_station, size: 1, polygons: 1", "attributes",
     "[0, 16777216]"},
    {LOBBY, "polygons", "[0, 16777216]"},
    {LOBBY ", polygons: 1", "attributes", "[0, 16777216]"},
    {"generator: flock_old_well, size: 1", "boids", "[0, 16777216]"},
    {"generator: flock_old_well, size: 1, boids: 1", "boid_polygons",
     "[0, 16777216]"},
    {"generator: flock_old_well, size: 1, boids: 1, boid_polygons: 1",
     "boid_colors", "[0, 16777216]"},
    {"generator: flock_old_well, size: 1, boids: 1, boid_polygons: 1, "
     "boid_colors: 1",
     "well_structs", "[0, 16777216]"},
    {"generator: flock_old_well, size: 1, boids: 1, boid_polygons: 1, "
     "boid_colors: 1, well_structs: 1",
     "well_polygons", "[0, 16777216]"},
    {FLOCK, "well_attributes", "[0, 16777216]"},
    {"generator: two_human_figures, size: 1", "figures", "[0, 16777216]"},
    {HUMANS, "structures", "[0, 16777216]"},
    {HUMANS ", structures: 1", "polygons", "[0, 16777216]"},
    {HUMANS ", structures: 1, polygons: 1", "levels", "[0, 16777216]"},
    {"generator: teapots, pn_triangles: {normals: linear", "level",
     "[0, 64]"},
    {"generator: teapots, path: {kind: fixed", "frames", "[1, 16777216]"},
};

/* Reals: a value below or above the range gives "a number in [lo, hi]". */
static const Range reals[] = {
    {"generator: teapots", "spacing", "[0, 1000]"},
    {"generator: teapots", "shift", "[-1000, 1000]"},
    {"generator: teapots", "yaw_step", "[-360, 360]"},
    {"generator: teapots", "yaw", "[-360, 360]"},
    {"generator: teapots", "across", "[0, 1000]"},
    {"generator: teapots, placements: [{at: [0, 0, 0]", "yaw", "[-360, 360]"},
    {"generator: teapots, placements: [{at: [0, 0, 0]", "scale",
     "[1e-06, 1e+06]"},
    {"generator: vehicle", "circle_radius", "[0, 1e+06]"},
    {"generator: vehicle", "camera_radius", "[0, 1e+06]"},
    {"generator: vehicle", "camera_height", "[-1e+06, 1e+06]"},
    {"generator: vehicle", "fov", "[1, 170]"},
    {"generator: vehicle", "degrees_per_frame", "[-360, 360]"},
    {"generator: isosurface", "iso", "[-1e+06, 1e+06]"},
    {"generator: isosurface", "periods", "[0, 1000]"},
    {"generator: nurbs", "amplitude", "[0, 0.9]"},
    {"generator: march", "periods", "[0, 1000]"},
    {"generator: march", "fill", "[0.05, 1]"},
    {"generator: march", "iso", "[-1e+06, 1e+06]"},
    {"generator: large_polygons", "huge_fraction", "[0, 1]"},
    {"generator: large_polygons", "min_size", "[0, 10]"},
    {"generator: large_polygons", "max_size", "[0, 10]"},
    {"generator: space_station", "size", "[1e-06, 1e+09]"},
    {"generator: building_lobby, size: 1", "fov_deg", "[1, 170]"},
    {"generator: teapots, view: {fit: box", "azimuth", "[-360, 360]"},
    {"generator: teapots, view: {fit: box", "elevation", "[-90, 90]"},
    {"generator: teapots, view: {fit: box", "fov", "[1, 170]"},
    {"generator: teapots, view: {fit: box", "fill", "[0.01, 4]"},
    {"generator: teapots, view: {fit: box", "aspect", "[0.001, 1000]"},
    {CAM, "fov", "[1, 170]"},
    {CAM, "height", "[1e-09, 1e+12]"},
    {CAM, "near", "[1e-09, 1e+12]"},
    {CAM, "far", "[1e-09, 1e+12]"},
    {CAM, "aspect", "[0.001, 1000]"},
    {"generator: teapots, path: {kind: orbit", "start", "[-360, 360]"},
    {"generator: teapots, path: {kind: orbit", "degrees_per_frame",
     "[-360, 360]"},
    {"generator: teapots, path: {kind: keyframes, keys: [{eye: [0, 0, 5]",
     "frame", "[0, 1e+09]"},
};

/* The section "scene: {prefix, key: value}" with the braces and brackets
 * `prefix` left open closed. */
static char *closed(const char *prefix, const char *key, const char *value)
{
    GString *s = g_string_new("scene: {");
    g_string_append_printf(s, "%s, %s: %s", prefix, key, value);
    char open[16];
    int n = 0;
    for (const char *c = prefix; *c; c++)
        if (*c == '{' || *c == '[')
            open[n++] = *c == '{' ? '}' : ']';
        else if (*c == '}' || *c == ']')
            n--;
    while (n > 0)
        g_string_append_c(s, open[--n]);
    g_string_append(s, "}\n");
    return g_string_free(s, FALSE);
}

static void test_count_ranges(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(counts); i++) {
        char *want = g_strdup_printf("a count in %s", counts[i].range);
        char *y = closed(counts[i].prefix, counts[i].key, "99999999999");
        fails_at_value(y, "99999999999", want);
        g_free(y);
        g_free(want);
    }
}

static void test_real_ranges(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(reals); i++) {
        char *want = g_strdup_printf("a number in %s", reals[i].range);
        for (int side = 0; side < 2; side++) {
            const char *v = side ? "2e20" : "-2e20";
            char *y = closed(reals[i].prefix, reals[i].key, v);
            fails_at_value(y, v, want);
            g_free(y);
        }
        g_free(want);
    }
}

/* [x, y, z] elements: coordinates within +-1e15, colours in [0, 1]. */
static void test_triples(void **st)
{
    (void)st;
    fails_at_value("scene: {generator: teapots, color: [0, 1, 1.5]}\n", "1.5",
                   "a number in [0, 1]");
    fails_at_value("scene: {generator: teapots, background: [-0.5, 0, 0]}\n",
                   "-0.5", "a number in [0, 1]");
    fails_at_value("scene: {generator: teapots, placements: [{at: [0, 2e15, "
                   "0]}]}\n",
                   "2e15", "a number in [-1e+15, 1e+15]");
    fails_at_value("scene: {generator: teapots, camera: {eye: [0, 0, 5], "
                   "target: [-2e15, 0, 0]}}\n",
                   "-2e15", "a number in [-1e+15, 1e+15]");
    fails_at_value("scene: {generator: teapots, path: {kind: orbit, "
                   "center: [0, 0, nan]}}\n",
                   "nan", "a number in [-1e+15, 1e+15]");
    GError *err = NULL;
    Scene *s = from_text("scene: {generator: teapots, color: [0, 1, 1], "
                         "vary_color: false, background: [1, 0, 0.5]}\n",
                         &err);
    assert_non_null(s);
    SceneColor c = scene_instance(s, 0)->color;
    assert_true(c.r == 0 && c.g == 1 && c.b == 1);
    assert_true(s->background.r == 1 && s->background.g == 0 &&
                s->background.b == 0.5f);
    scene_free(s);
}

static void fails_with(const char *yaml, const char *want)
{
    GError *err = NULL;
    Scene *s = from_text(yaml, &err);
    if (s)
        print_error("accepted: %s", yaml);
    assert_null(s);
    if (strcmp(err->message, want))
        print_error("got  %s\nwant %s\n", err->message, want);
    assert_string_equal(err->message, want);
    g_error_free(err);
}

/* The checks beyond ranges, each with its whole message. */
static void test_section_errors(void **st)
{
    (void)st;
    fails_with("scene: {generator: teapots, placements: [3]}\n",
               "t.yaml:1:42: found a non-map, expected a map {at, yaw, "
               "scale}");
    fails_with("scene: {generator: teapots, placements: 3}\n",
               "t.yaml:1:41: found not a list, expected a list of {at, yaw, "
               "scale}");
    fails_with("scene: {generator: teapots, arrangement: 3}\n",
               "t.yaml:1:42: found '3', expected one of: 1, 2");
    fails_with("scene: {generator: teapots, layout: grid}\n",
               "t.yaml:1:37: found 'grid', expected one of: spread, depth");
    fails_with("scene: {generator: march, grid: 64, cell: 24}\n",
               "t.yaml:1:43: found a cell size that does not divide the "
               "grid, expected a cell size dividing grid (64 / 16 in "
               "igehy98)");
    fails_with("scene: {generator: march, grid: 63}\n",
               "t.yaml:1:8: found a cell size that does not divide the grid, "
               "expected a cell size dividing grid (64 / 16 in igehy98)");
    fails_with("scene: {generator: large_polygons, min_size: 0.5, "
               "max_size: 0.25}\n",
               "t.yaml:1:61: found max_size < min_size, expected max_size >= "
               "min_size");
    fails_with("scene: {generator: teapots, path: {kind: orbit, "
               "axis: [0, 0, 0]}}\n",
               "t.yaml:1:55: found a zero axis, expected a non-zero axis");
    fails_with("scene: {generator: teapots, path: {kind: keyframes}}\n",
               "t.yaml:1:35: found no list of keys, expected keys: [{frame, "
               "eye, target ...}, ...]");
    fails_with("scene: {generator: teapots, path: {kind: keyframes, "
               "keys: []}}\n",
               "t.yaml:1:59: found no list of keys, expected keys: [{frame, "
               "eye, target ...}, ...]");
    fails_with("scene: {generator: teapots, path: {kind: keyframes, "
               "keys: [3]}}\n",
               "t.yaml:1:60: found a non-map, expected a key map");
    fails_with("scene: {generator: teapots, path: {kind: keyframes, "
               "keys: [{eye: [0, 0, 5]}]}}\n",
               "t.yaml:1:60: found no key 'frame' in this map, expected "
               "'frame': a number in [0, 1e+09]");
    fails_with("scene: {generator: teapots, path: {kind: keyframes, "
               "interp: cubic, keys: [{frame: 0}]}}\n",
               "t.yaml:1:61: found 'cubic', expected one of: linear, "
               "catmull_rom");
    fails_with("scene: {generator: teapots, path: {kind: keyframes, "
               "keys: [{frame: 1}, {frame: 0.5}]}}\n",
               "t.yaml:1:80: found a frame not after the previous key's, "
               "expected increasing frames");
    fails_with("scene: {generator: teapots, path: 3}\n",
               "t.yaml:1:35: found a non-map, expected a path map {kind ...}");
    fails_with("scene: {generator: teapots, view: 3}\n",
               "t.yaml:1:35: found a non-map, expected a map {azimuth, "
               "elevation, fov, fill ...}");
    fails_with("scene: {generator: teapots, view: {fit: all}}\n",
               "t.yaml:1:41: found 'all', expected one of: sphere, box, "
               "vertices");
    fails_with("scene: {generator: teapots, camera: 3}\n",
               "t.yaml:1:37: found a non-map, expected a camera map {eye, "
               "target, up, fov ...}");
    fails_with("scene: {generator: teapots, camera: {eye: [0, 0, 5], "
               "target: [0, 0, 0], up: [0, 0, 1]}}\n",
               "t.yaml:1:37: found a degenerate camera (near >= far, eye = "
               "target or up along the view direction), expected a valid "
               "camera");
    fails_with("scene: {generator: teapots, camera: {eye: [0, 0, 5], "
               "target: [0, 0, 0], near: 3, far: 2}}\n",
               "t.yaml:1:37: found a degenerate camera (near >= far, eye = "
               "target or up along the view direction), expected a valid "
               "camera");
    fails_with("scene: {generator: teapots, camera: {eye: [0, 0, 5], "
               "target: [0, 0, 0], projection: fisheye}}\n",
               "t.yaml:1:85: found 'fisheye', expected one of: perspective, "
               "orthographic");
    fails_with("scene: {file: [a]}\n",
               "t.yaml:1:15: found a sequence, expected a string");
    fails_with("scene: {file: tests/data/scene/none.obj}\n",
               "t.yaml:1:15: file: tests/data/scene/none.obj:0:0: found an "
               "unreadable file (No such file or directory), expected a "
               "readable file");
}

/* The ranges' edges are accepted: a far just past near, a one-frame
 * fixed path, the smallest march cell. */
static void test_edges_accepted(void **st)
{
    (void)st;
    GError *err = NULL;
    Scene *s = from_text("scene: {generator: teapots, camera: {eye: [0, 0, 5],"
                         " target: [0, 0, 0], near: 2, far: 2.000001}, "
                         "path: {kind: fixed}}\n",
                         &err);
    assert_non_null(s);
    assert_int_equal(scene_path_kind(s->path), SCENE_PATH_FIXED);
    assert_int_equal(scene_path_n_frames(s->path), 1);
    assert_true(s->camera.near == 2 && s->camera.far == 2.000001);
    SceneCamera c = scene_camera_at(s, 0);
    assert_true(c.eye.z == 5 && c.target.z == 0);
    scene_free(s);
    s = from_text("scene: {generator: teapots, path: {kind: fixed, "
                  "frames: 7}}\n",
                  &err);
    assert_non_null(s);
    assert_int_equal(scene_path_n_frames(s->path), 7);
    SceneCamera c6 = scene_camera_at(s, 6), c0 = scene_camera_at(s, 0);
    assert_true(c6.eye.x == c0.eye.x && c6.eye.y == c0.eye.y &&
                c6.eye.z == c0.eye.z);
    scene_free(s);
}

/* A keyframed path's frame count: the last key's frame + 1, raised (never
 * lowered) by `frames`. */
static void test_keyframe_frames(void **st)
{
    (void)st;
    const char *fmt = "scene: {generator: teapots, path: {kind: keyframes, "
                      "%s keys: [{frame: 0, eye: [0, 0, 5]}, "
                      "{frame: 4, eye: [4, 0, 5]}]}}\n";
    const char *extra[] = {"", "frames: 3,", "frames: 5,", "frames: 6,",
                           "frames: 20,"};
    const guint want[] = {5, 5, 5, 6, 20};
    for (guint i = 0; i < G_N_ELEMENTS(extra); i++) {
        char *y = g_strdup_printf(fmt, extra[i]);
        GError *err = NULL;
        Scene *s = from_text(y, &err);
        assert_non_null(s);
        assert_int_equal(scene_path_n_frames(s->path), want[i]);
        SceneCamera c = scene_camera_at(s, 2);
        assert_true(fabs(c.eye.x - 2) < 1e-9);
        scene_free(s);
        g_free(y);
    }
}

/* A model file as a scene: one white instance, tag 0, the default view
 * fitted; the extension in any case; a model without faces refused. */
static void test_from_file(void **st)
{
    (void)st;
    GError *err = NULL;
    char *dir = g_dir_make_tmp("pgsim-cfg-XXXXXX", NULL);
    char *up = g_build_filename(dir, "SQUARE.OBJ", NULL);
    char *none = g_build_filename(dir, "points.ply", NULL);
    assert_true(g_file_set_contents(up, "v 0 0 0\nv 2 0 0\nv 2 2 0\n"
                                        "v 0 2 0\nf 1 2 3 4\n", -1, NULL));
    assert_true(g_file_set_contents(none, "ply\nformat ascii 1.0\n"
                                          "element vertex 1\nproperty float x\n"
                                          "property float y\nproperty float z\n"
                                          "end_header\n0 0 0\n", -1, NULL));
    Scene *s = scene_from_file(up, &err);
    assert_non_null(s);
    assert_int_equal(scene_n_instances(s), 1);
    assert_int_equal(scene_n_polys(s), 1);
    const SceneInstance *in = scene_instance(s, 0);
    assert_true(in->color.r == 1 && in->color.g == 1 && in->color.b == 1);
    assert_int_equal(in->tag, 0);
    assert_true(s->camera.target.x == 1 && s->camera.target.y == 1);
    assert_true(s->camera.eye.z > 0 && s->camera.eye.x == 1);
    scene_free(s);
    assert_null(scene_from_file(none, &err));
    char *want = g_strdup_printf("%s:0:0: found a model without faces, "
                                 "expected at least one polygon (an OBJ 'f' "
                                 "line or a PLY face)",
                                 none);
    assert_string_equal(err->message, want);
    g_free(want);
    g_clear_error(&err);
    g_unlink(up);
    g_unlink(none);
    g_rmdir(dir);
    g_free(up);
    g_free(none);
    g_free(dir);
}

/* pn_triangles: level 1 unless given (each triangle becomes 4), level
 * 0 keeps the triangles. */
static void test_pn_default_level(void **st)
{
    (void)st;
    GError *err = NULL;
    Scene *flat = from_text("scene: {generator: teapots, polygons_per_teapot: "
                            "288}\n",
                            &err);
    assert_non_null(flat);
    uint64_t tris = scene_n_triangles(flat);
    scene_free(flat);
    const char *pn[] = {"{}", "{level: 0}", "{level: 2, normals: quadratic}"};
    const uint64_t per[] = {4, 1, 9};
    for (guint i = 0; i < 3; i++) {
        char *y = g_strdup_printf("scene: {generator: teapots, "
                                  "polygons_per_teapot: 288, "
                                  "pn_triangles: %s}\n",
                                  pn[i]);
        Scene *s = from_text(y, &err);
        assert_non_null(s);
        assert_int_equal(scene_n_polys(s), per[i] * tris);
        scene_free(s);
        g_free(y);
    }
}

int main(void)
{
    /* a failed section sets its error once: a GError set over another
     * (a reader going on after its error) warns, and that is a failure */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_count_ranges),
        cmocka_unit_test(test_real_ranges),
        cmocka_unit_test(test_triples),
        cmocka_unit_test(test_section_errors),
        cmocka_unit_test(test_edges_accepted),
        cmocka_unit_test(test_keyframe_frames),
        cmocka_unit_test(test_from_file),
        cmocka_unit_test(test_pn_default_level),
    };
    return cmocka_run_group_tests_name("scene_cfg_limits", tests, NULL, NULL);
}
