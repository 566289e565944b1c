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
/* Each op's portable work (sim/machine/work.h; the instruction counts
 * of models/sgi-onyx.yaml): a cost the model lacks is derived from it on
 * the kind's processor description. */
static const MachWork cpu_work[] = {
    /* the application's own work: ~2 ms of a 150 MHz R4400 */
    {"app_frame", {[MACH_W_INSTR] = 230000}},
    {"app_dcs", {[MACH_W_INSTR] = 400}},
    {"cull_node", {[MACH_W_FLOP] = 60, [MACH_W_INSTR] = 90}},
    {"cull_lod", {[MACH_W_FLOP] = 10, [MACH_W_INSTR] = 40}},
    {"cull_billboard", {[MACH_W_FLOP] = 60, [MACH_W_INSTR] = 150}},
    {"cull_item", {[MACH_W_INSTR] = 30}},
    {"draw_geoset", {[MACH_W_INSTR] = 600}},
    {"draw_state", {[MACH_W_INSTR] = 400}},
    {"draw_matrix", {[MACH_W_FLOP] = 64, [MACH_W_INSTR] = 100}},
    {"draw_vertex", {[MACH_W_INSTR] = 20, [MACH_W_MEMBYTE] = 32}},
    {"isect_node", {[MACH_W_FLOP] = 30, [MACH_W_INSTR] = 60}},
    {"isect_triangle", {[MACH_W_FLOP] = 50, [MACH_W_INSTR] = 40}},
    {NULL, {0}}};
/* a strip triangle: one new vertex, a set-up and ~50 pixels */
static const MachWork pipe_work[] = {
    {"triangle", {[MACH_W_VERTEX] = 1, [MACH_W_SETUP] = 1,
                  [MACH_W_PIXEL] = 50}},
    {"state", {[MACH_W_INSTR] = 300}},
    {NULL, {0}}};
const WlNeed wl_pf_town_needs[] = {{"cpu", cpu_ops, cpu_work},
                                   {"pipe", pipe_ops, pipe_work},
                                   {NULL, NULL, NULL}};

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
    for (int i = 0; i < WL_PF_MAX_PIPES * WL_PF_NBUF; i++)
        s->dl[i] = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    s->pipes = 1;
    s->frames = g_array_new(FALSE, TRUE, sizeof(WlPfFrameStats));
    g_array_set_size(s->frames, frames);
    s->ground = wl_pf_town_height(0, 0);
    return s;
}

void wl_pf_stages_free(WlPfStages *s)
{
    if (!s)
        return;
    for (int i = 0; i < WL_PF_MAX_PIPES * WL_PF_NBUF; i++)
        g_array_free(s->dl[i], TRUE);
    g_array_free(s->frames, TRUE);
    g_free(s);
}

void wl_pf_stages_set_pipes(WlPfStages *s, guint pipes)
{
    g_assert(pipes >= 1 && pipes <= WL_PF_MAX_PIPES);
    s->pipes = pipes;
}

static SimTime sum(SimTime a, SimTime b)
{
    return sim_time_add_sat(a, b);
}

/* Callbacks cost a time: CULL's and DRAW's work is then a time. */
static gboolean timed(const WlPfCosts *c)
{
    return c->cull_callback > 0 || c->draw_callback > 0;
}

/* Pipe i's display list for frame n. */
static GArray *dlist(WlPfStages *s, guint i, guint n)
{
    return s->dl[i * WL_PF_NBUF + n % WL_PF_NBUF];
}

/* Channel i of s->pipes: a 1/N slice of c's horizontal field of view,
 * turned about the vertical by its heading offset (one pipe: c). */
static SceneCamera channel_camera(const WlPfStages *s, SceneCamera c, guint i)
{
    if (s->pipes <= 1)
        return c;
    double tv = tan(c.fov_deg * G_PI / 360.0), h = atan(c.aspect * tv);
    double hi = h / s->pipes, yaw = -h + (2.0 * i + 1.0) * hi;
    Vec3 d = vec3_sub(c.target, c.eye);
    Vec3 r = vec3(d.x * cos(yaw) + d.z * sin(yaw), d.y,
                  -d.x * sin(yaw) + d.z * cos(yaw));
    c.target = vec3_add(c.eye, r);
    c.aspect = tan(hi) / tv;
    return c;
}

static void add_cull(WlPfCullStats *a, const WlPfCullStats *b)
{
    a->nodes_visited += b->nodes_visited, a->sphere_tests += b->sphere_tests;
    a->nodes_culled += b->nodes_culled, a->lods += b->lods;
    a->billboards += b->billboards, a->tris_culled += b->tris_culled;
    a->lod_sum += b->lod_sum, a->matrix_saved += b->matrix_saved;
    a->callbacks += b->callbacks;
}

static void add_draw(WlPfDrawStats *a, const WlPfDrawStats *b)
{
    a->geosets += b->geosets, a->tris += b->tris;
    a->matrix_ops += b->matrix_ops, a->state_changes += b->state_changes;
    a->state_naive += b->state_naive, a->vertices += b->vertices;
    a->callbacks += b->callbacks;
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
    wl_pf_frame_stats(s, n)->updates = moved + 1; /* the cars, the eye */
    MachOps *o = ops_reset(s);
    s->last_bytes = s->arena.entry * (moved + 1); /* the update list */
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
    SceneCamera cam = channel_camera(
        s, wl_pf_town_camera(s->town, n, f->ground), s->chan);
    WlPfView v = wl_pf_view(&cam, stress, s->cull);
    v.frame = n;
    GArray *dl = dlist(s, s->chan, n);
    g_array_set_size(dl, 0);
    WlPfCullStats cs = {0};
    wl_pf_cull(s->town->g, &v, dl, &cs);
    add_cull(&f->cull, &cs);
    f->dl_items += dl->len;
    const WlPfCosts *c = &s->c;
    MachOps *o = ops_reset(s);
    mach_ops_add(o, "cull_node", cs.nodes_visited);
    mach_ops_add(o, "cull_lod", cs.lods);
    mach_ops_add(o, "cull_billboard", cs.billboards);
    mach_ops_add(o, "cull_item", dl->len);
    s->last_bytes = s->arena.node * cs.nodes_visited + s->arena.item * dl->len;
    SimTime t = sim_time_mul_sat(c->cull_node, cs.nodes_visited);
    t = sum(t, sim_time_mul_sat(c->cull_lod, cs.lods));
    t = sum(t, sim_time_mul_sat(c->cull_billboard, cs.billboards));
    t = sum(t, sim_time_mul_sat(c->cull_callback, cs.callbacks));
    if (timed(c))
        o->n = 0;
    return sum(t, sim_time_mul_sat(c->cull_item, dl->len));
}

SimTime wl_pf_draw_cpu(const WlPfCosts *c, const WlPfDrawStats *st,
                       gboolean lazy)
{
    uint64_t states = lazy ? st->state_changes : st->state_naive;
    uint64_t v = st->vertices ? st->vertices : 3 * st->tris;
    SimTime t = sim_time_mul_sat(c->draw_geoset, st->geosets);
    t = sum(t, sim_time_mul_sat(c->draw_state, states));
    t = sum(t, sim_time_mul_sat(c->draw_matrix, st->matrix_ops));
    t = sum(t, sim_time_mul_sat(c->draw_callback, st->callbacks));
    return sum(t, sim_time_mul_sat(c->draw_vertex, v));
}


/* The vertices DRAW sends for the geosets of dl in strips of `strip`
 * triangles: T + 2 ceil(T / L) a geoset (3 T when L <= 1). */
static uint64_t strip_vertices(const WlPfGraph *g, const GArray *dl,
                               guint strip)
{
    uint64_t v = 0, L = MAX(strip, 1);
    for (guint i = 0; i < dl->len; i++) {
        const WlPfDlItem *it = &g_array_index(dl, WlPfDlItem, i);
        if (it->op != WL_PF_DL_GEOSET)
            continue;
        uint64_t t = wl_pf_geoset_tris(wl_pf_geoset(g, it->geoset));
        v += L == 1 ? 3 * t : t + 2 * ((t + L - 1) / L);
    }
    return v;
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
    mach_ops_add(o, "draw_vertex", st->vertices ? st->vertices : 3 * st->tris);
}

/* DRAW waits for the slowest of CPU, bus and pipe: the CPU's counts with
 * the pipe's and the stream as overlapping terms. */
static SimTime draw(void *ctx, guint n)
{
    WlPfStages *s = ctx;
    WlPfFrameStats *f = wl_pf_frame_stats(s, n);
    const WlPfCosts *c = &s->c;
    guint i = s->chan;
    WlPfDrawStats *d = &s->pdraw[i];
    *d = (WlPfDrawStats){0};
    wl_pf_draw(s->town->g, dlist(s, i, n), d);
    d->vertices = strip_vertices(s->town->g, dlist(s, i, n), c->strip);
    add_draw(&f->draw, d);
    uint64_t states = s->lazy ? d->state_changes : d->state_naive;
    SimTime cpu = wl_pf_draw_cpu(c, d, s->lazy);
    MachOps *o = ops_reset(s);
    if (!timed(c))
        draw_ops(o, d, states);
    double bytes = (double)d->vertices * (double)c->vertex_bytes;
    s->pcpu[i] = cpu, s->pbytes[i] = (uint64_t)bytes;
    s->ppipe[i] = sum(sim_time_mul_sat(c->pipe_triangle, d->tris),
                      sim_time_mul_sat(c->pipe_state, states));
    f->cpu = MAX(f->cpu, cpu), f->bytes += s->pbytes[i];
    f->pipe = MAX(f->pipe, s->ppipe[i]);
    if (s->piped) { /* the pipe runs it (draw_work); an idle bus's time */
        f->bus = MAX(f->bus, mach_shmem_time(&s->bus, s->pbytes[i]));
        return cpu;
    }
    f->bus = feed_pipe(s, &s->over, f->bytes, f->draw.tris, states);
    return MAX(f->cpu, MAX(f->bus, f->pipe));
}

/* The last DRAW's work for the graphics pipe (pf_gpipe.h). */
static void draw_work(void *ctx, guint n, WlPfDrawWork *w)
{
    WlPfStages *s = ctx;
    guint i = s->chan;
    const WlPfDrawStats *d = &s->pdraw[i];
    uint64_t states = s->lazy ? d->state_changes : d->state_naive;
    *w = (WlPfDrawWork){
        .cpu = s->pcpu[i], .bytes = s->pbytes[i], .pipe = s->ppipe[i]};
    if (!timed(&s->c))
        draw_ops(&w->cpu_ops, d, states);
    mach_ops_add(&w->pipe_ops, "triangle", d->tris);
    /* the display list and the geosets' vertices */
    w->arena_bytes = s->arena.item * dlist(s, i, n)->len +
                     d->vertices * s->c.vertex_bytes;
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
    /* nodes, and a triangle's three positions (36 B) */
    s->last_bytes =
        s->arena.node * f->isect.nodes_tested + 36 * f->isect.tris_tested;
    return sum(sim_time_mul_sat(s->c.isect_node, f->isect.nodes_tested),
               sim_time_mul_sat(s->c.isect_triangle, f->isect.tris_tested));
}

static void channel(void *ctx, guint pipe)
{
    ((WlPfStages *)ctx)->chan = pipe;
}

/* A CULL process applies APP's update list of frame n (pfBuffer). */
static SimTime update(void *ctx, guint n)
{
    WlPfStages *s = ctx;
    guint u = wl_pf_frame_stats(s, n)->updates;
    s->last_bytes = 2 * s->arena.entry * u; /* read it, write the copy */
    return sim_time_mul_sat(s->c.update, u);
}

static uint64_t arena_bytes(void *ctx)
{
    return ((WlPfStages *)ctx)->last_bytes;
}

WlPfStageFns wl_pf_stage_fns(gboolean with_isect)
{
    return (WlPfStageFns){app,       cull,    draw,   with_isect ? isect : NULL,
                          ops,       draw_work, channel, update, arena_bytes};
}
