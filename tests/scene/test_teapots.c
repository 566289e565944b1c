/* test_teapots.c — teapot scenes: Table 1 polygon counts of seed 003
 * through the C API, layouts (spread: no overlap, depth: overlap), and
 * the view rule.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/teapots.h"

static Scene *pots(guint count, SceneTeapotLayout layout)
{
    SceneTeapotsParams p = scene_teapots_defaults();
    p.polygons_per_teapot = 3751;
    p.count = count;
    p.layout = layout;
    p.shift = 0.4;
    Scene *s = scene_teapots_new(&p, "x", NULL);
    assert_non_null(s);
    return s;
}

static void test_table1_counts(void **st)
{
    (void)st;
    const char *name[] = {"1POT",   "2POT",   "4POT_1",
                          "4POT_2", "8POT_1", "8POT_2"};
    const guint count[] = {1, 2, 4, 4, 8, 8};
    const uint64_t polys[] = {3751, 7502, 15004, 15004, 30008, 30008};
    for (guint i = 0; i < 6; i++) {
        Scene *s =
            pots(count[i], i % 2 ? SCENE_TEAPOTS_DEPTH : SCENE_TEAPOTS_SPREAD);
        const SceneMesh *m = g_ptr_array_index(s->meshes, 0);
        print_message(
            "%-7s teapots %u polygons %" G_GUINT64_FORMAT
            " (per teapot %u quads + %u triangles) triangles %" G_GUINT64_FORMAT
            "\n",
            name[i], count[i], scene_n_polys(s), scene_mesh_count_ngons(m, 4),
            scene_mesh_count_ngons(m, 3), scene_n_triangles(s));
        assert_int_equal(scene_n_polys(s), polys[i]);
        assert_int_equal(scene_n_instances(s), count[i]);
        scene_free(s);
    }
}

/* Screen-space rectangles of instances i and j overlap? */
static gboolean screen_overlap(const Scene *s, guint i, guint j)
{
    Mat4 vp = scene_camera_view_proj(&s->camera);
    SceneBox a = scene_box_transform(scene_instance_bbox(s, i), vp);
    SceneBox b = scene_box_transform(scene_instance_bbox(s, j), vp);
    return a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y &&
           b.min.y < a.max.y;
}

static void test_layouts(void **st)
{
    (void)st;
    Scene *s = pots(4, SCENE_TEAPOTS_SPREAD);
    for (guint i = 0; i < 4; i++)
        for (guint j = i + 1; j < 4; j++)
            assert_false(scene_box_overlaps(scene_instance_bbox(s, i),
                                            scene_instance_bbox(s, j)));
    scene_free(s);
    s = pots(8, SCENE_TEAPOTS_DEPTH);
    guint overlaps = 0;
    for (guint i = 0; i + 1 < 8; i++)
        overlaps += screen_overlap(s, i, i + 1);
    assert_int_equal(overlaps, 7);
    /* Receding: each teapot farther from the eye than the previous. */
    for (guint i = 0; i + 1 < 8; i++) {
        Vec3 a = scene_box_center(scene_instance_bbox(s, i));
        Vec3 b = scene_box_center(scene_instance_bbox(s, i + 1));
        assert_true(vec3_len(vec3_sub(b, s->camera.eye)) >
                    vec3_len(vec3_sub(a, s->camera.eye)));
    }
    scene_free(s);
}

static void test_view_fits(void **st)
{
    (void)st;
    Scene *s = pots(2, SCENE_TEAPOTS_SPREAD);
    Mat4 vp = scene_camera_view_proj(&s->camera);
    SceneBox ndc = scene_box_transform(scene_bbox(s), vp);
    assert_true(ndc.min.x >= -1.0001 && ndc.max.x <= 1.0001);
    assert_true(ndc.min.y >= -1.0001 && ndc.max.y <= 1.0001);
    assert_true(ndc.max.x - ndc.min.x > 1.0); /* fills a good part */
    scene_free(s);
}

static void test_placements(void **st)
{
    (void)st;
    SceneTeapotPlacement pl[2] = {{{0, 0, 0}, 0, 1}, {{10, 0, 0}, 90, 2}};
    SceneTeapotsParams p = scene_teapots_defaults();
    p.count = 2;
    p.placements = pl;
    p.n_placements = 2;
    Scene *s = scene_teapots_new(&p, "x", NULL);
    Vec3 c = scene_box_center(scene_instance_bbox(s, 1));
    assert_true(fabs(c.x - 10) < 1e-6);
    Vec3 sz = scene_box_size(scene_instance_bbox(s, 1));
    assert_true(fabs(sz.z - 2 * 6.434) < 1e-3); /* turned, doubled */
    scene_free(s);
    p.polygons_per_teapot = 10;
    GError *err = NULL;
    assert_null(scene_teapots_new(&p, "x", &err));
    assert_non_null(err);
    g_error_free(err);
}

/* Depth layout with two columns: teapots 2k and 2k + 1 side by side
 * (`across` widths apart), rows `spacing` depths apart; `yaw` turns every
 * teapot (a quarter turn swaps its box's x and z extents). */
static void test_columns_and_yaw(void **st)
{
    (void)st;
    SceneTeapotsParams p = scene_teapots_defaults();
    p.polygons_per_teapot = 3751;
    p.count = 4;
    p.layout = SCENE_TEAPOTS_DEPTH;
    p.columns = 2;
    p.across = 1.5;
    p.spacing = 2.0;
    p.shift = 0;
    Scene *s = scene_teapots_new(&p, "x", NULL);
    Vec3 c[4], size = scene_box_size(scene_instance_bbox(s, 0));
    for (guint i = 0; i < 4; i++)
        c[i] = scene_box_center(scene_instance_bbox(s, i));
    assert_true(fabs(c[1].x - c[0].x - 1.5 * size.x) < 1e-6);
    assert_true(fabs(c[1].z - c[0].z) < 1e-6);
    assert_true(fabs(c[0].z - c[2].z - 2.0 * size.z) < 1e-6);
    assert_true(fabs(c[2].x - c[0].x) < 1e-6);
    scene_free(s);
    p.yaw = 90;
    s = scene_teapots_new(&p, "x", NULL);
    Vec3 turned = scene_box_size(scene_instance_bbox(s, 3));
    assert_true(fabs(turned.x - size.z) < 1e-6);
    assert_true(fabs(turned.z - size.x) < 1e-6);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table1_counts),
        cmocka_unit_test(test_layouts),
        cmocka_unit_test(test_view_fits),
        cmocka_unit_test(test_placements),
        cmocka_unit_test(test_columns_and_yaw),
    };
    return cmocka_run_group_tests_name("teapots", tests, NULL, NULL);
}
