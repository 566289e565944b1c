/* test_pm_blocks.c — the block decomposition (pm_blocks.h): the grid's
 * factorisations and its half-open cells; the visibility order from the
 * view is front to back along every pixel's ray for perspective and
 * orthographic cameras outside and inside the volume (the check shown
 * failing on the reversed order); every pixel whose ray meets a block
 * lies in its footprint rectangle; the block images composited by
 * binary swap, direct send, radix-k and 2-3 swap, with and without
 * bounding rectangles and RLE, at 1, 2, 3, 5, 8, 12, 16 and 64
 * processes equal the serial z-buffer (z) and the serial front-to-back
 * blend of the blocks in view order (over; in the reversed order the
 * blend differs); the pixels' own opacities are the ones blended. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pixelmerge/pm_blocks.h"
#include "sim/workload/pixelmerge/pm_composite.h"

enum { W = 40, H = 32 };

static const Vec3 lo = {-1, -1, -1}, hi = {1, 1, 1};
static const guint counts[] = {1, 2, 3, 5, 8, 12, 16, 64};
static const WlPmFormat fmt = {8, 4, 2, 4, 8};

static SceneCamera camera(gboolean persp, Vec3 eye)
{
    SceneCamera c = scene_camera_default();
    c.eye = eye;
    c.target = vec3(0.1, -0.05, 0.02);
    if (!persp) {
        c.proj = SCENE_ORTHOGRAPHIC;
        c.height = 3.6;
    }
    return c;
}

static void test_grid_shapes(void **st)
{
    (void)st;
    static const guint want[][4] = {
        {1, 1, 1, 1},  {2, 2, 1, 1}, {8, 2, 2, 2},  {12, 3, 2, 2},
        {64, 4, 4, 4}, {5, 5, 1, 1}, {16, 4, 2, 2}, {32768, 32, 32, 32}};
    for (guint i = 0; i < G_N_ELEMENTS(want); i++) {
        WlPmGrid g;
        wl_pm_grid_init(&g, want[i][0], lo, hi);
        for (int a = 0; a < 3; a++)
            assert_int_equal(g.dims[a], want[i][a + 1]);
        assert_int_equal(wl_pm_grid_count(&g), want[i][0]);
    }
}

/* Every point of the volume is in the box of the block it is given,
 * half-open, including points on the boundaries. */
static void test_cells_half_open(void **st)
{
    (void)st;
    WlPmGrid g;
    wl_pm_grid_init(&g, 12, lo, hi);
    GRand *r = g_rand_new_with_seed(5);
    for (int i = 0; i < 20000; i++) {
        Vec3 x =
            vec3(g_rand_double_range(r, -1, 1), g_rand_double_range(r, -1, 1),
                 g_rand_double_range(r, -1, 1));
        if (i % 4 == 0) /* on a boundary of axis x */
            x.x = -1 + 2.0 * g_rand_int_range(r, 0, 3) / 3;
        guint p = wl_pm_grid_block_of(&g, x);
        Vec3 a, b;
        wl_pm_grid_block(&g, p, &a, &b);
        assert_true(x.x >= a.x && x.x < b.x && x.y >= a.y && x.y < b.y &&
                    x.z >= a.z && x.z < b.z);
    }
    g_rand_free(r);
    assert_false(wl_pm_grid_inside(&g, vec3(1, 0, 0)));
    assert_true(wl_pm_grid_inside(&g, vec3(-1, -1, -1)));
}

/* How many rays meet the blocks out of `order` (a rank per block):
 * walking each pixel's ray in small steps, a block met after another must
 * come later in the order. */
static guint order_faults(const WlPmGrid *g, const SceneCamera *c,
                          const guint *order)
{
    guint n = wl_pm_grid_count(g), faults = 0;
    guint *rank = g_new(guint, n);
    for (guint i = 0; i < n; i++)
        rank[order[i]] = i;
    WlPmRays r;
    wl_pm_rays_init(&r, c, 16, 12);
    for (guint y = 0; y < 12; y++)
        for (guint x = 0; x < 16; x++) {
            Vec3 o, d;
            wl_pm_ray(&r, x, y, &o, &d);
            gint64 last = -1;
            gboolean bad = FALSE;
            for (double t = 0; t < 12; t += 0.004) {
                Vec3 q = vec3_add(o, vec3_scale(d, t));
                if (!wl_pm_grid_inside(g, q))
                    continue;
                guint k = rank[wl_pm_grid_block_of(g, q)];
                bad |= (gint64)k < last;
                last = k;
            }
            faults += bad;
        }
    g_free(rank);
    return faults;
}

static void test_order_front_to_back(void **st)
{
    (void)st;
    const Vec3 eyes[] = {{3.1, 2.2, 4.5},
                         {-4, 0.3, -2},
                         {0.2, 0.1, 4},
                         {0.3, -0.4, 0.2},
                         {0, 5, 0.01}};
    guint reversed_faults = 0;
    for (guint e = 0; e < G_N_ELEMENTS(eyes); e++)
        for (int persp = 0; persp < 2; persp++)
            for (guint i = 0; i < G_N_ELEMENTS(counts); i++) {
                if (!persp && e == 3)
                    continue; /* an orthographic eye inside the volume */
                WlPmGrid g;
                wl_pm_grid_init(&g, counts[i], lo, hi);
                SceneCamera c = camera(persp, eyes[e]);
                guint order[64], rev[64], n = counts[i];
                wl_pm_grid_order(&g, &c, order);
                assert_true(wl_pm_order_ok(order, n));
                if (order_faults(&g, &c, order))
                    fail_msg("eye %u persp %d P=%u: order not front to back", e,
                             persp, n);
                for (guint k = 0; k < n; k++)
                    rev[k] = order[n - 1 - k];
                reversed_faults += order_faults(&g, &c, rev);
            }
    assert_true(reversed_faults > 100);
}

/* Every pixel whose ray meets block p is inside its rectangle; the
 * image's pixels are exactly those. */
static void test_footprints(void **st)
{
    (void)st;
    for (int persp = 0; persp < 2; persp++) {
        SceneCamera c = camera(persp, vec3(2.5, 1.5, 3.5));
        WlPmRays r;
        wl_pm_rays_init(&r, &c, W, H);
        WlPmGrid g;
        wl_pm_grid_init(&g, 12, lo, hi);
        for (guint p = 0; p < 12; p++) {
            WlPmRect rc;
            gboolean on = wl_pm_block_rect(&g, &r, p, &rc);
            Vec3 a, b;
            wl_pm_grid_block(&g, p, &a, &b);
            guint hits = 0;
            for (guint y = 0; y < H; y++)
                for (guint x = 0; x < W; x++) {
                    Vec3 o, d;
                    double t0, t1;
                    wl_pm_ray(&r, x, y, &o, &d);
                    if (!wl_pm_ray_box(o, d, a, b, &t0, &t1))
                        continue;
                    hits++;
                    assert_true(on && x >= rc.x0 && x < rc.x1 && y >= rc.y0 &&
                                y < rc.y1);
                }
            WlPmCounts k;
            WlPmWpa *w = wl_pm_block_image(&g, &r, p, 1.0, &k);
            assert_int_equal(wl_pm_wpa_len(w), hits);
            assert_int_equal(k.rc.pixels, hits);
            assert_true(hits <= (on ? (rc.x1 - rc.x0) * (rc.y1 - rc.y0) : 0));
            wl_pm_wpa_free(w);
        }
    }
}

typedef struct {
    WlPmWpa **local;
    guint order[64], n;
} Blocks;

static Blocks blocks(guint n, double density)
{
    Blocks b = {g_new(WlPmWpa *, n), {0}, n};
    SceneCamera c = camera(TRUE, vec3(2.5, 1.8, 3.2));
    WlPmRays r;
    wl_pm_rays_init(&r, &c, W, H);
    WlPmGrid g;
    wl_pm_grid_init(&g, n, lo, hi);
    wl_pm_grid_order(&g, &c, b.order);
    for (guint p = 0; p < n; p++) {
        WlPmCounts k;
        b.local[p] = wl_pm_block_image(&g, &r, p, density, &k);
    }
    return b;
}

static void blocks_free(Blocks *b)
{
    for (guint p = 0; p < b->n; p++)
        wl_pm_wpa_free(b->local[p]);
    g_free(b->local);
}

static void test_composites_equal_serial(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(counts); i++) {
        guint n = counts[i];
        Blocks b = blocks(n, 1.5);
        WlPmFrame *ref = wl_pm_frame_new(W, H);
        for (guint p = 0; p < n; p++)
            wl_pm_frame_put_wpa(ref, b.local[p]);
        double *blend = wl_pm_over_serial(b.local, n, b.order, 0.5);
        for (guint sch = WL_PM_BINARY_SWAP; sch <= WL_PM_TWO_THREE_SWAP; sch++)
            for (int opt = 0; opt < 4; opt++)
                for (int op = 0; op < 2; op++) {
                    WlPmCompose c = {.bounding_rect = opt & 1,
                                     .rle = (opt & 2) != 0,
                                     .op = (WlPmOperator)op,
                                     .opacity = 0.5,
                                     .order = b.order};
                    WlPmComposite *r = wl_pm_composite_run((WlPmScheme)sch, &c,
                                                           b.local, n, &fmt);
                    gboolean ok =
                        op == WL_PM_OP_Z
                            ? wl_pm_frame_diff(ref, r->merge->image) < 0
                            : wl_pm_over_diff(blend, r->rgba,
                                              (gsize)W * H * 4) < 0;
                    if (!ok)
                        fail_msg("%s P=%u opt=%d op=%d: image differs",
                                 wl_pm_scheme_names[sch], n, opt, op);
                    wl_pm_composite_free(r);
                }
        if (n == 8) { /* the blend depends on the order */
            guint rev[8];
            for (guint k = 0; k < 8; k++)
                rev[k] = b.order[7 - k];
            double *back = wl_pm_over_serial(b.local, n, rev, 0.5);
            assert_true(wl_pm_over_diff(blend, back, (gsize)W * H * 4) >= 0);
            g_free(back);
        }
        g_free(blend);
        wl_pm_frame_free(ref);
        blocks_free(&b);
    }
}

/* A pixel's own opacity is what over blends: one block alone gives back
 * its rgba, 1 - exp(-density x length), not the compose opacity. */
static void test_own_opacity(void **st)
{
    (void)st;
    Blocks b = blocks(1, 0.7);
    WlPmCompose c = {.op = WL_PM_OP_OVER, .opacity = 0.5};
    WlPmComposite *r = wl_pm_composite_run(WL_PM_RADIX_K, &c, b.local, 1, &fmt);
    const WlPmWpa *l = b.local[0];
    assert_true(l->rgba && wl_pm_wpa_len(l) > 100);
    gboolean thick = FALSE;
    for (guint i = 0; i < wl_pm_wpa_len(l); i++) {
        const WlPmPixel *px = &g_array_index(l->px, WlPmPixel, i);
        const double *v = &g_array_index(l->rgba, double, 4 * i);
        const double *got = &r->rgba[((gsize)px->y * W + px->x) * 4];
        for (int j = 0; j < 4; j++)
            assert_true(fabs(got[j] - v[j]) < 1e-12);
        assert_true(v[3] > 0 && v[3] < 1 - exp(-0.7 * 2 * sqrt(3.0)) + 1e-9);
        thick |= v[3] > 0.6;
    }
    assert_true(thick); /* some rays cross more than a unit of the cube */
    wl_pm_composite_free(r);
    blocks_free(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grid_shapes),
        cmocka_unit_test(test_cells_half_open),
        cmocka_unit_test(test_order_front_to_back),
        cmocka_unit_test(test_footprints),
        cmocka_unit_test(test_composites_equal_serial),
        cmocka_unit_test(test_own_opacity),
    };
    return cmocka_run_group_tests_name("pm_blocks", tests, NULL, NULL);
}
