/* pf_workload.c — the `performer` workload: config, run, per-frame log
 * and metrics (docs/workloads.md, section "performer").
 *
 *   workload:
 *     type: performer
 *     mode: app_cull_draw | appcull_draw | app_culldraw | appculldraw
 *     pipes: 1                # graphics pipes, each with CULL and DRAW
 *     fork_isect: true        # false: ISECT in the APP process
 *     update_list: false      # pfBuffer hand-off at the frame boundary
 *     update_cost: 1 us       # applying one update-list entry
 *     arena: {node: 128 B, item: 16 B, entry: 64 B, pieces: 8}
 *                             # shared-arena traffic (absent: none)
 *     video_rate: 60          # Hz, retraces (assumption: a 60 Hz monitor)
 *     frame_rate: 30          # Hz, fixed frame rate; divides video_rate
 *     phase: locked | floating
 *     stress: {gain: 0.5, low: 0.7, high: 0.9, max: 4}   # absent: off
 *     cull: true  flatten: true  lazy_state: true  isect: true
 *     app_work: 2 ms          # overrides the model's cpu app_frame
 *     vertex_bytes: 32 B      # per vertex sent to the pipe
 *     strip_length: 1         # triangles per strip (1: independent)
 *     callbacks: {cull: 5 us, draw: 5 us}  # per house (absent: none)
 *     fifo: {depth: 64 KB, chunk: 8 KB}  # the pipe's command FIFO
 *     town: {blocks, houses, trees, cars, block, lod_ranges, speed,
 *            eye_height, fov, seed, hierarchy, partition: {cells}}
 *     frame_log: frames.csv   # else <out>/performer_frames.csv
 *     pn: {...}               # the PN-triangle measurement (pf_pn.h)
 *
 * The machine needs node kinds `cpu` (one per process, plus one for a
 * forked ISECT) and `pipe` (one per pipe), and a network bandwidth
 * (models/sgi-onyx.yaml).  Each pipe's FIFO stream has its own path of
 * the network's bandwidth (the programmed I/O of its DRAW CPU).
 */
#include "sim/workload/performer/pf_workload.h"

#include "sim/core/trace.h"
#include "sim/workload/performer/pf_pn.h"
#include "sim/workload/performer/pf_stages.h"

#include <string.h>

typedef struct {
    WlPfPipeParams pipe;
    double video_hz, frame_hz;
    gboolean cull, flatten, lazy, isect, has_app_work, fork_isect;
    SimTime app_work, update_cost;
    uint64_t vertex_bytes, strip;
    uint64_t fifo_depth, fifo_chunk; /* pf_gpipe.h */
    gboolean has_arena;
    SimTime cb_cull, cb_draw; /* traversal callbacks, one each */
    WlPfArenaParams arena; /* pf_arena.h */
    WlPfTownParams town;
    const char *frame_log; /* borrowed from the config */
    WlPfPnParams *pn;      /* NULL: the Performer pipeline */
    const CfgNode *at;     /* the section, for errors */
} PfParams;

static const char *const phases[] = {"locked", "floating", NULL};

static const char *const hierarchies[] = {"flat", "quadtree", NULL};

static gboolean parse_town(const CfgNode *sec, WlPfTownParams *t, GError **err)
{
    const CfgNode *n = cfg_get(sec, "town");
    uint64_t v[4] = {t->blocks, t->houses, t->trees, t->cars};
    uint64_t seed = t->seed, cells = t->partition;
    int deep = t->deep ? 1 : 0;
    /* no town: every getter below finds no key, so the defaults stay */
    if (!cfg_get_count(n, "blocks", FALSE, 1, 256, &v[0], err) ||
        !cfg_get_count(n, "houses", FALSE, 0, 256, &v[1], err) ||
        !cfg_get_count(n, "trees", FALSE, 0, 1024, &v[2], err) ||
        !cfg_get_count(n, "cars", FALSE, 0, 4096, &v[3], err) ||
        !cfg_get_double(n, "block", FALSE, 20, 1e4, &t->block, err) ||
        !cfg_get_double(n, "speed", FALSE, 0, 1e3, &t->speed, err) ||
        !cfg_get_double(n, "eye_height", FALSE, 0, 1e3, &t->eye_height, err) ||
        !cfg_get_double(n, "fov", FALSE, 1, 170, &t->fov_deg, err) ||
        !cfg_get_count(n, "seed", FALSE, 0, UINT64_MAX, &seed, err) ||
        !cfg_get_enum(n, "hierarchy", FALSE, hierarchies, &deep, err) ||
        !cfg_get_count(cfg_get(n, "partition"), "cells", FALSE, 1, 256, &cells,
                       err))
        return FALSE;
    t->partition = (guint)cells;
    t->deep = deep == 1;
    const CfgNode *r = cfg_get(n, "lod_ranges");
    if (r && (cfg_kind(r) != CFG_SEQ || cfg_seq_len(r) != 3)) {
        cfg_error(err, r, "not a list of 3", "[d01, d12, d2off] in metres");
        return FALSE;
    }
    for (guint i = 0; r && i < 3; i++) {
        const char *s = cfg_scalar(cfg_seq_at(r, i));
        char *end = NULL;
        double d = s ? g_ascii_strtod(s, &end) : -1;
        if (!s || *end || !(d > (i ? t->lod_ranges[i - 1] : 0))) {
            cfg_error(err, cfg_seq_at(r, i), "a non-increasing range",
                      "increasing positive distances");
            return FALSE;
        }
        t->lod_ranges[i] = d;
    }
    t->blocks = v[0], t->houses = v[1], t->trees = v[2], t->cars = v[3];
    t->seed = seed;
    return TRUE;
}

static gboolean parse_stress(const CfgNode *sec, WlPfPipeParams *p,
                             GError **err)
{
    const CfgNode *n = cfg_get(sec, "stress");
    p->low = 0.7, p->high = 0.9, p->gain = 0.5, p->max_stress = 4;
    if (!n)
        return TRUE;
    p->stress = TRUE;
    if (!cfg_get_map(sec, "stress", FALSE, "a map {gain, low, high, max}", &n,
                     err) ||
        !cfg_get_double(n, "gain", FALSE, 0, 1e3, &p->gain, err) ||
        !cfg_get_double(n, "low", FALSE, 0, 10, &p->low, err) ||
        !cfg_get_double(n, "high", FALSE, 0, 10, &p->high, err) ||
        !cfg_get_double(n, "max", FALSE, 1, 1e3, &p->max_stress, err))
        return FALSE;
    if (p->high >= p->low)
        return TRUE;
    cfg_error(err, n, "high < low", "a load band with low <= high");
    return FALSE;
}

static gboolean parse_rates(const CfgNode *sec, PfParams *p, GError **err)
{
    if (!cfg_get_double(sec, "video_rate", FALSE, 1, 1000, &p->video_hz, err) ||
        !cfg_get_double(sec, "frame_rate", FALSE, 0.1, 1000, &p->frame_hz, err))
        return FALSE;
    double k = p->video_hz / p->frame_hz;
    if (fabs(k - round(k)) > 1e-9 || k < 1) {
        cfg_error(err, cfg_get(sec, "frame_rate"),
                  "a frame rate that does not divide the video rate",
                  "video_rate / frame_rate a whole number >= 1");
        return FALSE;
    }
    p->pipe.per_frame = (guint)round(k);
    /* a whole number of picoseconds per retrace: frame boundaries are
     * exact multiples of it */
    return sim_time_from_s(1.0 / p->video_hz, &p->pipe.video);
}

static gboolean parse_flags(const CfgNode *sec, PfParams *p, GError **err)
{
    int mode = p->pipe.mode, phase = 0;
    uint64_t pipes = 1;
    p->has_app_work = cfg_get(sec, "app_work") != NULL;
    if (!cfg_get_enum(sec, "mode", FALSE, wl_pf_mp_mode_names, &mode, err) ||
        !cfg_get_enum(sec, "phase", FALSE, phases, &phase, err))
        return FALSE;
    p->pipe.mode = (WlPfMpMode)mode;
    p->pipe.locked = phase == 0;
    gboolean ok = cfg_get_bool(sec, "cull", FALSE, &p->cull, err) &&
           cfg_get_bool(sec, "flatten", FALSE, &p->flatten, err) &&
           cfg_get_bool(sec, "lazy_state", FALSE, &p->lazy, err) &&
           cfg_get_bool(sec, "isect", FALSE, &p->isect, err) &&
           cfg_get_bool(sec, "fork_isect", FALSE, &p->fork_isect, err) &&
           cfg_get_bool(sec, "update_list", FALSE, &p->pipe.update_list,
                        err) &&
           cfg_get_time(sec, "update_cost", FALSE, &p->update_cost, err) &&
           cfg_get_count(sec, "pipes", FALSE, 1, WL_PF_MAX_PIPES, &pipes,
                         err) &&
           cfg_get_time(sec, "app_work", FALSE, &p->app_work, err) &&
           cfg_get_size(sec, "vertex_bytes", FALSE, &p->vertex_bytes, err) &&
           cfg_get_count(sec, "strip_length", FALSE, 1, 1u << 20, &p->strip,
                         err) &&
           cfg_get_str(sec, "frame_log", FALSE, &p->frame_log, err);
    p->pipe.pipes = (guint)pipes;
    p->pipe.isect_in_app = !p->fork_isect;
    return ok;
}

/* fifo: {depth, chunk}: the graphics pipe's command FIFO (pf_gpipe.h). */
static gboolean parse_fifo(const CfgNode *sec, PfParams *p, GError **err)
{
    const CfgNode *n = NULL;
    if (!cfg_get_map(sec, "fifo", FALSE, "a map {depth, chunk}", &n, err) ||
        !cfg_get_size(n, "depth", FALSE, &p->fifo_depth, err) ||
        !cfg_get_size(n, "chunk", FALSE, &p->fifo_chunk, err))
        return FALSE;
    if (p->fifo_chunk >= 1 && p->fifo_chunk <= p->fifo_depth)
        return TRUE;
    cfg_error(err, n, "a chunk of 0 or larger than the depth",
              "1 B <= chunk <= depth");
    return FALSE;
}

/* arena: {node, item, entry, pieces}: the stages' shared-arena traffic
 * on the memory bus (pf_arena.h); absent: none. */
static gboolean parse_arena(const CfgNode *sec, PfParams *p, GError **err)
{
    const CfgNode *n = NULL;
    uint64_t pieces = 8;
    /* assumptions: a node's sphere, matrix and pointers in one 128-byte
     * secondary-cache line of the R4400; a display-list item of 16 B (a
     * token and a pointer); a 4 x 4 float matrix per update entry */
    p->arena = (WlPfArenaParams){.node = 128, .item = 16, .entry = 64};
    if (!cfg_get_map(sec, "arena", FALSE, "a map {node, item, entry, pieces}",
                     &n, err) ||
        !cfg_get_size(n, "node", FALSE, &p->arena.node, err) ||
        !cfg_get_size(n, "item", FALSE, &p->arena.item, err) ||
        !cfg_get_size(n, "entry", FALSE, &p->arena.entry, err) ||
        !cfg_get_count(n, "pieces", FALSE, 1, 1024, &pieces, err))
        return FALSE;
    p->has_arena = n != NULL;
    p->arena.pieces = (guint)pieces;
    return TRUE;
}

/* callbacks: {cull, draw}: pre- and post-traversal callbacks on every
 * house (pf_cull.h), each costing that time; absent: none. */
static gboolean parse_callbacks(const CfgNode *sec, PfParams *p,
                                GError **err)
{
    const CfgNode *n = NULL;
    if (!cfg_get_map(sec, "callbacks", FALSE, "a map {cull, draw}", &n, err) ||
        !cfg_get_time(n, "cull", FALSE, &p->cb_cull, err) ||
        !cfg_get_time(n, "draw", FALSE, &p->cb_draw, err))
        return FALSE;
    p->town.callbacks =
        n ? (p->cb_cull ? WL_PF_CB_CULL : 0) | (p->cb_draw ? WL_PF_CB_DRAW : 0)
          : 0;
    return TRUE;
}

static void pf_free(void *params)
{
    PfParams *p = params;
    if (p)
        wl_pf_pn_params_free(p->pn);
    g_free(p);
}

/* Own memory (WlOps.mem_bytes): the town's geometry, three Vec3 a
 * triangle (pf_town.h: a house's LODs hold 12 (16 + 4 + 1) triangles, a
 * block's terrain 128, a tree's billboard 2, a car 12), plus 512 B of
 * nodes and arrays per object (an assumption); flatten copies the
 * geometry under each SCS once more.  The pn pipeline builds no town:
 * its mesh is the scene's, checked with the scene. */
static double pf_mem_bytes(const void *params, GString *what)
{
    const PfParams *p = params;
    const WlPfTownParams *t = &p->town;
    if (p->pn) {
        g_string_append(what, "pn: no town");
        return 0;
    }
    double tri = 3 * sizeof(Vec3), blocks = (double)t->blocks * t->blocks;
    double geo = blocks * (128 + t->houses * 252.0 + t->trees * 2.0) * tri +
                 t->cars * 12.0 * tri;
    g_string_append_printf(what, "a town of %u x %u blocks, %u houses and "
                           "%u trees a block", t->blocks, t->blocks, t->houses,
                           t->trees);
    return geo * (p->flatten ? 2 : 1) +
           (blocks * (1.0 + t->houses + t->trees) + t->cars) * 512.0;
}

static void *pf_parse(const CfgNode *sec, GError **err)
{
    PfParams *p = g_new0(PfParams, 1);
    p->pipe.mode = WL_PF_MP_APP_CULL_DRAW;
    p->video_hz = 60, p->frame_hz = 30;
    p->cull = p->flatten = p->lazy = p->isect = p->fork_isect = TRUE;
    /* assumption: copy one 64-byte matrix into CULL's pfBuffer, about
     * 150 instructions at 150 MHz */
    p->update_cost = SIM_US;
    p->vertex_bytes = 32;
    p->strip = 1;
    p->fifo_depth = WL_PF_FIFO_DEPTH, p->fifo_chunk = WL_PF_FIFO_CHUNK;
    p->town = wl_pf_town_defaults();
    p->at = sec;
    const CfgNode *pn = cfg_get(sec, "pn");
    if ((pn && !(p->pn = wl_pf_pn_params_parse(pn, err))) ||
        !parse_flags(sec, p, err) || !parse_fifo(sec, p, err) ||
        !parse_arena(sec, p, err) || !parse_callbacks(sec, p, err) ||
        !parse_rates(sec, p, err) ||
        !parse_stress(sec, &p->pipe, err) || !parse_town(sec, &p->town, err)) {
        pf_free(p);
        return NULL;
    }
    if (p->pn) { /* the PN measurement runs through the same pipe */
        p->pn->fifo_depth = p->fifo_depth, p->pn->fifo_chunk = p->fifo_chunk;
        p->pn->pipe = p->pipe; /* and its LOD through the same frames */
    }
    return p;
}

/* ---- per-frame log ----------------------------------------------------- */

static double ms(SimTime t)
{
    return sim_time_to_s(t) * 1e3;
}

static void log_row(GString *s, guint n, const WlPfFrameRec *r,
                    const WlPfFrameRec *prev, const WlPfFrameStats *f)
{
    double lod = f->cull.lods ? (double)f->cull.lod_sum / f->cull.lods : 0;
    g_string_append_printf(
        s,
        "%u,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,%.4f,"
        "%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT
        ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT
        ",%.6f,%.6f,%.6f\n",
        n, ms(r->app_start), ms(r->app_end - r->app_start),
        ms(r->cull_ms), ms(r->draw_ms),
        ms(r->isect), ms(r->swap), ms(r->swap - r->app_start),
        prev ? ms(r->swap - prev->swap) : 0, r->stress, lod, f->draw.tris,
        f->draw.geosets, f->draw.state_changes,
        f->draw.state_naive - f->draw.state_changes, f->draw.matrix_ops,
        f->cull.tris_culled, ms(f->cpu), ms(f->bus), ms(f->pipe));
}

static gboolean write_log(const char *path, const GArray *recs, WlPfStages *st,
                          GError **err)
{
    GString *s = g_string_new(
        "frame,app_start_ms,app_ms,cull_ms,draw_ms,isect_ms,swap_ms,"
        "latency_ms,interval_ms,stress,mean_lod,tris,geosets,state_changes,"
        "state_saved,matrix_ops,tris_culled,draw_cpu_ms,draw_bus_ms,"
        "draw_pipe_ms\n");
    for (guint n = 0; n < recs->len; n++)
        log_row(s, n, &g_array_index(recs, WlPfFrameRec, n),
                n ? &g_array_index(recs, WlPfFrameRec, n - 1) : NULL,
                wl_pf_frame_stats(st, n));
    gboolean ok = wl_frame_log_write(path, s, "performer", err);
    g_string_free(s, TRUE);
    return ok;
}

/* Beside the log, <stem>_stages.csv: one row per frame and stage (app,
 * cull, draw, isect, and the interval between swaps), the long form
 * `pgsim plot --series=stage` draws as one chart. */
static gboolean write_stages(const char *log, const GArray *recs, GError **err)
{
    GString *s = g_string_new("frame,stage,ms\n");
    for (guint n = 0; n < recs->len; n++) {
        const WlPfFrameRec *r = &g_array_index(recs, WlPfFrameRec, n);
        SimTime prev =
            n ? g_array_index(recs, WlPfFrameRec, n - 1).swap : r->app_start;
        g_string_append_printf(
            s,
            "%u,app,%.6f\n%u,cull,%.6f\n%u,draw,%.6f\n%u,isect,%.6f\n"
            "%u,frame,%.6f\n",
            n, ms(r->app_end - r->app_start), n,
            ms(r->cull_ms), n, ms(r->draw_ms),
            n, ms(r->isect), n, ms(r->swap - prev));
    }
    char *stem = g_str_has_suffix(log, ".csv") ? g_strndup(log, strlen(log) - 4)
                                               : g_strdup(log);
    char *path = g_strconcat(stem, "_stages.csv", NULL);
    gboolean ok = wl_frame_log_write(path, s, "performer", err);
    g_free(stem);
    g_free(path);
    g_string_free(s, TRUE);
    return ok;
}

/* ---- metrics ----------------------------------------------------------- */

typedef struct {
    double app, cull, draw, tris, states, saved, mats, culled, stress, lod;
    double verts, vsaved, nodes, cbs;
    double cpu, bus, pipe; /* DRAW's three rates */
    double isect, itests;  /* ISECT's time and nodes + triangles tested */
} Means;

static Means means(const GArray *recs, WlPfStages *st, guint skip)
{
    Means m = {0};
    guint c = 0;
    for (guint n = skip; n < recs->len; n++, c++) {
        const WlPfFrameRec *r = &g_array_index(recs, WlPfFrameRec, n);
        const WlPfFrameStats *f = wl_pf_frame_stats(st, n);
        m.app += ms(r->app_end - r->app_start);
        m.cull += ms(r->cull_ms);
        m.draw += ms(r->draw_ms);
        m.tris += f->draw.tris;
        m.verts += f->draw.vertices;
        m.vsaved += 3 * f->draw.tris - f->draw.vertices;
        m.nodes += f->cull.nodes_visited;
        m.cbs += f->cull.callbacks + f->draw.callbacks;
        m.states += f->draw.state_changes;
        m.saved += f->draw.state_naive - f->draw.state_changes;
        m.mats += f->draw.matrix_ops;
        m.culled += f->cull.tris_culled;
        m.stress += r->stress;
        m.lod += f->cull.lods ? (double)f->cull.lod_sum / f->cull.lods : 0;
        m.cpu += ms(f->cpu);
        m.bus += ms(f->bus);
        m.pipe += ms(f->pipe);
        m.isect += ms(r->isect);
        m.itests += f->isect.nodes_tested + f->isect.tris_tested;
    }
    double *v = &m.app;
    for (guint i = 0; c && i < sizeof m / sizeof *v; i++)
        v[i] /= c;
    return m;
}

/* Busy, blocked and idle time of DRAW's CPU and of the pipe, per frame
 * over the whole run (idle: the rest of the mean frame interval). */
static void set_pipe_metrics(SimResult *out, const WlPfGpipeStats *g,
                             guint frames, SimTime elapsed)
{
    double per = 1.0 / frames, T = ms(elapsed) * per;
    double v[] = {ms(g->cpu_busy) * per, ms(g->cpu_blocked) * per,
                  ms(g->pipe_busy) * per, ms(g->pipe_blocked) * per};
    sim_result_set_metric(out, "draw_busy_ms", v[0], "ms");
    sim_result_set_metric(out, "draw_blocked_ms", v[1], "ms");
    sim_result_set_metric(out, "draw_idle_ms", MAX(T - v[0] - v[1], 0), "ms");
    sim_result_set_metric(out, "pipe_busy_ms", v[2], "ms");
    sim_result_set_metric(out, "pipe_blocked_ms", v[3], "ms");
    sim_result_set_metric(out, "pipe_idle_ms", MAX(T - v[2] - v[3], 0), "ms");
    sim_result_set_metric(out, "fifo_peak_bytes", (double)g->max_used, "B");
}

static void set_metrics(SimResult *out, const PfParams *p, const GArray *recs,
                        WlPfStages *st, guint flattened)
{
    guint skip = MIN(4u, recs->len / 4); /* < recs->len: frames >= 1 */
    double iv = wl_pf_mean_interval_s(recs, skip);
    Means m = means(recs, st, skip);
    uint64_t msaved = 0;
    for (guint n = skip; n < recs->len; n++)
        msaved += wl_pf_frame_stats(st, n)->cull.matrix_saved;
    sim_result_set_metric(out, "target_rate_hz", p->frame_hz, "Hz");
    sim_result_set_metric(out, "frame_rate_hz", iv > 0 ? 1 / iv : 0, "Hz");
    double lat = wl_pf_mean_latency_s(recs, skip);
    sim_result_set_metric(out, "latency_ms", lat * 1e3, "ms");
    sim_result_set_metric(out, "latency_frames", lat * p->frame_hz, "");
    sim_result_set_metric(out, "app_ms", m.app, "ms");
    sim_result_set_metric(out, "cull_ms", m.cull, "ms");
    sim_result_set_metric(out, "draw_ms", m.draw, "ms");
    sim_result_set_metric(out, "draw_cpu_ms", m.cpu, "ms");
    sim_result_set_metric(out, "draw_bus_ms", m.bus, "ms");
    sim_result_set_metric(out, "draw_pipe_ms", m.pipe, "ms");
    sim_result_set_metric(out, "tris_per_frame", m.tris, "");
    sim_result_set_metric(out, "vertices_per_frame", m.verts, "");
    sim_result_set_metric(out, "vertices_saved_per_frame", m.vsaved, "");
    sim_result_set_metric(out, "tris_culled_per_frame", m.culled, "");
    sim_result_set_metric(out, "cull_nodes_per_frame", m.nodes, "");
    sim_result_set_metric(out, "callbacks_per_frame", m.cbs, "");
    sim_result_set_metric(out, "isect_ms", m.isect, "ms");
    sim_result_set_metric(out, "isect_tests_per_frame", m.itests, "");
    sim_result_set_metric(out, "state_changes_per_frame", m.states, "");
    sim_result_set_metric(out, "state_changes_saved_per_frame", m.saved, "");
    sim_result_set_metric(out, "matrix_ops_per_frame", m.mats, "");
    sim_result_set_metric(out, "matrix_ops_saved_per_frame",
                          (double)msaved / (recs->len - skip), "");
    sim_result_set_metric(out, "scs_flattened", flattened, "");
    sim_result_set_metric(out, "stress_mean", m.stress, "");
    sim_result_set_metric(out, "lod_mean", m.lod, "");
}

/* ---- running ----------------------------------------------------------- */

/* The processes the mode needs for its pipes, then a forked ISECT's. */
static guint procs_needed(const PfParams *p)
{
    return wl_pf_mp_procs(p->pipe.mode, p->pipe.pipes) +
           (p->isect && p->fork_isect ? 1 : 0);
}

static gboolean get_procs(MachMachine *m, const PfParams *p, MachProc **procs,
                          GError **err)
{
    guint need = procs_needed(p), pipes = MAX(p->pipe.pipes, 1);
    /* run_pipeline calls this after wl_pf_costs_read found the costs of
     * both kinds (mach_costs_new fails on a missing kind) */
    const MachKindInfo *k = mach_kind(m, "cpu"), *g = mach_kind(m, "pipe");
    g_assert(k && g);
    if (k->count < need || g->count < pipes) {
        const char *isect = p->isect && p->fork_isect ? " + isect" : "";
        char *found =
            pipes > 1 ? g_strdup_printf("machine '%s' with %u cpu and %u "
                                        "pipe nodes",
                                        mach_name(m), k->count, g->count)
                      : g_strdup_printf("machine '%s' with %u cpu nodes",
                                        mach_name(m), k->count);
        char *exp =
            pipes > 1
                ? g_strdup_printf("%u cpus (mode %s, %u pipes%s) and %u pipes",
                                  need, wl_pf_mp_mode_names[p->pipe.mode],
                                  pipes, isect, pipes)
                : g_strdup_printf("%u cpus (mode %s%s) and a pipe", need,
                                  wl_pf_mp_mode_names[p->pipe.mode], isect);
        cfg_error(err, p->at, found, exp);
        g_free(found);
        g_free(exp);
        return FALSE;
    }
    for (guint i = 0; i < need; i++)
        procs[i] = mach_proc(m, "cpu", i);
    return TRUE;
}

static void fill_result(SimResult *out, MachMachine *m, const GArray *recs,
                        WlPfStages *st)
{
    uint64_t bytes = 0;
    for (guint n = 0; n < recs->len; n++) {
        const WlPfFrameRec *r = &g_array_index(recs, WlPfFrameRec, n);
        SimTime prev =
            n ? g_array_index(recs, WlPfFrameRec, n - 1).swap : r->app_start;
        sim_result_add_frame(out, r->swap - prev);
        wl_mark_frame(mach_engine(m), n, r->swap);
        bytes += wl_pf_frame_stats(st, n)->draw.vertices * st->c.vertex_bytes;
    }
    mach_fill_result(m, out);
    out->comm_bytes = bytes;
    out->comm_messages = recs->len;
    out->elapsed = recs->len && !sim_engine_cut(mach_engine(m))
                       ? g_array_index(recs, WlPfFrameRec, recs->len - 1).swap
                       : sim_now(mach_engine(m));
}

/* The graphics pipe processes, one per pipe: pipe i fed by its DRAW's
 * CPU through its own stream path (buses[i], pipe 0's the stages' bus). */
static void new_gpipes(const WlContext *ctx, MachMachine *m, const PfParams *p,
                       WlPfStages *st, MachProc *const *procs,
                       MachShmem *buses, WlPfGpipe **gp)
{
    for (guint i = 0; i < MAX(p->pipe.pipes, 1); i++) {
        MachProc *cpu = procs[wl_pf_mp_proc(p->pipe.mode, i, TRUE)];
        buses[i] = st->bus; /* unused yet: free from time 0 */
        gp[i] = wl_pf_gpipe_new(ctx->eng, cpu, mach_proc(m, "pipe", i),
                                i ? &buses[i] : &st->bus, p->fifo_depth,
                                p->fifo_chunk);
    }
}

/* The shared arena's metrics: the memory bus's use, the time the
 * stages' transfers waited for it and the bytes, per frame. */
static void set_arena_metrics(SimResult *out, const WlPfArena *a,
                              guint frames, SimTime elapsed)
{
    sim_result_set_metric(out, "arena_util_pct",
                          100 * mach_shmem_utilisation(&a->bus, elapsed), "%");
    sim_result_set_metric(out, "arena_wait_ms", ms(a->queued) / frames, "ms");
    sim_result_set_metric(out, "arena_bytes_per_frame",
                          (double)a->bus.bytes / frames, "B");
}

/* Runs the frames over st and reports them. */
static gboolean run_frames(const WlContext *ctx, MachMachine *m, PfParams *p,
                           WlPfStages *st, guint flattened, SimResult *out,
                           GError **err)
{
    MachProc *procs[2 + 2 * WL_PF_MAX_PIPES];
    WlPfArena arena = {0};
    if (!get_procs(m, p, procs, err) ||
        (p->has_arena &&
         !wl_pf_arena_init(&arena, ctx->eng, m, &p->arena, err)))
        return FALSE;
    guint np = MAX(p->pipe.pipes, 1);
    WlPfStageFns fns = wl_pf_stage_fns(p->isect);
    st->draw_cpu = procs[wl_pf_mp_proc(p->pipe.mode, 0, TRUE)];
    st->piped = TRUE;
    st->arena = p->arena;
    wl_pf_stages_set_pipes(st, np);
    MachShmem buses[WL_PF_MAX_PIPES];
    WlPfGpipe *gp[WL_PF_MAX_PIPES] = {NULL};
    new_gpipes(ctx, m, p, st, procs, buses, gp);
    WlPfPipeParams pp = p->pipe;
    pp.gpipe = gp[0];
    pp.gpipes = gp;
    pp.arena = p->has_arena ? &arena : NULL;
    for (guint i = 0; i < np; i++)
        wl_pf_gpipe_set_arena(gp[i], pp.arena);
    GArray *recs = g_array_new(FALSE, TRUE, sizeof(WlPfFrameRec));
    gboolean ok = wl_pf_pipe_run(ctx->eng, procs, &pp, &fns, st, recs,
                                 ctx->until, err);
    if (ok) {
        fill_result(out, m, recs, st);
        /* one message per FIFO chunk over the bus, as a replay counts */
        out->comm_messages = 0;
        for (guint i = 0; i < np; i++)
            out->comm_messages += wl_pf_gpipe_stats(gp[i])->chunks;
        sim_result_set_phases(out, ctx->eng);
    }
    if (ok && !sim_engine_cut(ctx->eng)) { /* whole runs only (run.until) */
        set_metrics(out, p, recs, st, flattened);
        set_pipe_metrics(out, wl_pf_gpipe_stats(gp[0]), recs->len,
                         out->elapsed);
        sim_result_set_metric(out, "processes", procs_needed(p), "");
        if (pp.arena)
            set_arena_metrics(out, &arena, recs->len, out->elapsed);
    }
    for (guint i = 0; i < np; i++)
        wl_pf_gpipe_free(gp[i]);
    wl_pf_arena_clear(&arena);
    char *log =
        ok ? wl_frame_log_path(ctx, p->frame_log, "performer_frames.csv")
           : NULL;
    if (log)
        ok = write_log(log, recs, st, err) && write_stages(log, recs, err);
    g_free(log);
    g_array_free(recs, TRUE);
    return ok;
}

static gboolean run_pipeline(const WlContext *ctx, MachMachine *m, PfParams *p,
                             SimResult *out, GError **err)
{
    WlPfCosts c;
    if (!wl_pf_costs_read(m, p->vertex_bytes, &c, err))
        return FALSE;
    if (p->has_app_work)
        c.app_frame = p->app_work;
    c.update = p->update_cost;
    c.strip = (guint)p->strip;
    c.cull_callback = p->cb_cull, c.draw_callback = p->cb_draw;
    WlPfTown *town = wl_pf_town_new(&p->town);
    guint flattened = p->flatten ? wl_pf_flatten(town->g) : 0;
    p->pipe.frames = (guint)ctx->frames;
    WlPfStages *st = wl_pf_stages_new(m, town, &c, p->cull, p->lazy, p->isect,
                                      p->pipe.frames, err);
    if (st)
        st->app_timed = p->has_app_work;
    gboolean ok = st && run_frames(ctx, m, p, st, flattened, out, err);
    wl_pf_stages_free(st);
    wl_pf_town_free(town);
    return ok;
}

static gboolean pf_run(const WlContext *ctx, void *params, SimResult *out,
                       GError **err)
{
    PfParams *p = params;
    return p->pn ? wl_pf_pn_run(ctx, ctx->machine, p->pn, out, err)
                 : run_pipeline(ctx, ctx->machine, p, out, err);
}

/* The pipeline generates its town (workload.town); the PN measurement
 * tessellates the config's scene. */
static void pf_plan(const void *params, WlPlan *plan)
{
    const PfParams *p = params;
    plan->reads = WL_READS_MACHINE | (p->pn ? WL_READS_SCENE : 0);
}

/* Every metric pf_run sets (set_metrics; the town's means skip the first
 * 4 frames) and wl_pf_pn_run with pn: (docs/workloads.md, "performer",
 * "PN triangles"). */
static const WlMetric pf_metrics[] = {
    {"target_rate_hz", "Hz", "the frame rate asked for"},
    {"frame_rate_hz", "Hz", "1 / mean swap interval"},
    {"latency_ms", "ms", "mean time from APP's start to the swap"},
    {"latency_frames", "", "latency_ms in frame periods (1 / frame_rate)"},
    {"processes", "", "CPUs the process model uses (with a forked ISECT)"},
    {"arena_util_pct", "%", "arena: memory bus busy / run time"},
    {"arena_wait_ms", "ms", "arena: stages' transfers waiting for the bus, "
                            "per frame"},
    {"arena_bytes_per_frame", "B", "arena: bytes the stages moved per frame"},
    {"app_ms", "ms", "mean APP stage time"},
    {"cull_ms", "ms", "mean CULL stage time"},
    {"draw_ms", "ms", "mean DRAW stage time (start to its last write)"},
    {"draw_cpu_ms", "ms", "DRAW's CPU issuing stream, mean"},
    {"draw_bus_ms", "ms", "DRAW's bus-to-pipe stream, mean"},
    {"draw_pipe_ms", "ms", "DRAW's graphics-pipe stream, mean"},
    {"draw_busy_ms", "ms", "DRAW's CPU busy per frame (whole run)"},
    {"draw_blocked_ms", "ms", "DRAW's CPU blocked on a full FIFO per frame"},
    {"draw_idle_ms", "ms", "DRAW's CPU idle per frame"},
    {"pipe_busy_ms", "ms", "graphics pipe busy per frame (whole run)"},
    {"pipe_blocked_ms", "ms", "graphics pipe holding a swap per frame"},
    {"pipe_idle_ms", "ms", "graphics pipe idle (no commands) per frame"},
    {"fifo_peak_bytes", "B", "highest fill of the pipe's command FIFO"},
    {"tris_per_frame", "", "triangles drawn per frame"},
    {"vertices_per_frame", "", "vertices DRAW sent per frame"},
    {"vertices_saved_per_frame", "",
     "vertices strips saved per frame (3 x triangles - vertices)"},
    {"tris_culled_per_frame", "", "triangles culled per frame"},
    {"cull_nodes_per_frame", "", "nodes CULL visited per frame"},
    {"callbacks_per_frame", "", "traversal callbacks run per frame"},
    {"isect_ms", "ms", "mean ISECT time (0: no isect)"},
    {"isect_tests_per_frame", "",
     "ISECT's nodes + triangles tested per frame (partition: fewer)"},
    {"state_changes_per_frame", "", "graphics state changes per frame"},
    {"state_changes_saved_per_frame", "",
     "state changes lazy evaluation saved (eager - lazy)"},
    {"matrix_ops_per_frame", "", "matrix operations per frame"},
    {"matrix_ops_saved_per_frame", "", "matrix operations pfFlatten saved"},
    {"scs_flattened", "", "static coordinate systems flattened"},
    {"stress_mean", "", "mean load-management stress"},
    {"lod_mean", "", "mean LOD child chosen (3 = none)"},
    {"level", "", "pn: tessellation level L"},
    {"coarse_tris", "", "pn: triangles of the coarse mesh"},
    {"fine_tris", "", "pn: triangles after tessellation"},
    {"link_bytes_per_frame", "B",
     "pn: bytes to the tessellating processors per frame"},
    {"command_bytes_per_frame", "B",
     "pn, Pixel-Planes 5: renderer command bytes per frame"},
    {"cpu_ms", "ms", "pn, shared memory: CPU time"},
    {"bus_ms", "ms", "pn, shared memory: bus time"},
    {"pipe_ms", "ms", "pn, shared memory: graphics-pipe time"},
    {"gp_ms", "ms", "pn, Pixel-Planes 5: GP time"},
    {"frame_ms", "ms", "pn: mean frame time"},
    {"fine_tris_per_s", "1/s", "pn: fine triangles per second"},
    {"lod_memory_bytes", "B",
     "pn with memory: pre-tessellated levels from..to stored"},
    {"pn_memory_bytes", "B", "pn with memory: base mesh + PN control data"},
    {"level_first", "", "pn with lod: PN level of the first frame"},
    {"level_last", "", "pn with lod: PN level of the last frame"},
    {"fine_tris_first", "", "pn with lod: triangles drawn, first frame"},
    {"fine_tris_last", "", "pn with lod: triangles drawn, last frame"},
    {"interval_ms_last", "ms",
     "pn with lod: mean frame interval over the last quarter"},
    {"stress_max", "", "pn with lod: largest stress CULL used"},
    {"lod_memory_ratio", "",
     "pn with memory: lod_memory_bytes / pn_memory_bytes (slides: 70x)"},
    {NULL, NULL, NULL},
};

const WlOps wl_pf_ops = {
    .name = "performer",
    .summary = "IRIS Performer's multiprocessed frame pipeline (APP, CULL, "
               "DRAW, ISECT) on a shared-memory machine with one graphics "
               "pipe; with pn:, curved PN triangles as geometry compression",
    .parse = pf_parse,
    .free_params = pf_free,
    .plan = pf_plan,
    .run = pf_run,
    .needs = wl_pf_town_needs,
    .needs_alt = wl_pf_pn_needs,
    .mem_bytes = pf_mem_bytes,
    .metrics = pf_metrics,
};
