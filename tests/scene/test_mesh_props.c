/* test_mesh_props.c — sim/scene/mesh.c at its edges: boxes (empty ones,
 * points on a face count as inside, boxes touching on one face overlap,
 * projective transforms divide by w unless w is 0), polygon counts, the
 * Newell normal's direction and size, area-weighted vertex normals,
 * appending meshes (indices offset, normals and colours kept only when
 * both sides have them) and every error of scene_mesh_validate with its
 * polygon index.  Found unchecked by make mutate (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/mesh.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static SceneBox box(Vec3 lo, Vec3 hi)
{
    return scene_box_add_point(scene_box_add_point(scene_box_empty(), lo), hi);
}

static gboolean same(Vec3 a, Vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

static void test_boxes(void **st)
{
    (void)st;
    SceneBox e = scene_box_empty(), b = box(vec3(1, 2, 3), vec3(4, 6, 8));
    assert_true(scene_box_is_empty(e));
    assert_false(scene_box_is_empty(b));
    assert_true(same(scene_box_center(e), vec3(0, 0, 0)));
    assert_true(same(scene_box_size(e), vec3(0, 0, 0)));
    assert_true(scene_box_radius(e) == 0);
    /* empty by one inverted axis (mesh.h): the same zero centre and size */
    SceneBox inv = {{1, 2, 3}, {4, 5, 0}};
    assert_true(scene_box_is_empty(inv));
    assert_true(same(scene_box_center(inv), vec3(0, 0, 0)));
    assert_true(same(scene_box_size(inv), vec3(0, 0, 0)));
    assert_true(scene_box_radius(inv) == 0);
    assert_true(same(scene_box_center(b), vec3(2.5, 4, 5.5)));
    assert_true(same(scene_box_size(b), vec3(3, 4, 5)));
    NEAR(scene_box_radius(b), 0.5 * sqrt(50), 1e-12);
    /* a single point is a box; flat boxes are not empty */
    SceneBox p = box(vec3(1, 1, 1), vec3(1, 1, 1));
    assert_false(scene_box_is_empty(p));
    for (int axis = 0; axis < 3; axis++) {
        SceneBox f = b;
        double *mx = axis == 0 ? &f.max.x : axis == 1 ? &f.max.y : &f.max.z;
        double *mn = axis == 0 ? &f.min.x : axis == 1 ? &f.min.y : &f.min.z;
        *mx = *mn;
        assert_false(scene_box_is_empty(f));
        *mx = *mn - 1e-9;
        assert_true(scene_box_is_empty(f));
    }
    /* union with an empty box either side */
    SceneBox u = scene_box_union(e, b);
    assert_true(same(u.min, b.min) && same(u.max, b.max));
    u = scene_box_union(b, e);
    assert_true(same(u.min, b.min) && same(u.max, b.max));
    u = scene_box_union(b, box(vec3(-1, 7, 4), vec3(0, 9, 5)));
    assert_true(same(u.min, vec3(-1, 2, 3)) && same(u.max, vec3(4, 9, 8)));
    assert_true(scene_box_is_empty(scene_box_union(e, e)));
    /* contains: faces and corners are inside, anything past one is not */
    assert_true(scene_box_contains(b, vec3(1, 2, 3)));
    assert_true(scene_box_contains(b, vec3(4, 6, 8)));
    const Vec3 outside[] = {{0.99, 3, 4}, {4.01, 3, 4}, {2, 1.99, 4},
                            {2, 6.01, 4}, {2, 3, 2.99}, {2, 3, 8.01}};
    for (guint i = 0; i < 6; i++)
        assert_false(scene_box_contains(b, outside[i]));
    assert_false(scene_box_contains(e, vec3(0, 0, 0)));
}

static void test_overlaps(void **st)
{
    (void)st;
    SceneBox b = box(vec3(0, 0, 0), vec3(1, 1, 1));
    /* touching on one face (the far one or the near one): overlapping */
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            Vec3 d = vec3(axis == 0, axis == 1, axis == 2);
            Vec3 rest = vec3_scale(vec3_sub(vec3(1, 1, 1), d), 0.25);
            Vec3 lo = vec3_add(rest, vec3_scale(d, side ? 1 : -1));
            Vec3 hi = vec3_add(vec3_scale(rest, 3), vec3_scale(d, side ? 2 : 0));
            SceneBox t = box(lo, hi);
            assert_true(scene_box_overlaps(b, t));
            assert_true(scene_box_overlaps(t, b));
        }
    /* separated along each axis alone */
    for (int axis = 0; axis < 3; axis++) {
        Vec3 d = vec3(axis == 0, axis == 1, axis == 2);
        SceneBox t = box(vec3_scale(d, 1.01), vec3_add(vec3_scale(d, 2),
                                                       vec3(0.5, 0.5, 0.5)));
        assert_false(scene_box_overlaps(b, t));
        assert_false(scene_box_overlaps(t, b));
        t = box(vec3_scale(d, -2), vec3_sub(vec3(0.5, 0.5, 0.5),
                                            vec3_scale(d, 0.51)));
        assert_false(scene_box_overlaps(b, t));
        assert_false(scene_box_overlaps(t, b));
    }
    assert_false(scene_box_overlaps(scene_box_empty(), b));
    assert_false(scene_box_overlaps(b, scene_box_empty()));
}

static void test_box_transform(void **st)
{
    (void)st;
    SceneBox b = box(vec3(-1, 0, 2), vec3(1, 3, 4));
    SceneBox t = scene_box_transform(b, mat4_translate(1, 2, 3));
    assert_true(same(t.min, vec3(0, 2, 5)) && same(t.max, vec3(2, 5, 7)));
    t = scene_box_transform(b, mat4_rotate(vec3(0, 0, 1), G_PI / 2));
    NEAR(t.min.x, -3, 1e-12);
    NEAR(t.max.x, 0, 1e-12);
    NEAR(t.min.y, -1, 1e-12);
    NEAR(t.max.y, 1, 1e-12);
    Mat4 h = mat4_identity();
    h.m[3][3] = 2; /* w = 2 everywhere: halved */
    t = scene_box_transform(b, h);
    assert_true(same(t.min, vec3(-0.5, 0, 1)) && same(t.max, vec3(0.5, 1.5, 2)));
    h.m[3][3] = 0; /* w = 0 everywhere: left as they are */
    t = scene_box_transform(b, h);
    assert_true(same(t.min, b.min) && same(t.max, b.max));
    assert_true(scene_box_is_empty(scene_box_transform(scene_box_empty(), h)));
}

static SceneMesh *two_polys(void)
{
    SceneMesh *m = scene_mesh_new();
    for (int i = 0; i < 5; i++)
        scene_mesh_add_vertex(m, vec3(i & 1 ? 2 : 0, i & 2 ? 2 : 0, i == 4));
    assert_int_equal(scene_mesh_add_quad(m, 0, 1, 3, 2, scene_color(1, 0, 0), 7),
                     0);
    assert_int_equal(scene_mesh_add_tri(m, 0, 1, 4, scene_color(0, 1, 0), 9), 1);
    return m;
}

static void test_counts_and_normals(void **st)
{
    (void)st;
    SceneMesh *m = two_polys();
    assert_int_equal(scene_mesh_n_vertices(m), 5);
    assert_int_equal(scene_mesh_n_polys(m), 2);
    assert_int_equal(scene_mesh_n_triangles(m), 3);
    assert_int_equal(scene_mesh_count_ngons(m, 4), 1);
    assert_int_equal(scene_mesh_count_ngons(m, 3), 1);
    assert_int_equal(scene_mesh_count_ngons(m, 5), 0);
    SceneBox b = scene_mesh_bbox(m);
    assert_true(same(b.min, vec3(0, 0, 0)) && same(b.max, vec3(2, 2, 1)));
    /* the quad (0,0) (2,0) (2,2) (0,2) faces +z */
    Vec3 n = scene_mesh_poly_normal(m, 0);
    assert_true(same(n, vec3(0, 0, 1)));
    /* the triangle (0,0,0) (2,0,0) (0,0,1) faces -y */
    n = scene_mesh_poly_normal(m, 1);
    NEAR(n.y, -1, 1e-12);
    /* vertex normals: area-weighted sums, normalised; vertex 0 is shared
     * by the quad (area 4) and the triangle (area 1) */
    scene_mesh_compute_normals(m);
    assert_int_equal(m->normals->len, 5);
    Vec3 v0 = g_array_index(m->normals, Vec3, 0);
    NEAR(v0.z, 4 / sqrt(17), 1e-12);
    NEAR(v0.y, -1 / sqrt(17), 1e-12);
    Vec3 v3 = g_array_index(m->normals, Vec3, 3);
    assert_true(same(v3, vec3(0, 0, 1)));
    Vec3 v4 = g_array_index(m->normals, Vec3, 4);
    NEAR(v4.y, -1, 1e-12);
    /* tilted in x: the Newell sum picks up every component */
    SceneMesh *t = scene_mesh_new();
    scene_mesh_add_vertex(t, vec3(0, 0, 0));
    scene_mesh_add_vertex(t, vec3(0, 1, 0));
    scene_mesh_add_vertex(t, vec3(0, 0, 1));
    scene_mesh_add_tri(t, 0, 1, 2, scene_color(1, 1, 1), 0);
    assert_true(same(scene_mesh_poly_normal(t, 0), vec3(1, 0, 0)));
    scene_mesh_free(t);
    scene_mesh_free(m);
}

/* Vertex normals start from zero: a vertex no polygon uses keeps the
 * zero vector, and a flat triangle's normals have exactly zero x and y. */
static void test_normals_from_zero(void **st)
{
    (void)st;
    SceneMesh *m = scene_mesh_new();
    scene_mesh_add_vertex(m, vec3(0, 0, 0));
    scene_mesh_add_vertex(m, vec3(1, 0, 0));
    scene_mesh_add_vertex(m, vec3(0, 1, 0));
    scene_mesh_add_vertex(m, vec3(5, 5, 5)); /* in no polygon */
    scene_mesh_add_tri(m, 0, 1, 2, scene_color(1, 1, 1), 0);
    scene_mesh_compute_normals(m);
    for (guint i = 0; i < 3; i++) {
        Vec3 n = g_array_index(m->normals, Vec3, i);
        assert_true(n.x == 0 && n.y == 0 && n.z == 1);
    }
    Vec3 lone = g_array_index(m->normals, Vec3, 3);
    assert_true(lone.x == 0 && lone.y == 0 && lone.z == 0);
    scene_mesh_free(m);
}

static void test_append(void **st)
{
    (void)st;
    SceneMesh *a = two_polys(), *b = two_polys();
    scene_mesh_compute_normals(b);
    g_array_set_size(b->colors, 5);
    for (guint i = 0; i < 5; i++)
        g_array_index(b->colors, SceneColor, i) = scene_color(0, 0, i / 4.0f);
    /* into an empty mesh: normals and colours kept, rotated with it */
    SceneMesh *d = scene_mesh_new();
    scene_mesh_append(d, b, mat4_rotate(vec3(1, 0, 0), G_PI / 2));
    assert_int_equal(d->normals->len, 5);
    assert_int_equal(d->colors->len, 5);
    Vec3 n3 = g_array_index(d->normals, Vec3, 3);
    NEAR(n3.y, -1, 1e-12); /* +z turned about x by 90 degrees */
    assert_true(g_array_index(d->colors, SceneColor, 4).b == 1);
    /* then a second copy, translated: indices and starts offset */
    scene_mesh_append(d, b, mat4_translate(10, 0, 0));
    assert_int_equal(scene_mesh_n_vertices(d), 10);
    assert_int_equal(scene_mesh_n_polys(d), 4);
    assert_int_equal(d->normals->len, 10);
    assert_int_equal(scene_mesh_poly_len(d, 2), 4);
    assert_int_equal(scene_mesh_poly_len(d, 3), 3);
    const uint32_t *q = scene_mesh_poly(d, 3);
    assert_true(q[0] == 5 && q[1] == 6 && q[2] == 9);
    assert_true(scene_mesh_vertex(d, 9).x == 10);
    assert_int_equal(g_array_index(d->poly_tag, uint32_t, 3), 9);
    assert_true(g_array_index(d->poly_color, SceneColor, 2).r == 1);
    assert_true(scene_mesh_validate(d, "d", NULL));
    /* a mesh without normals or colours drops both */
    scene_mesh_append(d, a, mat4_identity());
    assert_int_equal(d->normals->len, 0);
    assert_int_equal(d->colors->len, 0);
    assert_int_equal(scene_mesh_n_vertices(d), 15);
    /* ... and they stay dropped though the next one has them */
    scene_mesh_append(d, b, mat4_identity());
    assert_int_equal(d->normals->len, 0);
    assert_int_equal(d->colors->len, 0);
    /* one bare vertex already there: b's normals and colours dropped */
    SceneMesh *one = scene_mesh_new();
    scene_mesh_add_vertex(one, vec3(0, 0, 0));
    scene_mesh_append(one, b, mat4_identity());
    assert_int_equal(one->normals->len, 0);
    assert_int_equal(one->colors->len, 0);
    scene_mesh_free(one);
    /* a single coloured vertex with its normal, into an empty mesh: kept */
    SceneMesh *src = scene_mesh_new(), *dst = scene_mesh_new();
    scene_mesh_add_vertex(src, vec3(1, 2, 3));
    Vec3 up = vec3(0, 1, 0);
    SceneColor red = scene_color(1, 0, 0);
    g_array_append_val(src->normals, up);
    g_array_append_val(src->colors, red);
    scene_mesh_append(dst, src, mat4_identity());
    assert_int_equal(dst->normals->len, 1);
    assert_int_equal(dst->colors->len, 1);
    assert_true(g_array_index(dst->colors, SceneColor, 0).r == 1);
    scene_mesh_free(src);
    scene_mesh_free(dst);
    /* projective: w = 2 halves the points, w = 0 leaves them */
    SceneMesh *p = scene_mesh_new();
    Mat4 h = mat4_identity();
    h.m[3][3] = 2;
    scene_mesh_append(p, a, h);
    assert_true(same(scene_mesh_vertex(p, 3), vec3(1, 1, 0)));
    h.m[3][3] = 0;
    scene_mesh_append(p, a, h);
    assert_true(same(scene_mesh_vertex(p, 8), vec3(2, 2, 0)));
    /* a copy is equal and independent */
    SceneMesh *c = scene_mesh_copy(d);
    assert_int_equal(scene_mesh_n_polys(c), scene_mesh_n_polys(d));
    assert_memory_equal(c->idx->data, d->idx->data, d->idx->len * 4);
    scene_mesh_add_vertex(c, vec3(0, 0, 0));
    assert_int_equal(scene_mesh_n_vertices(d), 20);
    scene_mesh_free(c);
    scene_mesh_free(p);
    scene_mesh_free(d);
    scene_mesh_free(a);
    scene_mesh_free(b);
}

static void test_validate(void **st)
{
    (void)st;
    SceneMesh *m = two_polys();
    GError *err = NULL;
    assert_true(scene_mesh_validate(m, "m", &err));
    /* the last index of the last polygon one past the vertices */
    g_array_index(m->idx, uint32_t, m->idx->len - 1) = 5;
    assert_false(scene_mesh_validate(m, "m", &err));
    assert_string_equal(err->message, "m: polygon 1: found a vertex index out "
                                      "of range, expected a valid polygon");
    g_clear_error(&err);
    g_array_index(m->idx, uint32_t, m->idx->len - 1) = 4; /* the last one */
    assert_true(scene_mesh_validate(m, "m", NULL));
    /* the second polygon cut to two corners */
    g_array_index(m->start, uint32_t, 2) = 6;
    g_array_set_size(m->idx, 6);
    assert_false(scene_mesh_validate(m, "x.obj", &err));
    assert_string_equal(err->message, "x.obj: polygon 1: found fewer than 3 "
                                      "vertices, expected a valid polygon");
    g_clear_error(&err);
    scene_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_boxes),
        cmocka_unit_test(test_overlaps),
        cmocka_unit_test(test_box_transform),
        cmocka_unit_test(test_counts_and_normals),
        cmocka_unit_test(test_normals_from_zero),
        cmocka_unit_test(test_append),
        cmocka_unit_test(test_validate),
    };
    return cmocka_run_group_tests_name("mesh_props", tests, NULL, NULL);
}
