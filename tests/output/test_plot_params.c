/* test_plot_params.c — charts that do not mislead (issue 33, point 5): a
 * sweep chart never averages over a swept parameter it does not plot (the
 * issue's machines x processors sweep drawn without series gets one
 * series per machine; with a series, or two such parameters, it is
 * refused, naming them); bars say they span repetitions; log axes carry
 * a labelled tick per decade; the key sits below the plot; --where
 * filters appear in the title.  Text only: no gnuplot is run. */
#include "sim/output/plot.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

/* Machines x processors, two repetitions: a cluster 3000x faster. */
static const char sweep_csv[] =
    "point,repetition,seed,machine.model,workload.processors,"
    "workload.scheme,status,error,mean_frame_s\n"
    "0,0,1,ipsc2,2,pair,ok,,0.1\n"
    "0,1,2,ipsc2,2,pair,ok,,0.12\n"
    "1,0,1,ipsc2,4,pair,ok,,0.05\n"
    "2,0,1,cluster-ib,2,pair,ok,,0.00003\n"
    "3,0,1,cluster-ib,4,pair,ok,,0.000016\n";

static DataTable *table(void)
{
    GError *err = NULL;
    DataTable *t = dt_parse_csv(sweep_csv, "t.csv", &err);
    g_assert_no_error(err);
    return t;
}

static gboolean texts(const PlotSpec *p, GString **dat, GString **gp,
                      GError **err)
{
    DataTable *t = table();
    gboolean ok = plot_texts(p, t, dat, gp, err);
    dt_free(t);
    return ok;
}

static void test_split_by_unplotted(void **state)
{
    (void)state;
    PlotSpec *p = plot_spec_new("c", "workload.processors", "mean_frame_s");
    p->logy = TRUE;
    GString *dat, *gp;
    GError *err = NULL;
    assert_true(texts(p, &dat, &gp, &err));
    /* one series per machine, never their mean (0.0x s) */
    assert_non_null(strstr(gp->str, "title 'machine.model=ipsc2'"));
    assert_non_null(strstr(gp->str, "title 'machine.model=cluster-ib'"));
    assert_null(strstr(dat->str, "\t0.05001"));
    /* bars: repetitions, said in the key */
    assert_non_null(strstr(gp->str, "keyentry with yerrorbars"));
    assert_non_null(strstr(gp->str, "'bars: min to max over the "
                                    "repetitions (point: mean)'"));
    /* y spans 1.6e-5 .. 0.12: every decade labelled, the key below */
    assert_non_null(strstr(gp->str, "set yrange [1e-05:0.2]\n"
                                    "set format y '%g'\nset mytics 10\n"
                                    "set ytics (1e-05, 0.0001, 0.001, "
                                    "0.01, 0.1)\n"));
    assert_non_null(strstr(gp->str, "set key below"));
    g_string_free(dat, TRUE);
    g_string_free(gp, TRUE);
    plot_spec_free(p);
}

static void test_refused_naming_it(void **state)
{
    (void)state;
    PlotSpec *p = plot_spec_new("c", "workload.processors", "mean_frame_s");
    p->series = g_strdup("workload.scheme");
    GString *dat = NULL, *gp = NULL;
    GError *err = NULL;
    assert_false(texts(p, &dat, &gp, &err));
    assert_non_null(err);
    assert_non_null(strstr(err->message, "differ in the swept parameter "
                                         "'machine.model' ('ipsc2' and "
                                         "'cluster-ib' where "
                                         "workload.processors = 2)"));
    g_clear_error(&err);
    plot_spec_free(p);
}

static void test_where_in_title_and_decades(void **state)
{
    (void)state;
    PlotSpec *p = plot_spec_new("c", "workload.processors", "mean_frame_s");
    p->series = g_strdup("machine.model");
    p->where = g_strdup("workload.scheme=pair");
    p->logx = TRUE;
    GString *dat, *gp;
    GError *err = NULL;
    assert_true(texts(p, &dat, &gp, &err));
    assert_non_null(strstr(gp->str, "(rows where workload.scheme=pair)'"));
    /* x 2..4 inside one decade: 1-2-5 ticks, so never one lone label */
    assert_non_null(strstr(gp->str, "set xrange [2:5]\n"));
    assert_non_null(strstr(gp->str, "set xtics (2, 5)\n"));
    g_string_free(dat, TRUE);
    g_string_free(gp, TRUE);
    plot_spec_free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_split_by_unplotted),
        cmocka_unit_test(test_refused_naming_it),
        cmocka_unit_test(test_where_in_title_and_decades),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
