/* evq.c — implicit 4-ary min-heap of event entries.
 *
 * Invariant: for every i > 0, !less(h[i], h[(i-1)/4]).  A 4-ary heap is
 * shallower than a binary one (log4 n levels), and with 16-byte entries
 * stored from element 3 of a 64-byte aligned block, the children 4i+1 ..
 * 4i+4 of node i lie in one cache line.  Sift-down moves a hole instead
 * of swapping.  Ties on time are broken by seq, read from the side array
 * only then.  Measured against alternatives in docs/engine.md.
 */
#include "sim/core/evq.h"
#include <stdlib.h>
#include <string.h>

#define EVQ_PAD 3 /* entries before h[0], so that h[1] is line-aligned */

static inline gboolean entry_less(const SimEvq *q, SimEvEntry a, SimEvEntry b)
{
    return a.time < b.time ||
           (a.time == b.time && q->seqs[a.slot] < q->seqs[b.slot]);
}

static void grow_heap(SimEvq *q, size_t cap)
{
    size_t bytes = (cap + EVQ_PAD + 1) * sizeof(SimEvEntry);
    bytes = (bytes + 63) & ~(size_t)63;
    void *mem = aligned_alloc(64, bytes);
    if (!mem)
        g_error("evq: out of memory for %zu pending events", cap);
    SimEvEntry *h = (SimEvEntry *)mem + EVQ_PAD;
    if (q->n)
        memcpy(h, q->h, q->n * sizeof(SimEvEntry));
    free(q->mem);
    q->mem = mem;
    q->h = h;
    q->cap = cap;
}

SimEvq *sim_evq_new(void)
{
    SimEvq *q = g_new0(SimEvq, 1);
    grow_heap(q, 64);
    return q;
}

void sim_evq_free(SimEvq *q)
{
    if (!q)
        return;
    free(q->mem);
    g_free(q->seqs);
    g_free(q);
}

static void note_seq(SimEvq *q, SimEvKey k)
{
    if (k.slot >= q->seq_cap) {
        size_t cap = q->seq_cap ? q->seq_cap : 64;
        while (cap <= k.slot)
            cap *= 2;
        q->seqs = g_renew(uint64_t, q->seqs, cap);
        q->seq_cap = cap;
    }
    q->seqs[k.slot] = k.seq;
}

/* Places e at the hole i and moves it up past greater parents. */
static inline void sift_up(SimEvq *q, size_t i, SimEvEntry e)
{
    SimEvEntry *h = q->h;
    while (i > 0) {
        size_t p = (i - 1) >> 2;
        if (!entry_less(q, e, h[p]))
            break;
        h[i] = h[p];
        i = p;
    }
    h[i] = e;
}

/* The lesser of h[a] and h[b].  Equal times are rare in most models and
 * take the predictable branch to the seq side array; otherwise the choice
 * compiles to a conditional move, not a branch the CPU must guess. */
static inline size_t lesser(const SimEvq *q, const SimEvEntry *h, size_t a,
                            size_t b)
{
    SimTime ta = h[a].time, tb = h[b].time;
    if (G_UNLIKELY(ta == tb))
        return q->seqs[h[b].slot] < q->seqs[h[a].slot] ? b : a;
    size_t take_b = -(size_t)(tb < ta); /* all ones or zero: no branch */
    return a ^ ((a ^ b) & take_b);
}

/* The least of the children c .. c+3 of heap h (those below n): a
 * three-comparison, branch-free tournament when all four exist (the
 * common case).  Choosing the least child is a coin toss for a branch
 * predictor; callgrind's branch simulation counted 6.8 mispredictions per
 * PHOLD event with a compare loop, 1.4 with the tournament. */
static inline size_t least_child(const SimEvq *q, const SimEvEntry *h, size_t n,
                                 size_t c)
{
    if (G_LIKELY(c + 4 <= n))
        return lesser(q, h, lesser(q, h, c, c + 1), lesser(q, h, c + 2, c + 3));
    size_t m = c;
    for (size_t j = c + 1; j < n; j++)
        m = lesser(q, h, m, j);
    return m;
}

void sim_evq_push(SimEvq *q, SimEvKey k)
{
    if (q->n == q->cap)
        grow_heap(q, q->cap * 2);
    note_seq(q, k);
    sift_up(q, q->n++, (SimEvEntry){k.time, k.slot});
}

/* Places e at the hole i and sifts it down to its place. */
static void sift_down(SimEvq *q, size_t i, SimEvEntry e)
{
    SimEvEntry *h = q->h;
    size_t n = q->n;
    for (;;) {
        size_t c = 4 * i + 1;
        if (c >= n)
            break;
        size_t m = least_child(q, h, n, c);
        if (!entry_less(q, h[m], e))
            break;
        h[i] = h[m];
        i = m;
    }
    h[i] = e;
}

SimEvKey sim_evq_pop(SimEvq *q)
{
    SimEvKey top = sim_evq_top(q);
    SimEvEntry last = q->h[--q->n];
    if (q->n > 0)
        sift_down(q, 0, last);
    return top;
}

/* Bottom-up replace (Wegener's bottom-up heapsort idea): walk the hole
 * down the path of least children to a leaf without comparing against e,
 * then sift e up from there.  A new event is usually later than most
 * pending ones, so it settles near the leaves and the walk up is short:
 * 3 comparisons a level instead of 4. */
static void sift_bottom_up(SimEvq *q, SimEvEntry e)
{
    SimEvEntry *h = q->h;
    size_t n = q->n, i = 0;
    for (;;) {
        size_t c = 4 * i + 1;
        if (c >= n)
            break;
        size_t m = least_child(q, h, n, c);
        h[i] = h[m];
        i = m;
    }
    sift_up(q, i, e);
}

void sim_evq_replace_top(SimEvq *q, SimEvKey k)
{
    g_assert(q->n > 0);
    note_seq(q, k);
    sift_bottom_up(q, (SimEvEntry){k.time, k.slot});
}
