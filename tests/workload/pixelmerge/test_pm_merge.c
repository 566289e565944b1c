/* test_pm_merge.c — ZBUF-EXC, PAIR and AAPC on synthetic active pixels:
 * the merged image equals the serial z-buffer, and messages, work and the
 * concurrent volume follow seed 003 §3. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/core/rng.h"
#include "sim/workload/pixelmerge/pm_merge.h"

enum { W = 37, H = 29, NPOLY = 60 };

/* Random rectangles with random depths, polygon i to processor i % n;
 * local[p] is p's local z-buffer as an active pixel array; *serial the
 * serial z-buffer of all polygons (id order). */
static void synth(guint n, uint64_t seed, WlPmWpa **local, WlPmFrame **serial)
{
    SimRng r;
    sim_rng_init(&r, seed, 0);
    WlPmFrame **lf = g_new(WlPmFrame *, n);
    for (guint p = 0; p < n; p++)
        lf[p] = wl_pm_frame_new(W, H);
    *serial = wl_pm_frame_new(W, H);
    for (uint32_t id = 0; id < NPOLY; id++) {
        guint x0 = sim_rng_below(&r, W), y0 = sim_rng_below(&r, H);
        guint w = 1 + sim_rng_below(&r, 12), h = 1 + sim_rng_below(&r, 9);
        /* Few depth levels so that equal depths (ties) happen. */
        float z = (float)sim_rng_below(&r, 6);
        for (guint y = y0; y < MIN(H, y0 + h); y++)
            for (guint x = x0; x < MIN(W, x0 + w); x++) {
                WlPmPixel px = {(uint16_t)x, (uint16_t)y, z, id,
                                id * 2654435761u};
                wl_pm_frame_put(lf[id % n], &px);
                wl_pm_frame_put(*serial, &px);
            }
    }
    for (guint p = 0; p < n; p++) {
        local[p] = wl_pm_frame_to_wpa(lf[p]);
        wl_pm_frame_free(lf[p]);
    }
    g_free(lf);
}

static const WlPmFormat fmt = {8, 5, 2, 0, 0};

static WlPmPartition *partition_for(WlPmBalance b, WlPmWpa **local, guint n)
{
    uint64_t counts[H] = {0};
    for (guint p = 0; p < n; p++)
        wl_pm_wpa_add_row_counts(local[p], counts);
    return wl_pm_partition_new(b, n, counts, H);
}

static void check_owned_rows(const WlPmMerge *m, const WlPmPartition *part)
{
    for (guint p = 0; p < m->n_procs; p++)
        for (guint i = 0; i < wl_pm_wpa_len(m->held[p]); i++) {
            const WlPmPixel *px = &g_array_index(m->held[p]->px, WlPmPixel, i);
            if (m->scheme == WL_PM_ZBUF_EXC)
                continue; /* a full z-buffer holds empty locations */
            assert_int_not_equal(px->poly, WL_PM_EMPTY);
            assert_int_equal(part->owner[px->y], p);
        }
}

static void test_image_equals_serial(void **state)
{
    (void)state;
    for (guint n = 1; n <= 16; n *= 2)
        for (int s = 0; s < 3; s++)
            for (int b = 0; b < 3; b++) {
                WlPmWpa *local[16];
                WlPmFrame *serial;
                synth(n, 100 + n, local, &serial);
                WlPmPartition *part = partition_for(b, local, n);
                WlPmMerge *m = wl_pm_merge_run(s, local, n, part, &fmt);
                assert_int_equal(wl_pm_frame_diff(m->image, serial), -1);
                check_owned_rows(m, part);
                wl_pm_merge_free(m);
                wl_pm_partition_free(part);
                wl_pm_frame_free(serial);
                for (guint p = 0; p < n; p++)
                    wl_pm_wpa_free(local[p]);
            }
}

/* A wrong merge is caught: drop one processor's pixels. */
static void test_diff_detects_loss(void **state)
{
    (void)state;
    WlPmWpa *local[4];
    WlPmFrame *serial;
    synth(4, 5, local, &serial);
    WlPmWpa *saved = local[2];
    local[2] = wl_pm_wpa_new(W, H);
    wl_pm_wpa_finish(local[2]);
    WlPmPartition *part = partition_for(WL_PM_BAL_RS, local, 4);
    WlPmMerge *m = wl_pm_merge_run(WL_PM_AAPC, local, 4, part, &fmt);
    assert_int_not_equal(wl_pm_frame_diff(m->image, serial), -1);
    wl_pm_merge_free(m);
    wl_pm_partition_free(part);
    wl_pm_frame_free(serial);
    wl_pm_wpa_free(saved);
    for (guint p = 0; p < 4; p++)
        wl_pm_wpa_free(local[p]);
}

static void test_step_shapes(void **state)
{
    (void)state;
    WlPmWpa *local[8];
    WlPmFrame *serial;
    synth(8, 3, local, &serial);
    WlPmPartition *part = partition_for(WL_PM_BAL_HBP, local, 8);
    WlPmMerge *pair = wl_pm_merge_run(WL_PM_PAIR, local, 8, part, &fmt);
    WlPmMerge *aapc = wl_pm_merge_run(WL_PM_AAPC, local, 8, part, &fmt);
    assert_int_equal(pair->steps->len, 3);
    assert_int_equal(aapc->steps->len, 8); /* 7 exchanges + z-buffer */
    for (guint j = 1; j < 8; j++) {
        const WlPmStep *st = g_ptr_array_index(aapc->steps, j - 1);
        assert_true(st->exchange);
        for (guint p = 0; p < 8; p++)
            assert_int_equal(st->msg[p].dst, p ^ j);
    }
    /* AAPC sends each pixel at most once; PAIR forwards some. */
    uint64_t total = 0;
    for (guint p = 0; p < 8; p++)
        total += wl_pm_wpa_len(local[p]);
    uint64_t sent = 0;
    for (guint j = 0; j + 1 < aapc->steps->len; j++) {
        const WlPmStep *st = g_ptr_array_index(aapc->steps, j);
        for (guint p = 0; p < 8; p++)
            sent += st->msg[p].pixels;
    }
    assert_true(sent <= total);
    /* Merge ops of AAPC: every local pixel z-buffered exactly once. */
    uint64_t ops = 0;
    for (guint p = 0; p < 8; p++)
        ops += aapc->merge_ops[p];
    assert_int_equal(ops, total);
    wl_pm_merge_free(pair);
    wl_pm_merge_free(aapc);
    wl_pm_partition_free(part);
    wl_pm_frame_free(serial);
    for (guint p = 0; p < 8; p++)
        wl_pm_wpa_free(local[p]);
}

/* ZBUF-EXC moves N^2 (1 - 1/P) locations per processor; the concurrent
 * volume is the sum of halving messages N^2/2 + N^2/4 + ... */
static void test_zbuf_exc_volume(void **state)
{
    (void)state;
    WlPmWpa *local[4];
    WlPmFrame *serial;
    synth(4, 11, local, &serial);
    WlPmMerge *m = wl_pm_merge_run(WL_PM_ZBUF_EXC, local, 4, NULL, &fmt);
    /* H = 29 rows: stage 0 halves 29 -> 14 | 15, stage 1 14 -> 7 | 7 and
     * 15 -> 7 | 8; largest messages 15 rows then 8 rows. */
    assert_int_equal(m->concurrent_volume,
                     (15 + 8) * W * fmt.bytes_per_location);
    const WlPmStep *st = g_ptr_array_index(m->steps, 0);
    assert_int_equal(st->msg[0].bytes, 15 * W * fmt.bytes_per_location);
    assert_int_equal(st->msg[1].bytes, 14 * W * fmt.bytes_per_location);
    wl_pm_merge_free(m);
    wl_pm_frame_free(serial);
    for (guint p = 0; p < 4; p++)
        wl_pm_wpa_free(local[p]);
}

static void test_concurrent_volume(void **state)
{
    (void)state;
    GPtrArray *steps = g_ptr_array_new();
    WlPmMsg m1[2] = {{0, 1, 0, 100}, {1, 0, 0, 40}};
    WlPmMsg m2[2] = {{0, 1, 0, 10}, {1, 0, 0, 70}};
    WlPmStep s1 = {TRUE, m1, 2, NULL}, s2 = {TRUE, m2, 2, NULL};
    WlPmStep s3 = {FALSE, m1, 2, NULL};
    g_ptr_array_add(steps, &s1);
    g_ptr_array_add(steps, &s2);
    g_ptr_array_add(steps, &s3);
    assert_int_equal(wl_pm_concurrent_volume(steps, 2), 170);
    g_ptr_array_free(steps, TRUE);
}

/* The merge and the partition free functions take NULL. */
static void test_free_null(void **state)
{
    (void)state;
    wl_pm_merge_free(NULL);
    wl_pm_partition_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_null),
        cmocka_unit_test(test_image_equals_serial),
        cmocka_unit_test(test_diff_detects_loss),
        cmocka_unit_test(test_step_shapes),
        cmocka_unit_test(test_zbuf_exc_volume),
        cmocka_unit_test(test_concurrent_volume),
    };
    return cmocka_run_group_tests_name("pm_merge", tests, NULL, NULL);
}
