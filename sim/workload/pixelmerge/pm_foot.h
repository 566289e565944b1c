/* pm_foot.h — synthetic per-process images for compositing at scale:
 * the screen footprints of a regular 3-D block decomposition of a cube
 * among P processes, each drawn as the ellipse inscribed in its block's
 * screen rectangle, at any rung of pm_rung.h.
 *
 * P = bx x by x bz (bz the largest factor <= cbrt P, by the largest <=
 * sqrt(P / bz)); process p is block (i, j, k) with p = i + bx (j + by k),
 * k the depth slab, nearest first, so processor order is visibility
 * order.  A point (x, y, z) of the unit cube is seen obliquely at screen
 * (x + 0.35 z) / 1.35, (y + 0.25 z) / 1.25 of the central 90 % of the
 * screen; a block's footprint is the box of its corners.  The pixel rung
 * gives every pixel depth k and polygon id p; the runs rung the same
 * rows; the counts rung the rectangle with the ellipse's area, pi/4 of
 * it (coverage only).
 * Cost: O(P) for the footprints; O(rows) a process for pixels and runs,
 * O(1) for counts.
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_FOOT_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_FOOT_H

#include "sim/workload/pixelmerge/pm_rung.h"

/* Footprint of process p of n on a width x height screen: box x0..x1,
 * y0..y1 inclusive (in rect; active unset). */
void wl_pm_foot_box(guint p, guint n, guint width, guint height, WlPmCover *r);

/* Row y of the ellipse inscribed in r: FALSE when it has no pixel there,
 * else its first and last columns. */
gboolean wl_pm_foot_span(const WlPmCover *r, guint y, guint *x0, guint *x1);

/* Process p's image at the pixel rung (an active pixel array, free with
 * wl_pm_wpa_free) ... */
WlPmWpa *wl_pm_foot_pixels(guint p, guint n, guint width, guint height);
/* ... and at the runs or counts rung (free with wl_pm_rung_image_free). */
WlPmRungImage *wl_pm_foot_image(WlPmRung rung, guint p, guint n, guint width,
                                guint height);

#endif
