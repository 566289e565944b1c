/* pf_stages.c — the Performer stages on the town and their costs (see
 * pf_stages.h).  Every cost is a count times a model cost; no timing is
 * invented here.  O(traversal) per stage call.
 */
#include "sim/workload/performer/pf_stages.h"

#include "sim/core/trace.h"

static const char *const cpu_ops[] = {
    "app_frame",   "app_dcs",        "cull_node",
    "cull_lod",    "cull_billboard", "cull_item",
    "draw_geoset", "draw_state",     "draw_matrix",
    "draw_vertex", "isect_node",     "isect_triangle",
    NULL};
static const char *const pipe_ops[] = {"triangle", "state", NULL};
const WlNeed wl_pf_town_needs[] = {
    {"cpu", cpu_ops}, {"pipe", pipe_ops}, {NULL, NULL}};

gboolean wl_pf_costs_read(MachMachine *m, uint64_t vertex_bytes, WlPfCosts *c,
                          GError **err)
{
    *c = (WlPfCosts){.vertex_bytes = vertex_bytes};
    SimTime *const cpu[] = {
        &c->app_frame,   &c->app_dcs,        &c->cull_node,
        &c->cull_lod,    &c->cull_billboard, &c->cull_item,
        &c->draw_geoset, &c->draw_state,     &c->draw_matrix,
        &c->draw_vertex, &c->isect_node,     &c->isect_triangle};
    SimTime *const pipe[] = {&c->pipe_triangle, &c->pipe_state};
    G_STATIC_ASSERT(G_N_ELEMENTS(cpu) == G_N_ELEMENTS(cpu_ops) - 1);
    G_STATIC_ASSERT(G_N_ELEMENTS(pipe) == G_N_ELEMENTS(pipe_ops) - 1);
    MachCosts *set = mach_costs_new(m, wl_pf_town_needs, err);
    if (!set)
        return FALSE;
    mach_costs_fill(set, "cpu", cpu_ops, cpu);
    mach_costs_fill(set, "pipe", pipe_ops, pipe);
    mach_costs_free(set);
    return TRUE;
}

WlPfStages *wl_pf_stages_new(MachMachine *m, WlPfTown *town, const WlPfCosts *c,
                             gboolean cull, gboolean lazy, gboolean isect,
                             guint frames, GError **err)
{
    WlPfStages *s = g_new0(WlPfStages, 1);
    if (!mach_shmem_init(&s->bus, m, err)) {
        g_free(s);
        return NULL;
    }
    s->eng = mach_engine(m);
    s->town = town;
    s->c = *c;
    s->cull = cull;
    s->lazy = lazy;
    s->isect = isect;
    for (int i = 0; i < WL_PF_NBUF; i++)
        s->dl[i] = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    s->frames = g_array_new(FALSE, TRUE, sizeof(WlPfFrameStats));
    g_array_set_size(s->frames, frames);
    s->ground = wl_pf_town_height(0, 0);
    return s;
}

void wl_pf_stages_free(WlPfStages *s)
{
    if (!s)
        return;
    for (int i = 0; i < WL_PF_NBUF; i++)
        g_array_free(s->dl[i], TRUE);
    g_array_free(s->frames, TRUE);
    g_free(s);
}

static SimTime sum(SimTime a, SimTime b)
{
    return sim_time_add_sat(a, b);
}

/* ---- the stages -------------------------------------------------------- */

/* The stage's counts start afresh (the `ops` hook reads them). */
static MachOps *ops_reset(WlPfStages *s)
{
    s->last.n = 0;
    mach_overlap_reset(&s->over);
    return &s->last;
}

/* The last stage's counts with its terms (none but for DRAW). */
static const MachOverlap *ops(void *ctx)
{
    WlPfStages *s = ctx;
    s->over.own = s->last;
    return &s->over;
}

static SimTime app(void *ctx, guint n)
{
    WlPfStages *s = ctx;
    guint moved = wl_pf_town_update(s->town, n);
    wl_pf_frame_stats(s, n)->ground = s->ground;
    MachOps *o = ops_reset(s);
    if (!s->app_timed) {
        mach_ops_add(o, "app_frame", 1);
        mach_ops_add(o, "app_dcs", moved);
    }
    return sum(s->c.app_frame, sim_time_mul_sat(s->c.app_dcs, moved));
}

static SimTime cull(void *ctx, guint n, double stress)
{
    WlPfStages *s = ctx;
    WlPfFrameStats *f = wl_pf_frame_stats(s, n);
    SceneCamera cam = wl_pf_town_camera(s->town, n, f->ground);
    WlPfView v = wl_pf_view(&cam, stress, s->cull);
    GArray *dl = s->dl[n % WL_PF_NBUF];
    g_array_set_size(dl, 0);
    wl_pf_cull(s->town->g, &v, dl, &f->cull);
    f->dl_items = dl->len;
    const WlPfCosts *c = &s->c;
    MachOps *o = ops_reset(s);
    mach_ops_add(o, "cull_node", f->cull.nodes_visited);
    mach_ops_add(o, "cull_lod", f->cull.lods);
    mach_ops_add(o, "cull_billboard", f->cull.billboards);
    mach_ops_add(o, "cull_item", dl->len);
    SimTime t = sim_time_mul_sat(c->cull_node, f->cull.nodes_visited);
    t = sum(t, sim_time_mul_sat(c->cull_lod, f->cull.lods));
    t = sum(t, sim_time_mul_sat(c->cull_billboard, f->cull.billboards));
    return sum(t, sim_time_mul_sat(c->cull_item, dl->len));
}

SimTime wl_pf_draw_cpu(const WlPfCosts *c, const WlPfDrawStats *st,
                       gboolean lazy)
{
    uint64_t states = lazy ? st->state_changes : st->state_naive;
    SimTime t = sim_time_mul_sat(c->draw_geoset, st->geosets);
    t = sum(t, sim_time_mul_sat(c->draw_state, states));
    t = sum(t, sim_time_mul_sat(c->draw_matrix, st->matrix_ops));
    return sum(t, sim_time_mul_sat(c->draw_vertex, 3 * st->tris));
}

/* The DRAW CPU's stream to the pipe as one traced message per frame. */
static void trace_bus(WlPfStages *s, uint64_t bytes, SimTime from, SimTime to)
{
    MachMachine *m = mach_proc_machine(s->draw_cpu);
    MachProc *pipe = mach_proc(m, "pipe", 0);
    sim_trace_flow(sim_engine_trace(s->eng), mach_proc_id(s->draw_cpu),
                   mach_proc_name(s->draw_cpu), mach_proc_id(pipe),
                   mach_proc_name(pipe), bytes, from, to);
}

/* The pipe's share of DRAW, as counts on the pipe (phase "pipe"), and
 * the stream that feeds it, as a shared-memory transfer; both are also
 * the terms DRAW's CPU overlaps with (o).  Returns the stream's time. */
static SimTime feed_pipe(WlPfStages *s, MachOverlap *o, uint64_t bytes,
                         uint64_t tris, uint64_t states)
{
    MachProc *pipe = mach_proc(mach_proc_machine(s->draw_cpu), "pipe", 0);
    MachOps po = {0};
    mach_ops_add(&po, "triangle", tris);
    mach_ops_add(&po, "state", states);
    mach_proc_compute_list(pipe, &po, sim_engine_phase(s->eng, "pipe"), NULL,
                           NULL, NULL);
    mach_overlap_ops(o, pipe, &po);
    SimTime now = sim_now(s->eng);
    mach_shmem_send(&s->bus, s->eng, mach_proc_id(s->draw_cpu),
                    mach_proc_id(pipe), bytes, NULL, NULL, NULL);
    SimTime end = s->bus.last_end;
    mach_overlap_bus(o, &s->bus, pipe, bytes);
    trace_bus(s, bytes, now, end);
    return end - now;
}

/* DRAW's own counts on the CPU (what wl_pf_draw_cpu() prices). */
static void draw_ops(MachOps *o, const WlPfDrawStats *st, uint64_t states)
{
    mach_ops_add(o, "draw_geoset", st->geosets);
    mach_ops_add(o, "draw_state", states);
    mach_ops_add(o, "draw_matrix", st->matrix_ops);
    mach_ops_add(o, "draw_vertex", 3 * st->tris);
}

/* DRAW waits for the slowest of CPU, bus and pipe: the CPU's counts with
 * the pipe's and the stream as overlapping terms. */
static SimTime draw(void *ctx, guint n)
{
    WlPfStages *s = ctx;
    WlPfFrameStats *f = wl_pf_frame_stats(s, n);
    const WlPfCosts *c = &s->c;
    wl_pf_draw(s->town->g, s->dl[n % WL_PF_NBUF], &f->draw);
    uint64_t states = s->lazy ? f->draw.state_changes : f->draw.state_naive;
    f->cpu = wl_pf_draw_cpu(c, &f->draw, s->lazy);
    draw_ops(ops_reset(s), &f->draw, states);
    double bytes = 3.0 * (double)f->draw.tris * (double)c->vertex_bytes;
    f->bytes = (uint64_t)bytes;
    f->pipe = sum(sim_time_mul_sat(c->pipe_triangle, f->draw.tris),
                  sim_time_mul_sat(c->pipe_state, states));
    if (s->piped) { /* the pipe runs it (draw_work); an idle bus's time */
        f->bus = mach_shmem_time(&s->bus, f->bytes);
        return f->cpu;
    }
    f->bus = feed_pipe(s, &s->over, f->bytes, f->draw.tris, states);
    return MAX(f->cpu, MAX(f->bus, f->pipe));
}

/* The last DRAW's work for the graphics pipe (pf_gpipe.h). */
static void draw_work(void *ctx, guint n, WlPfDrawWork *w)
{
    WlPfStages *s = ctx;
    const WlPfFrameStats *f = wl_pf_frame_stats(s, n);
    uint64_t states = s->lazy ? f->draw.state_changes : f->draw.state_naive;
    *w = (WlPfDrawWork){.cpu = f->cpu, .bytes = f->bytes, .pipe = f->pipe};
    draw_ops(&w->cpu_ops, &f->draw, states);
    mach_ops_add(&w->pipe_ops, "triangle", f->draw.tris);
    mach_ops_add(&w->pipe_ops, "state", states);
}

static SimTime isect(void *ctx, guint n)
{
    WlPfStages *s = ctx;
    WlPfFrameStats *f = wl_pf_frame_stats(s, n);
    SceneCamera cam = wl_pf_town_camera(s->town, n, 0);
    wl_pf_isect(s->town->g, cam.eye.x, cam.eye.z, -100, 100, &f->isect);
    if (f->isect.hit)
        s->ground = f->isect.height; /* APP of a later frame reads it */
    MachOps *o = ops_reset(s);
    mach_ops_add(o, "isect_node", f->isect.nodes_tested);
    mach_ops_add(o, "isect_triangle", f->isect.tris_tested);
    return sum(sim_time_mul_sat(s->c.isect_node, f->isect.nodes_tested),
               sim_time_mul_sat(s->c.isect_triangle, f->isect.tris_tested));
}

WlPfStageFns wl_pf_stage_fns(gboolean with_isect)
{
    return (WlPfStageFns){app, cull, draw, with_isect ? isect : NULL, ops,
                          draw_work};
}
