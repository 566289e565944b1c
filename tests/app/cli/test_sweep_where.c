/* test_sweep_where.c — a sweep chart's where: {COLUMN: VALUE} (plot.c,
 * cmd_sweep.c): over two swept parameters, a chart keeping one value of
 * the second is drawn with only those rows (the title says which), a
 * where that keeps no row is reported as a chart not drawn, naming the
 * filter, and a where on a column that is not there likewise; a
 * non-scalar value is refused at its place in the sweep file. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>

#include "tests/support.h"

#include "tests/app/cli/pgsim_spawn.h"

static void test_where_charts(void **state)
{
    (void)state;
    char *gnuplot = g_find_program_in_path("gnuplot");
    if (!gnuplot)
        skip();
    g_free(gnuplot);
    char *top = g_dir_make_tmp("pgsim-sweepwhere-XXXXXX", NULL);
    char *sweep = test_ring_sweep(top, "4, 8");
    char *text = NULL;
    assert_true(g_file_get_contents(sweep, &text, NULL, NULL));
    char *more =
        g_strdup_printf("%s  workload.compute: [20 us, 40 us]\nplots:\n"
                        "  - {name: a, x: workload.nodes, y: mean_frame_s, "
                        "where: {workload.compute: 40 us}}\n"
                        "  - {name: b, x: workload.nodes, y: mean_frame_s, "
                        "where: {workload.compute: 99 us}}\n"
                        "  - {name: c, x: workload.nodes, y: mean_frame_s, "
                        "where: {no_such: 1}}\n",
                        text);
    assert_true(g_file_set_contents(sweep, more, -1, NULL));
    char *od = g_build_filename(top, "o", NULL);
    const char *run[] = {"sweep", sweep, "-q", "-j", "1", "--out", od, NULL};
    char *out = NULL, *err = NULL;
    test_pgsim(run, &out, &err);
    char *gp = g_build_filename(od, "a.gp", NULL), *script = NULL;
    assert_true(g_file_get_contents(gp, &script, NULL, NULL));
    assert_non_null(strstr(script, "workload.compute=40 us"));
    char *dat = g_build_filename(od, "a.dat", NULL), *rows = NULL;
    assert_true(g_file_get_contents(dat, &rows, NULL, NULL));
    guint points = 0; /* data lines: the 2 nodes at 40 us, not 4 */
    for (const char *c = rows; *c; c++)
        points += (c == rows || c[-1] == '\n') && g_ascii_isdigit(*c);
    assert_int_equal(points, 2);
    if (!strstr(err, "chart b not drawn") ||
        !strstr(err, "no row with workload.compute=99 us") ||
        !strstr(err, "chart c not drawn") || !strstr(err, "no_such"))
        fail_msg("%s", err);
    g_free(rows);
    g_free(dat);
    g_free(script);
    g_free(gp);
    g_free(out);
    g_free(err);
    g_free(od);
    g_free(more);
    g_free(text);
    g_free(sweep);
    support_rm_tree(top);
    g_free(top);
}

static void test_where_refused(void **state)
{
    (void)state;
    char *top = g_dir_make_tmp("pgsim-sweepwhere-XXXXXX", NULL);
    char *sweep = test_ring_sweep(top, "4, 8");
    char *text = NULL;
    assert_true(g_file_get_contents(sweep, &text, NULL, NULL));
    char *more = g_strdup_printf("%splots:\n  - {x: workload.nodes, y: "
                                 "mean_frame_s, where: {a: [1, 2]}}\n",
                                 text);
    assert_true(g_file_set_contents(sweep, more, -1, NULL));
    const char *run[] = {"sweep", sweep, "-q", "-j", "1", NULL};
    char *out = NULL, *err = NULL;
    assert_int_equal(test_pgsim(run, &out, &err), 2);
    if (!strstr(err, "s.yaml:6:") || !strstr(err, "non-scalar 'where'"))
        fail_msg("%s", err);
    g_free(out);
    g_free(err);
    g_free(more);
    g_free(text);
    g_free(sweep);
    support_rm_tree(top);
    g_free(top);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_where_charts),
        cmocka_unit_test(test_where_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
