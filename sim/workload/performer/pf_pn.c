/* pf_pn.c — the PN-triangle geometry-compression measurement (see
 * pf_pn.h).  Each frame is a few messages and computations whose
 * completions are counted down; the frame ends when the count is zero.
 * Costs are the model's; bytes are counted at the sender and moved by
 * the machine's network.
 */
#include "sim/workload/performer/pf_pn.h"

#include "sim/core/trace.h"
#include "sim/machine/shmem.h"
#include "sim/workload/performer/pf_gpipe.h"
#include "sim/workload/performer/pf_pnlod.h"
#include "sim/scene/scene_cfg.h"

static const char *const normals[] = {"linear", "quadratic", NULL};
static const char *const sends[] = {"coarse", "fine", NULL};

/* The optional `memory:` map: the counting rule of pn_memory.h. */
static gboolean mem_parse(const CfgNode *pn, WlPfPnParams *p, GError **err)
{
    const CfgNode *mem;
    if (!cfg_get_map(pn, "memory", FALSE,
                     "a map {from, to, layout, index_bytes, control_bytes}",
                     &mem, err))
        return FALSE;
    if (!mem)
        return TRUE;
    uint64_t lo = 0, hi = 4;
    int layout = SCENE_PN_MEM_INDEXED;
    ScenePnMemRule *r = &p->mem;
    r->index_bytes = 4;
    if (!cfg_get_count(mem, "from", FALSE, 0, 32, &lo, err) ||
        !cfg_get_count(mem, "to", FALSE, lo, 32, &hi, err) ||
        !cfg_get_enum(mem, "layout", FALSE, scene_pn_mem_layouts, &layout,
                      err) ||
        !cfg_get_size(mem, "index_bytes", FALSE, &r->index_bytes, err) ||
        !cfg_get_size(mem, "control_bytes", FALSE, &r->control_bytes, err))
        return FALSE;
    r->lo = (guint)lo, r->hi = (guint)hi;
    r->layout = (ScenePnMemLayout)layout;
    p->memory = TRUE;
    return TRUE;
}

WlPfPnParams *wl_pf_pn_params_parse(const CfgNode *pn, GError **err)
{
    WlPfPnParams *p = g_new0(WlPfPnParams, 1);
    uint64_t level = 2;
    int nk = 0, send = 0;
    p->vertex_bytes = 32;
    p->fifo_depth = WL_PF_FIFO_DEPTH, p->fifo_chunk = WL_PF_FIFO_CHUNK;
    p->command_bytes = 100;
    if (cfg_kind(pn) != CFG_MAP) {
        cfg_error(err, pn, "a non-map", "pn: {level, normals, send}");
    } else if (cfg_get_count(pn, "level", FALSE, 0, 32, &level, err) &&
               cfg_get_enum(pn, "normals", FALSE, normals, &nk, err) &&
               cfg_get_enum(pn, "send", FALSE, sends, &send, err) &&
               cfg_get_size(pn, "vertex_bytes", FALSE, &p->vertex_bytes, err) &&
               cfg_get_size(pn, "command_bytes", FALSE, &p->command_bytes,
                            err)) {
        p->pn = (ScenePnParams){(guint)level, (ScenePnNormals)nk, FALSE};
        p->send_fine = send == 1;
        const CfgNode *lod = cfg_get(pn, "lod");
        if (mem_parse(pn, p, err) &&
            (!lod || (p->lod = wl_pf_pnlod_parse(lod, err))))
            return p;
    }
    g_free(p);
    return NULL;
}

void wl_pf_pn_params_free(WlPfPnParams *p)
{
    if (p)
        wl_pf_pnlod_free(p->lod);
    g_free(p);
}

/* ---- the mesh ---------------------------------------------------------- */

typedef struct {
    uint64_t coarse_tris, fine_tris, fine_points; /* per frame */
    uint64_t lod_bytes, base_bytes; /* with memory: (pn_memory.h) */
} PnMesh;

/* Adds one instance's LOD store and PN store (the scene draws every
 * instance, so each is stored). */
static void p_mem_add(PnMesh *out, const SceneMesh *m, const WlPfPnParams *p)
{
    ScenePnMemRule r = p->mem;
    r.vertex_bytes = p->vertex_bytes;
    out->lod_bytes += scene_pn_lod_store_bytes(m, &r);
    out->base_bytes += scene_pn_base_store_bytes(m, &r);
}

static gboolean pn_mesh(const WlContext *ctx, const WlPfPnParams *p,
                        PnMesh *out, GError **err)
{
    const CfgNode *sec = cfg_get(ctx->root, "scene");
    if (sec && cfg_get(sec, "pn_triangles")) {
        cfg_error(err, cfg_get(sec, "pn_triangles"), "a pre-tessellated scene",
                  "the coarse scene (workload.pn tessellates it)");
        return FALSE;
    }
    const Scene *s = ctx->scene;
    *out = (PnMesh){0};
    for (guint i = 0; i < scene_n_instances(s); i++) {
        SceneMesh *fine =
            scene_pn_tessellate(scene_instance_mesh(s, i), &p->pn);
        out->fine_tris += scene_mesh_n_triangles(fine);
        out->fine_points += scene_mesh_n_vertices(fine);
        scene_mesh_free(fine);
        if (p->memory)
            p_mem_add(out, scene_instance_mesh(s, i), p);
    }
    out->coarse_tris = scene_n_triangles(s);
    return TRUE;
}

/* ---- one frame's countdown --------------------------------------------- */

typedef struct {
    const WlContext *ctx;
    MachMachine *m;
    const WlPfPnParams *p;
    PnMesh mesh;
    SimResult *out;
    guint pending, frames_left;
    SimTime frame_start;
    uint64_t link_bytes;        /* to the tessellating processors */
    uint64_t cmd_bytes;         /* Pixel-Planes 5: GPs to renderers */
    SimTime cpu, bus, pipe, gp; /* stage times of the last frame */
    MachShmem bus_mem;          /* shared-memory machine: CPU -> pipe */
    WlPfGpipe *gpipe;           /* ... through the pipe's FIFO */
    void (*start)(void *run);
} PnRun;

static void frame_start(SimEngine *eng, void *ctx, void *arg);

static void part_done(PnRun *r)
{
    g_assert(r->pending > 0);
    if (--r->pending)
        return;
    SimEngine *eng = mach_engine(r->m);
    sim_result_add_frame(r->out, sim_now(eng) - r->frame_start);
    wl_mark_frame(eng, r->out->frame_times->len - 1, sim_now(eng));
    if (--r->frames_left)
        sim_schedule_in(eng, 0, frame_start, r, NULL);
}

static void proc_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    part_done(ctx);
}

static uint64_t sent_tris(const PnRun *r)
{
    return r->p->send_fine ? r->mesh.fine_tris : r->mesh.coarse_tris;
}

/* ---- shared-memory machine: CPU -> bus -> pipe ------------------------- */

void wl_pf_pn_draw_work(const WlPfPnParams *p, guint level, uint64_t coarse,
                        uint64_t fine, uint64_t points, WlPfDrawWork *w)
{
    uint64_t verts = 3 * (p->send_fine ? fine : coarse);
    gboolean tess = !p->send_fine && level > 0;
    *w = (WlPfDrawWork){.bytes = verts * p->vertex_bytes};
    mach_ops_add(&w->cpu_ops, "draw_vertex", verts);
    mach_ops_add(&w->pipe_ops, "pn_vertex", tess ? points : 0);
    mach_ops_add(&w->pipe_ops, "triangle", fine);
}

/* The pipe swapped the frame: it is done. */
static void smp_swapped(void *ctx, guint n)
{
    (void)n;
    part_done(ctx);
}

/* One frame through the graphics pipe process (pf_gpipe.h), as the town's
 * DRAW: the CPU issues in chunks into the FIFO over the bus, the pipe
 * tessellates and draws them; the frame ends at the pipe's last command
 * (swaps on no retrace). */
static void smp_frame(void *run)
{
    PnRun *r = run;
    MachMachine *m = r->m;
    MachProc *cpu = mach_proc(m, "cpu", 0), *pipe = mach_proc(m, "pipe", 0);
    WlPfDrawWork w;
    wl_pf_pn_draw_work(r->p, r->p->pn.level, r->mesh.coarse_tris,
                       r->mesh.fine_tris, r->mesh.fine_points, &w);
    uint64_t bytes = w.bytes;
    r->cpu = mach_proc_ops_cost(cpu, &w.cpu_ops);
    r->pipe = mach_proc_ops_cost(pipe, &w.pipe_ops);
    r->bus = mach_shmem_time(&r->bus_mem, bytes);
    r->pending = 1;
    r->link_bytes += bytes;
    if (!r->gpipe) {
        r->gpipe = wl_pf_gpipe_new(mach_engine(m), cpu, pipe, &r->bus_mem,
                                   r->p->fifo_depth, r->p->fifo_chunk);
        wl_pf_gpipe_set_swap(r->gpipe, 1, NULL, smp_swapped, r);
    }
    wl_pf_gpipe_frame(r->gpipe, r->out->frame_times->len, &w);
}

/* ---- Pixel-Planes 5: host -> ring -> GPs -> ring -> renderers ---------- */

typedef struct {
    PnRun *r;
    guint gp;
} GpJob;

static uint64_t share(uint64_t total, guint i, guint n)
{
    return total / n + (i < total % n);
}

/* A renderer receives GP g's k-th share of renderer commands. */
static void rd_arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    PnRun *r = ctx;
    MachMachine *m = r->m;
    guint k = GPOINTER_TO_UINT(d->payload);
    MachOp op = {"primitive", d->bytes / r->p->command_bytes};
    mach_proc_compute_ops(mach_proc(m, "renderer", k), &op, 1, 0, proc_done, r,
                          NULL);
}

/* GP g has tessellated and transformed its share: it sends every
 * renderer its part of the fine triangles as renderer commands. */
static void gp_computed(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    PnRun *r = ctx;
    MachMachine *m = r->m;
    guint g = GPOINTER_TO_UINT(arg), ng = mach_kind(m, "gp")->count;
    guint nr = mach_kind(m, "renderer")->count;
    uint64_t mine = share(r->mesh.fine_tris, g, ng);
    uint32_t src = mach_proc_id(mach_proc(m, "gp", g));
    for (guint k = 0; k < nr; k++) {
        uint64_t cmds = share(mine, k, nr);
        if (!cmds)
            continue;
        r->pending++;
        r->cmd_bytes += cmds * r->p->command_bytes;
        net_send(mach_net(m), src, mach_proc_id(mach_proc(m, "renderer", k)),
                 cmds * r->p->command_bytes, GUINT_TO_POINTER(k), rd_arrived,
                 r);
    }
    part_done(r);
}

static void gp_arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    PnRun *r = ctx;
    MachMachine *m = r->m;
    guint g = GPOINTER_TO_UINT(d->payload), ng = mach_kind(m, "gp")->count;
    uint64_t fine = share(r->mesh.fine_tris, g, ng);
    gboolean tess = !r->p->send_fine && r->p->pn.level > 0;
    MachProc *gp = mach_proc(m, "gp", g);
    MachOps o = {0}; /* named counts, for a recording */
    mach_ops_add(&o, "polygon", fine);
    mach_ops_add(&o, "vertex", 3 * fine);
    mach_ops_add(&o, "send_primitive", fine);
    mach_ops_add(&o, "pn_vertex", tess ? share(r->mesh.fine_points, g, ng) : 0);
    r->gp = MAX(r->gp, mach_proc_ops_cost(gp, &o));
    mach_proc_compute_list(gp, &o, 0, gp_computed, r, GUINT_TO_POINTER(g));
}

static void pp5_frame(void *run)
{
    PnRun *r = run;
    MachMachine *m = r->m;
    guint ng = mach_kind(m, "gp")->count;
    uint32_t host = mach_proc_id(mach_proc(m, "host", 0));
    r->pending = ng;
    r->gp = 0;
    for (guint g = 0; g < ng; g++) {
        uint64_t bytes = 3 * share(sent_tris(r), g, ng) * r->p->vertex_bytes;
        r->link_bytes += bytes;
        net_send(mach_net(m), host, mach_proc_id(mach_proc(m, "gp", g)), bytes,
                 GUINT_TO_POINTER(g), gp_arrived, r);
    }
}

static void frame_start(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    PnRun *r = ctx;
    r->frame_start = sim_now(eng);
    r->start(r);
}

/* ---- run --------------------------------------------------------------- */

static const char *const smp_ops[] = {"draw_vertex", NULL};
static const char *const pipe_ops[] = {"triangle", "pn_vertex", NULL};
static const char *const gp_ops[] = {"polygon", "vertex", "send_primitive",
                                     "pn_vertex", NULL};
static const char *const rd_ops[] = {"primitive", NULL};
/* Each op's portable work (sim/machine/work.h), as the town's and
 * pphigs' tables: a cost the model lacks is derived from it.  A grid
 * point is a cubic position and a quadratic normal (~90 flops). */
static const MachWork smp_work[] = {
    {"draw_vertex", {[MACH_W_INSTR] = 20, [MACH_W_MEMBYTE] = 32}},
    {"triangle", {[MACH_W_VERTEX] = 1, [MACH_W_SETUP] = 1,
                  [MACH_W_PIXEL] = 50}},
    {"pn_vertex", {[MACH_W_FLOP] = 90, [MACH_W_INSTR] = 30}},
    {NULL, {0}}};
static const MachWork pp5_work[] = {
    {"polygon", {[MACH_W_SETUP] = 1, [MACH_W_FLOP] = 40, [MACH_W_INSTR] = 60}},
    {"vertex", {[MACH_W_VERTEX] = 1}},
    {"send_primitive", {[MACH_W_INSTR] = 20, [MACH_W_MEMBYTE] = 200}},
    {"pn_vertex", {[MACH_W_FLOP] = 90, [MACH_W_INSTR] = 30}},
    /* 7 linear expressions and a z compare over a 128 x 128 region */
    {"primitive", {[MACH_W_FLOP] = 7 * 16384.0, [MACH_W_ZCMP] = 16384}},
    {NULL, {0}}};
static const WlNeed smp_needs[] = {{"cpu", smp_ops, smp_work},
                                   {"pipe", pipe_ops, smp_work},
                                   {NULL, NULL, NULL}};
static const WlNeed pp5_needs[] = {{"gp", gp_ops, pp5_work},
                                   {"renderer", rd_ops, pp5_work},
                                   {NULL, NULL, NULL}};
const WlNeedAlt wl_pf_pn_needs[] = {
    {"with pn:, on a cpu + pipe machine", smp_needs},
    {"with pn:, on Pixel-Planes 5 (host + gp + renderer)", pp5_needs},
    {NULL, NULL}};

static gboolean pick_machine(PnRun *r, GError **err)
{
    MachMachine *m = r->m;
    if (mach_kind(m, "cpu") && mach_kind(m, "pipe")) {
        r->start = smp_frame;
        return mach_shmem_init(&r->bus_mem, m, err) &&
               mach_costs_check(m, smp_needs, err);
    }
    if (mach_kind(m, "host") && mach_kind(m, "gp") &&
        mach_kind(m, "renderer")) {
        r->start = pp5_frame;
        return mach_require_net(m, err) && mach_costs_check(m, pp5_needs, err);
    }
    /* located at the config's machine section (the runner built it) */
    const CfgNode *at = cfg_get(r->ctx->root, "machine");
    char *found = g_strdup_printf("machine '%s' with no node kinds cpu + "
                                  "pipe or host + gp + renderer",
                                  mach_name(m));
    const char *exp = "a shared-memory machine with a pipe "
                      "(models/sgi-onyx.yaml) or Pixel-Planes 5";
    if (at)
        cfg_error(err, at, found, exp);
    else
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "performer: found %s, expected %s", found, exp);
    g_free(found);
    return FALSE;
}

static void set_metrics(PnRun *r, SimResult *out)
{
    double frames = out->frame_times->len;
    sim_result_set_metric(out, "level", r->p->pn.level, "");
    sim_result_set_metric(out, "coarse_tris", r->mesh.coarse_tris, "");
    sim_result_set_metric(out, "fine_tris", r->mesh.fine_tris, "");
    sim_result_set_metric(out, "link_bytes_per_frame",
                          frames ? r->link_bytes / frames : 0, "B");
    sim_result_set_metric(out, "command_bytes_per_frame",
                          frames ? r->cmd_bytes / frames : 0, "B");
    const char *names[] = {"cpu_ms", "bus_ms", "pipe_ms", "gp_ms"};
    SimTime v[] = {r->cpu, r->bus, r->pipe, r->gp};
    for (guint i = 0; i < 4; i++)
        if (v[i])
            sim_result_set_metric(out, names[i], sim_time_to_s(v[i]) * 1e3,
                                  "ms");
    if (r->p->memory) {
        const PnMesh *pm = &r->mesh;
        sim_result_set_metric(out, "lod_memory_bytes", pm->lod_bytes, "B");
        sim_result_set_metric(out, "pn_memory_bytes", pm->base_bytes, "B");
        sim_result_set_metric(out, "lod_memory_ratio",
                              pm->base_bytes ? (double)pm->lod_bytes /
                                                   pm->base_bytes
                                             : 0,
                              "");
    }
    sim_result_set_metric(out, "frame_ms", sim_result_mean_frame_s(out) * 1e3,
                          "ms");
    sim_result_set_metric(out, "fine_tris_per_s",
                          sim_result_mean_frame_s(out) > 0
                              ? r->mesh.fine_tris / sim_result_mean_frame_s(out)
                              : 0,
                          "1/s");
}

gboolean wl_pf_pn_run(const WlContext *ctx, MachMachine *m,
                      const WlPfPnParams *p, SimResult *out, GError **err)
{
    if (p->lod)
        return wl_pf_pnlod_run(ctx, m, p, out, err);
    PnRun r = {.ctx = ctx, .m = m, .p = p, .out = out};
    if (!pick_machine(&r, err) || !pn_mesh(ctx, p, &r.mesh, err))
        return FALSE;
    r.frames_left = (guint)ctx->frames;
    sim_schedule_at(ctx->eng, 0, frame_start, &r, NULL);
    gboolean ok = sim_engine_run(ctx->eng, ctx->until, err);
    wl_pf_gpipe_free(r.gpipe);
    if (!ok)
        return FALSE;
    mach_fill_result(m, out);
    if (r.start == smp_frame) {
        out->comm_bytes = r.bus_mem.bytes;
        out->comm_messages = r.bus_mem.transfers;
    }
    out->elapsed = sim_now(ctx->eng);
    set_metrics(&r, out); /* over the frames run.until left whole */
    return TRUE;
}
