/* test_ortega93_cv.c — the CM-200 fit's cross-validation rows
 * (sim/reproduce/ortega93_cv.c) against the published times of
 * configs/papers/ortega93/published.yaml: cells built exactly on a line
 * give back its send_slice with no error in or out of sample; one cell
 * moved off the line shows a larger error when left out than in sample;
 * a cell the paper does not have is an error, not a number. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/reproduce/ortega93.h"

static const double pub[2][9] = {
    {1.894, 1.04, 0.571, 1.637, 0.848, 0.482, 1.162, 0.625, 0.335},
    {22.094, 15.005, 8.574, 18.015, 11.855, 6.834, 10.548, 6.789, 4.039}};

/* The 18 CM-200 cells, each time = a + s * b with s = 50 us. */
static GArray *cells(void)
{
    static const char *const res[] = {"1280x1024", "1024x768", "640x480"};
    static const char *const part[] = {"16K", "32K", "64K"};
    GArray *c = g_array_new(FALSE, FALSE, sizeof(RpOrCell));
    for (int t = 0; t < 2; t++)
        for (int i = 0; i < 9; i++) {
            RpOrCell x = {.s = 50e-6};
            g_snprintf(x.table, sizeof x.table, "%d", t + 1);
            g_snprintf(x.row, sizeof x.row, "%s/%s", part[i % 3], res[i / 3]);
            x.a = 0.1 * pub[t][i];
            x.b = 0.9 * pub[t][i] / x.s;
            g_array_append_val(c, x);
        }
    return c;
}

static double get(GPtrArray *rows, const char *col)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        if (g_strcmp0(r->table, "cv") == 0 && g_strcmp0(r->row, "CM-200") == 0 &&
            g_strcmp0(r->column, col) == 0)
            return r->sim;
    }
    fail_msg("no cv row %s", col);
    return NAN;
}

static void test_exact_line(void **state)
{
    (void)state;
    GArray *c = cells();
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    GError *err = NULL;
    assert_true(rp_ortega93_cv(c, rows, &err));
    assert_true(fabs(get(rows, "send_slice_fit_us") - 50.0) < 1e-9);
    assert_true(get(rows, "in_sample_mean_abs_pct") < 1e-9);
    assert_true(get(rows, "loo_worst_abs_pct") < 1e-9);
    g_ptr_array_free(rows, TRUE);
    /* One cell off the line: the fit on all 18 leans towards it, so the
     * cells predicted without it (and it without itself) do worse. */
    g_array_index(c, RpOrCell, 4).b *= 1.3;
    rows = g_ptr_array_new_with_free_func(rp_row_free);
    assert_true(rp_ortega93_cv(c, rows, &err));
    assert_true(get(rows, "send_slice_fit_us") < 50.0);
    assert_true(get(rows, "loo_mean_abs_pct") >
                get(rows, "refit_mean_abs_pct"));
    assert_true(fabs(get(rows, "loo_worst_abs_pct") - 27.0) < 1e-6);
    g_ptr_array_free(rows, TRUE);
    g_array_free(c, TRUE);
}

static void test_unknown_cell(void **state)
{
    (void)state;
    GArray *c = cells();
    g_strlcpy(g_array_index(c, RpOrCell, 0).row, "8K/1280x1024",
              sizeof(((RpOrCell *)0)->row));
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    GError *err = NULL;
    assert_false(rp_ortega93_cv(c, rows, &err));
    assert_non_null(err);
    assert_non_null(strstr(err->message, "8K/1280x1024"));
    g_clear_error(&err);
    assert_int_equal(rows->len, 0);
    g_ptr_array_free(rows, TRUE);
    g_array_free(c, TRUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exact_line),
        cmocka_unit_test(test_unknown_cell),
    };
    return cmocka_run_group_tests_name("ortega93_cv", tests, NULL, NULL);
}
