/* ag_workload.c — the `argus` workload: the parallel graphics API of
 * Igehy, Stoll and Hanrahan (SIGGRAPH 1998, seed 002) on its Argus
 * implementation, a sort-middle tiled renderer of application, geometry
 * and rasterisation threads on a shared-memory multiprocessor.
 *
 *   workload:
 *     type: argus
 *     processors: 24        # P <= the machine's `cpu` count
 *     contexts: 4           # graphics contexts = application threads
 *     geometry: 10          # geometry threads (default (P - C) / 2)
 *     rasterisers: 10       # rasterisation threads (default P - C - G)
 *     workers: split        # split: G geometry threads and R rasterisers
 *                           # owning tiles statically; pool: G + R
 *                           # workers, each taking geometry work first,
 *                           # else any ready tile (ag_pipe.h)
 *     uniprocessor: false   # everything on one processor, no queues
 *     application: nurbs    # none | nurbs | march (application work)
 *     voxels_per_cell: 4096 # march: voxels visited per cell (16^3)
 *     cells: 4              # order cells/none: cells per axis (0: from
 *                           # the last tag)
 *     order: frame          # frame | cells | none (ag_stream.h)
 *     primitives: strips    # strips | triangles (vertices issued)
 *     pixels: opaque        # opaque (z-buffer) | blend (back to front)
 *     alpha: 0.35           # blend opacity
 *     fill_rate: infinite   # infinite (seed 002's footnote) | finite
 *     tile: 128             # tile side in pixels
 *     block: 64             # triangles per command block
 *     bytes: {vertex: 32 B, triangle: 64 B, state: 32 B, call: 8 B}
 *     state: none           # none | stateful | stateless (ag_stream.h)
 *     mode: immediate       # immediate | retained (display lists)
 *     buffer: 0             # command buffer per context (0: unbounded)
 *     sync: glp             # glp | finish (the glFinish baseline)
 *     finish: pipe          # sync finish: glFinish drains the pipe | context
 *     ordering: pixel       # pixel | geometry (ag_pipe.h AgScheme)
 *     width: 1200           # default: the scene's suggested viewport
 *     height: 1000
 *     check_image: true     # every frame equals the serial render
 *
 * The scene (`scene:`) gives the batches: runs of polygons with one tag
 * (generator nurbs: patches; march: cells).  The machine needs a `cpu`
 * node kind with the costs of ag_pipe.h and a bus network (the shared
 * memory, sim/machine/shmem.h): models/origin2000.yaml.  Frames: the
 * camera is fixed (seed 002 measures a static scene), frames repeat the
 * whole pipeline; frame_hz is 1 / mean frame time.
 */
#include "sim/workload/argus/ag_workload.h"
#include "sim/scene/scene_cfg.h"
#include <string.h>

static const char *const fills[] = {"infinite", "finite", NULL};
static const char *const workers[] = {"split", "pool", NULL};
static const char *const modes[] = {"immediate", "retained", NULL};
static const char *const scopes[] = {"pipe", "context", NULL};

static gboolean parse_words(const CfgNode *sec, WlAgParams *p, GError **err)
{
    int app = WL_AG_APP_NONE, ord = WL_AG_ORDER_FRAME, prim = 0, pix = 0;
    int fill = 0, work = 0, state = 0, scheme = 0, sync = 0, mode = 0;
    int scope = 0;
    gboolean ok =
        cfg_get_enum(sec, "application", FALSE, wl_ag_app_names, &app, err) &&
        cfg_get_enum(sec, "order", FALSE, wl_ag_order_names, &ord, err) &&
        cfg_get_enum(sec, "primitives", FALSE, wl_ag_prim_names, &prim, err) &&
        cfg_get_enum(sec, "pixels", FALSE, wl_ag_pixel_names, &pix, err) &&
        cfg_get_enum(sec, "fill_rate", FALSE, fills, &fill, err) &&
        cfg_get_enum(sec, "workers", FALSE, workers, &work, err) &&
        cfg_get_enum(sec, "state", FALSE, wl_ag_state_names, &state, err) &&
        cfg_get_enum(sec, "ordering", FALSE, wl_ag_scheme_names, &scheme,
                     err) &&
        cfg_get_enum(sec, "sync", FALSE, wl_ag_sync_names, &sync, err) &&
        cfg_get_enum(sec, "mode", FALSE, modes, &mode, err) &&
        cfg_get_enum(sec, "finish", FALSE, scopes, &scope, err);
    p->setup.app = (AgApp)app;
    p->order = (AgOrder)ord;
    p->prim = (AgPrim)prim;
    p->pixels = (AgPixelMode)pix;
    p->setup.fill_infinite = fill == 0;
    p->setup.pool = work == 1;
    p->state = (AgStateMode)state;
    p->setup.scheme = (AgScheme)scheme;
    p->setup.sync = (AgSyncMode)sync;
    p->setup.retained = mode == 1;
    p->setup.finish_context = scope == 1;
    return ok;
}

static gboolean parse_bytes(const CfgNode *sec, WlAgParams *p, GError **err)
{
    uint64_t v = 32, t = 64, st = 32, call = 8, buf = 0;
    const CfgNode *n;
    if (!cfg_get_map(sec, "bytes", FALSE, "a map {vertex, triangle} of sizes",
                     &n, err))
        return FALSE;
    if (n && (!cfg_get_size(n, "vertex", FALSE, &v, err) ||
              !cfg_get_size(n, "triangle", FALSE, &t, err) ||
              !cfg_get_size(n, "state", FALSE, &st, err) ||
              !cfg_get_size(n, "call", FALSE, &call, err)))
        return FALSE;
    if (!cfg_get_size(sec, "buffer", FALSE, &buf, err))
        return FALSE;
    p->setup.state_bytes = (guint)MIN(st, 1u << 20);
    p->setup.call_bytes = (guint)MIN(call, 1u << 20);
    p->setup.buffer_bytes = buf;
    p->setup.vertex_bytes = (guint)MIN(v, 1u << 20);
    p->setup.triangle_bytes = (guint)MIN(t, 1u << 20);
    return TRUE;
}

/* contexts, geometry, rasterisers: defaults split P - C evenly. */
static gboolean parse_threads(const CfgNode *sec, WlAgParams *p, GError **err)
{
    uint64_t P = 24, C = 1, G = 0, R = 0;
    if (!cfg_get_count(sec, "processors", FALSE, 1, 4096, &P, err) ||
        !cfg_get_count(sec, "contexts", FALSE, 1, 1024, &C, err) ||
        !cfg_get_count(sec, "geometry", FALSE, 1, 1024, &G, err) ||
        !cfg_get_count(sec, "rasterisers", FALSE, 1, 1024, &R, err))
        return FALSE;
    uint64_t rest = P - MIN(P, C); /* processors beyond the contexts */
    if (!G)
        G = MAX(1, rest / 2);
    if (!R)
        R = rest > G ? rest - G : 1;
    p->setup.procs = (guint)P;
    p->setup.contexts = (guint)C;
    p->setup.geometry = (guint)G;
    p->setup.rasterisers = (guint)R;
    return TRUE;
}

static void *ag_parse(const CfgNode *sec, GError **err)
{
    WlAgParams *p = g_new0(WlAgParams, 1);
    uint64_t vox = 4096, tile = 128, block = 64, w = 0, h = 0, cells = 0;
    p->alpha = 0.35;
    p->check_image = TRUE;
    gboolean ok =
        parse_words(sec, p, err) && parse_threads(sec, p, err) &&
        parse_bytes(sec, p, err) &&
        cfg_get_bool(sec, "uniprocessor", FALSE, &p->setup.uniprocessor, err) &&
        cfg_get_count(sec, "voxels_per_cell", FALSE, 0, 1u << 30, &vox, err) &&
        cfg_get_count(sec, "tile", FALSE, 8, 4096, &tile, err) &&
        cfg_get_count(sec, "cells", FALSE, 0, 1024, &cells, err) &&
        cfg_get_count(sec, "block", FALSE, 1, 1u << 20, &block, err) &&
        cfg_get_double(sec, "alpha", FALSE, 0, 1, &p->alpha, err) &&
        cfg_get_count(sec, "width", FALSE, 16, RAST_MAX_SIDE, &w, err) &&
        cfg_get_count(sec, "height", FALSE, 16, RAST_MAX_SIDE, &h, err) &&
        cfg_get_bool(sec, "check_image", FALSE, &p->check_image, err);
    if (!ok) {
        g_free(p);
        return NULL;
    }
    p->setup.voxels_per_batch = vox;
    p->tile = (guint)tile;
    p->cells = (guint)cells;
    p->block_tris = (guint)block;
    p->width = (int)w;
    p->height = (int)h;
    if (p->setup.uniprocessor) {
        p->setup.procs = 1;
        p->setup.contexts = p->setup.geometry = p->setup.rasterisers = 1;
    }
    return p;
}

static void ag_free_params(void *params)
{
    g_free(params);
}

/* Own memory (WlOps.mem_bytes): the tiled frame (rgb floats, depth, prim
 * id: 24 B a pixel; twice with check_image, for the serial reference),
 * the output image (3 B a pixel) and the per-tile tables (a cursor per
 * context, a semaphore, a round-robin slot).  Width or height 0 (the
 * scene's viewport) counts as the 1200 used without a scene size. */
static double ag_mem_bytes(const void *params, GString *what)
{
    const WlAgParams *p = params;
    double w = p->width ? p->width : 1200, h = p->height ? p->height : 1200;
    double tiles = (double)(((guint)w + p->tile - 1) / p->tile) *
                   (double)(((guint)h + p->tile - 1) / p->tile);
    g_string_append_printf(what, "%.0f x %.0f pixels, %u contexts", w, h,
                           p->setup.contexts);
    return w * h * (24.0 * (p->check_image ? 2 : 1) + 3) +
           tiles * 4.0 * (p->setup.contexts + 2);
}

/* ---- running ------------------------------------------------------------ */

typedef struct {
    MachMachine *m; /* borrowed from the runner */
    const Scene *scene; /* borrowed from the runner */
    SceneMesh *mesh; /* flattened, triangles only */
    AgStreams *st;
    AgFrame *f;
    RastView view;
    AgPipe *pipe;
    GArray *stats; /* AgFrameStats */
} Run;

static void run_clear(Run *r)
{
    wl_ag_pipe_free(r->pipe);
    wl_ag_frame_free(r->f);
    wl_ag_streams_free(r->st);
    scene_mesh_free(r->mesh);
    if (r->stats)
        g_array_unref(r->stats);
}

static gboolean triangles_only(const SceneMesh *m, GError **err)
{
    for (guint i = 0; i < scene_mesh_n_polys(m); i++)
        if (scene_mesh_poly_len(m, i) != 3) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "argus: found a polygon of %u vertices (polygon %u), "
                        "expected triangles (generators nurbs, march)",
                        scene_mesh_poly_len(m, i), i);
            return FALSE;
        }
    return TRUE;
}

static gboolean check_machine(Run *r, WlAgParams *p, const CfgNode *root,
                              GError **err)
{
    const MachKindInfo *k = mach_kind(r->m, "cpu");
    if (!k || k->count < p->setup.procs) {
        char *found = g_strdup_printf("%u processors", p->setup.procs);
        char *exp = g_strdup_printf("at most the %u 'cpu' processors of "
                                    "machine '%s'",
                                    k ? k->count : 0, mach_name(r->m));
        const CfgNode *at = cfg_path(root, "workload.processors");
        cfg_error(err, at ? at : root, found, exp);
        g_free(found);
        g_free(exp);
        return FALSE;
    }
    if (p->setup.uniprocessor)
        return TRUE;
    MachShmem sh;
    if (!mach_shmem_init(&sh, r->m, err))
        return FALSE;
    p->setup.mem_bandwidth = sh.bandwidth;
    p->setup.mem_latency = sh.latency;
    return TRUE;
}

static gboolean build(Run *r, const WlContext *ctx, WlAgParams *p, GError **err)
{
    r->scene = ctx->scene;
    r->m = ctx->machine;
    if (!check_machine(r, p, ctx->root, err) ||
        !mach_costs_check(r->m, wl_ag_needs, err))
        return FALSE;
    r->mesh = scene_flatten(r->scene);
    if (!triangles_only(r->mesh, err))
        return FALSE;
    r->st = wl_ag_streams_new(r->mesh, p->setup.contexts, p->order, p->prim,
                              p->block_tris, p->cells, err);
    if (!r->st)
        return FALSE;
    wl_ag_streams_set_state(r->st, r->mesh, p->state);
    int w =
        p->width ? p->width : (r->scene->width ? (int)r->scene->width : 1200);
    int h = p->height ? p->height
                      : (r->scene->height ? (int)r->scene->height : 1000);
    RastColor bg = {r->scene->background.r, r->scene->background.g,
                    r->scene->background.b};
    r->f = wl_ag_frame_new(w, h, (int)p->tile, p->pixels, (float)p->alpha, bg);
    r->view = rast_view_for_camera(&r->scene->camera, w, h);
    r->view.cull_back = FALSE;
    r->pipe =
        wl_ag_pipe_new(r->m, &p->setup, r->st, r->f, r->mesh, &r->view);
    return TRUE;
}

/* Pixels that differ from the serial render (all batches in mesh order,
 * one stream, the whole frame at once). */
static uint64_t serial_diff(const Run *r, const WlAgParams *p, RastImage *img)
{
    AgFrame *ref = wl_ag_frame_new(r->f->width, r->f->height, (int)p->tile,
                                   p->pixels, (float)p->alpha, r->f->bg);
    guint n = scene_mesh_n_polys(r->mesh);
    uint32_t *all = g_new(uint32_t, n); /* NULL for n = 0: never read */
    for (guint i = 0; i < n; i++)
        all[i] = i;
    wl_ag_draw(ref, G_MAXUINT, &r->view, r->mesh, all, n);
    RastImage *a = wl_ag_frame_image(ref);
    uint64_t d = rast_image_diff(a, img);
    rast_image_free(a);
    g_free(all);
    wl_ag_frame_free(ref);
    return d;
}

static void set(SimResult *out, const char *name, double v, const char *unit)
{
    sim_result_set_metric(out, name, v, unit);
}

static void fill_metrics(SimResult *out, const Run *r, const WlAgParams *p)
{
    const AgSetup *s = &p->setup;
    double n = r->stats->len, ms = 0, app = 0, geo = 0, ras = 0, px = 0;
    double blocked = 0, waited = 0, bad = 0;
    const AgFrameStats *f0 = &g_array_index(r->stats, AgFrameStats, 0);
    for (guint i = 0; i < r->stats->len; i++) {
        const AgFrameStats *f = &g_array_index(r->stats, AgFrameStats, i);
        ms += sim_time_to_ms(f->end - f->start);
        app += sim_time_to_ms(f->app_busy);
        geo += sim_time_to_ms(f->geom_busy);
        ras += sim_time_to_ms(f->rast_busy);
        px += (double)f->pixels;
        blocked += sim_time_to_ms(f->issue_blocked);
        waited += sim_time_to_ms(f->finish_wait);
        bad += (double)f->order_violations;
    }
    const AgFrameStats *fl =
        &g_array_index(r->stats, AgFrameStats, r->stats->len - 1);
    set(out, "processors", s->procs, "");
    set(out, "contexts", s->contexts, "");
    set(out, "geometry_threads", s->geometry, "");
    set(out, "rasterisers", s->rasterisers, "");
    set(out, "tiles", wl_ag_n_tiles(r->f), "");
    set(out, "frame_ms", ms / n, "ms");
    set(out, "frame_hz", ms > 0 ? 1000.0 * n / ms : 0, "Hz");
    set(out, "triangles", (double)f0->triangles, "");
    set(out, "vertices_issued", (double)f0->verts_issued, "");
    set(out, "batches", r->st->batches->len, "");
    set(out, "blocks", (double)f0->blocks, "");
    set(out, "sync_commands", (double)r->st->syncs, "");
    set(out, "tile_syncs", (double)f0->syncs, "");
    set(out, "bucketed_triangles", (double)f0->bucketed, "");
    set(out, "pixels", px / n, "");
    set(out, "application_ms", app / n, "ms");
    set(out, "geometry_ms", geo / n, "ms");
    set(out, "rasterisation_ms", ras / n, "ms");
    set(out, "shared_memory_bytes", (double)f0->shmem_bytes, "B");
    set(out, "state_commands", (double)f0->states, "");
    set(out, "command_bytes", (double)f0->command_bytes, "B");
    set(out, "command_bytes_last", (double)fl->command_bytes, "B");
    set(out, "application_ms_last", sim_time_to_ms(fl->app_busy), "ms");
    set(out, "frame_ms_last", sim_time_to_ms(fl->end - fl->start), "ms");
    set(out, "issue_blocked_ms", blocked / n, "ms");
    set(out, "finish_wait_ms", waited / n, "ms");
    set(out, "order_violations", bad, "");
}

/* The serial-render check of the last frame (check_image). */
static void check_image(Run *r, WlAgParams *p, SimResult *out)
{
    if (!p->check_image)
        return;
    RastImage *img = wl_ag_frame_front_image(r->f);
    uint64_t d = serial_diff(r, p, img);
    set(out, "image_matches_serial", d == 0, "");
    set(out, "pixels_differing", (double)d, "");
    rast_image_free(img);
}

/* The frame hook (pgsim run --out DIR): DIR/frame.png, or every frame's
 * image with --frames all. */
static gboolean emit_frame(const WlContext *ctx, const Run *r, int f,
                           GError **err)
{
    if (!wl_wants_frame(ctx, f))
        return TRUE;
    RastImage *img = wl_ag_frame_front_image(r->f);
    gboolean ok = wl_emit_frame(ctx, f, img, err);
    rast_image_free(img);
    return ok;
}

static gboolean ag_run(const WlContext *ctx, void *params, SimResult *out,
                       GError **err)
{
    WlAgParams *p = params;
    Run r = {0};
    gboolean ok = build(&r, ctx, p, err);
    r.stats = g_array_new(FALSE, TRUE, sizeof(AgFrameStats));
    for (int f = 0; ok && f < ctx->frames; f++) {
        AgFrameStats fs;
        ok = wl_ag_pipe_frame(r.pipe, ctx->until, &fs, err);
        if (ok && sim_engine_cut(ctx->eng))
            break; /* run.until ended the run inside this frame */
        if (ok) {
            g_array_append_val(r.stats, fs);
            sim_result_add_frame(out, fs.end - fs.start);
            wl_mark_frame(ctx->eng, (guint)f, fs.end);
            ok = emit_frame(ctx, &r, f, err);
        }
    }
    if (ok && sim_engine_cut(ctx->eng)) {
        mach_fill_result(r.m, out);
        out->elapsed = sim_now(ctx->eng);
    } else if (ok) {
        mach_fill_result(r.m, out);
        fill_metrics(out, &r, p);
        check_image(&r, p, out);
        out->elapsed = sim_now(ctx->eng);
    }
    run_clear(&r);
    return ok;
}

/* Every metric ag_run sets, in order (docs/workloads.md, "argus");
 * per-frame figures of the first frame unless said. */
static const WlMetric ag_metrics[] = {
    {"processors", "", "processors of the machine used"},
    {"contexts", "", "application contexts (drawing streams)"},
    {"geometry_threads", "", "geometry threads"},
    {"rasterisers", "", "rasteriser threads"},
    {"tiles", "", "screen tiles"},
    {"frame_ms", "ms", "mean frame time"},
    {"frame_hz", "Hz", "frames per second of simulated time"},
    {"triangles", "", "triangles drawn"},
    {"vertices_issued", "", "vertices the contexts issued"},
    {"batches", "", "batches in the streams"},
    {"blocks", "", "command blocks"},
    {"sync_commands", "", "synchronisation commands in the streams"},
    {"tile_syncs", "", "synchronisation commands processed at tiles"},
    {"bucketed_triangles", "", "triangles put in tile queues"},
    {"pixels", "", "fragments per frame, mean over frames"},
    {"application_ms", "ms", "application busy time summed over threads"},
    {"geometry_ms", "ms", "geometry busy time summed over threads"},
    {"rasterisation_ms", "ms", "rasteriser busy time summed over threads"},
    {"shared_memory_bytes", "B", "bytes booked on the shared memory"},
    {"state_commands", "", "state commands the contexts issued"},
    {"command_bytes", "B", "bytes written into the command buffers"},
    {"command_bytes_last", "B",
     "the same in the last frame (retained: display-list calls)"},
    {"application_ms_last", "ms", "application busy time, last frame"},
    {"frame_ms_last", "ms", "the last frame's time"},
    {"issue_blocked_ms", "ms",
     "application threads blocked on a full command buffer, summed, mean "
     "over frames"},
    {"finish_wait_ms", "ms",
     "sync finish: application threads in glFinish or waiting for another "
     "thread, summed, mean over frames"},
    {"order_violations", "",
     "synchronisation commands a tile's drawing order broke, all frames"},
    {"image_matches_serial", "",
     "check_image: 1 when the last frame equals the serial render"},
    {"pixels_differing", "", "check_image: pixels that differ from it"},
    {NULL, NULL, NULL},
};

const WlOps wl_argus_ops = {
    .name = "argus",
    .summary = "igehy98: the parallel graphics API (glpBarrier, glpPSema/"
               "VSema) on Argus, a sort-middle tiled renderer of "
               "application, geometry and rasterisation threads on a "
               "shared-memory multiprocessor",
    .parse = ag_parse,
    .free_params = ag_free_params,
    .plan = wl_plan_machine_scene,
    .run = ag_run,
    .mem_bytes = ag_mem_bytes,
    .needs = wl_ag_needs,
    .metrics = ag_metrics,
};
