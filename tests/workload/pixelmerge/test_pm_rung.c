/* test_pm_rung.c — the image fidelity ladder (pm_rung.h, pm_runs.h,
 * pm_foot.h): the runs rung sends the pixel rung's messages exactly
 * (every scheme, process counts 1 .. 64, every optimisation, processor
 * and shuffled order, random and footprint images), and a one-pixel
 * change shows the comparison can fail; the counts rung is exact on
 * disjoint solid rectangles and off on overlapping ellipses (measured,
 * within 25 % in bytes); the O(1) box count against a brute one; and
 * 1,024 processes compositing real footprint pixels (binary swap and
 * radix-k, z and over) give the serial image. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pixelmerge/pm_foot.h"
#include "sim/workload/pixelmerge/pm_runs.h"

enum { W = 24, H = 20 };

static const guint counts[] = {1, 2, 3, 5, 8, 12, 16, 64};
static const WlPmFormat fmt = {8, 4, 2, 4, 8};
static const WlPmScheme schemes[] = {WL_PM_BINARY_SWAP, WL_PM_DIRECT_SEND,
                                     WL_PM_RADIX_K, WL_PM_TWO_THREE_SWAP};

static WlPmWpa **random_locals(guint n, guint w, guint h, guint32 seed)
{
    GRand *r = g_rand_new_with_seed(seed);
    WlPmWpa **l = g_new(WlPmWpa *, n);
    for (guint p = 0; p < n; p++) {
        l[p] = wl_pm_wpa_new(w, h);
        guint x0 = g_rand_int_range(r, 0, w / 2),
              y0 = g_rand_int_range(r, 0, h / 2);
        for (guint y = y0; y < h; y++)
            for (guint x = x0; x < w; x++) {
                if (g_rand_int_range(r, 0, 3))
                    continue;
                WlPmPixel px = {(uint16_t)x, (uint16_t)y, p, p, 0};
                wl_pm_wpa_push(l[p], &px);
            }
        wl_pm_wpa_finish(l[p]);
    }
    g_rand_free(r);
    return l;
}

static WlPmWpa **foot_locals(guint n, guint w, guint h)
{
    WlPmWpa **l = g_new(WlPmWpa *, n);
    for (guint p = 0; p < n; p++)
        l[p] = wl_pm_foot_pixels(p, n, w, h);
    return l;
}

static void free_locals(WlPmWpa **l, guint n)
{
    for (guint p = 0; p < n; p++)
        wl_pm_wpa_free(l[p]);
    g_free(l);
}

static WlPmRungImage **to_rung(WlPmRung rung, WlPmWpa *const *l, guint n)
{
    WlPmRungImage **im = g_new(WlPmRungImage *, n);
    for (guint p = 0; p < n; p++)
        im[p] = wl_pm_rung_from_wpa(rung, l[p]);
    return im;
}

static void free_images(WlPmRungImage **im, guint n)
{
    for (guint p = 0; p < n; p++)
        wl_pm_rung_image_free(im[p]);
    g_free(im);
}

/* The first step and message where a and b differ: -1 when the same. */
static int steps_differ(const WlPmMerge *a, const WlPmMerge *b)
{
    if (a->steps->len != b->steps->len)
        return 0;
    for (guint s = 0; s < a->steps->len; s++) {
        const WlPmStep *x = g_ptr_array_index(a->steps, s);
        const WlPmStep *y = g_ptr_array_index(b->steps, s);
        if (x->n_msgs != y->n_msgs)
            return (int)s;
        for (guint i = 0; i < x->n_msgs; i++)
            if (x->msg[i].src != y->msg[i].src ||
                x->msg[i].dst != y->msg[i].dst ||
                x->msg[i].pixels != y->msg[i].pixels ||
                x->msg[i].bytes != y->msg[i].bytes)
                return (int)s;
        for (guint p = 0; p < a->n_procs; p++)
            if (x->work[p].pack != y->work[p].pack ||
                x->work[p].compare != y->work[p].compare)
                return (int)s;
    }
    return -1;
}

static guint *shuffled(guint n, guint32 seed)
{
    guint *o = g_new(guint, n);
    for (guint i = 0; i < n; i++)
        o[i] = i;
    GRand *r = g_rand_new_with_seed(seed);
    for (guint i = n; i > 1; i--) {
        guint j = g_rand_int_range(r, 0, i), t = o[i - 1];
        o[i - 1] = o[j], o[j] = t;
    }
    g_rand_free(r);
    return o;
}

/* Runs rung against pixel rung for one image set, every scheme and
 * optimisation, both orders. */
static void check_runs_exact(WlPmWpa **l, guint n)
{
    WlPmRungImage **im = to_rung(WL_PM_RUNG_RUNS, l, n);
    guint *order = shuffled(n, n);
    for (guint s = 0; s < G_N_ELEMENTS(schemes); s++)
        for (guint opt = 0; opt < 8; opt++) {
            WlPmCompose c = {.bounding_rect = opt & 1,
                             .rle = (opt >> 1) & 1,
                             .opacity = 1,
                             .order = opt & 4 ? order : NULL};
            WlPmComposite *px = wl_pm_composite_run(schemes[s], &c, l, n, &fmt);
            WlPmMerge *ru = wl_pm_rung_run(schemes[s], &c, im, n, &fmt, NULL);
            if (steps_differ(px->merge, ru) >= 0)
                fail_msg("%s, %u processes, option %u: runs differ",
                         wl_pm_scheme_names[schemes[s]], n, opt);
            assert_int_equal(px->merge->total_bytes, ru->total_bytes);
            wl_pm_rung_merge_free(ru);
            wl_pm_composite_free(px);
        }
    g_free(order);
    free_images(im, n);
}

static void test_runs_equal_pixels(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(counts); i++) {
        guint n = counts[i];
        WlPmWpa **l = random_locals(n, W, H, 7 + n);
        check_runs_exact(l, n);
        free_locals(l, n);
        l = foot_locals(n, 40, 36);
        check_runs_exact(l, n);
        free_locals(l, n);
    }
}

/* One pixel fewer in one image: the runs rung's messages differ. */
static void test_runs_check_can_fail(void **st)
{
    (void)st;
    guint n = 8;
    WlPmWpa **l = random_locals(n, W, H, 3);
    WlPmRungImage **im = to_rung(WL_PM_RUNG_RUNS, l, n);
    WlPmRun *r = &g_array_index(im[5]->el, WlPmRun, 0);
    r->s++;
    WlPmCompose c = {.rle = TRUE, .opacity = 1};
    WlPmComposite *px = wl_pm_composite_run(WL_PM_BINARY_SWAP, &c, l, n, &fmt);
    WlPmMerge *ru = wl_pm_rung_run(WL_PM_BINARY_SWAP, &c, im, n, &fmt, NULL);
    assert_true(steps_differ(px->merge, ru) >= 0);
    wl_pm_rung_merge_free(ru);
    wl_pm_composite_free(px);
    free_images(im, n);
    free_locals(l, n);
}

/* Disjoint solid rectangles: the counts rung is exact. */
static void test_counts_exact_on_solid_rects(void **st)
{
    (void)st;
    guint n = 12, w = 48, h = 40;
    WlPmWpa **l = g_new(WlPmWpa *, n);
    for (guint p = 0; p < n; p++) {
        l[p] = wl_pm_wpa_new(w, h);
        guint x0 = p % 4 * 12 + 1, y0 = p / 4 * 13 + 2;
        for (guint y = y0; y < y0 + 9; y++)
            for (guint x = x0; x < x0 + 7 + p % 3; x++) {
                WlPmPixel px = {(uint16_t)x, (uint16_t)y, p, p, 0};
                wl_pm_wpa_push(l[p], &px);
            }
        wl_pm_wpa_finish(l[p]);
    }
    WlPmRungImage **im = to_rung(WL_PM_RUNG_COUNTS, l, n);
    for (guint s = 0; s < G_N_ELEMENTS(schemes); s++)
        for (guint opt = 0; opt < 3; opt++) {
            WlPmCompose c = {
                .bounding_rect = opt >= 1, .rle = opt == 2, .opacity = 1};
            WlPmComposite *px = wl_pm_composite_run(schemes[s], &c, l, n, &fmt);
            WlPmMerge *co = wl_pm_rung_run(schemes[s], &c, im, n, &fmt, NULL);
            assert_int_equal(px->merge->total_bytes, co->total_bytes);
            assert_int_equal(steps_differ(px->merge, co), -1);
            wl_pm_rung_merge_free(co);
            wl_pm_composite_free(px);
        }
    free_images(im, n);
    free_locals(l, n);
}

/* Overlapping ellipses: counts differ from pixels, within 25 % in
 * bytes with bounding rectangles and RLE. */
static void test_counts_error_on_footprints(void **st)
{
    (void)st;
    guint n = 64, w = 256, h = 256;
    WlPmWpa **l = foot_locals(n, w, h);
    WlPmRungImage **im = g_new(WlPmRungImage *, n);
    for (guint p = 0; p < n; p++)
        im[p] = wl_pm_foot_image(WL_PM_RUNG_COUNTS, p, n, w, h);
    WlPmCompose c = {.bounding_rect = TRUE, .rle = TRUE, .opacity = 1};
    WlPmComposite *px = wl_pm_composite_run(WL_PM_RADIX_K, &c, l, n, &fmt);
    WlPmMerge *co = wl_pm_rung_run(WL_PM_RADIX_K, &c, im, n, &fmt, NULL);
    double err = (double)co->total_bytes / px->merge->total_bytes - 1;
    assert_true(steps_differ(px->merge, co) >= 0);
    assert_true(err > -0.25 && err < 0.25);
    wl_pm_rung_merge_free(co);
    wl_pm_composite_free(px);
    free_images(im, n);
    free_locals(l, n);
}

static void test_box_locations(void **st)
{
    (void)st;
    GRand *r = g_rand_new_with_seed(11);
    for (guint t = 0; t < 2000; t++) {
        guint w = g_rand_int_range(r, 1, 30), h = g_rand_int_range(r, 1, 30);
        guint box[4] = {g_rand_int_range(r, 0, w), 0, g_rand_int_range(r, 0, h),
                        0};
        box[1] = g_rand_int_range(r, box[0], w);
        box[3] = g_rand_int_range(r, box[2], h);
        uint64_t a = g_rand_int_range(r, 0, w * h + 1);
        uint64_t b = g_rand_int_range(r, a, w * h + 1), n = 0;
        for (uint64_t i = a; i < b; i++) {
            guint x = i % w, y = i / w;
            n += x >= box[0] && x <= box[1] && y >= box[2] && y <= box[3];
        }
        assert_int_equal(wl_pm_box_locations(w, a, b, box), n);
    }
    g_rand_free(r);
}

/* 1,024 processes, real pixels: the composited image is the serial one
 * (z: the z-buffer; over: the front-to-back blend). */
static void test_1024_real_pixels(void **st)
{
    (void)st;
    guint n = 1024, w = 320, h = 320;
    WlPmWpa **l = foot_locals(n, w, h);
    WlPmFrame *ref = wl_pm_frame_new(w, h);
    for (guint p = 0; p < n; p++)
        wl_pm_frame_put_wpa(ref, l[p]);
    double *blend = wl_pm_over_serial(l, n, NULL, 0.5);
    const WlPmScheme s2[] = {WL_PM_BINARY_SWAP, WL_PM_RADIX_K};
    for (guint s = 0; s < 2; s++) {
        WlPmCompose c = {.bounding_rect = TRUE, .rle = TRUE, .opacity = 1};
        WlPmComposite *px = wl_pm_composite_run(s2[s], &c, l, n, &fmt);
        assert_int_equal(wl_pm_frame_diff(ref, px->merge->image), -1);
        wl_pm_composite_free(px);
        c.op = WL_PM_OP_OVER, c.opacity = 0.5;
        px = wl_pm_composite_run(s2[s], &c, l, n, &fmt);
        assert_int_equal(wl_pm_over_diff(blend, px->rgba, (gsize)w * h * 4),
                         -1);
        wl_pm_composite_free(px);
    }
    assert_true(wl_pm_frame_count(ref) > w * h / 4);
    g_free(blend);
    wl_pm_frame_free(ref);
    free_locals(l, n);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_runs_equal_pixels),
        cmocka_unit_test(test_runs_check_can_fail),
        cmocka_unit_test(test_counts_exact_on_solid_rects),
        cmocka_unit_test(test_counts_error_on_footprints),
        cmocka_unit_test(test_box_locations),
        cmocka_unit_test(test_1024_real_pixels),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
