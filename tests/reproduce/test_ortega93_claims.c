/* test_ortega93_claims.c — seed 004 §6's sentences as computed rows
 * (sim/reproduce/ortega93_claims.c) decide from the simulated cells and
 * can come out false: times built so that each claim holds, then each
 * broken in turn (a slow 64K CM-200, a large set twenty-five times
 * slower, a large set that scales better), and a missing cell gives NaN,
 * not a verdict. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/reproduce/ortega93.h"

static const char *const res[] = {"1280x1024", "1024x768", "640x480"};

/* Tables 1-4 (time_s; Table 1's 64K rate): the small set halves its time
 * per doubling of the partition (i doublings: 2^-i), the large set is
 * `ratio` times slower on the smallest partition and scales as
 * 2^(-i * large_exp). */
static void fill(GPtrArray *rows, double ratio, double large_exp,
                 double rate64k)
{
    static const char *const p200[] = {"16K", "32K", "64K"};
    static const char *const p5[] = {"32", "64", "128", "256", "512"};
    for (guint r = 0; r < 3; r++)
        for (guint m = 0; m < 2; m++) {
            guint n = m == 0 ? 3 : 5;
            for (guint i = 0; i < n; i++) {
                char row[64];
                g_snprintf(row, sizeof row, "%s/%s", m == 0 ? p200[i] : p5[i],
                           res[r]);
                double small = 1.0 / pow(2.0, i);
                double large = ratio * pow(2.0, -(double)i * large_exp);
                g_ptr_array_add(rows, rp_row_new(m == 0 ? "1" : "3", row,
                                                 "time_s", small, NULL));
                g_ptr_array_add(rows, rp_row_new(m == 0 ? "2" : "4", row,
                                                 "time_s", large, NULL));
                if (m == 0 && i == 2)
                    g_ptr_array_add(rows, rp_row_new("1", row,
                                                     "polygons_per_s",
                                                     rate64k, NULL));
            }
        }
}

static double holds(GPtrArray *rows, const char *id)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        if (g_strcmp0(r->table, "claims") == 0 && g_strcmp0(r->row, id) == 0 &&
            g_strcmp0(r->column, "holds") == 0)
            return r->sim;
    }
    fail_msg("no claims row %s", id);
    return NAN;
}

static GPtrArray *claims(double ratio, double large_exp, double rate64k)
{
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    fill(rows, ratio, large_exp, rate64k);
    rp_ortega93_claims(rows);
    return rows;
}

static void test_all_hold(void **state)
{
    (void)state;
    /* Large ten times slower, scaling as 2^-0.8 per doubling. */
    GPtrArray *rows = claims(10.0, 0.8, 681456.0);
    assert_true(holds(rows, "over600k CM-200 64K") == 1.0);
    assert_true(holds(rows, "magnitude CM-200") == 1.0);
    assert_true(holds(rows, "magnitude CM-5") == 1.0);
    assert_true(holds(rows, "speedup CM-200") == 1.0);
    assert_true(holds(rows, "speedup CM-5") == 1.0);
    g_ptr_array_free(rows, TRUE);
}

static void test_each_can_fail(void **state)
{
    (void)state;
    GPtrArray *rows = claims(10.0, 0.8, 550000.0);
    assert_true(holds(rows, "over600k CM-200 64K") == 0.0);
    g_ptr_array_free(rows, TRUE);
    /* Twenty-five times slower: not "an order of magnitude" by [5, 20]. */
    rows = claims(25.0, 0.8, 681456.0);
    assert_true(holds(rows, "magnitude CM-200") == 0.0);
    assert_true(holds(rows, "magnitude CM-5") == 0.0);
    g_ptr_array_free(rows, TRUE);
    /* The large set scaling better than linear (2^-1.1 per doubling). */
    rows = claims(10.0, 1.1, 681456.0);
    assert_true(holds(rows, "speedup CM-200") == 0.0);
    assert_true(holds(rows, "speedup CM-5") == 0.0);
    g_ptr_array_free(rows, TRUE);
}

static void test_missing_cell_is_nan(void **state)
{
    (void)state;
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    g_ptr_array_add(rows, rp_row_new("1", "16K/640x480", "time_s", 1.0, NULL));
    rp_ortega93_claims(rows);
    assert_true(isnan(holds(rows, "over600k CM-200 64K")));
    assert_true(isnan(holds(rows, "magnitude CM-5")));
    assert_true(isnan(holds(rows, "speedup CM-200")));
    g_ptr_array_free(rows, TRUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_hold),
        cmocka_unit_test(test_each_can_fail),
        cmocka_unit_test(test_missing_cell_is_nan),
    };
    return cmocka_run_group_tests_name("ortega93_claims", tests, NULL, NULL);
}
