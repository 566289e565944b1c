/* igehy98.c — seed 002's Argus table from the simulator (igehy98.h).
 *
 * Each cell is one run of the argus workload: an application's config
 * with the row's overrides, frame rate times the row's factor.  Nothing
 * is read from the published table here; the row's role (calibration,
 * prediction or leave-one-out) from setup.yaml becomes the row's note,
 * so the printed table shows which errors are in-sample.  A
 * leave-one-out row reruns a calibration row with, per application, the
 * cost fitted on that cell replaced by its unfitted estimate
 * (`leave_out: {app: {cost, estimate}}`): what the cell would be had it
 * not been used in the fit (first order: the other three costs are
 * each fixed by their own cell).  Cost: 16 runs, each
 * O(triangles + pixels) (about 1 s each on one core).
 */
#include "sim/reproduce/igehy98.h"
#include "sim/output/plot.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/workload/metrics.h"
#include <math.h>

gboolean rp_igehy98_metrics(const RpContext *ctx, const char *path,
                            const char *const *sets,
                            const char *const *names, double *vals,
                            GError **err)
{
    GPtrArray *ov = g_ptr_array_new_with_free_func(g_free);
    for (guint i = 0; sets && sets[i]; i++)
        g_ptr_array_add(ov, g_strdup(sets[i]));
    g_ptr_array_add(ov, g_strdup("run.frames=1"));
    g_ptr_array_add(ov, NULL);
    CfgRun *r =
        rp_run_build(ctx, NULL, path, (const char *const *)ov->pdata, err);
    g_ptr_array_free(ov, TRUE);
    SimResult *res = r ? rp_run_exec(ctx, r, NULL, err) : NULL;
    gboolean ok = res != NULL;
    for (guint i = 0; ok && names[i]; i++)
        ok = wl_get_metric(res, names[i], &vals[i]);
    sim_result_free(res);
    cfg_run_free(r);
    return ok;
}

gboolean rp_igehy98_rate(const RpContext *ctx, const char *path,
                         const char *const *sets, double *hz, GError **err)
{
    static const char *const hz_only[] = {"frame_hz", NULL};
    return rp_igehy98_metrics(ctx, path, sets, hz_only, hz, err);
}

static const char *const roles[] = {"calibration", "prediction",
                                    "leave-one-out", NULL};
static const char *const role_notes[] = {"calibration (fitted)",
                                         "prediction", NULL};

typedef struct {
    const RpContext *ctx;
    char *dir;        /* of setup.yaml */
    const CfgNode *apps;
    GPtrArray *rows;  /* RpRow * */
    DataTable *chart; /* row, hz, application */
} IgRun;

/* The row's sets plus, for a leave-one-out row, the override that puts
 * this application's left-out cost at its estimate; *note says which. */
static char **cell_sets(const CfgNode *row, const char *app, char **sets,
                        char **note, GError **err)
{
    const CfgNode *lo = cfg_get(row, "leave_out");
    const CfgNode *a = lo ? cfg_get(lo, app) : NULL;
    const char *cost = NULL, *est = NULL;
    if (!a)
        return g_strdupv(sets);
    if (!cfg_get_str(a, "cost", TRUE, &cost, err) ||
        !cfg_get_str(a, "estimate", TRUE, &est, err))
        return NULL;
    guint n = g_strv_length(sets);
    char **v = g_new0(char *, n + 2);
    for (guint i = 0; i < n; i++)
        v[i] = g_strdup(sets[i]);
    v[n] = g_strdup_printf("machine.nodes.cpu.costs.%s=%s", cost, est);
    g_free(*note);
    *note = g_strdup_printf("leave-one-out: %s at its estimate %s", cost, est);
    return v;
}

static gboolean app_cell(IgRun *r, const char *row, const char *app,
                         char **sets, double factor, const char *note,
                         GError **err)
{
    const char *rel = NULL;
    if (!cfg_get_str(r->apps, app, TRUE, &rel, err))
        return FALSE;
    char *path = g_build_filename(r->dir, rel, NULL);
    double hz = NAN;
    gboolean ok =
        rp_igehy98_rate(r->ctx, path, (const char *const *)sets, &hz, err);
    g_free(path);
    if (!ok)
        return FALSE;
    char col[32], ys[40];
    g_snprintf(col, sizeof col, "%s_hz", app);
    g_ptr_array_add(r->rows, rp_row_new("1", row, col, factor * hz, note));
    g_snprintf(ys, sizeof ys, "%.17g", factor * hz);
    char *cells[] = {(char *)row, ys, (char *)app};
    dt_add_row(r->chart, cells);
    return TRUE;
}

static gboolean one_row(IgRun *r, const char *name, const CfgNode *row,
                        GError **err)
{
    int role = 0;
    double factor = 1;
    if (!cfg_get_enum(row, "role", TRUE, roles, &role, err) ||
        !cfg_get_double(row, "factor", FALSE, 0, 1e6, &factor, err))
        return FALSE;
    char **sets = rp_sets_of(row, err);
    if (!sets)
        return FALSE;
    gboolean ok = TRUE;
    for (guint a = 0; ok && a < cfg_map_len(r->apps); a++) {
        const char *app = cfg_map_key(r->apps, a);
        char *note = g_strdup(role_notes[role] ? role_notes[role] : "");
        char **v = cell_sets(row, app, sets, &note, err);
        ok = v && app_cell(r, name, app, v, factor, note, err);
        g_strfreev(v);
        g_free(note);
    }
    g_strfreev(sets);
    return ok;
}

static void draw(const DataTable *t, const char *dir)
{
    if (!dir || g_mkdir_with_parents(dir, 0755) != 0)
        return;
    PlotSpec *p = plot_spec_new("igehy98-rates", "row", "hz");
    p->series = g_strdup("application");
    p->style = g_strdup("points");
    p->title = g_strdup("Argus on a 24-processor Origin 2000 (simulated)");
    p->ylabel = g_strdup("frames per second");
    GError *e = NULL;
    if (!plot_render(p, t, dir, &e)) {
        g_printerr("igehy98: chart not drawn: %s\n", e->message);
        g_clear_error(&e);
    }
    plot_spec_free(p);
}

static gboolean igehy98_run(const RpContext *ctx, GPtrArray *rows,
                            GError **err)
{
    CfgNode *root = cfg_load_file(ctx->setup, err);
    if (!root)
        return FALSE;
    static const char *const chart_cols[] = {"row", "hz", "application", NULL};
    IgRun r = {ctx, g_path_get_dirname(ctx->setup), NULL, rows,
               dt_new_named(chart_cols)};
    const CfgNode *rs = NULL;
    gboolean ok = cfg_get_map(root, "applications", TRUE,
                              "a map {nurbs: config, march: config}",
                              &r.apps, err) &&
                  cfg_get_map(root, "rows", TRUE, "a map of rows", &rs, err);
    for (guint i = 0; ok && i < cfg_map_len(rs); i++)
        ok = one_row(&r, cfg_map_key(rs, i), cfg_map_value(rs, i), err);
    const CfgNode *claims = cfg_get(root, "claims");
    if (ok && claims)
        ok = rp_igehy98_claims(ctx, r.dir, claims, r.apps, rows, err);
    if (ok)
        draw(r.chart, ctx->out_dir);
    dt_free(r.chart);
    g_free(r.dir);
    cfg_free(root);
    return ok;
}

const RpPaperOps rp_igehy98 = {
    .name = "igehy98",
    .citation = "igehy98: the parallel graphics API on Argus, a 24-processor "
                "shared-memory machine (Performance of Argus)",
    .setup = "setup.yaml",
    .rows = igehy98_run,
    .cost_s = 4.5, /* measured: user time of `pgsim reproduce igehy98` */
};
