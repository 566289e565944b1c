/* record.h — hooks for recording what a run does, time-independently.
 *
 * A SimRecorder (attached with sim_engine_set_recorder) hears of every
 * piece of work a processor is given and every message a network is
 * asked to carry, and of the handler that runs when each completes.  The
 * model layers call the sim_record_* helpers below, which cost one NULL
 * test when no recorder is attached.  The trace writer that implements
 * the table lives in sim/app/replay/ (docs/traces.md).
 *
 * Causality: every action gets an id from the recorder; while the
 * handler of action X's completion runs, the recorder is told (begin X
 * ... end X), so whatever is issued inside it is caused by X.  Work
 * issued outside any such handler (setup, a workload's own timer) has
 * no recorded cause.
 */
#ifndef PGSIM_CORE_RECORD_H
#define PGSIM_CORE_RECORD_H

#include "sim/core/engine.h"

typedef struct SimRecorder SimRecorder;

/* A named operation and how many of it (a processor's work as counts:
 * mach_proc_compute_ops); the name is borrowed, a static string. */
typedef struct {
    const char *name;
    uint64_t count;
} SimOp;

/* A further term of work whose resources overlap (the work lasts as
 * long as its longest term: sim/machine/overlap.h): named counts priced
 * on processor `node`'s kind, or (bus) `bytes` streamed from the worker
 * to `node` through the shared memory, priced as that transfer's time. */
typedef struct {
    uint32_t node;
    gboolean bus;
    uint64_t bytes;
    const SimOp *ops;
    unsigned n_ops;
} SimOpTerm;

/* The counts of one piece of work as a recorder hears of them: its own
 * operations and, for overlapped work, its further terms (a `c` line's
 * `|` terms, docs/traces.md).  All borrowed. */
typedef struct {
    const SimOp *ops;
    unsigned n_ops;
    const SimOpTerm *terms;
    unsigned n_terms;
} SimWork;

typedef struct {
    /* `node` was given `cost` in `phase`, to end at `end`; `handled`: a
     * handler runs when it completes.  ops[0 .. n_ops-1]: the named counts
     * that cost is priced from (n_ops 0: a time only); terms[0 ..
     * n_terms-1]: further terms on overlapping resources (cost is the
     * longest of all).  Returns the action's id. */
    uint64_t (*compute)(SimRecorder *r, SimTime now, uint32_t node,
                        unsigned phase, SimTime cost, SimTime end,
                        const SimWork *w, gboolean handled);
    /* A message of `bytes` from src to dst was sent. */
    uint64_t (*send)(SimRecorder *r, SimTime now, uint32_t src, uint32_t dst,
                     uint64_t bytes, gboolean handled);
    /* `bytes` moved from src to dst through the shared memory
     * (sim/machine/shmem.h), to complete at `end`. */
    uint64_t (*transfer)(SimRecorder *r, SimTime now, uint32_t src,
                         uint32_t dst, uint64_t bytes, SimTime end);
    /* `node` waits for the first multiple of `period` at or after now
     * (a display refresh: sim_wait_refresh). */
    uint64_t (*refresh)(SimRecorder *r, SimTime now, uint32_t node,
                        SimTime period);
    /* Action `id` completed at `t` (work done / message delivered); for a
     * handled action, its handler runs between begin and end. */
    void (*begin)(SimRecorder *r, uint64_t id, SimTime t);
    void (*end)(SimRecorder *r, uint64_t id);
    /* Optional (NULL: joins are not recorded).  cause: the action whose
     * completion handler runs now, or SIM_RECORD_NONE.  after: the next
     * action issued waits also for action `id`'s completion (a join:
     * work that needs two earlier completions, e.g. its own send done
     * and its partner's message arrived; docs/traces.md `after`). */
    uint64_t (*cause)(SimRecorder *r);
    void (*after)(SimRecorder *r, uint64_t id);
} SimRecorderOps;

struct SimRecorder {
    const SimRecorderOps *ops;
    void *state;
};

/* Schedules done(eng, ctx, arg) at `t` for recorded action `id`, telling
 * the recorder when it begins and ends (done may be NULL: the recorder
 * still hears of the completion).  Returns FALSE on overflow. */
gboolean sim_record_schedule_done(SimEngine *eng, SimRecorder *r, uint64_t id,
                                  SimTime t, SimHandler done, void *ctx,
                                  void *arg);

#define SIM_RECORD_NONE G_MAXUINT64

/* The recorded action whose completion handler runs now
 * (SIM_RECORD_NONE without a recorder, outside a handler, or with a
 * recorder that keeps no joins).  O(1). */
uint64_t sim_record_cause(SimEngine *eng);
/* The next action issued on eng also waits for recorded action `id`
 * (a no-op for SIM_RECORD_NONE or without a recorder).  A workload whose
 * work needs two completions (whichever came last runs its handler)
 * keeps the first one's sim_record_cause() and calls this before issuing
 * the work from the second's handler, so that a replay waits for both. */
void sim_record_after(SimEngine *eng, uint64_t id);

/* A wait for a display refresh: done(eng, ctx, arg) runs at the first
 * multiple of `period` (>= 1 ps) at or after now, for `node` (a
 * processor id: whose wait it is, for a recording's `v` action; it
 * occupies nothing).  Returns FALSE on overflow. */
gboolean sim_wait_refresh(SimEngine *eng, uint32_t node, SimTime period,
                          SimHandler done, void *ctx, void *arg);
/* The first multiple of period at or after t (SIM_TIME_MAX on overflow). */
SimTime sim_refresh_at(SimTime t, SimTime period);

#endif
