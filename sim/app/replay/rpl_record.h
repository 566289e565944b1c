/* rpl_record.h — `pgsim run CONFIG --record FILE`: a run's trace.
 *
 * The recorder implements the hooks of sim/core/record.h: every piece of
 * work a processor is given (mach_proc_compute) and every message a
 * network carries (net_send, collectives included, as their messages)
 * becomes an action; whatever is issued while the handler of an action's
 * completion runs forms the group `on ID` of that action; the rest (set
 * up, a workload's own timers) forms `at TIME` groups, or `sync TIME`
 * when the timer fired just as all earlier work ended (no message in
 * flight): the workload waited for that work.  Frame marks are
 * placed after the run: frame k ends at the sum of the first k+1 frame
 * times, on the last action that completes then (docs/traces.md).
 *
 * Work given as named counts (mach_proc_compute_ops) is recorded as
 * counts (`c`), other work as the time it took (`w`); shared-memory
 * transfers (mach_shmem_send) as `b`, refresh waits (sim_wait_refresh)
 * as `v`, and frames that end at a refresh on their `v` wait (`swap`)
 * (docs/traces.md, "What a recorded trace holds").
 *
 * Memory: 32 bytes per action and per group, held until the trace is
 * written after the run (flags are known only then).
 */
#ifndef PGSIM_APP_REPLAY_RPL_RECORD_H
#define PGSIM_APP_REPLAY_RPL_RECORD_H

#include "sim/run/run.h"
#include "sim/core/record.h"

typedef struct RplRecorder RplRecorder;

RplRecorder *rpl_recorder_new(void);
void rpl_recorder_free(RplRecorder *r);
/* The hook table to attach to the run's engine (borrowed from r). */
SimRecorder *rpl_recorder_hook(RplRecorder *r);
uint64_t rpl_recorder_actions(const RplRecorder *r);

/* Writes the trace of a finished run to path (gzip if it ends in .gz):
 * the machine of `run` (its kinds and clocks), the result's phases and
 * frame marks.  *unplaced (may be NULL) gets the number of frames whose
 * end no action completes at.  FALSE with *err on failure (no file). */
gboolean rpl_recorder_write(RplRecorder *r, const char *path,
                            const CfgRun *run, const SimResult *res,
                            guint *unplaced, GError **err);

/* rpl_recorder_write(), then a note on stderr (unless quiet): the
 * actions written and any frames left unmarked. */
gboolean rpl_record_finish(RplRecorder *r, const char *path,
                           const CfgRun *run, const SimResult *res,
                           gboolean quiet, GError **err);

#endif
