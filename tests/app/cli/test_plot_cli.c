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
    assert_int_equal(support_entries(top), 1);
    assert_int_equal(support_entries(dir), 5);
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
    assert_int_equal(support_entries(top), 1);
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

/* Every bad CSV is refused at its place in the file, "file:line:col:
 * found ..., expected ...", with exit 2 and nothing written: too many
 * series or categories (the line counted through a comment and a quoted
 * field over two lines), a missing column, no numeric row, a --where
 * that keeps nothing, and a file or chart over the memory limit.  Needs
 * no gnuplot (all are refused before it runs). */
static void test_bad_csv_located(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-plotcsv-XXXXXX", NULL);
    GString *ser = g_string_new("# provenance\nx,y,s\n1,2,\"two\nlines\"\n");
    for (int i = 1; i < 600; i++)
        g_string_append_printf(ser, "1,2,s%d\n", i);
    GString *cat = g_string_new("x,y\n");
    for (int i = 0; i < 1200; i++)
        g_string_append_printf(cat, "c%d,2\n", i);
    GString *big = g_string_new("x,y\n");
    for (int i = 0; i < 20000; i++)
        g_string_append_printf(big, "%050d,2\n", i);
    const GString *texts[] = {ser, cat, big};
    const char *names[] = {"ser.csv", "cat.csv", "big.csv"};
    for (int i = 0; i < 3; i++) {
        char *path = g_build_filename(dir, names[i], NULL);
        assert_true(g_file_set_contents(path, texts[i]->str, -1, NULL));
        g_free(path);
    }
    static const struct {
        const char *csv, *x, *y, *more, *more_value, *want;
    } cases[] = {
        {"ser.csv", "x", "y", "--series", "s",
         "ser.csv:504:5: found a series number 501, 's500' in column 's', "
         "expected at most 500 series in chart 'y-vs-x'"},
        {"cat.csv", "x", "y", NULL, NULL,
         "cat.csv:1002:1: found a category number 1001, 'c1000' in column "
         "'x', expected at most 1000 categories in chart 'y-vs-x'"},
        {"cat.csv", "x", "nope", NULL, NULL,
         "cat.csv:1:1: found no column 'nope' for y, expected a column of: "
         "x, y"},
        {"cat.csv", "y", "x", NULL, NULL,
         "cat.csv:1:1: found no row with a number in both 'y' and 'x', "
         "expected at least one"},
        {"cat.csv", "x", "y", "--where", "y=3",
         "cat.csv:1:3: found no row with y=3, expected at least one"},
        {"big.csv", "x", "y", "--mem-limit", "2M",
         "big.csv:1:1: found a CSV file of 40003 cells needing about 3.9 MiB, "
         "expected at most 2.0 MiB (--mem-limit"},
        {"big.csv", "x", "y", "--mem-limit", "5500k",
         "big.csv:1:3: found a chart of 20000 rows needing about 6.1 MiB, "
         "expected at most 5.4 MiB (--mem-limit"},
    };
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++) {
        char *csv = g_build_filename(dir, cases[i].csv, NULL);
        const char *args[] = {"plot", csv, "--x", cases[i].x, "--y",
                              cases[i].y, cases[i].more, cases[i].more_value,
                              NULL};
        char *err = NULL;
        int st = plot(args, &err);
        if (st != 2 || !strstr(err, cases[i].want))
            fail_msg("case %u: exit %d, stderr '%s', expected 2 and '%s'", i,
                     st, err, cases[i].want);
        assert_int_equal(support_entries(dir), 3); /* nothing written */
        g_free(err);
        g_free(csv);
    }
    g_string_free(ser, TRUE);
    g_string_free(cat, TRUE);
    g_string_free(big, TRUE);
    support_rm_tree(dir);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_backquoted_series_runs_nothing),
        cmocka_unit_test(test_bad_output_names_refused),
        cmocka_unit_test(test_sweep_plot_runs_nothing),
        cmocka_unit_test(test_bad_csv_located),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
