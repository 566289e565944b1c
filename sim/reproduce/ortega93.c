/* ortega93.c — seed 004's Tables 1-4 from the simulator (ortega93.h).
 *
 * For each data set and resolution the scene is scan converted once
 * (dp_geom.h); each table then costs that geometry on each of its
 * partitions with its machine's model (dp_frame.h).  Nothing is read
 * from the published tables here.  Cost: 6 geometry builds (O(spans)
 * each) plus O(segments) per cell.
 */
#include "sim/reproduce/ortega93.h"
#include "sim/scene/scene_cfg.h"
#include "sim/workload/dpscan/dp_exec.h"
#include "sim/workload/dpscan/dp_model.h"
#include <stdio.h>

#define MODELS_DIR "models"

typedef struct {
    const RpContext *ctx;
    const CfgNode *root;
    char *dir;       /* directory of the sweep file */
    GPtrArray *rows; /* RpRow * */
    FILE *coef;      /* PGSIM_DP_COEF or NULL */
} OrRun;

/* Loads the scene file named by scenes.<key>. */
static Scene *load_scene(OrRun *r, const char *key, GError **err)
{
    const char *rel = NULL;
    if (!cfg_get_str(cfg_get(r->root, "scenes"), key, TRUE, &rel, err))
        return NULL;
    char *path = g_build_filename(r->dir, rel, NULL);
    CfgNode *doc = cfg_load_file(path, err);
    g_free(path);
    if (!doc)
        return NULL;
    Scene *s = scene_from_cfg(cfg_get(doc, "scene"), err);
    cfg_free(doc);
    return s;
}

static void partition_name(uint64_t p, char *buf, size_t n)
{
    if (p >= 1024 && p % 1024 == 0)
        g_snprintf(buf, n, "%" G_GUINT64_FORMAT "K", p / 1024);
    else
        g_snprintf(buf, n, "%" G_GUINT64_FORMAT, p);
}

/* One frame on a fresh engine and machine at the pass's fidelity. */
static gboolean run_cell(OrRun *r, const char *model, const WlDpGeom *g,
                         const WlDpMachine *m, WlDpFrame *f, GError **err)
{
    WlDpAlgo a = wl_dp_algo_defaults();
    SimEngine *eng = sim_engine_new(1);
    const char *fid =
        r->ctx && r->ctx->fidelity ? r->ctx->fidelity : "analytic";
    MachMachine *mach = wl_dp_exec_machine(eng, model, m, fid, err);
    gboolean ok = mach && wl_dp_exec_frame(mach, m, g, &a, f, err);
    mach_free(mach);
    sim_engine_free(eng);
    return ok;
}

static gboolean cell(OrRun *r, const char *table, const char *model,
                     const WlDpGeom *g, WlDpMachine *m, uint64_t procs,
                     GError **err)
{
    WlDpFrame f;
    m->procs = procs;
    if (!run_cell(r, model, g, m, &f, err))
        return FALSE;
    char part[32], row[64];
    partition_name(procs, part, sizeof part);
    g_snprintf(row, sizeof row, "%s/%dx%d", part, g->width, g->height);
    double t = sim_time_to_s(f.total);
    g_ptr_array_add(r->rows, rp_row_new(table, row, "time_s", t, NULL));
    g_ptr_array_add(r->rows, rp_row_new(table, row, "polygons_per_s",
                                        (double)g->n_polys / t, NULL));
    if (r->coef && m->arch == WL_DP_SIMD)
        fprintf(r->coef, "%s,%s,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f\n", table, row,
                f.coef.op_slices, f.coef.steps, f.coef.scan_slices,
                f.coef.sends, f.coef.slices, f.coef.vp_slices);
    return TRUE;
}

/* Costs geometry g on every partition of `table`. */
static gboolean table_cells(OrRun *r, const char *table, const CfgNode *t,
                            const WlDpGeom *g, GError **err)
{
    const char *mname = NULL;
    WlDpMachine m = {0};
    if (!cfg_get_str(t, "machine", TRUE, &mname, err) ||
        !wl_dp_machine_load(MODELS_DIR, mname, &m, err))
        return FALSE;
    const CfgNode *parts = cfg_get(t, "partitions");
    if (cfg_kind(parts) != CFG_SEQ || cfg_seq_len(parts) == 0) {
        cfg_error(err, parts ? parts : t, "no partition list",
                  "partitions: [n, ...]");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(parts); i++) {
        uint64_t p = 0;
        GError *e = NULL;
        const char *s = cfg_scalar(cfg_seq_at(parts, i));
        if (!s || !cfg_parse_count(s, "partition", &p, &e) || p == 0) {
            g_clear_error(&e);
            cfg_error(err, cfg_seq_at(parts, i), s ? s : "a non-scalar",
                      "a processor count > 0");
            return FALSE;
        }
        if (!cell(r, table, mname, g, &m, p, err))
            return FALSE;
    }
    return TRUE;
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
    Scene *s = load_scene(r, key, err);
    if (!s)
        return FALSE;
    const CfgNode *tabs = cfg_get(r->root, "tables");
    const CfgNode *res = cfg_get(r->root, "resolutions");
    gboolean ok = TRUE;
    for (guint i = 0; ok && i < cfg_seq_len(res); i++) {
        int w, h;
        if (!(ok = read_res(cfg_seq_at(res, i), &w, &h, err)))
            break;
        WlDpGeom *g = wl_dp_geom_new(s, 0.0, w, h, TRUE);
        for (guint t = 0; ok && t < cfg_map_len(tabs); t++) {
            const CfgNode *tab = cfg_map_value(tabs, t);
            const char *sk = NULL;
            ok = cfg_get_str(tab, "scene", TRUE, &sk, err);
            if (ok && g_strcmp0(sk, key) == 0)
                ok = table_cells(r, cfg_map_key(tabs, t), tab, g, err);
        }
        wl_dp_geom_free(g);
    }
    scene_free(s);
    return ok;
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
               .rows = rows};
    const char *coef = g_getenv("PGSIM_DP_COEF");
    if (coef)
        r.coef = fopen(coef, "w");
    gboolean ok =
        scene_cells(&r, "small", err) && scene_cells(&r, "large", err);
    if (r.coef)
        fclose(r.coef);
    g_free(r.dir);
    cfg_free(root);
    return ok;
}

const RpPaperOps rp_ortega93 = {
    .name = "ortega93",
    .citation = "seed 004: data-parallel polygon rendering, CM-200 and "
               "CM-5 (Tables 1-4)",
    .setup = "setup.yaml",
    .rows = ortega93_run,
};
