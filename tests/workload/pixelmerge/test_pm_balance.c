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
    assert_float_equal(wl_pm_load_imbalance(l, 4), 30.0 / 25.0, 1e-12);
    uint64_t z[2] = {0, 0};
    assert_float_equal(wl_pm_load_imbalance(z, 2), 0.0, 0.0);
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
    };
    return cmocka_run_group_tests_name("pm_balance", tests, NULL, NULL);
}
