/* test_metric_decl.c — every shipped config's metrics are declared (issue
 * 31): each run config configs/NAME.yaml, a few variants that reach the
 * metrics set only in some modes, and the first and last point of each
 * configs/sweep-NAME.yaml run through the runner (cfg_run_exec), which
 * refuses a result holding a metric its workload does not declare; each
 * sweep chart's y is a sweep column or a declared metric.  The runner's
 * refusal is shown with a workload that sets one undeclared name.
 * A few seconds: the configs are small or made small with overrides. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/run/run.h"
#include "sim/app/sweep/sweep_spec.h"
#include "sim/core/error.h"
#include "sim/output/plot.h"
#include "sim/workload/metrics.h"

/* Loads and runs config (after the overrides); fails the test unless the
 * runner accepts every metric; returns the number of metrics. */
static guint run_tree(CfgRun *run, const char *what)
{
    GError *e = NULL;
    if (!run)
        fail_msg("%s", what);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = cfg_run_exec(run, &o, &e);
    if (!res)
        fail_msg("%s: %s", what, e->message);
    assert_true(wl_check_metrics(run->wl, res, NULL));
    guint n = res->metrics->len;
    sim_result_free(res);
    cfg_run_free(run);
    return n;
}

static guint run_file(const char *path, const char *const *sets)
{
    GError *e = NULL;
    CfgRun *run = cfg_run_load(path, sets, &e);
    if (!run)
        fail_msg("%s: %s", path, e->message);
    return run_tree(run, path);
}

static void test_shipped_configs(void **st)
{
    (void)st;
    GDir *d = g_dir_open("configs", 0, NULL);
    assert_non_null(d);
    guint configs = 0;
    for (const char *f; (f = g_dir_read_name(d));) {
        if (!g_str_has_suffix(f, ".yaml") || g_str_has_prefix(f, "sweep-"))
            continue;
        char *path = g_build_filename("configs", f, NULL);
        assert_true(run_file(path, NULL) >= 3);
        g_free(path);
        configs++;
    }
    g_dir_close(d);
    assert_true(configs >= 10);
}

/* Modes whose metrics the shipped configs do not set. */
static void test_variants(void **st)
{
    (void)st;
    const char *sf_pull[] = {"workload.migration=pull",
                             "workload.bookkeeping=minset",
                             "workload.regions=static", "run.frames=3",
                             "workload.resolution=128", NULL};
    const char *sf_edits[] = {"workload.mastership=dynamic",
                              "workload.edits={matrix: 1, execute: 1, "
                              "unpost: 1, post: 1}",
                              "run.frames=3", "workload.resolution=128", NULL};
    const char *ph_edits[] = {"workload.edits={append: 1, insert: 1, "
                              "delete: 1, unpost: 1, post: 1}",
                              "run.frames=2", NULL};
    const char *dp_cm5[] = {"machine.model=cm5", "workload.processors=32",
                            "workload.width=256", "workload.height=256",
                            "run.fidelity=flow", NULL};
    const char *pn_pp5[] = {"machine.model=pixel-planes-5", NULL};
    assert_int_equal(run_file("configs/sortfirst-vehicle.yaml", sf_pull), 45);
    assert_int_equal(run_file("configs/sortfirst-vehicle.yaml", sf_edits), 52);
    assert_int_equal(run_file("configs/pphigs-flock.yaml", ph_edits), 39);
    assert_int_equal(run_file("configs/dpscan-cm200.yaml", dp_cm5), 18);
    assert_true(run_file("configs/pn-onyx.yaml", pn_pp5) >= 8);
}

/* y of a chart: a column every sweep line has (sweep_run.h) or a metric
 * the workload declares. */
static gboolean sweep_column(const WlOps *w, const char *y)
{
    static const char *const fixed[] = {
        "frames",        "mean_frame_s", "elapsed_s", "events", "comm_bytes",
        "comm_messages", "util_mean",    "util_max",  "nodes_used",
        "nodes_idle",    NULL};
    for (guint i = 0; fixed[i]; i++)
        if (strcmp(fixed[i], y) == 0)
            return TRUE;
    return wl_metric_decl(w, y) != NULL;
}

static const WlOps *run_point(const SweepSpec *s, guint i)
{
    GError *e = NULL;
    SweepPoint pt = sweep_spec_point(s, i);
    CfgNode *cfg = sweep_spec_config(s, &pt, &e);
    CfgRun *run = cfg ? cfg_run_from_tree(cfg, NULL, &e) : NULL;
    char *what = g_strdup_printf("%s point %u: %s", s->path, i,
                                 e ? e->message : "");
    const WlOps *w = run ? run->wl : NULL;
    run_tree(run, what);
    g_free(what);
    return w;
}

static void test_sweeps(void **st)
{
    (void)st;
    GDir *d = g_dir_open("configs", 0, NULL);
    assert_non_null(d);
    guint sweeps = 0;
    for (const char *f; (f = g_dir_read_name(d));) {
        if (!g_str_has_prefix(f, "sweep-") || !g_str_has_suffix(f, ".yaml"))
            continue;
        char *path = g_build_filename("configs", f, NULL);
        GError *e = NULL;
        SweepSpec *s = sweep_spec_load(path, &e);
        if (!s)
            fail_msg("%s: %s", path, e->message);
        const WlOps *w = run_point(s, 0);
        run_point(s, sweep_spec_points(s) - 1);
        for (guint p = 0; p < s->plots->len; p++) {
            const PlotSpec *ps = g_ptr_array_index(s->plots, p);
            if (!sweep_column(w, ps->y))
                fail_msg("%s: chart '%s' plots '%s', which is neither a "
                         "sweep column nor a metric of '%s'",
                         path, ps->name, ps->y, w->name);
        }
        sweep_spec_free(s);
        g_free(path);
        sweeps++;
    }
    g_dir_close(d);
    assert_true(sweeps >= 6);
    /* the chart check can come out false */
    const WlOps *tr = wl_find("tokenring");
    assert_true(sweep_column(tr, "events") && sweep_column(tr, "hops"));
    assert_false(sweep_column(tr, "hopz"));
}

/* tokenring, then one metric it does not declare. */
static gboolean bad_run(const WlContext *ctx, void *params, SimResult *out,
                        GError **err)
{
    if (!wl_find("tokenring")->run(ctx, params, out, err))
        return FALSE;
    sim_result_set_metric(out, "hopz", 1, "");
    return TRUE;
}

static void test_runner_refuses_undeclared(void **st)
{
    (void)st;
    GError *e = NULL;
    CfgRun *run = cfg_run_load("configs/tokenring.yaml", NULL, &e);
    assert_non_null(run);
    WlOps bad = *run->wl;
    bad.run = bad_run;
    run->wl = &bad;
    CfgRunOpts o = {.quiet = TRUE};
    assert_null(cfg_run_exec(run, &o, &e));
    assert_true(g_error_matches(e, SIM_ERROR, SIM_ERROR_INTERNAL));
    assert_non_null(strstr(e->message, "found metric 'hopz'"));
    assert_int_equal(sim_error_exit_status(e), 1);
    g_clear_error(&e);
    cfg_run_free(run);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_configs),
        cmocka_unit_test(test_variants),
        cmocka_unit_test(test_sweeps),
        cmocka_unit_test(test_runner_refuses_undeclared),
    };
    return cmocka_run_group_tests_name("metric_decl", tests, NULL, NULL);
}
