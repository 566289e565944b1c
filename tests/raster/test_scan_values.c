/* test_scan_values.c — exact results of sim/raster/scan.c (issue 21).
 *
 * The guard band, viewport mapping and signed area by hand; one triangle
 * whose every span field is worked out by hand; and random triangles and
 * convex polygons (partly off screen, either winding, corners on pixel
 * centres now and then) checked span by span against brute-force
 * references: per-pixel edge functions with the top-left rule for exact
 * coverage, and the row's exact intersection with the polygon (rational
 * arithmetic) for the end-point rule, with depth and colour against the
 * plane the corners were put on. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/core/rng.h"
#include "sim/raster/scan.h"

#define S RAST_SUBPIX

static void test_guard_band(void **state)
{
    (void)state;
    assert_true(rast_guard_band(64, 32) == 1024.0);
    assert_true(rast_guard_band(32, 64) == 1024.0);
    assert_true(rast_guard_band(100, 100) == 655.36);
    assert_true(rast_guard_band(1, 1) == 65536.0);
}

static void test_viewport_and_area(void **state)
{
    (void)state;
    RastVert v = {{0.5, -0.25, 0.2, 2}, {0.25f, 0.5f, 0.75f}};
    RastScreenVert s = rast_viewport(&v, 64, 32);
    /* x: (0.25 + 1) / 2 * 64 = 40; y: (1 + 0.125) / 2 * 32 = 18 */
    assert_true(s.x == 40 * S && s.y == 18 * S);
    assert_true(fabs(s.z - 0.55) < 1e-15);
    assert_true(s.col.r == 0.25f && s.col.g == 0.5f && s.col.b == 0.75f);
    /* snapping rounds to the nearest 1/256 pixel */
    RastVert q = {{-1 + 2.0 * (3 + 0.4 / S) / 64, 1 - 2.0 * (5 + 0.6 / S) / 32,
                   0, 1},
                  {0, 0, 0}};
    s = rast_viewport(&q, 64, 32);
    assert_true(s.x == 3 * S && s.y == 5 * S + 1);
    assert_true(s.z == 0.5);
    /* depth clamped to [0, 1] */
    RastVert n = {{0, 0, -3, 1}, {0, 0, 0}}, f = {{0, 0, 3, 1}, {0, 0, 0}};
    assert_true(rast_viewport(&n, 8, 8).z == 0.0);
    assert_true(rast_viewport(&f, 8, 8).z == 1.0);
    /* twice the area, negative when clockwise on screen (y down) */
    RastScreenVert a = {0, 0, 0, {0, 0, 0}}, b = {2, 0, 0, {0, 0, 0}},
                   c = {0, 3, 0, {0, 0, 0}}, d = {5, 7, 0, {0, 0, 0}};
    assert_true(rast_area2(&a, &b, &c) == -6);
    assert_true(rast_area2(&a, &c, &b) == 6);
    assert_true(rast_area2(&b, &c, &d) == -((-2) * 7 - 3 * 3));
}

typedef struct {
    RastSpan s[256];
    int n;
} Spans;

static void collect(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    Spans *k = ctx;
    g_assert(k->n < 256);
    k->s[k->n++] = *s;
}

static RastScreenVert sv(double x, double y, double z, float r, float g,
                         float b)
{
    return (RastScreenVert){(int64_t)llround(x * S), (int64_t)llround(y * S), z,
                            {r, g, b}};
}

/* Corners (2, 1), (10, 1), (2, 9): rows 1..7 are [2, 10 - y) (row 8's
 * only centre candidate, 2.5 + 8.5 = 11, lies on the hypotenuse, a right
 * edge); z = 0.2 + 0.05 (x - 2) + 0.1 (y - 1), red falls and green rises
 * along x, blue rises along y. */
static void test_triangle_spans_by_hand(void **state)
{
    (void)state;
    RastScreenVert v[3] = {sv(2, 1, 0.2, 1, 0, 0), sv(10, 1, 0.6, 0, 1, 0),
                           sv(2, 9, 1.0, 0, 0, 1)};
    for (int k = 0; k < 4; k++) {
        RastScreenVert t[3] = {v[0], v[1], v[2]};
        if (k % 2) { /* the other winding */
            t[1] = v[2];
            t[2] = v[1];
        }
        Spans got = {.n = 0};
        RastCounters c = {0};
        RastSpanSink sink = {collect, &got};
        uint64_t n = k < 2 ? rast_scan_triangle(t, 42, 16, 16, sink, &c)
                           : rast_scan_polygon(t, 3, 42, 16, 16,
                                               RAST_SPAN_EXACT, sink, &c);
        assert_int_equal(n, 7);
        assert_int_equal(got.n, 7);
        assert_int_equal(c.spans, 7);
        assert_int_equal(c.pixels, 7 + 6 + 5 + 4 + 3 + 2 + 1);
        for (int i = 0; i < 7; i++) {
            const RastSpan *s = &got.s[i];
            int y = i + 1;
            assert_int_equal(s->y, y);
            assert_int_equal(s->x0, 2);
            assert_int_equal(s->x1, 10 - y);
            assert_int_equal(s->prim, 42);
            assert_true(fabs(s->z0 - (0.2 + 0.025 + 0.1 * (y - 0.5))) < 1e-12);
            assert_true(fabs(s->dzdx - 0.05) < 1e-12);
            assert_true(s->zlo == 0.2 && s->zhi == 1.0);
            assert_true(fabs(s->c0[0] - (1 - 0.0625 - (y - 0.5) / 8)) < 1e-6);
            assert_true(fabs(s->c0[1] - 0.0625) < 1e-6);
            assert_true(fabs(s->c0[2] - (y - 0.5) / 8) < 1e-6);
            assert_true(fabs(s->dcdx[0] + 0.125) < 1e-6);
            assert_true(fabs(s->dcdx[1] - 0.125) < 1e-6);
            assert_true(fabs(s->dcdx[2]) < 1e-6);
        }
    }
}

/* ---- brute-force references --------------------------------------------- */

static int64_t fdiv(int64_t a, int64_t b) /* floor(a / b), b > 0 */
{
    int64_t q = a / b;
    return q * b > a ? q - 1 : q;
}

/* Exact coverage of pixel (x, y) by the convex polygon t[0..n) (either
 * winding): the centre strictly inside every edge, or on an edge that is
 * a left or top one (oriented so that the inside is positive). */
static gboolean covers(const RastScreenVert *t, int n, int64_t sign, int x,
                       int y)
{
    int64_t px = (int64_t)x * S + S / 2, py = (int64_t)y * S + S / 2;
    for (int i = 0; i < n; i++) {
        const RastScreenVert *a = &t[i], *b = &t[(i + 1) % n];
        int64_t dx = (b->x - a->x) * sign, dy = (b->y - a->y) * sign;
        if (dx == 0 && dy == 0)
            continue; /* a repeated corner */
        int64_t e = dx * (py - a->y) - dy * (px - a->x);
        if (e < 0 || (e == 0 && !(dy < 0 || (dy == 0 && dx > 0))))
            return FALSE;
    }
    return TRUE;
}

/* The end-point span of row y: from the pixel holding the row centre
 * line's leftmost point on the polygon to the one holding its rightmost
 * one; FALSE outside the polygon's height or on a bottom edge. */
static gboolean ends_span(const RastScreenVert *t, int n, int64_t sign, int y,
                          int w, int *x0, int *x1)
{
    int64_t py = (int64_t)y * S + S / 2, lo = INT64_MAX, hi = INT64_MIN;
    for (int i = 0; i < n; i++) {
        const RastScreenVert *a = &t[i], *b = &t[(i + 1) % n];
        if (a->y == b->y) {
            if (a->y == py && (b->x - a->x) * sign < 0)
                return FALSE; /* on a bottom edge */
            continue;
        }
        if (py < MIN(a->y, b->y) || py > MAX(a->y, b->y))
            continue;
        /* x = a.x + (py - a.y) (b.x - a.x) / (b.y - a.y), in pixels */
        int64_t num = a->x * (b->y - a->y) + (py - a->y) * (b->x - a->x);
        int64_t den = (b->y - a->y) * S;
        if (den < 0) {
            num = -num;
            den = -den;
        }
        int64_t f = fdiv(num, den);
        lo = MIN(lo, f);
        hi = MAX(hi, f);
    }
    if (lo > hi)
        return FALSE;
    *x0 = (int)MAX(lo, 0);
    *x1 = (int)MIN(hi + 1, w);
    return *x0 < *x1;
}

static int64_t winding_sign(const RastScreenVert *t, int n)
{
    int64_t a = 0;
    for (int i = 1; i + 1 < n; i++)
        a += rast_area2(&t[0], &t[i], &t[i + 1]);
    return a < 0 ? 1 : -1; /* E > 0 inside for negative area */
}

/* A random coordinate: anywhere, on a pixel centre, or on a pixel edge. */
static double coord(SimRng *r, double lo, double hi)
{
    double v = lo + (hi - lo) * sim_rng_uniform(r);
    switch (sim_rng_below(r, 4)) {
    case 0:
        return floor(v) + 0.5;
    case 1:
        return floor(v);
    default:
        return v;
    }
}

/* Convex polygon about (cx, cy): n corners at increasing angles. */
static int random_polygon(SimRng *r, RastScreenVert *t, int n, double W)
{
    double cx = coord(r, -4, W + 4), cy = coord(r, -4, W + 4);
    double rad = 0.4 + 9 * sim_rng_uniform(r), a0 = sim_rng_uniform(r);
    for (int k = 0; k < n; k++) {
        double a = (a0 + k + 0.7 * sim_rng_uniform(r)) * 2 * G_PI / n;
        t[k] = sv(cx + rad * cos(a), cy + rad * sin(a), 0, 0, 0, 0);
        if (sim_rng_below(r, 3) == 0) { /* snap a corner to the grid */
            t[k].x = (t[k].x / (S / 2)) * (S / 2);
            t[k].y = (t[k].y / (S / 2)) * (S / 2);
        }
    }
    if (sim_rng_below(r, 2)) /* the other winding */
        for (int k = 0; k < n / 2; k++) {
            RastScreenVert s = t[k];
            t[k] = t[n - 1 - k];
            t[n - 1 - k] = s;
        }
    /* planar depth and colour: z = 0.3 + 0.01 x + 0.02 y (pixels) */
    for (int k = 0; k < n; k++) {
        double x = (double)t[k].x / S, y = (double)t[k].y / S;
        t[k].z = 0.3 + 0.01 * x + 0.02 * y;
        t[k].col = (RastColor){(float)(0.5 + 0.01 * x), (float)(0.02 * y),
                               (float)(0.25 - 0.005 * x + 0.01 * y)};
    }
    /* convex with non-zero area, no repeated corner */
    for (int k = 0; k < n; k++)
        if (rast_area2(&t[k], &t[(k + 1) % n], &t[(k + 2) % n]) *
                -winding_sign(t, n) <= 0)
            return 0;
    return n;
}

static void check_attributes(const RastSpan *s, const RastScreenVert *t, int n)
{
    double px = s->x0 + 0.5, py = s->y + 0.5;
    double zlo = t[0].z, zhi = t[0].z;
    for (int k = 1; k < n; k++) {
        zlo = fmin(zlo, t[k].z);
        zhi = fmax(zhi, t[k].z);
    }
    assert_true(s->zlo == zlo && s->zhi == zhi);
    if (fabs(s->z0 - (0.3 + 0.01 * px + 0.02 * py)) > 1e-9 ||
        fabs(s->dzdx - 0.01) > 1e-9)
        fail_msg("row %d: z0 %.12g dzdx %.12g", s->y, s->z0, s->dzdx);
    assert_true(fabsf(s->c0[0] - (float)(0.5 + 0.01 * px)) < 1e-5f);
    assert_true(fabsf(s->c0[1] - (float)(0.02 * py)) < 1e-5f);
    assert_true(fabsf(s->c0[2] - (float)(0.25 - 0.005 * px + 0.01 * py)) <
                1e-5f);
    assert_true(fabsf(s->dcdx[0] - 0.01f) < 1e-6f);
    assert_true(fabsf(s->dcdx[1]) < 1e-6f);
    assert_true(fabsf(s->dcdx[2] + 0.005f) < 1e-6f);
}

static void check_polygon(const RastScreenVert *t, int n, RastSpanRule rule,
                          int W, int k)
{
    Spans got = {.n = 0};
    RastCounters c = {0};
    RastSpanSink sink = {collect, &got};
    uint64_t ns = rast_scan_polygon(t, n, 7, W, W, rule, sink, &c);
    assert_int_equal(ns, got.n);
    assert_int_equal(c.spans, got.n);
    int64_t sign = winding_sign(t, n);
    uint64_t pixels = 0;
    int i = 0;
    for (int y = 0; y < W; y++) {
        int x0 = 0, x1 = 0;
        gboolean has;
        if (rule == RAST_SPAN_EXACT) {
            for (x0 = 0; x0 < W && !covers(t, n, sign, x0, y); x0++)
                ;
            for (x1 = x0; x1 < W && covers(t, n, sign, x1, y); x1++)
                ;
            has = x0 < x1;
        } else {
            has = ends_span(t, n, sign, y, W, &x0, &x1);
        }
        if (!has)
            continue;
        if (i >= got.n || got.s[i].y != y || got.s[i].x0 != x0 ||
            got.s[i].x1 != x1)
            fail_msg("polygon %d (%d corners, rule %d) row %d: expected "
                     "[%d, %d), got row %d [%d, %d)",
                     k, n, rule, y, x0, x1, i < got.n ? got.s[i].y : -1,
                     i < got.n ? got.s[i].x0 : -1,
                     i < got.n ? got.s[i].x1 : -1);
        assert_int_equal(got.s[i].prim, 7);
        check_attributes(&got.s[i], t, n);
        pixels += (uint64_t)(x1 - x0);
        i++;
    }
    if (i != got.n)
        fail_msg("polygon %d (%d corners, rule %d): %d spans, expected %d", k,
                 n, rule, got.n, i);
    assert_int_equal(c.pixels, pixels);
}

/* Triangles through rast_scan_triangle and polygons of 3 to 8 corners
 * through rast_scan_polygon, both rules, against the references. */
static void test_against_brute_force(void **state)
{
    (void)state;
    const int W = 24;
    SimRng r;
    sim_rng_init(&r, 31337, 0);
    int done = 0;
    for (int k = 0; done < 1500; k++) {
        RastScreenVert t[8];
        int n = 3 + (int)sim_rng_below(&r, 6);
        if (!random_polygon(&r, t, n, W))
            continue;
        done++;
        check_polygon(t, n, RAST_SPAN_EXACT, W, k);
        check_polygon(t, n, RAST_SPAN_ENDPOINTS, W, k);
        /* a corner repeated next to itself changes nothing */
        RastScreenVert u[9];
        int j = (int)sim_rng_below(&r, (uint64_t)n);
        for (int i = 0, o = 0; i < n; i++) {
            u[o++] = t[i];
            if (i == j)
                u[o++] = t[i];
        }
        check_polygon(u, n + 1, RAST_SPAN_EXACT, W, k);
        check_polygon(u, n + 1, RAST_SPAN_ENDPOINTS, W, k);
        if (n == 3) {
            Spans a = {.n = 0};
            RastCounters c = {0};
            rast_scan_triangle(t, 7, W, W, (RastSpanSink){collect, &a}, &c);
            Spans b = {.n = 0};
            rast_scan_polygon(t, 3, 7, W, W, RAST_SPAN_EXACT,
                              (RastSpanSink){collect, &b}, &c);
            assert_int_equal(a.n, b.n);
            assert_memory_equal(a.s, b.s, sizeof(RastSpan) * (size_t)a.n);
        }
    }
}

/* A narrow downward spike under the end-point rule: its apex (10.5, 5.6)
 * is above row 6's centre, where the two sides' lines have crossed but
 * still fall in one pixel; row 6 is below the polygon and has no span.
 * Likewise an upward spike's apex below row 1's centre. */
static void test_endpoints_apex_rows(void **state)
{
    (void)state;
    RastScreenVert down[3] = {sv(9.5, 1.0, 0.5, 1, 1, 1),
                              sv(11.5, 1.0, 0.5, 1, 1, 1),
                              sv(10.5, 5.6, 0.5, 1, 1, 1)};
    RastScreenVert up[3] = {sv(10.5, 1.4, 0.5, 1, 1, 1),
                            sv(11.5, 6.0, 0.5, 1, 1, 1),
                            sv(9.5, 6.0, 0.5, 1, 1, 1)};
    for (int k = 0; k < 2; k++) {
        Spans got = {.n = 0};
        RastCounters c = {0};
        rast_scan_polygon(k ? up : down, 3, 1, 16, 16, RAST_SPAN_ENDPOINTS,
                          (RastSpanSink){collect, &got}, &c);
        assert_int_equal(got.n, 5);
        int y0 = 1;
        for (int i = 0; i < got.n; i++)
            assert_int_equal(got.s[i].y, y0 + i);
    }
}

/* A triangle one subpixel wide at the top: its top edge runs from the
 * centre of pixel (5, 5) one subpixel right, one subpixel above the
 * centre line of row 5, so E = 1 there (inside); the left edge runs
 * down through the centres of column 5 (inside, a left edge), and the
 * hypotenuse stays right of them down to row 14: column 5 of rows 5..14
 * is covered, nothing else. */
static void test_one_subpixel_top_edge(void **state)
{
    (void)state;
    const int64_t c = 5 * S + S / 2;
    RastScreenVert v[3] = {{c, c - 1, 0.5, {1, 1, 1}},
                           {c + 1, c - 1, 0.5, {1, 1, 1}},
                           {c, c - 1 + 10 * S, 0.5, {1, 1, 1}}};
    for (int k = 0; k < 2; k++) {
        Spans got = {.n = 0};
        RastCounters cn = {0};
        rast_scan_polygon(v, 3, 1, 16, 16, RAST_SPAN_EXACT,
                          (RastSpanSink){collect, &got}, &cn);
        assert_int_equal(got.n, 10);
        for (int i = 0; i < got.n; i++)
            assert_true(got.s[i].y == 5 + i && got.s[i].x0 == 5 &&
                        got.s[i].x1 == 6);
        RastScreenVert t = v[1]; /* the other winding */
        v[1] = v[2];
        v[2] = t;
    }
}

/* The smallest quad with a repeated corner: its first fan triangle
 * (0, 1, 2) has area 0, the second twice-area 1; the depth plane comes
 * from the second (the widest), so depth is the corners' 0.5, flat. */
static void test_widest_fan_tiny(void **state)
{
    (void)state;
    const int64_t c = 5 * S + S / 2;
    RastScreenVert v[4] = {{c, c, 0.5, {1, 1, 1}},
                           {c + 1, c, 0.5, {1, 1, 1}},
                           {c + 1, c, 0.5, {1, 1, 1}},
                           {c, c + 1, 0.5, {1, 1, 1}}};
    Spans got = {.n = 0};
    RastCounters cn = {0};
    rast_scan_polygon(v, 4, 1, 16, 16, RAST_SPAN_ENDPOINTS,
                      (RastSpanSink){collect, &got}, &cn);
    assert_int_equal(got.n, 1);
    assert_true(got.s[0].y == 5 && got.s[0].x0 == 5 && got.s[0].x1 == 6);
    assert_true(got.s[0].z0 == 0.5 && got.s[0].dzdx == 0.0);
}

/* A square whose two fan triangles have equal area and one corner deep
 * (z 0.8, the others 0): the first widest fan triangle, the flat one,
 * gives the planes, so every span has depth 0 and slope 0.  Listed both
 * ways round, the deep corner last of the fan each time. */
static void test_widest_fan_first_of_equals(void **state)
{
    (void)state;
    RastScreenVert sq[2][4] = {
        {sv(2, 2, 0, 1, 1, 1), sv(10, 2, 0, 1, 1, 1), sv(10, 10, 0, 1, 1, 1),
         sv(2, 10, 0.8, 1, 1, 1)},
        {sv(2, 2, 0, 1, 1, 1), sv(2, 10, 0.8, 1, 1, 1), sv(10, 10, 0, 1, 1, 1),
         sv(10, 2, 0, 1, 1, 1)}};
    for (int k = 0; k < 4; k++) {
        Spans got = {.n = 0};
        RastCounters c = {0};
        rast_scan_polygon(sq[k % 2], 4, 1, 16, 16, k / 2,
                          (RastSpanSink){collect, &got}, &c);
        assert_int_equal(got.n, 8);
        for (int i = 0; i < got.n; i++)
            if (got.s[i].z0 != 0.0 || got.s[i].dzdx != 0.0 ||
                got.s[i].zhi != 0.8)
                fail_msg("square %d rule %d row %d: z0 %g dzdx %g zhi %g",
                         k % 2, k / 2, got.s[i].y, got.s[i].z0,
                         got.s[i].dzdx, got.s[i].zhi);
    }
}

/* Rows are clamped to the image: a polygon taller than a 4x3 image gets
 * exactly rows 0..2, each [0, 4). */
static void test_rows_clamped(void **state)
{
    (void)state;
    RastScreenVert q[4] = {sv(-5, -5, 0.5, 1, 1, 1), sv(9, -5, 0.5, 1, 1, 1),
                           sv(9, 9, 0.5, 1, 1, 1), sv(-5, 9, 0.5, 1, 1, 1)};
    for (int rule = 0; rule < 2; rule++) {
        Spans got = {.n = 0};
        RastCounters c = {0};
        assert_int_equal(rast_scan_polygon(q, 4, 1, 4, 3, rule,
                                           (RastSpanSink){collect, &got}, &c),
                         3);
        for (int i = 0; i < 3; i++) {
            assert_int_equal(got.s[i].y, i);
            assert_int_equal(got.s[i].x0, 0);
            assert_int_equal(got.s[i].x1, 4);
        }
        assert_int_equal(c.pixels, 12);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_guard_band),
        cmocka_unit_test(test_viewport_and_area),
        cmocka_unit_test(test_triangle_spans_by_hand),
        cmocka_unit_test(test_against_brute_force),
        cmocka_unit_test(test_endpoints_apex_rows),
        cmocka_unit_test(test_rows_clamped),
        cmocka_unit_test(test_one_subpixel_top_edge),
        cmocka_unit_test(test_widest_fan_tiny),
        cmocka_unit_test(test_widest_fan_first_of_equals),
    };
    return cmocka_run_group_tests_name("scan_values", tests, NULL, NULL);
}
