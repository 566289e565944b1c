/* test_sf_adapt_split.c — the k-d split of the adaptive regions
 * (sf_adapt.h) on weight grids worked out by hand: the cut that
 * minimises the larger side's load per processor (the one nearest the
 * proportional position on a tie), the longer side cut first, each side
 * keeping a line per processor (else the other axis), cell edges
 * scaled to pixels, the cells visited, and weights scaled by the
 * calibrated factor (rounded). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/sortfirst/sf_adapt.h"

static void expect_rect(const WlSfRegions *r, guint p, int x0, int y0, int x1,
                        int y1)
{
    WlSfRect q = r->rect[p];
    if (q.x0 != x0 || q.y0 != y0 || q.x1 != x1 || q.y1 != y1)
        fail_msg("region %u: [%d, %d) x [%d, %d), expected [%d, %d) x [%d, "
                 "%d)",
                 p, q.x0, q.x1, q.y0, q.y1, x0, x1, y0, y1);
}

/* Row 0 weighs 1 .. 8 by column (36 in all), 2 processors: a cut at c
 * leaves max(S(c), 36 - S(c)); S = 1 3 6 10 15 21 28: c = 5 and c = 6
 * both give 21, c = 5 is nearer the middle (4).  Cells are 1 px. */
static void test_weighted_cut(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(8, 2);
    for (guint x = 0; x < 8; x++)
        a->weight[x] = x + 1;
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 8, 8);
    /* visited: 64 cells of the table, 2 x 8 lines of the marginal */
    assert_int_equal(wl_sf_adapt_split(a, &r), 64 + 16);
    expect_rect(&r, 0, 0, 0, 5, 8);
    expect_rect(&r, 1, 5, 0, 8, 8);
    /* the factor scales the weights: columns 5 .. 7 at 0.25 weigh 1.5,
     * 1.75, 2 (rounded 2, 2, 2): S = 1 3 6 10 15 17 19 21, total 21;
     * c = 4: max(10, 11) = 11, the best */
    for (guint x = 5; x < 8; x++)
        a->factor[x] = 0.25;
    assert_int_equal(wl_sf_adapt_split(a, &r), 64 + 16);
    expect_rect(&r, 0, 0, 0, 4, 8);
    expect_rect(&r, 1, 4, 0, 8, 8);
    wl_sf_adapt_free(a);
}

/* 6 x 6 cells of weight 1 on a 12 x 12 screen (2 px a cell), 3
 * processors: a vertical cut for 1 of 3: c = 2 gives max(12 x 2, 24 x 1)
 * = 24, the least; the right part (4 wide, 6 high) is cut across its
 * longer side, y, at 3 (12 and 12). */
static void test_three_ways(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(6, 3);
    for (guint i = 0; i < 36; i++)
        a->weight[i] = 1;
    WlSfRegions r;
    wl_sf_regions_init(&r, 3, 12, 12);
    assert_int_equal(wl_sf_adapt_split(a, &r), 36 + 12 + 12);
    expect_rect(&r, 0, 0, 0, 4, 12);
    expect_rect(&r, 1, 4, 0, 12, 6);
    expect_rect(&r, 2, 4, 6, 12, 12);
    wl_sf_adapt_free(a);
}

/* 2 x 2 cells, 4 processors, no weight: the first cut is vertical at 1
 * (each half needs one column for its 2 processors over 2 rows), then
 * each column is cut across y: regions in k-d order (0, 0), (0, 1),
 * (1, 0), (1, 1). */
static void test_one_cell_each(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(2, 4);
    WlSfRegions r;
    wl_sf_regions_init(&r, 4, 8, 8);
    wl_sf_adapt_split(a, &r);
    expect_rect(&r, 0, 0, 0, 4, 4);
    expect_rect(&r, 1, 0, 4, 4, 8);
    expect_rect(&r, 2, 4, 0, 8, 4);
    expect_rect(&r, 3, 4, 4, 8, 8);
    wl_sf_adapt_free(a);
}

/* A 4 x 4 grid for 2 processors whose weight sits in row 0, 4 0 0 4 by
 * column: the cut is vertical (a square counts as wide); c = 1, 2, 3
 * all leave a side of 4, and the proportional position 2 wins. */
static void test_tie_nearest_middle(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(4, 2);
    a->weight[0] = 4;
    a->weight[3] = 4;
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16);
    wl_sf_adapt_split(a, &r);
    expect_rect(&r, 0, 0, 0, 8, 16);
    expect_rect(&r, 1, 8, 0, 16, 16);
    wl_sf_adapt_free(a);
    /* 3 columns weighing 2 0 2: c = 1 and c = 2 both leave 2 and lie 0.5
     * from the middle (1.5): the first stays */
    a = wl_sf_adapt_new(3, 2);
    a->weight[0] = 2;
    a->weight[2] = 2;
    wl_sf_regions_init(&r, 2, 6, 6);
    wl_sf_adapt_split(a, &r);
    expect_rect(&r, 0, 0, 0, 2, 6);
    expect_rect(&r, 1, 2, 0, 6, 6);
    wl_sf_adapt_free(a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_weighted_cut),
        cmocka_unit_test(test_three_ways),
        cmocka_unit_test(test_one_cell_each),
        cmocka_unit_test(test_tie_nearest_middle),
    };
    return cmocka_run_group_tests_name("sf_adapt_split", tests, NULL, NULL);
}
