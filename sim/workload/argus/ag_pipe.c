/* ag_pipe.c — the Argus pipeline as per-thread state machines on a
 * simulated shared-memory machine (ag_pipe.h).
 *
 * Invariants: a tile passes each context's blocks in sequence; a block is
 * drawn at a tile only after its geometry is done and, at that tile,
 * every P it carries has a matching V; a rasteriser draws one (tile,
 * block) at a time.  The frame ends when every tile has passed every
 * block.  O(blocks x tiles) bookkeeping per frame (empty blocks are
 * skipped in bulk), O(triangles + pixels) real work.
 */
#include "sim/workload/argus/ag_pipe_int.h"
#include <string.h>

const char *const wl_ag_app_names[] = {"none", "nurbs", "march", NULL};
const char *const wl_ag_cost_ops[] = {"nurbs_vertex",
                                      "march_voxel",
                                      "march_triangle",
                                      "issue_vertex",
                                      "issue_batch",
                                      "geom_vertex",
                                      "geom_triangle",
                                      "geom_tile",
                                      "rast_triangle",
                                      "rast_pixel",
                                      "rast_blend",
                                      "rast_clear",
                                      "lock",
                                      "sema",
                                      "issue_state",
                                      "geom_state",
                                      NULL};
const char *const wl_ag_scheme_names[] = {"pixel", "geometry", NULL};
const char *const wl_ag_sync_names[] = {"glp", "finish", NULL};

/* Each op's portable work (sim/machine/work.h; the instruction counts
 * of models/origin2000.yaml's notes): a cost the model lacks is derived
 * from it on the cpu's processor description. */
static const MachWork ag_work[] = {
    /* a bicubic point and normal: 16 control points x 3 coordinates,
     * two tangents */
    {"nurbs_vertex", {[MACH_W_FLOP] = 300, [MACH_W_INSTR] = 50}},
    {"march_voxel", {[MACH_W_INSTR] = 8}},
    {"march_triangle", {[MACH_W_FLOP] = 60, [MACH_W_INSTR] = 40}},
    {"issue_vertex", {[MACH_W_INSTR] = 20, [MACH_W_MEMBYTE] = 32}},
    {"issue_batch", {[MACH_W_INSTR] = 200}},
    {"geom_vertex", {[MACH_W_VERTEX] = 1}},
    {"geom_triangle", {[MACH_W_INSTR] = 60}},
    {"geom_tile", {[MACH_W_INSTR] = 30}},
    {"rast_triangle", {[MACH_W_SETUP] = 1}},
    {"rast_pixel", {[MACH_W_PIXEL] = 1}},
    {"rast_blend", {[MACH_W_PIXEL] = 1, [MACH_W_FLOP] = 6}},
    {"rast_clear", {[MACH_W_MEMBYTE] = 8}},
    {"lock", {[MACH_W_MISS] = 3}},
    {"sema", {[MACH_W_MISS] = 2}},
    /* one state command (4 to 16 floats) copied into the buffer */
    {"issue_state", {[MACH_W_INSTR] = 30, [MACH_W_MEMBYTE] = 64}},
    {"geom_state", {[MACH_W_INSTR] = 45, [MACH_W_MEMBYTE] = 64}},
    {NULL, {0}}};
const MachNeed wl_ag_needs[] = {{"cpu", wl_ag_cost_ops, ag_work},
                                {NULL, NULL, NULL}};

gboolean wl_ag_costs_from_machine(const MachMachine *m, AgCosts *c,
                                  GError **err)
{
    MachCosts *set = mach_costs_new(m, wl_ag_needs, err);
    if (!set)
        return FALSE;
    SimTime *const dst[] = {
        &c->nurbs_vertex,  &c->march_voxel, &c->march_triangle,
        &c->issue_vertex,  &c->issue_batch, &c->geom_vertex,
        &c->geom_triangle, &c->geom_tile,   &c->rast_triangle,
        &c->rast_pixel,    &c->rast_blend,  &c->rast_clear,
        &c->lock,          &c->sema,        &c->issue_state,
        &c->geom_state};
    G_STATIC_ASSERT(G_N_ELEMENTS(dst) == G_N_ELEMENTS(wl_ag_cost_ops) - 1);
    mach_costs_fill(set, "cpu", wl_ag_cost_ops, dst);
    mach_costs_free(set);
    return TRUE;
}

MachProc *wl_ag_thread_proc(AgPipe *p, guint thread)
{
    return mach_proc(p->m, "cpu", thread % p->s.procs);
}

const AgBlock *wl_ag_block_at(const AgPipe *p, guint b, guint *ctx)
{
    g_assert(b < p->nblocks);
    guint c = 0;
    while (c + 1 < p->C && p->ctx_off[c + 1] <= b)
        c++;
    if (ctx)
        *ctx = c;
    return &g_array_index(wl_ag_ctx_blocks(p->st, c), AgBlock,
                          b - p->ctx_off[c]);
}

/* Work given as named counts of the cpu's costs (wl_ag_cost_ops):
 * priced by the machine, written as such by a recording; *busy gets its
 * time. */
/* A lock or semaphore operation: none on a uniprocessor, where nothing
 * is shared between threads (the costs the machine gives are for the
 * multiprocessor's synchronisation). */
void wl_ag_sync_ops(const AgPipe *p, MachOps *o, const char *op, uint64_t n)
{
    mach_ops_add(o, op, p->s.uniprocessor ? 0 : n);
}

void wl_ag_compute(MachProc *proc, const MachOps *o, unsigned phase,
                    SimHandler done, AgPipe *p, guint arg, SimTime *busy)
{
    *busy += mach_proc_ops_cost(proc, o);
    mach_proc_compute_list(proc, o, phase, done, p, GUINT_TO_POINTER(arg));
}

/* ---- geometry threads --------------------------------------------------- */

typedef struct {
    GArray *pairs; /* (tile, tri) as two guint */
    guint tri;
} Bucket;

static void add_pair(guint tile, void *ctx)
{
    Bucket *k = ctx;
    guint pr[2] = {tile, k->tri};
    g_array_append_vals(k->pairs, pr, 2);
}

/* (tile, triangle) pairs by tile, then triangle (the tie-break is for
 * clarity: the pairs of a tile arrive in triangle order and the sort is
 * stable). */
static gint cmp_pair(gconstpointer a, gconstpointer b, gpointer unused)
{
    (void)unused;
    const guint *x = a, *y = b;
    if (x[0] != y[0])
        return x[0] < y[0] ? -1 : 1;
    return x[1] < y[1] ? -1 : (x[1] > y[1]);
}

/* Sorts the block's triangles into per-tile lists; returns the pairs. */
static guint bucket_block(AgPipe *p, const AgBlock *k, BlockState *s)
{
    Bucket bk = {g_array_new(FALSE, FALSE, sizeof(guint)), 0};
    for (guint i = k->first; i < k->first + k->n; i++) {
        bk.tri = i;
        wl_ag_bucket(p->f, &p->view->view_proj, p->mesh, i, add_pair, &bk);
    }
    guint np = bk.pairs->len / 2;
    guint *pr = (guint *)bk.pairs->data;
    if (np > 1) /* GLib's sort is documented stable, unlike qsort */
        g_qsort_with_data(pr, (gint)np, 2 * sizeof(guint), cmp_pair, NULL);
    s->tris = g_new(uint32_t, np); /* NULL for no pair: never read */
    s->tile_ids = g_new(guint, np);
    s->tile_start = g_new(guint, np + 1);
    s->n_tiles = 0;
    for (guint i = 0; i < np; i++) {
        if (i == 0 || pr[2 * i] != pr[2 * i - 2]) {
            s->tile_ids[s->n_tiles] = pr[2 * i];
            s->tile_start[s->n_tiles++] = i;
        }
        s->tris[i] = pr[2 * i + 1];
    }
    s->tile_start[s->n_tiles] = np;
    g_array_free(bk.pairs, TRUE);
    return np;
}

static void geom_kick(AgPipe *p);
static void rast_kick(AgPipe *p, guint r);
static void pool_kick(AgPipe *p);

/* The thread of geometry thread or pool worker g (role 0) or of
 * rasteriser or pool worker r (role 1). */
static MachProc *worker_proc(AgPipe *p, int role, guint i)
{
    guint base = p->C + (role == 1 && !p->nw ? p->s.geometry : 0);
    return wl_ag_thread_proc(p, base + i);
}

static void block_ready(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    AgPipe *p = ctx;
    p->bs[GPOINTER_TO_UINT(arg)].done = TRUE;
    if (p->nw) {
        pool_kick(p);
        wl_ag_finish_poll(p);
        return;
    }
    for (guint r = 0; r < p->s.rasterisers; r++)
        rast_kick(p, r);
    wl_ag_finish_poll(p);
}

static void geom_done(SimEngine *eng, void *ctx, void *arg)
{
    AgPipe *p = ctx;
    guint g = GPOINTER_TO_UINT(arg), b = p->g_block[g];
    BlockState *s = &p->bs[b];
    SimTime t = mach_shmem_transfer(&p->mem, sim_now(eng),
                                    (uint64_t)s->tile_start[s->n_tiles] *
                                        p->s.triangle_bytes);
    sim_schedule_at(eng, t, block_ready, p, GUINT_TO_POINTER(b));
    p->g_busy[g] = FALSE;
    wl_ag_issue_freed(p, b);
    geom_kick(p);
}

static void geom_start(AgPipe *p, guint g, guint b)
{
    const AgBlock *k = wl_ag_block_at(p, b, NULL);
    guint pairs = bucket_block(p, k, &p->bs[b]);
    p->out->bucketed += pairs;
    p->out->triangles += k->n;
    p->out->verts_issued += k->verts;
    MachOps o = {0};
    wl_ag_sync_ops(p, &o, "lock", 1);
    mach_ops_add(&o, "geom_vertex", k->verts);
    mach_ops_add(&o, "geom_triangle", k->n);
    mach_ops_add(&o, "geom_tile", pairs);
    mach_ops_add(&o, "geom_state", k->n_state);
    if (p->s.scheme == WL_AG_SCHEME_GEOMETRY && p->s.sync == WL_AG_SYNC_GLP)
        wl_ag_sync_ops(p, &o, "sema", k->n_pre + k->n_post);
    p->g_busy[g] = TRUE;
    p->g_block[g] = b;
    wl_ag_compute(worker_proc(p, 0, g), &o, p->ph_geom, geom_done, p, g,
            &p->out->geom_busy);
}

void wl_ag_enqueue(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    AgPipe *p = ctx;
    g_queue_push_tail(&p->gq, arg);
    geom_kick(p);
}

static void geom_kick(AgPipe *p)
{
    if (p->nw) {
        pool_kick(p);
        return;
    }
    for (guint g = 0; g < p->s.geometry; g++) {
        if (p->g_busy[g])
            continue;
        guint b = wl_ag_geom_pop(p);
        if (b == G_MAXUINT)
            return;
        geom_start(p, g, b);
    }
}

/* ---- tiles and rasterisation threads ----------------------------------- */

guint *wl_ag_tnext(AgPipe *p, guint t, guint c)
{
    return &p->tnext[(gsize)t * p->C + c];
}

/* The triangles of block state s for tile t (n = 0 when none). */
static const uint32_t *tile_tris(const BlockState *s, guint t, guint *n)
{
    guint lo = 0, hi = s->n_tiles;
    while (lo < hi) {
        guint mid = (lo + hi) / 2;
        if (s->tile_ids[mid] < t)
            lo = mid + 1;
        else
            hi = mid;
    }
    *n = 0;
    if (lo == s->n_tiles || s->tile_ids[lo] != t)
        return NULL;
    *n = s->tile_start[lo + 1] - s->tile_start[lo];
    return s->tris + s->tile_start[lo];
}

/* Whether tile t may pass block gb (k) without drawing it: its geometry
 * is done, it has nothing for t and no clear or swap, and no command
 * the tile must honour. */
static gboolean skippable(AgPipe *p, guint t, guint gb, const AgBlock *k)
{
    const BlockState *s = &p->bs[gb];
    guint n;
    if (!s->done || k->clear || k->swap || tile_tris(s, t, &n))
        return FALSE;
    return !wl_ag_tile_syncs(p) || (!k->n_pre && !k->n_post);
}

gboolean wl_ag_tile_busy(const AgPipe *p, guint t)
{
    if (p->nw)
        return p->t_busy[t];
    guint r = wl_ag_tile_owner(p->f, t, p->s.rasterisers);
    return p->r_busy[r] && p->r_tile[r] == t;
}

/* Skips, per context (GEOMETRY: in the sequence), done blocks with
 * nothing for t; counts t finished when every context is through. */
void wl_ag_tile_advance(AgPipe *p, guint t)
{
    if (*wl_ag_tnext(p, t, 0) == G_MAXUINT)
        return;
    gboolean all = TRUE;
    for (guint b; p->s.scheme == WL_AG_SCHEME_GEOMETRY &&
                  (b = wl_ag_seq_pick(p, t)) != G_MAXUINT;) {
        guint c;
        if (!skippable(p, t, b, wl_ag_block_at(p, b, &c)))
            break;
        wl_ag_tile_pass(p, t, c, b);
    }
    for (guint c = 0; c < p->C; c++) {
        guint *nx = wl_ag_tnext(p, t, c);
        GArray *blocks = wl_ag_ctx_blocks(p->st, c);
        while (p->s.scheme == WL_AG_SCHEME_PIXEL && *nx < blocks->len &&
               skippable(p, t, p->ctx_off[c] + *nx,
                         &g_array_index(blocks, AgBlock, *nx)))
            wl_ag_tile_pass(p, t, c, p->ctx_off[c] + *nx);
        all &= *nx == blocks->len;
    }
    if (all) {
        *wl_ag_tnext(p, t, 0) = G_MAXUINT; /* finished marker */
        if (--p->tiles_left == 0)
            p->out->end = sim_now(p->eng);
    }
}

static int32_t *sem_at(AgPipe *p, guint t, const AgSync *s)
{
    return wl_ag_count_at(&p->sem[(gsize)t * p->nsem], p->st, s);
}

/* Whether block gb (k) may be drawn at tile t now: every glpPSema has a
 * glpVSema there, every party of a glpBarrier has arrived there, and
 * the tile has passed the blocks a glpWaitContext names. */
static gboolean waits_met(AgPipe *p, guint t, guint gb, const AgBlock *k)
{
    if (!wl_ag_tile_syncs(p))
        return TRUE;
    for (guint i = 0; i < k->n_pre; i++) {
        const AgSync *s = &k->pre[i];
        if (s->kind == WL_AG_SYNC_P && *sem_at(p, t, s) <= 0)
            return FALSE;
        if (s->kind == WL_AG_SYNC_BARRIER_WAIT &&
            *sem_at(p, t, s) < (int32_t)p->st->barrier_parties)
            return FALSE;
        if (s->kind == WL_AG_SYNC_WAIT_CONTEXT &&
            *wl_ag_tnext(p, t, s->id) < p->bs[gb].wait_upto)
            return FALSE;
    }
    return TRUE;
}

/* A ready block of tile t (global index), or G_MAXUINT. */
static guint tile_pick(AgPipe *p, guint t)
{
    if (*wl_ag_tnext(p, t, 0) == G_MAXUINT)
        return G_MAXUINT;
    if (p->s.scheme == WL_AG_SCHEME_GEOMETRY)
        return wl_ag_seq_pick(p, t);
    for (guint i = 0; i < p->C; i++) {
        guint c = (p->t_rr[t] + i) % p->C;
        GArray *blocks = wl_ag_ctx_blocks(p->st, c);
        guint nx = *wl_ag_tnext(p, t, c);
        if (nx >= blocks->len || !p->bs[p->ctx_off[c] + nx].done)
            continue;
        if (waits_met(p, t, p->ctx_off[c] + nx,
                      &g_array_index(blocks, AgBlock, nx))) {
            p->t_rr[t] = (c + 1) % p->C;
            return p->ctx_off[c] + nx;
        }
    }
    return G_MAXUINT;
}

/* At tile t: a glpPSema consumes a signal, a glpVSema or a glpBarrier
 * arrival adds one. */
static void sync_apply(AgPipe *p, guint t, const AgSync *s, guint n)
{
    if (!wl_ag_tile_syncs(p))
        return;
    for (guint i = 0; i < n; i++) {
        if (s[i].kind == WL_AG_SYNC_P)
            (*sem_at(p, t, &s[i]))--;
        if (s[i].kind == WL_AG_SYNC_V || s[i].kind == WL_AG_SYNC_BARRIER)
            (*sem_at(p, t, &s[i]))++;
    }
}

static void rast_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    AgPipe *p = ctx;
    guint r = GPOINTER_TO_UINT(arg), t = p->r_tile[r], c;
    const AgBlock *k = wl_ag_block_at(p, p->r_block[r], &c);
    sync_apply(p, t, k->post, k->n_post);
    wl_ag_tile_pass(p, t, c, p->r_block[r]);
    p->r_busy[r] = FALSE;
    if (p->nw)
        p->t_busy[t] = FALSE;
    wl_ag_tile_advance(p, t);
    rast_kick(p, r);
    wl_ag_finish_poll(p);
}

static void rast_start(AgPipe *p, guint r, guint t, guint b)
{
    const AgBlock *k = wl_ag_block_at(p, b, NULL);
    guint n;
    const uint32_t *tris = tile_tris(&p->bs[b], t, &n);
    sync_apply(p, t, k->pre, k->n_pre);
    uint64_t cleared = k->clear ? wl_ag_frame_clear_tile(p->f, t) : 0;
    uint64_t px = wl_ag_draw(p->f, t, p->view, p->mesh, tris, n);
    if (k->swap)
        wl_ag_frame_present_tile(p->f, t);
    p->out->pixels += px;
    guint syncs = wl_ag_tile_syncs(p) ? k->n_pre + k->n_post : 0;
    p->out->syncs += syncs;
    MachOps o = {0};
    mach_ops_add(&o, "rast_triangle", n);
    if (!p->s.fill_infinite) {
        mach_ops_add(&o,
                     p->f->mode == WL_AG_BLEND ? "rast_blend" : "rast_pixel",
                     px);
        mach_ops_add(&o, "rast_clear", cleared);
    }
    wl_ag_sync_ops(p, &o, "sema", syncs);
    p->r_busy[r] = TRUE;
    p->r_tile[r] = t;
    p->r_block[r] = b;
    if (p->nw)
        p->t_busy[t] = TRUE;
    wl_ag_compute(worker_proc(p, 1, r), &o, p->ph_rast, rast_done, p, r,
            &p->out->rast_busy);
}

static void rast_kick(AgPipe *p, guint r)
{
    if (p->nw) {
        pool_kick(p);
        return;
    }
    GArray *own = p->r_tiles[r];
    guint mine = own->len;
    if (p->r_busy[r] || mine == 0)
        return;
    for (guint i = 0; i < mine; i++) {
        guint t = g_array_index(own, guint, (p->r_cursor[r] + i) % mine);
        wl_ag_tile_advance(p, t);
        guint b = tile_pick(p, t);
        if (b != G_MAXUINT) {
            p->r_cursor[r] = (p->r_cursor[r] + i + 1) % mine;
            rast_start(p, r, t, b);
            return;
        }
    }
}

/* ---- the worker pool (workers: pool) ------------------------------------ */

static gboolean worker_idle(const AgPipe *p, guint w)
{
    return !p->g_busy[w] && !p->r_busy[w];
}

/* A tile no worker is drawing with a block ready for it, from the
 * cursor on (round robin). */
static gboolean pool_tile(AgPipe *p, guint *t, guint *b)
{
    for (guint i = 0; i < p->ntiles; i++) {
        guint x = (p->pool_cursor + i) % p->ntiles;
        if (p->t_busy[x])
            continue;
        wl_ag_tile_advance(p, x);
        guint k = tile_pick(p, x);
        if (k != G_MAXUINT) {
            p->pool_cursor = (x + 1) % p->ntiles;
            *t = x;
            *b = k;
            return TRUE;
        }
    }
    return FALSE;
}

/* Gives every idle worker work: a block from the geometry queue first,
 * else a ready (tile, block). */
static void pool_kick(AgPipe *p)
{
    for (guint w = 0; w < p->nw; w++) {
        if (!worker_idle(p, w))
            continue;
        guint t, b = wl_ag_geom_pop(p);
        if (b != G_MAXUINT)
            geom_start(p, w, b);
        else if (pool_tile(p, &t, &b))
            rast_start(p, w, t, b);
        else
            return;
    }
}

/* ---- lifetime and frames ------------------------------------------------ */

AgPipe *wl_ag_pipe_new(MachMachine *m, const AgSetup *s, const AgStreams *st,
                       AgFrame *f, const SceneMesh *mesh, const RastView *view)
{
    AgPipe *p = g_new0(AgPipe, 1);
    p->m = m;
    p->eng = mach_engine(m);
    p->s = *s;
    p->st = st;
    p->f = f;
    p->mesh = mesh;
    p->view = view;
    p->C = st->contexts;
    mach_shmem_init_with(&p->mem, s->mem_bandwidth, s->mem_latency);
    p->ph_app = sim_engine_phase(p->eng, "application");
    p->ph_geom = sim_engine_phase(p->eng, "geometry");
    p->ph_rast = sim_engine_phase(p->eng, "rasterisation");
    p->ctx_off = g_new0(guint, p->C + 1);
    for (guint k = 0; k < p->C; k++)
        p->ctx_off[k + 1] = p->ctx_off[k] + wl_ag_ctx_blocks(st, k)->len;
    p->nblocks = p->ctx_off[p->C];
    /* streams have glpBarrier 0 (ag_stream.c); bs is NULL for no block
     * and then never indexed */
    g_assert(st->barriers >= 1);
    p->bs = g_new0(BlockState, p->nblocks);
    p->app_next = g_new0(guint, p->C);
    p->app_bar = g_new0(guint, st->barriers);
    p->app_arrived = g_new0(gboolean, p->C);
    p->app_parked = g_new0(gboolean, p->C);
    g_queue_init(&p->gq);
    p->nw = s->pool ? s->geometry + s->rasterisers : 0;
    guint ng = MAX(s->geometry, p->nw), nr = MAX(s->rasterisers, p->nw);
    p->g_busy = g_new0(gboolean, ng);
    p->g_block = g_new0(guint, ng);
    p->ntiles = wl_ag_n_tiles(f);
    p->tnext = g_new0(guint, (gsize)p->ntiles * p->C);
    p->nsem = st->sems + st->barriers;
    p->sem = g_new0(int32_t, (gsize)p->ntiles * p->nsem);
    p->t_rr = g_new0(guint, p->ntiles);
    p->r_busy = g_new0(gboolean, nr);
    p->r_cursor = g_new0(guint, nr);
    p->r_tile = g_new0(guint, nr);
    p->r_block = g_new0(guint, nr);
    p->t_busy = g_new0(gboolean, p->ntiles);
    p->r_tiles = g_new0(GArray *, s->rasterisers);
    for (guint r = 0; r < s->rasterisers; r++)
        p->r_tiles[r] = g_array_new(FALSE, FALSE, sizeof(guint));
    for (guint t = 0; t < p->ntiles; t++) {
        guint r = wl_ag_tile_owner(f, t, s->rasterisers);
        g_array_append_val(p->r_tiles[r], t);
    }
    wl_ag_issue_alloc(p);
    wl_ag_order_alloc(p);
    return p;
}

static void clear_blocks(AgPipe *p)
{
    for (guint b = 0; b < p->nblocks; b++) {
        g_free(p->bs[b].tris);
        g_free(p->bs[b].tile_ids);
        g_free(p->bs[b].tile_start);
        memset(&p->bs[b], 0, sizeof p->bs[b]);
    }
}

void wl_ag_pipe_free(AgPipe *p)
{
    if (!p)
        return;
    clear_blocks(p);
    wl_ag_issue_free(p);
    wl_ag_order_free(p);
    g_free(p->bs);
    g_free(p->ctx_off);
    g_free(p->app_next);
    g_free(p->app_bar);
    g_free(p->app_arrived);
    g_free(p->app_parked);
    g_queue_clear(&p->gq);
    g_free(p->g_busy);
    g_free(p->g_block);
    g_free(p->tnext);
    g_free(p->sem);
    g_free(p->t_rr);
    g_free(p->r_busy);
    g_free(p->t_busy);
    g_free(p->r_cursor);
    g_free(p->r_tile);
    g_free(p->r_block);
    for (guint r = 0; r < p->s.rasterisers; r++)
        g_array_free(p->r_tiles[r], TRUE);
    g_free(p->r_tiles);
    g_free(p);
}

static void reset(AgPipe *p)
{
    clear_blocks(p);
    memset(p->app_next, 0, p->C * sizeof(guint));
    memset(p->tnext, 0, (gsize)p->ntiles * p->C * sizeof(guint));
    memset(p->sem, 0, (gsize)p->ntiles * p->nsem * sizeof(int32_t));
    memset(p->t_rr, 0, p->ntiles * sizeof(guint));
    p->pool_cursor = 0;
    memset(p->app_bar, 0, p->st->barriers * sizeof(guint));
    memset(p->app_arrived, 0, p->C * sizeof(gboolean));
    memset(p->app_parked, 0, p->C * sizeof(gboolean));
    p->tiles_left = p->ntiles;
    wl_ag_issue_reset(p);
    wl_ag_order_reset(p);
}

gboolean wl_ag_pipe_frame(AgPipe *p, SimTime until, AgFrameStats *out,
                          GError **err)
{
    memset(out, 0, sizeof *out);
    p->out = out;
    reset(p);
    out->start = out->end = sim_now(p->eng);
    out->blocks = p->nblocks;
    uint64_t bytes0 = p->mem.bytes;
    for (guint c = 0; c < p->C; c++)
        wl_ag_app_issue(p->eng, p, GUINT_TO_POINTER(c));
    for (guint t = 0; t < p->ntiles; t++)
        wl_ag_tile_advance(p, t); /* a tile no context draws into */
    if (!sim_engine_run(p->eng, until, err))
        return FALSE;
    out->shmem_bytes = p->mem.bytes - bytes0;
    out->order_violations = wl_ag_order_violations(p, p->st);
    if (p->s.retained && !sim_engine_cut(p->eng))
        p->compiled = TRUE;
    if (p->tiles_left && !sim_engine_cut(p->eng)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "argus: %u of %u tiles left undrawn at %.3f ms with "
                    "nothing left to run: the streams' semaphores deadlock, "
                    "expected every block drawn",
                    p->tiles_left, p->ntiles, sim_time_to_ms(sim_now(p->eng)));
        return FALSE;
    }
    return TRUE;
}
