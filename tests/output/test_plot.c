/* test_plot.c — charts from hostile data (issue 32): a text that reaches
 * the gnuplot script (a series cell, a column name, a title or a label)
 * holding backquotes, system("..."), $(...), quotes or line ends stays
 * text: real gnuplot runs the script and a marker file the payload would
 * create does not appear, and the script has no backquote or line outside
 * a single-quoted string; chart names that could leave the folder or hide
 * a file are refused (in a sweep file, with a located error); a failed
 * gnuplot leaves the folder as it was; 200,000 series or categories are
 * refused at once, and 200,000 points of one series are drawn. */
#include "sim/output/plot.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <glib/gstdio.h>

#include "tests/support.h"

/* ---- helpers --------------------------------------------------------- */

static char *tmp_dir(void)
{
    char *d = g_dir_make_tmp("pgsim-plot-XXXXXX", NULL);
    assert_non_null(d);
    return d;
}

/* The sorted names in a folder, joined with spaces (g_free). */
static char *listing(const char *dir)
{
    GPtrArray *names = g_ptr_array_new_with_free_func(g_free);
    GDir *d = g_dir_open(dir, 0, NULL);
    const char *e;
    while (d && (e = g_dir_read_name(d)))
        g_ptr_array_add(names, g_strdup(e));
    if (d)
        g_dir_close(d);
    g_ptr_array_sort(names, (GCompareFunc)g_strcmp0);
    g_ptr_array_add(names, NULL);
    char *s = g_strjoinv(" ", (char **)names->pdata);
    g_ptr_array_free(names, TRUE);
    return s;
}

static char *read_text(const char *dir, const char *file)
{
    char *path = g_build_filename(dir, file, NULL), *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    g_free(path);
    return text;
}

/* A gnuplot script is safe when every backquote is inside a
 * single-quoted string (where gnuplot substitutes nothing) and every line
 * is a comment, a set, a plot or a continued plot clause (a line end
 * inside a string would start a new command, such as `!cmd`). */
static void assert_script_safe(const char *gp)
{
    gboolean sq = FALSE, dq = FALSE, cont = FALSE, bol = TRUE;
    for (const char *c = gp; *c; c++) {
        if (bol) {
            if (sq || dq)
                fail_msg("a string spans lines:\n%s", gp);
            if (!cont && !g_str_has_prefix(c, "# ") &&
                !g_str_has_prefix(c, "set ") && !g_str_has_prefix(c, "plot "))
                fail_msg("a line that is no command of ours: %.40s\n%s", c,
                         gp);
            bol = FALSE;
        }
        if (*c == '\n') {
            cont = c > gp && c[-1] == '\\' && !sq && !dq;
            bol = TRUE;
        } else if (*c == '`' && !sq) {
            fail_msg("a backquote outside single quotes:\n%s", gp);
        } else if (*c == '#' && !sq && !dq) {
            while (c[1] && c[1] != '\n')
                c++;
        } else if (*c == '\'' && !dq) {
            sq = !sq; /* '' inside a string: closes and reopens */
        } else if (*c == '"' && !sq) {
            dq = !dq;
        } else if (*c == '\\' && dq && c[1]) {
            c++;
        }
    }
}

static DataTable *table3(const char *x, const char *y, const char *s)
{
    GPtrArray *cols = g_ptr_array_new();
    g_ptr_array_add(cols, (gpointer)x);
    g_ptr_array_add(cols, (gpointer)y);
    g_ptr_array_add(cols, (gpointer)s);
    DataTable *t = dt_new(cols);
    g_ptr_array_free(cols, TRUE);
    return t;
}

static void add3(DataTable *t, const char *x, const char *y, const char *s)
{
    char *row[] = {(char *)x, (char *)y, (char *)s};
    dt_add_row(t, row);
}

/* ---- hostile strings ------------------------------------------------- */

/* Payloads that each create `marker` if gnuplot runs them. */
static char **payloads(const char *marker)
{
    char **p = g_new0(char *, 8);
    p[0] = g_strdup_printf("`touch %s`", marker);
    p[1] = g_strdup_printf("\" . system(\"touch %s\") . \"", marker);
    p[2] = g_strdup_printf("' . system('touch %s') . '", marker);
    p[3] = g_strdup_printf("a\n!touch %s\n#", marker);
    p[4] = g_strdup_printf("a'\nsystem \"touch %s\"\n'", marker);
    p[5] = g_strdup_printf("$(touch %s) \\\" \\' \\", marker);
    p[6] = g_strdup_printf("\\`touch %s\\` \\\\`touch %s`", marker, marker);
    return p;
}

/* One chart with the payload in slot `slot` (0 a series cell, 1-3 the x,
 * y and series column names, 4-6 title, x and y label, 7 a later series
 * cell): drawn by gnuplot, no marker, a safe script. */
static void chart_with(const char *dir, const char *marker, const char *pay,
                       int slot)
{
    const char *x = slot == 1 ? pay : "n", *y = slot == 2 ? pay : "t";
    const char *s = slot == 3 ? pay : "kind";
    DataTable *t = table3(x, y, s);
    const char *cell = slot == 0 ? pay : "plain";
    add3(t, "1", "2", cell);
    add3(t, "2", "3", cell);
    add3(t, "2", "4", "other");
    add3(t, "3", "1", slot == 7 ? pay : "other");
    PlotSpec *p = plot_spec_new("c", x, y);
    p->series = g_strdup(s);
    p->title = slot == 4 ? g_strdup(pay) : NULL;
    p->xlabel = slot == 5 ? g_strdup(pay) : NULL;
    p->ylabel = slot == 6 ? g_strdup(pay) : NULL;
    GError *err = NULL;
    gboolean ok = plot_render(p, t, dir, &err);
    if (!ok)
        fail_msg("slot %d, payload '%s': %s", slot, pay, err->message);
    if (g_file_test(marker, G_FILE_TEST_EXISTS))
        fail_msg("slot %d, payload '%s' ran a command", slot, pay);
    char *gp = read_text(dir, "c.gp");
    assert_script_safe(gp);
    g_free(gp);
    plot_spec_free(p);
    dt_free(t);
}

static void test_hostile_text_stays_text(void **state)
{
    (void)state;
    char *gnuplot = g_find_program_in_path("gnuplot");
    if (!gnuplot)
        skip(); /* scripts/deps.sh installs it for make test */
    g_free(gnuplot);
    char *dir = tmp_dir();
    char *marker = g_build_filename(dir, "MARKER", NULL);
    char **pay = payloads(marker);
    for (int i = 0; pay[i]; i++)
        for (int slot = 0; slot < 8; slot++)
            chart_with(dir, marker, pay[i], slot);
    /* a categorical x whose labels are payloads (the xtic column) */
    DataTable *t = table3("x", "y", "s");
    add3(t, pay[0], "1", "a");
    add3(t, pay[3], "2", "a");
    PlotSpec *p = plot_spec_new("cat", "x", "y");
    assert_true(plot_render(p, t, dir, NULL));
    assert_false(g_file_test(marker, G_FILE_TEST_EXISTS));
    plot_spec_free(p);
    dt_free(t);
    g_strfreev(pay);
    g_free(marker);
    support_rm_tree(dir);
    g_free(dir);
}

/* ---- names ----------------------------------------------------------- */

static void test_bad_names_refused(void **state)
{
    (void)state;
    const char *bad[] = {"../../x", "a/b",  ".hidden",  "-o",
                         "x`touch M`", "a b", "a\nb", "",
                         "..", "/abs", "x'y", "a\"b"};
    char *top = tmp_dir();
    char *dir = g_build_filename(top, "a", "b", NULL);
    DataTable *t = table3("x", "y", "s");
    add3(t, "1", "2", "a");
    for (size_t i = 0; i < G_N_ELEMENTS(bad); i++) {
        PlotSpec *p = plot_spec_new(bad[i], "x", "y");
        GError *err = NULL;
        assert_false(plot_render(p, t, dir, &err));
        assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_INPUT));
        if (!strstr(err->message, "expected a name of letters"))
            fail_msg("%s: %s", bad[i], err->message);
        g_error_free(err);
        plot_spec_free(p);
    }
    char *l = listing(top);
    assert_string_equal(l, ""); /* nothing written, not even the folder */
    g_free(l);
    const char *good[] = {"frame-vs-nodes", "kurc96-fig1a", "a.b_c+d",
                          "_x", "9"};
    for (size_t i = 0; i < G_N_ELEMENTS(good); i++)
        assert_true(plot_name_ok(good[i]));
    assert_false(plot_name_ok(NULL));
    char *longest = g_strnfill(PLOT_NAME_MAX, 'a');
    assert_true(plot_name_ok(longest));
    char *longer = g_strnfill(PLOT_NAME_MAX + 1, 'a');
    assert_false(plot_name_ok(longer));
    g_free(longest);
    g_free(longer);
    dt_free(t);
    g_free(dir);
    support_rm_tree(top);
    g_free(top);
}

static void test_spec_name_located(void **state)
{
    (void)state;
    const char *yaml = "- {x: a, y: b}\n- {x: a, y: b, name: ../../x}\n";
    GError *err = NULL;
    CfgNode *root = cfg_load_string(yaml, "p.yaml", &err);
    assert_non_null(root);
    GPtrArray *specs = g_ptr_array_new_with_free_func(plot_spec_free);
    assert_false(plot_specs_read(specs, root, &err));
    if (!strstr(err->message, "p.yaml:2:22: found the plot name '../../x', "
                              "expected a name of letters"))
        fail_msg("got: %s", err->message);
    g_error_free(err);
    g_ptr_array_free(specs, TRUE);
    cfg_free(root);
}

/* ---- failures leave nothing ------------------------------------------ */

/* A folder holding a `gnuplot` that runs `body` (sh), put first on PATH;
 * returns the old PATH (g_free). */
static char *fake_gnuplot(const char *bin, const char *body)
{
    char *path = g_build_filename(bin, "gnuplot", NULL);
    char *text = g_strdup_printf("#!/bin/sh\n%s\n", body);
    assert_true(g_file_set_contents(path, text, -1, NULL));
    assert_int_equal(g_chmod(path, 0755), 0);
    char *old = g_strdup(g_getenv("PATH"));
    char *now = g_strdup_printf("%s:%s", bin, old ? old : "/usr/bin:/bin");
    g_setenv("PATH", now, TRUE);
    g_free(now);
    g_free(text);
    g_free(path);
    return old;
}

static void test_failed_chart_leaves_nothing(void **state)
{
    (void)state;
    const char *bodies[] = {
        /* fails after an empty PNG */
        ": > \"${1%.gp}.png\"; echo 'line 9: bad' >&2; exit 1",
        /* exits 0 but draws an empty PNG and no SVG */
        ": > \"${1%.gp}.png\"; exit 0",
        /* exits 0 and draws nothing */
        "exit 0",
    };
    char *top = tmp_dir();
    char *bin = g_build_filename(top, "bin", NULL);
    char *dir = g_build_filename(top, "out", NULL);
    g_mkdir(bin, 0755);
    g_mkdir(dir, 0755);
    /* an earlier chart of the same name stays as it was */
    char *old_png = g_build_filename(dir, "c.png", NULL);
    assert_true(g_file_set_contents(old_png, "old", -1, NULL));
    DataTable *t = table3("x", "y", "s");
    add3(t, "1", "2", "a");
    PlotSpec *p = plot_spec_new("c", "x", "y");
    for (size_t i = 0; i < G_N_ELEMENTS(bodies); i++) {
        char *old_path = fake_gnuplot(bin, bodies[i]);
        GError *err = NULL;
        gboolean ok = plot_render(p, t, dir, &err);
        g_setenv("PATH", old_path, TRUE);
        g_free(old_path);
        assert_false(ok);
        assert_non_null(err);
        g_error_free(err);
        char *l = listing(dir), *png = read_text(dir, "c.png");
        assert_string_equal(l, "c.png");
        assert_string_equal(png, "old");
        g_free(png);
        g_free(l);
    }
    plot_spec_free(p);
    dt_free(t);
    g_free(old_png);
    g_free(bin);
    g_free(dir);
    support_rm_tree(top);
    g_free(top);
}

/* ---- size ------------------------------------------------------------ */

static void test_many_series_refused(void **state)
{
    (void)state;
    DataTable *t = table3("x", "y", "s");
    for (int i = 0; i < 200000; i++) {
        char s[24];
        g_snprintf(s, sizeof s, "s%d", i);
        add3(t, "1", "2", s);
    }
    char *dir = tmp_dir();
    PlotSpec *p = plot_spec_new("many", "x", "y");
    p->series = g_strdup("s");
    GError *err = NULL;
    assert_false(plot_render(p, t, dir, &err));
    if (!strstr(err->message, "found a series number 501, 's500' in column "
                              "'s' (data row 501), expected at most 500"))
        fail_msg("got: %s", err->message);
    g_clear_error(&err);
    /* 200,000 categories on x (gnuplot takes minutes over their labels) */
    g_free(p->series);
    p->series = NULL;
    for (guint r = 0; r < t->rows->len; r++) {
        char **row = g_ptr_array_index(t->rows, r);
        g_free(row[0]);
        row[0] = g_strdup_printf("c%u", r);
    }
    assert_false(plot_render(p, t, dir, &err));
    if (!strstr(err->message, "found a category number 1001, 'c1000' in "
                              "column 'x' (data row 1001), expected at most "
                              "1000 categories"))
        fail_msg("got: %s", err->message);
    g_error_free(err);
    char *l = listing(dir);
    assert_string_equal(l, "");
    g_free(l);
    plot_spec_free(p);
    dt_free(t);
    support_rm_tree(dir);
    g_free(dir);
}

/* 200,000 rows of one series over 100,000 x values, each twice, in
 * descending order: one data line per x, ascending, mean/min/max of two
 * (the fake gnuplot draws two non-empty files). */
static void test_many_points_grouped(void **state)
{
    (void)state;
    DataTable *t = table3("x", "y", "s");
    for (int i = 200000 - 1; i >= 0; i--) {
        char x[24], y[24];
        g_snprintf(x, sizeof x, "%d", i / 2);
        g_snprintf(y, sizeof y, "%d", i % 2 ? 3 : 1);
        add3(t, x, y, "a");
    }
    char *top = tmp_dir();
    char *bin = g_build_filename(top, "bin", NULL);
    g_mkdir(bin, 0755);
    char *old_path = fake_gnuplot(
        bin, "echo x > \"${1%.gp}.png\"; echo x > \"${1%.gp}.svg\"");
    PlotSpec *p = plot_spec_new("big", "x", "y");
    p->series = g_strdup("s");
    GError *err = NULL;
    gboolean ok = plot_render(p, t, top, &err);
    g_setenv("PATH", old_path, TRUE);
    g_free(old_path);
    g_assert_no_error(err);
    assert_true(ok);
    char *dat = read_text(top, "big.dat");
    char **lines = g_strsplit(dat, "\n", -1);
    assert_int_equal(g_strv_length(lines), 2 + 100000 + 3);
    assert_string_equal(lines[1], "# series a");
    assert_string_equal(lines[2], "0\t2\t1\t3\t\"0\"");
    assert_string_equal(lines[100001], "99999\t2\t1\t3\t\"99999\"");
    g_strfreev(lines);
    g_free(dat);
    plot_spec_free(p);
    dt_free(t);
    g_free(bin);
    support_rm_tree(top);
    g_free(top);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hostile_text_stays_text),
        cmocka_unit_test(test_bad_names_refused),
        cmocka_unit_test(test_spec_name_located),
        cmocka_unit_test(test_failed_chart_leaves_nothing),
        cmocka_unit_test(test_many_series_refused),
        cmocka_unit_test(test_many_points_grouped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
