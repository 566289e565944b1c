/* test_plot_cli.c — `pgsim plot` on hostile input (issue 32): a CSV whose
 * series column, column names or --title hold backquoted commands,
 * system("...") or $(...) draws its chart and runs nothing; the default
 * chart name made from hostile column names stays in the CSV's folder;
 * an -o name that could run or hide something is refused with exit 2.
 * Runs the built binary with the real gnuplot (skipped without it). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>
#include <glib/gstdio.h>

#include "tests/support.h"

#include "tests/app/cli/pgsim_spawn.h"

static int entries(const char *dir)
{
    GDir *d = g_dir_open(dir, 0, NULL);
    int n = 0;
    while (d && g_dir_read_name(d))
        n++;
    if (d)
        g_dir_close(d);
    return n;
}

static int plot(const char *const *args, char **err)
{
    char *out = NULL;
    int st = test_pgsim(args, &out, err);
    g_free(out);
    return st;
}

static void test_backquoted_series_runs_nothing(void **state)
{
    (void)state;
    char *gnuplot = g_find_program_in_path("gnuplot");
    if (!gnuplot)
        skip(); /* scripts/deps.sh installs it for make test */
    g_free(gnuplot);
    char *top = g_dir_make_tmp("pgsim-plotcli-XXXXXX", NULL);
    char *dir = g_build_filename(top, "d", NULL);
    g_mkdir(dir, 0755);
    char *mark = g_build_filename(top, "X", NULL);
    char *csv = g_build_filename(dir, "r.csv", NULL);
    /* the series cells, the column names and the title are commands */
    char *text = g_strdup_printf(
        "\"$(touch %s)\",\"y`touch %s`\",s\n1,2,`touch %s`\n"
        "2,3,\"system(\"\"touch %s\"\")\"\n3,1,\"a'\n!touch %s\"\n",
        mark, mark, mark, mark, mark);
    assert_true(g_file_set_contents(csv, text, -1, NULL));
    char *x = g_strdup_printf("$(touch %s)", mark);
    char *y = g_strdup_printf("y`touch %s`", mark);
    char *title = g_strdup_printf("`touch %s`", mark);
    const char *args[] = {"plot",     csv,      "--x",     x,     "--y", y,
                          "--series", "s",      "--title", title, NULL};
    char *err = NULL;
    int st = plot(args, &err);
    if (st != 0)
        fail_msg("exit %d: %s", st, err);
    g_free(err);
    assert_false(g_file_test(mark, G_FILE_TEST_EXISTS));
    /* the chart, named from the columns with '_' for the rest, is in d/ */
    assert_int_equal(entries(top), 1);
    assert_int_equal(entries(dir), 5);
    GDir *d = g_dir_open(dir, 0, NULL);
    const char *e;
    while ((e = g_dir_read_name(d)))
        if (strcmp(e, "r.csv") != 0 && !g_str_has_prefix(e, "y_touch_"))
            fail_msg("unexpected file %s", e);
    g_dir_close(d);
    g_free(x);
    g_free(y);
    g_free(title);
    g_free(text);
    g_free(csv);
    g_free(mark);
    g_free(dir);
    support_rm_tree(top);
    g_free(top);
}

static void test_bad_output_names_refused(void **state)
{
    (void)state;
    char *top = g_dir_make_tmp("pgsim-plotcli-XXXXXX", NULL);
    char *csv = g_build_filename(top, "r.csv", NULL);
    assert_true(g_file_set_contents(csv, "x,y\n1,2\n", -1, NULL));
    const char *names[] = {"a`touch X`.png", ".hidden.png", "-o.png",
                           "a b.png", "a'b.png", "$(x).png"};
    for (size_t i = 0; i < G_N_ELEMENTS(names); i++) {
        char *out = g_build_filename(top, names[i], NULL);
        const char *args[] = {"plot", csv, "--x", "x", "--y", "y", "-o",
                              out, NULL};
        char *err = NULL;
        assert_int_equal(plot(args, &err), 2);
        if (!strstr(err, "-o: found the name"))
            fail_msg("%s: %s", names[i], err);
        g_free(err);
        g_free(out);
    }
    assert_int_equal(entries(top), 1);
    g_free(csv);
    support_rm_tree(top);
    g_free(top);
}

/* A sweep file's plot title, labels and series column with commands in
 * them: the sweep draws its chart and runs nothing. */
static void test_sweep_plot_runs_nothing(void **state)
{
    (void)state;
    char *gnuplot = g_find_program_in_path("gnuplot");
    if (!gnuplot)
        skip();
    g_free(gnuplot);
    char *top = g_dir_make_tmp("pgsim-plotcli-XXXXXX", NULL);
    char *mark = g_build_filename(top, "X", NULL);
    char *sweep = test_ring_sweep(top, "4, 8");
    char *text = NULL;
    assert_true(g_file_get_contents(sweep, &text, NULL, NULL));
    char *plots = g_strdup_printf(
        "%splots:\n  - {name: c, x: workload.nodes, y: mean_frame_s, "
        "title: '`touch %s`', xlabel: 'a''\" . system(\"touch %s\") . \"',"
        " ylabel: \"x\\n!touch %s\"}\n",
        text, mark, mark, mark);
    assert_true(g_file_set_contents(sweep, plots, -1, NULL));
    char *od = g_build_filename(top, "o", NULL);
    const char *run[] = {"sweep", sweep, "-q", "-j", "1", "--out", od, NULL};
    char *err = NULL;
    int st = plot(run, &err);
    if (st != 0)
        fail_msg("exit %d: %s", st, err);
    g_free(err);
    assert_false(g_file_test(mark, G_FILE_TEST_EXISTS));
    char *png = g_build_filename(od, "c.png", NULL);
    assert_true(g_file_test(png, G_FILE_TEST_EXISTS));
    g_free(png);
    g_free(od);
    g_free(plots);
    g_free(text);
    g_free(sweep);
    g_free(mark);
    support_rm_tree(top);
    g_free(top);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_backquoted_series_runs_nothing),
        cmocka_unit_test(test_bad_output_names_refused),
        cmocka_unit_test(test_sweep_plot_runs_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
