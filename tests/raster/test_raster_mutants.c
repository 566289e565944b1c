/* test_raster_mutants.c — claims of sim/raster that mutation testing
 * (make mutate, docs/testing.md) found unchecked: a polygon's attribute
 * planes come from its widest fan triangle (scan.c widest_fan: the best
 * conditioned vertices), whichever way it winds. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/raster/scan.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_widest_fan_planes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
