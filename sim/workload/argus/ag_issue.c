/* ag_issue.c — Argus's application threads (ag_pipe.h, ag_pipe_int.h):
 * each issues its context's blocks in order, with what the API around
 * the primitives costs.
 *
 *   work and issue: per block, the batch's application work when it
 *       opens a batch, issue_vertex per vertex, issue_batch per batch,
 *       issue_state per state command (ag_stream.h), one lock to append
 *       it to the geometry queue; the commands (vertices and state)
 *       cross the shared memory before the block is queued.
 *   retained mode (seed 002, "Three Issues of a Parallel API #2"): the
 *       first frame compiles each batch into a display list (issued as
 *       in immediate mode); later frames issue one glCallList per batch
 *       (priced issue_batch, call_bytes into the buffer) and no
 *       application work or vertex: the list is executed by reference,
 *       and the geometry threads still read its bytes from memory.
 *   bounded buffer (buffer_bytes): a block's commands stay in its
 *       context's buffer until its geometry is done; a thread whose
 *       next block does not fit in what is left (and the buffer is not
 *       empty) waits: issue_blocked.
 *   sync: finish (the paper's baseline, seed 002 "Past Work: OpenGL and
 *       X"): the streams' glp commands are honoured by the threads, not
 *       the pipe.  After a block that signals (glpVSema, glpBarrier
 *       arrival) the thread calls glFinish — waits until every tile has
 *       passed the commands every context had issued (the whole pipe
 *       drains; finish_context: its own context's only) — then signals at the
 *       application level; before a block that waits (glpPSema, the
 *       barrier, glpWaitContext(m): m's commands issued then, drained)
 *       the thread waits for that signal.  Both waits: finish_wait.
 *       The application barrier (appBarrier) is the same in both modes.
 * O(1) per block, plus O(tiles x contexts^2) per completion while a
 * thread waits on glFinish.
 */
#include "sim/workload/argus/ag_pipe_int.h"
#include <string.h>

void wl_ag_issue_alloc(AgPipe *p)
{
    p->buf_used = g_new0(uint64_t, p->C);
    p->park = g_new0(AgPark, p->C);
    p->since = g_new0(SimTime, p->C);
    p->finish_upto = g_new0(guint, (gsize)p->C * p->C);
    p->app_sem = g_new0(int32_t, p->nsem);
    p->app_passed = g_new0(gboolean, p->C);
}

void wl_ag_issue_free(AgPipe *p)
{
    g_free(p->buf_used);
    g_free(p->park);
    g_free(p->since);
    g_free(p->finish_upto);
    g_free(p->app_sem);
    g_free(p->app_passed);
}

void wl_ag_issue_reset(AgPipe *p)
{
    memset(p->buf_used, 0, p->C * sizeof *p->buf_used);
    memset(p->park, 0, p->C * sizeof *p->park);
    memset(p->finish_upto, 0, (gsize)p->C * p->C * sizeof *p->finish_upto);
    memset(p->app_sem, 0, p->nsem * sizeof *p->app_sem);
    memset(p->app_passed, 0, p->C * sizeof *p->app_passed);
}

/* Executing display lists (retained mode after the first frame). */
static gboolean executing(const AgPipe *p)
{
    return p->s.retained && p->compiled;
}

/* Bytes block b puts in its context's command buffer. */
static uint64_t cmd_bytes(const AgPipe *p, const AgBlock *b)
{
    if (executing(p))
        return b->opens ? p->s.call_bytes : 0;
    return b->verts * p->s.vertex_bytes +
           (uint64_t)b->n_state * p->s.state_bytes;
}

static void app_work(const AgPipe *p, const AgBlock *b, MachOps *o)
{
    if (!b->opens || executing(p))
        return;
    const AgBatch *x = &g_array_index(p->st->batches, AgBatch, b->batch);
    if (p->s.app == WL_AG_APP_NURBS)
        mach_ops_add(o, "nurbs_vertex", x->distinct);
    if (p->s.app == WL_AG_APP_MARCH) {
        mach_ops_add(o, "march_voxel", p->s.voxels_per_batch);
        mach_ops_add(o, "march_triangle", x->n);
    }
}

/* Application-level counters (sync: finish). */
static int32_t *app_sem_at(AgPipe *p, const AgSync *s)
{
    return wl_ag_count_at(p->app_sem, p->st, s);
}

/* Context m's blocks every tile has passed. */
static guint drained(AgPipe *p, guint m)
{
    guint len = wl_ag_ctx_blocks(p->st, m)->len, low = len;
    for (guint t = 0; t < p->ntiles; t++) {
        if (!wl_ag_tile_busy(p, t))
            wl_ag_tile_advance(p, t);
        guint nx = *wl_ag_tnext(p, t, 0) == G_MAXUINT
                       ? len
                       : *wl_ag_tnext(p, t, m);
        low = MIN(low, nx);
    }
    return low;
}

/* sync: finish — whether block gb (b) may be issued now. */
static gboolean app_waits_met(AgPipe *p, guint gb, const AgBlock *b)
{
    for (guint i = 0; i < b->n_pre; i++) {
        const AgSync *s = &b->pre[i];
        if (s->kind == WL_AG_SYNC_P && *app_sem_at(p, s) <= 0)
            return FALSE;
        if (s->kind == WL_AG_SYNC_BARRIER_WAIT &&
            *app_sem_at(p, s) < (int32_t)p->st->barrier_parties)
            return FALSE;
        if (s->kind == WL_AG_SYNC_WAIT_CONTEXT &&
            drained(p, s->id) < p->bs[gb].wait_upto)
            return FALSE;
    }
    return TRUE;
}

static void app_apply(AgPipe *p, const AgSync *s, guint n)
{
    for (guint i = 0; i < n; i++) {
        if (s[i].kind == WL_AG_SYNC_P)
            (*app_sem_at(p, &s[i]))--;
        if (s[i].kind == WL_AG_SYNC_V || s[i].kind == WL_AG_SYNC_BARRIER)
            (*app_sem_at(p, &s[i]))++;
    }
}

static void park(AgPipe *p, guint c, AgPark why)
{
    p->park[c] = why;
    p->since[c] = sim_now(p->eng);
}

/* Ends c's wait (booked to *into) and lets it issue now. */
static void unpark(AgPipe *p, guint c, SimTime *into)
{
    *into += sim_now(p->eng) - p->since[c];
    p->park[c] = AG_RUN;
    sim_schedule_at(p->eng, sim_now(p->eng), wl_ag_app_issue, p,
                    GUINT_TO_POINTER(c));
}

static gboolean signals(const AgBlock *b)
{
    for (guint i = 0; i < b->n_post; i++)
        if (b->post[i].kind == WL_AG_SYNC_V ||
            b->post[i].kind == WL_AG_SYNC_BARRIER)
            return TRUE;
    return FALSE;
}

/* Whether context c's glFinish is over: every tile has passed the
 * blocks it waits for, of its own context or of every one. */
static gboolean finished(AgPipe *p, guint c)
{
    for (guint m = 0; m < p->C; m++)
        if (p->finish_upto[(gsize)c * p->C + m] > 0 &&
            drained(p, m) < p->finish_upto[(gsize)c * p->C + m])
            return FALSE;
    return TRUE;
}

/* glFinish by context c: what it waits for. */
static void call_finish(AgPipe *p, guint c)
{
    for (guint m = 0; m < p->C; m++)
        p->finish_upto[(gsize)c * p->C + m] =
            m == c || !p->s.finish_context ? p->app_next[m] : 0;
}

void wl_ag_finish_poll(AgPipe *p)
{
    if (p->s.sync != WL_AG_SYNC_FINISH)
        return;
    for (guint c = 0; c < p->C; c++)
        if (p->park[c] == AG_PARK_FINISH && finished(p, c)) {
            const AgBlock *b = wl_ag_block_at(
                p, p->ctx_off[c] + p->app_next[c] - 1, NULL);
            app_apply(p, b->post, b->n_post);
            unpark(p, c, &p->out->finish_wait);
        }
    for (guint c = 0; c < p->C; c++) {
        guint gb = p->ctx_off[c] + p->app_next[c];
        if (p->park[c] == AG_PARK_WAIT &&
            app_waits_met(p, gb, wl_ag_block_at(p, gb, NULL)))
            unpark(p, c, &p->out->finish_wait);
    }
}

void wl_ag_issue_freed(AgPipe *p, guint gb)
{
    guint c;
    wl_ag_block_at(p, gb, &c);
    p->buf_used[c] -= p->bs[gb].cmd_bytes;
    if (p->park[c] == AG_PARK_BUFFER)
        unpark(p, c, &p->out->issue_blocked);
}

static void app_done(SimEngine *eng, void *ctx, void *arg)
{
    AgPipe *p = ctx;
    guint c = GPOINTER_TO_UINT(arg);
    guint b = p->ctx_off[c] + p->app_next[c]++;
    const AgBlock *k = wl_ag_block_at(p, b, NULL);
    SimTime t = mach_shmem_transfer(
        &p->mem, sim_now(eng),
        k->verts * p->s.vertex_bytes + (uint64_t)k->n_state * p->s.state_bytes);
    sim_schedule_at(eng, t, wl_ag_enqueue, p, GUINT_TO_POINTER(b));
    if (p->s.sync == WL_AG_SYNC_FINISH && signals(k)) {
        call_finish(p, c);
        park(p, c, AG_PARK_FINISH);
        return; /* wl_ag_finish_poll wakes it */
    }
    wl_ag_app_issue(eng, p, arg);
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
                sim_schedule_at(p->eng, sim_now(p->eng), wl_ag_app_issue, p,
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

/* Whether c must wait for buffer space for `bytes` more. */
static gboolean buffer_full(const AgPipe *p, guint c, uint64_t bytes)
{
    return p->s.buffer_bytes && p->buf_used[c] > 0 &&
           p->buf_used[c] + bytes > p->s.buffer_bytes;
}

void wl_ag_app_issue(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    AgPipe *p = ctx;
    guint c = GPOINTER_TO_UINT(arg);
    GArray *blocks = wl_ag_ctx_blocks(p->st, c);
    if (p->app_next[c] >= blocks->len || p->park[c] != AG_RUN)
        return;
    guint gb = p->ctx_off[c] + p->app_next[c];
    const AgBlock *b = &g_array_index(blocks, AgBlock, p->app_next[c]);
    if (!p->app_passed[c]) { /* once per block, whatever waits follow */
        if (!app_barrier(p, c, b))
            return;
        p->app_passed[c] = TRUE;
        resolve_waits(p, gb, b);
    }
    gboolean finish = p->s.sync == WL_AG_SYNC_FINISH;
    if (finish && !app_waits_met(p, gb, b)) {
        park(p, c, AG_PARK_WAIT);
        return;
    }
    uint64_t bytes = cmd_bytes(p, b);
    if (buffer_full(p, c, bytes)) {
        park(p, c, AG_PARK_BUFFER);
        return;
    }
    if (finish)
        app_apply(p, b->pre, b->n_pre);
    p->app_passed[c] = FALSE;
    p->buf_used[c] += bytes;
    p->bs[gb].cmd_bytes = bytes;
    p->out->command_bytes += bytes;
    MachOps o = {0};
    app_work(p, b, &o);
    if (!executing(p)) {
        mach_ops_add(&o, "issue_vertex", b->verts);
        mach_ops_add(&o, "issue_state", b->n_state);
        p->out->states += b->n_state;
    }
    mach_ops_add(&o, "issue_batch", b->opens ? 1 : 0);
    wl_ag_sync_ops(p, &o, "lock", 1);
    if (finish)
        wl_ag_sync_ops(p, &o, "sema", b->n_pre + b->n_post);
    wl_ag_compute(wl_ag_thread_proc(p, c), &o, p->ph_app, app_done, p, c,
                  &p->out->app_busy);
}
