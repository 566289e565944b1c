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
#include "sim/workload/argus/ag_pipe.h"
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
                                      NULL};
const MachNeed wl_ag_needs[] = {{"cpu", wl_ag_cost_ops}, {NULL, NULL}};

typedef struct {
    gboolean done;
    guint wait_upto; /* glpWaitContext: the context's blocks issued then */
    guint n_tiles;
    guint *tile_ids;   /* sorted */
    guint *tile_start; /* n_tiles + 1 offsets into tris */
    uint32_t *tris;
} BlockState;

struct AgPipe {
    MachMachine *m;
    SimEngine *eng;
    AgSetup s;
    const AgStreams *st;
    AgFrame *f;
    const SceneMesh *mesh;
    const RastView *view;
    MachShmem mem;
    unsigned ph_app, ph_geom, ph_rast;
    guint *ctx_off, nblocks;
    BlockState *bs;
    guint *app_next;
    guint *app_bar;        /* per application barrier: threads arrived */
    gboolean *app_arrived; /* per context: at its barrier's head block */
    gboolean *app_parked;  /* per context: waiting there */
    GQueue gq;
    gboolean *g_busy;
    guint *g_block;
    guint ntiles, C;
    guint *tnext; /* ntiles x C */
    int32_t *sem; /* ntiles x (sems + barriers): semaphore counts, then
                   * glpBarrier arrivals */
    guint nsem;   /* sems + barriers */
    guint *t_rr;  /* per tile: context to try first */
    guint tiles_left;
    gboolean *r_busy;
    guint nw;          /* workers of the pool (workers: pool), else 0 */
    gboolean *t_busy;  /* pool: a worker is drawing the tile */
    guint pool_cursor; /* pool: the tile to try first */
    guint *r_cursor, *r_tile, *r_block;
    GArray **r_tiles; /* tiles of each rasteriser, in row-major order */
    AgFrameStats *out;
};

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
        &c->lock,          &c->sema};
    G_STATIC_ASSERT(G_N_ELEMENTS(dst) == G_N_ELEMENTS(wl_ag_cost_ops) - 1);
    mach_costs_fill(set, "cpu", wl_ag_cost_ops, dst);
    mach_costs_free(set);
    return TRUE;
}

static MachProc *thread_proc(AgPipe *p, guint thread)
{
    return mach_proc(p->m, "cpu", thread % p->s.procs);
}

static const AgBlock *block_at(const AgPipe *p, guint b, guint *ctx)
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
static void sync_ops(const AgPipe *p, MachOps *o, const char *op, uint64_t n)
{
    mach_ops_add(o, op, p->s.uniprocessor ? 0 : n);
}

static void compute(MachProc *proc, const MachOps *o, unsigned phase,
                    SimHandler done, AgPipe *p, guint arg, SimTime *busy)
{
    *busy += mach_proc_ops_cost(proc, o);
    mach_proc_compute_list(proc, o, phase, done, p, GUINT_TO_POINTER(arg));
}

/* ---- application threads ---------------------------------------------- */

static void app_work(const AgPipe *p, const AgBlock *b, MachOps *o)
{
    if (!b->opens)
        return;
    const AgBatch *x = &g_array_index(p->st->batches, AgBatch, b->batch);
    if (p->s.app == WL_AG_APP_NURBS)
        mach_ops_add(o, "nurbs_vertex", x->distinct);
    if (p->s.app == WL_AG_APP_MARCH) {
        mach_ops_add(o, "march_voxel", p->s.voxels_per_batch);
        mach_ops_add(o, "march_triangle", x->n);
    }
}

static void app_issue(SimEngine *eng, void *ctx, void *arg);

static void enqueue(SimEngine *eng, void *ctx, void *arg);

static void app_done(SimEngine *eng, void *ctx, void *arg)
{
    AgPipe *p = ctx;
    guint c = GPOINTER_TO_UINT(arg);
    guint b = p->ctx_off[c] + p->app_next[c]++;
    const AgBlock *k = block_at(p, b, NULL);
    SimTime t = mach_shmem_transfer(&p->mem, sim_now(eng),
                                    k->verts * p->s.vertex_bytes);
    sim_schedule_at(eng, t, enqueue, p, GUINT_TO_POINTER(b));
    app_issue(eng, p, arg);
}

/* The application barrier before block b of context c (appBarrier of
 * Figure 2): TRUE when c may go on, FALSE when it parks until the last
 * thread arrives, which wakes the others. */
static gboolean app_barrier(AgPipe *p, guint c, const AgBlock *b)
{
    for (guint i = 0; i < b->n_pre; i++) {
        if (b->pre[i].kind != WL_AG_SYNC_APP_BARRIER)
            continue;
        guint id = b->pre[i].id;
        if (!p->app_arrived[c]) {
            p->app_arrived[c] = TRUE;
            p->app_bar[id]++;
        }
        if (p->app_bar[id] < p->C) {
            p->app_parked[c] = TRUE;
            return FALSE;
        }
        for (guint o = 0; o < p->C; o++)
            if (p->app_parked[o] && o != c) {
                p->app_parked[o] = FALSE;
                sim_schedule_at(p->eng, sim_now(p->eng), app_issue, p,
                                GUINT_TO_POINTER(o));
            }
    }
    p->app_arrived[c] = p->app_parked[c] = FALSE;
    return TRUE;
}

/* glpWaitContext(m) in block b: the point of m's stream it waits for is
 * what m has issued now (the paper's semantics: commands issued by m
 * before the call). */
static void resolve_waits(AgPipe *p, guint gb, const AgBlock *b)
{
    for (guint i = 0; i < b->n_pre; i++)
        if (b->pre[i].kind == WL_AG_SYNC_WAIT_CONTEXT)
            p->bs[gb].wait_upto = p->app_next[b->pre[i].id];
}

static void app_issue(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    AgPipe *p = ctx;
    guint c = GPOINTER_TO_UINT(arg);
    GArray *blocks = wl_ag_ctx_blocks(p->st, c);
    if (p->app_next[c] >= blocks->len)
        return;
    const AgBlock *b = &g_array_index(blocks, AgBlock, p->app_next[c]);
    if (!app_barrier(p, c, b))
        return;
    resolve_waits(p, p->ctx_off[c] + p->app_next[c], b);
    MachOps o = {0};
    app_work(p, b, &o);
    mach_ops_add(&o, "issue_vertex", b->verts);
    mach_ops_add(&o, "issue_batch", b->opens ? 1 : 0);
    sync_ops(p, &o, "lock", 1);
    compute(thread_proc(p, c), &o, p->ph_app, app_done, p, c,
            &p->out->app_busy);
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
    return thread_proc(p, base + i);
}

static void block_ready(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    AgPipe *p = ctx;
    p->bs[GPOINTER_TO_UINT(arg)].done = TRUE;
    if (p->nw) {
        pool_kick(p);
        return;
    }
    for (guint r = 0; r < p->s.rasterisers; r++)
        rast_kick(p, r);
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
    geom_kick(p);
}

static void geom_start(AgPipe *p, guint g, guint b)
{
    const AgBlock *k = block_at(p, b, NULL);
    guint pairs = bucket_block(p, k, &p->bs[b]);
    p->out->bucketed += pairs;
    p->out->triangles += k->n;
    p->out->verts_issued += k->verts;
    MachOps o = {0};
    sync_ops(p, &o, "lock", 1);
    mach_ops_add(&o, "geom_vertex", k->verts);
    mach_ops_add(&o, "geom_triangle", k->n);
    mach_ops_add(&o, "geom_tile", pairs);
    p->g_busy[g] = TRUE;
    p->g_block[g] = b;
    compute(worker_proc(p, 0, g), &o, p->ph_geom, geom_done, p, g,
            &p->out->geom_busy);
}

static void enqueue(SimEngine *eng, void *ctx, void *arg)
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
    for (guint g = 0; g < p->s.geometry && !g_queue_is_empty(&p->gq); g++)
        if (!p->g_busy[g])
            geom_start(p, g, GPOINTER_TO_UINT(g_queue_pop_head(&p->gq)));
}

/* ---- tiles and rasterisation threads ----------------------------------- */

static guint *tnext(AgPipe *p, guint t, guint c)
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

/* Skips, per context, done blocks with nothing for t; counts t finished
 * when every context is through. */
static void tile_advance(AgPipe *p, guint t)
{
    gboolean all = TRUE;
    for (guint c = 0; c < p->C; c++) {
        guint *nx = tnext(p, t, c);
        GArray *blocks = wl_ag_ctx_blocks(p->st, c);
        while (*nx < blocks->len) {
            const AgBlock *k = &g_array_index(blocks, AgBlock, *nx);
            const BlockState *s = &p->bs[p->ctx_off[c] + *nx];
            guint n;
            if (!s->done || k->n_pre || k->n_post || k->clear || k->swap ||
                tile_tris(s, t, &n))
                break;
            (*nx)++;
        }
        all &= *nx == blocks->len;
    }
    if (all && *tnext(p, t, 0) != G_MAXUINT) {
        *tnext(p, t, 0) = G_MAXUINT; /* finished marker */
        if (--p->tiles_left == 0)
            p->out->end = sim_now(p->eng);
    }
}

static int32_t *sem_at(AgPipe *p, guint t, const AgSync *s)
{
    guint i = s->id + (s->kind == WL_AG_SYNC_P || s->kind == WL_AG_SYNC_V
                           ? 0
                           : p->st->sems);
    g_assert(i < p->nsem);
    return &p->sem[(gsize)t * p->nsem + i];
}

/* Whether block gb (k) may be drawn at tile t now: every glpPSema has a
 * glpVSema there, every party of a glpBarrier has arrived there, and
 * the tile has passed the blocks a glpWaitContext names. */
static gboolean waits_met(AgPipe *p, guint t, guint gb, const AgBlock *k)
{
    for (guint i = 0; i < k->n_pre; i++) {
        const AgSync *s = &k->pre[i];
        if (s->kind == WL_AG_SYNC_P && *sem_at(p, t, s) <= 0)
            return FALSE;
        if (s->kind == WL_AG_SYNC_BARRIER_WAIT &&
            *sem_at(p, t, s) < (int32_t)p->st->barrier_parties)
            return FALSE;
        if (s->kind == WL_AG_SYNC_WAIT_CONTEXT &&
            *tnext(p, t, s->id) < p->bs[gb].wait_upto)
            return FALSE;
    }
    return TRUE;
}

/* A ready block of tile t (global index), or G_MAXUINT. */
static guint tile_pick(AgPipe *p, guint t)
{
    if (*tnext(p, t, 0) == G_MAXUINT)
        return G_MAXUINT;
    for (guint i = 0; i < p->C; i++) {
        guint c = (p->t_rr[t] + i) % p->C;
        GArray *blocks = wl_ag_ctx_blocks(p->st, c);
        guint nx = *tnext(p, t, c);
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
    const AgBlock *k = block_at(p, p->r_block[r], &c);
    sync_apply(p, t, k->post, k->n_post);
    (*tnext(p, t, c))++;
    p->r_busy[r] = FALSE;
    if (p->nw)
        p->t_busy[t] = FALSE;
    tile_advance(p, t);
    rast_kick(p, r);
}

static void rast_start(AgPipe *p, guint r, guint t, guint b)
{
    const AgBlock *k = block_at(p, b, NULL);
    guint n;
    const uint32_t *tris = tile_tris(&p->bs[b], t, &n);
    sync_apply(p, t, k->pre, k->n_pre);
    uint64_t cleared = k->clear ? wl_ag_frame_clear_tile(p->f, t) : 0;
    uint64_t px = wl_ag_draw(p->f, t, p->view, p->mesh, tris, n);
    if (k->swap)
        wl_ag_frame_present_tile(p->f, t);
    p->out->pixels += px;
    p->out->syncs += k->n_pre + k->n_post;
    MachOps o = {0};
    mach_ops_add(&o, "rast_triangle", n);
    if (!p->s.fill_infinite) {
        mach_ops_add(&o,
                     p->f->mode == WL_AG_BLEND ? "rast_blend" : "rast_pixel",
                     px);
        mach_ops_add(&o, "rast_clear", cleared);
    }
    sync_ops(p, &o, "sema", k->n_pre + k->n_post);
    p->r_busy[r] = TRUE;
    p->r_tile[r] = t;
    p->r_block[r] = b;
    if (p->nw)
        p->t_busy[t] = TRUE;
    compute(worker_proc(p, 1, r), &o, p->ph_rast, rast_done, p, r,
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
        tile_advance(p, t);
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
        tile_advance(p, x);
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
        guint t, b;
        if (!g_queue_is_empty(&p->gq))
            geom_start(p, w, GPOINTER_TO_UINT(g_queue_pop_head(&p->gq)));
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
        app_issue(p->eng, p, GUINT_TO_POINTER(c));
    for (guint t = 0; t < p->ntiles; t++)
        tile_advance(p, t); /* a tile no context draws into */
    if (!sim_engine_run(p->eng, until, err))
        return FALSE;
    out->shmem_bytes = p->mem.bytes - bytes0;
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
