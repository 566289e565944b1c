/* test_pipeline.c — clipping, culling and the numerically hard cases. */
#include "tests/raster/rast_testutil.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

static SceneCamera camera(Vec3 eye, Vec3 target, double fov, double near)
{
    SceneCamera c = scene_camera_default();
    c.eye = eye;
    c.target = target;
    c.up = vec3(0, 1, 0);
    c.fov_deg = fov;
    c.near = near;
    c.far = 100;
    return c;
}

static TuCoverage *cover_mesh(const RastView *v, const SceneMesh *m, Mat4 model,
                              RastCounters *c)
{
    TuCoverage *cv = tu_coverage_new(v->width, v->height);
    rast_draw_mesh(v, m, model, scene_color(1, 1, 1), 0, NULL,
                   tu_coverage_sink(cv), c);
    return cv;
}

/* An edge crossing the near plane is cut at bit-identical points by the
 * two triangles that share it, whatever their windings. */
static void test_clip_shared_edge(void **state)
{
    (void)state;
    RastVert a = tu_cv(0.3, 0.1, -2.0, 0.5), b = tu_cv(-0.2, 0.4, 0.7, 1.3);
    RastVert c = tu_cv(0.9, -0.6, 0.2, 1.1), d = tu_cv(-0.8, -0.5, 0.3, 1.2);
    RastVert t1[3] = {a, b, c}, t2[3] = {b, a, d}, o1[RAST_CLIP_MAX],
             o2[RAST_CLIP_MAX];
    int n1 = rast_clip_polygon(t1, 3, 4.0, o1);
    int n2 = rast_clip_polygon(t2, 3, 4.0, o2);
    assert_int_equal(n1, 4);
    assert_int_equal(n2, 4);
    int matches = 0;
    for (int i = 0; i < n1; i++)
        for (int j = 0; j < n2; j++)
            if (memcmp(&o1[i].pos, &o2[j].pos, sizeof(Vec4)) == 0) {
                assert_true(fabs(o1[i].pos.z + o1[i].pos.w) < 1e-15 ||
                            o1[i].pos.z + o1[i].pos.w > 0);
                matches++;
            }
    assert_int_equal(matches, 2); /* b and the cut point */
    for (int i = 0; i < n1; i++)
        assert_int_equal(rast_clip_outcode(o1[i].pos, 4.0) & RAST_OUT_NEAR, 0);
}

/* Triangles behind the eye (w <= 0) vanish; one crossing w = 0 is
 * clipped and drawn with depths in [0, 1]. */
static void test_behind_eye(void **state)
{
    (void)state;
    RastView v = rast_view_make(mat4_identity(), 32, 32);
    v.cull_back = FALSE;
    TuCoverage *cv = tu_coverage_new(32, 32);
    RastCounters c = {0};
    RastVert behind[3] = {tu_cv(0, 0, 0, -1), tu_cv(1, 0, 0, -2),
                          tu_cv(0, 1, 0, 0)};
    rast_draw_clip_polygon(&v, behind, 3, 0, tu_coverage_sink(cv), &c);
    assert_int_equal(c.rejected, 1);
    assert_int_equal(c.pixels, 0);
    /* Vertices with x/w of both signs: naive division would flip them. */
    RastVert cross[3] = {tu_cv(-0.5, -0.5, 0.0, 1.0),
                         tu_cv(0.5, -0.5, 0.0, 1.0), tu_cv(0.2, 3.0, 0, -1.0)};
    rast_draw_clip_polygon(&v, cross, 3, 1, tu_coverage_sink(cv), &c);
    assert_int_equal(c.clipped, 1);
    assert_true(c.pixels > 100);
    assert_int_equal(tu_coverage_max(cv), 1);
    /* The kept part lies above y = -0.5 in NDC: rows 24.. stay empty. */
    for (int y = 25; y < 32; y++)
        for (int x = 0; x < 32; x++)
            assert_int_equal(cv->count[y * 32 + x], 0);
    tu_coverage_free(cv);
    /* The clip-space origin (w = 0) lies on the near (z >= -w), far
     * (z <= w) and every guard-band plane (|x|, |y| <= g w): only the w
     * plane keeps it from the viewport's division by w, and the cut
     * points must not round below w = RAST_CLIP_WMIN (this aborted).
     * Every point (s x, s y, 0, s) of the edges to it projects onto
     * their other end, so what is left has no area. */
    RastCounters c2 = {0};
    cv = tu_coverage_new(32, 32);
    RastVert at_eye[3] = {tu_cv(-0.5, -0.5, 0.0, 1.0),
                          tu_cv(0.5, -0.5, 0.0, 1.0), tu_cv(0, 0, 0, 0)};
    rast_draw_clip_polygon(&v, at_eye, 3, 2, tu_coverage_sink(cv), &c2);
    assert_int_equal(c2.prims, 1);
    assert_int_equal(c2.clipped, 1);
    assert_int_equal(c2.degenerate, 1);
    assert_int_equal(c2.pixels, 0);
    tu_coverage_free(cv);
}

/* The eye inside a closed sphere of inward-facing polygons, looking in
 * several directions: every pixel is covered exactly once, with polygons
 * crossing the near plane and behind the eye.  The outward sphere is
 * entirely back-facing. */
static void test_inside_sphere_watertight(void **state)
{
    (void)state;
    SceneMesh *in = tu_sphere(1.0, 37, 23, TRUE);
    SceneMesh *out = tu_sphere(1.0, 37, 23, FALSE);
    Vec3 dirs[4] = {vec3(0, 0, -1), vec3(1, 0.3, 0.2), vec3(-0.2, 0.9, 0.1),
                    vec3(0.3, -1, 0.6)};
    for (int i = 0; i < 4; i++) {
        SceneCamera cam = camera(vec3(0.1, -0.05, 0.2), dirs[i], 100, 0.05);
        cam.target = vec3_add(cam.eye, dirs[i]);
        RastView v = rast_view_for_camera(&cam, 96, 72);
        Mat4 model = mat4_rotate(vec3(0.3, 1, 0.2), 0.7 * i);
        RastCounters c = {0};
        TuCoverage *cv = cover_mesh(&v, in, model, &c);
        assert_int_equal(tu_coverage_count(cv, 1), 96 * 72);
        assert_true(c.rejected > 0 && c.clipped > 0);
        assert_int_equal(c.culled, 0);
        tu_coverage_free(cv);
        RastCounters co = {0};
        cv = cover_mesh(&v, out, model, &co);
        assert_int_equal(co.pixels, 0);
        assert_true(co.culled > 0);
        tu_coverage_free(cv);
    }
    scene_mesh_free(in);
    scene_mesh_free(out);
}

/* From outside: the silhouette is covered once with culling, twice
 * without; its area matches the projected disc. */
static void test_outside_sphere(void **state)
{
    (void)state;
    SceneMesh *m = tu_sphere(1.0, 64, 32, FALSE);
    SceneCamera cam = camera(vec3(0, 0, 4), vec3(0, 0, 0), 40, 0.5);
    RastView v = rast_view_for_camera(&cam, 128, 128);
    RastCounters c = {0};
    TuCoverage *cv = cover_mesh(&v, m, mat4_identity(), &c);
    assert_int_equal(tu_coverage_max(cv), 1);
    /* Angular radius asin(1/4); the image spans tan(20°) each way. */
    double r = tan(asin(0.25)) / tan(G_PI / 9) * 64;
    double disc = G_PI * r * r;
    assert_true(fabs(tu_coverage_count(cv, 1) - disc) < 0.02 * disc);
    assert_true(c.culled > scene_mesh_n_polys(m) / 3);
    tu_coverage_free(cv);
    v.cull_back = FALSE;
    cv = cover_mesh(&v, m, mat4_identity(), &c);
    assert_int_equal(tu_coverage_max(cv), 2);
    assert_true(fabs(tu_coverage_count(cv, 2) - disc) < 0.02 * disc);
    tu_coverage_free(cv);
    scene_mesh_free(m);
}

/* Zero-area, repeated-vertex, collinear and non-finite polygons. */
static void test_degenerate(void **state)
{
    (void)state;
    RastView v = rast_view_make(mat4_identity(), 16, 16);
    v.cull_back = FALSE;
    RastCounters c = {0};
    TuCoverage *cv = tu_coverage_new(16, 16);
    RastVert same[3] = {tu_cv(0.1, 0.1, 0, 1), tu_cv(0.1, 0.1, 0, 1),
                        tu_cv(0.1, 0.1, 0, 1)};
    RastVert line[3] = {tu_cv(-1, -1, 0, 1), tu_cv(0, 0, 0.5, 1),
                        tu_cv(1, 1, 0, 1)};
    RastVert tiny[3] = {tu_cv(0, 0, 0, 1), tu_cv(1e-9, 0, 0, 1),
                        tu_cv(0, 1e-9, 0, 1)};
    RastVert nan[3] = {tu_cv(0, 0, 0, 1), tu_cv(NAN, 0, 0, 1),
                       tu_cv(0, 1, 0, 1)};
    RastVert inf[3] = {tu_cv(0, 0, 0, 1), tu_cv(INFINITY, 0, 0, 1),
                       tu_cv(0, 1, 0, 1)};
    rast_draw_clip_polygon(&v, same, 3, 0, tu_coverage_sink(cv), &c);
    rast_draw_clip_polygon(&v, line, 3, 1, tu_coverage_sink(cv), &c);
    rast_draw_clip_polygon(&v, tiny, 3, 2, tu_coverage_sink(cv), &c);
    rast_draw_clip_polygon(&v, nan, 3, 3, tu_coverage_sink(cv), &c);
    rast_draw_clip_polygon(&v, inf, 3, 4, tu_coverage_sink(cv), &c);
    assert_int_equal(c.prims, 5);
    assert_int_equal(c.degenerate, 3);
    assert_int_equal(c.rejected, 2);
    assert_int_equal(c.pixels, 0);
    tu_coverage_free(cv);
}

/* Vertices at 1e7 (far outside the screen) are cut by the guard band; a
 * quad of two such triangles still covers every pixel once. */
static void test_huge_screen_coordinates(void **state)
{
    (void)state;
    RastView v = rast_view_make(mat4_identity(), 50, 40);
    RastCounters c = {0};
    TuCoverage *cv = tu_coverage_new(50, 40);
    RastVert q[4] = {tu_cv(-1e7, -9999999.7, 0.1, 1), tu_cv(2e7, -1e7, 0.2, 1),
                     tu_cv(1e7, 1e7, 0.3, 1), tu_cv(-1e7, 1.3e7, 0.4, 1)};
    RastVert t1[3] = {q[0], q[1], q[2]}, t2[3] = {q[0], q[2], q[3]};
    rast_draw_clip_polygon(&v, t1, 3, 0, tu_coverage_sink(cv), &c);
    rast_draw_clip_polygon(&v, t2, 3, 1, tu_coverage_sink(cv), &c);
    assert_int_equal(tu_coverage_count(cv, 1), 50 * 40);
    assert_int_equal(c.clipped, 2);
    tu_coverage_free(cv);
}

static RastImage *render(const RastView *v, const SceneMesh *m, Mat4 model)
{
    RastZBuffer *zb = rast_zbuffer_new(v->width, v->height);
    RastCounters c = {0};
    rast_draw_mesh(v, m, model, scene_color(1, 1, 1), 0, NULL,
                   rast_zbuffer_sink(zb), &c);
    RastImage *img = rast_image_new(v->width, v->height);
    rast_image_from_zbuffer(img, zb, (RastColor){0, 0, 0});
    rast_zbuffer_free(zb);
    return img;
}

/* World coordinates around 1e7: the same view of the same object,
 * translated by 1e7, gives (almost) the same picture. */
static void test_world_at_1e7(void **state)
{
    (void)state;
    SceneMesh *m = tu_sphere(1.0, 40, 20, FALSE);
    Vec3 off = vec3(1.0e7, -1.0e7, 1.0e7);
    SceneCamera c0 = camera(vec3(0.5, 1, 3.5), vec3(0, 0, 0), 45, 0.1);
    SceneCamera c1 = c0;
    c1.eye = vec3_add(c0.eye, off);
    c1.target = off;
    RastView v0 = rast_view_for_camera(&c0, 100, 100);
    RastView v1 = rast_view_for_camera(&c1, 100, 100);
    v1.light_dir = v0.light_dir;
    RastImage *a = render(&v0, m, mat4_identity());
    RastImage *b = render(&v1, m, mat4_translate(off.x, off.y, off.z));
    /* Double rounding at 1e7 is ~2e-9 world units, 1e-7 pixel here: at
     * most a handful of edge pixels may flip. */
    assert_true(rast_image_diff(a, b) <= 10);
    rast_image_free(a);
    rast_image_free(b);
    scene_mesh_free(m);
}

/* Drift through 64 nested transforms.  Bound (docs/raster.md): composing
 * 64 unit-determinant rotations-with-translation keeps every matrix entry
 * within 64 * 8 * DBL_EPSILON * (1 + |t|) of the exact product, and
 * points agree to 1e-12 relative; the pictures agree pixel for pixel
 * except at most a few edge pixels. */
static void test_nested_transforms(void **state)
{
    (void)state;
    Mat4 step = mat4_mul(mat4_translate(0.25, -0.125, 0.5),
                         mat4_rotate(vec3(0.2, 1, 0.3), 2 * G_PI / 64));
    Mat4 inv = mat4_mul(mat4_rotate(vec3(0.2, 1, 0.3), -2 * G_PI / 64),
                        mat4_translate(-0.25, 0.125, -0.5));
    Mat4 acc = mat4_identity();
    for (int i = 0; i < 64; i++)
        acc = mat4_mul(acc, step);
    for (int i = 0; i < 64; i++)
        acc = mat4_mul(acc, inv);
    double worst = 0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            worst = fmax(worst, fabs(acc.m[i][j] - (i == j)));
    assert_true(worst < 64 * 8 * DBL_EPSILON * 2);
    /* One full turn in 64 nested steps about the object's own axis. */
    Mat4 turn = mat4_identity();
    for (int i = 0; i < 64; i++)
        turn = mat4_mul(turn, mat4_rotate(vec3(0, 1, 0), 2 * G_PI / 64));
    Vec4 p = mat4_apply_point(turn, vec3(1e3, -2e3, 3e3));
    double rel = vec3_len(vec3(p.x - 1e3, p.y + 2e3, p.z - 3e3)) / 3.8e3;
    assert_true(rel < 1e-12);
    SceneMesh *m = tu_sphere(1.0, 33, 17, FALSE);
    SceneCamera cam = camera(vec3(0.3, 0.8, 3), vec3(0, 0, 0), 45, 0.1);
    RastView v = rast_view_for_camera(&cam, 96, 96);
    RastImage *a = render(&v, m, mat4_identity());
    RastImage *b = render(&v, m, acc);
    RastImage *t = render(&v, m, turn);
    assert_true(rast_image_diff(a, b) <= 4);
    assert_true(rast_image_diff(a, t) <= 4);
    rast_image_free(a);
    rast_image_free(b);
    rast_image_free(t);
    scene_mesh_free(m);
}

/* Flat shading: one colour per polygon, ambient + diffuse |n.l| from its
 * face normal; Gouraud: per-vertex colours from the vertex normals,
 * interpolated across the polygon. */
static void test_shading(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    scene_mesh_add_vertex(m, vec3(-0.9, -0.9, 0));
    scene_mesh_add_vertex(m, vec3(0.9, -0.9, 0));
    scene_mesh_add_vertex(m, vec3(-0.9, 0.9, 0));
    scene_mesh_add_tri(m, 0, 1, 2, scene_color(1, 1, 1), 0);
    /* vertex 0 faces the light, vertex 1 is tilted 60 degrees off it,
     * vertex 2 90 degrees */
    Vec3 n[3] = {vec3(0, 0, 1), vec3(sin(G_PI / 3), 0, cos(G_PI / 3)),
                 vec3(0, 1, 0)};
    g_array_append_vals(m->normals, n, 3);
    RastView v = rast_view_make(mat4_identity(), 40, 40); /* light +z */
    v.shading = RAST_SHADE_FLAT;
    RastImage *flat = render(&v, m, mat4_identity());
    v.shading = RAST_SHADE_GOURAUD;
    RastImage *gour = render(&v, m, mat4_identity());
    /* screen y points down: vertex 0 is bottom-left, 1 bottom-right,
     * 2 top-left */
    uint32_t f0 = rast_image_get(flat, 2, 37),
             f1 = rast_image_get(flat, 35, 37);
    assert_int_equal(f0 & 0xff, 255); /* 0.25 + 0.75 |(0,0,1).l| */
    assert_int_equal(f1, f0);
    uint32_t g0 = rast_image_get(gour, 2, 37) & 0xff;
    uint32_t g1 = rast_image_get(gour, 35, 37) & 0xff;
    uint32_t g2 = rast_image_get(gour, 2, 3) & 0xff;
    /* near the vertices: 1, 0.25 + 0.75 cos 60 = 0.625, 0.25 */
    assert_true(g0 > 240);
    assert_true(g1 > 150 && g1 < 175);
    assert_true(g2 > 62 && g2 < 90);
    rast_image_free(flat);
    rast_image_free(gour);
    /* per-vertex colours, unlit: Gouraud blends red, green and blue from
     * the corners; flat uses the polygon's colour (white) */
    SceneColor vc[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    g_array_append_vals(m->colors, vc, 3);
    v.lighting = FALSE;
    gour = render(&v, m, mat4_identity());
    v.shading = RAST_SHADE_FLAT;
    flat = render(&v, m, mat4_identity());
    assert_int_equal(rast_image_get(flat, 2, 37), 0xffffffffu);
    uint32_t c0 = rast_image_get(gour, 2, 37), c1 = rast_image_get(gour, 35, 37);
    uint32_t c2 = rast_image_get(gour, 2, 3);
    assert_true((c0 & 0xff) > 220 && (c0 >> 8 & 0xff) < 35);   /* red */
    assert_true((c1 >> 8 & 0xff) > 220 && (c1 & 0xff) < 35);   /* green */
    assert_true((c2 >> 16 & 0xff) > 220 && (c2 & 0xff) < 35);  /* blue */
    rast_image_free(flat);
    rast_image_free(gour);
    scene_mesh_free(m);
}

/* Pixels where some channel differs by more than `tol`. */
static uint64_t diff_beyond(const RastImage *a, const RastImage *b, int tol)
{
    uint64_t n = 0;
    for (int y = 0; y < a->height; y++)
        for (int x = 0; x < a->width; x++) {
            uint32_t p = rast_image_get(a, x, y), q = rast_image_get(b, x, y);
            for (int k = 0; k < 24; k += 8) {
                int d = (int)((p >> k) & 0xff) - (int)((q >> k) & 0xff);
                if (d > tol || d < -tol) {
                    n++;
                    break;
                }
            }
        }
    return n;
}

/* Normals under non-uniform scaling go by the inverse transpose: an
 * ellipsoid drawn as a sphere with model = rotation x scale(1, 3, 0.4)
 * is lit exactly like the same ellipsoid pre-transformed into world
 * space (positions by the matrix, normals by its cofactors, re-derived
 * independently for flat shading from the world polygons).  Transforming
 * the normals by the model matrix itself tilts them (for a normal
 * (1, 1, 0)/sqrt 2 under scale(1, 3, 1): towards (1, 3, 0) instead of
 * (1, 1/3, 0)) and changes most pixels. */
static void test_nonuniform_scale_normals(void **state)
{
    (void)state;
    SceneMesh *m = tu_sphere(1.0, 36, 18, FALSE);
    scene_mesh_compute_normals(m);
    Mat4 model =
        mat4_mul(mat4_rotate(vec3(1, 0.5, 0.2), 0.7), mat4_scale(1, 3, 0.4));
    SceneMesh *w = scene_mesh_new();
    scene_mesh_append(w, m, model);
    SceneCamera cam = camera(vec3(1, 2, 9), vec3(0, 0, 0), 40, 0.1);
    RastView v = rast_view_for_camera(&cam, 120, 120);
    for (int shading = 0; shading < 2; shading++) {
        v.shading = shading ? RAST_SHADE_FLAT : RAST_SHADE_GOURAUD;
        RastImage *a = render(&v, m, model);
        RastImage *b = render(&v, w, mat4_identity());
        uint64_t bad = diff_beyond(a, b, 1);
        print_message("%s: %" G_GUINT64_FORMAT " pixels differ by > 1\n",
                      shading ? "flat" : "gouraud", bad);
        /* edge pixels may flip (positions round differently) */
        assert_true(bad <= 12);
        rast_image_free(a);
        rast_image_free(b);
    }
    scene_mesh_free(w);
    scene_mesh_free(m);
}

/* Exactly coplanar duplicates (depth ties) and random overlaps: the
 * picture does not depend on the order in which polygons are drawn. */
static void test_order_independent(void **state)
{
    (void)state;
    SceneMesh *m = tu_random_tris(3, 300, 0.6);
    /* Duplicate 100 triangles with new colours: ties on every pixel. */
    for (guint i = 0; i < 100; i++) {
        const uint32_t *t = scene_mesh_poly(m, i);
        uint32_t a = t[0], b = t[1], c = t[2];
        scene_mesh_add_tri(m, a, b, c, scene_color(1, 1, 0), 0);
    }
    guint np = scene_mesh_n_polys(m);
    uint32_t *order = g_new(uint32_t, np);
    for (guint i = 0; i < np; i++)
        order[i] = i;
    RastView v = rast_view_make(mat4_identity(), 80, 60);
    v.cull_back = FALSE;
    RastImage *f0, *s0;
    RastCounters c = {0};
    tu_render_both(&v, m, order, np, &f0, &s0, &c, &c);
    SimRng r;
    sim_rng_init(&r, 99, 0);
    for (int round = 0; round < 3; round++) {
        for (guint i = np - 1; i > 0; i--) {
            guint j = (guint)sim_rng_below(&r, i + 1);
            uint32_t t = order[i];
            order[i] = order[j];
            order[j] = t;
        }
        RastImage *f, *s;
        tu_render_both(&v, m, order, np, &f, &s, &c, &c);
        assert_true(rast_image_equal(f0, f));
        assert_true(rast_image_equal(s0, s));
        rast_image_free(f);
        rast_image_free(s);
    }
    assert_true(rast_image_equal(f0, s0));
    /* Ties went to the lower id: no yellow duplicate is visible. */
    uint64_t yellow = 0;
    for (int y = 0; y < 60; y++)
        for (int x = 0; x < 80; x++)
            yellow += rast_image_get(f0, x, y) == 0xff00ffffu;
    assert_int_equal(yellow, 0);
    rast_image_free(f0);
    rast_image_free(s0);
    g_free(order);
    scene_mesh_free(m);
}

/* Counters: vertices, primitives, culling on a closed sphere. */
static void test_counters(void **state)
{
    (void)state;
    SceneMesh *m = tu_sphere(1.0, 16, 8, FALSE);
    SceneCamera cam = camera(vec3(0.3, 0.7, 5), vec3(0, 0, 0), 45, 0.1);
    RastView v = rast_view_for_camera(&cam, 64, 64);
    RastCounters c = {0};
    TuCoverage *cv = cover_mesh(&v, m, mat4_identity(), &c);
    uint64_t nv = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++)
        nv += scene_mesh_poly_len(m, i);
    assert_int_equal(c.verts, nv);
    assert_int_equal(c.prims, scene_mesh_n_polys(m));
    assert_int_equal(c.culled + c.degenerate + c.rejected + cv->spans > 0, 1);
    /* Culling agrees with the object-space facing test. */
    uint64_t back = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        Vec3 p = scene_mesh_vertex(m, scene_mesh_poly(m, i)[0]);
        Vec3 n = scene_mesh_poly_normal(m, i);
        back += vec3_dot(n, vec3_sub(cam.eye, p)) < 0;
    }
    assert_int_equal(c.culled, back);
    assert_int_equal(c.spans, cv->spans);
    /* TPG is the pixels the spans cover; a convex closed mesh from
     * outside, culled, covers each once, so TPF (the winners) = TPG. */
    uint64_t sum = 0;
    for (int i = 0; i < 64 * 64; i++)
        sum += cv->count[i];
    assert_int_equal(c.pixels, sum);
    assert_int_equal(tu_coverage_max(cv), 1);
    assert_int_equal(c.clipped + c.rejected, 0);
    RastZBuffer *zb = rast_zbuffer_new(64, 64);
    RastCounters cz = {0};
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   rast_zbuffer_sink(zb), &cz);
    assert_int_equal(rast_zbuffer_covered(zb), c.pixels);
    assert_int_equal(cz.zcompares, c.pixels);
    rast_zbuffer_free(zb);
    char *s = rast_counters_format(&c);
    assert_non_null(strstr(s, "TPG="));
    g_free(s);
    tu_coverage_free(cv);
    scene_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clip_shared_edge),
        cmocka_unit_test(test_behind_eye),
        cmocka_unit_test(test_inside_sphere_watertight),
        cmocka_unit_test(test_outside_sphere),
        cmocka_unit_test(test_degenerate),
        cmocka_unit_test(test_huge_screen_coordinates),
        cmocka_unit_test(test_world_at_1e7),
        cmocka_unit_test(test_nested_transforms),
        cmocka_unit_test(test_nonuniform_scale_normals),
        cmocka_unit_test(test_shading),
        cmocka_unit_test(test_order_independent),
        cmocka_unit_test(test_counters),
    };
    return cmocka_run_group_tests_name("pipeline", tests, NULL, NULL);
}
