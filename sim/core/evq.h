/* evq.h — the pending-event priority queue.
 *
 * An implicit 4-ary min-heap of small keys (time, seq, slot); the slot
 * points into the engine's event pool, so sifting moves 24 bytes, never
 * the payload.  Keys order by (time, seq); seq counts schedules, so equal
 * times pop in schedule order and runs are deterministic.
 * push, pop and replace_top are O(log4 n); the array grows by doubling.
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

typedef struct SimEvq SimEvq;

/* Returns a new empty queue; free with sim_evq_free(). */
SimEvq *sim_evq_new(void);
void sim_evq_free(SimEvq *q);

size_t sim_evq_len(const SimEvq *q);
void sim_evq_push(SimEvq *q, SimEvKey k);
/* The least key; the queue must not be empty. */
SimEvKey sim_evq_top(const SimEvq *q);
/* Removes and returns the least key; the queue must not be empty. */
SimEvKey sim_evq_pop(SimEvq *q);
/* Removes the least key and inserts k in one sift (the engine's hot path:
 * an event handler that schedules one successor). */
void sim_evq_replace_top(SimEvq *q, SimEvKey k);

static inline gboolean sim_evkey_less(SimEvKey a, SimEvKey b)
{
    return a.time < b.time || (a.time == b.time && a.seq < b.seq);
}

#endif
