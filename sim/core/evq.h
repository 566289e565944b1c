/* evq.h — the pending-event priority queue.
 *
 * A monotone priority queue of events ordered by (time, seq); seq counts
 * schedules, so equal times pop in schedule order and runs are
 * deterministic.  Monotone: a pushed time is never less than the time of
 * the last event popped (a discrete-event engine never schedules into the
 * past), which lets it be a radix heap (Ahuja, Mehlhorn, Orlin & Tarjan,
 * "Faster algorithms for the shortest path problem", J. ACM 37(2), 1990):
 * 65 buckets of whole event records, bucket b > 0 holding the events
 * whose time first differs from `last` in bit b - 1, bucket 0 the run:
 * the least events in (time, seq) order (a small bucket sorted whole, or
 * the events at time `last`).  Records are stored in the buckets (no
 * pool, no side array), so every access is sequential.
 * push O(1); pop O(1) plus amortised O(log of the time span) record moves.
 */
#ifndef PGSIM_CORE_EVQ_H
#define PGSIM_CORE_EVQ_H

#include "sim/core/time.h"
#include <stddef.h>

typedef struct SimEngine SimEngine;
typedef void (*SimHandler)(SimEngine *eng, void *ctx, void *arg);

/* One pending event: its key (time, seq) and its record. */
typedef struct {
    SimTime time;
    uint64_t seq;
    SimHandler fn;
    void *ctx, *arg;
} SimEvKey;

static inline gboolean sim_evkey_less(SimEvKey a, SimEvKey b)
{
    return a.time < b.time || (a.time == b.time && a.seq < b.seq);
}

typedef struct {
    SimEvKey *a;
    size_t n, cap;
    SimTime min; /* least time in a[0 .. n) (buckets > 0) */
} SimEvBucket;

#define SIM_EVQ_BUCKETS 65

/* Exposed so that len and top inline into the engine's loop; use the
 * functions, never the fields. */
typedef struct SimEvq {
    SimEvBucket b[SIM_EVQ_BUCKETS];
    size_t head;   /* bucket 0 is consumed from a[head] */
    uint64_t used; /* bit b - 1 set: bucket b > 0 is not empty */
    SimTime last;  /* bucket 0's time; no pending time is below it */
    size_t n;      /* events pending */
} SimEvq;

/* Returns a new empty queue; free with sim_evq_free(). */
SimEvq *sim_evq_new(void);
void sim_evq_free(SimEvq *q);

static inline size_t sim_evq_len(const SimEvq *q)
{
    return q->n;
}
/* Seqs must grow with pushes at equal times (the engine's do).  Pushing
 * a time below the least pending one after top() has been asked costs
 * O(n) once (the engine does it only after a run stopped at a limit). */
void sim_evq_push(SimEvq *q, SimEvKey k);
/* The run (bucket 0) is empty: moves the least events into it (evq.c). */
void sim_evq_settle(SimEvq *q);
/* The least event (borrowed until the next call); the queue must not be
 * empty. */
static inline const SimEvKey *sim_evq_top(SimEvq *q)
{
    g_assert(q->n > 0);
    if (G_UNLIKELY(q->head == q->b[0].n))
        sim_evq_settle(q);
    return &q->b[0].a[q->head];
}
/* Removes and returns the least event; the queue must not be empty. */
SimEvKey sim_evq_pop(SimEvq *q);
/* Removes the least event and inserts k (the engine's hot path: a
 * handler that schedules one successor); top() must have been called
 * since the last push, and k.time >= its time. */
void sim_evq_replace_top(SimEvq *q, SimEvKey k);

#endif
