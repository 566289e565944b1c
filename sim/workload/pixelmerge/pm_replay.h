/* pm_replay.h — the timing of the pixel merging phase: replays the steps
 * recorded by pm_merge.h as per-processor state machines on a simulated
 * hypercube (net.h), so that message times come from the selected network
 * fidelity and compute times from counted pixel operations.
 *
 * Each processor, step after step: computes the step's "pre" work (packing
 * pixels into a send buffer), sends its one message of the step
 * (net_send), waits until the message addressed to it in that step has
 * arrived, computes the "post" work (scatter, compare, gather) and goes
 * on.  Messages that arrive early are remembered per (step, receiver).
 *
 * With RS and HBP the merge starts with the global sum of the
 * per-scanline counts (seed 003 §4.1) by recursive doubling: d exchanges
 * of N counts with the neighbour over channel i, each followed by N
 * additions; HBP then sorts the N counts (N log2 N comparison steps of
 * sort_elem) and gives each scanline to the least loaded processor by a
 * linear search (N P steps of assign_step) (§4.2); RS cuts d levels by
 * binary search (d log2 N steps of sort_elem).
 * Cost: O(steps x P) memory and events.
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_REPLAY_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_REPLAY_H

#include "sim/core/stats.h"
#include "sim/machine/proc.h"
#include "sim/net/net.h"
#include "sim/workload/pixelmerge/pm_merge.h"

/* Cost of one operation of the merge phase. */
typedef struct {
    SimTime pack;         /* copy a pixel into a send buffer */
    SimTime scatter;      /* store a pixel without depth comparison */
    SimTime compare;      /* depth-test a received pixel */
    SimTime gather;       /* copy a pixel back into consecutive storage */
    SimTime sum_elem;     /* add one scanline count in the global sum */
    SimTime sort_elem;    /* one comparison step of a sort or search */
    SimTime assign_step;  /* HBP: one step of the least-loaded search */
    uint32_t count_bytes; /* bytes of one scanline count in a message */
} WlPmMergeCosts;

/* The result of a replay: per processor, busy time in `phase` accumulated
 * into busy[p] and the time its merge finished, done[p]. */
typedef struct {
    SimTime *done; /* n_procs */
    SimTime end;   /* max of done */
} WlPmReplayOut;

/* Replays merge m (borrowed) with balancing `bal` on `net` (its engine,
 * at time now): processor p starts at ready[p] (>= now).  Runs the
 * engine until the merge is over.  busy[p] receives the compute time in
 * `phase`.  `height` is the screen's scanline count.  FALSE with *err if
 * the engine failed (overflow). */
gboolean wl_pm_replay(NetNet *net, const WlPmMerge *m, WlPmBalance bal,
                      guint height, const WlPmMergeCosts *costs,
                      const SimTime *ready, SimBusy *busy, unsigned phase,
                      WlPmReplayOut *out, GError **err);
/* The same, computing on machine processors: procs[p] (borrowed; NULL:
 * plain engine events) is charged every compute in `phase` through
 * mach_proc_compute(), so its busy time and trace spans are the
 * machine's as well as busy[p]'s. */
gboolean wl_pm_replay_procs(NetNet *net, MachProc *const *procs,
                            const WlPmMerge *m, WlPmBalance bal, guint height,
                            const WlPmMergeCosts *costs, const SimTime *ready,
                            SimBusy *busy, unsigned phase, WlPmReplayOut *out,
                            GError **err);
void wl_pm_replay_out_clear(WlPmReplayOut *out);

#endif
