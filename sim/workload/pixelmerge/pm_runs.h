/* pm_runs.h — the image elements of the runs and counts rungs
 * (pm_rung.h): cutting a process's elements to a linear range of the
 * image, compositing two element lists, and measuring what a message of
 * them holds.  pm_rung.c runs the plans on them.
 * Cost: O(elements touched) per call; a counts composite O(r^2) in its
 * r rectangles (few: intersecting ones are merged).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_RUNS_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_RUNS_H

#include "sim/workload/pixelmerge/pm_rung.h"

/* Context of the runs and counts representations: the image's width. */
typedef struct {
    WlPmRung rung;
    guint width;
} WlPmRunsCtx;

/* The representation of a rung (runs or counts) on ctx (borrowed). */
WlPmRep wl_pm_runs_rep(const WlPmRunsCtx *ctx);
/* Measures el at ctx's rung (pm_rung.h's measure). */
void wl_pm_runs_measure(const void *ctx, const GArray *el, gboolean box_mode,
                        WlPmMeasure *m);

#endif
