/* dp_workload.c — workload `dpscan` (dp_workload.h): parses its section, measures
 * each frame's geometry (dp_geom.h), schedules it (dp_frame.h) and fills
 * the SimResult.  The SIMD array is one processor in the result (design:
 * steps over arrays); its per-phase busy time is the frame's phases.
 * O(spans + segments) per frame.
 */
#include "sim/workload/dpscan/dp_workload.h"
#include "sim/scene/scene_cfg.h"
#include "sim/workload/dpscan/dp_exec.h"
#include "sim/workload/dpscan/dp_model.h"

typedef struct {
    const char *model;
    uint64_t procs;
    int64_t width, height;
    double buffer_factor;
} DpParams;

static void *dp_parse(const CfgNode *sec, GError **err)
{
    DpParams *p = g_new0(DpParams, 1);
    p->model = "cm200";
    p->procs = 16384;
    p->width = 1280;
    p->height = 1024;
    p->buffer_factor = 1.0;
    if (!cfg_get_str(sec, "model", FALSE, &p->model, err) ||
        !cfg_get_count(sec, "processors", FALSE, 1, G_MAXUINT32, &p->procs,
                       err) ||
        !cfg_get_int(sec, "width", FALSE, 1, RAST_MAX_SIDE, &p->width, err) ||
        !cfg_get_int(sec, "height", FALSE, 1, RAST_MAX_SIDE, &p->height, err) ||
        !cfg_get_double(sec, "buffer_factor", FALSE, 1e-6, 1e6,
                        &p->buffer_factor, err)) {
        g_free(p);
        return NULL;
    }
    return p;
}

static void dp_free_params(void *p)
{
    g_free(p);
}

static void add_metrics(SimResult *out, const WlDpFrame *f, const WlDpGeom *g)
{
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++) {
        char *name = g_strdup_printf("%s_s", wl_dp_phase_name(ph));
        sim_result_set_metric(out, name, sim_time_to_s(f->phase[ph]), "s");
        g_free(name);
    }
    sim_result_set_metric(out, "polygons_per_s",
                          (double)g->n_polys / sim_time_to_s(f->total), "1/s");
    sim_result_set_metric(out, "steps", (double)f->steps, "");
    sim_result_set_metric(out, "scan_iters", (double)f->counts.scan_iters, "");
    sim_result_set_metric(out, "pixel_iters", (double)f->counts.pixel_iters,
                          "");
    sim_result_set_metric(out, "flushes", (double)f->counts.flushes, "");
    sim_result_set_metric(out, "pixels", (double)g->pixels, "");
    sim_result_set_metric(out, "collisions", (double)wl_dp_geom_collisions(g),
                          "");
    sim_result_set_metric(out, "messages", (double)f->counts.messages, "");
}

static gboolean run_frames(const WlContext *ctx, DpParams *p,
                           const WlDpMachine *m, MachMachine *mach,
                           const Scene *s, SimResult *out, GError **err)
{
    WlDpAlgo a = wl_dp_algo_defaults();
    a.buffer_factor = p->buffer_factor;
    for (int fr = 0; fr < ctx->frames; fr++) {
        WlDpGeom *g =
            wl_dp_geom_new(s, fr, (int)p->width, (int)p->height, TRUE);
        WlDpFrame f;
        gboolean ok = wl_dp_exec_frame(mach, m, g, &a, &f, err);
        if (ok) {
            sim_result_add_frame(out, f.total);
            add_metrics(out, &f, g);
        }
        wl_dp_geom_free(g);
        if (!ok)
            return FALSE;
    }
    return TRUE;
}

static gboolean dp_run(const WlContext *ctx, void *params, SimResult *out,
                       GError **err)
{
    DpParams *p = params;
    WlDpMachine m = {0};
    if (!wl_dp_machine_load("models", p->model, &m, err))
        return FALSE;
    m.procs = p->procs;
    Scene *s = scene_from_cfg(cfg_get(ctx->root, "scene"), err);
    if (!s)
        return FALSE;
    MachMachine *mach =
        wl_dp_exec_machine(ctx->eng, p->model, &m, ctx->fidelity, err);
    gboolean ok = mach && run_frames(ctx, p, &m, mach, s, out, err);
    if (ok) {
        mach_fill_result(mach, out);
        out->elapsed = sim_now(ctx->eng);
        if (m.arch == WL_DP_SIMD) {
            out->comm_bytes = 0;
            out->comm_messages = 0;
        }
    }
    mach_free(mach);
    scene_free(s);
    return ok;
}

const WlOps wl_dpscan_ops = {
    .name = "dpscan",
    .summary = "seed 004: data-parallel scan conversion on SIMD/SPMD "
               "machines (CM-200, CM-5)",
    .parse = dp_parse,
    .free_params = dp_free_params,
    .run = dp_run,
};
