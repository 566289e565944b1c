/* ag_order.c — Argus's second ordering scheme and the check of both
 * (ag_pipe.h AgScheme; graphics.stanford.edu/projects/flashg/argus/
 * implementation, Figure 1 (c): "synchronization is performed between
 * the geometry processors to allow the command processors to run more
 * freely").
 *
 *   GEOMETRY: a geometry thread takes the first queued block that is
 *       its context's next and whose glp waits are met at the geometry
 *       stage (a glpPSema has a glpVSema of a block sequenced before it,
 *       a glpBarrier has every party's arrival sequenced, a
 *       glpWaitContext(m) has m's blocks named sequenced); taking it
 *       gives it the next sequence number and applies its signals.
 *       Every tile passes the blocks in that one sequence, drawing a
 *       block when its geometry is done and skipping a done block with
 *       nothing for it (the reclaim pointer of the Argus page).  The
 *       geometry thread pays `sema` per synchronisation command.
 *   the check: every tile logs the blocks it passes (drawn or skipped);
 *       replaying a tile's log against the streams — a glpPSema needs
 *       a glpVSema of the same semaphore passed earlier at that tile and
 *       consumes it, a glpBarrier wait needs every party's arrival, a
 *       glpWaitContext(m) needs m's blocks it names, and each context's
 *       blocks come in their order — counts the commands the tile's
 *       order breaks (command-sequential consistency as the rasteriser
 *       sees it; 0 for both schemes and for sync: finish).
 * O(queue) per geometry pop, O(blocks x tiles) per check.
 */
#include "sim/workload/argus/ag_pipe_int.h"
#include <string.h>

void wl_ag_order_alloc(AgPipe *p)
{
    p->seq_block = g_new0(guint, MAX(p->nblocks, 1));
    p->seq_ctx = g_new0(guint, p->C);
    p->tseq = g_new0(guint, p->ntiles);
    p->gsem = g_new0(int32_t, p->nsem);
    p->log = g_new0(GArray *, p->ntiles);
    for (guint t = 0; t < p->ntiles; t++)
        p->log[t] = g_array_new(FALSE, FALSE, sizeof(guint));
}

void wl_ag_order_free(AgPipe *p)
{
    for (guint t = 0; t < p->ntiles; t++)
        g_array_free(p->log[t], TRUE);
    g_free(p->log);
    g_free(p->seq_block);
    g_free(p->seq_ctx);
    g_free(p->tseq);
    g_free(p->gsem);
}

void wl_ag_order_reset(AgPipe *p)
{
    p->next_seq = 0;
    memset(p->seq_ctx, 0, p->C * sizeof *p->seq_ctx);
    memset(p->tseq, 0, p->ntiles * sizeof *p->tseq);
    memset(p->gsem, 0, p->nsem * sizeof *p->gsem);
    for (guint t = 0; t < p->ntiles; t++)
        g_array_set_size(p->log[t], 0);
}

int32_t *wl_ag_count_at(int32_t *tab, const AgStreams *st, const AgSync *s)
{
    gboolean sem = s->kind == WL_AG_SYNC_P || s->kind == WL_AG_SYNC_V;
    guint i = s->id + (sem ? 0 : st->sems);
    g_assert(i < st->sems + st->barriers);
    return &tab[i];
}

/* Whether the waits of block gb (k) are met: `count` the counters,
 * `seen` per context the blocks already through. */
static gboolean met(const AgPipe *p, int32_t *count, const guint *seen,
                    guint gb, const AgBlock *k)
{
    for (guint i = 0; i < k->n_pre; i++) {
        const AgSync *s = &k->pre[i];
        if (s->kind == WL_AG_SYNC_P && *wl_ag_count_at(count, p->st, s) <= 0)
            return FALSE;
        if (s->kind == WL_AG_SYNC_BARRIER_WAIT &&
            *wl_ag_count_at(count, p->st, s) < (int32_t)p->st->barrier_parties)
            return FALSE;
        if (s->kind == WL_AG_SYNC_WAIT_CONTEXT &&
            seen[s->id] < p->bs[gb].wait_upto)
            return FALSE;
    }
    return TRUE;
}

static void apply(const AgStreams *st, int32_t *count, const AgBlock *k)
{
    for (guint i = 0; i < k->n_pre; i++)
        if (k->pre[i].kind == WL_AG_SYNC_P)
            (*wl_ag_count_at(count, st, &k->pre[i]))--;
    for (guint i = 0; i < k->n_post; i++)
        if (k->post[i].kind == WL_AG_SYNC_V ||
            k->post[i].kind == WL_AG_SYNC_BARRIER)
            (*wl_ag_count_at(count, st, &k->post[i]))++;
}

guint wl_ag_geom_pop(AgPipe *p)
{
    if (p->s.scheme == WL_AG_SCHEME_PIXEL) {
        if (g_queue_is_empty(&p->gq))
            return G_MAXUINT;
        return GPOINTER_TO_UINT(g_queue_pop_head(&p->gq));
    }
    gboolean glp = p->s.sync == WL_AG_SYNC_GLP;
    for (GList *l = p->gq.head; l; l = l->next) {
        guint gb = GPOINTER_TO_UINT(l->data), c;
        const AgBlock *k = wl_ag_block_at(p, gb, &c);
        if (gb - p->ctx_off[c] != p->seq_ctx[c] ||
            (glp && !met(p, p->gsem, p->seq_ctx, gb, k)))
            continue;
        g_queue_delete_link(&p->gq, l);
        if (glp)
            apply(p->st, p->gsem, k);
        p->seq_ctx[c]++;
        p->seq_block[p->next_seq++] = gb;
        return gb;
    }
    return G_MAXUINT;
}

guint wl_ag_seq_pick(AgPipe *p, guint t)
{
    if (p->tseq[t] >= p->next_seq)
        return G_MAXUINT;
    guint gb = p->seq_block[p->tseq[t]];
    return p->bs[gb].done ? gb : G_MAXUINT;
}

void wl_ag_tile_pass(AgPipe *p, guint t, guint c, guint gb)
{
    (*wl_ag_tnext(p, t, c))++;
    if (p->s.scheme == WL_AG_SCHEME_GEOMETRY)
        p->tseq[t]++;
    g_array_append_val(p->log[t], gb);
}

/* Replays tile t's log against st; returns the commands it breaks. */
static uint64_t replay(const AgPipe *p, const AgStreams *st, guint t,
                       int32_t *count, guint *seen)
{
    memset(count, 0, (st->sems + st->barriers) * sizeof *count);
    memset(seen, 0, st->contexts * sizeof *seen);
    const GArray *log = p->log[t];
    uint64_t bad = 0;
    for (guint i = 0; i < log->len; i++) {
        guint gb = g_array_index(log, guint, i), c;
        wl_ag_block_at(p, gb, &c);
        const AgBlock *k =
            &g_array_index(wl_ag_ctx_blocks(st, c), AgBlock,
                           gb - p->ctx_off[c]);
        bad += gb - p->ctx_off[c] != seen[c]; /* out of its order */
        for (guint j = 0; j < k->n_pre; j++) {
            AgBlock one = {.n_pre = 1, .pre = {k->pre[j]}};
            bad += !met(p, count, seen, gb, &one);
        }
        apply(st, count, k);
        seen[c]++;
    }
    return bad;
}

uint64_t wl_ag_order_violations(const AgPipe *p, const AgStreams *st)
{
    int32_t *count = g_new0(int32_t, st->sems + st->barriers + 1);
    guint *seen = g_new0(guint, st->contexts);
    uint64_t bad = 0;
    for (guint t = 0; t < p->ntiles; t++)
        bad += replay(p, st, t, count, seen);
    g_free(count);
    g_free(seen);
    return bad;
}

uint64_t wl_ag_pipe_order_check(const AgPipe *p, const AgStreams *st)
{
    g_assert(st->contexts == p->C && wl_ag_n_blocks(st) == p->nblocks &&
             st->sems == p->st->sems && st->barriers == p->st->barriers);
    return wl_ag_order_violations(p, st);
}
