/* test_argus_scenes.c — the Nurbs and March generators of seed 002 have
 * the slides' counts (117,504 stripped triangles in 102 patches of 14 x 14
 * control points; about 53,346 triangles from a 64^3 volume in 16^3
 * cells, within 1 %), strips really share edges, the patch surface is
 * continuous across patches, cells come out in increasing order, and the
 * March scene keeps its defaults, frame, view and fill. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/march.h"
#include "sim/scene/nurbs.h"

static void test_nurbs_counts_and_strips(void **state)
{
    (void)state;
    SceneNurbsParams p = scene_nurbs_defaults();
    SceneMesh *m = scene_nurbs_mesh(&p);
    assert_int_equal(p.patches_u * p.patches_v, 102);
    assert_int_equal(scene_mesh_n_polys(m), 117504);
    guint shared2 = 0;
    for (guint i = 1; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *a = scene_mesh_poly(m, i - 1),
                       *b = scene_mesh_poly(m, i);
        guint n = 0;
        for (int x = 0; x < 3; x++)
            for (int y = 0; y < 3; y++)
                n += a[x] == b[y];
        shared2 += n == 2;
    }
    /* 24 strips of 48 triangles per patch: 47 continuations each */
    assert_int_equal(shared2, 102 * 24 * 47);
    assert_int_equal(g_array_index(m->poly_tag, uint32_t, 117503), 101);
    scene_mesh_free(m);
}

static void test_nurbs_patches_meet(void **state)
{
    (void)state;
    SceneNurbsParams p = scene_nurbs_defaults();
    /* the end of patch (0, 0) in t is the start of patch (0, 1) */
    for (double s = 0; s <= 11; s += 2.75) {
        Vec3 a = scene_nurbs_eval(&p, 0, 0, s, 11);
        Vec3 b = scene_nurbs_eval(&p, 0, 1, s, 0);
        assert_true(vec3_len(vec3_sub(a, b)) < 1e-9);
    }
    /* and a patch is not a point: its corners differ */
    Vec3 c0 = scene_nurbs_eval(&p, 0, 0, 0, 0),
         c1 = scene_nurbs_eval(&p, 0, 0, 11, 11);
    assert_true(vec3_len(vec3_sub(c0, c1)) > 0.1);
}

static void test_march_count_and_cells(void **state)
{
    (void)state;
    SceneMarchParams p = scene_march_defaults();
    assert_int_equal(scene_march_cells(&p), 4);
    SceneMesh *m = scene_iso_mesh_cells(&p.iso, p.cell);
    double n = scene_mesh_n_polys(m);
    assert_true(fabs(n - 53346) / 53346 < 0.01);
    assert_int_equal(n, 53340); /* march.h's count for the defaults */
    uint32_t last = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        uint32_t t = g_array_index(m->poly_tag, uint32_t, i);
        assert_true(t >= last && t < 64);
        last = t;
    }
    /* the same surface as the one-piece polygonisation */
    SceneMesh *whole = scene_iso_mesh(&p.iso);
    assert_int_equal(scene_mesh_n_polys(whole), scene_mesh_n_polys(m));
    scene_mesh_free(whole);
    scene_mesh_free(m);
}

/* The defaults field by field (march.h), and the scene: 1200 x 1000,
 * two-sided, one white untransformed instance of the cell-ordered mesh,
 * seen from (1, 1, 1) (azimuth 45, elevation atan(1 / sqrt 2)) with
 * aspect 1.2 and the vertices filling exactly `fill` of the frame. */
static void test_march_scene(void **state)
{
    (void)state;
    SceneMarchParams p = scene_march_defaults();
    assert_int_equal(p.iso.field, SCENE_FIELD_METABALLS);
    assert_true(p.iso.grid == 64 && p.iso.balls == 10 && p.iso.seed == 2);
    assert_true(p.iso.iso == 1.67 && p.cell == 16 && p.fill == 0.95);
    assert_true(p.iso.color.r == 0.95f && p.iso.color.g == 0.90f &&
                p.iso.color.b == 0.80f);
    assert_true(p.iso.periods == scene_iso_defaults().periods);
    p.iso.grid = 12;
    p.cell = 4;
    p.fill = 0.5;
    Scene *s = scene_march_new(&p);
    assert_string_equal(s->name, "march");
    assert_true(s->width == 1200 && s->height == 1000 && s->two_sided);
    assert_int_equal(scene_n_instances(s), 1);
    SceneMesh *cells = scene_iso_mesh_cells(&p.iso, p.cell);
    const SceneMesh *m = scene_instance_mesh(s, 0);
    assert_int_equal(scene_mesh_n_polys(m), scene_mesh_n_polys(cells));
    for (guint i = 0; i < scene_mesh_n_polys(m); i++)
        assert_int_equal(g_array_index(m->poly_tag, uint32_t, i),
                         g_array_index(cells->poly_tag, uint32_t, i));
    scene_mesh_free(cells);
    SceneCamera c = s->camera;
    Vec3 d = vec3_norm(vec3_sub(c.eye, c.target));
    double k = 1 / sqrt(3.0);
    assert_true(fabs(d.x - k) < 1e-12 && fabs(d.y - k) < 1e-12 &&
                fabs(d.z - k) < 1e-12);
    assert_true(c.aspect == 1.2 && c.fov_deg == 45 &&
                c.proj == SCENE_PERSPECTIVE);
    Mat4 vp = scene_camera_view_proj(&c);
    double hi = 0;
    for (guint i = 0; i < scene_mesh_n_vertices(m); i++) {
        Vec4 q = mat4_apply_point(vp, scene_mesh_vertex(m, i));
        hi = fmax(hi, fmax(fabs(q.x / q.w), fabs(q.y / q.w)));
    }
    assert_true(fabs(hi - 0.5) < 1e-6);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nurbs_counts_and_strips),
        cmocka_unit_test(test_nurbs_patches_meet),
        cmocka_unit_test(test_march_count_and_cells),
        cmocka_unit_test(test_march_scene),
    };
    return cmocka_run_group_tests_name("argus_scenes", tests, NULL, NULL);
}
