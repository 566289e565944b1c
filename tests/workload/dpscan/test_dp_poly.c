/* test_dp_poly.c — the screen-space polygon kernels of dp_poly.h on
 * polygons built by hand, every expected value computed here (issue 21):
 * a square's spans (crossings at the row centre, first pixel, length),
 * crossings at the same x and depth keeping their edges' order (the
 * insertion sort is stable), an edge's line pixels running from the
 * pixel of one end to the pixel of the other in unit steps, the key
 * layout (depth, id, colour index), mode names, shaded and contour colour
 * indices, point and line pixels with their keys, rows of polygons that
 * start or end inside a row, and the edge length limit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim/scene/scene.h"
#include "sim/workload/dpscan/dp_color.h"
#include "sim/workload/dpscan/dp_poly.h"

/* One polygon of k vertices (x, y, z, val): the caller's arrays. */
typedef struct {
    WlDpPolys p;
    uint32_t start[2];
    uint8_t color[1], ok[1];
} One;

static void one_init(One *o, uint32_t k, double *x, double *y, double *z,
                     double *v, WlDpMode mode)
{
    o->start[0] = 0;
    o->start[1] = k;
    o->color[0] = 3;
    o->ok[0] = 1;
    o->p = (WlDpPolys){.n = 1, .n_ok = 1, .kmax = k, .start = o->start,
                       .x = x, .y = y, .z = z, .val = v, .color = o->color,
                       .ok = o->ok, .n_verts = k, .mode = mode};
}

static void test_square_spans(void **state)
{
    (void)state;
    double x[4] = {1.2, 5.7, 5.7, 1.2}, y[4] = {1.0, 1.0, 3.9, 3.9};
    double z[4] = {0.5, 0.5, 0.5, 0.5}, v[4] = {0, 1, 1, 0};
    One o;
    one_init(&o, 4, x, y, z, v, WL_DP_MODE_FLAT);
    int32_t y0 = -1;
    assert_int_equal(wl_dp_poly_rows(&o.p, 0, &y0), 3);
    assert_int_equal(y0, 1);
    WlDpSpan s[WL_DP_MAX_VERTS / 2];
    for (int32_t row = 1; row <= 3; row++) {
        assert_int_equal(wl_dp_poly_spans(&o.p, 0, row, s), 1);
        assert_true(s[0].xl == 1.2 && s[0].xr == 5.7);
        assert_true(s[0].vl == 0 && s[0].vr == 1);
        assert_int_equal(s[0].y, row);
        assert_int_equal(s[0].x0, 1);
        assert_int_equal(s[0].len, 5); /* pixels 1 .. 5 */
        assert_int_equal(s[0].poly, 0);
    }
    /* end rows count: to y = 4.0 the polygon touches row 4 too */
    y[2] = y[3] = 4.0;
    assert_int_equal(wl_dp_poly_rows(&o.p, 0, &y0), 4);
    /* no area, or behind the eye: no rows */
    y[2] = y[3] = 1.0;
    assert_int_equal(wl_dp_poly_rows(&o.p, 0, &y0), 0);
    y[2] = y[3] = 3.9;
    o.ok[0] = 0;
    assert_int_equal(wl_dp_poly_rows(&o.p, 0, &y0), 0);
}

/* A bow tie: edges 0 (A -> B) and 2 (C -> D) cross at (2, 2.5), the
 * centre of row 2, at the same depth but with different values. */
static void test_equal_crossings_keep_edge_order(void **state)
{
    (void)state;
    double x[4] = {0, 4, 0, 4}, y[4] = {0.5, 4.5, 4.5, 0.5};
    double z[4] = {0.25, 0.25, 0.25, 0.25}, v[4] = {0, 1, 1, 3};
    One o;
    one_init(&o, 4, x, y, z, v, WL_DP_MODE_FLAT);
    WlDpSpan s[WL_DP_MAX_VERTS / 2];
    assert_int_equal(wl_dp_poly_spans(&o.p, 0, 2, s), 1);
    assert_true(s[0].xl == 2 && s[0].xr == 2);
    /* edge 0 at half way: 0.5; edge 2 at half way: 2 */
    assert_true(s[0].vl == 0.5 && s[0].vr == 2);
    /* the same crossings met in the other order stay in that order */
    double x2[4] = {0, 4, 0, 4}, y2[4] = {4.5, 0.5, 0.5, 4.5};
    double v2[4] = {1, 3, 0, 1};
    one_init(&o, 4, x2, y2, z, v2, WL_DP_MODE_FLAT);
    assert_int_equal(wl_dp_poly_spans(&o.p, 0, 2, s), 1);
    assert_true(s[0].vl == 2 && s[0].vr == 0.5);
}

static void check_edge(One *o, uint32_t e)
{
    uint32_t k = (uint32_t)(o->p.start[1]), a = e, b = (e + 1) % k;
    int64_t ax = (int64_t)floor(o->p.x[a]), ay = (int64_t)floor(o->p.y[a]);
    int64_t bx = (int64_t)floor(o->p.x[b]), by = (int64_t)floor(o->p.y[b]);
    uint32_t n = wl_dp_edge_pixels(&o->p, 0, e);
    assert_int_equal(n, MAX(llabs(bx - ax), llabs(by - ay)) + 1);
    int64_t px = 0, py = 0;
    for (uint32_t j = 0; j < n; j++) {
        int64_t qx, qy;
        uint64_t key;
        wl_dp_edge_pixel(&o->p, 0, e, j, &qx, &qy, &key);
        if (j == 0)
            assert_true(qx == ax && qy == ay);
        else
            assert_true(llabs(qx - px) <= 1 && llabs(qy - py) <= 1);
        if (j == n - 1)
            assert_true(qx == bx && qy == by);
        assert_int_equal(wl_dp_key_id(key), 0);
        px = qx;
        py = qy;
    }
}

static void test_edge_pixels_join_the_ends(void **state)
{
    (void)state;
    double x[3] = {1.7, 9.2, 3.4}, y[3] = {2.9, 5.1, 12.6};
    double z[3] = {0.1, 0.5, 0.9}, v[3] = {0, 0, 0};
    One o;
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_WIREFRAME);
    for (uint32_t e = 0; e < 3; e++)
        check_edge(&o, e);
    /* a one-pixel edge */
    double x1[3] = {4.1, 4.9, 4.5}, y1[3] = {7.2, 7.8, 7.5};
    one_init(&o, 3, x1, y1, z, v, WL_DP_MODE_WIREFRAME);
    assert_int_equal(wl_dp_edge_pixels(&o.p, 0, 0), 1);
    check_edge(&o, 0);
    /* a two-pixel edge: one pixel at each end */
    double x2[3] = {4.1, 5.9, 4.5}, y2[3] = {7.2, 7.8, 9.5};
    one_init(&o, 3, x2, y2, z, v, WL_DP_MODE_WIREFRAME);
    assert_int_equal(wl_dp_edge_pixels(&o.p, 0, 0), 2);
    check_edge(&o, 0);
    /* line keys: depth along the edge where lines hide each other (LINES;
     * the one-pixel edge at its first end's), none in WIREFRAME; the
     * polygon's colour at full shade */
    int64_t qx, qy;
    uint64_t key;
    one_init(&o, 3, x1, y1, z, v, WL_DP_MODE_LINES);
    wl_dp_edge_pixel(&o.p, 0, 0, 0, &qx, &qy, &key);
    assert_int_equal(key, wl_dp_key(0.1, 0, wl_dp_color_index(3, 1)));
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_LINES);
    assert_int_equal(wl_dp_edge_pixels(&o.p, 0, 0), 9);
    wl_dp_edge_pixel(&o.p, 0, 0, 4, &qx, &qy, &key); /* t 0.5 */
    assert_int_equal(key, wl_dp_key(0.1 + 0.5 * (0.5 - 0.1), 0,
                                    wl_dp_color_index(3, 1)));
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_WIREFRAME);
    wl_dp_edge_pixel(&o.p, 0, 0, 4, &qx, &qy, &key);
    assert_int_equal(key >> 32, 0);
    /* a polygon behind the eye draws no line */
    one_init(&o, 3, x2, y2, z, v, WL_DP_MODE_WIREFRAME);
    o.ok[0] = 0;
    assert_int_equal(wl_dp_edge_pixels(&o.p, 0, 0), 0);
}

static void test_key_layout(void **state)
{
    (void)state;
    uint64_t k = wl_dp_key(0.25, 0x123456, 7);
    assert_int_equal(k >> 32, (uint64_t)(0.75 * 4294967295.0));
    assert_int_equal(wl_dp_key_id(k), 0x123456);
    assert_int_equal(wl_dp_key_index(k), 7);
    assert_true(wl_dp_key(0.1, 1, 1) > wl_dp_key(0.2, 1, 1)); /* nearer */
    assert_int_equal(wl_dp_key(-1, 0, 0) >> 32, 4294967295u);
    assert_int_equal(wl_dp_key(2, 0, 0), 0);
}

/* A U shape: four crossings of row 2 at x = 100, 101, 105, 106. */
static double ux[8] = {100, 106, 106, 105, 105, 101, 101, 100};
static double uy[8] = {0, 0, 5, 5, 1, 1, 5, 5};
static double uz[8], uv[8];

/* Every call goes through here, at the same stack depth, so that the
 * crossings array of wl_dp_poly_spans holds the previous call's values. */
static __attribute__((noinline)) guint spans(const One *o, int32_t y,
                                             WlDpSpan *s)
{
    return wl_dp_poly_spans(&o->p, 0, y, s);
}

/* Crossings are sorted by x, then depth, whatever order the edges give
 * them in (each case after a row of four crossings far to the right, so
 * that a comparison with a slot past the crossings found so far, which
 * holds that row's values, shows). */
static void test_crossings_sorted(void **state)
{
    (void)state;
    WlDpSpan s[WL_DP_MAX_VERTS / 2];
    One u;
    one_init(&u, 8, ux, uy, uz, uv, WL_DP_MODE_FLAT);
    assert_int_equal(spans(&u, 2, s), 2);
    assert_true(s[0].xl == 100 && s[0].xr == 101);
    assert_true(s[1].xl == 105 && s[1].xr == 106);
    /* the left edge first */
    double x[4] = {1.2, 1.2, 5.7, 5.7}, y[4] = {3.9, 1.0, 1.0, 3.9};
    double z[4] = {0.5, 0.5, 0.5, 0.5}, v[4] = {0, 0, 1, 1};
    One o;
    one_init(&o, 4, x, y, z, v, WL_DP_MODE_FLAT);
    assert_int_equal(spans(&u, 2, s), 2);
    assert_int_equal(spans(&o, 2, s), 1);
    assert_true(s[0].xl == 1.2 && s[0].xr == 5.7);
    /* the right edge first */
    double x2[4] = {5.7, 5.7, 1.2, 1.2}, v2[4] = {1, 1, 0, 0};
    one_init(&o, 4, x2, y, z, v2, WL_DP_MODE_FLAT);
    assert_int_equal(spans(&u, 2, s), 2);
    assert_int_equal(spans(&o, 2, s), 1);
    assert_true(s[0].xl == 1.2 && s[0].xr == 5.7);
    /* a bow tie crossing at x = 2 on row 2's centre: the nearer first */
    double bx[4] = {0, 4, 0, 4}, by[4] = {0.5, 4.5, 4.5, 0.5};
    double bz[4] = {0.2, 0.4, 0.3, 0.1}, bv[4] = {0, 0, 0, 0};
    one_init(&o, 4, bx, by, bz, bv, WL_DP_MODE_FLAT);
    assert_int_equal(spans(&u, 2, s), 2);
    assert_int_equal(spans(&o, 2, s), 1);
    assert_true(s[0].xl == 2 && s[0].xr == 2);
    assert_true(fabs(s[0].zl - 0.2) < 1e-12 && fabs(s[0].zr - 0.3) < 1e-12);
}

static uint64_t depth_bits(double z)
{
    return wl_dp_key(z, 0, 0) >> 32;
}

/* A span's pixel key: depth interpolated at the pixel centre, clamped to
 * the span's ends; a zero-width span takes its left end's. */
static void test_span_key_depth(void **state)
{
    (void)state;
    double x[3] = {0, 1, 0}, y[3] = {0, 0, 1}, z[3] = {0}, v[3] = {0};
    One o;
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_FLAT);
    WlDpSpan s = {.xl = 1.5, .xr = 5.5, .zl = 0.2, .zr = 0.6, .vl = 0,
                  .vr = 0, .y = 0, .x0 = 1, .len = 5, .poly = 0};
    /* pixel 1 (centre 1.5): t 0; pixel 3 (3.5): t 0.5; pixel 5: t 1 */
    assert_int_equal(wl_dp_span_key(&o.p, &s, 0) >> 32, depth_bits(0.2));
    assert_int_equal(wl_dp_span_key(&o.p, &s, 2) >> 32, depth_bits(0.4));
    assert_int_equal(wl_dp_span_key(&o.p, &s, 4) >> 32, depth_bits(0.6));
    assert_int_equal(wl_dp_key_id(wl_dp_span_key(&o.p, &s, 2)), 0);
    /* the shade is interpolated like the depth: pixel 3 at v 0.5 */
    s.vl = 0;
    s.vr = 1;
    assert_int_equal(wl_dp_key_index(wl_dp_span_key(&o.p, &s, 2)),
                     wl_dp_color_index(o.color[0], 0.5));
    assert_int_equal(wl_dp_key_index(wl_dp_span_key(&o.p, &s, 4)),
                     wl_dp_color_index(o.color[0], 1));
    assert_int_equal(wl_dp_key_index(wl_dp_span_key(&o.p, &s, 0)),
                     wl_dp_color_index(o.color[0], 0));
    /* a pixel centre right of xr clamps to the right end */
    s.xr = 5.25;
    assert_int_equal(wl_dp_span_key(&o.p, &s, 4) >> 32, depth_bits(0.6));
    s.xr = 5.5;
    /* a pixel centre left of xl clamps to the left end */
    s.xl = 1.9;
    assert_int_equal(wl_dp_span_key(&o.p, &s, 0) >> 32, depth_bits(0.2));
    /* zero width */
    WlDpSpan d = {.xl = 2, .xr = 2, .zl = 0.2, .zr = 0.3, .y = 2, .x0 = 2,
                  .len = 1, .poly = 0};
    assert_int_equal(wl_dp_span_key(&o.p, &d, 0) >> 32, depth_bits(0.2));
    /* under a pixel wide: still interpolated (centre 2.5 halfway along
     * 2.25 .. 2.75) */
    d.xl = 2.25;
    d.xr = 2.75;
    d.zr = 0.4;
    assert_int_equal(wl_dp_span_key(&o.p, &d, 0) >> 32, depth_bits(0.3));
}

/* A polygon's colour is the palette entry nearest in RGB (squared
 * Euclidean distance), the first of equals. */
static void test_nearest_palette_colour(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(0, 0, 0)),
                     scene_mesh_add_vertex(m, vec3(1, 0, 0)),
                     scene_mesh_add_vertex(m, vec3(0, 1, 0))};
    scene_mesh_add_poly(m, v, 3, scene_color(0.5f, 0.5f, 0.5f), 0);
    scene_mesh_add_poly(m, v, 3, scene_color(0.5f, 0.1f, 0.5f), 0);
    scene_mesh_add_poly(m, v, 3, scene_color(0.5f, 0.5f, 0.1f), 0);
    scene_mesh_add_poly(m, v, 3, scene_color(0.9f, 0.5f, 0.9f), 0);
    Scene *sc = scene_new("one");
    guint id = scene_add_mesh(sc, m);
    scene_add_instance(sc, id, mat4_identity(), scene_color(1, 1, 1), 0);
    sc->camera = scene_camera_default();
    sc->camera.eye = vec3(0.3, 0.3, 5);
    scene_camera_fit(&sc->camera, scene_bbox(sc), 0.9);
    float pal[WL_DP_COLORS][3];
    for (int k = 0; k < WL_DP_COLORS; k++)
        pal[k][0] = 0.9f, pal[k][1] = 0.5f, pal[k][2] = 0.9f;
    /* entry 0 differs from grey in green only; 1 and 3 are the grey */
    pal[0][0] = 0.5f, pal[0][1] = 0, pal[0][2] = 0.5f;
    pal[1][0] = pal[1][1] = pal[1][2] = 0.5f;
    pal[3][0] = pal[3][1] = pal[3][2] = 0.5f;
    WlDpPolys *p = wl_dp_polys_new(sc, 0, 16, 16, WL_DP_MODE_FLAT, pal);
    assert_int_equal(p->n, 4);
    assert_int_equal(p->color[0], 1);
    assert_int_equal(p->color[1], 0);
    assert_int_equal(p->color[2], 1); /* blue 0.4 off: still the grey */
    assert_int_equal(p->color[3], 2); /* the first (0.9, 0.5, 0.9) entry */
    wl_dp_polys_free(p);
    scene_free(sc);
}

/* wl_dp_polys_new: each vertex through the camera's view-projection
 * (aspect width / height) to the screen, x = (ndc x + 1) w / 2, y =
 * (1 - ndc y) h / 2, depth (ndc z + 1) / 2 clamped to [0, 1]; the value
 * interpolated across the polygon is |polygon normal . view direction|
 * (flat), |vertex normal . view direction| (Gouraud), the world height
 * over the scene's extent (contour) or 1 (hidden line); the colour is the
 * nearest palette entry; a polygon with a vertex behind the eye is not
 * drawable. */
static Scene *tilted(void)
{
    SceneMesh *m = scene_mesh_new();
    const double t[2][4][3] = {
        {{-0.8, -0.6, 0}, {0.4, -0.5, -0.3}, {0.5, 0.6, -0.6}, {-0.7, 0.5, 0}},
        {{-0.2, 0.1, 0.5}, {0.9, -0.9, 0.2}, {0.3, 0.9, 0.4}, {0, 0, 0}}};
    for (int k = 0; k < 2; k++) {
        uint32_t v[4];
        int n = k ? 3 : 4;
        for (int j = 0; j < n; j++)
            v[j] = scene_mesh_add_vertex(m, vec3(t[k][j][0], t[k][j][1],
                                                 t[k][j][2]));
        scene_mesh_add_poly(m, v, n,
                            k ? scene_color(0.1f, 0.55f, 0.12f)
                              : scene_color(0.92f, 0.12f, 0.08f),
                            0);
    }
    Scene *s = scene_new("tilted");
    scene_add_instance(s, scene_add_mesh(s, m), mat4_translate(0.1, 0, 0),
                       scene_color(1, 1, 1), 0);
    s->camera.eye = vec3(0.3, 0.4, 3);
    s->camera.target = vec3(0, 0, 0);
    return s;
}

static void test_polys_new(void **state)
{
    (void)state;
    Scene *s = tilted();
    float pal[WL_DP_COLORS][3];
    for (int c = 0; c < WL_DP_COLORS; c++)
        for (int k = 0; k < 3; k++)
            pal[c][k] = (float)((c * 7 + k * 3) % 10) / 10.0f;
    pal[4][0] = 0.9f, pal[4][1] = 0.1f, pal[4][2] = 0.1f;
    pal[9][0] = 0.1f, pal[9][1] = 0.5f, pal[9][2] = 0.1f;
    SceneMesh *m = scene_flatten(s);
    scene_mesh_compute_normals(m);
    SceneCamera cam = scene_camera_at(s, 0);
    cam.aspect = 40.0 / 30;
    Mat4 vp = scene_camera_view_proj(&cam);
    Vec3 fwd = vec3_norm(vec3_sub(cam.target, cam.eye));
    const WlDpMode modes[4] = {WL_DP_MODE_FLAT, WL_DP_MODE_GOURAUD,
                               WL_DP_MODE_CONTOUR, WL_DP_MODE_HIDDEN_LINE};
    for (int md = 0; md < 4; md++) {
        WlDpPolys *p = wl_dp_polys_new(s, 0, 40, 30, modes[md], pal);
        assert_int_equal(p->n, 2);
        assert_int_equal(p->n_verts, 7);
        assert_int_equal(p->kmax, 4);
        assert_int_equal(p->n_ok, 2);
        assert_int_equal(p->start[1], 4);
        assert_int_equal(p->start[2], 7);
        assert_int_equal(p->color[0], 4);
        assert_int_equal(p->color[1], 9);
        for (guint i = 0; i < 2; i++) {
            const uint32_t *idx = scene_mesh_poly(m, i);
            double flat = fabs(vec3_dot(scene_mesh_poly_normal(m, i), fwd));
            for (uint32_t j = 0; j < wl_dp_poly_len(p, i); j++) {
                Vec3 w = scene_mesh_vertex(m, idx[j]);
                Vec4 c = mat4_apply_point(vp, w);
                uint32_t a = p->start[i] + j;
                assert_true(fabs(p->x[a] - (c.x / c.w + 1) * 20) < 1e-9);
                assert_true(fabs(p->y[a] - (1 - c.y / c.w) * 15) < 1e-9);
                double z = CLAMP((c.z / c.w + 1) / 2, 0, 1);
                assert_true(fabs(p->z[a] - z) < 1e-12);
                assert_true(z > 0.5 && z < 1);
                double want = flat;
                if (modes[md] == WL_DP_MODE_GOURAUD)
                    want = fabs(vec3_dot(
                        vec3_norm(g_array_index(m->normals, Vec3, idx[j])),
                        fwd));
                if (modes[md] == WL_DP_MODE_CONTOUR)
                    want = (w.y + 0.9) / 1.8;
                if (modes[md] == WL_DP_MODE_HIDDEN_LINE)
                    want = 1;
                if (!(fabs(p->val[a] - want) <= 1e-9)) /* NaN fails */
                    fail_msg("mode %d polygon %u vertex %u: value %f, "
                             "expected %f", md, i, j, p->val[a], want);
            }
        }
        wl_dp_polys_free(p);
    }
    /* depth clamped to [0, 1]: every vertex beyond the far plane at 1,
     * every one nearer than the near plane (but in front) at 0 */
    const double planes[2][2] = {{0.5, 1.5}, {4.5, 10}};
    for (int k = 0; k < 2; k++) {
        s->camera.near = planes[k][0];
        s->camera.far = planes[k][1];
        WlDpPolys *q = wl_dp_polys_new(s, 0, 40, 30, WL_DP_MODE_FLAT, pal);
        assert_int_equal(q->n_ok, 2);
        for (uint32_t a = 0; a < q->n_verts; a++)
            assert_true(q->z[a] == (k ? 0.0 : 1.0));
        wl_dp_polys_free(q);
    }
    /* the eye moved between the polygons: the far one is behind it */
    s->camera.eye = vec3(0.3, 0.4, 0.1);
    s->camera.target = vec3(0.3, 0.4, -1);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 40, 30, WL_DP_MODE_FLAT, pal);
    assert_int_equal(p->ok[0], 1);
    assert_int_equal(p->ok[1], 0);
    assert_int_equal(p->n_ok, 1);
    wl_dp_polys_free(p);
    scene_mesh_free(m);
    scene_free(s);
}

/* Mode names in WlDpMode order, parsed back; which modes fill. */
static void test_modes(void **state)
{
    (void)state;
    static const char *const names[WL_DP_N_MODES] = {
        "flat", "gouraud", "wireframe", "hidden_line", "contour", "points",
        "lines"};
    for (int m = 0; m < WL_DP_N_MODES; m++) {
        assert_string_equal(wl_dp_mode_name((WlDpMode)m), names[m]);
        WlDpMode got = WL_DP_N_MODES;
        assert_true(wl_dp_mode_parse(names[m], &got));
        assert_int_equal(got, m);
        gboolean fills = m == WL_DP_MODE_FLAT || m == WL_DP_MODE_GOURAUD ||
                         m == WL_DP_MODE_HIDDEN_LINE ||
                         m == WL_DP_MODE_CONTOUR;
        assert_int_equal(wl_dp_mode_fills((WlDpMode)m), fills);
    }
    WlDpMode keep = WL_DP_MODE_LINES;
    assert_false(wl_dp_mode_parse("shaded", &keep));
    assert_false(wl_dp_mode_parse(NULL, &keep));
    assert_int_equal(keep, WL_DP_MODE_LINES);
}

/* Shaded index: 30 + 15 colour + round(14 shade), shade clamped to
 * [0, 1]; contour index: band floor(15 v) (at most 14), its brightest
 * shade: 30 + 15 band + 14. */
static void test_colour_indices(void **state)
{
    (void)state;
    assert_int_equal(wl_dp_color_index(0, 0), 30);
    assert_int_equal(wl_dp_color_index(2, 0.5), 30 + 30 + 7);
    assert_int_equal(wl_dp_color_index(1, 0.75 / 14), 30 + 15 + 1);
    assert_int_equal(wl_dp_color_index(1, 0.25 / 14), 30 + 15);
    assert_int_equal(wl_dp_color_index(14, 1), 30 + 210 + 14);
    assert_int_equal(wl_dp_color_index(3, -2), 30 + 45);
    assert_int_equal(wl_dp_color_index(3, 7), 30 + 45 + 14);
    assert_int_equal(wl_dp_contour_index(0), 44);
    assert_int_equal(wl_dp_contour_index(0.1), 30 + 15 + 14);
    assert_int_equal(wl_dp_contour_index(0.5), 30 + 105 + 14);
    assert_int_equal(wl_dp_contour_index(0.99), 30 + 210 + 14);
    assert_int_equal(wl_dp_contour_index(1), 30 + 210 + 14);
    assert_int_equal(wl_dp_contour_index(-1), 44);
    assert_int_equal(wl_dp_contour_index(3), 254);
    /* contour mode keys a pixel by its value's band, not the colour */
    double x[3] = {0, 1, 0}, y[3] = {0, 0, 1}, z[3] = {0}, v[3] = {0};
    One o;
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_CONTOUR);
    WlDpSpan s = {.xl = 0, .xr = 4, .zl = 0.5, .zr = 0.5, .vl = 0.5,
                  .vr = 0.5, .y = 0, .x0 = 0, .len = 4, .poly = 0};
    assert_int_equal(wl_dp_key_index(wl_dp_span_key(&o.p, &s, 1)),
                     30 + 105 + 14);
}

/* Points and line pixels: the pixel holding the vertex (floor, also
 * below 0), the polygon's colour at full shade, the depth of the point
 * (interpolated along an edge) except in wireframe, where lines never
 * hide each other (depth 1 for all: the key's depth bits are 0). */
static void test_point_and_line_keys(void **state)
{
    (void)state;
    double x[3] = {3.7, 9.2, 3.4}, y[3] = {-0.2, 5.1, 12.6};
    double z[3] = {0.25, 0.75, 0.875}, v[3] = {0, 0, 0};
    One o;
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_POINTS);
    int64_t px, py;
    uint64_t key;
    wl_dp_point_pixel(&o.p, 0, 0, &px, &py, &key);
    assert_true(px == 3 && py == -1);
    assert_true(key == wl_dp_key(0.25, 0, wl_dp_color_index(3, 1)));
    wl_dp_point_pixel(&o.p, 0, 2, &px, &py, &key);
    assert_true(px == 3 && py == 12);
    assert_true(key == wl_dp_key(0.875, 0, 30 + 45 + 14));
    /* edge 0 from (3, -1) to (9, 5): 7 pixels, t = k / 6 */
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_LINES);
    assert_int_equal(wl_dp_edge_pixels(&o.p, 0, 0), 7);
    wl_dp_edge_pixel(&o.p, 0, 0, 3, &px, &py, &key);
    assert_true(px == 6 && py == 2);
    assert_true(key == wl_dp_key(0.5, 0, 30 + 45 + 14));
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_WIREFRAME);
    wl_dp_edge_pixel(&o.p, 0, 0, 3, &px, &py, &key);
    assert_true(key == wl_dp_key(1.0, 0, 30 + 45 + 14));
    assert_int_equal(key >> 32, 0);
    wl_dp_point_pixel(&o.p, 0, 1, &px, &py, &key);
    assert_true(px == 9 && py == 5 && key >> 32 == 0);
}

/* Rows of polygons that start or end inside a row: every row touched,
 * from floor(lowest y) (negative too) to floor(highest y); a row is
 * sampled at its centre moved inside the polygon, so a polygon from y
 * 2.6 to 3.2 has a span on both rows 2 and 3. */
static void test_partial_rows(void **state)
{
    (void)state;
    double x[4] = {1.2, 5.7, 5.7, 1.2}, y[4] = {2.6, 2.6, 3.2, 3.2};
    double z[4] = {0.5, 0.5, 0.5, 0.5}, v[4] = {0, 0, 0, 0};
    One o;
    one_init(&o, 4, x, y, z, v, WL_DP_MODE_FLAT);
    int32_t y0 = 99;
    assert_int_equal(wl_dp_poly_rows(&o.p, 0, &y0), 2);
    assert_int_equal(y0, 2);
    WlDpSpan s[WL_DP_MAX_VERTS / 2];
    assert_int_equal(wl_dp_poly_spans(&o.p, 0, 2, s), 1);
    assert_int_equal(wl_dp_poly_spans(&o.p, 0, 3, s), 1);
    assert_int_equal(s[0].x0, 1);
    assert_int_equal(s[0].len, 5);
    /* inside one row */
    y[0] = y[1] = 1.3, y[2] = y[3] = 1.7;
    assert_int_equal(wl_dp_poly_rows(&o.p, 0, &y0), 1);
    assert_int_equal(y0, 1);
    assert_int_equal(wl_dp_poly_spans(&o.p, 0, 1, s), 1);
    /* above the screen: rows -2, -1 and 0 */
    y[0] = y[1] = -1.5, y[2] = y[3] = 0.5;
    assert_int_equal(wl_dp_poly_rows(&o.p, 0, &y0), 3);
    assert_int_equal(y0, -2);
    assert_int_equal(wl_dp_poly_spans(&o.p, 0, -2, s), 1);
    assert_int_equal(s[0].y, -2);
    /* not behind the eye, not flat: rows reset y0 to 0 first */
    o.ok[0] = 0;
    y0 = 99;
    assert_int_equal(wl_dp_poly_rows(&o.p, 0, &y0), 0);
    assert_int_equal(y0, 0);
}

/* An edge of 10^7 pixel steps is still drawn (10^7 + 1 pixels); a longer
 * one is not (the guard against coordinates out of range). */
static void test_edge_length_limit(void **state)
{
    (void)state;
    double x[3] = {0.5, 1e7 + 0.5, 0.5}, y[3] = {0.5, 0.5, 3.5};
    double z[3] = {0}, v[3] = {0};
    One o;
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_LINES);
    assert_int_equal(wl_dp_edge_pixels(&o.p, 0, 0), 10000001);
    x[1] = 1e7 + 1.5;
    assert_int_equal(wl_dp_edge_pixels(&o.p, 0, 0), 0);
    assert_int_equal(wl_dp_edge_pixels(&o.p, 0, 2), 4); /* (0,3) to (0,0) */
}

/* A vertex exactly on a row's centre: an edge holds its lower end (the
 * smaller y), not its upper one, so the left vertex D (1, 2.5) of the
 * triangle A (4, 0.5), B (7, 4.5), D is crossed once on row 2, whichever
 * way the polygon winds: one span from 1 to 5.5 (pixels 1 .. 5). */
static void test_vertex_on_row_centre(void **state)
{
    (void)state;
    const double xs[2][3] = {{4, 7, 1}, {4, 1, 7}};
    const double ys[2][3] = {{0.5, 4.5, 2.5}, {0.5, 2.5, 4.5}};
    for (int w = 0; w < 2; w++) {
        double x[3], y[3], z[3] = {0.5, 0.5, 0.5}, v[3] = {0, 0, 0};
        memcpy(x, xs[w], sizeof x);
        memcpy(y, ys[w], sizeof y);
        One o;
        one_init(&o, 3, x, y, z, v, WL_DP_MODE_FLAT);
        WlDpSpan s[WL_DP_MAX_VERTS / 2];
        assert_int_equal(wl_dp_poly_spans(&o.p, 0, 2, s), 1);
        assert_true(s[0].xl == 1 && s[0].xr == 5.5);
        assert_int_equal(s[0].x0, 1);
        assert_int_equal(s[0].len, 5);
    }
}

/* A row the polygon starts within is sampled just inside its extent,
 * at lo + (hi - lo) 1e-6: the edge from (2, 2.6) to (6, 4.6) is crossed
 * at x = 2 + 2 (2e-6) on row 2, the vertical edge x = 2 at 2. */
static void test_row_sampled_inside(void **state)
{
    (void)state;
    double x[3] = {2, 6, 2}, y[3] = {2.6, 4.6, 4.6};
    double z[3] = {0.5, 0.5, 0.5}, v[3] = {0, 0, 0};
    One o;
    one_init(&o, 3, x, y, z, v, WL_DP_MODE_FLAT);
    WlDpSpan s[WL_DP_MAX_VERTS / 2];
    assert_int_equal(wl_dp_poly_spans(&o.p, 0, 2, s), 1);
    assert_true(s[0].xl == 2);
    assert_true(fabs(s[0].xr - (2 + 2 * 2e-6)) < 1e-12);
}

/* ---- projection limits of wl_dp_polys_new ------------------------------ */

/* ok[] of the triangles (a, b, c) of pts in threes, seen on a 2 x 2
 * screen by cam (aspect set to 1 as wl_dp_polys_new does). */
static void oks(const SceneCamera *cam, const Vec3 *pts, guint n, uint8_t *ok)
{
    Scene *s = scene_new("limits");
    s->camera = *cam;
    SceneMesh *m = scene_mesh_new();
    for (guint i = 0; i < n; i++)
        scene_mesh_add_vertex(m, pts[i]);
    for (guint t = 0; t < n / 3; t++)
        scene_mesh_add_tri(m, 3 * t, 3 * t + 1, 3 * t + 2,
                           scene_color(1, 1, 1), t);
    scene_add_instance(s, scene_add_mesh(s, m), mat4_identity(),
                       scene_color(1, 1, 1), 0);
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 2, 2, WL_DP_MODE_FLAT, pal);
    assert_int_equal(p->n, n / 3);
    memcpy(ok, p->ok, p->n);
    wl_dp_polys_free(p);
    scene_free(s);
}

/* An eye at the origin looking down -z. */
static SceneCamera down_z(SceneProjection proj)
{
    SceneCamera c = scene_camera_default();
    c.proj = proj;
    c.eye = vec3(0, 0, 0);
    c.target = vec3(0, 0, -1);
    c.up = vec3(0, 1, 0);
    c.height = 2; /* orthographic: x, y in [-1, 1] fill the screen */
    c.aspect = 1;
    return c;
}

/* A vertex with clip w exactly 1e-12 is behind the eye (w <= 1e-12),
 * one a rounding step further in front (w > 1e-12) is drawable. */
static void test_behind_eye_bound(void **state)
{
    (void)state;
    SceneCamera c = down_z(SCENE_PERSPECTIVE);
    Mat4 vp = scene_camera_view_proj(&c);
    double z = -1e-12;
    for (int i = 0; i < 64 && mat4_apply_point(vp, vec3(0, 0, z)).w != 1e-12;
         i++)
        z = nextafter(z, mat4_apply_point(vp, vec3(0, 0, z)).w < 1e-12
                             ? -1.0 : 1.0);
    assert_true(mat4_apply_point(vp, vec3(0, 0, z)).w == 1e-12);
    double z2 = z;
    while (!(mat4_apply_point(vp, vec3(0, 0, z2)).w > 1e-12))
        z2 = nextafter(z2, -1.0);
    Vec3 pts[6] = {vec3(0, 0, z),  vec3(1, 0, -1), vec3(0, 1, -1),
                   vec3(0, 0, z2), vec3(1, 0, -1), vec3(0, 1, -1)};
    uint8_t ok[2];
    oks(&c, pts, 6, ok);
    assert_int_equal(ok[0], 0);
    assert_int_equal(ok[1], 1);
}

/* Orthographic, height 2 on 2 x 2 pixels: screen x = x + 1 and
 * y = 1 - y exactly, so a vertex at x = 9999999 lands at screen x 1e7,
 * the first coordinate refused (|x| < 1e7), and 9999998.5 is drawable;
 * the same along y (y = -9999999). */
static void test_far_outside_bound(void **state)
{
    (void)state;
    SceneCamera c = down_z(SCENE_ORTHOGRAPHIC);
    Vec3 pts[12] = {vec3(9999999, 0, -1),    vec3(0, 0, -1), vec3(0, 1, -1),
                    vec3(9999998.5, 0, -1),  vec3(0, 0, -1), vec3(0, 1, -1),
                    vec3(0, -9999999, -1),   vec3(0, 0, -1), vec3(1, 0, -1),
                    vec3(0, -9999998.5, -1), vec3(0, 0, -1), vec3(1, 0, -1)};
    uint8_t ok[4];
    oks(&c, pts, 12, ok);
    assert_int_equal(ok[0], 0);
    assert_int_equal(ok[1], 1);
    assert_int_equal(ok[2], 0);
    assert_int_equal(ok[3], 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vertex_on_row_centre),
        cmocka_unit_test(test_row_sampled_inside),
        cmocka_unit_test(test_polys_new),
        cmocka_unit_test(test_square_spans),
        cmocka_unit_test(test_equal_crossings_keep_edge_order),
        cmocka_unit_test(test_edge_pixels_join_the_ends),
        cmocka_unit_test(test_key_layout),
        cmocka_unit_test(test_crossings_sorted),
        cmocka_unit_test(test_span_key_depth),
        cmocka_unit_test(test_nearest_palette_colour),
        cmocka_unit_test(test_modes),
        cmocka_unit_test(test_colour_indices),
        cmocka_unit_test(test_point_and_line_keys),
        cmocka_unit_test(test_partial_rows),
        cmocka_unit_test(test_edge_length_limit),
        cmocka_unit_test(test_behind_eye_bound),
        cmocka_unit_test(test_far_outside_bound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
