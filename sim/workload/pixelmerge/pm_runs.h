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

/* What a fragment holds: active pixels, runs (linear order, or the
 * box's rows when box_mode), and the bounding box of its active pixels
 * x0, x1, y0, y1 (inclusive; any FALSE when it holds none). */
typedef struct {
    uint64_t active, runs;
    gboolean any;
    guint box[4];
} WlPmMeasure;

/* The elements of `el` (NULL: none) inside linear indices [a, b) of an
 * image `w` wide: a new array. */
GArray *wl_pm_runs_slice(WlPmRung rung, const GArray *el, guint w, uint64_t a,
                         uint64_t b);
/* front composited over back (both consumed): a new array. */
GArray *wl_pm_runs_over(WlPmRung rung, GArray *front, GArray *back);
void wl_pm_runs_measure(WlPmRung rung, const GArray *el, guint w,
                        gboolean box_mode, WlPmMeasure *m);

#endif
