/* test_pm_balance.c — strips, RS and HBP partitions (seed 003 §4). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <cmocka.h>

#include "sim/core/rng.h"
#include "sim/workload/pixelmerge/pm_balance.h"

static void test_strips_equal_and_halving(void **state)
{
    (void)state;
    WlPmPartition *p = wl_pm_partition_new(WL_PM_BAL_STRIPS, 4, NULL, 16);
    /* Top half to bit0 = 0, then quarters by bit1: owners 0, 2, 1, 3. */
    guint want[4] = {0, 2, 1, 3};
    for (guint y = 0; y < 16; y++)
        assert_int_equal(p->owner[y], want[y / 4]);
    assert_true(p->banded);
    wl_pm_partition_free(p);
}

static uint64_t band_sum(const uint64_t *c, guint lo, guint hi)
{
    uint64_t s = 0;
    for (guint y = lo; y < hi; y++)
        s += c[y];
    return s;
}

/* The first RS cut is the best single cut (checked by brute force). */
static void test_rs_first_cut_is_optimal(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 7, 1);
    for (int trial = 0; trial < 50; trial++) {
        guint h = 5 + (guint)sim_rng_below(&r, 60);
        uint64_t c[64];
        for (guint y = 0; y < h; y++)
            c[y] = sim_rng_below(&r, 100);
        WlPmPartition *p = wl_pm_partition_new(WL_PM_BAL_RS, 2, c, h);
        guint cut = 0;
        while (cut < h && p->owner[cut] == 0)
            cut++;
        for (guint y = cut; y < h; y++)
            assert_int_equal(p->owner[y], 1);
        uint64_t tot = band_sum(c, 0, h);
        int64_t got = (int64_t)(2 * band_sum(c, 0, cut)) - (int64_t)tot;
        for (guint s = 0; s <= h; s++) {
            int64_t d = (int64_t)(2 * band_sum(c, 0, s)) - (int64_t)tot;
            assert_true(llabs(got) <= llabs(d));
        }
        wl_pm_partition_free(p);
    }
}

/* RS gives each processor one band; bands of a subcube are adjacent. */
static void test_rs_bands(void **state)
{
    (void)state;
    uint64_t c[40];
    for (guint y = 0; y < 40; y++)
        c[y] = (y * 37) % 11;
    WlPmPartition *p = wl_pm_partition_new(WL_PM_BAL_RS, 8, c, 40);
    guint changes = 0;
    for (guint y = 1; y < 40; y++)
        changes += p->owner[y] != p->owner[y - 1];
    assert_true(changes <= 7);
    /* Top half (bit 0 = 0) comes before the bottom half. */
    gboolean seen_bottom = FALSE;
    for (guint y = 0; y < 40; y++) {
        if (p->owner[y] & 1)
            seen_bottom = TRUE;
        else
            assert_false(seen_bottom);
    }
    wl_pm_partition_free(p);
}

static void test_hbp_greedy(void **state)
{
    (void)state;
    uint64_t c[6] = {5, 9, 1, 7, 3, 3};
    WlPmPartition *p = wl_pm_partition_new(WL_PM_BAL_HBP, 2, c, 6);
    /* 9 -> 0, 7 -> 1, 5 -> 1 (12), 3 -> 0 (12), 3 -> 0 (15), 1 -> 1. */
    guint want[6] = {1, 0, 1, 1, 0, 0};
    for (guint y = 0; y < 6; y++)
        assert_int_equal(p->owner[y], want[y]);
    uint64_t load[2];
    wl_pm_partition_loads(p, c, load);
    assert_int_equal(load[0], 15);
    assert_int_equal(load[1], 13);
    assert_false(p->banded);
    wl_pm_partition_free(p);
}

/* HBP spread is bounded by the largest scanline count. */
static void test_hbp_bound(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 9, 2);
    uint64_t c[200], load[16], mx = 0;
    for (guint y = 0; y < 200; y++) {
        c[y] = sim_rng_below(&r, 500);
        mx = MAX(mx, c[y]);
    }
    WlPmPartition *p = wl_pm_partition_new(WL_PM_BAL_HBP, 16, c, 200);
    wl_pm_partition_loads(p, c, load);
    uint64_t lo = load[0], hi = load[0];
    for (int k = 0; k < 16; k++) {
        lo = MIN(lo, load[k]);
        hi = MAX(hi, load[k]);
    }
    assert_true(hi - lo <= mx);
    wl_pm_partition_free(p);
}

static void test_imbalance(void **state)
{
    (void)state;
    uint64_t l[4] = {10, 20, 30, 40};
    assert_true(wl_pm_load_imbalance(l, 4) == 30.0 / 25.0);
    /* no load at all: 0, not 0 / 0 (assert_float_equal passes a NaN) */
    uint64_t z[2] = {0, 0};
    assert_true(wl_pm_load_imbalance(z, 2) == 0.0);
    /* the first processor neither the least nor the most loaded */
    uint64_t m[3] = {5, 2, 11};
    assert_true(wl_pm_load_imbalance(m, 3) == 9.0 / 6.0);
    uint64_t one[1] = {7};
    assert_true(wl_pm_load_imbalance(one, 1) == 0.0);
}

static void expect_owner(WlPmBalance how, guint procs, const uint64_t *counts,
                         guint h, const guint *want, gboolean banded)
{
    WlPmPartition *p = wl_pm_partition_new(how, procs, counts, h);
    assert_int_equal(p->banded, banded);
    assert_memory_equal(p->owner, want, h * sizeof *want);
    wl_pm_partition_free(p);
}

/* Owners worked out by hand.  RS cuts a band at the s whose prefix is
 * nearest the middle, the lower s on a tie: [1, 2, 1] (S 0 1 3 4, middle
 * 2: S[1] = 1 and S[2] = 3 tie) -> [0, 1, 1]; [1, 1, 1, 1] -> [0, 0, 1, 1];
 * [3, 1, 1, 3] on 4 (S 0 3 4 5 8): first cut 2; [0, 2): middle 1.5,
 * S[1] = 3 against S[0] = 0 -> cut 1; [2, 4): middle 6.5, S[3] = 5
 * against S[4] = 8 -> cut 3; the upper half of each cut takes bit
 * `level`: [0, 2, 1, 3].  Strips on 6 rows, 4 procs: cut 3, then 1 (tie
 * 1 / 2 at 1.5 -> 1) and 4 (tie at 4.5 -> 4): [0, 2, 2, 1, 3, 3].  HBP
 * deals rows by count, larger first (equal counts by row), each to the
 * least-loaded processor (the lowest on a tie): [2, 5, 5, 1, 3] on 2 ->
 * y1 0, y2 1, y4 0 (5 = 5), y0 1, y3 1 (8 > 7). */
static void test_exact_owners(void **state)
{
    (void)state;
    static const uint64_t c1[] = {1, 2, 1}, c2[] = {1, 1, 1, 1},
                          c3[] = {3, 1, 1, 3}, c5[] = {2, 5, 5, 1, 3},
                          c6[] = {9, 0, 0, 0, 0, 9};
    static const guint o1[] = {0, 1, 1}, o2[] = {0, 0, 1, 1},
                       o3[] = {0, 2, 1, 3}, o6[] = {0, 2, 2, 1, 3, 3},
                       o5[] = {1, 0, 1, 1, 0};
    expect_owner(WL_PM_BAL_RS, 2, c1, 3, o1, TRUE);
    expect_owner(WL_PM_BAL_RS, 2, c2, 4, o2, TRUE);
    expect_owner(WL_PM_BAL_RS, 4, c3, 4, o3, TRUE);
    expect_owner(WL_PM_BAL_STRIPS, 4, c6, 6, o6, TRUE);
    expect_owner(WL_PM_BAL_HBP, 2, c5, 5, o5, FALSE);
    /* prefixes equal to the middle over several rows (zero counts): the
     * first such s, [2, 0, 0, 2] -> cut 1; all zero: the cut at the
     * band's start, every row to the upper half */
    static const uint64_t c7[] = {2, 0, 0, 2}, z4[] = {0, 0, 0, 0};
    static const guint o7[] = {0, 1, 1, 1}, oz[] = {1, 1, 1, 1};
    expect_owner(WL_PM_BAL_RS, 2, c7, 4, o7, TRUE);
    expect_owner(WL_PM_BAL_RS, 2, z4, 4, oz, TRUE);
    static const guint one[] = {0, 0, 0};
    expect_owner(WL_PM_BAL_RS, 1, c1, 3, one, TRUE);
    expect_owner(WL_PM_BAL_HBP, 1, c1, 3, one, FALSE);
    /* loads and imbalance (max - min) / mean */
    WlPmPartition *p = wl_pm_partition_new(WL_PM_BAL_RS, 4, c3, 4);
    uint64_t load[4];
    wl_pm_partition_loads(p, c3, load);
    static const uint64_t want[] = {3, 1, 1, 3};
    assert_memory_equal(load, want, sizeof want);
    assert_true(wl_pm_load_imbalance(load, 4) == 1.0);
    wl_pm_partition_free(p);
    static const uint64_t l3[] = {4, 1, 1};
    assert_true(wl_pm_load_imbalance(l3, 3) == 1.5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_strips_equal_and_halving),
        cmocka_unit_test(test_rs_first_cut_is_optimal),
        cmocka_unit_test(test_rs_bands),
        cmocka_unit_test(test_hbp_greedy),
        cmocka_unit_test(test_hbp_bound),
        cmocka_unit_test(test_imbalance),
        cmocka_unit_test(test_exact_owners),
    };
    return cmocka_run_group_tests_name("pm_balance", tests, NULL, NULL);
}
