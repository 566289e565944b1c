/* test_prerender.c — a mesh rasterised once (sim/raster/prerender.h):
 * for random subsets and screen rectangles, the counts read from the
 * kept spans equal those of drawing the subset again through a sink that
 * clips spans to the rectangle (random triangles partly off screen, back
 * faces, and a 12-gon split into fan triangles and cut by the near
 * plane); a set builds each key once and keeps it, keys asked in any
 * order. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/raster/prerender.h"
#include "tests/raster/rast_testutil.h"

enum { W = 64, H = 48 };

/* The reference: spans and pixels inside a rectangle, as a sort-first
 * region's sink counts them. */
typedef struct {
    RastRect r;
    uint64_t spans, pixels;
} RectSink;

static void rect_span(void *ctx, const RastSpan *s, RastCounters *c)
{
    RectSink *k = ctx;
    int x0 = MAX(s->x0, k->r.x0), x1 = MIN(s->x1, k->r.x1);
    if (s->y < k->r.y0 || s->y >= k->r.y1 || x0 >= x1)
        return;
    k->spans++;
    k->pixels += (uint64_t)(x1 - x0);
    c->zcompares += (uint64_t)(x1 - x0);
}

/* Random triangles (some past the screen's sides, half back-facing), a
 * nonagon and a 12-gon reaching through the near plane. */
static SceneMesh *test_mesh(void)
{
    SceneMesh *m = tu_random_tris(7, 400, 0.5);
    uint32_t idx[12];
    /* a nonagon (RAST_POLY_MAX corners): one primitive of nine vertices */
    for (int k = 0; k < 9; k++) {
        double a = 2 * G_PI * k / 9;
        idx[k] = scene_mesh_add_vertex(
            m, vec3(-0.5 + 0.3 * cos(a), 0.4 + 0.3 * sin(a), 0.2));
    }
    scene_mesh_add_poly(m, idx, 9, scene_color(1, 1, 1), 0);
    for (int k = 0; k < 12; k++) {
        double a = 2 * G_PI * k / 12;
        idx[k] = scene_mesh_add_vertex(
            m, vec3(0.6 * cos(a), 0.6 * sin(a), -0.9 + 0.4 * cos(a)));
    }
    scene_mesh_add_poly(m, idx, 12, scene_color(1, 1, 1), 0);
    return m;
}

static RastView test_view(double zoom)
{
    RastView v = rast_view_make(mat4_scale(zoom, zoom, 1), W, H);
    v.cull_back = TRUE;
    return v;
}

/* Draws subset[0..n) (NULL: every polygon) again and compares with the
 * prerender's counts. */
static void compare(const RastPrerender *p, const RastView *v,
                    const SceneMesh *m, const uint32_t *subset, guint n,
                    RastRect r)
{
    uint32_t *all = NULL;
    if (!subset) {
        n = scene_mesh_n_polys(m);
        subset = all = g_new(uint32_t, n);
        for (guint i = 0; i < n; i++)
            all[i] = i;
    }
    RastCounters want = {0}, got = {0};
    RectSink k = {r, 0, 0};
    rast_draw_mesh(v, m, mat4_identity(), (SceneColor){1, 1, 1}, 0,
                   &(RastSubset){subset, n}, (RastSpanSink){rect_span, &k},
                   &want);
    uint64_t spans = 0, pixels = 0;
    rast_prerender_count(p, m, subset, n, r, &got, &spans, &pixels);
    assert_int_equal(spans, k.spans);
    assert_int_equal(pixels, k.pixels);
    assert_int_equal(got.verts, want.verts);
    assert_int_equal(got.prims, want.prims);
    assert_int_equal(got.spans, want.spans);
    assert_int_equal(got.pixels, want.pixels);
    assert_int_equal(got.zcompares, want.zcompares);
    g_free(all);
}

static void test_counts_equal_a_redraw(void **state)
{
    (void)state;
    SceneMesh *m = test_mesh();
    RastView v = test_view(1.3);
    RastPrerender *p = rast_prerender_new(&v, m);
    guint np = scene_mesh_n_polys(m);
    SimRng rng;
    sim_rng_init(&rng, 11, 0);
    uint32_t *subset = g_new(uint32_t, np);
    uint64_t seen = 0;
    for (int trial = 0; trial < 40; trial++) {
        guint n = 0;
        for (guint i = 0; i < np; i++)
            if (i == np - 1 || sim_rng_uniform(&rng) < 0.3)
                subset[n++] = i;
        int x0 = (int)(sim_rng_uniform(&rng) * W);
        int y0 = (int)(sim_rng_uniform(&rng) * H);
        RastRect r = {x0, y0, x0 + 1 + (int)(sim_rng_uniform(&rng) * W),
                      y0 + 1 + (int)(sim_rng_uniform(&rng) * H)};
        compare(p, &v, m, subset, n, r);
        uint64_t s = 0, px = 0;
        RastCounters c = {0};
        rast_prerender_count(p, m, subset, n, r, &c, &s, &px);
        seen += px;
    }
    compare(p, &v, m, NULL, 0, (RastRect){0, 0, W, H});
    assert_true(seen > 1000); /* the rectangles held pixels */
    RastCounters big = {0}; /* the 12-gon: 10 fan triangles, clipped */
    subset[0] = np - 1;
    rast_draw_mesh(&v, m, mat4_identity(), (SceneColor){1, 1, 1}, 0,
                   &(RastSubset){subset, 1},
                   (RastSpanSink){rect_span, &(RectSink){{0, 0, W, H}, 0, 0}},
                   &big);
    assert_true(big.prims == 10 && big.clipped > 0 && big.clipped < 10);
    assert_true(big.spans > 10);
    g_free(subset);
    rast_prerender_free(p);
    scene_mesh_free(m);
}

/* The kept spans belong to their view: another zoom counts otherwise,
 * so a comparison against a redraw can fail. */
static void test_view_matters(void **state)
{
    (void)state;
    SceneMesh *m = test_mesh();
    RastView a = test_view(1.3), b = test_view(0.7);
    RastPrerender *pa = rast_prerender_new(&a, m);
    RastPrerender *pb = rast_prerender_new(&b, m);
    uint32_t all[1] = {0};
    RastCounters c = {0};
    uint64_t sa = 0, pxa = 0, sb = 0, pxb = 0;
    RastRect r = {0, 0, W, H};
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        all[0] = i;
        rast_prerender_count(pa, m, all, 1, r, &c, &sa, &pxa);
        rast_prerender_count(pb, m, all, 1, r, &c, &sb, &pxb);
    }
    assert_true(pxa != pxb && sa > 0 && sb > 0);
    assert_true(rast_prerender_n_spans(pa) == sa);
    rast_prerender_free(pa);
    rast_prerender_free(pb);
    scene_mesh_free(m);
}

static void test_set_builds_once(void **state)
{
    (void)state;
    SceneMesh *m = test_mesh();
    RastView a = test_view(1.3), b = test_view(0.7);
    RastPrerenderSet *s = rast_prerender_set_new();
    const RastPrerender *p3 = rast_prerender_set_get(s, 3, &a, m);
    const RastPrerender *p0 = rast_prerender_set_get(s, 0, &b, m);
    assert_ptr_equal(rast_prerender_set_get(s, 3, &a, m), p3);
    assert_ptr_equal(rast_prerender_set_get(s, 0, &b, m), p0);
    assert_ptr_not_equal(p0, p3);
    compare(p3, &a, m, NULL, 0, (RastRect){5, 5, 40, 30});
    compare(p0, &b, m, NULL, 0, (RastRect){5, 5, 40, 30});
    rast_prerender_set_free(s);
    scene_mesh_free(m);
}

/* Keys asked in order 0, 1 (each equal to the set's length so far) are
 * built and kept like any other; a set of NULL frees nothing. */
static void test_set_keys_in_order(void **state)
{
    (void)state;
    SceneMesh *m = test_mesh();
    RastView a = test_view(1.3), b = test_view(0.7);
    RastPrerenderSet *s = rast_prerender_set_new();
    const RastPrerender *p0 = rast_prerender_set_get(s, 0, &a, m);
    const RastPrerender *p1 = rast_prerender_set_get(s, 1, &b, m);
    assert_non_null(p0);
    assert_non_null(p1);
    assert_ptr_not_equal(p0, p1);
    assert_ptr_equal(rast_prerender_set_get(s, 0, &a, m), p0);
    assert_ptr_equal(rast_prerender_set_get(s, 1, &b, m), p1);
    RastPrerender *direct = rast_prerender_new(&b, m);
    assert_int_equal(rast_prerender_n_spans(p1),
                     rast_prerender_n_spans(direct));
    rast_prerender_free(direct);
    compare(p0, &a, m, NULL, 0, (RastRect){0, 0, W, H});
    rast_prerender_set_free(s);
    rast_prerender_set_free(NULL);
    rast_prerender_free(NULL);
    scene_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts_equal_a_redraw),
        cmocka_unit_test(test_view_matters),
        cmocka_unit_test(test_set_builds_once),
        cmocka_unit_test(test_set_keys_in_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
