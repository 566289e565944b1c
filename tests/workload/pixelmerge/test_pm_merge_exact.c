/* test_pm_merge_exact.c — the merge schemes (pm_merge.h) on pixels placed
 * by hand, every recorded number worked out by hand (issue 21): each
 * step's messages (destination, pixels, bytes = pixels x bytes_per_pixel
 * + scanlines x bytes_per_scanline, or locations x bytes_per_location)
 * and work (pack, scatter, compare, gather), merge_ops, total bytes and
 * messages, the concurrent volume, what each processor holds and the
 * merged image. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pixelmerge/pm_merge.h"

enum { W = 4, H = 5 };

static const WlPmFormat fmt = {8, 5, 2, 0, 0};

static void put(WlPmWpa *w, guint x, guint y, double z, uint32_t id)
{
    WlPmPixel p = {(uint16_t)x, (uint16_t)y, z, id, 100 + id};
    wl_pm_wpa_push(w, &p);
}

/* Processor 0: row 0 x0 x1 (id 0, z 1), row 1 x0 (id 1, z 2), row 3 x2 x3
 * (id 2, z 5 and 1).  Processor 1: row 0 x0 (id 3, z 0.5), row 1 x0 x3
 * (id 4, z 3 and 1), row 2 x1 (id 5, z 1). */
static void two_locals(WlPmWpa **l)
{
    l[0] = wl_pm_wpa_new(W, H);
    put(l[0], 0, 0, 1, 0);
    put(l[0], 1, 0, 1, 0);
    put(l[0], 0, 1, 2, 1);
    put(l[0], 2, 3, 5, 2);
    put(l[0], 3, 3, 1, 2);
    wl_pm_wpa_finish(l[0]);
    l[1] = wl_pm_wpa_new(W, H);
    put(l[1], 0, 0, 0.5, 3);
    put(l[1], 0, 1, 3, 4);
    put(l[1], 3, 1, 1, 4);
    put(l[1], 1, 2, 1, 5);
    wl_pm_wpa_finish(l[1]);
}

static void free_locals(WlPmWpa **l, guint n)
{
    for (guint p = 0; p < n; p++)
        wl_pm_wpa_free(l[p]);
}

static void expect_msg(const WlPmMerge *m, guint s, guint p, guint dst,
                       uint64_t pixels, uint64_t bytes)
{
    const WlPmStep *st = g_ptr_array_index(m->steps, s);
    assert_true(st->exchange);
    assert_int_equal(st->msg[p].dst, dst);
    assert_int_equal(st->msg[p].pixels, pixels);
    assert_int_equal(st->msg[p].bytes, bytes);
}

static void expect_work(const WlPmMerge *m, guint s, guint p, uint64_t pack,
                        uint64_t scatter, uint64_t compare, uint64_t gather)
{
    const WlPmStep *st = g_ptr_array_index(m->steps, s);
    assert_int_equal(st->work[p].pack, pack);
    assert_int_equal(st->work[p].scatter, scatter);
    assert_int_equal(st->work[p].compare, compare);
    assert_int_equal(st->work[p].gather, gather);
}

static void expect_totals(const WlPmMerge *m, guint steps, uint64_t ops0,
                          uint64_t ops1, uint64_t bytes, uint64_t msgs,
                          uint64_t volume)
{
    assert_int_equal(m->steps->len, steps);
    assert_int_equal(m->merge_ops[0], ops0);
    assert_int_equal(m->merge_ops[1], ops1);
    assert_int_equal(m->total_bytes, bytes);
    assert_int_equal(m->total_msgs, msgs);
    assert_int_equal(m->concurrent_volume, volume);
}

/* The merged image: (0,0) id 3 (z 0.5 beats 1), (1,0) id 0, (0,1) id 1
 * (z 2 beats 3), (3,1) id 4, (1,2) id 5, (2,3) and (3,3) id 2. */
static void expect_image(const WlPmMerge *m)
{
    static const struct {
        guint x, y;
        uint32_t id;
    } want[] = {{0, 0, 3}, {1, 0, 0}, {0, 1, 1}, {3, 1, 4},
                {1, 2, 5}, {2, 3, 2}, {3, 3, 2}};
    assert_int_equal(wl_pm_frame_count(m->image), G_N_ELEMENTS(want));
    for (guint i = 0; i < G_N_ELEMENTS(want); i++) {
        const WlPmPixel *p = &m->image->px[want[i].y * W + want[i].x];
        assert_int_equal(p->poly, want[i].id);
        assert_int_equal(p->color, 100 + want[i].id);
    }
}

/* Owners 0 1 0 1 1 (not banded).  Processor 0 sends rows 1, 3, 4 (3
 * pixels, 3 scanlines: 30 B), keeps rows 0, 2 (2); processor 1 sends rows
 * 0, 2 (2 pixels, 2 scanlines: 20 B), keeps 2.  Holding then: 0 merges
 * 2 + 2 into 3, 1 merges 2 + 3 into 4. */
static const guint owner_mixed[H] = {0, 1, 0, 1, 1};

static void test_pair_two(void **state)
{
    (void)state;
    WlPmWpa *l[2];
    two_locals(l);
    WlPmPartition part = {2, H, (guint *)owner_mixed, FALSE};
    WlPmMerge *m = wl_pm_merge_run(WL_PM_PAIR, l, 2, &part, &fmt);
    expect_msg(m, 0, 0, 1, 3, 30);
    expect_msg(m, 0, 1, 0, 2, 20);
    expect_work(m, 0, 0, 3, 2, 2, 3);
    expect_work(m, 0, 1, 2, 2, 3, 4);
    expect_totals(m, 1, 4, 5, 50, 2, 30);
    assert_int_equal(wl_pm_wpa_len(m->held[0]), 3);
    assert_int_equal(wl_pm_wpa_len(m->held[1]), 4);
    /* row 0 of processor 0: its own x0 replaced in place, then x1 */
    const WlPmPixel *r0 = wl_pm_wpa_row(m->held[0], 0);
    assert_int_equal(wl_pm_wpa_row_len(m->held[0], 0), 2);
    assert_int_equal(r0[0].poly, 3);
    assert_int_equal(r0[1].poly, 0);
    assert_int_equal(wl_pm_wpa_row_len(m->held[1], 3), 2);
    expect_image(m);
    wl_pm_merge_free(m);
    free_locals(l, 2);
}

/* AAPC on the same pixels: one exchange (sizes as PAIR's, the
 * scanline count being the receiver's rows: 3 for 1, 2 for 0), then the
 * z-buffer step: own pixels scattered, received ones compared. */
static void test_aapc_two(void **state)
{
    (void)state;
    WlPmWpa *l[2];
    two_locals(l);
    WlPmPartition part = {2, H, (guint *)owner_mixed, FALSE};
    WlPmMerge *m = wl_pm_merge_run(WL_PM_AAPC, l, 2, &part, &fmt);
    expect_msg(m, 0, 0, 1, 3, 30);
    expect_msg(m, 0, 1, 0, 2, 20);
    expect_work(m, 0, 0, 3, 0, 0, 0);
    expect_work(m, 0, 1, 2, 0, 0, 0);
    const WlPmStep *z = g_ptr_array_index(m->steps, 1);
    assert_false(z->exchange);
    expect_work(m, 1, 0, 0, 2, 2, 0);
    expect_work(m, 1, 1, 0, 2, 3, 0);
    expect_totals(m, 2, 4, 5, 50, 2, 30);
    assert_int_equal(wl_pm_wpa_len(m->held[0]), 3);
    assert_int_equal(wl_pm_wpa_len(m->held[1]), 4);
    expect_image(m);
    wl_pm_merge_free(m);
    free_locals(l, 2);
}

/* Banded owners 0 0 1 1 1: nothing to pack.  Processor 0 sends rows 2-4
 * (2 pixels, 3 scanlines: 22 B), processor 1 rows 0-1 (3 pixels, 2
 * scanlines: 28 B), in both schemes. */
static void test_banded(void **state)
{
    (void)state;
    static const guint owner[H] = {0, 0, 1, 1, 1};
    WlPmWpa *l[2];
    two_locals(l);
    WlPmPartition part = {2, H, (guint *)owner, TRUE};
    for (int s = WL_PM_PAIR; s <= WL_PM_AAPC; s++) {
        WlPmMerge *m = wl_pm_merge_run((WlPmScheme)s, l, 2, &part, &fmt);
        expect_msg(m, 0, 0, 1, 2, 22);
        expect_msg(m, 0, 1, 0, 3, 28);
        const WlPmStep *st = g_ptr_array_index(m->steps, 0);
        assert_int_equal(st->work[0].pack, 0);
        assert_int_equal(st->work[1].pack, 0);
        assert_int_equal(m->total_bytes, 50);
        assert_int_equal(m->concurrent_volume, 28);
        expect_image(m);
        wl_pm_merge_free(m);
    }
    free_locals(l, 2);
}

/* ZBUF-EXC: full 4 x 5 buffers; strips cut 5 rows at 2 (tie 2 / 3 goes
 * low): processor 0 sends rows 2-4 (12 locations, 60 B) and compares the
 * 8 it receives, processor 1 the reverse; no pack, scatter or gather. */
static void test_zbuf_exc_two(void **state)
{
    (void)state;
    WlPmWpa *l[2];
    two_locals(l);
    WlPmMerge *m = wl_pm_merge_run(WL_PM_ZBUF_EXC, l, 2, NULL, &fmt);
    expect_msg(m, 0, 0, 1, 12, 60);
    expect_msg(m, 0, 1, 0, 8, 40);
    expect_work(m, 0, 0, 0, 0, 8, 0);
    expect_work(m, 0, 1, 0, 0, 12, 0);
    expect_totals(m, 1, 8, 12, 100, 2, 60);
    assert_int_equal(wl_pm_wpa_len(m->held[0]), 8);
    assert_int_equal(wl_pm_wpa_len(m->held[1]), 12);
    expect_image(m);
    wl_pm_merge_free(m);
    free_locals(l, 2);
}

/* Four processors, one pixel each at (0, y) of every row y, row y owned
 * by y.  PAIR stage 0 (channel 0): 2 rows out (2 x 8 + 2 x 2 = 20 B),
 * stage 1 (channel 1): 1 row (10 B); AAPC: 3 exchanges of 1 pixel and
 * 1 scanline (10 B), then 1 scattered and 3 compared each. */
static void test_four(void **state)
{
    (void)state;
    static const guint owner[4] = {0, 1, 2, 3};
    WlPmWpa *l[4];
    for (guint p = 0; p < 4; p++) {
        l[p] = wl_pm_wpa_new(2, 4);
        for (guint y = 0; y < 4; y++)
            put(l[p], 0, y, 1 + (p + y) % 4, 10 * p + y);
        wl_pm_wpa_finish(l[p]);
    }
    WlPmPartition part = {4, 4, (guint *)owner, TRUE};
    WlPmMerge *pr = wl_pm_merge_run(WL_PM_PAIR, l, 4, &part, &fmt);
    WlPmMerge *aa = wl_pm_merge_run(WL_PM_AAPC, l, 4, &part, &fmt);
    assert_int_equal(pr->steps->len, 2);
    assert_int_equal(aa->steps->len, 4);
    for (guint p = 0; p < 4; p++) {
        expect_msg(pr, 0, p, p ^ 1, 2, 20);
        expect_msg(pr, 1, p, p ^ 2, 1, 10);
        expect_work(pr, 0, p, 0, 2, 2, 2);
        expect_work(pr, 1, p, 0, 1, 1, 1);
        assert_int_equal(pr->merge_ops[p], 6);
        for (guint j = 1; j < 4; j++)
            expect_msg(aa, j - 1, p, p ^ j, 1, 10);
        expect_work(aa, 3, p, 0, 1, 3, 0);
        assert_int_equal(aa->merge_ops[p], 4);
        /* row p's winner: z = 1 + (q + p) % 4 is least for q = 4 - p */
        guint q = (4 - p) % 4;
        assert_int_equal(wl_pm_wpa_len(pr->held[p]), 1);
        assert_int_equal(wl_pm_wpa_row(pr->held[p], p)[0].poly, 10 * q + p);
        assert_int_equal(wl_pm_wpa_row(aa->held[p], p)[0].poly, 10 * q + p);
    }
    assert_int_equal(pr->total_bytes, 4 * 20 + 4 * 10);
    assert_int_equal(pr->total_msgs, 8);
    assert_int_equal(pr->concurrent_volume, 30);
    assert_int_equal(aa->total_bytes, 12 * 10);
    assert_int_equal(aa->total_msgs, 12);
    assert_int_equal(aa->concurrent_volume, 30);
    wl_pm_merge_free(pr);
    wl_pm_merge_free(aa);
    free_locals(l, 4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pair_two),
        cmocka_unit_test(test_aapc_two),
        cmocka_unit_test(test_banded),
        cmocka_unit_test(test_zbuf_exc_two),
        cmocka_unit_test(test_four),
    };
    return cmocka_run_group_tests_name("pm_merge_exact", tests, NULL, NULL);
}
