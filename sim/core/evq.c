/* evq.c — radix heap of event records (evq.h).
 *
 * Invariants: every event of bucket b > 0 has a time t > last whose
 * highest bit differing from last is bit b - 1; bucket 0 (from `head`),
 * the run, holds events in (time, seq) order, none later than any event
 * of a bucket b > 0 and none before `last`.  When top() finds the run
 * empty it settles: the lowest non-empty bucket (a bit scan of `used`)
 * gives its least time to `last`; if it holds at most RUN_MAX events they
 * become the run, sorted (they never move again), else they move to
 * lower buckets (those at `last` to the run, in seq order), so an event
 * moves at most 64 times and in practice a few.  A new event earlier than
 * the run's last one is inserted into the run; any other is bucketed
 * against `last` (all bucketed events stay later than the run).  Settling
 * is lazy (pops never settle), so pushes before the first top() — an
 * engine's set-up — may come in any time order; a push below `last`
 * afterwards (only after a run stopped at a time limit) re-buckets every
 * event once.
 *
 * Chosen by measurement over the cache-aligned 4-ary heap of (time, slot)
 * keys with a pool of records it replaces (docs/engine.md): at 262,144
 * and 1,048,576 pending the heap's sift touched a random cache line per
 * level and the pool one more per event; here pushes append and settles
 * scan, both sequential, and the record travels with its key.  Sorting
 * small buckets whole (RUN_MAX 32; 16 and 64 measured within noise)
 * instead of spreading them saved the last few moves of most events:
 * engine / bare 4-ary heap in `bench phold` went from 0.77 to 0.88 at
 * 1,024 pending, 1.12 to 1.27 at 262,144 and 1.41 to 1.46 at 1,048,576
 * (CPU seconds, two runs each).
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

/* Inserts e into the run (bucket 0) in (time, seq) order; drops the
 * consumed prefix when it is most of the array (many events at one
 * time).  e is never less than the run's head (times are monotone and a
 * new seq is the largest), so the search stops at head. */
static void run_insert(SimEvq *q, const SimEvKey *e)
{
    SimEvBucket *z = &q->b[0];
    if (G_UNLIKELY(q->head >= 4096 && 2 * q->head >= z->n)) {
        memmove(z->a, z->a + q->head, (z->n - q->head) * sizeof *z->a);
        z->n -= q->head;
        q->head = 0;
    }
    append(z, e);
    size_t i = z->n - 1;
    while (i > q->head && sim_evkey_less(*e, z->a[i - 1])) {
        z->a[i] = z->a[i - 1];
        i--;
    }
    z->a[i] = *e;
}

static inline void place(SimEvq *q, const SimEvKey *e)
{
    SimEvBucket *z = &q->b[0];
    if (q->head < z->n && e->time < z->a[z->n - 1].time) {
        run_insert(q, e); /* inside the run's span */
        return;
    }
    unsigned b = bucket_of(q->last, e->time);
    if (b == 0) {
        run_insert(q, e);
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

/* A settled bucket of at most RUN_MAX events becomes the run whole,
 * sorted, instead of being spread over lower buckets. */
#define RUN_MAX 32

static void sort_into_run(SimEvq *q, const SimEvKey *a, size_t n)
{
    SimEvBucket *z = &q->b[0];
    for (size_t k = 0; k < n; k++) {
        append(z, &a[k]);
        size_t i = z->n - 1;
        while (i > 0 && sim_evkey_less(a[k], z->a[i - 1])) {
            z->a[i] = z->a[i - 1];
            i--;
        }
        z->a[i] = a[k];
    }
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
    if (n <= RUN_MAX) {
        sort_into_run(q, bk->a, n);
        return;
    }
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
