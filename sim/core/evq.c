/* evq.c — implicit 4-ary min-heap of event keys.
 *
 * Invariant: for every i > 0, !less(h[i], h[(i-1)/4]).  A 4-ary heap is
 * shallower than a binary one (log4 n levels) and its four children share
 * one or two cache lines, which measured faster for PHOLD here (see
 * docs/engine.md).  Sift-down moves the hole instead of swapping.
 */
#include "sim/core/evq.h"

struct SimEvq {
    SimEvKey *h;
    size_t n, cap;
};

SimEvq *sim_evq_new(void)
{
    SimEvq *q = g_new0(SimEvq, 1);
    q->cap = 64;
    q->h = g_new(SimEvKey, q->cap);
    return q;
}

void sim_evq_free(SimEvq *q)
{
    if (!q)
        return;
    g_free(q->h);
    g_free(q);
}

size_t sim_evq_len(const SimEvq *q)
{
    return q->n;
}

void sim_evq_push(SimEvq *q, SimEvKey k)
{
    if (q->n == q->cap) {
        q->cap *= 2;
        q->h = g_renew(SimEvKey, q->h, q->cap);
    }
    size_t i = q->n++;
    while (i > 0) {
        size_t p = (i - 1) >> 2;
        if (!sim_evkey_less(k, q->h[p]))
            break;
        q->h[i] = q->h[p];
        i = p;
    }
    q->h[i] = k;
}

SimEvKey sim_evq_top(const SimEvq *q)
{
    g_assert(q->n > 0);
    return q->h[0];
}

/* Places k at the hole i and sifts it down to its place. */
static void sift_down(SimEvq *q, size_t i, SimEvKey k)
{
    SimEvKey *h = q->h;
    size_t n = q->n;
    for (;;) {
        size_t c = 4 * i + 1;
        if (c >= n)
            break;
        size_t end = c + 4 < n ? c + 4 : n, m = c;
        for (size_t j = c + 1; j < end; j++)
            if (sim_evkey_less(h[j], h[m]))
                m = j;
        if (!sim_evkey_less(h[m], k))
            break;
        h[i] = h[m];
        i = m;
    }
    h[i] = k;
}

SimEvKey sim_evq_pop(SimEvq *q)
{
    g_assert(q->n > 0);
    SimEvKey top = q->h[0];
    SimEvKey last = q->h[--q->n];
    if (q->n > 0)
        sift_down(q, 0, last);
    return top;
}

void sim_evq_replace_top(SimEvq *q, SimEvKey k)
{
    g_assert(q->n > 0);
    sift_down(q, 0, k);
}
