/* wl_pphigs.c — the `pphigs` workload: a display list distributed over
 * the GPs of Pixel-Planes 5 (seed 001), drawn frame after frame on the
 * event-driven model (frame.h), with per-frame matrix edits (§1.3, §3.1:
 * "changing only a few transformation matrices") and rebalancing (§5).
 *
 * workload section:
 *   type: pphigs
 *   algorithm: simple | complex        (default complex)
 *   gps: 1..64                          (default: the model's GP count)
 *   database: space_station | building_lobby | flock_old_well |
 *             two_human_figures
 *   databases: path of the generator parameters
 *   frame: path of the frame sizes (configs/pphigs/frame.yaml)
 *   edits_per_frame: matrix modifies per frame (default 0)
 *   edit_angle_deg: rotation each edit applies (default 0)
 *   rebalance: {enabled, threshold, frames, fraction, max_moves}
 * The model file is models/<machine.model>.yaml.
 * Cost per frame: the frame's (frame.h) plus O(host size) per edit.
 */
#include "sim/workload/pphigs/pphigs_cfg.h"
#include "sim/workload/pphigs/rebalance.h"
#include "sim/workload/workload.h"

typedef struct {
    int algo;
    int64_t gps; /* 0: the model's count */
    char *database, *databases, *frame;
    int64_t edits;
    double edit_angle;
    gboolean rebalance;
    WlPphigsRebalParams rb;
} Params;

static void params_free(void *p)
{
    Params *x = p;
    if (!x)
        return;
    g_free(x->database);
    g_free(x->databases);
    g_free(x->frame);
    g_free(x);
}

static gboolean parse_rebalance(const CfgNode *sec, Params *p, GError **err)
{
    const CfgNode *r = cfg_get(sec, "rebalance");
    uint64_t frames = p->rb.frames, moves = p->rb.max_moves;
    if (!r)
        return TRUE;
    gboolean ok =
        cfg_get_bool(r, "enabled", FALSE, &p->rebalance, err) &&
        cfg_get_double(r, "threshold", FALSE, 1e-6, 1, &p->rb.threshold,
                       err) &&
        cfg_get_count(r, "frames", FALSE, 1, 1000000, &frames, err) &&
        cfg_get_double(r, "fraction", FALSE, 1e-6, 1, &p->rb.fraction,
                       err) &&
        cfg_get_count(r, "max_moves", FALSE, 1, 1000000, &moves, err);
    p->rb.frames = (guint)frames;
    p->rb.max_moves = (guint)moves;
    return ok;
}

static void *parse(const CfgNode *sec, GError **err)
{
    static const char *const algos[] = {"simple", "complex", NULL};
    Params *p = g_new0(Params, 1);
    p->algo = WL_PPHIGS_COMPLEX;
    p->rebalance = TRUE;
    p->rb = (WlPphigsRebalParams){0.10, 3, 0.5, 16, 1};
    const char *db = NULL, *dbs = NULL, *fr = NULL;
    gboolean ok =
        cfg_get_enum(sec, "algorithm", FALSE, algos, &p->algo, err) &&
        cfg_get_int(sec, "gps", FALSE, 1, 64, &p->gps, err) &&
        cfg_get_str(sec, "database", TRUE, &db, err) &&
        cfg_get_str(sec, "databases", TRUE, &dbs, err) &&
        cfg_get_str(sec, "frame", TRUE, &fr, err) &&
        cfg_get_int(sec, "edits_per_frame", FALSE, 0, 1000000, &p->edits,
                    err) &&
        cfg_get_double(sec, "edit_angle_deg", FALSE, -360, 360,
                       &p->edit_angle, err) &&
        parse_rebalance(sec, p, err);
    p->database = g_strdup(db);
    p->databases = g_strdup(dbs);
    p->frame = g_strdup(fr);
    if (!ok) {
        params_free(p);
        return NULL;
    }
    return p;
}

/* ---- one run ---------------------------------------------------------- */

typedef struct {
    const Params *p;
    WlPphigsHw hw;
    ScenePphigsDb db;
    WlPphigsDist *d;
    NetTopo *topo;
    NetNet *net;
    WlPphigsFrame *frame;
    WlPphigsRebal *rb;
    SimRng *rng;
    guint ngp;
    uint64_t edits, moves, commands;
    double imbalance;
} Run;

static gboolean load(Run *r, const WlContext *ctx, GError **err)
{
    const char *model = "pixel-planes-5";
    const CfgNode *m = cfg_get(ctx->root, "machine");
    if (m && !cfg_get_str(m, "model", FALSE, &model, err))
        return FALSE;
    char *path = g_strdup_printf("models/%s.yaml", model);
    CfgNode *fr = cfg_load_file(r->p->frame, err);
    gboolean ok = fr && wl_pphigs_hw_load(path, fr, &r->hw, err) &&
                  cfg_check_unused(fr, err);
    cfg_free(fr);
    g_free(path);
    if (ok && !net_fidelity_parse(ctx->fidelity, &r->hw.fidelity)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "found fidelity '%s', expected analytic, flow or packet",
                    ctx->fidelity);
        ok = FALSE;
    }
    ScenePphigsSpec spec;
    return ok &&
           wl_pphigs_spec_load(r->p->databases, r->p->database, &spec,
                               err) &&
           scene_pphigs_generate(&spec, &r->db, err);
}

static void build(Run *r, const WlContext *ctx)
{
    r->ngp = r->p->gps ? (guint)r->p->gps : MIN(r->hw.max_gps, 64);
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(
        &r->hw.costs,
        MAX(1.0, r->hw.cluster_scale / r->ngp), &w);
    r->d = wl_pphigs_dist_new(r->db.db, r->ngp, (WlPphigsAlgo)r->p->algo,
                              &w);
    r->topo = net_ring_new(
        wl_pphigs_frame_stations(r->ngp, r->hw.frame.renderers));
    r->net = net_new(ctx->eng, r->topo, &r->hw.net, r->hw.fidelity);
    r->frame = wl_pphigs_frame_new(ctx->eng, r->net, r->ngp, &r->hw.frame);
    WlPphigsRebalParams rb = r->p->rb;
    rb.seed = ctx->seed;
    r->rb = r->p->rebalance ? wl_pphigs_rebal_new(&rb) : NULL;
    r->rng = sim_entity_rng(ctx->eng, sim_entity_add(ctx->eng, "host"));
}

static void run_clear(Run *r)
{
    wl_pphigs_rebal_free(r->rb);
    wl_pphigs_frame_free(r->frame);
    net_free(r->net);
    net_topo_free(r->topo);
    wl_pphigs_dist_free(r->d);
    if (r->db.db)
        scene_pphigs_db_clear(&r->db);
}

/* One modify of a random matrix element of the host list (§3.1). */
static void edit_one(Run *r)
{
    const SceneDb *h = wl_pphigs_dist_host(r->d);
    GArray *at = g_array_new(FALSE, FALSE, sizeof(guint) * 2);
    for (guint s = 0; s < scene_db_struct_count(h); s++)
        for (guint i = 0; i < scene_db_len(h, s); i++)
            if (scene_db_elem(h, s, i)->kind == SCENE_EL_MATRIX) {
                guint sp[2] = {s, i};
                g_array_append_val(at, sp);
            }
    if (at->len) {
        guint *sp = (guint *)at->data +
                    2 * sim_rng_below(r->rng, at->len);
        SceneElem e = *scene_db_elem(h, sp[0], sp[1]);
        double a = r->p->edit_angle * G_PI / 180;
        e.matrix = mat4_mul(e.matrix, mat4_rotate(vec3(0, 1, 0), a));
        gboolean ok = wl_pphigs_dist_modify(r->d, sp[0], sp[1], &e, NULL);
        g_assert(ok);
        r->edits++;
    }
    g_array_unref(at);
}

static gboolean one_frame(Run *r, SimResult *out, GError **err)
{
    for (int64_t k = 0; k < r->p->edits; k++)
        edit_one(r);
    WlPphigsFrameStats st;
    Mat4 vp = scene_camera_view_proj(&r->db.camera);
    if (!wl_pphigs_frame_run(r->frame, r->d, vp, &st, err))
        return FALSE;
    sim_result_add_frame(out, st.time);
    r->commands += st.commands;
    r->imbalance = wl_pphigs_imbalance(st.gp_traverse_us, r->ngp);
    if (r->rb) {
        WlPphigsRebalStep rs;
        wl_pphigs_rebal_frame(r->rb, r->d, vp, &r->hw.costs,
                              st.gp_traverse_us, &rs);
        r->moves = rs.total_moves;
    }
    return TRUE;
}

static void fill(Run *r, const WlContext *ctx, SimResult *out)
{
    SimTime now = sim_now(ctx->eng);
    out->elapsed = now;
    out->seed = ctx->seed;
    out->events = sim_engine_events(ctx->eng);
    g_free(out->fidelity);
    out->fidelity = g_strdup(net_fidelity_name(r->hw.fidelity));
    wl_pphigs_frame_fill_result(r->frame, out);
    net_fill_result(r->net, out);
    double gu, ru;
    wl_pphigs_frame_util(r->frame, now, &gu, &ru);
    double n = MAX(out->frame_times->len, 1);
    sim_result_set_metric(out, "frame_ms", sim_result_mean_frame_s(out) * 1e3,
                          "ms");
    sim_result_set_metric(out, "gp_util_pct", 100 * gu, "%");
    sim_result_set_metric(out, "renderer_util_pct", 100 * ru, "%");
    sim_result_set_metric(out, "ring_bytes_per_frame",
                          (double)net_total_bytes(r->net) / n, "B");
    sim_result_set_metric(out, "commands_per_frame", r->commands / n, "");
    sim_result_set_metric(out, "gps", r->ngp, "");
    sim_result_set_metric(out, "last_imbalance_pct", 100 * r->imbalance,
                          "%");
    sim_result_set_metric(out, "edits", (double)r->edits, "");
    sim_result_set_metric(out, "rebalance_moves", (double)r->moves, "");
}

static gboolean run(const WlContext *ctx, void *params, SimResult *out,
                    GError **err)
{
    Run r = {.p = params};
    gboolean ok = load(&r, ctx, err);
    if (ok) {
        build(&r, ctx);
        for (int f = 0; ok && f < ctx->frames; f++)
            ok = one_frame(&r, out, err);
        if (ok)
            fill(&r, ctx, out);
    }
    run_clear(&r);
    return ok;
}

const WlOps wl_pphigs_ops = {
    .name = "pphigs",
    .summary = "PPHIGS display list distributed by primitive over the "
               "GPs of Pixel-Planes 5 (seed 001)",
    .parse = parse,
    .free_params = params_free,
    .run = run,
};
