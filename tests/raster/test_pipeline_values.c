/* test_pipeline_values.c — exact results of sim/raster/pipeline.c (issue 21).
 *
 * With the identity view a mesh vertex (x, y, z) lands on pixel
 * ((x + 1) 32, (1 - y) 32) of a 64x64 image at depth (z + 1) / 2, so every
 * span's colour, id and count can be worked out by hand: the view
 * defaults and the camera light, flat colours (ambient + diffuse |n.l|
 * times polygon colour times tint), Gouraud vertex colours read back from
 * the spans' colour planes, every counter for each way a polygon can
 * end (drawn, culled, degenerate, rejected, clipped), subsets, id bases
 * and scene instances. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/raster/pipeline.h"

typedef struct {
    RastSpan s[512];
    int n;
} Spans;

static void collect(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    Spans *k = ctx;
    g_assert(k->n < 512);
    k->s[k->n++] = *s;
}

static RastSpanSink sink_of(Spans *k)
{
    k->n = 0;
    return (RastSpanSink){collect, k};
}

static void test_view_defaults(void **state)
{
    (void)state;
    Mat4 vp = mat4_translate(1, 2, 3);
    RastView v = rast_view_make(vp, 80, 40);
    assert_memory_equal(&v.view_proj, &vp, sizeof vp);
    assert_int_equal(v.width, 80);
    assert_int_equal(v.height, 40);
    assert_true(v.cull_back);
    assert_int_equal(v.span_rule, RAST_SPAN_EXACT);
    assert_true(v.lighting);
    assert_int_equal(v.shading, RAST_SHADE_GOURAUD);
    assert_true(v.light_dir.x == 0 && v.light_dir.y == 0 && v.light_dir.z == 1);
    assert_true(v.ambient == 0.25f && v.diffuse == 0.75f);
    /* a camera on +x looking at the origin: back = +x, right = -z, up =
     * +y; the light is back + right / 2 + 0.6 up, normalised */
    SceneCamera cam = scene_camera_default();
    cam.eye = vec3(3, 0, 0);
    cam.target = vec3(0, 0, 0);
    cam.up = vec3(0, 1, 0);
    RastView c = rast_view_for_camera(&cam, 80, 40);
    double len = sqrt(1 + 0.36 + 0.25);
    assert_true(fabs(c.light_dir.x - 1 / len) < 1e-12);
    assert_true(fabs(c.light_dir.y - 0.6 / len) < 1e-12);
    assert_true(fabs(c.light_dir.z + 0.5 / len) < 1e-12);
    SceneCamera wide = cam;
    wide.aspect = 2.0;
    Mat4 want = scene_camera_view_proj(&wide);
    assert_memory_equal(&c.view_proj, &want, sizeof want);
    assert_int_equal(c.width, 80);
    assert_true(c.cull_back && c.ambient == 0.25f);
}

/* A front-facing triangle (counter-clockwise seen from +z) over pixels
 * x, y in [16, 48]. */
static SceneMesh *one_triangle(SceneColor col)
{
    SceneMesh *m = scene_mesh_new();
    scene_mesh_add_vertex(m, vec3(-0.5, -0.5, 0));
    scene_mesh_add_vertex(m, vec3(0.5, -0.5, 0));
    scene_mesh_add_vertex(m, vec3(-0.5, 0.5, 0));
    scene_mesh_add_tri(m, 0, 1, 2, col, 0);
    return m;
}

static void assert_flat(const Spans *k, float r, float g, float b)
{
    assert_true(k->n > 0);
    for (int i = 0; i < k->n; i++) {
        const RastSpan *s = &k->s[i];
        if (fabsf(s->c0[0] - r) > 1e-6f || fabsf(s->c0[1] - g) > 1e-6f ||
            fabsf(s->c0[2] - b) > 1e-6f)
            fail_msg("span %d: colour (%g %g %g), expected (%g %g %g)", i,
                     s->c0[0], s->c0[1], s->c0[2], r, g, b);
        for (int j = 0; j < 3; j++)
            assert_true(fabsf(s->dcdx[j]) < 1e-6f);
    }
}

/* Flat shading: k = 0.25 + 0.75 |n.l| with n = +z and l = (0, 0.6,
 * 0.8), so k = 0.85; colour (0.5, 0.4, 1) times tint (1, 0.5, 0.8). */
static void test_flat_colour(void **state)
{
    (void)state;
    SceneMesh *m = one_triangle(scene_color(0.5f, 0.4f, 1.0f));
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    v.shading = RAST_SHADE_FLAT;
    v.light_dir = vec3(0, 0.6, 0.8);
    SceneColor tint = scene_color(1.0f, 0.5f, 0.8f);
    Spans k;
    RastCounters c = {0};
    rast_draw_mesh(&v, m, mat4_identity(), tint, 0, NULL, sink_of(&k), &c);
    assert_flat(&k, 0.425f, 0.17f, 0.68f);
    /* a translated model: normals ignore translation */
    rast_draw_mesh(&v, m, mat4_translate(0.1, -0.05, 0.2), tint, 0, NULL,
                   sink_of(&k), &c);
    assert_flat(&k, 0.425f, 0.17f, 0.68f);
    /* Gouraud without vertex normals uses the face normal: the same */
    v.shading = RAST_SHADE_GOURAUD;
    rast_draw_mesh(&v, m, mat4_identity(), tint, 0, NULL, sink_of(&k), &c);
    assert_flat(&k, 0.425f, 0.17f, 0.68f);
    /* other ambient and diffuse weights: 0.1 + 0.5 * 0.8 = 0.5 */
    v.ambient = 0.1f;
    v.diffuse = 0.5f;
    rast_draw_mesh(&v, m, mat4_identity(), tint, 0, NULL, sink_of(&k), &c);
    assert_flat(&k, 0.25f, 0.1f, 0.4f);
    /* unlit: the colour times the tint */
    v.lighting = FALSE;
    rast_draw_mesh(&v, m, mat4_identity(), tint, 0, NULL, sink_of(&k), &c);
    assert_flat(&k, 0.5f, 0.2f, 0.8f);
    v.shading = RAST_SHADE_FLAT;
    rast_draw_mesh(&v, m, mat4_identity(), tint, 0, NULL, sink_of(&k), &c);
    assert_flat(&k, 0.5f, 0.2f, 0.8f);
    /* the back face, not culled, is lit from both sides: the same k */
    v.lighting = TRUE;
    v.ambient = 0.25f;
    v.diffuse = 0.75f;
    v.cull_back = FALSE;
    rast_draw_mesh(&v, m, mat4_scale(1, 1, -1), tint, 0, NULL, sink_of(&k), &c);
    assert_flat(&k, 0.425f, 0.17f, 0.68f);
    rast_draw_mesh(&v, m, mat4_scale(-1, 1, 1), tint, 0, NULL, sink_of(&k), &c);
    assert_flat(&k, 0.425f, 0.17f, 0.68f);
    scene_mesh_free(m);
}

/* The colour a span list's plane gives at pixel point (x, y): the x
 * slope from the spans, the y slope from the first and last rows. */
static void colour_at(const Spans *k, double x, double y, double out[3])
{
    const RastSpan *a = &k->s[0], *b = &k->s[k->n - 1];
    g_assert(b->y != a->y);
    for (int j = 0; j < 3; j++) {
        double dcdy =
            (b->c0[j] - a->c0[j] - a->dcdx[j] * (b->x0 - a->x0)) / (b->y - a->y);
        out[j] = a->c0[j] + a->dcdx[j] * (x - a->x0 - 0.5) +
                 dcdy * (y - a->y - 0.5);
    }
}

static void assert_colour_at(const Spans *k, double x, double y, double r,
                             double g, double b)
{
    double c[3];
    colour_at(k, x, y, c);
    if (fabs(c[0] - r) > 2e-3 || fabs(c[1] - g) > 2e-3 || fabs(c[2] - b) > 2e-3)
        fail_msg("at (%g, %g): (%g %g %g), expected (%g %g %g)", x, y, c[0],
                 c[1], c[2], r, g, b);
}

/* Gouraud: per-vertex colours from per-vertex normals; vertex 0 (pixel
 * (16, 48)) faces the light (k = 1), vertex 1 (48, 48) is at right
 * angles to it (k = 0.25), vertex 2 (16, 16) has n.l = 0.8 (k = 0.85). */
static void test_gouraud_vertices(void **state)
{
    (void)state;
    SceneMesh *m = one_triangle(scene_color(1, 1, 1));
    Vec3 n[3] = {vec3(0, 0, 1), vec3(0, 1, 0), vec3(0.6, 0, 0.8)};
    g_array_append_vals(m->normals, n, 3);
    SceneColor vc[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    g_array_append_vals(m->colors, vc, 3);
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    Spans k;
    RastCounters c = {0};
    SceneColor tint = scene_color(1.0f, 0.5f, 0.5f);
    rast_draw_mesh(&v, m, mat4_identity(), tint, 0, NULL, sink_of(&k), &c);
    assert_colour_at(&k, 16, 48, 1, 0, 0);
    assert_colour_at(&k, 48, 48, 0, 0.125, 0);
    assert_colour_at(&k, 16, 16, 0, 0, 0.425);
    /* unlit Gouraud: the vertex colours times the tint */
    v.lighting = FALSE;
    rast_draw_mesh(&v, m, mat4_identity(), tint, 0, NULL, sink_of(&k), &c);
    assert_colour_at(&k, 16, 48, 1, 0, 0);
    assert_colour_at(&k, 48, 48, 0, 0.5, 0);
    assert_colour_at(&k, 16, 16, 0, 0, 0.5);
    /* flat: the polygon colour (white) with the face normal, k = 1 */
    v.lighting = TRUE;
    v.shading = RAST_SHADE_FLAT;
    rast_draw_mesh(&v, m, mat4_identity(), tint, 0, NULL, sink_of(&k), &c);
    assert_flat(&k, 1.0f, 0.5f, 0.5f);
    /* vertex normals, no vertex colours: the polygon colour per vertex */
    g_array_set_size(m->colors, 0);
    v.shading = RAST_SHADE_GOURAUD;
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   sink_of(&k), &c);
    assert_colour_at(&k, 16, 48, 1, 1, 1);
    assert_colour_at(&k, 48, 48, 0.25, 0.25, 0.25);
    assert_colour_at(&k, 16, 16, 0.85, 0.85, 0.85);
    /* normals go by the normal matrix: a quarter turn about z takes
     * vertex 1's normal (0, 1, 0) to (-1, 0, 0), still at right angles
     * to the light, and vertex 2's (0.6, 0, 0.8) to (0, 0.6, 0.8) */
    rast_draw_mesh(&v, m, mat4_rotate(vec3(0, 0, 1), G_PI / 2),
                   scene_color(1, 1, 1), 0, NULL, sink_of(&k), &c);
    assert_true(k.n > 0);
    for (int i = 0; i < k.n; i++) /* every colour in [0.25, 1] */
        assert_true(k.s[i].c0[0] >= 0.249f && k.s[i].c0[0] <= 1.0001f);
    scene_mesh_free(m);
}

static uint32_t add_tri(SceneMesh *m, Vec3 a, Vec3 b, Vec3 c)
{
    uint32_t i = scene_mesh_add_vertex(m, a);
    scene_mesh_add_vertex(m, b);
    scene_mesh_add_vertex(m, c);
    return scene_mesh_add_tri(m, i, i + 1, i + 2, scene_color(1, 1, 1), 0);
}

/* Every way a polygon can end, one each, with the counters exact. */
static void test_counters_each_fate(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    /* 0: drawn whole; 1: back-facing; 2: degenerate (collinear); 3:
     * behind the far plane; 4: non-finite; 5: cut by the near plane;
     * 6: a quad, drawn whole */
    add_tri(m, vec3(-0.5, -0.5, 0), vec3(0, -0.5, 0), vec3(-0.5, 0, 0));
    add_tri(m, vec3(0, 0, 0), vec3(0, 0.5, 0), vec3(0.5, 0, 0));
    add_tri(m, vec3(-0.75, 0.75, 0), vec3(-0.5, 0.5, 0), vec3(-0.25, 0.25, 0));
    add_tri(m, vec3(-0.5, -0.5, 2), vec3(0, -0.5, 2), vec3(-0.5, 0, 3));
    add_tri(m, vec3(NAN, -0.5, 0), vec3(0, -0.5, 0), vec3(-0.5, 0, 0));
    add_tri(m, vec3(0.2, -0.9, -3), vec3(0.9, -0.9, 0), vec3(0.2, -0.2, 0));
    uint32_t q = scene_mesh_add_vertex(m, vec3(0.5, 0.5, 0.5));
    scene_mesh_add_vertex(m, vec3(0.75, 0.5, 0.5));
    scene_mesh_add_vertex(m, vec3(0.75, 0.75, 0.5));
    scene_mesh_add_vertex(m, vec3(0.5, 0.75, 0.5));
    scene_mesh_add_quad(m, q, q + 1, q + 2, q + 3, scene_color(1, 1, 1), 0);
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    v.lighting = FALSE;
    Spans k;
    RastCounters c = {0};
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 100, NULL,
                   sink_of(&k), &c);
    assert_int_equal(c.verts, 6 * 3 + 4);
    assert_int_equal(c.prims, 7);
    assert_int_equal(c.culled, 1);
    assert_int_equal(c.degenerate, 1);
    assert_int_equal(c.rejected, 2);
    assert_int_equal(c.clipped, 1);
    assert_int_equal(c.spans, (uint64_t)k.n);
    uint64_t px = 0, by[7] = {0};
    for (int i = 0; i < k.n; i++) {
        px += (uint64_t)(k.s[i].x1 - k.s[i].x0);
        assert_true(k.s[i].prim >= 100 && k.s[i].prim < 107);
        by[k.s[i].prim - 100] += (uint64_t)(k.s[i].x1 - k.s[i].x0);
    }
    assert_int_equal(c.pixels, px);
    /* triangle 0: corners (16, 48), (32, 48), (16, 32); row y of 33..47
     * holds 16 <= x < y - 16 (the hypotenuse is a right edge) */
    assert_int_equal(by[0], 120);
    assert_int_equal(by[1] + by[2] + by[3] + by[4], 0);
    assert_true(by[5] > 0);
    assert_int_equal(by[6], 8 * 8); /* the quad: [48, 56) x [8, 16) */
    /* the end-point rule: the same fates and counts (the degenerate
     * triangle stops before the scan, which needs a non-zero area) */
    v.span_rule = RAST_SPAN_ENDPOINTS;
    RastCounters e0 = {0};
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 100, NULL,
                   sink_of(&k), &e0);
    assert_int_equal(e0.prims, 7);
    assert_int_equal(e0.culled, 1);
    assert_int_equal(e0.degenerate, 1);
    assert_int_equal(e0.rejected, 2);
    assert_int_equal(e0.clipped, 1);
    v.span_rule = RAST_SPAN_EXACT;
    /* the same without culling: the back face is drawn too */
    v.cull_back = FALSE;
    RastCounters d = {0};
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   sink_of(&k), &d);
    assert_int_equal(d.culled, 0);
    assert_int_equal(d.degenerate, 1);
    assert_int_equal(d.rejected, 2);
    /* triangle 1: (32, 32), (32, 16), (48, 32); rows 17..31 */
    assert_int_equal(d.spans, c.spans + 15);
    assert_int_equal(d.pixels, c.pixels + 120);
    /* a subset: only polygons 6 and 1 (ids id_base + index) */
    const uint32_t sub[2] = {6, 1};
    RastCounters e = {0};
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 7,
                   &(RastSubset){sub, 2}, sink_of(&k), &e);
    assert_int_equal(e.prims, 2);
    assert_int_equal(e.verts, 7);
    for (int i = 0; i < k.n; i++)
        assert_true(k.s[i].prim == 13 || k.s[i].prim == 8);
    assert_int_equal(k.n, 15 + 15);
    scene_mesh_free(m);
}

/* The end-point rule scans the quad whole: one span per row, 8 rows of
 * 9 pixels (the far end's pixel included); the exact rule's fan gives
 * two triangles' spans per row but the last (the diagonal x + y = 64
 * leaves row 15 to the second triangle). */
static void test_span_rule_through_pipeline(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    uint32_t q = scene_mesh_add_vertex(m, vec3(0.5, 0.5, 0.5));
    scene_mesh_add_vertex(m, vec3(0.75, 0.5, 0.5));
    scene_mesh_add_vertex(m, vec3(0.75, 0.75, 0.5));
    scene_mesh_add_vertex(m, vec3(0.5, 0.75, 0.5));
    scene_mesh_add_quad(m, q, q + 1, q + 2, q + 3, scene_color(1, 1, 1), 0);
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    Spans k;
    RastCounters c = {0};
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   sink_of(&k), &c);
    assert_int_equal(k.n, 15);
    assert_int_equal(c.pixels, 64);
    v.span_rule = RAST_SPAN_ENDPOINTS;
    RastCounters d = {0};
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   sink_of(&k), &d);
    assert_int_equal(k.n, 8);
    for (int i = 0; i < k.n; i++) {
        assert_int_equal(k.s[i].y, 8 + i);
        assert_int_equal(k.s[i].x0, 48);
        assert_int_equal(k.s[i].x1, 57);
    }
    assert_int_equal(d.pixels, 72);
    scene_mesh_free(m);
}

/* rast_draw_clip_polygon keeps the given colours (no shading) and counts
 * one primitive; clip-space input, w = 2 halves the screen size. */
static void test_clip_polygon_entry(void **state)
{
    (void)state;
    RastVert in[3] = {{{-1, -1, 0, 2}, {0.2f, 0.4f, 0.6f}},
                      {{0, -1, 0, 2}, {0.2f, 0.4f, 0.6f}},
                      {{-1, 0, 0, 2}, {0.2f, 0.4f, 0.6f}}};
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    Spans k;
    RastCounters c = {0};
    rast_draw_clip_polygon(&v, in, 3, 9, sink_of(&k), &c);
    assert_int_equal(c.prims, 1);
    assert_int_equal(c.verts, 0);
    assert_flat(&k, 0.2f, 0.4f, 0.6f);
    /* pixels (16, 48), (32, 48), (16, 32): rows 33..47 */
    assert_int_equal(k.n, 15);
    assert_int_equal(k.s[0].y, 33);
    assert_int_equal(k.s[0].x0, 16);
    assert_int_equal(k.s[0].x1, 17);
    assert_int_equal(k.s[k.n - 1].x1, 31);
    assert_int_equal(k.s[0].prim, 9);
}

/* The smallest triangle there is (twice its area one subpixel unit,
 * front facing) with a corner on the centre of pixel (5, 5), where its
 * top and left edges meet: the fan keeps it and it covers that pixel. */
static void test_smallest_front_triangle(void **state)
{
    (void)state;
    const double p = -0.828125, q = -0.8280029296875; /* 1408, 1409 / 256 */
    RastVert in[3] = {{{p, -p, 0, 1}, {1, 1, 1}},
                      {{p, -q, 0, 1}, {1, 1, 1}},
                      {{q, -p, 0, 1}, {1, 1, 1}}};
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    Spans k;
    RastCounters c = {0};
    rast_draw_clip_polygon(&v, in, 3, 4, sink_of(&k), &c);
    assert_int_equal(c.culled + c.degenerate + c.rejected, 0);
    assert_int_equal(k.n, 1);
    assert_true(k.s[0].y == 5 && k.s[0].x0 == 5 && k.s[0].x1 == 6);
}

/* A triangle with a corner exactly on the near plane and one beyond it:
 * clipping emits that corner twice; the end-point rule still scans the
 * polygon (corners (16, 48), (32, 48), (16, 16): rows 16..47). */
static void test_endpoints_clipped_repeat(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    add_tri(m, vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, -2), vec3(-0.5, 0.5, -1));
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    v.span_rule = RAST_SPAN_ENDPOINTS;
    Spans k;
    RastCounters c = {0};
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   sink_of(&k), &c);
    assert_int_equal(c.clipped, 1);
    assert_int_equal(k.n, 32);
    for (int i = 0; i < k.n; i++) {
        assert_int_equal(k.s[i].y, 16 + i);
        assert_int_equal(k.s[i].x0, 16);
    }
    scene_mesh_free(m);
}

/* A nonagon (RAST_POLY_MAX corners) is drawn whole: one primitive of
 * nine vertices, flat white when unlit. */
static void test_nonagon_whole(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    uint32_t idx[9];
    for (int i = 0; i < 9; i++)
        idx[i] = scene_mesh_add_vertex(
            m, vec3(0.5 * cos(2 * G_PI * i / 9), 0.5 * sin(2 * G_PI * i / 9), 0));
    scene_mesh_add_poly(m, idx, 9, scene_color(1, 1, 1), 0);
    for (int rule = 0; rule < 2; rule++) {
        RastView v = rast_view_make(mat4_identity(), 64, 64);
        v.lighting = FALSE;
        v.span_rule = rule;
        Spans k;
        RastCounters c = {0};
        rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                       sink_of(&k), &c);
        assert_int_equal(c.prims, 1);
        assert_int_equal(c.verts, 9);
        assert_flat(&k, 1, 1, 1);
    }
    scene_mesh_free(m);
}

/* Scene instances: ids run on over the instances' polygons, each placed
 * by its transform and tinted by its colour. */
static void test_scene_instances(void **state)
{
    (void)state;
    Scene *s = scene_new("t");
    SceneMesh *two = scene_mesh_new();
    add_tri(two, vec3(-0.5, -0.5, 0), vec3(0, -0.5, 0), vec3(-0.5, 0, 0));
    add_tri(two, vec3(0, 0, 0), vec3(0.5, 0, 0), vec3(0, 0.5, 0));
    guint a = scene_add_mesh(s, two);
    guint b = scene_add_mesh(s, one_triangle(scene_color(1, 1, 1)));
    scene_add_instance(s, a, mat4_identity(), scene_color(1, 0, 0), 0);
    scene_add_instance(s, b, mat4_translate(0, 0, 0.5),
                       scene_color(0, 0.5f, 0), 0);
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    v.lighting = FALSE;
    Spans k;
    RastCounters c = {0};
    rast_draw_scene(&v, s, sink_of(&k), &c);
    assert_int_equal(c.prims, 3);
    int seen[3] = {0, 0, 0};
    for (int i = 0; i < k.n; i++) {
        uint32_t p = k.s[i].prim;
        assert_true(p < 3);
        seen[p]++;
        if (p < 2)
            assert_true(k.s[i].c0[0] == 1.0f && k.s[i].c0[1] == 0.0f);
        else
            assert_true(k.s[i].c0[0] == 0.0f && k.s[i].c0[1] == 0.5f &&
                        fabs(k.s[i].z0 - 0.75) < 1e-12);
    }
    assert_true(seen[0] == 15 && seen[1] == 15 && seen[2] == 31);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_view_defaults),
        cmocka_unit_test(test_flat_colour),
        cmocka_unit_test(test_gouraud_vertices),
        cmocka_unit_test(test_counters_each_fate),
        cmocka_unit_test(test_span_rule_through_pipeline),
        cmocka_unit_test(test_clip_polygon_entry),
        cmocka_unit_test(test_scene_instances),
        cmocka_unit_test(test_smallest_front_triangle),
        cmocka_unit_test(test_endpoints_clipped_repeat),
        cmocka_unit_test(test_nonagon_whole),
    };
    return cmocka_run_group_tests_name("pipeline_values", tests, NULL, NULL);
}
