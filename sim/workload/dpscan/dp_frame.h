/* dp_frame.h — one frame of data-parallel rendering in closed form.
 *
 * Walks the steps of dp_sched.h and adds up their costs (dp_cost.h)
 * without an engine: the "analytic" evaluation of a frame, used by the
 * calibration (its linear coefficients) and as the reference the
 * event-driven executor (dp_exec.h) must match on the SIMD machine.
 * O(steps + pixels) time; memory O(procs) scratch besides the schedule.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_FRAME_H
#define PGSIM_WORKLOAD_DPSCAN_DP_FRAME_H

#include "sim/workload/dpscan/dp_cost.h"
#include "sim/workload/dpscan/dp_sched.h"

typedef struct {
    SimTime phase[WL_DP_N_PHASES];
    SimTime total;
    WlDpCoef coef;     /* linear coefficients (SIMD calibration) */
    WlDpCounts counts; /* iterations, flushes, segments, messages */
    uint64_t steps;    /* data-parallel operations issued */
    double util;       /* element ops / element-op slots (padding) */
} WlDpFrame;

/* Costs one frame of geometry g on machine m; fills *out. */
void wl_dp_frame_run(const WlDpGeom *g, const WlDpMachine *m, const WlDpAlgo *a,
                     WlDpFrame *out);

#endif
