/* test_isosurface.c — marching-tetrahedra isosurfaces (closed, outward,
 * the right volume; seed 004's triangle count at the configured grid)
 * and the large-polygon set.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/isosurface.h"
#include "tests/scene/mesh_check.h"

/* One metaball, level 1: the sphere |p - c| = 0.25, closed, genus 0. */
static void test_sphere(void **st)
{
    (void)st;
    SceneIsoParams p = scene_iso_defaults();
    p.field = SCENE_FIELD_METABALLS;
    p.balls = 1;
    p.iso = 1;
    p.grid = 24;
    SceneMesh *m = scene_iso_mesh(&p);
    assert_true(scene_mesh_n_polys(m) > 500);
    assert_int_equal(mesh_check_open_edges(m), 0);
    long chi = (long)scene_mesh_n_vertices(m) - (long)mesh_check_edges(m) +
               (long)scene_mesh_n_polys(m);
    assert_int_equal(chi, 2);
    double vol = mesh_check_volume(m), want = 4.0 / 3 * G_PI * 0.015625;
    /* Triangles face f < iso, outward for a ball: positive volume, a
     * little over the sphere's because linear interpolation of the convex
     * field 1/d^2 places vertices slightly outside it. */
    assert_true(vol > 0.95 * want && vol < 1.1 * want);
    scene_mesh_free(m);
    /* closed: back faces never show, so the scene may be culled */
    Scene *s = scene_iso_new(&p);
    assert_false(s->two_sided);
    scene_free(s);
}

/* Seed 004's 355,948 small polygons: the configured grid (80) gives a
 * count within 2 %; the count grows as grid^2. */
static void test_gyroid_count(void **st)
{
    (void)st;
    SceneIsoParams p = scene_iso_defaults();
    p.grid = 80;
    Scene *s = scene_iso_new(&p);
    uint64_t n = scene_n_triangles(s);
    print_message("isosurface gyroid grid 80: %" G_GUINT64_FORMAT
                  " triangles (seed 004: 355,948)\n",
                  n);
    assert_true(n > 355948 * 0.98 && n < 355948 * 1.02);
    SceneMesh *m = g_ptr_array_index(s->meshes, 0);
    assert_int_equal(scene_mesh_count_ngons(m, 3), scene_mesh_n_polys(m));
    /* small: mean edge well under 1 % of the box */
    Vec3 a = scene_mesh_vertex(m, scene_mesh_poly(m, 0)[0]);
    Vec3 b = scene_mesh_vertex(m, scene_mesh_poly(m, 0)[1]);
    assert_true(vec3_len(vec3_sub(a, b)) < 0.04);
    /* consistently wound although the gyroid is exactly 0 at many
     * lattice points (mesh_check_open_edges() fails on a directed edge
     * used twice), and cut open by the lattice's faces: back faces show */
    assert_true(mesh_check_open_edges(m) > 0);
    assert_true(s->two_sided);
    scene_free(s);
    p.grid = 40;
    SceneMesh *q = scene_iso_mesh(&p);
    double ratio = (double)n / scene_mesh_n_polys(q);
    print_message("isosurface gyroid grid 40: %u triangles\n",
                  scene_mesh_n_polys(q));
    assert_true(ratio > 3.6 && ratio < 4.4);
    scene_mesh_free(q);
}

/* Fraction of [-1, 1]^2 inside convex polygon i (a 64 x 64 grid of
 * sample points; independent of the generator's clipping). */
static double screen_cover(const SceneMesh *m, guint i)
{
    const uint32_t *v = scene_mesh_poly(m, i);
    guint n = scene_mesh_poly_len(m, i), in = 0;
    for (int gy = 0; gy < 64; gy++)
        for (int gx = 0; gx < 64; gx++) {
            double x = -1 + (gx + 0.5) / 32, y = -1 + (gy + 0.5) / 32;
            int pos = 0, neg = 0;
            for (guint k = 0; k < n; k++) {
                Vec3 a = scene_mesh_vertex(m, v[k]);
                Vec3 b = scene_mesh_vertex(m, v[(k + 1) % n]);
                double c = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
                pos += c > 0, neg += c < 0;
            }
            in += pos == 0 || neg == 0;
        }
    return in / 4096.0;
}

static void test_bigpoly(void **st)
{
    (void)st;
    SceneBigPolyParams p = scene_bigpoly_defaults();
    p.count = 2000;
    p.huge_fraction = 0.1;
    Scene *s = scene_bigpoly_new(&p);
    const SceneMesh *m = g_ptr_array_index(s->meshes, 0);
    assert_int_equal(scene_mesh_n_polys(m), 2000);
    Mat4 vp = scene_camera_view_proj(&s->camera);
    guint huge = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        SceneBox b = scene_box_empty();
        const uint32_t *v = scene_mesh_poly(m, i);
        for (guint k = 0; k < scene_mesh_poly_len(m, i); k++)
            b = scene_box_add_point(b, scene_mesh_vertex(m, v[k]));
        b = scene_box_transform(b, vp);
        assert_true(b.min.z >= -1 && b.max.z <= 1);
        Vec3 sz = scene_box_size(b);
        if (sz.x * sz.y >= 0.75 * 4) {
            huge++;
            assert_true(screen_cover(m, i) > 0.74); /* "over 3/4" */
        } else {
            assert_true(screen_cover(m, i) < 0.5);
        }
        assert_true(scene_mesh_poly_normal(m, i).z > 0.999);
    }
    assert_true(huge > 150 && huge < 250); /* ~10 % of 2000 */
    Scene *t = scene_bigpoly_new(&p);      /* deterministic */
    const SceneMesh *m2 = g_ptr_array_index(t->meshes, 0);
    assert_memory_equal(m->pos->data, m2->pos->data,
                        m->pos->len * sizeof(Vec3));
    scene_free(t);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere),
        cmocka_unit_test(test_gyroid_count),
        cmocka_unit_test(test_bigpoly),
    };
    return cmocka_run_group_tests_name("isosurface", tests, NULL, NULL);
}
