/* test_zbuffer_values.c — exact results of sim/raster/zbuffer.c (issue 21).
 *
 * Merging pixel by pixel, first and last pixel included: nearer wins,
 * equal depth goes to the lower id, empty source pixels cost nothing;
 * a sorted list with an empty first row z-buffered with exact comparison
 * and write counts and per-pixel depth, id and colour. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/raster/zbuffer.h"

static void put(RastZBuffer *zb, int i, double z, uint32_t prim, uint32_t rgba)
{
    zb->depth[i] = z;
    zb->prim[i] = prim;
    zb->rgba[i] = rgba;
}

/* Six pixels: 0 source nearer, 1 both empty, 2 equal depth and the
 * source's lower id, 3 destination empty, 4 source empty, 5 source
 * farther. */
static void test_merge_each_case(void **state)
{
    (void)state;
    RastZBuffer *dst = rast_zbuffer_new(3, 2), *src = rast_zbuffer_new(3, 2);
    put(dst, 0, 0.5, 10, 0xff000010u);
    put(src, 0, 0.25, 20, 0xff000020u);
    put(dst, 2, 0.5, 11, 0xff000011u);
    put(src, 2, 0.5, 3, 0xff000003u);
    put(src, 3, 0.75, 21, 0xff000021u);
    put(dst, 4, 0.1, 12, 0xff000012u);
    put(dst, 5, 0.2, 13, 0xff000013u);
    put(src, 5, 0.9, 22, 0xff000022u);
    RastCounters c = {0};
    rast_zbuffer_merge(dst, src, &c);
    const uint32_t prim[6] = {20, RAST_NO_PRIM, 3, 21, 12, 13};
    const double depth[6] = {0.25, INFINITY, 0.5, 0.75, 0.1, 0.2};
    const uint32_t rgba[6] = {0xff000020u, 0,           0xff000003u,
                              0xff000021u, 0xff000012u, 0xff000013u};
    for (int i = 0; i < 6; i++) {
        assert_int_equal(dst->prim[i], prim[i]);
        assert_true(dst->depth[i] == depth[i]);
        assert_int_equal(dst->rgba[i], rgba[i]);
    }
    assert_int_equal(c.zcompares, 4); /* source-covered pixels 0, 2, 3, 5 */
    assert_int_equal(c.zwrites, 3);
    assert_int_equal(rast_zbuffer_covered(dst), 5);
    assert_int_equal(rast_zbuffer_covered(src), 4);
    rast_zbuffer_free(dst);
    rast_zbuffer_free(src);
}

static RastSpan span(int y, int x0, int x1, double z0, double dzdx,
                     uint32_t prim, float red)
{
    RastSpan s = {0};
    s.y = y;
    s.x0 = x0;
    s.x1 = x1;
    s.z0 = z0;
    s.dzdx = dzdx;
    s.zlo = 0;
    s.zhi = 1;
    s.prim = prim;
    s.c0[0] = red;
    return s;
}

/* Row 0 empty; row 1: A [0, 4) at depth 0.5 rising 0.1 a pixel, B [2, 6)
 * flat at 0.75 (A keeps 2, at 0.7; B wins 3, where A is 0.8, and 4, 5); row 2:
 * C [5, 6).  Comparisons = pixels of the spans (4 + 4 + 1), writes =
 * 4 + 3 + 1. */
static void test_spans_from_list(void **state)
{
    (void)state;
    RastSpanList *sl = rast_spanlist_new(6, 3);
    RastSpan s[3] = {span(1, 0, 4, 0.5, 0.1, 1, 1.0f),
                     span(1, 2, 6, 0.75, 0.0, 2, 0.0f),
                     span(2, 5, 6, 0.3, 0.0, 3, 1.0f)};
    for (int i = 2; i >= 0; i--)
        rast_spanlist_add(sl, &s[i]);
    rast_spanlist_sort(sl);
    RastZBuffer *zb = rast_zbuffer_new(6, 3);
    RastCounters c = {0};
    rast_zbuffer_spans(zb, sl, &c);
    assert_int_equal(c.zcompares, 9);
    assert_int_equal(c.zwrites, 8);
    const uint32_t row1[6] = {1, 1, 1, 2, 2, 2};
    for (int x = 0; x < 6; x++) {
        assert_int_equal(zb->prim[x], RAST_NO_PRIM);
        assert_int_equal(zb->prim[6 + x], row1[x]);
        double z = row1[x] == 1 ? 0.5 + 0.1 * x : 0.75;
        assert_true(fabs(zb->depth[6 + x] - z) < 1e-12);
        assert_int_equal(zb->rgba[6 + x], row1[x] == 1 ? 0xff0000ffu
                                                        : 0xff000000u);
        assert_int_equal(zb->prim[12 + x], x == 5 ? 3u : RAST_NO_PRIM);
    }
    assert_true(zb->depth[17] == 0.3);
    assert_int_equal(rast_zbuffer_covered(zb), 7);
    /* a sink z-buffers as the spans come */
    RastZBuffer *zi = rast_zbuffer_new(6, 3);
    RastSpanSink sink = rast_zbuffer_sink(zi);
    RastCounters d = {0};
    for (int i = 0; i < 3; i++)
        sink.fn(sink.ctx, &s[i], &d);
    assert_memory_equal(zi->prim, zb->prim, sizeof(uint32_t) * 18);
    assert_int_equal(d.zcompares, 9);
    rast_zbuffer_free(zi);
    rast_zbuffer_free(zb);
    rast_spanlist_free(sl);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_merge_each_case),
        cmocka_unit_test(test_spans_from_list),
    };
    return cmocka_run_group_tests_name("zbuffer_values", tests, NULL, NULL);
}
