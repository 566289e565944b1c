/* pm_replay.h — the timing of the pixel merging phase: replays the steps
 * recorded by pm_merge.h as per-processor state machines on a simulated
 * hypercube (net.h), so that message times come from the selected network
 * fidelity and compute times from counted pixel operations.
 *
 * Each processor, step after step: computes the step's "pre" work (packing
 * pixels into a send buffer), sends its messages of the step (net_send;
 * one in Kurç's schemes, any number, maybe none, in the compositing
 * schemes), waits until every message addressed to it in that step has
 * arrived, computes the "post" work (scatter, compare, gather) and goes
 * on.  Messages that arrive early are counted per (step, receiver).
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

/* Where a cost struct (WlPmMergeCosts, WlPmCosts) keeps the price of
 * one named operation: the offset of its SimTime.  Tables end with a
 * NULL name. */
typedef struct {
    const char *name;
    size_t off;
} WlPmUnit;

/* Named counts o[0 .. n-1] at the prices of `costs`, laid out as units
 * says (every name must be there), saturating: the pricing of a frame
 * run without machine processors. */
SimTime wl_pm_price(const void *costs, const WlPmUnit *units, const MachOp *o,
                    guint n);

/* The result of a replay: the time each processor's merge finished,
 * done[p]. */
typedef struct {
    SimTime *done; /* n_procs */
    SimTime end;   /* max of done */
} WlPmReplayOut;

/* Where a merge is replayed and who does its computing.  With procs,
 * every compute is charged once, to machine processor procs[p], priced
 * by its kind's cost table (mach_proc_compute_ops): its busy time per
 * phase is the record, and costs supplies only count_bytes.  Without
 * procs (an engine and a network alone), computes are engine events
 * priced by costs, and busy[p] receives their time in `phase`. */
typedef struct {
    NetNet *net;                 /* its engine, at time now */
    MachProc *const *procs;      /* borrowed; NULL: engine events */
    const WlPmMergeCosts *costs; /* prices without procs; count_bytes */
    const SimTime *ready;        /* processor p starts at ready[p] (>= now) */
    SimBusy *busy;               /* without procs; NULL with procs */
    unsigned phase;              /* of every compute */
    WlPmBalance bal;             /* the partition's global sum and setup */
    guint height;                /* the screen's scanline count */
} WlPmReplayRig;

/* Replays merge m (borrowed) as rig says: runs the engine until the
 * merge is over and fills *out (free with wl_pm_replay_out_clear).
 * FALSE with *err if the engine failed (overflow). */
gboolean wl_pm_replay(const WlPmReplayRig *rig, const WlPmMerge *m,
                      WlPmReplayOut *out, GError **err);
void wl_pm_replay_out_clear(WlPmReplayOut *out);

#endif
