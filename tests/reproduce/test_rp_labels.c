/* test_rp_labels.c — labelling a joined table from a labels file:
 * fitted, cross-validated, predicted, claim and leave-one-out cells, the
 * out-of-sample and in-sample headline, intervals and the count of
 * visible cells inside their own leave-one-out interval; located errors
 * in a bad labels file. */
#include "sim/reproduce/rp_labels.h"
#include <glib/gstdio.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static const char paper_yaml[] =
    "paper: {name: fake, citation: test}\n"
    "cells:\n"
    "  - {table: \"1\", row: a, column: t, value: 10}\n"
    "  - {table: \"1\", row: b, column: t, value: 10}\n"
    "  - {table: \"1\", row: c, column: t, value: 10}\n"
    "  - {table: \"1\", row: d, column: t, value: 10}\n"
    "  - {table: \"2\", row: p, column: t, value: 10}\n"
    "  - {table: \"2\", row: w, column: t, withheld: true}\n";

static const char labels_yaml[] =
    "claims: [{table: claims}]\n"
    "leave_one_out: [{table: cv}]\n"
    "fits:\n"
    "  - constant: k1\n"
    "    cells: [{table: \"1\", row: a}, {table: \"1\", row: \"[bc]\"},\n"
    "            {table: \"1\", row: \"?\", column: \"x*\"},\n"
    "            {table: \"1\", row: b}, {table: \"1\", row: c}]\n"
    "    loo: {table: cv, row: \"{row}\", column: \"loo_{column}\"}\n"
    "  - constant: k2\n"
    "    cells: [{table: \"1\", row: d}]\n";

static char *write_tmp(const char *dir, const char *name, const char *text)
{
    char *p = g_build_filename(dir, name, NULL);
    g_assert_true(g_file_set_contents(p, text, -1, NULL));
    return p;
}

static void add(GPtrArray *rows, const char *t, const char *r, const char *c,
                double v)
{
    g_ptr_array_add(rows, rp_row_new(t, r, c, v, NULL));
}

/* The joined, labelled table; labels from `text`. */
static RpTable *labelled(const char *text)
{
    char *dir = g_dir_make_tmp("pgsim-rpl-XXXXXX", NULL);
    char *pp = write_tmp(dir, "published.yaml", paper_yaml);
    char *lp = write_tmp(dir, "labels.yaml", text);
    RpPaper *paper = rp_paper_load(pp, NULL);
    assert_non_null(paper);
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    add(rows, "1", "a", "t", 10.5); /* in +5 %, left out +10 % */
    add(rows, "1", "b", "t", 9.8);  /* in -2 %, left out -10 % */
    add(rows, "1", "c", "t", 10.1); /* in +1 %, left out +5 % */
    add(rows, "1", "d", "t", 10.2); /* fitted, no leave-one-out */
    add(rows, "2", "p", "t", 12.0); /* predicted +20 % */
    add(rows, "2", "w", "t", 20.0); /* withheld */
    add(rows, "cv", "a", "loo_t", 11.0);
    add(rows, "cv", "b", "loo_t", 9.0);
    add(rows, "cv", "c", "loo_t", 10.5);
    add(rows, "claims", "x", "holds", 1.0);
    RpTable *t = rp_table_join(paper, rows, "analytic", 0);
    RpLabels *l = rp_labels_load(lp, NULL);
    assert_non_null(l);
    rp_labels_apply(l, t);
    rp_labels_free(l);
    g_ptr_array_free(rows, TRUE);
    rp_paper_free(paper);
    g_unlink(pp);
    g_unlink(lp);
    g_rmdir(dir);
    g_free(pp);
    g_free(lp);
    g_free(dir);
    return t;
}

static void test_labels(void **state)
{
    (void)state;
    RpTable *t = labelled(labels_yaml);
    const RpJoined *a = rp_table_find(t, "1", "a", "t");
    assert_int_equal(a->label, RP_LABEL_CV);
    assert_string_equal(a->fitted_by, "k1");
    assert_true(fabs(a->loo_sim - 11.0) < 1e-12);
    assert_true(fabs(a->loo_rel_error - 0.1) < 1e-12);
    const RpJoined *d = rp_table_find(t, "1", "d", "t");
    assert_int_equal(d->label, RP_LABEL_FITTED);
    assert_string_equal(d->fitted_by, "k2");
    assert_true(isnan(d->loo_sim));
    assert_int_equal(rp_table_find(t, "2", "p", "t")->label,
                     RP_LABEL_PREDICTED);
    assert_int_equal(rp_table_find(t, "2", "w", "t")->label,
                     RP_LABEL_PREDICTED);
    assert_int_equal(rp_table_find(t, "cv", "a", "loo_t")->label,
                     RP_LABEL_LOO);
    assert_int_equal(rp_table_find(t, "claims", "x", "holds")->label,
                     RP_LABEL_CLAIM);
    char *s = rp_label_text(d);
    assert_string_equal(s, "fitted (k2)");
    g_free(s);
    rp_table_free(t);
}

static void test_headline(void **state)
{
    (void)state;
    RpTable *t = labelled(labels_yaml);
    /* out of sample: a, b, c left out (10, 10, 5 %) and p (20 %) */
    assert_int_equal(t->oos_n, 4);
    assert_int_equal(t->oos_cv, 3);
    assert_true(fabs(t->oos_mean - 0.1125) < 1e-12);
    assert_true(fabs(t->oos_worst - 0.2) < 1e-12);
    /* in sample: a, b, c, d as printed (5, 2, 1, 2 %) */
    assert_int_equal(t->ins_n, 4);
    assert_true(fabs(t->ins_mean - 0.025) < 1e-12);
    /* all compared cells, as before labels */
    assert_int_equal(t->compared, 5);
    GString *g = g_string_new(NULL);
    rp_table_summary(t, g);
    assert_non_null(strstr(g->str, "out-of-sample mean |rel_error| 11.2% "
                                   "over 4 cells (3 cross-validated, 1 "
                                   "predicted), worst 20.0% (table 2, p, t)"));
    assert_non_null(strstr(g->str, "in-sample (fitted cells) mean "
                                   "|rel_error| 2.5% over 4 cells"));
    g_string_free(g, TRUE);
    rp_table_free(t);
}

static void test_intervals(void **state)
{
    (void)state;
    RpTable *t = labelled(labels_yaml);
    assert_true(fabs(t->loo_min + 0.1) < 1e-12);
    assert_true(fabs(t->loo_max - 0.1) < 1e-12);
    const RpJoined *w = rp_table_find(t, "2", "w", "t");
    assert_true(fabs(w->lo - 20.0 / 1.1) < 1e-9);
    assert_true(fabs(w->hi - 20.0 / 0.9) < 1e-9);
    /* a (+10 %) and b (-10 %) are the others' extremes, p (+20 %) is
     * outside [-10, +10] %; c (+5 %) lies in [-10, +10] % */
    assert_int_equal(t->inside_of, 4);
    assert_int_equal(t->inside, 1);
    GString *c = g_string_new(NULL);
    rp_table_csv(t, TRUE, c);
    assert_non_null(strstr(c->str, "rel_error,label,fitted_by,loo_sim,"
                                   "loo_rel_error,interval_lo,interval_hi\n"));
    assert_non_null(strstr(c->str, "fake,1,d,t,10.2,10,"));
    assert_non_null(strstr(c->str, ",fitted,k2,,,,\n"));
    g_string_free(c, TRUE);
    rp_table_free(t);
}

static void test_bad_file(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-rpl-XXXXXX", NULL);
    char *p = write_tmp(dir, "labels.yaml",
                        "fits:\n  - constant: k\n    cells: [{row: a}]\n");
    GError *e = NULL;
    assert_null(rp_labels_load(p, &e));
    assert_non_null(e);
    assert_non_null(strstr(e->message, "labels.yaml:3:"));
    g_clear_error(&e);
    g_file_set_contents(p, "fits:\n  - constant: k\n    cels: []\n", -1, NULL);
    assert_null(rp_labels_load(p, &e));
    assert_non_null(e);
    assert_non_null(strstr(e->message, "labels.yaml:"));
    g_clear_error(&e);
    g_unlink(p);
    g_rmdir(dir);
    g_free(p);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_labels),
        cmocka_unit_test(test_headline),
        cmocka_unit_test(test_intervals),
        cmocka_unit_test(test_bad_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
