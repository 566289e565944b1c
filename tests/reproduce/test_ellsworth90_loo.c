/* test_ellsworth90_loo.c — ellsworth90's stored leave-one-out values
 * (ellsworth90_cv.c, configs/papers/ellsworth90/loo.yaml): the real
 * paper's 12 fitted cells come out cross-validated with their
 * leave-one-out value and the predicted cells with intervals; a loo.yaml
 * whose `fitted` values the reproduction no longer gives is stale and
 * yields no leave-one-out value; a bad file is a located error. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <math.h>
#include <string.h>

#include "sim/reproduce/ellsworth90.h"
#include "sim/reproduce/rp_driver.h"

static void test_real_labels(void **state)
{
    (void)state;
    const RpPaperOps *rp = rp_find("ellsworth90");
    RpContext ctx = {.fidelity = "analytic", .quiet = TRUE};
    GError *err = NULL;
    RpTable *t = rp_drive(rp, RP_PAPERS_DIR, &ctx, &err);
    if (!t)
        fail_msg("%s", err->message);
    guint cv = 0, predicted = 0;
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        if (strcmp(j->table, "1") != 0 || !isfinite(j->published))
            continue;
        if (j->label == RP_LABEL_CV) {
            cv++;
            assert_true(isfinite(j->loo_sim));
            assert_true(isfinite(j->loo_rel_error));
            assert_true(isfinite(j->lo) && j->lo <= j->hi);
        } else {
            assert_int_equal(j->label, RP_LABEL_PREDICTED);
            assert_string_equal(j->column, "speedup_4");
            assert_true(isfinite(j->lo) && j->lo <= j->hi);
            predicted++;
        }
    }
    assert_int_equal(cv, 12);
    assert_int_equal(predicted, 4);
    assert_int_equal(t->oos_n, 16);
    assert_int_equal(t->oos_cv, 12);
    assert_int_equal(t->inside_of, 16);
    printf("inside own interval %u of %u\n", t->inside, t->inside_of);
    rp_table_free(t);
}

/* loo.yaml with `body` in a new directory; the setup path beside it. */
static char *write_loo(const char *body, char **dir)
{
    *dir = g_dir_make_tmp("pgsim-ellloo-XXXXXX", NULL);
    char *path = g_build_filename(*dir, "loo.yaml", NULL);
    assert_true(g_file_set_contents(path, body, -1, NULL));
    g_free(path);
    return g_build_filename(*dir, "setup.yaml", NULL);
}

static void remove_loo(char *dir, char *setup)
{
    char *path = g_build_filename(dir, "loo.yaml", NULL);
    g_unlink(path);
    g_rmdir(dir);
    g_free(path);
    g_free(dir);
    g_free(setup);
}

static const char *one_refit =
    "refits:\n"
    "  - left_out: {table: \"1\", row: a, column: util_4}\n"
    "    published: 90\n"
    "    fitted: %s\n"
    "    loo: 88\n"
    "    constants: {color: 1}\n"
    "    predicted:\n"
    "      - {row: a, column: speedup_4, value: 3.5}\n";

/* The rows rp_ellsworth90_loo() makes with table 1's a/util_4 at 91. */
static GPtrArray *loo_rows(const char *fitted, gboolean *ok, GError **err)
{
    char *dir = NULL, *body = g_strdup_printf(one_refit, fitted);
    char *setup = write_loo(body, &dir);
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    g_ptr_array_add(rows, rp_row_new("1", "a", "util_4", 91, NULL));
    *ok = rp_ellsworth90_loo(setup, rows, err);
    remove_loo(dir, setup);
    g_free(body);
    return rows;
}

static const RpRow *row_of(const GPtrArray *rows, const char *table,
                           const char *col)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = g_ptr_array_index(rows, i);
        if (strcmp(r->table, table) == 0 && strcmp(r->column, col) == 0)
            return r;
    }
    return NULL;
}

static void test_current_and_stale(void **state)
{
    (void)state;
    gboolean ok = FALSE;
    GPtrArray *rows = loo_rows("91", &ok, NULL);
    assert_true(ok);
    assert_non_null(row_of(rows, "cv", "loo_util_4"));
    assert_float_equal(row_of(rows, "cv", "loo_util_4")->sim, 88, 0);
    assert_float_equal(row_of(rows, "cv", "refit_max_speedup_4")->sim, 3.5, 0);
    assert_null(row_of(rows, "cv", "stale"));
    g_ptr_array_free(rows, TRUE);
    rows = loo_rows("92", &ok, NULL); /* the constants moved since */
    assert_true(ok);
    assert_null(row_of(rows, "cv", "loo_util_4"));
    assert_non_null(row_of(rows, "cv", "stale"));
    g_ptr_array_free(rows, TRUE);
}

static void test_bad_file(void **state)
{
    (void)state;
    gboolean ok = TRUE;
    GError *err = NULL;
    GPtrArray *rows = loo_rows("ninety", &ok, &err);
    assert_false(ok);
    assert_non_null(strstr(err->message, "loo.yaml:4:"));
    g_error_free(err);
    g_ptr_array_free(rows, TRUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_real_labels),
        cmocka_unit_test(test_current_and_stale),
        cmocka_unit_test(test_bad_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
