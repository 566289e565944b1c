/* pf_gpipe.c — the graphics pipe fed through a bounded FIFO (see
 * pf_gpipe.h): DRAW's CPU side (issue, write, block) and the pipe's side
 * (queue, compute, swap).  Deterministic; O(1) per chunk.
 */
#include "sim/workload/performer/pf_gpipe.h"

#include "sim/core/trace.h"

typedef struct {
    guint frame;
    uint64_t bytes;
    SimTime pipe;
    MachOps ops; /* the pipe's counts (empty: the time) */
    gboolean last;
    uint64_t cause; /* its arrival, for a recording's join */
} Chunk;

struct WlPfGpipe {
    SimEngine *eng;
    MachProc *cpu, *pipe;
    MachShmem *bus;
    uint64_t depth, chunk, used;
    unsigned ph_draw, ph_pipe;
    SimTime step;
    WlPfGpipeFn cpu_done, swapped;
    void *ctx;
    /* CPU side: the frame being issued */
    guint n, k, nchunks;
    WlPfDrawWork w;
    Chunk *pending;    /* computed, waiting for FIFO space */
    SimTime blocked_at;
    uint64_t cpu_cause; /* the pending chunk's computation (a recording) */
    /* pipe side */
    GQueue queue; /* Chunk *, arrived */
    gboolean pipe_busy;
    SimTime swap_wait_at;
    uint64_t pipe_cause; /* the pipe's last action done (a recording) */
    GArray *ends; /* SimTime per frame: the pipe's last command */
    WlPfGpipeStats st;
    WlPfArena *arena; /* NULL: DRAW reads no arena bytes */
};

WlPfGpipe *wl_pf_gpipe_new(SimEngine *eng, MachProc *cpu, MachProc *pipe,
                           MachShmem *bus, uint64_t depth, uint64_t chunk)
{
    g_assert(chunk >= 1 && chunk <= depth);
    WlPfGpipe *g = g_new0(WlPfGpipe, 1);
    g->eng = eng, g->cpu = cpu, g->pipe = pipe, g->bus = bus;
    g->depth = depth, g->chunk = chunk, g->step = 1;
    g->pipe_cause = SIM_RECORD_NONE;
    g_queue_init(&g->queue);
    g->ends = g_array_new(FALSE, TRUE, sizeof(SimTime));
    return g;
}

void wl_pf_gpipe_free(WlPfGpipe *g)
{
    if (!g)
        return;
    g_queue_clear_full(&g->queue, g_free);
    g_free(g->pending);
    g_array_free(g->ends, TRUE);
    g_free(g);
}

void wl_pf_gpipe_set_swap(WlPfGpipe *g, SimTime step, WlPfGpipeFn cpu_done,
                          WlPfGpipeFn swapped, void *ctx)
{
    g->step = MAX(step, 1);
    /* here, not in _new: the pipeline's phases come first in reports */
    g->ph_draw = sim_engine_phase(g->eng, "draw");
    g->ph_pipe = sim_engine_phase(g->eng, "pipe");
    g->cpu_done = cpu_done, g->swapped = swapped, g->ctx = ctx;
}

SimTime wl_pf_gpipe_frame_end(const WlPfGpipe *g, guint n)
{
    return n < g->ends->len ? g_array_index(g->ends, SimTime, n) : 0;
}

const WlPfGpipeStats *wl_pf_gpipe_stats(const WlPfGpipe *g)
{
    return &g->st;
}

static void span(WlPfGpipe *g, MachProc *p, const char *phase, SimTime from)
{
    SimTime now = sim_now(g->eng);
    if (now > from)
        sim_trace_span(sim_engine_trace(g->eng), mach_proc_id(p),
                       mach_proc_name(p), phase, from, now);
}

static void issue(WlPfGpipe *g);
static void computed(SimEngine *eng, void *ctx, void *arg);
static void pipe_next(WlPfGpipe *g);

/* ---- the pipe ------------------------------------------------------------ */

static void swap_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    WlPfGpipe *g = ctx;
    guint n = GPOINTER_TO_UINT(arg);
    g->st.pipe_blocked += sim_now(g->eng) - g->swap_wait_at;
    g->pipe_cause = sim_record_cause(eng);
    span(g, g->pipe, "swap_wait", g->swap_wait_at);
    g->pipe_busy = FALSE;
    if (g->swapped)
        g->swapped(g->ctx, n);
    pipe_next(g);
}

static void chunk_done(SimEngine *eng, void *ctx, void *arg)
{
    WlPfGpipe *g = ctx;
    Chunk *c = arg;
    g->used -= c->bytes;
    g->pipe_cause = sim_record_cause(eng);
    if (g->blocked_at) /* DRAW's CPU waits for room: try again */
        issue(g);
    if (!c->last) {
        g->pipe_busy = FALSE;
        g_free(c);
        pipe_next(g);
        return;
    }
    SimTime now = sim_now(eng);
    if (c->frame >= g->ends->len)
        g_array_set_size(g->ends, c->frame + 1);
    g_array_index(g->ends, SimTime, c->frame) = now;
    g->swap_wait_at = now; /* the pipe holds the swap until the refresh */
    sim_wait_refresh(eng, mach_proc_id(g->pipe), g->step, swap_done, g,
                     GUINT_TO_POINTER(c->frame));
    g_free(c);
}

static void pipe_next(WlPfGpipe *g)
{
    if (g->pipe_busy || g_queue_is_empty(&g->queue))
        return;
    Chunk *c = g_queue_pop_head(&g->queue);
    g->pipe_busy = TRUE;
    /* a recording's join: the other of its arrival and the pipe's last */
    uint64_t now = sim_record_cause(g->eng);
    sim_record_after(g->eng, now == c->cause ? g->pipe_cause : c->cause);
    if (c->ops.n) {
        c->pipe = mach_proc_ops_cost(g->pipe, &c->ops);
        g->st.pipe_busy += c->pipe;
        mach_proc_compute_list(g->pipe, &c->ops, g->ph_pipe, chunk_done, g, c);
        return;
    }
    g->st.pipe_busy += c->pipe;
    mach_proc_compute(g->pipe, c->pipe, g->ph_pipe, chunk_done, g, c);
}

static void arrived(SimEngine *eng, void *ctx, void *arg)
{
    WlPfGpipe *g = ctx;
    ((Chunk *)arg)->cause = sim_record_cause(eng);
    g_queue_push_tail(&g->queue, arg);
    pipe_next(g);
}

/* ---- DRAW's CPU ---------------------------------------------------------- */

void wl_pf_gpipe_set_arena(WlPfGpipe *g, WlPfArena *a)
{
    g->arena = a;
}

static void compute_pending(SimEngine *eng, void *ctx, void *arg);

/* DRAW's CPU reads chunk k's share of the arena bytes (with an arena),
 * then computes the chunk; it is written when done. */
static void compute_chunk(WlPfGpipe *g)
{
    Chunk *c = g_new0(Chunk, 1);
    c->frame = g->n;
    c->bytes = wl_pf_share(g->w.bytes, g->k, g->nchunks);
    c->pipe = wl_pf_share(g->w.pipe, g->k, g->nchunks);
    wl_pf_share_ops(&c->ops, &g->w.pipe_ops, g->k, g->nchunks);
    c->last = g->k + 1 == g->nchunks;
    g->pending = c;
    uint64_t b = g->arena ? wl_pf_share(g->w.arena_bytes, g->k, g->nchunks)
                          : 0;
    if (b)
        wl_pf_arena_move(g->arena, g->cpu, b, compute_pending, g, NULL);
    else
        compute_pending(g->eng, g, NULL);
}

static void compute_pending(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    WlPfGpipe *g = ctx;
    if (g->w.cpu_ops.n) {
        MachOps o;
        wl_pf_share_ops(&o, &g->w.cpu_ops, g->k, g->nchunks);
        g->st.cpu_busy += mach_proc_ops_cost(g->cpu, &o);
        mach_proc_compute_list(g->cpu, &o, g->ph_draw, computed, g, NULL);
        return;
    }
    SimTime t = wl_pf_share(g->w.cpu, g->k, g->nchunks);
    g->st.cpu_busy += t;
    mach_proc_compute(g->cpu, t, g->ph_draw, computed, g, NULL);
}

/* Writes the pending chunk into the FIFO if it fits (an empty FIFO takes
 * any chunk), then computes the next one; else DRAW's CPU blocks. */
static void issue(WlPfGpipe *g)
{
    Chunk *c = g->pending;
    SimTime now = sim_now(g->eng);
    if (g->used > 0 && g->used + c->bytes > g->depth) {
        if (!g->blocked_at)
            g->blocked_at = now + 1; /* +1: 0 means not blocked */
        return;
    }
    if (g->blocked_at) { /* the write waits for its computation too */
        sim_record_after(g->eng, g->cpu_cause);
        g->st.cpu_blocked += now - (g->blocked_at - 1);
        span(g, g->cpu, "fifo_full", g->blocked_at - 1);
        g->blocked_at = 0;
    }
    g->pending = NULL;
    g->used += c->bytes;
    g->st.max_used = MAX(g->st.max_used, g->used);
    g->st.chunks++;
    if (!mach_shmem_send(g->bus, g->eng, mach_proc_id(g->cpu),
                         mach_proc_id(g->pipe), c->bytes, arrived, g, c))
        return;
    sim_trace_flow(sim_engine_trace(g->eng), mach_proc_id(g->cpu),
                   mach_proc_name(g->cpu), mach_proc_id(g->pipe),
                   mach_proc_name(g->pipe), c->bytes, now, g->bus->last_end);
    if (c->last) {
        if (g->cpu_done)
            g->cpu_done(g->ctx, c->frame);
        return;
    }
    g->k++;
    compute_chunk(g);
}

static void computed(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    WlPfGpipe *g = ctx;
    g->cpu_cause = sim_record_cause(eng);
    issue(g);
}

void wl_pf_gpipe_frame(WlPfGpipe *g, guint n, const WlPfDrawWork *w)
{
    g_assert(!g->pending);
    g->n = n, g->w = *w, g->k = 0;
    uint64_t k = (w->bytes + g->chunk - 1) / g->chunk;
    g->nchunks = (guint)CLAMP(k, 1, G_MAXUINT);
    compute_chunk(g);
}
