/* test_rp_bounds.c — each paper's agreement may not get worse unnoticed
 * (issue 33, point 3).
 *
 * Each paper runs as `pgsim reproduce NAME` does (faithful fidelity, its
 * real setup and labels) and its out-of-sample headline (rp_labels.h:
 * predicted cells at their error, cross-validated cells at their
 * leave-one-out error) must stay within MARGIN of today's, over as many
 * cells as today.  Today's figures (at d9d59a6, the commit that
 * labelled the cells) are the table below; a change that
 * improves a paper should lower its line here.  mueller97 has no
 * published value to compare (published.yaml), so its bound is on its
 * computed claims: as many must hold as today.
 *
 * test_bound_can_fail shows the check failing: ellsworth90 with
 * Pixel-Planes 5's matrix_concat at 5 us instead of its fitted 57.28 us
 * (a copy of models/pixel-planes-5.yaml shadowing the real one, found
 * first in the working directory; PGSIM_DATA points at the checkout for
 * the rest) moves its out-of-sample error from 3.7 % over 16 cells to
 * 8.2 % over its 4 predicted cells: the fitted cells move, so its
 * loo.yaml is stale and gives no leave-one-out value.
 *
 * Cost: one faithful pass of every paper (about 65 s of CPU, half of it
 * mueller97's 120-frame revolution).
 */
#include "sim/reproduce/rp_driver.h"
#include <glib/gstdio.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

/* How much worse the out-of-sample mean |rel_error| may get: one
 * percentage point, unless a paper's line says otherwise. */
#define MARGIN 0.01

typedef struct {
    const char *paper;
    guint cells;      /* out-of-sample cells today */
    double oos_mean;  /* today's out-of-sample mean |rel_error| */
    double margin;    /* how much worse it may get; 0: MARGIN */
} Bound;

static const Bound bounds[] = {
    {"ortega93", 18, 0.0754, 0},    /* 18 cross-validated CM-200 times */
    /* 12 cross-validated (stored loo.yaml; was 4 cells at 4.23 % before
     * it) and 4 predicted speedup_4 cells.  The stored leave-one-out
     * values cannot move (a change that moves a fitted cell makes
     * loo.yaml stale and the cell count fails), so only the 4 predicted
     * cells can: a quarter of a point over 16 cells is the old point
     * over those 4. */
    {"ellsworth90", 16, 0.0374, 0.0025},
    {"kurc96", 36, 0.0498, 0},      /* 36 cross-validated P=16 cells */
    {"igehy98", 12, 0.1799, 0},     /* 4 cross-validated, 8 predicted */
};

static RpTable *drive(const char *name)
{
    const RpPaperOps *rp = rp_find(name);
    assert_non_null(rp);
    RpContext ctx = {.fidelity = RP_DEFAULT_FIDELITY, .quiet = TRUE};
    GError *err = NULL;
    RpTable *t = rp_drive(rp, RP_PAPERS_DIR, &ctx, &err);
    if (!t)
        fail_msg("%s: %s", name, err->message);
    assert_true(t->labelled);
    return t;
}

static const Bound *bound_of(const char *name)
{
    for (guint i = 0; i < G_N_ELEMENTS(bounds); i++)
        if (strcmp(bounds[i].paper, name) == 0)
            return &bounds[i];
    fail_msg("no bound for %s", name);
    return NULL;
}

/* TRUE when t is within its paper's bound. */
static gboolean within(const RpTable *t, const Bound *b)
{
    double m = b->margin > 0 ? b->margin : MARGIN;
    printf("%s: out-of-sample %.2f%% over %u cells (bound %.2f%% over %u)\n",
           t->paper, 100 * t->oos_mean, t->oos_n, 100 * (b->oos_mean + m),
           b->cells);
    return t->oos_n == b->cells && t->oos_mean <= b->oos_mean + m;
}

static void check(const char *name)
{
    RpTable *t = drive(name);
    assert_true(within(t, bound_of(name)));
    rp_table_free(t);
}

static void test_ortega93(void **state)
{
    (void)state;
    check("ortega93");
}

static void test_ellsworth90(void **state)
{
    (void)state;
    check("ellsworth90");
}

static void test_kurc96(void **state)
{
    (void)state;
    check("kurc96");
}

static void test_igehy98(void **state)
{
    (void)state;
    check("igehy98");
}

static void test_mueller97(void **state)
{
    (void)state;
    RpTable *t = drive("mueller97");
    guint hold = 0, claims = 0;
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        if (j->label == RP_LABEL_CLAIM && strcmp(j->column, "holds") == 0) {
            claims++;
            hold += j->sim == 1.0;
        }
    }
    assert_int_equal(t->oos_n, 0); /* nothing published to compare */
    assert_int_equal(claims, 8);
    assert_true(hold >= 6); /* C2 and C7 do not hold today */
    rp_table_free(t);
}

/* A copy of models/<model>.yaml with `from` replaced by `to` in a new
 * directory that becomes the working directory; returns it. */
static char *shadow_model(const char *model, const char *from, const char *to,
                          char **home)
{
    char *rel = g_strdup_printf("models/%s.yaml", model), *text = NULL;
    assert_true(g_file_get_contents(rel, &text, NULL, NULL));
    assert_non_null(strstr(text, from));
    GString *s = g_string_new(text);
    g_string_replace(s, from, to, 1);
    char *dir = g_dir_make_tmp("pgsim-bound-XXXXXX", NULL);
    char *mdir = g_build_filename(dir, "models", NULL);
    char *path = g_build_filename(dir, rel, NULL);
    assert_int_equal(g_mkdir(mdir, 0755), 0);
    assert_true(g_file_set_contents(path, s->str, -1, NULL));
    *home = g_get_current_dir();
    g_setenv("PGSIM_DATA", *home, TRUE);
    assert_int_equal(g_chdir(dir), 0);
    g_free(rel);
    g_free(text);
    g_string_free(s, TRUE);
    g_free(mdir);
    g_free(path);
    return dir;
}

static void test_bound_can_fail(void **state)
{
    (void)state;
    char *home = NULL;
    char *dir = shadow_model("pixel-planes-5", "value: 57.28 us",
                             "value: 5 us", &home);
    RpTable *t = drive("ellsworth90");
    assert_int_equal(g_chdir(home), 0);
    g_unsetenv("PGSIM_DATA");
    char *m = g_build_filename(dir, "models", "pixel-planes-5.yaml", NULL);
    char *md = g_build_filename(dir, "models", NULL);
    g_unlink(m);
    g_rmdir(md);
    g_rmdir(dir);
    assert_false(within(t, bound_of("ellsworth90")));
    assert_true(t->oos_mean > 0.07);
    assert_int_equal(t->loo_n, 0); /* loo.yaml is stale at 5 us */
    rp_table_free(t);
    g_free(m);
    g_free(md);
    g_free(dir);
    g_free(home);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ortega93),   cmocka_unit_test(test_ellsworth90),
        cmocka_unit_test(test_kurc96),     cmocka_unit_test(test_igehy98),
        cmocka_unit_test(test_mueller97),  cmocka_unit_test(test_bound_can_fail),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
