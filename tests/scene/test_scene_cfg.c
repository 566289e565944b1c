/* test_scene_cfg.c — scenes from YAML: the configs/scenes/ files give the
 * published counts (seed 003 Table 1, seed 000, seed 004), and every
 * malformed section fails with a located error.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/scene_cfg.h"

static Scene *from_file(const char *path)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_file(path, &err);
    if (!root)
        print_error("%s\n", err->message);
    assert_non_null(root);
    Scene *s = scene_from_cfg(cfg_get(root, "scene"), &err);
    if (!s)
        print_error("%s\n", err->message);
    assert_non_null(s);
    cfg_free(root);
    return s;
}

static void test_table1_configs(void **st)
{
    (void)st;
    const char *files[] = {"1pot", "2pot", "4pot_1", "4pot_2", "8pot_1",
                           "8pot_2"};
    const uint64_t polys[] = {3751, 7502, 15004, 15004, 30008, 30008};
    for (guint i = 0; i < 6; i++) {
        char *path = g_strdup_printf("configs/scenes/%s.yaml", files[i]);
        Scene *s = from_file(path);
        assert_int_equal(scene_n_polys(s), polys[i]);
        /* the view rule keeps every teapot on screen */
        Mat4 vp = scene_camera_view_proj(&s->camera);
        SceneBox ndc = scene_box_transform(scene_bbox(s), vp);
        assert_true(ndc.max.z <= 1 && ndc.min.z >= -1);
        scene_free(s);
        g_free(path);
    }
}

static void test_other_configs(void **st)
{
    (void)st;
    Scene *s = from_file("configs/scenes/bronco.yaml");
    SceneDbStats ds;
    scene_db_stats(s->db, &ds);
    assert_int_equal(ds.min_primitives, 74647);
    assert_int_equal(ds.structures, 466 + 1);
    assert_int_equal(scene_n_instances(s), 3);
    assert_int_equal(scene_path_n_frames(s->path), 120);
    scene_free(s);
    s = from_file("configs/scenes/isosurface_table1.yaml");
    print_message("isosurface_table1: %" G_GUINT64_FORMAT " triangles\n",
                  scene_n_triangles(s));
    assert_true(scene_n_triangles(s) > 228288 * 0.98 &&
                scene_n_triangles(s) < 228288 * 1.02);
    scene_free(s);
    s = from_file("configs/scenes/large_polygons.yaml");
    assert_int_equal(scene_n_polys(s), 217976);
    scene_free(s);
}

static Scene *from_text(const char *yaml, GError **err)
{
    CfgNode *root = cfg_load_string(yaml, "t.yaml", err);
    assert_non_null(root);
    Scene *s = scene_from_cfg(cfg_get(root, "scene"), err);
    cfg_free(root);
    return s;
}

static void test_camera_and_path(void **st)
{
    (void)st;
    GError *err = NULL;
    Scene *s = from_text("scene:\n"
                         "  generator: teapots\n"
                         "  teapots: 2\n"
                         "  arrangement: 2\n"
                         "  camera: {eye: [0, 0, 20], target: [0, 0, 0],"
                         " fov: 30, near: 1, far: 50}\n"
                         "  path: {kind: orbit, frames: 4}\n"
                         "  background: [0.5, 0, 1]\n",
                         &err);
    assert_non_null(s);
    assert_true(s->camera.fov_deg == 30);
    SceneCamera c1 = scene_camera_at(s, 1);
    assert_true(fabs(c1.eye.x - 20) < 1e-9 && fabs(c1.eye.z) < 1e-9);
    assert_true(s->background.b == 1.0f);
    scene_free(s);
    s = from_text("scene:\n"
                  "  file: ../data/scene/square.obj\n"
                  "  path:\n"
                  "    kind: keyframes\n"
                  "    interp: catmull_rom\n"
                  "    keys:\n"
                  "      - {frame: 0, eye: [0, 0, 5]}\n"
                  "      - {frame: 10, eye: [5, 0, 5], fov: 60}\n",
                  &err);
    /* relative to t.yaml's directory (the repo root): not found */
    assert_null(s);
    assert_int_equal(err->code, SIM_ERROR_IO);
    g_clear_error(&err);
    s = from_text("scene:\n"
                  "  file: tests/data/scene/square.obj\n"
                  "  path:\n"
                  "    kind: keyframes\n"
                  "    keys:\n"
                  "      - {frame: 0, eye: [0, 0, 5]}\n"
                  "      - {frame: 10, eye: [5, 0, 5], fov: 60}\n",
                  &err);
    assert_non_null(s);
    assert_int_equal(scene_n_polys(s), 2);
    SceneCamera c = scene_camera_at(s, 5);
    assert_true(fabs(c.eye.x - 2.5) < 1e-9 && fabs(c.fov_deg - 52.5) < 1e-9);
    assert_int_equal(scene_path_n_frames(s->path), 11);
    scene_free(s);
}

typedef struct {
    const char *yaml, *message;
} Bad;

static const Bad bad[] = {
    {"scene: {generator: teapot}\n",
     "t.yaml:1:20: found 'teapot', expected one of: teapots, vehicle"},
    {"scene: {generator: teapots, colour: [1, 1, 1]}\n",
     "t.yaml:1:29: found unknown key 'colour'"},
    {"scene: {generator: teapots, polygons_per_teapot: 100}\n",
     "t.yaml:1:50: found 100 polygons per teapot, expected 288 to"},
    {"scene: {generator: teapots, color: [1, 1]}\n",
     "t.yaml:1:36: found not a list of 3, expected [x, y, z]"},
    {"scene: {generator: teapots, color: [1, x, 1]}\n",
     "t.yaml:1:40: found 'x', expected a finite number"},
    {"scene: {generator: vehicle, structures: 466, triangles: 100}\n",
     "t.yaml:1:57: found 466 structures and 100 triangles"},
    {"scene: {generator: isosurface, field: sphere}\n",
     "t.yaml:1:39: found 'sphere', expected one of: gyroid, metaballs"},
    {"scene: {generator: teapots, path: {kind: spiral}}\n",
     "t.yaml:1:42: found 'spiral', expected one of: fixed, orbit"},
    {"scene: {generator: teapots, camera: {eye: [0, 0, 0], "
     "target: [0, 0, 0]}}\n",
     "t.yaml:1:37: found a degenerate camera"},
    {"scene:\n  generator: teapots\n  path:\n    kind: keyframes\n"
     "    keys:\n      - {frame: 5}\n      - {frame: 5}\n",
     "t.yaml:7:17: found a frame not after the previous key's"},
    {"scene: {file: tests/data/bad/scene/obj_index_zero.obj}\n",
     "tests/data/bad/scene/obj_index_zero.obj:4:3: found '0'"},
    {"scene: {file: model.stl}\n",
     "model.stl: found an unknown extension, expected .obj or .ply"},
    {"scene: [1, 2]\n", "t.yaml:1:8: found a non-map, expected a scene map"},
};

static void test_bad_sections(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        GError *err = NULL;
        Scene *s = from_text(bad[i].yaml, &err);
        assert_null(s);
        assert_non_null(err);
        if (!g_str_has_prefix(err->message, bad[i].message))
            print_error("case %u: got  %s\n        want %s\n", i,
                        err->message, bad[i].message);
        assert_true(g_str_has_prefix(err->message, bad[i].message));
        g_error_free(err);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table1_configs),
        cmocka_unit_test(test_other_configs),
        cmocka_unit_test(test_camera_and_path),
        cmocka_unit_test(test_bad_sections),
    };
    return cmocka_run_group_tests_name("scene_cfg", tests, NULL, NULL);
}
