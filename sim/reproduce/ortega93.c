/* ortega93.c — seed 004's Tables 1-4 from the simulator (ortega93.h).
 *
 * For each data set, resolution and table, one run of workload dpscan
 * through the runner (sim/run/run.h) on the table's machine model, its
 * first partition the machine's and every partition costed from the same
 * render (workload.partitions); the cells are read from the run's
 * declared metrics (time_s@P, polygons).  On a SIMD machine a second run
 * with dpscan.send_slice overridden to 0 gives each cell's time as a
 * line in send_slice (ortega93_cv.c).  Nothing is read from the
 * published tables here.  Cost: 12 runs plus 6 for the fit, each O(spans
 * + segments x partitions).
 */
#include "sim/reproduce/ortega93.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/machine/model_param.h"
#include "sim/raster/scan.h"
#include "sim/run/run.h"
#include "sim/workload/metrics.h"
#include <math.h>
#include <stdio.h>

typedef struct {
    const RpContext *ctx;
    const CfgNode *root;
    char *dir;       /* directory of the sweep file */
    GPtrArray *rows; /* RpRow * */
    FILE *coef;      /* PGSIM_DP_COEF or NULL */
    GArray *simd;    /* RpOrCell of every SIMD cell, for table "cv" */
} OrRun;

/* Loads the scene file named by scenes.<key>: its whole document. */
static CfgNode *load_scene(OrRun *r, const char *key, GError **err)
{
    const char *rel = NULL;
    if (!cfg_get_str(cfg_get(r->root, "scenes"), key, TRUE, &rel, err))
        return NULL;
    char *path = g_build_filename(r->dir, rel, NULL);
    CfgNode *doc = cfg_load_file(path, err);
    g_free(path);
    if (doc && !cfg_get(doc, "scene")) {
        cfg_error(err, doc, "no scene: section", "a scene file");
        cfg_free(doc);
        return NULL;
    }
    return doc;
}

static void partition_name(uint64_t p, char *buf, size_t n)
{
    if (p >= 1024 && p % 1024 == 0)
        g_snprintf(buf, n, "%" G_GUINT64_FORMAT "K", p / 1024);
    else
        g_snprintf(buf, n, "%" G_GUINT64_FORMAT, p);
}

/* The run config of one table at w x h: its machine model at its first
 * partition, every partition costed, the scene `scene` (a section of
 * another file, copied with its locations). */
static CfgNode *table_tree(const OrRun *r, const CfgNode *tab,
                           const CfgNode *scene, int w, int h, GError **err)
{
    const CfgNode *parts = cfg_get(tab, "partitions");
    if (!cfg_get(tab, "machine") || cfg_kind(parts) != CFG_SEQ ||
        cfg_seq_len(parts) == 0) {
        cfg_error(err, parts ? parts : tab, "no machine or partition list",
                  "machine: NAME, partitions: [n, ...]");
        return NULL;
    }
    char *text = g_strdup_printf("schema_version: 1\n"
                                 "machine: {}\n"
                                 "workload: {type: dpscan, width: %d, "
                                 "height: %d, wire: formula}\n",
                                 w, h);
    CfgNode *root = cfg_load_string(text, "<ortega93 run>", err);
    g_free(text);
    if (!root)
        return NULL;
    CfgNode *wl = (CfgNode *)cfg_get(root, "workload");
    cfg_map_put((CfgNode *)cfg_get(root, "machine"), "model",
                cfg_copy(cfg_get(tab, "machine")));
    cfg_map_put(wl, "processors", cfg_copy(cfg_seq_at(parts, 0)));
    cfg_map_put(wl, "partitions", cfg_copy(parts));
    const CfgNode *bf = cfg_get(r->root, "buffer_factor");
    cfg_map_put(wl, "buffer_factor",
                bf ? cfg_copy(bf) : cfg_load_string("1", "<ortega93>", NULL));
    cfg_map_put(root, "scene", cfg_copy(scene));
    return root;
}

/* Runs `tree` (taken) with `set` (may be NULL): the result, and in *send
 * the machine's dpscan.send_slice on a SIMD machine (else 0). */
static SimResult *run_tree(const OrRun *r, CfgNode *tree, const char *set,
                           SimTime *send, GError **err)
{
    const char *const sets[] = {set, NULL};
    CfgRun *run = rp_run_build_as_is(r->ctx, tree, sets, err);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = run ? cfg_run_exec(run, &o, err) : NULL;
    const CfgNode *sec =
        res ? cfg_get(mach_model_cfg(run->machine_built), "dpscan") : NULL;
    *send = 0;
    if (sec && !g_strcmp0(mach_param_word(sec, "arch"), "simd") &&
        !mach_param_time(sec, "send_slice", TRUE, send, err)) {
        sim_result_free(res);
        res = NULL;
    }
    cfg_run_free(run);
    return res;
}

/* Metric NAME@P of res. */
static double at_p(const SimResult *res, const char *name, uint64_t p)
{
    char *full = g_strdup_printf("%s@%" G_GUINT64_FORMAT, name, p);
    double v = wl_metric(res, full);
    g_free(full);
    return v;
}

/* A time in seconds back in picoseconds (exact below 2^53 ps). */
static int64_t ps_of(double s)
{
    return (int64_t)llround(s * 1e12);
}

/* Cell (table, row) at partition p as a line a + s * b in send_slice s:
 * b from the run at the model's send_slice (res) and the run at 0
 * (zero); exact, or FALSE with *err when the time is not linear in it. */
static gboolean simd_cell(OrRun *r, const char *table, const char *row,
                          uint64_t p, const SimResult *res,
                          const SimResult *zero, SimTime send, GError **err)
{
    double t = at_p(res, "time_s", p);
    int64_t d = ps_of(t) - ps_of(at_p(zero, "time_s", p));
    if (send == 0 || d < 0 || d % (int64_t)send != 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                    "ortega93: table %s row %s: the time is not linear in "
                    "dpscan.send_slice (%" G_GINT64_FORMAT " ps at 0)",
                    table, row, d);
        return FALSE;
    }
    RpOrCell c = {.b = (double)(d / (int64_t)send),
                  .s = sim_time_to_s(send)};
    g_strlcpy(c.table, table, sizeof c.table);
    g_strlcpy(c.row, row, sizeof c.row);
    c.a = t - c.s * c.b;
    g_array_append_val(r->simd, c);
    return TRUE;
}

/* The linear coefficients of a SIMD cell (PGSIM_DP_COEF, for
 * scripts/fit-ortega93.py). */
static void coef_line(OrRun *r, const char *table, const char *row,
                      const SimResult *res, uint64_t p)
{
    static const char *const keys[] = {"op", "step", "scan_slice",
                                       "send_setup", "send_slice", "send_vp",
                                       "news_slice", "send_msg"};
    fprintf(r->coef, "%s,%s", table, row);
    for (guint k = 0; k < G_N_ELEMENTS(keys); k++) {
        char *name = g_strdup_printf("%s_count", keys[k]);
        fprintf(r->coef, ",%.0f", at_p(res, name, p));
        g_free(name);
    }
    fprintf(r->coef, ",%.0f,%.0f,%.0f\n", wl_metric(res, "scan_iters"),
            wl_metric(res, "pixel_iters"), wl_metric(res, "flushes"));
}

/* Table `table` at w x h on scene `scene`: its rows (and SIMD cells). */
static gboolean table_cells(OrRun *r, const char *table, const CfgNode *tab,
                            const CfgNode *scene, int w, int h, GError **err)
{
    CfgNode *tree = table_tree(r, tab, scene, w, h, err);
    SimTime send = 0, zs = 0;
    SimResult *res = tree ? run_tree(r, tree, NULL, &send, err) : NULL;
    SimResult *zero =
        res && send ? run_tree(r, table_tree(r, tab, scene, w, h, err),
                               "machine.dpscan.send_slice=0 us", &zs, err)
                    : NULL;
    gboolean ok = res && (!send || zero);
    const CfgNode *parts = cfg_get(tab, "partitions");
    for (guint i = 0; ok && i < cfg_seq_len(parts); i++) {
        uint64_t p = 0;
        if (!(ok = cfg_parse_count(cfg_scalar(cfg_seq_at(parts, i)),
                                   "partition", &p, err)))
            break;
        char part[32], row[64];
        partition_name(p, part, sizeof part);
        g_snprintf(row, sizeof row, "%s/%dx%d", part, w, h);
        double t = at_p(res, "time_s", p);
        g_ptr_array_add(r->rows, rp_row_new(table, row, "time_s", t, NULL));
        g_ptr_array_add(r->rows,
                        rp_row_new(table, row, "polygons_per_s",
                                   wl_metric(res, "polygons") / t, NULL));
        if (ok && send)
            ok = simd_cell(r, table, row, p, res, zero, send, err);
        if (ok && send && r->coef)
            coef_line(r, table, row, res, p);
    }
    sim_result_free(res);
    sim_result_free(zero);
    return ok;
}

/* Every table that uses scene `key` at w x h, in table order. */
static gboolean render_tables(OrRun *r, const char *key, const CfgNode *scene,
                              int w, int h, GError **err)
{
    const CfgNode *tabs = cfg_get(r->root, "tables");
    gboolean ok = TRUE;
    for (guint t = 0; ok && t < cfg_map_len(tabs); t++) {
        const CfgNode *tab = cfg_map_value(tabs, t);
        const char *sk = NULL;
        ok = cfg_get_str(tab, "scene", TRUE, &sk, err) &&
             (g_strcmp0(sk, key) != 0 ||
              table_cells(r, cfg_map_key(tabs, t), tab, scene, w, h, err));
    }
    return ok;
}

static gboolean read_res(const CfgNode *res, int *w, int *h, GError **err)
{
    int64_t v[2];
    for (guint k = 0; k < 2; k++) {
        const char *s = cfg_kind(res) == CFG_SEQ && cfg_seq_len(res) == 2
                            ? cfg_scalar(cfg_seq_at(res, k))
                            : NULL;
        char *end = NULL;
        v[k] = s ? g_ascii_strtoll(s, &end, 10) : 0;
        if (!s || *end || v[k] < 1 || v[k] > RAST_MAX_SIDE) {
            cfg_error(err, res, "a bad resolution", "[width, height]");
            return FALSE;
        }
    }
    *w = (int)v[0];
    *h = (int)v[1];
    return TRUE;
}

/* Every table that uses scene `key`, at every resolution. */
static gboolean scene_cells(OrRun *r, const char *key, GError **err)
{
    CfgNode *doc = load_scene(r, key, err);
    if (!doc)
        return FALSE;
    const CfgNode *res = cfg_get(r->root, "resolutions");
    gboolean ok = TRUE;
    for (guint i = 0; ok && i < cfg_seq_len(res); i++) {
        int w, h;
        if (!(ok = read_res(cfg_seq_at(res, i), &w, &h, err)))
            break;
        char what[96];
        g_snprintf(what, sizeof what, "%s at %dx%d", key, w, h);
        rp_step(r->ctx, what);
        ok = render_tables(r, key, cfg_get(doc, "scene"), w, h, err);
    }
    cfg_free(doc);
    return ok;
}

/* The fastest polygons_per_s of `table` over rows starting with
 * `prefix` (NAN if none). */
static double fastest(GPtrArray *rows, const char *table, const char *prefix)
{
    double best = NAN;
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        if (g_strcmp0(r->table, table) == 0 &&
            g_str_has_prefix(r->row, prefix) &&
            g_strcmp0(r->column, "polygons_per_s") == 0 &&
            (isnan(best) || r->sim > best))
            best = r->sim;
    }
    return best;
}

/* The two sentences of §6 (configs/papers/ortega93/published.yaml). */
static void text_rows(GPtrArray *rows)
{
    double a = fastest(rows, "1", "64K/"), b = fastest(rows, "3", "512/");
    g_ptr_array_add(rows, rp_row_new("text", "CM-200 64K small",
                                     "polygons_per_s", a, NULL));
    g_ptr_array_add(rows, rp_row_new("text", "CM-5 512 small",
                                     "polygons_per_s", b, NULL));
}

/* The table's label names the transport: every machine's sends are
 * priced by the cost formulas of dp_cost.h (the CM-200's fitted router,
 * the CM-5's analytic fat tree), not by a network at the pass's fidelity
 * (`pgsim run` does that for the CM-5: dp_workload.h). */
static void note_transports(OrRun *r)
{
    const CfgNode *tabs = cfg_get(r->root, "tables");
    for (guint t = 0; t < cfg_map_len(tabs); t++) {
        const char *m = NULL;
        if (cfg_get_str(cfg_map_value(tabs, t), "machine", FALSE, &m, NULL) &&
            m)
            rp_note_fidelity(r->ctx, m, "formula");
    }
}

static gboolean ortega93_run(const RpContext *ctx, GPtrArray *rows,
                             GError **err)
{
    CfgNode *root = cfg_load_file(ctx->setup, err);
    if (!root)
        return FALSE;
    OrRun r = {.ctx = ctx,
               .root = root,
               .dir = g_path_get_dirname(ctx->setup),
               .rows = rows,
               .simd = g_array_new(FALSE, FALSE, sizeof(RpOrCell))};
    double bf = 1.0; /* checked here, read by dpscan */
    if (!cfg_get_double(root, "buffer_factor", FALSE, 1e-3, 1e3, &bf, err)) {
        g_array_free(r.simd, TRUE);
        g_free(r.dir);
        cfg_free(root);
        return FALSE;
    }
    const char *coef = g_getenv("PGSIM_DP_COEF");
    if (coef)
        r.coef = fopen(coef, "w");
    note_transports(&r);
    gboolean ok =
        scene_cells(&r, "small", err) && scene_cells(&r, "large", err);
    if (ok) {
        text_rows(rows);
        rp_ortega93_claims(rows);
        ok = rp_ortega93_cv(r.simd, rows, err);
    }
    if (ok && ctx->out_dir)
        rp_ortega93_charts(rows, ctx->out_dir);
    if (r.coef)
        fclose(r.coef);
    g_array_free(r.simd, TRUE);
    g_free(r.dir);
    cfg_free(root);
    return ok;
}

const RpPaperOps rp_ortega93 = {
    .name = "ortega93",
    .citation = "ortega93: data-parallel polygon rendering, CM-200 and "
               "CM-5 (Tables 1-4)",
    .setup = "setup.yaml",
    .rows = ortega93_run,
    .cost_s = 8, /* measured: user time of `pgsim reproduce ortega93` */
};
