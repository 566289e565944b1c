/* evq.h — the pending-event priority queue.
 *
 * An implicit 4-ary min-heap ordered by (time, seq); seq counts schedules,
 * so equal times pop in schedule order and runs are deterministic.  The
 * heap stores 16-byte entries (time, slot); a slot names the engine's pool
 * record, and the queue keeps each slot's seq in a side array consulted
 * only when two times are equal.  The array is offset so that the four
 * children of a node fill exactly one 64-byte cache line.
 * push, pop and replace_top are O(log4 n); storage grows by doubling.
 */
#ifndef PGSIM_CORE_EVQ_H
#define PGSIM_CORE_EVQ_H

#include "sim/core/time.h"
#include <stddef.h>

typedef struct {
    SimTime time;
    uint64_t seq;
    uint32_t slot;
} SimEvKey;

static inline gboolean sim_evkey_less(SimEvKey a, SimEvKey b)
{
    return a.time < b.time || (a.time == b.time && a.seq < b.seq);
}

/* Heap entry: what sifting moves. */
typedef struct {
    SimTime time;
    uint64_t slot;
} SimEvEntry;

/* Exposed so that len and top inline into the engine's loop; use the
 * functions, never the fields. */
typedef struct SimEvq {
    SimEvEntry *h; /* h[0] is the root; 64-byte aligned children groups */
    void *mem;     /* the allocation behind h */
    size_t n, cap;
    uint64_t *seqs; /* seq of each slot */
    size_t seq_cap;
} SimEvq;

/* Returns a new empty queue; free with sim_evq_free(). */
SimEvq *sim_evq_new(void);
void sim_evq_free(SimEvq *q);

static inline size_t sim_evq_len(const SimEvq *q)
{
    return q->n;
}
/* k.slot must be unique among the pending keys (the engine's pool slot). */
void sim_evq_push(SimEvq *q, SimEvKey k);
/* The least key; the queue must not be empty. */
static inline SimEvKey sim_evq_top(const SimEvq *q)
{
    g_assert(q->n > 0);
    uint32_t slot = (uint32_t)q->h[0].slot;
    return (SimEvKey){q->h[0].time, q->seqs[slot], slot};
}
/* Removes and returns the least key; the queue must not be empty. */
SimEvKey sim_evq_pop(SimEvq *q);
/* Removes the least key and inserts k in one sift (the engine's hot path:
 * an event handler that schedules one successor). */
void sim_evq_replace_top(SimEvq *q, SimEvKey k);

#endif
