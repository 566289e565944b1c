/* test_vehicle.c — the procedural vehicle: exact structure and triangle
 * counts (seed 000: 466 structures, 74,647 triangles), hierarchy, the
 * three-copy scene and its revolving camera, and the order a modelling
 * tool writes (strips along each part's longer side).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/vehicle.h"

static void test_paper_counts(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint root;
    assert_true(scene_vehicle_build(db, 466, 74647, "x", &root, NULL));
    scene_db_post(db, root);
    SceneDbStats s;
    scene_db_stats(db, &s);
    print_message("vehicle: structures %u triangles %" G_GUINT64_FORMAT
                  " depth %u\n",
                  s.structures, s.min_primitives, s.depth);
    assert_int_equal(s.structures, 466);
    assert_int_equal(s.min_primitives, 74647);
    assert_int_equal(s.primitives, 74647);
    assert_int_equal(s.depth, 3);
    assert_int_equal(scene_db_struct_count(db), 466);
    SceneBox b = scene_db_struct_bbox(db, root);
    assert_true(b.min.y > -0.01 && b.max.y < 2.0);
    assert_true(b.max.x - b.min.x > 4.0 && b.max.x - b.min.x < 4.5);
    scene_db_free(db);
}

static void test_other_counts(void **st)
{
    (void)st;
    const guint structs[] = {10, 50, 467, 1000};
    const uint64_t tris[] = {8, 999, 74648, 200001};
    for (guint i = 0; i < G_N_ELEMENTS(structs); i++) {
        SceneDb *db = scene_db_new();
        guint root;
        assert_true(
            scene_vehicle_build(db, structs[i], tris[i], "x", &root, NULL));
        scene_db_post(db, root);
        SceneDbStats s;
        scene_db_stats(db, &s);
        assert_int_equal(s.structures, structs[i]);
        assert_int_equal(s.min_primitives, tris[i]);
        scene_db_free(db);
    }
    GError *err = NULL;
    SceneDb *db = scene_db_new();
    guint root;
    assert_false(scene_vehicle_build(db, 466, 100, "v.yaml:2:3", &root, &err));
    assert_non_null(strstr(err->message, "v.yaml:2:3: found 466 structures"));
    g_error_free(err);
    scene_db_free(db);
}

static double longest(SceneBox b)
{
    Vec3 d = scene_box_size(b);
    return MAX(d.x, MAX(d.y, d.z));
}

/* Triangles of sid written before their box spans the part's longest
 * side (to 1 %). */
static guint tris_to_span(const SceneDb *db, guint sid)
{
    double want = 0.99 * longest(scene_db_struct_bbox(db, sid));
    SceneBox b = scene_box_empty();
    guint n = scene_db_len(db, sid);
    for (guint i = 0; i < n; i++) {
        const SceneElem *e = scene_db_elem(db, sid, i);
        for (guint k = 0; k < e->nverts; k++)
            b = scene_box_add_point(b, e->verts[k]);
        if (e->nverts && longest(b) >= want)
            return i + 1;
    }
    return n;
}

/* Most body panels are long and narrow: written as a modelling tool
 * writes them, the first strip already runs their whole length, so
 * their box spans the part after a small fraction of the triangles (a
 * square parameter grid written across the short side needs almost
 * all of them: the order that made unsorted chunks spatially sorted). */
static void test_strip_order(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint root, body = 0, quick = 0;
    assert_true(scene_vehicle_build(db, 466, 74647, "x", &root, NULL));
    for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
        if (!g_str_has_prefix(scene_db_struct_name(db, sid), "body."))
            continue;
        body++;
        quick += tris_to_span(db, sid) * 4 <= scene_db_len(db, sid);
    }
    print_message("vehicle: %u of %u body parts span their length within "
                  "a quarter of their triangles\n", quick, body);
    assert_true(body > 100);
    assert_true(quick * 4 >= body * 3); /* the others are near square */
    scene_db_free(db);
}

static void test_scene(void **st)
{
    (void)st;
    SceneVehicleParams p = scene_vehicle_defaults();
    p.structures = 466;
    p.triangles = 74647;
    Scene *s = scene_vehicle_new(&p, "x", NULL);
    assert_non_null(s);
    assert_int_equal(scene_n_instances(s), 3);
    assert_int_equal(scene_n_triangles(s), 3 * 74647);
    assert_int_equal(scene_mesh_n_polys(g_ptr_array_index(s->meshes, 0)),
                     74647);
    SceneDbStats ds;
    scene_db_stats(s->db, &ds);
    assert_int_equal(ds.structures, 467); /* + the world structure */
    assert_int_equal(ds.primitives, 3 * 74647);
    /* Copies sit on the circle, 120 degrees apart. */
    for (guint k = 0; k < 3; k++) {
        Vec3 c = scene_box_center(scene_instance_bbox(s, k));
        double r = sqrt(c.x * c.x + c.z * c.z);
        assert_true(fabs(r - p.circle_radius) < 0.3);
    }
    /* The camera revolves about the centre at constant distance. */
    SceneCamera c0 = scene_camera_at(s, 0), c30 = scene_camera_at(s, 30);
    assert_true(fabs(vec3_len(c0.eye) - vec3_len(c30.eye)) < 1e-9);
    assert_true(fabs(c30.eye.z) > 1);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paper_counts),
        cmocka_unit_test(test_other_counts),
        cmocka_unit_test(test_scene),
        cmocka_unit_test(test_strip_order),
    };
    return cmocka_run_group_tests_name("vehicle", tests, NULL, NULL);
}
