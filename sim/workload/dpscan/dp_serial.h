/* dp_serial.h — the serial reference renderer of seed 004's pixel rule.
 *
 * One polygon at a time, one scan line at a time, one pixel at a time,
 * each pixel's key kept if it beats the z-buffer's: the textbook
 * scan-line z-buffer with the same pixel rule and key as the data-parallel
 * renderer (dp_poly.h), so the two images must be equal whatever the
 * order the data-parallel one sends pixels in.  No costs.  O(pixels +
 * polygons x rows x k^2) time, O(screen) memory.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_SERIAL_H
#define PGSIM_WORKLOAD_DPSCAN_DP_SERIAL_H

#include "sim/workload/dpscan/dp_render.h"

/* Renders p (every mode) into a new image; free with
 * wl_dp_image_free(). */
WlDpImage *wl_dp_serial_render(const WlDpPolys *p, int width, int height);

#endif
