/* test_scan.c — scan conversion: fill rule, exactness, watertightness. */
#include "tests/raster/rast_testutil.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

static void test_square_is_exact(void **state)
{
    (void)state;
    TuCoverage *cv = tu_coverage_new(8, 8);
    RastCounters c = {0};
    assert_true(tu_scan(0, 0, 4, 0, 4, 4, 0, 8, 8, tu_coverage_sink(cv), &c));
    assert_true(tu_scan(0, 0, 4, 4, 0, 4, 1, 8, 8, tu_coverage_sink(cv), &c));
    assert_int_equal(tu_coverage_count(cv, 1), 16);
    assert_int_equal(tu_coverage_max(cv), 1);
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++)
            assert_int_equal(cv->count[y * 8 + x], 1);
    assert_int_equal(c.pixels, 16);
    tu_coverage_free(cv);
}

/* Vertices on pixel centres: the top and left edges own their centres,
 * the diagonal (a right edge for the first triangle) does not. */
static void test_top_left_rule(void **state)
{
    (void)state;
    TuCoverage *a = tu_coverage_new(8, 8), *b = tu_coverage_new(8, 8);
    RastCounters c = {0};
    assert_true(tu_scan(0.5, 0.5, 4.5, 0.5, 0.5, 4.5, 0, 8, 8,
                        tu_coverage_sink(a), &c));
    assert_int_equal(tu_coverage_count(a, 1), 10);
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++)
            assert_int_equal(a->count[y * 8 + x], x + y < 4 ? 1 : 0);
    assert_true(tu_scan(4.5, 0.5, 4.5, 4.5, 0.5, 4.5, 1, 8, 8,
                        tu_coverage_sink(b), &c));
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++)
            assert_int_equal(b->count[y * 8 + x],
                             x + y >= 4 && x < 4 && y < 4 ? 1 : 0);
    tu_coverage_free(a);
    tu_coverage_free(b);
}

/* Winding does not change coverage. */
static void test_winding_independent(void **state)
{
    (void)state;
    TuCoverage *a = tu_coverage_new(16, 16), *b = tu_coverage_new(16, 16);
    RastCounters c = {0};
    tu_scan(1.3, 2.7, 14.1, 5.5, 6.5, 13.5, 0, 16, 16, tu_coverage_sink(a), &c);
    tu_scan(6.5, 13.5, 14.1, 5.5, 1.3, 2.7, 0, 16, 16, tu_coverage_sink(b), &c);
    assert_memory_equal(a->count, b->count, 16 * 16 * sizeof(uint16_t));
    assert_true(tu_coverage_count(a, 1) > 40);
    tu_coverage_free(a);
    tu_coverage_free(b);
}

/* A coordinate on the pixel grid: random, on a centre, or on an edge. */
static double grid_coord(SimRng *r, double base)
{
    switch (sim_rng_below(r, 3)) {
    case 0:
        return base + sim_rng_uniform(r) * 0.9;
    case 1:
        return floor(base) + 0.5;
    default:
        return floor(base);
    }
}

/* A jittered grid over a region larger than the image, triangulated with
 * random diagonals and windings, covers every pixel exactly once. */
static void test_jittered_grid_watertight(void **state)
{
    (void)state;
    const int W = 67, H = 45, G = 9;
    for (uint64_t seed = 1; seed <= 5; seed++) {
        SimRng r;
        sim_rng_init(&r, seed, 7);
        double X[G + 1][G + 1], Y[G + 1][G + 1];
        for (int j = 0; j <= G; j++)
            for (int i = 0; i <= G; i++) {
                double bx = -5 + i * (W + 10.0) / G;
                double by = -5 + j * (H + 10.0) / G;
                X[j][i] = (i == 0 || i == G) ? bx : grid_coord(&r, bx);
                Y[j][i] = (j == 0 || j == G) ? by : grid_coord(&r, by);
            }
        TuCoverage *cv = tu_coverage_new(W, H);
        RastCounters c = {0};
        uint32_t id = 0;
        for (int j = 0; j < G; j++)
            for (int i = 0; i < G; i++) {
                double ax = X[j][i], ay = Y[j][i], bx = X[j][i + 1],
                       by = Y[j][i + 1], cx = X[j + 1][i + 1],
                       cy = Y[j + 1][i + 1], dx = X[j + 1][i], dy = Y[j + 1][i];
                RastSpanSink s = tu_coverage_sink(cv);
                if (sim_rng_below(&r, 2)) {
                    tu_scan(ax, ay, bx, by, cx, cy, id++, W, H, s, &c);
                    tu_scan(cx, cy, dx, dy, ax, ay, id++, W, H, s, &c);
                } else {
                    tu_scan(bx, by, dx, dy, ax, ay, id++, W, H, s, &c);
                    tu_scan(dx, dy, bx, by, cx, cy, id++, W, H, s, &c);
                }
            }
        assert_int_equal(tu_coverage_count(cv, 1), (uint64_t)W * H);
        assert_int_equal(c.pixels, (uint64_t)W * H);
        tu_coverage_free(cv);
    }
}

/* A fan about an interior point whose rim vertices are 1e-6 apart in
 * places: slivers snap to zero area and vanish, the rest stays
 * watertight. */
static void test_sliver_fan_watertight(void **state)
{
    (void)state;
    const int W = 40, H = 30;
    double rim[64][2];
    int n = 0;
    for (int i = 0; i < 8; i++) {
        double x = -2 + i * (W + 4.0) / 8;
        rim[n][0] = x, rim[n][1] = -2, n++;
        rim[n][0] = x + 1e-6, rim[n][1] = -2, n++;
    }
    for (int i = 0; i < 8; i++) {
        double y = -2 + i * (H + 4.0) / 8;
        rim[n][0] = W + 2, rim[n][1] = y, n++;
    }
    for (int i = 0; i < 8; i++) {
        double x = W + 2 - i * (W + 4.0) / 8;
        rim[n][0] = x, rim[n][1] = H + 2, n++;
        rim[n][0] = x - 1e-6, rim[n][1] = H + 2 + 1e-6, n++;
    }
    for (int i = 0; i < 8; i++) {
        double y = H + 2 - i * (H + 4.0) / 8;
        rim[n][0] = -2, rim[n][1] = y, n++;
    }
    TuCoverage *cv = tu_coverage_new(W, H);
    RastCounters c = {0};
    int dropped = 0;
    for (int i = 0; i < n; i++) {
        int k = (i + 1) % n;
        if (!tu_scan(17.5, 12.5, rim[i][0], rim[i][1], rim[k][0], rim[k][1],
                     (uint32_t)i, W, H, tu_coverage_sink(cv), &c))
            dropped++;
    }
    assert_int_equal(dropped, 16);
    assert_int_equal(tu_coverage_count(cv, 1), (uint64_t)W * H);
    tu_coverage_free(cv);
}

/* A sliver that survives snapping (1/256 pixel wide at one end) covers
 * at most one pixel per row, and its depth stays in the vertex range. */
typedef struct {
    double zmin, zmax;
    uint64_t pixels;
    int max_span;
} SpanStats;

static void stats_fn(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    SpanStats *st = ctx;
    for (int x = s->x0; x < s->x1; x++) {
        double z = rast_span_z(s, x);
        assert_true(isfinite(z));
        st->zmin = fmin(st->zmin, z);
        st->zmax = fmax(st->zmax, z);
    }
    st->pixels += (uint64_t)(s->x1 - s->x0);
    st->max_span = MAX(st->max_span, s->x1 - s->x0);
}

static void test_sliver_depth_bounded(void **state)
{
    (void)state;
    SpanStats st = {INFINITY, -INFINITY, 0, 0};
    RastScreenVert v[3] = {tu_sv(0.5, 0.25, 0.0), tu_sv(0.5, 60.0, 1.0),
                           tu_sv(0.5 + 1.0 / RAST_SUBPIX, 60.0, 0.3)};
    RastCounters c = {0};
    rast_scan_triangle(v, 0, 64, 64, (RastSpanSink){stats_fn, &st}, &c);
    assert_true(st.pixels > 0 && st.pixels <= 60);
    assert_int_equal(st.max_span, 1);
    assert_true(st.zmin >= 0.0 && st.zmax <= 1.0);
    /* Sub-snap sliver: 1e-6 wide collapses to zero area. */
    assert_false(tu_scan(0.5, 0.5, 60.5, 30.5, 60.5, 30.5 + 1e-6, 0, 64, 64,
                         (RastSpanSink){stats_fn, &st}, &c));
}

typedef struct {
    uint64_t pixels, raw_out, clamped_out;
} ClampStats;

static void clamp_fn(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    ClampStats *st = ctx;
    for (int x = s->x0; x < s->x1; x++) {
        double raw = s->z0 + s->dzdx * (double)(x - s->x0);
        double z = rast_span_z(s, x);
        st->pixels++;
        st->raw_out += raw < s->zlo || raw > s->zhi;
        st->clamped_out += z < s->zlo || z > s->zhi;
    }
}

/* Long slivers a few 1/256 pixel wide whose nearest vertex (depth 1, the
 * largest) sits on a pixel centre: the depth plane is steep across the
 * sliver, so evaluating it at that centre overshoots the vertex range by
 * rounding (~1e-13) at hundreds of pixels; the clamp keeps every depth
 * the z-buffers see inside the triangle's range. */
static void test_sliver_depth_clamped(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 5, 0);
    ClampStats st = {0};
    for (int i = 0; i < 4000; i++) {
        double x = (double)sim_rng_below(&r, 60) + 2.5;
        double y = (double)sim_rng_below(&r, 60) + 2.5;
        double ang = sim_rng_uniform(&r) * 2 * G_PI;
        double len = 20 + sim_rng_uniform(&r) * 40;
        double w = 3.0 * (1 + (double)sim_rng_below(&r, 4)) / RAST_SUBPIX;
        double bx = floor(x + len * cos(ang)) + 0.5;
        double by = floor(y + len * sin(ang)) + 0.5;
        RastScreenVert v[3] = {
            tu_sv(x + 0.3, y + 0.2, sim_rng_uniform(&r)), tu_sv(bx, by, 1.0),
            tu_sv(bx - w * sin(ang), by + w * cos(ang), sim_rng_uniform(&r))};
        if (rast_area2(&v[0], &v[1], &v[2]) == 0)
            continue;
        RastCounters c = {0};
        rast_scan_triangle(v, 0, 128, 128, (RastSpanSink){clamp_fn, &st}, &c);
    }
    print_message("%" G_GUINT64_FORMAT " pixels, %" G_GUINT64_FORMAT
                  " planes overshoot the vertex range\n",
                  st.pixels, st.raw_out);
    assert_true(st.raw_out > 0); /* the case is real */
    assert_int_equal(st.clamped_out, 0);
}

/* Spans are clipped to the image and attributes interpolate linearly. */
static void test_span_attributes(void **state)
{
    (void)state;
    RastScreenVert v[3] = {tu_sv(-10, -10, 0.0), tu_sv(30, -10, 0.4),
                           tu_sv(-10, 30, 0.8)};
    v[1].col = (RastColor){1, 0, 0};
    v[0].col = v[2].col = (RastColor){0, 0, 0};
    RastSpanList *sl = rast_spanlist_new(16, 16);
    RastCounters c = {0};
    rast_scan_triangle(v, 3, 16, 16, rast_spanlist_sink(sl), &c);
    rast_spanlist_sort(sl);
    size_t n;
    const RastSpan *row = rast_spanlist_row(sl, 5, &n);
    assert_int_equal(n, 1);
    assert_int_equal(row[0].x0, 0);
    assert_int_equal(row[0].x1, 14);
    /* Row 5 ends at the hypotenuse x + y = 20: x + 0.5 < 14.5. */
    /* z = 0.01 (x + 10) + 0.02 (y + 10) at pixel centres. */
    double z = 0.01 * (3.5 + 10) + 0.02 * (5.5 + 10);
    assert_true(fabs(rast_span_z(&row[0], 3) - z) < 1e-12);
    uint32_t rgba = rast_span_rgba(&row[0], 3);
    assert_int_equal(rgba & 0xff, (uint32_t)(255 * (13.5 / 40) + 0.5));
    assert_int_equal(c.spans, 16);
    rast_spanlist_free(sl);
}

/* ---- the end-point span rule (RAST_SPAN_ENDPOINTS) ---------------------- */

static void scan_poly(const double *xy, int n, RastSpanRule rule, int w,
                      TuCoverage *cv, RastCounters *c)
{
    RastScreenVert v[RAST_SCAN_MAX];
    for (int i = 0; i < n; i++)
        v[i] = tu_sv(xy[2 * i], xy[2 * i + 1], 0.5);
    rast_scan_polygon(v, n, 0, w, w, rule, tu_coverage_sink(cv), c);
}

/* A rectangle from x 2.6 to 5.4: exact coverage takes the centres 3.5
 * and 4.5, the end-point rule every pixel from 2 (holding 2.6) to 5
 * (holding 5.4); rows are the same (centres 1.5 .. 3.5). */
static void test_endpoints_rectangle(void **state)
{
    (void)state;
    const double r[] = {2.6, 1.2, 5.4, 1.2, 5.4, 3.9, 2.6, 3.9};
    TuCoverage *ex = tu_coverage_new(8, 8), *ep = tu_coverage_new(8, 8);
    RastCounters ce = {0}, cp = {0};
    scan_poly(r, 4, RAST_SPAN_EXACT, 8, ex, &ce);
    scan_poly(r, 4, RAST_SPAN_ENDPOINTS, 8, ep, &cp);
    assert_int_equal(ce.spans, 3);
    assert_int_equal(cp.spans, 3);
    assert_int_equal(ce.pixels, 3 * 2);
    assert_int_equal(cp.pixels, 3 * 4);
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) {
            gboolean row = y >= 1 && y <= 3;
            assert_int_equal(ex->count[y * 8 + x], row && x >= 3 && x <= 4);
            assert_int_equal(ep->count[y * 8 + x], row && x >= 2 && x <= 5);
        }
    tu_coverage_free(ex);
    tu_coverage_free(ep);
}

/* Random convex polygons: the end-point rule covers a superset of exact
 * coverage, one span per row (never two for a quad, unlike fan
 * triangles), and adds between 0 and 2 pixels per span, about 1 on
 * average (each end adds half a pixel on average). */
static void test_endpoints_superset(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 11, 0);
    uint64_t extra = 0, spans = 0;
    for (int i = 0; i < 300; i++) {
        double cx = 20 + sim_rng_uniform(&r) * 24, cy = 20 + sim_rng_uniform(&r) * 24;
        double rad = 2 + sim_rng_uniform(&r) * 12, a0 = sim_rng_uniform(&r);
        double xy[10];
        int n = 3 + (int)sim_rng_below(&r, 3);
        for (int k = 0; k < n; k++) {
            double a = (a0 + k + 0.8 * sim_rng_uniform(&r)) * 2 * G_PI / n;
            xy[2 * k] = cx + rad * cos(a);
            xy[2 * k + 1] = cy + rad * sin(a);
        }
        TuCoverage *ex = tu_coverage_new(64, 64), *ep = tu_coverage_new(64, 64);
        RastCounters ce = {0}, cp = {0};
        scan_poly(xy, n, RAST_SPAN_EXACT, 64, ex, &ce);
        scan_poly(xy, n, RAST_SPAN_ENDPOINTS, 64, ep, &cp);
        assert_true(tu_coverage_max(ep) <= 1);
        for (int p = 0; p < 64 * 64; p++)
            assert_true(ep->count[p] >= ex->count[p]);
        assert_true(cp.spans >= ce.spans);
        assert_true(cp.pixels <= ce.pixels + 2 * cp.spans);
        extra += cp.pixels - ce.pixels;
        spans += cp.spans;
        tu_coverage_free(ex);
        tu_coverage_free(ep);
    }
    double per = (double)extra / (double)spans;
    print_message("end-point rule: %.3f extra pixels per span\n", per);
    assert_true(per > 0.85 && per < 1.15);
}

/* Two triangles sharing an edge: exact coverage owns each pixel once,
 * the end-point rule generates the pixels on the shared edge twice. */
static void test_endpoints_shared_edge(void **state)
{
    (void)state;
    const double a[] = {1.3, 1.1, 30.7, 2.2, 9.9, 29.6};
    const double b[] = {30.7, 2.2, 28.4, 30.3, 9.9, 29.6};
    TuCoverage *ex = tu_coverage_new(32, 32), *ep = tu_coverage_new(32, 32);
    RastCounters c = {0};
    scan_poly(a, 3, RAST_SPAN_EXACT, 32, ex, &c);
    scan_poly(b, 3, RAST_SPAN_EXACT, 32, ex, &c);
    scan_poly(a, 3, RAST_SPAN_ENDPOINTS, 32, ep, &c);
    scan_poly(b, 3, RAST_SPAN_ENDPOINTS, 32, ep, &c);
    assert_int_equal(tu_coverage_max(ex), 1);
    assert_int_equal(tu_coverage_max(ep), 2);
    assert_true(tu_coverage_count(ep, 2) >= 25); /* about a pixel a row */
    tu_coverage_free(ex);
    tu_coverage_free(ep);
}

/* Exact rule through rast_scan_polygon on a triangle is the triangle
 * scanner itself. */
static void test_polygon_exact_is_triangle(void **state)
{
    (void)state;
    const double t[] = {1.3, 2.7, 14.1, 5.5, 6.5, 13.5};
    TuCoverage *a = tu_coverage_new(16, 16), *b = tu_coverage_new(16, 16);
    RastCounters c = {0};
    scan_poly(t, 3, RAST_SPAN_EXACT, 16, a, &c);
    tu_scan(1.3, 2.7, 14.1, 5.5, 6.5, 13.5, 0, 16, 16, tu_coverage_sink(b), &c);
    assert_memory_equal(a->count, b->count, 16 * 16 * sizeof(uint16_t));
    tu_coverage_free(a);
    tu_coverage_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_square_is_exact),
        cmocka_unit_test(test_endpoints_rectangle),
        cmocka_unit_test(test_endpoints_superset),
        cmocka_unit_test(test_endpoints_shared_edge),
        cmocka_unit_test(test_polygon_exact_is_triangle),
        cmocka_unit_test(test_top_left_rule),
        cmocka_unit_test(test_winding_independent),
        cmocka_unit_test(test_jittered_grid_watertight),
        cmocka_unit_test(test_sliver_fan_watertight),
        cmocka_unit_test(test_sliver_depth_bounded),
        cmocka_unit_test(test_sliver_depth_clamped),
        cmocka_unit_test(test_span_attributes),
    };
    return cmocka_run_group_tests_name("scan", tests, NULL, NULL);
}
