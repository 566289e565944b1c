/* sweep_run.h — running the points of a sweep.
 *
 * A point's config is the base with the point's parameters and seed
 * applied; a SweepRunFn turns it into a SimResult.  sweep_point_line()
 * runs one point in this process and formats its JSON line: point,
 * repetition, seed, every parameter, status ("ok"/"error"), error, then
 * the metrics (frames, mean_frame_s, elapsed_s, events, comm_bytes,
 * comm_messages, util_mean, util_max over the processors used,
 * nodes_used, nodes_idle and every workload metric).  Wall
 * time is left out so that rows are identical however the sweep is run.
 *
 * Locally, points run in forked worker processes (at most `jobs` at a
 * time, one process per point): a crash or abort in one point is recorded
 * as that point's error and the others go on.  A SweepJob is the master's
 * bookkeeping, shared by the local pool and the MPI master.
 */
#ifndef PGSIM_APP_SWEEP_SWEEP_RUN_H
#define PGSIM_APP_SWEEP_SWEEP_RUN_H

#include "sim/output/progress.h"
#include "sim/app/sweep/sweep_log.h"
#include "sim/core/result.h"

/* Runs a config (seed already applied at the spec's seed_key, also passed
 * as `seed`); returns a new result in *out or FALSE with *err. */
typedef gboolean (*SweepRunFn)(const CfgNode *cfg, uint64_t seed,
                               SimResult **out, GError **err);

/* The JSON line (ending in '\n') of point i, run in this process. */
char *sweep_point_line(const SweepSpec *s, guint i, SweepRunFn fn);
/* The line of a point that failed with `msg`. */
char *sweep_point_error_line(const SweepSpec *s, guint i, const char *msg);
/* Runs point i in a forked child and returns its line; a child that dies
 * gives an error line ("worker killed by signal 11"). */
char *sweep_point_isolated(const SweepSpec *s, guint i, SweepRunFn fn);

typedef struct {
    const SweepSpec *spec;
    SweepLog *log;
    SweepRunFn fn;
    GArray *todo;     /* guint point indices not yet done, ascending */
    guint next;       /* next entry of todo to hand out */
    guint finished;   /* points finished in this run */
    guint failed;     /* of which failed */
    RptProgress *bar; /* progress on a terminal; NULL: none */
} SweepJob;

void sweep_job_init(SweepJob *j, const SweepSpec *s, SweepLog *log,
                    SweepRunFn fn, gboolean progress);
void sweep_job_clear(SweepJob *j);
/* Hands out the next point; FALSE when none are left. */
gboolean sweep_job_next(SweepJob *j, guint *i);
/* Records a finished point's line (appends it to the log, updates the
 * progress bar). */
gboolean sweep_job_finish(SweepJob *j, const char *line, GError **err);
/* Ends the progress line. */
void sweep_job_done(SweepJob *j);

/* Runs every point not yet done with up to `jobs` worker processes. */
gboolean sweep_run_local(SweepJob *j, int jobs, GError **err);

#endif
