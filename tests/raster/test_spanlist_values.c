/* test_spanlist_values.c — exact results of sim/raster/spanlist.c (issue 21).
 *
 * The order within a run of equal (y, x_min) from its very first two
 * records on; a cleared list reads empty on every row (the last ones
 * too) before and after sorting; a re-sort of fewer spans than the sort
 * before it never picks up a record or a span left from that sort;
 * sizes, lengths and the sorted flag; freeing NULL. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/raster/spanlist.h"

static RastSpan span(int y, int x0, int x1, uint32_t prim, double z0)
{
    RastSpan s = {0};
    s.y = y;
    s.x0 = x0;
    s.x1 = x1;
    s.prim = prim;
    s.z0 = z0;
    return s;
}

static void add(RastSpanList *sl, RastSpan s)
{
    rast_spanlist_add(sl, &s);
}

/* Row 0 starts with a run of equal (y, x_min) given in reverse key
 * order: prim, then x_max, then z0 decide, whatever the insertion order;
 * fully equal keys keep insertion order (told apart by c0[0]). */
static void test_first_run_ordered(void **state)
{
    (void)state;
    RastSpanList *sl = rast_spanlist_new(16, 4);
    RastSpan s[6] = {span(0, 2, 9, 5, 0.5), span(0, 2, 9, 4, 0.5),
                     span(0, 2, 8, 4, 0.5), span(0, 2, 8, 4, 0.25),
                     span(0, 2, 8, 4, 0.25), span(0, 1, 3, 9, 0.9)};
    for (int i = 0; i < 6; i++) {
        s[i].c0[0] = (float)i;
        add(sl, s[i]);
    }
    assert_false(rast_spanlist_sorted(sl));
    rast_spanlist_sort(sl);
    assert_true(rast_spanlist_sorted(sl));
    size_t n;
    const RastSpan *row = rast_spanlist_row(sl, 0, &n);
    assert_int_equal(n, 6);
    const int want[6] = {5, 3, 4, 2, 1, 0}; /* by x0, prim, x1, z0, order */
    for (int i = 0; i < 6; i++)
        if (row[i].c0[0] != (float)want[i])
            fail_msg("position %d holds span %g, expected %d", i, row[i].c0[0],
                     want[i]);
    /* just two, the first two records of the list, out of order */
    RastSpanList *two = rast_spanlist_new(4, 2);
    add(two, span(0, 0, 2, 7, 0.5));
    add(two, span(0, 0, 2, 3, 0.5));
    rast_spanlist_sort(two);
    row = rast_spanlist_row(two, 0, &n);
    assert_int_equal(n, 2);
    assert_int_equal(row[0].prim, 3);
    assert_int_equal(row[1].prim, 7);
    rast_spanlist_free(two);
    rast_spanlist_free(sl);
}

static void assert_all_empty(const RastSpanList *sl)
{
    for (int y = 0; y < rast_spanlist_height(sl); y++) {
        size_t n = 99;
        const RastSpan *row = rast_spanlist_row(sl, y, &n);
        if (n != 0 || row != NULL)
            fail_msg("row %d: %zu spans after a clear", y, n);
    }
}

/* Spans on the last rows, sorted, then cleared: every row reads empty
 * at once (the list counts as sorted) and after another sort. */
static void test_clear_empties_every_row(void **state)
{
    (void)state;
    RastSpanList *sl = rast_spanlist_new(6, 5);
    add(sl, span(4, 0, 6, 1, 0.5));
    add(sl, span(4, 1, 2, 2, 0.5));
    add(sl, span(3, 2, 3, 3, 0.5));
    add(sl, span(0, 0, 1, 4, 0.5));
    rast_spanlist_sort(sl);
    size_t n;
    rast_spanlist_row(sl, 4, &n);
    assert_int_equal(n, 2);
    rast_spanlist_clear(sl);
    assert_true(rast_spanlist_sorted(sl));
    assert_int_equal(rast_spanlist_len(sl), 0);
    assert_all_empty(sl);
    rast_spanlist_sort(sl);
    assert_all_empty(sl);
    /* filled again, only on row 1 */
    add(sl, span(1, 3, 4, 8, 0.5));
    rast_spanlist_sort(sl);
    for (int y = 0; y < 5; y++) {
        const RastSpan *row = rast_spanlist_row(sl, y, &n);
        assert_int_equal(n, y == 1);
        if (y == 1)
            assert_int_equal(row[0].prim, 8);
    }
    rast_spanlist_free(sl);
}

/* Three spans of one key sorted, then cleared and two of the same key
 * sorted: the third record and span of the first sort are still in the
 * scratch arrays and must stay out. */
static void test_resort_fewer(void **state)
{
    (void)state;
    RastSpanList *sl = rast_spanlist_new(8, 2);
    add(sl, span(0, 0, 4, 1, 0.5));
    add(sl, span(0, 0, 4, 2, 0.5));
    add(sl, span(0, 0, 4, 3, 0.5));
    rast_spanlist_sort(sl);
    rast_spanlist_clear(sl);
    add(sl, span(0, 0, 4, 9, 0.5));
    add(sl, span(0, 0, 4, 8, 0.5));
    rast_spanlist_sort(sl);
    size_t n;
    const RastSpan *row = rast_spanlist_row(sl, 0, &n);
    assert_int_equal(n, 2);
    assert_int_equal(row[0].prim, 8);
    assert_int_equal(row[1].prim, 9);
    rast_spanlist_row(sl, 1, &n);
    assert_int_equal(n, 0);
    rast_spanlist_free(sl);
}

/* Sizes as given; the sink appends without touching the counters; a
 * list whose width exceeds its height (and the reverse) sorts x_min up
 * to width - 1 and y up to height - 1. */
static void test_sizes_and_sink(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        int w = k ? 3 : 40, h = k ? 30 : 2;
        RastSpanList *sl = rast_spanlist_new(w, h);
        assert_int_equal(rast_spanlist_width(sl), w);
        assert_int_equal(rast_spanlist_height(sl), h);
        RastSpanSink sink = rast_spanlist_sink(sl);
        RastCounters c = {0};
        RastSpan a = span(h - 1, w - 1, w, 1, 0.5), b = span(h - 1, 0, 1, 2, 0.5),
                 d = span(0, w - 1, w, 3, 0.5);
        sink.fn(sink.ctx, &a, &c);
        sink.fn(sink.ctx, &b, &c);
        sink.fn(sink.ctx, &d, &c);
        assert_int_equal(c.spans + c.pixels + c.zcompares, 0);
        assert_int_equal(rast_spanlist_len(sl), 3);
        rast_spanlist_sort(sl);
        size_t n;
        const RastSpan *row = rast_spanlist_row(sl, h - 1, &n);
        assert_int_equal(n, 2);
        assert_int_equal(row[0].prim, 2);
        assert_int_equal(row[1].prim, 1);
        row = rast_spanlist_row(sl, 0, &n);
        assert_int_equal(n, 1);
        assert_int_equal(row[0].prim, 3);
        rast_spanlist_free(sl);
    }
    rast_spanlist_free(NULL);
}

/* Exactly 8 and 16 spans (sort scratch of a power-of-two size), in
 * reverse order over 4 rows: sorted by row, then x_min. */
static void test_power_of_two_counts(void **state)
{
    (void)state;
    for (int n = 8; n <= 16; n += 8) {
        RastSpanList *sl = rast_spanlist_new(16, 4);
        for (int i = n - 1; i >= 0; i--)
            add(sl, span(i % 4, i / 4, i / 4 + 1, (uint32_t)i, 0.5));
        rast_spanlist_sort(sl);
        assert_int_equal(rast_spanlist_len(sl), n);
        for (int y = 0; y < 4; y++) {
            size_t k;
            const RastSpan *row = rast_spanlist_row(sl, y, &k);
            assert_int_equal(k, n / 4);
            for (size_t j = 0; j < k; j++)
                assert_int_equal(row[j].prim, (uint32_t)(4 * j + y));
        }
        rast_spanlist_free(sl);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_first_run_ordered),
        cmocka_unit_test(test_clear_empties_every_row),
        cmocka_unit_test(test_resort_fewer),
        cmocka_unit_test(test_sizes_and_sink),
        cmocka_unit_test(test_power_of_two_counts),
    };
    return cmocka_run_group_tests_name("spanlist_values", tests, NULL, NULL);
}
