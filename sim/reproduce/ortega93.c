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
#include "sim/workload/dpscan/dp_color.h"
#include "sim/workload/dpscan/dp_render.h"
#include "sim/raster/scan.h"
#include "sim/workload/dpscan/dp_model.h"
#include "sim/machine/model.h"
#include <math.h>
#include <stdio.h>

typedef struct {
    const RpContext *ctx;
    const CfgNode *root;
    char *dir;       /* directory of the sweep file */
    GPtrArray *rows; /* RpRow * */
    FILE *coef;      /* PGSIM_DP_COEF or NULL */
    GArray *simd;    /* RpOrCell of every SIMD cell, for table "cv" */
    double buffer_factor; /* segment buffer slots per polygon */
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

/* A table's machine at each of its partitions, appended to ms. */
static gboolean table_machines(const CfgNode *t, GArray *ms, GError **err)
{
    const char *mname = NULL;
    WlDpMachine m = {0};
    if (!cfg_get_str(t, "machine", TRUE, &mname, err))
        return FALSE;
    CfgNode *model = mach_load_model(mname, err);
    gboolean ok = model && wl_dp_machine_from_model(model, NULL, &m, err);
    cfg_free(model);
    if (!ok)
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
        if (!s || !cfg_parse_count(s, "partition", &p, &e) || p == 0 ||
            p > G_MAXUINT32) {
            g_clear_error(&e);
            cfg_error(err, cfg_seq_at(parts, i), s ? s : "a non-scalar",
                      "a processor count > 0");
            return FALSE;
        }
        m.procs = p;
        g_array_append_val(ms, m);
    }
    return TRUE;
}

static void cell_rows(OrRun *r, const char *table, const WlDpTarget *t,
                      const WlDpImage *img, uint64_t n_polys)
{
    char part[32], row[64];
    partition_name(t->m.procs, part, sizeof part);
    g_snprintf(row, sizeof row, "%s/%dx%d", part, img->width, img->height);
    double s = sim_time_to_s(t->total);
    g_ptr_array_add(r->rows, rp_row_new(table, row, "time_s", s, NULL));
    g_ptr_array_add(r->rows, rp_row_new(table, row, "polygons_per_s",
                                        (double)n_polys / s, NULL));
    const WlDpCoef *k = &t->coef;
    if (t->m.arch == WL_DP_SIMD) {
        RpOrCell c = {.b = k->slices, .s = sim_time_to_s(t->m.send_slice)};
        g_strlcpy(c.table, table, sizeof c.table);
        g_strlcpy(c.row, row, sizeof c.row);
        c.a = s - c.s * c.b;
        g_array_append_val(r->simd, c);
    }
    if (r->coef && t->m.arch == WL_DP_SIMD)
        fprintf(r->coef,
                "%s,%s,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%" G_GUINT64_FORMAT
                ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT "\n",
                table, row, k->op_slices, k->steps, k->scan_slices, k->sends,
                k->slices, k->vp_slices, k->news_slices, k->msg_slices,
                img->scan_iters,
                img->pixel_iters, img->flushes);
}

/* Renders scene s once at w x h and costs it on every partition of
 * every table that uses it. */
static gboolean render_tables(OrRun *r, const char *key, const Scene *s,
                              int w, int h, GError **err)
{
    const CfgNode *tabs = cfg_get(r->root, "tables");
    GArray *ms = g_array_new(FALSE, FALSE, sizeof(WlDpMachine));
    GPtrArray *names = g_ptr_array_new();
    gboolean ok = TRUE;
    for (guint t = 0; ok && t < cfg_map_len(tabs); t++) {
        const CfgNode *tab = cfg_map_value(tabs, t);
        const char *sk = NULL;
        guint before = ms->len;
        ok = cfg_get_str(tab, "scene", TRUE, &sk, err) &&
             (g_strcmp0(sk, key) != 0 || table_machines(tab, ms, err));
        for (guint i = before; ok && i < ms->len; i++)
            g_ptr_array_add(names, (gpointer)cfg_map_key(tabs, t));
    }
    if (ok && ms->len > 0) {
        float pal[WL_DP_COLORS][3];
        wl_dp_palette_default(pal);
        WlDpRenderOpts o = {.mode = WL_DP_MODE_GOURAUD,
                            .buffer_factor = r->buffer_factor,
                            .ops = wl_dp_ops_defaults()};
        WlDpPolys *p = wl_dp_polys_new(s, 0.0, w, h, o.mode, pal);
        WlDpVm *vm = wl_dp_vm_new((WlDpMachine *)ms->data, ms->len,
                                  (uint32_t)w, (uint32_t)h);
        WlDpImage *img = wl_dp_render(vm, p, w, h, &o);
        for (guint i = 0; i < ms->len; i++)
            cell_rows(r, names->pdata[i], wl_dp_vm_target(vm, i), img, p->n);
        wl_dp_image_free(img);
        wl_dp_vm_free(vm);
        wl_dp_polys_free(p);
    }
    g_ptr_array_free(names, TRUE);
    g_array_free(ms, TRUE);
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
    Scene *s = load_scene(r, key, err);
    if (!s)
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
        ok = render_tables(r, key, s, w, h, err);
    }
    scene_free(s);
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
               .simd = g_array_new(FALSE, FALSE, sizeof(RpOrCell)),
               .buffer_factor = 1.0};
    if (!cfg_get_double(root, "buffer_factor", FALSE, 1e-3, 1e3,
                        &r.buffer_factor, err)) {
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
    .citation = "seed 004: data-parallel polygon rendering, CM-200 and "
               "CM-5 (Tables 1-4)",
    .setup = "setup.yaml",
    .rows = ortega93_run,
    .cost_s = 8, /* measured: user time of `pgsim reproduce ortega93` */
};
