/* engine.h — the discrete-event engine.
 *
 * Events are whole records (time, seq, handler, ctx, arg) held in a
 * SimEvq (evq.h), a monotone radix heap ordered on (time, seq), where seq
 * counts schedules so equal times run in schedule order.  Handlers run
 * one at a time; a handler may schedule any number of events at or after
 * the current time (never before: the queue relies on it).  Scheduling
 * past SIM_TIME_MAX is an error, never a wrap: the engine records it,
 * stops, and sim_engine_run() returns FALSE with SIM_ERROR_OVERFLOW; so
 * is growing the pending events past the memory limit (--mem-limit).
 *
 * Cancellation is left to the caller (a generation counter in ctx that the
 * handler checks), which keeps the queue free of position bookkeeping.
 *
 * Entities are named ids; each has a lazily created RNG stream seeded from
 * (run seed, entity id).  Phases are interned names for busy-time
 * accounting.  Cost per event: O(1) to schedule, O(1) plus amortised
 * O(log of the pending time span) record moves to run (docs/engine.md).
 */
#ifndef PGSIM_CORE_ENGINE_H
#define PGSIM_CORE_ENGINE_H

#include "sim/core/error.h"
#include "sim/core/rng.h"
#include "sim/core/time.h"

typedef struct SimEngine SimEngine;
typedef struct SimTrace SimTrace;
typedef struct SimRecorder SimRecorder;

typedef void (*SimHandler)(SimEngine *eng, void *ctx, void *arg);
/* Progress: called every `every` events with the current time. */
typedef void (*SimProgressFn)(SimEngine *eng, void *ctx);

/* Returns a new engine at time 0; free with sim_engine_free(). */
SimEngine *sim_engine_new(uint64_t seed);
void sim_engine_free(SimEngine *eng);

SimTime sim_now(const SimEngine *eng);
uint64_t sim_engine_seed(const SimEngine *eng);
uint64_t sim_engine_events(const SimEngine *eng); /* handlers run so far */
size_t sim_engine_pending(const SimEngine *eng);

/* Schedules fn(eng, ctx, arg) at now + delay / at absolute time t (>= now).
 * Returns FALSE on overflow (the engine then stops with an error). */
gboolean sim_schedule_in(SimEngine *eng, SimTime delay, SimHandler fn,
                         void *ctx, void *arg);
gboolean sim_schedule_at(SimEngine *eng, SimTime t, SimHandler fn, void *ctx,
                         void *arg);

/* Runs events with time <= until (SIM_TIME_MAX: until none are left) or
 * until sim_engine_stop().  Returns FALSE with *err set if the run hit an
 * error (overflow, or one a handler reported with sim_engine_fail()). */
gboolean sim_engine_run(SimEngine *eng, SimTime until, GError **err);
void sim_engine_stop(SimEngine *eng);
/* The run's stop time (`run.until`, set by the runner, sim/run/run.h):
 * every sim_engine_run() stops at the earlier of its own `until` and the
 * horizon, so a workload honours run.until without reading it.
 * SIM_TIME_MAX (the default): none. */
void sim_engine_set_horizon(SimEngine *eng, SimTime t);
SimTime sim_engine_horizon(const SimEngine *eng);
/* TRUE once a run has stopped at the horizon with events still pending
 * after it: the simulation was cut short.  A workload then ends its frame
 * loop and does not count the frame in progress. */
gboolean sim_engine_cut(const SimEngine *eng);
/* Dry run (`pgsim validate`): sim_engine_run() runs no event and returns
 * FALSE with SIM_ERROR_DRY_RUN, so a workload performs every check and
 * allocation that precedes its first simulated event and then stops the
 * way it stops on any engine error. */
void sim_engine_set_dry_run(SimEngine *eng, gboolean dry);
/* A handler reports an error: the engine stops; takes ownership of e. */
void sim_engine_fail(SimEngine *eng, GError *e);

/* Entities: returns a new id (0, 1, 2 ...) for a name (copied). */
uint32_t sim_entity_add(SimEngine *eng, const char *name);
const char *sim_entity_name(const SimEngine *eng, uint32_t id);
/* The entity's RNG stream, created on first use.  Borrowed. */
SimRng *sim_entity_rng(SimEngine *eng, uint32_t id);

/* Phases: interns a name; the same name always gives the same id. */
unsigned sim_engine_phase(SimEngine *eng, const char *name);
const char *sim_engine_phase_name(const SimEngine *eng, unsigned id);
unsigned sim_engine_phase_count(const SimEngine *eng);

void sim_engine_set_progress(SimEngine *eng, uint64_t every, SimProgressFn fn,
                             void *ctx);
/* Optional trace sink (sim/core/trace.h); borrowed, may be NULL. */
void sim_engine_set_trace(SimEngine *eng, SimTrace *tr);
SimTrace *sim_engine_trace(const SimEngine *eng);
/* Optional recorder (sim/core/record.h, `pgsim run --record`); borrowed. */
void sim_engine_set_recorder(SimEngine *eng, SimRecorder *r);
SimRecorder *sim_engine_recorder(const SimEngine *eng);
/* Names of network endpoints for traces: whoever numbers the nodes (the
 * machine) registers fn(ctx, id); sim_engine_node_name() returns its
 * answer (borrowed) or NULL when no namer is set.  fn NULL clears it. */
typedef const char *(*SimNodeNameFn)(void *ctx, uint32_t node);
void sim_engine_set_node_namer(SimEngine *eng, SimNodeNameFn fn, void *ctx);
const char *sim_engine_node_name(const SimEngine *eng, uint32_t node);

#endif
