/* test_raster_mutants.c — claims of sim/raster that mutation testing
 * (make mutate, docs/testing.md) found unchecked: a polygon's attribute
 * planes come from its widest fan triangle (scan.c widest_fan: the best
 * conditioned vertices), whichever way it winds; every span carries
 * the depth clamp range [min z, max z] of its polygon's corners. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "sim/raster/clip.h"
#include "sim/raster/counters.h"
#include "sim/raster/scan.h"
#include "sim/raster/zbuffer.h"

static void worst(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    double *w = ctx;
    *w = MAX(*w, MAX(fabs(s->z0), fabs(s->dzdx)));
}

static RastScreenVert at(int x, int y, double z)
{
    RastScreenVert v = {(int64_t)x * RAST_SUBPIX, (int64_t)y * RAST_SUBPIX, z,
                        {1, 1, 1}};
    return v;
}

/* A quad with three corners at depth 0 spanning a wide triangle and a
 * fourth near their diagonal at depth 0.5: the planes are those of the
 * wide triangle, so every span has depth 0 and slope 0. */
static void test_widest_fan_planes(void **state)
{
    (void)state;
    /* the deep corner near the diagonal last, then second: the widest
     * fan triangle is the first, then the last one of the fan */
    RastScreenVert quads[2][4] = {
        {at(2, 2, 0), at(60, 2, 0), at(60, 60, 0), at(28, 34, 0.5)},
        {at(2, 2, 0), at(34, 28, 0.5), at(60, 60, 0), at(2, 60, 0)}};
    for (int k = 0; k < 4; k++) {
        const RastScreenVert *q = quads[k / 2];
        int wind = k % 2;
        RastScreenVert v[4];
        for (int i = 0; i < 4; i++)
            v[i] = wind ? q[(4 - i) % 4] : q[i];
        double w = 0;
        RastCounters c = {0};
        RastSpanSink sink = {worst, &w};
        assert_true(rast_scan_polygon(v, 4, 1, 64, 64, RAST_SPAN_EXACT, sink,
                                      &c) > 0);
        if (w > 1e-12)
            fail_msg("quad %d winding %d: a span at depth or slope %g", k / 2, wind,
                     w);
    }
}

static void range(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    double *r = ctx;
    r[0] = s->zlo;
    r[1] = s->zhi;
    r[2] += 1;
}

/* A triangle whose nearest and farthest corners take each position in
 * turn, both windings: every span's clamp range is exactly [0.1, 0.7]. */
static void test_triangle_depth_range(void **state)
{
    (void)state;
    const double z[3] = {0.1, 0.4, 0.7};
    const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                            {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < 12; k++) {
        const int *q = perm[k % 6];
        RastScreenVert v[3] = {at(4, 4, z[q[0]]), at(40, 8, z[q[1]]),
                               at(12, 36, z[q[2]])};
        if (k >= 6) { /* the other winding */
            RastScreenVert t = v[1];
            v[1] = v[2];
            v[2] = t;
        }
        double r[3] = {0, 0, 0};
        RastCounters c = {0};
        RastSpanSink sink = {range, r};
        uint64_t n = k % 2 ? rast_scan_triangle(v, 1, 64, 64, sink, &c)
                           : rast_scan_polygon(v, 3, 1, 64, 64,
                                               RAST_SPAN_ENDPOINTS, sink, &c);
        assert_true(n > 0 && r[2] == (double)n);
        if (r[0] != 0.1 || r[1] != 0.7)
            fail_msg("case %d: clamp range [%g, %g], not [0.1, 0.7]", k, r[0],
                     r[1]);
    }
}

static void count_span(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    (void)s;
    (*(int *)ctx)++;
}

/* The smallest polygon there is: twice its area one subpixel unit, one
 * winding -1, the other +1 (the winding sum starts at 0); both are
 * scanned, to the same spans. */
static void test_smallest_polygon(void **state)
{
    (void)state;
    const int64_t o = 5 * RAST_SUBPIX + RAST_SUBPIX / 2;
    RastScreenVert a = {o, o, 0.5, {1, 1, 1}}, b = a, c = a;
    b.x += 1;
    c.y += 1;
    RastScreenVert tri[2][3] = {{a, b, c}, {a, c, b}};
    int spans[2] = {0, 0};
    for (int w = 0; w < 2; w++) {
        assert_true(llabs(rast_area2(&tri[w][0], &tri[w][1], &tri[w][2])) == 1);
        RastCounters cn = {0};
        RastSpanSink sink = {count_span, &spans[w]};
        rast_scan_polygon(tri[w], 3, 1, 16, 16, RAST_SPAN_ENDPOINTS, sink, &cn);
    }
    assert_int_equal(spans[0], spans[1]);
    assert_int_equal(spans[0], 1);
}

/* A triangle poking out through one side of the guard band g = 2 (each
 * side in turn): clipped to a quad whose corners all lie within |x|,
 * |y| <= g w, two of them on the crossed plane. */
static void test_guard_sides(void **state)
{
    (void)state;
    const double g = 2, dir[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    for (int k = 0; k < 4; k++) {
        double dx = dir[k][0], dy = dir[k][1];
        RastVert in[3] = {{{10 * dx, 10 * dy, 0, 1}, {1, 1, 1}},
                          {{0.5 * dx - 0.5 * dy, 0.5 * dy + 0.5 * dx, 0, 1},
                           {1, 1, 1}},
                          {{0.5 * dx + 0.5 * dy, 0.5 * dy - 0.5 * dx, 0, 1},
                           {1, 1, 1}}};
        RastVert out[RAST_CLIP_MAX];
        int n = rast_clip_polygon(in, 3, g, out);
        assert_int_equal(n, 4);
        int on = 0;
        for (int i = 0; i < n; i++) {
            double along = out[i].pos.x * dx + out[i].pos.y * dy;
            assert_true(fabs(out[i].pos.x) <= g + 1e-12 &&
                        fabs(out[i].pos.y) <= g + 1e-12);
            on += fabs(along - g) < 1e-12;
        }
        if (on != 2)
            fail_msg("side %d: %d corners on the plane, expected 2", k, on);
    }
}

/* A new or cleared z-buffer: every pixel empty (depth +inf, no
 * primitive, colour 0), also after a span was drawn and cleared. */
static void test_zbuffer_cleared(void **state)
{
    (void)state;
    RastZBuffer *zb = rast_zbuffer_new(5, 3);
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < 15; i++)
            assert_true(isinf(zb->depth[i]) && zb->depth[i] > 0 &&
                        zb->prim[i] == RAST_NO_PRIM && zb->rgba[i] == 0);
        RastSpan sp = {.y = 1, .x0 = 0, .x1 = 5, .prim = 7, .z0 = 0.5,
                       .zlo = 0, .zhi = 1, .c0 = {1, 1, 1}};
        RastCounters c = {0};
        rast_zbuffer_span(zb, &sp, &c);
        assert_true(zb->prim[5] == 7 && zb->rgba[5] != 0);
        rast_zbuffer_clear(zb);
    }
    rast_zbuffer_free(zb);
}

/* Counters add field by field: each sum, and its name in the text form. */
static void test_counters_add(void **state)
{
    (void)state;
    RastCounters d = {.verts = 10, .prims = 20, .culled = 30, .clipped = 40,
                      .rejected = 50, .degenerate = 60, .spans = 70,
                      .pixels = 80, .winners = 90, .zcompares = 100,
                      .zwrites = 110};
    RastCounters s = {.verts = 1, .prims = 2, .culled = 3, .clipped = 4,
                      .rejected = 5, .degenerate = 6, .spans = 7, .pixels = 8,
                      .winners = 9, .zcompares = 10, .zwrites = 11};
    rast_counters_add(&d, &s);
    char *t = rast_counters_format(&d);
    assert_string_equal(t, "verts=11 prims=22 culled=33 clipped=44 "
                           "rejected=55 degenerate=66 spans=77 TPG=88 TPF=99 "
                           "zcmp=110 zwrites=121");
    g_free(t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_widest_fan_planes),
        cmocka_unit_test(test_triangle_depth_range),
        cmocka_unit_test(test_smallest_polygon),
        cmocka_unit_test(test_guard_sides),
        cmocka_unit_test(test_zbuffer_cleared),
        cmocka_unit_test(test_counters_add),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
