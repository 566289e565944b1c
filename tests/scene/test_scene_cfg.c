/* test_scene_cfg.c — scenes from YAML: the configs/scenes/ files give the
 * published counts (seed 003 Table 1, seed 000, seed 004, and seed 001's
 * four PPHIGS databases against configs/papers/ellsworth90/published.yaml), a
 * camera or view re-bases a generator's camera path, and every malformed
 * section fails with a located error.  Run from the repository root.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/pphigs_db.h"
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
    const char *files[] = {"1pot",   "2pot",   "4pot_1",
                           "4pot_2", "8pot_1", "8pot_2"};
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

static Scene *from_text(const char *yaml, GError **err);

/* fit: vertices puts the silhouette exactly at +-fill of the viewport. */
static void test_fit_vertices(void **st)
{
    (void)st;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "scene: {generator: teapots, count: 3, polygons_per_teapot: 300,\n"
        "        layout: depth, view: {azimuth: 0, elevation: 20,\n"
        "        fill: 0.8, fit: vertices}}\n",
        "v.yaml", &err);
    assert_non_null(root);
    Scene *s = scene_from_cfg(cfg_get(root, "scene"), &err);
    assert_non_null(s);
    Mat4 vp = scene_camera_view_proj(&s->camera);
    double ext = 0;
    for (guint i = 0; i < scene_n_instances(s); i++) {
        const SceneMesh *m = scene_instance_mesh(s, i);
        Mat4 x = mat4_mul(vp, scene_instance(s, i)->xform);
        for (guint k = 0; k < scene_mesh_n_vertices(m); k++) {
            Vec4 p = mat4_apply_point(x, scene_mesh_vertex(m, k));
            ext = MAX(ext, MAX(fabs(p.x / p.w), fabs(p.y / p.w)));
        }
    }
    assert_true(ext <= 0.8 + 1e-6);
    assert_true(ext >= 0.8 - 1e-3); /* it touches: no slack */
    scene_free(s);
    cfg_free(root);
    /* fit: box puts the instances' box corners there instead */
    s = from_text("scene: {generator: teapots, count: 3, polygons_per_teapot: "
                  "300,\n layout: depth, view: {azimuth: 0, elevation: 20, "
                  "fill: 0.8, fit: box}}\n",
                  &err);
    assert_non_null(s);
    vp = scene_camera_view_proj(&s->camera);
    ext = 0;
    for (guint i = 0; i < scene_n_instances(s); i++) {
        SceneBox b = scene_instance_bbox(s, i);
        for (int k = 0; k < 8; k++) {
            Vec4 p = mat4_apply_point(
                vp, vec3(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y,
                         k & 4 ? b.max.z : b.min.z));
            ext = MAX(ext, MAX(fabs(p.x / p.w), fabs(p.y / p.w)));
        }
    }
    assert_true(ext <= 0.8 + 1e-6 && ext >= 0.8 - 1e-3);
    scene_free(s);
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

static const char *const pphigs_names[] = {
    "space_station", "building_lobby", "flock_old_well", "two_human_figures"};

/* A published cell of seed 001's "db" table; FALSE when absent. */
static gboolean paper_cell(const CfgNode *paper, const char *row,
                           const char *col, double *v)
{
    char *path = g_strdup_printf("tables.db.rows.%s.%s", row, col);
    const CfgNode *n = cfg_path(paper, path);
    g_free(path);
    if (!n)
        return FALSE;
    *v = g_ascii_strtod(cfg_scalar(n), NULL);
    return TRUE;
}

/* Within the table's printed precision (3 significant digits). */
static void assert_near(double sim, double pub, double rel)
{
    if (fabs(sim - pub) > rel * fabs(pub))
        print_error("simulated %g, published %g\n", sim, pub);
    assert_true(fabs(sim - pub) <= rel * fabs(pub));
}

/* The four PPHIGS scene files have the published statistics, and their
 * generator parameters are those of configs/pphigs/databases.yaml (the
 * pphigs workload's copy). */
static void test_pphigs_configs(void **st)
{
    (void)st;
    CfgNode *paper = cfg_load_file("configs/papers/ellsworth90/published.yaml", NULL);
    CfgNode *dbs = cfg_load_file("configs/pphigs/databases.yaml", NULL);
    assert_non_null(paper);
    assert_non_null(dbs);
    for (guint i = 0; i < G_N_ELEMENTS(pphigs_names); i++) {
        const char *name = pphigs_names[i];
        char *path = g_strdup_printf("configs/scenes/%s.yaml", name);
        Scene *s = from_file(path);
        assert_string_equal(s->name, name);
        assert_true(s->two_sided);
        SceneDbStats x;
        scene_db_stats(s->db, &x);
        double v;
        assert_true(paper_cell(paper, name, "depth", &v));
        assert_int_equal(x.depth, (guint)v);
        assert_true(paper_cell(paper, name, "structures", &v));
        assert_int_equal(x.instances, (guint)v); /* per instance */
        assert_true(paper_cell(paper, name, "polys_per_structure", &v));
        assert_near((double)x.primitives / x.instances, v, 0.005);
        assert_true(paper_cell(paper, name, "poly_attr_ratio", &v));
        assert_near((double)x.primitives / x.attributes, v, 0.005);
        /* the flattened mesh holds every primitive instance */
        assert_int_equal(scene_n_polys(s), x.primitives);
        /* same parameters as the workload's file */
        CfgNode *root = cfg_load_file(path, NULL);
        const CfgNode *sec = cfg_get(root, "scene");
        const CfgNode *ref = cfg_get(dbs, name);
        assert_non_null(ref);
        for (guint k = 0; k < cfg_map_len(ref); k++) {
            const char *key = cfg_map_key(ref, k);
            if (!strcmp(key, "kind"))
                continue;
            const CfgNode *mine = cfg_get(sec, key);
            if (!mine)
                print_error("%s: no key %s\n", path, key);
            assert_non_null(mine);
            assert_string_equal(cfg_scalar(mine),
                                cfg_scalar(cfg_map_value(ref, k)));
        }
        cfg_free(root);
        g_free(path);
        scene_free(s);
    }
    /* the lobby keeps its standard view: 55 % off-screen */
    Scene *s = from_file("configs/scenes/building_lobby.yaml");
    double off =
        scene_pphigs_offscreen_share(s->db, scene_camera_view_proj(&s->camera));
    double v;
    assert_true(paper_cell(paper, "building_lobby", "offscreen_pct", &v));
    assert_true(fabs(100 * off - v) < 2.0);
    scene_free(s);
    cfg_free(dbs);
    cfg_free(paper);
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

/* teapots `placements:` put one teapot per entry at its spot, scaled. */
static void test_teapot_placements(void **st)
{
    (void)st;
    gboolean listed = FALSE; /* the generator names include this one */
    for (const char *const *g = scene_generator_names(); *g; g++)
        listed |= strcmp(*g, "teapots") == 0;
    assert_true(listed);
    GError *err = NULL;
    Scene *s = from_text("scene:\n"
                         "  generator: teapots\n"
                         "  placements:\n"
                         "    - {at: [0, 0, 0]}\n"
                         "    - {at: [40, 0, 0], yaw: 90, scale: 2}\n",
                         &err);
    assert_non_null(s);
    assert_int_equal(scene_n_instances(s), 2);
    SceneBox a = scene_instance_bbox(s, 0), b = scene_instance_bbox(s, 1);
    Vec3 ca = scene_box_center(a), cb = scene_box_center(b);
    Vec3 sa = scene_box_size(a), sb = scene_box_size(b);
    assert_true(fabs(cb.x - ca.x - 40) < 0.25 * sb.x);
    assert_true(fabs(sb.y - 2 * sa.y) < 1e-6 * sb.y); /* yaw keeps y (up) */
    assert_true(fabs(sb.z - 2 * sa.x) < 1e-6 * sb.z); /* yaw 90 swaps x, z */
    assert_int_equal(scene_n_vertices(s), 2 * scene_mesh_n_vertices(
                                                  scene_instance_mesh(s, 0)));
    scene_free(s);
    /* one colour for all: white unless given */
    s = from_text("scene: {generator: teapots, vary_color: false}\n", &err);
    assert_non_null(s);
    SceneColor w = scene_instance(s, 0)->color;
    assert_true(w.r == 1 && w.g == 1 && w.b == 1);
    scene_free(s);
    s = from_text("scene: {generator: nurbs, patches_u: 1, patches_v: 1}\n",
                  &err);
    assert_non_null(s); /* one patch is a surface */
    scene_free(s);
    s = from_text("scene: {generator: large_polygons, count: 10, seed: 0}\n",
                  &err);
    assert_non_null(s); /* seed 0 is a seed like any other */
    scene_free(s);
}

/* PPHIGS counts may be 0 where the shape allows it: a flock of no boids
 * is the Old Well alone. */
static void test_pphigs_zero_count(void **st)
{
    (void)st;
    GError *err = NULL;
    Scene *s = from_text("scene: {generator: flock_old_well, size: 10, "
                         "boids: 0, boid_polygons: 5, boid_colors: 1, "
                         "well_structs: 1, well_polygons: 4, "
                         "well_attributes: 1}\n",
                         &err);
    assert_non_null(s);
    assert_int_equal(scene_n_polys(s), 4);
    scene_free(s);
}

/* `camera:` or `view:` on a generator with its own path (the vehicle's
 * orbit) moves the path: frame 0 is the camera asked for, and later
 * frames orbit from there. */
static void test_camera_rebases_path(void **st)
{
    (void)st;
    GError *err = NULL;
    Scene *s = from_text("scene:\n"
                         "  generator: vehicle\n"
                         "  structures: 10\n"
                         "  triangles: 100\n"
                         "  degrees_per_frame: 90\n"
                         "  camera: {eye: [0, 3, 20], target: [0, 1, 0]}\n",
                         &err);
    assert_non_null(s);
    SceneCamera c0 = scene_camera_at(s, 0), c1 = scene_camera_at(s, 1);
    assert_true(fabs(c0.eye.z - 20) < 1e-12 && fabs(c0.eye.y - 3) < 1e-12);
    assert_true(fabs(c0.target.y - 1) < 1e-12);
    /* a quarter turn about +y: (0, 3, 20) -> (20, 3, 0) */
    assert_true(fabs(c1.eye.x - 20) < 1e-9 && fabs(c1.eye.z) < 1e-9);
    scene_free(s);
    s = from_text("scene: {generator: vehicle, structures: 10, "
                  "triangles: 100, view: {azimuth: 90, elevation: 10}}\n",
                  &err);
    assert_non_null(s);
    c0 = scene_camera_at(s, 0);
    /* seen from +x: the eye is due east of the target */
    assert_true(c0.eye.x > c0.target.x);
    assert_true(fabs(c0.eye.z - c0.target.z) < 1e-9);
    assert_true(fabs(c0.eye.x - s->camera.eye.x) < 1e-12);
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
     "t.yaml:1:40: found 'x', expected a number in [0, 1]"},
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
    {"scene: {generator: flock_old_well, size: 10, boids: 3}\n",
     "t.yaml:1:8: found no key 'boid_polygons'"},
    {"scene: {generator: two_human_figures, size: 10, figures: 2, "
     "structures: 3, polygons: 30, levels: 9}\n",
     "t.yaml:1:20: found too few structures for the figures' depth"},
    {"scene: {generator: building_lobby, size: 10, polygons: 30, "
     "attributes: 3}\n",
     "t.yaml:1:8: found no key 'fov_deg'"},
    {"scene: {generator: space_station, size: 10, polygons: 30, "
     "attributes: 3, boids: 4}\n",
     "t.yaml:1:74: found unknown key 'boids'"},
    {"scene: {generator: teapots, two_sided: maybe}\n",
     "t.yaml:1:40: found 'maybe'"},
    {"scene: {generator: teapots, pn_triangles: {level: 65}}\n",
     "t.yaml:1:51: found '65', expected a count in [0, 64]"},
    {"scene: {generator: teapots, pn_triangles: {normals: cubic}}\n",
     "t.yaml:1:53: found 'cubic', expected one of: linear, quadratic"},
    {"scene: {generator: vehicle, instances: 0}\n", "t.yaml:1:40: found '0', expected a count in [1, 1024]"},
    {"scene: {generator: teapots, camera: {eye: [0, 0, 5], "
     "target: [0, 0, 0], near: 2, far: 2}}\n",
     "t.yaml:1:37: found a degenerate camera (near >= far"},
    {"scene: {generator: teapots, placements: []}\n", "t.yaml:1:41: found not a list, expected a list of {at, yaw, scale}"},
    {"scene: {generator: teapots, pn_triangles: 2}\n",
     "t.yaml:1:43: found a non-map, expected a map {level: L"},
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
            print_error("case %u: got  %s\n        want %s\n", i, err->message,
                        bad[i].message);
        assert_true(g_str_has_prefix(err->message, bad[i].message));
        g_error_free(err);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table1_configs),
        cmocka_unit_test(test_fit_vertices),
        cmocka_unit_test(test_other_configs),
        cmocka_unit_test(test_camera_and_path),
        cmocka_unit_test(test_teapot_placements),
        cmocka_unit_test(test_pphigs_zero_count),
        cmocka_unit_test(test_pphigs_configs),
        cmocka_unit_test(test_camera_rebases_path),
        cmocka_unit_test(test_bad_sections),
    };
    return cmocka_run_group_tests_name("scene_cfg", tests, NULL, NULL);
}
