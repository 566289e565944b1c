/* evq.c — radix heap of event records (evq.h).
 *
 * Invariants: every event of bucket b > 0 has a time t > last whose
 * highest bit differing from last is bit b - 1; bucket 0 (from `head`)
 * holds the events at time `last` in seq order.  When top() finds bucket
 * 0 empty it settles: the lowest non-empty bucket (a bit scan of `used`)
 * gives its least time to `last` and its events move to lower buckets,
 * so an event moves at most 64 times and in practice a few.  Settling is
 * lazy (pops never settle), so pushes before the first top() — an
 * engine's set-up — may come in any time order; a push below `last`
 * afterwards (only after a run stopped at a time limit) re-buckets every
 * event once.  Equal times reaching bucket 0 together are put in seq
 * order there (insertion; a direct push lands at the end, its seq being
 * the largest).
 *
 * Chosen by measurement over the cache-aligned 4-ary heap of (time, slot)
 * keys with a pool of records it replaces (docs/engine.md): at 262,144
 * and 1,048,576 pending the heap's sift touched a random cache line per
 * level and the pool one more per event; here pushes append and settles
 * scan, both sequential, and the record travels with its key.
 */
#include "sim/core/evq.h"
#include <string.h>

SimEvq *sim_evq_new(void)
{
    return g_new0(SimEvq, 1);
}

void sim_evq_free(SimEvq *q)
{
    if (!q)
        return;
    for (int b = 0; b < SIM_EVQ_BUCKETS; b++)
        g_free(q->b[b].a);
    g_free(q);
}

static inline unsigned bucket_of(SimTime last, SimTime t)
{
    return t == last ? 0 : 64 - (unsigned)__builtin_clzll(t ^ last);
}

static inline void append(SimEvBucket *bk, const SimEvKey *e)
{
    if (G_UNLIKELY(bk->n == bk->cap)) {
        bk->cap = bk->cap ? 2 * bk->cap : 64;
        bk->a = g_renew(SimEvKey, bk->a, bk->cap);
    }
    bk->a[bk->n++] = *e;
}

/* Appends e to bucket 0 and moves it before later-seq events; drops the
 * consumed prefix when it is most of the array (many events at one time). */
static void append_zero(SimEvq *q, const SimEvKey *e)
{
    SimEvBucket *z = &q->b[0];
    if (G_UNLIKELY(q->head >= 4096 && 2 * q->head >= z->n)) {
        memmove(z->a, z->a + q->head, (z->n - q->head) * sizeof *z->a);
        z->n -= q->head;
        q->head = 0;
    }
    append(z, e);
    size_t i = z->n - 1;
    while (i > q->head && z->a[i - 1].seq > e->seq) {
        z->a[i] = z->a[i - 1];
        i--;
    }
    z->a[i] = *e;
}

static inline void place(SimEvq *q, const SimEvKey *e)
{
    unsigned b = bucket_of(q->last, e->time);
    if (b == 0) {
        append_zero(q, e);
        return;
    }
    SimEvBucket *bk = &q->b[b];
    if (bk->n == 0 || e->time < bk->min)
        bk->min = e->time;
    append(bk, e);
    q->used |= (uint64_t)1 << (b - 1);
}

/* k.time < last: every event is re-bucketed against the new last. */
static void lower_last(SimEvq *q, SimTime t)
{
    GArray *all = g_array_new(FALSE, FALSE, sizeof(SimEvKey));
    for (int b = 0; b < SIM_EVQ_BUCKETS; b++) {
        size_t from = b == 0 ? q->head : 0;
        g_array_append_vals(all, q->b[b].a + from, q->b[b].n - from);
        q->b[b].n = 0;
    }
    q->head = 0;
    q->used = 0;
    q->last = t;
    for (guint i = 0; i < all->len; i++)
        place(q, &g_array_index(all, SimEvKey, i));
    g_array_free(all, TRUE);
}

void sim_evq_push(SimEvq *q, SimEvKey k)
{
    if (G_UNLIKELY(k.time < q->last))
        lower_last(q, k.time);
    q->n++;
    place(q, &k);
}

void sim_evq_settle(SimEvq *q)
{
    g_assert(q->n > 0 && q->used != 0);
    q->b[0].n = 0;
    q->head = 0;
    unsigned b = (unsigned)__builtin_ctzll(q->used) + 1;
    SimEvBucket *bk = &q->b[b];
    q->last = bk->min;
    size_t n = bk->n;
    bk->n = 0;
    q->used &= ~((uint64_t)1 << (b - 1));
    for (size_t i = 0; i < n; i++)
        place(q, &bk->a[i]);
}

SimEvKey sim_evq_pop(SimEvq *q)
{
    SimEvKey top = *sim_evq_top(q);
    q->n--;
    q->head++;
    return top;
}

void sim_evq_replace_top(SimEvq *q, SimEvKey k)
{
    g_assert(q->n > 0 && q->head < q->b[0].n && k.time >= q->last);
    place(q, &k);
    q->head++;
}
