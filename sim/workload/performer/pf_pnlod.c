/* pf_pnlod.c — PN triangles as a level of detail under Performer's LOD
 * node and stress filter (see pf_pnlod.h).  The scene graph is one pfLOD
 * whose children hold the scene tessellated at each level; the frames
 * run through Performer's pipeline (pf_pipeline.h), CULL through
 * Performer's traversal (pf_cull.h).
 */
#include "sim/workload/performer/pf_pnlod.h"

#include "sim/machine/shmem.h"
#include "sim/workload/performer/pf_cull.h"
#include "sim/workload/performer/pf_gpipe.h"

/* ---- config ------------------------------------------------------------ */

/* A list of numbers in [lo, hi], increasing when `rising`. */
static GArray *num_list(const CfgNode *lod, const char *key, double lo,
                        double hi, gboolean rising, GError **err)
{
    const CfgNode *s = cfg_get(lod, key);
    if (!s || cfg_kind(s) != CFG_SEQ || cfg_seq_len(s) == 0) {
        cfg_error(err, s ? s : lod, s ? "not a list" : "no list",
                  rising ? "ranges: [r0, r1, ...] increasing distances"
                         : "levels: [L0, L1, ...] PN levels 0..32");
        return NULL;
    }
    GArray *a = g_array_new(FALSE, FALSE, sizeof(double));
    for (guint i = 0; i < cfg_seq_len(s); i++) {
        const char *t = cfg_scalar(cfg_seq_at(s, i));
        char *end = NULL;
        double d = t ? g_ascii_strtod(t, &end) : -1;
        if (!t || *end || d < lo || d > hi ||
            (rising && i && d <= g_array_index(a, double, i - 1))) {
            cfg_error(err, cfg_seq_at(s, i), "an out-of-order or bad value",
                      rising ? "increasing distances >= 0"
                             : "a PN level 0..32");
            g_array_free(a, TRUE);
            return NULL;
        }
        g_array_append_val(a, d);
    }
    return a;
}

WlPfPnLod *wl_pf_pnlod_parse(const CfgNode *lod, GError **err)
{
    if (cfg_kind(lod) != CFG_MAP) {
        cfg_error(err, lod, "a non-map", "lod: {levels, ranges, from, to}");
        return NULL;
    }
    WlPfPnLod *l = g_new0(WlPfPnLod, 1);
    GArray *lv = num_list(lod, "levels", 0, 32, FALSE, err);
    l->ranges = lv ? num_list(lod, "ranges", 0, 1e12, TRUE, err) : NULL;
    if (l->ranges && l->ranges->len != lv->len + 1) {
        cfg_error(err, cfg_get(lod, "ranges"), "a list of another length",
                  "one more range than levels");
        g_array_free(l->ranges, TRUE);
        l->ranges = NULL;
    }
    l->from = 1, l->to = 1;
    if (l->ranges &&
        cfg_get_double(lod, "from", FALSE, 0, 1e12, &l->from, err) &&
        cfg_get_double(lod, "to", FALSE, 0, 1e12, &l->to, err)) {
        l->levels = g_array_new(FALSE, FALSE, sizeof(guint));
        for (guint i = 0; i < lv->len; i++) {
            guint v = (guint)g_array_index(lv, double, i);
            g_array_append_val(l->levels, v);
        }
        g_array_free(lv, TRUE);
        return l;
    }
    if (lv)
        g_array_free(lv, TRUE);
    wl_pf_pnlod_free(l);
    return NULL;
}

void wl_pf_pnlod_free(WlPfPnLod *l)
{
    if (!l)
        return;
    if (l->levels)
        g_array_free(l->levels, TRUE);
    if (l->ranges)
        g_array_free(l->ranges, TRUE);
    g_free(l);
}

/* ---- the graph: one LOD, a geode per level ----------------------------- */

typedef struct {
    uint64_t coarse_tris, fine_tris, points; /* per frame at this level */
} LevelMesh;

/* Adds the scene tessellated at level L as one geoset under `geode`. */
static void add_level(WlPfGraph *g, guint geode, const Scene *s,
                      const WlPfPnParams *p, guint L, LevelMesh *lm)
{
    GArray *tris = g_array_new(FALSE, FALSE, sizeof(Vec3));
    ScenePnParams pp = p->pn;
    pp.level = L;
    *lm = (LevelMesh){scene_n_triangles(s), 0, 0};
    for (guint i = 0; i < scene_n_instances(s); i++) {
        SceneMesh *f = scene_pn_tessellate(scene_instance_mesh(s, i), &pp);
        for (guint t = 0; t < scene_mesh_n_polys(f); t++) {
            const uint32_t *ix = scene_mesh_poly(f, t);
            for (int c = 0; c < 3; c++) {
                Vec3 v = scene_mesh_vertex(f, ix[c]);
                g_array_append_val(tris, v);
            }
        }
        lm->fine_tris += scene_mesh_n_triangles(f);
        lm->points += scene_mesh_n_vertices(f);
        scene_mesh_free(f);
    }
    wl_pf_add_geoset(g, geode, (const Vec3 *)(void *)tris->data,
                     tris->len / 3, 0);
    g_array_free(tris, TRUE);
}

/* ---- the stages -------------------------------------------------------- */

typedef struct {
    const WlPfPnParams *p;
    MachMachine *m;
    WlPfGraph *g;
    guint lod_node;
    LevelMesh *levels; /* per LOD child */
    MachShmem bus;
    guint frames;
    GArray *chosen; /* int per frame: LOD child CULL picked, -1: none */
} LodRun;

static double eye_distance(const LodRun *r, guint frame)
{
    const WlPfPnLod *l = r->p->lod;
    double t = r->frames > 1 ? (double)frame / (r->frames - 1) : 0;
    return l->from + (l->to - l->from) * t;
}

static SimTime st_app(void *ctx, guint frame)
{
    (void)ctx, (void)frame;
    return 0;
}

/* Performer's CULL of the LOD: the eye on +z of the node's centre. */
static SimTime st_cull(void *ctx, guint frame, double stress)
{
    LodRun *r = ctx;
    const WlPfNode *n = wl_pf_node(r->g, r->lod_node);
    WlPfView v = {.stress = stress, .cull = FALSE};
    v.eye = vec3_add(n->center, (Vec3){0, 0, eye_distance(r, frame)});
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfCullStats cs = {0};
    wl_pf_cull(r->g, &v, dl, &cs);
    int child = -1;
    for (guint i = 0; i < dl->len; i++)
        if (g_array_index(dl, WlPfDlItem, i).op == WL_PF_DL_GEOSET)
            child = (int)g_array_index(dl, WlPfDlItem, i).geoset;
    g_array_free(dl, TRUE);
    g_array_index(r->chosen, int, frame) = child; /* geoset i: child i */
    return 0;
}

/* DRAW of the level CULL chose, through the graphics pipe process
 * (pf_gpipe.h): the CPU's time is the pipe's business. */
static SimTime st_draw(void *ctx, guint frame)
{
    (void)ctx, (void)frame;
    return 0;
}

static void st_draw_work(void *ctx, guint frame, WlPfDrawWork *w)
{
    LodRun *r = ctx;
    int child = g_array_index(r->chosen, int, frame);
    if (child < 0) {
        *w = (WlPfDrawWork){0};
        return;
    }
    const LevelMesh *lm = &r->levels[child];
    wl_pf_pn_draw_work(r->p, g_array_index(r->p->lod->levels, guint, child),
                       lm->coarse_tris, lm->fine_tris, lm->points, w);
}

/* ---- run --------------------------------------------------------------- */

static void set_metrics(const LodRun *r, const GArray *recs, SimResult *out)
{
    guint n = recs->len;
    double lsum = 0, tsum = 0;
    int first_c = -1, last_c = -1;
    for (guint i = 0; i < n; i++) {
        int c = g_array_index(r->chosen, int, i);
        guint L = c < 0 ? 0 : g_array_index(r->p->lod->levels, guint, c);
        lsum += L;
        tsum += c < 0 ? 0 : r->levels[c].fine_tris;
        if (i == 0)
            first_c = c;
        last_c = c;
    }
    const GArray *lv = r->p->lod->levels;
    sim_result_set_metric(out, "level", n ? lsum / n : 0, "");
    sim_result_set_metric(
        out, "level_first",
        first_c < 0 ? 0 : g_array_index(lv, guint, first_c), "");
    sim_result_set_metric(
        out, "level_last", last_c < 0 ? 0 : g_array_index(lv, guint, last_c),
        "");
    sim_result_set_metric(out, "fine_tris", n ? tsum / n : 0, "");
    sim_result_set_metric(out, "fine_tris_first",
                          first_c < 0 ? 0 : r->levels[first_c].fine_tris, "");
    sim_result_set_metric(out, "fine_tris_last",
                          last_c < 0 ? 0 : r->levels[last_c].fine_tris, "");
    sim_result_set_metric(out, "coarse_tris", r->levels[0].coarse_tris, "");
    sim_result_set_metric(out, "frame_ms",
                          wl_pf_mean_interval_s(recs, 0) * 1e3, "ms");
    /* the rate held at the end: the mean interval over the last quarter */
    guint tail = MAX(n / 4, 2); /* intervals between the last frames */
    sim_result_set_metric(
        out, "interval_ms_last",
        n > tail ? wl_pf_mean_interval_s(recs, n - tail) * 1e3 : 0, "ms");
    double smax = 0;
    for (guint i = 0; i < n; i++)
        smax = MAX(smax, g_array_index(recs, WlPfFrameRec, i).stress);
    sim_result_set_metric(out, "stress_max", smax, "");
}

static gboolean get_procs(MachMachine *m, const WlPfPipeParams *pp,
                          MachProc **procs, LodRun *r, GError **err)
{
    guint need = wl_pf_mp_procs(pp->mode, 1);
    const MachKindInfo *k = mach_kind(m, "cpu");
    if (!k || !mach_kind(m, "pipe") || k->count < need) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "performer: found machine '%s' without %u cpus and a "
                    "pipe, expected a shared-memory machine with a pipe for "
                    "pn: {lod}",
                    mach_name(m), need);
        return FALSE;
    }
    for (guint i = 0; i < need; i++)
        procs[i] = mach_proc(m, "cpu", i);
    return mach_shmem_init(&r->bus, m, err) &&
           mach_costs_check(m, wl_pf_pn_needs[0].needs, err);
}

gboolean wl_pf_pnlod_run(const WlContext *ctx, MachMachine *m,
                         const WlPfPnParams *p, SimResult *out, GError **err)
{
    MachProc *procs[4];
    LodRun r = {.p = p, .m = m, .frames = (guint)ctx->frames};
    WlPfPipeParams pp = p->pipe;
    if (pp.pipes > 1) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "performer: found pipes: %u with pn: {lod}, expected one "
                    "pipe", pp.pipes);
        return FALSE;
    }
    if (!get_procs(m, &pp, procs, &r, err))
        return FALSE;
    r.g = wl_pf_graph_new();
    wl_pf_add_gstate(r.g, (WlPfGeoState){0, 0, 0});
    r.lod_node = wl_pf_add_node(r.g, r.g->root, WL_PF_LOD);
    WlPfNode *n = wl_pf_node(r.g, r.lod_node);
    g_array_append_vals(n->ranges, p->lod->ranges->data, p->lod->ranges->len);
    guint nl = p->lod->levels->len;
    r.levels = g_new0(LevelMesh, nl);
    for (guint i = 0; i < nl; i++) {
        guint geode = wl_pf_add_node(r.g, r.lod_node, WL_PF_GEODE);
        add_level(r.g, geode, ctx->scene, p,
                  g_array_index(p->lod->levels, guint, i), &r.levels[i]);
    }
    wl_pf_update_bounds(r.g, r.g->root);
    r.chosen = g_array_new(FALSE, TRUE, sizeof(int));
    g_array_set_size(r.chosen, r.frames);
    pp.frames = r.frames;
    MachProc *draw = procs[wl_pf_mp_proc(pp.mode, 0, TRUE)];
    pp.gpipe = wl_pf_gpipe_new(ctx->eng, draw, mach_proc(m, "pipe", 0), &r.bus,
                               p->fifo_depth, p->fifo_chunk);
    pp.gpipes = NULL, pp.arena = NULL, pp.pipes = 1;
    WlPfStageFns fns = {.app = st_app, .cull = st_cull, .draw = st_draw,
                        .draw_work = st_draw_work};
    GArray *recs = g_array_new(FALSE, TRUE, sizeof(WlPfFrameRec));
    gboolean ok = wl_pf_pipe_run(ctx->eng, procs, &pp, &fns, &r, recs,
                                 ctx->until, err);
    if (ok) { /* as the town's run: frames end at their swaps */
        SimTime prev = 0;
        for (guint i = 0; i < recs->len; i++) {
            SimTime s = g_array_index(recs, WlPfFrameRec, i).swap;
            sim_result_add_frame(out, s - prev);
            wl_mark_frame(ctx->eng, i, s);
            prev = s;
        }
        mach_fill_result(m, out);
        out->comm_bytes = r.bus.bytes; /* DRAW's CPU -> pipe, as pf_pn */
        out->comm_messages = r.bus.transfers;
        out->elapsed = recs->len && !sim_engine_cut(ctx->eng)
                           ? prev
                           : sim_now(ctx->eng);
        set_metrics(&r, recs, out);
    }
    wl_pf_gpipe_free(pp.gpipe);
    g_array_free(recs, TRUE);
    g_array_free(r.chosen, TRUE);
    g_free(r.levels);
    wl_pf_graph_free(r.g);
    return ok;
}
