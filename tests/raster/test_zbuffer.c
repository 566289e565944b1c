/* test_zbuffer.c — the full and the modified scanline z-buffers. */
#include "tests/raster/rast_testutil.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

static RastSpan flat_span(int y, int x0, int x1, double z, uint32_t prim,
                          float red)
{
    RastSpan s = {0};
    s.y = y;
    s.x0 = x0;
    s.x1 = x1;
    s.prim = prim;
    s.z0 = z;
    s.zlo = s.zhi = z;
    s.c0[0] = red;
    return s;
}

static void test_depth_and_ties(void **state)
{
    (void)state;
    RastZBuffer *zb = rast_zbuffer_new(8, 1);
    RastCounters c = {0};
    RastSpan a = flat_span(0, 0, 4, 0.5, 7, 1.0f);
    RastSpan b = flat_span(0, 2, 6, 0.5, 3, 0.5f);  /* same z, lower id */
    RastSpan d = flat_span(0, 3, 8, 0.25, 9, 0.0f); /* nearer */
    rast_zbuffer_span(zb, &a, &c);
    rast_zbuffer_span(zb, &b, &c);
    rast_zbuffer_span(zb, &d, &c);
    uint32_t want[8] = {7, 7, 3, 9, 9, 9, 9, 9};
    for (int x = 0; x < 8; x++)
        assert_int_equal(zb->prim[x], want[x]);
    assert_int_equal(c.zcompares, 4 + 4 + 5);
    assert_int_equal(rast_zbuffer_covered(zb), 8);
    /* Reverse order: same winners. */
    RastZBuffer *zr = rast_zbuffer_new(8, 1);
    rast_zbuffer_span(zr, &d, &c);
    rast_zbuffer_span(zr, &b, &c);
    rast_zbuffer_span(zr, &a, &c);
    assert_memory_equal(zb->prim, zr->prim, sizeof(uint32_t) * 8);
    assert_memory_equal(zb->rgba, zr->rgba, sizeof(uint32_t) * 8);
    rast_zbuffer_free(zb);
    rast_zbuffer_free(zr);
    rast_zbuffer_free(NULL);
}

/* Three overlapping spans on row 0, inserted out of order: sorted by
 * x_min they are A [0,5), C [3,15), B [10,20); only overlaps compare. */
static void test_scanline_segments(void **state)
{
    (void)state;
    RastSpanList *sl = rast_spanlist_new(32, 3);
    RastSpan sp[] = {
        flat_span(0, 0, 5, 0.5, 1, 1), flat_span(0, 10, 20, 0.5, 2, 1),
        flat_span(0, 3, 15, 0.2, 3, 1), flat_span(1, 5, 8, 0.9, 4, 1),
        flat_span(2, 0, 32, 0.9, 5, 1)};
    for (int i = 4; i >= 0; i--) /* unsorted insertion */
        rast_spanlist_add(sl, &sp[i]);
    rast_spanlist_sort(sl);
    RastActive *a = rast_active_new(32, 3);
    RastCounters c = {0};
    rast_scanline_zbuffer(a, sl, &c);
    const size_t *off = rast_active_offsets(a);
    assert_int_equal(off[1] - off[0], 20);
    assert_int_equal(off[2] - off[1], 3);
    assert_int_equal(off[3] - off[2], 32);
    /* Row 0: C splits at 5 ([3,5) compared), B at 15 ([10,15) compared);
     * rows 1 and 2 reuse the MSA without clearing and compare nothing. */
    assert_int_equal(c.zcompares, 2 + 5);
    assert_int_equal(c.zwrites, 20 + 2 + 3 + 32);
    assert_int_equal(c.winners, 55);
    size_t n;
    const RastActivePixel *row = rast_active_row(a, 0, &n);
    uint32_t owner[20];
    for (size_t i = 0; i < n; i++)
        owner[row[i].x] = row[i].prim;
    for (int x = 0; x < 20; x++)
        assert_int_equal(owner[x], x < 3 ? 1u : (x < 15 ? 3u : 2u));
    /* every row is in x order as generated: 0..19, 5..7, 0..31 */
    const int first[3] = {0, 5, 0};
    for (int y = 0; y < 3; y++) {
        row = rast_active_row(a, y, &n);
        for (size_t i = 0; i < n; i++)
            assert_int_equal(row[i].x, first[y] + (int)i);
    }
    /* Running again reuses the MSA without clearing rows: same result. */
    RastCounters c2 = {0};
    rast_scanline_zbuffer(a, sl, &c2);
    assert_int_equal(c2.winners, 55);
    rast_active_free(a);
    rast_active_free(NULL);
    rast_spanlist_free(sl);
}

/* Random overlapping triangles: both z-buffers give the same image, the
 * same TPF and TPG; the scanline variant compares less. */
static void test_full_equals_scanline(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4; seed++) {
        SceneMesh *m = tu_random_tris(seed, 400, 0.5);
        RastView v = rast_view_make(mat4_identity(), 97, 83);
        v.cull_back = FALSE;
        v.shading = seed % 2 ? RAST_SHADE_GOURAUD : RAST_SHADE_FLAT;
        RastImage *f, *s;
        RastCounters cf = {0}, cs = {0};
        tu_render_both(&v, m, NULL, 0, &f, &s, &cf, &cs);
        assert_true(rast_image_equal(f, s));
        assert_int_equal(cf.winners, cs.winners);
        assert_int_equal(cf.pixels, cs.pixels);
        assert_true(cs.zcompares < cf.zcompares);
        assert_true(cf.winners > 97 * 83 / 2);
        rast_image_free(f);
        rast_image_free(s);
        /* a sorted span list z-buffered row by row covers the same
         * pixels, and the scanline z-buffer keeps one active pixel per
         * covered pixel; counters add field by field */
        RastSpanList *sl = rast_spanlist_new(97, 83);
        RastCounters c = {0}, sum = cf;
        rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL, rast_spanlist_sink(sl), &c);
        rast_spanlist_sort(sl);
        assert_int_equal(rast_spanlist_len(sl), c.spans);
        RastZBuffer *zb = rast_zbuffer_new(97, 83);
        rast_zbuffer_spans(zb, sl, &c);
        assert_int_equal(rast_zbuffer_covered(zb), cf.winners);
        RastActive *a = rast_active_new(97, 83);
        rast_scanline_zbuffer(a, sl, &c);
        size_t n = 0;
        assert_non_null(rast_active_pixels(a, &n));
        assert_int_equal(n, cf.winners);
        assert_int_equal(rast_active_count(a), cf.winners);
        /* each row's active pixels: in x order, and each the full
         * z-buffer's winner there (id, depth and colour) */
        const size_t *off = rast_active_offsets(a);
        for (int y = 0; y < 83; y++) {
            size_t k;
            const RastActivePixel *row = rast_active_row(a, y, &k);
            assert_int_equal(k, off[y + 1] - off[y]);
            for (size_t i = 0; i < k; i++) {
                size_t at = (size_t)y * 97 + (size_t)row[i].x;
                assert_true(i == 0 || row[i].x > row[i - 1].x);
                assert_true(row[i].prim == zb->prim[at] &&
                            row[i].z == zb->depth[at] &&
                            row[i].rgba == zb->rgba[at]);
            }
        }
        rast_counters_add(&sum, &cs);
        assert_int_equal(sum.pixels, cf.pixels + cs.pixels);
        assert_int_equal(sum.zcompares, cf.zcompares + cs.zcompares);
        rast_active_free(a);
        rast_zbuffer_free(zb);
        rast_spanlist_free(sl);
        scene_mesh_free(m);
    }
}

/* Object-space parallelism: two processors z-buffer halves of the
 * polygons; merging their active pixels by depth gives the full image. */
static void test_subsets_merge(void **state)
{
    (void)state;
    const int W = 64, H = 48;
    SceneMesh *m = tu_random_tris(11, 300, 0.6);
    RastView v = rast_view_make(mat4_identity(), W, H);
    v.cull_back = FALSE;
    guint np = scene_mesh_n_polys(m);
    uint32_t *ids = g_new(uint32_t, np);
    for (guint i = 0; i < np; i++)
        ids[i] = i;
    RastZBuffer *merged = rast_zbuffer_new(W, H);
    RastCounters c = {0};
    for (int p = 0; p < 2; p++) {
        RastSpanList *sl = rast_spanlist_new(W, H);
        /* Interleaved subset: polygons p, p + 2, ... */
        guint k = 0;
        uint32_t *sub = g_new(uint32_t, np);
        for (guint i = (guint)p; i < np; i += 2)
            sub[k++] = ids[i];
        rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0,
                       &(RastSubset){sub, k}, rast_spanlist_sink(sl), &c);
        rast_spanlist_sort(sl);
        RastActive *a = rast_active_new(W, H);
        rast_scanline_zbuffer(a, sl, &c);
        for (int y = 0; y < H; y++) {
            size_t n;
            const RastActivePixel *row = rast_active_row(a, y, &n);
            for (size_t i = 0; i < n; i++) {
                size_t at = (size_t)y * W + row[i].x;
                if (rast_depth_wins(row[i].z, row[i].prim, merged->depth[at],
                                    merged->prim[at])) {
                    merged->depth[at] = row[i].z;
                    merged->prim[at] = row[i].prim;
                    merged->rgba[at] = row[i].rgba;
                }
            }
        }
        rast_active_free(a);
        rast_spanlist_free(sl);
        g_free(sub);
    }
    RastImage *f, *s, *g = rast_image_new(W, H);
    RastCounters cf = {0}, cs = {0};
    tu_render_both(&v, m, NULL, 0, &f, &s, &cf, &cs);
    rast_image_from_zbuffer(g, merged, (RastColor){0.1f, 0.2f, 0.3f});
    assert_true(rast_image_equal(f, g));
    rast_image_free(f);
    rast_image_free(s);
    rast_image_free(g);
    rast_zbuffer_free(merged);
    g_free(ids);
    scene_mesh_free(m);
}

/* Full z-buffer merging of two local buffers equals one buffer. */
static void test_zbuffer_merge(void **state)
{
    (void)state;
    SceneMesh *m = tu_random_tris(5, 200, 0.5);
    RastView v = rast_view_make(mat4_identity(), 40, 40);
    v.cull_back = FALSE;
    guint np = scene_mesh_n_polys(m);
    RastZBuffer *all = rast_zbuffer_new(40, 40), *a = rast_zbuffer_new(40, 40),
                *b = rast_zbuffer_new(40, 40);
    RastCounters c = {0};
    uint32_t lo[100], hi[100];
    for (guint i = 0; i < 100; i++) {
        lo[i] = i;
        hi[i] = np - 1 - i;
    }
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   rast_zbuffer_sink(all), &c);
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0,
                   &(RastSubset){lo, 100}, rast_zbuffer_sink(a), &c);
    rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0,
                   &(RastSubset){hi, 100}, rast_zbuffer_sink(b), &c);
    rast_zbuffer_merge(a, b, &c);
    assert_memory_equal(a->prim, all->prim, sizeof(uint32_t) * 1600);
    assert_memory_equal(a->rgba, all->rgba, sizeof(uint32_t) * 1600);
    rast_zbuffer_free(all);
    rast_zbuffer_free(a);
    rast_zbuffer_free(b);
    scene_mesh_free(m);
}

/* The reference order: (y, x_min, prim, x_max, z0), then insertion
 * order (c0[1] holds the insertion number). */
static int ref_cmp(const void *pa, const void *pb)
{
    const RastSpan *a = pa, *b = pb;
    int64_t ka[6] = {a->y, a->x0, a->prim, a->x1, 0, 0};
    int64_t kb[6] = {b->y, b->x0, b->prim, b->x1, 0, 0};
    for (int i = 0; i < 4; i++)
        if (ka[i] != kb[i])
            return ka[i] < kb[i] ? -1 : 1;
    if (a->z0 != b->z0)
        return a->z0 < b->z0 ? -1 : 1;
    return (a->c0[1] > b->c0[1]) - (a->c0[1] < b->c0[1]);
}

/* The radix sort of the span list against qsort on the full key, with
 * many ties on x_min (and fully equal keys, which keep insertion order),
 * on a wide image (x_min up to 3000) and across clear/re-sort. */
static void test_spanlist_sort_reference(void **state)
{
    (void)state;
    const int W = 3001, H = 37, N = 20000;
    SimRng r;
    sim_rng_init(&r, 42, 0);
    RastSpan *ref = g_new(RastSpan, N);
    RastSpanList *sl = rast_spanlist_new(W, H);
    for (int round = 0; round < 2; round++) {
        rast_spanlist_clear(sl);
        for (int i = 0; i < N; i++) {
            int x0 = round ? (int)sim_rng_below(&r, 8) * 375
                           : (int)sim_rng_below(&r, (uint64_t)W - 3);
            RastSpan s = flat_span((int)sim_rng_below(&r, H), x0,
                                   x0 + 1 + (int)sim_rng_below(&r, 3),
                                   0.25 * (double)sim_rng_below(&r, 3),
                                   (uint32_t)sim_rng_below(&r, 4), 0.0f);
            s.c0[1] = (float)i;
            ref[i] = s;
            rast_spanlist_add(sl, &s);
        }
        qsort(ref, N, sizeof *ref, ref_cmp);
        rast_spanlist_sort(sl);
        assert_true(rast_spanlist_sorted(sl));
        size_t k = 0;
        for (int y = 0; y < H; y++) {
            size_t n;
            const RastSpan *row = rast_spanlist_row(sl, y, &n);
            for (size_t i = 0; i < n; i++, k++) {
                assert_int_equal(row[i].y, y);
                assert_true(row[i].c0[1] == ref[k].c0[1]);
            }
        }
        assert_int_equal(k, N);
    }
    rast_spanlist_free(sl);
    g_free(ref);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_depth_and_ties),
        cmocka_unit_test(test_scanline_segments),
        cmocka_unit_test(test_full_equals_scanline),
        cmocka_unit_test(test_subsets_merge),
        cmocka_unit_test(test_zbuffer_merge),
        cmocka_unit_test(test_spanlist_sort_reference),
    };
    return cmocka_run_group_tests_name("zbuffer", tests, NULL, NULL);
}
