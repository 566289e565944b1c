/* rpl_replay.h — `pgsim replay TRACE --machine MODEL ...`: a recorded
 * (or hand-written) trace played on any machine model.
 *
 * Each trace processor is mapped onto one of the target machine's
 * processors (block, cyclic or a map file); `c` work is priced from the
 * target's cost table (every missing cost is listed in one located
 * error before anything runs), `w` work is scaled by the ratio of the
 * recording and target clocks, and messages go through the target's
 * network at the chosen fidelity.  A group `on ID` is issued when action
 * ID completes on the target, an `at T` group at T.  On the machine a
 * trace was recorded on, this reproduces the run: same frame times,
 * busy times and communication volume (tests/app/replay).
 *
 * Streaming: the trace is read twice (a check, then the replay), each
 * time line by line; the replay holds the actions that are issued and
 * awaited (marked `+` or `frame`) and the groups read ahead of their
 * cause, so memory follows the actions in flight, not the trace length.
 */
#ifndef PGSIM_APP_REPLAY_RPL_REPLAY_H
#define PGSIM_APP_REPLAY_RPL_REPLAY_H

#include "sim/core/result.h"

typedef struct {
    const char *trace;       /* the trace file */
    const char *machine;     /* a model name (models/NAME.yaml) */
    guint nodes;             /* 0: the model's own size */
    const char *map;         /* "block" (NULL), "cyclic" or a map file */
    const char *fidelity;    /* NULL: the trace header's, else faithful */
    const char *const *sets; /* machine.KEY=VALUE overrides, NULL-ended */
    /* KIND=HZ: the recording clock of a trace kind that has none (an
     * assumption the user states), NULL-ended; may be NULL */
    const char *const *clocks;
    /* A model whose cost table prices the `c` operations the target's
     * lacks, scaled by its clock / the target's (same kind name); NULL:
     * none (a missing cost is an error) */
    const char *costs_from;
} RplReplayOpts;

/* Replays a trace; a new result (sim_result_free), or NULL with a
 * located *err (bad trace, missing costs, unknown model ...). */
SimResult *rpl_replay(const RplReplayOpts *o, GError **err);

/* Trace processor -> target processor: "block" keeps runs of
 * ceil(n/t) consecutive ids together, "cyclic" deals them round robin;
 * both are the identity when n <= t.  For the map file and tests. */
guint rpl_map_block(guint p, guint n, guint t);
guint rpl_map_cyclic(guint p, guint n, guint t);

#endif
