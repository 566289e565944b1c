/* dp_frame.h — one frame of data-parallel polygon rendering (seed 004).
 *
 * The schedule of Ortega, Hansen and Ahrens (seed 004, §4), step by step
 * over arrays, on the geometry measured by dp_geom.h:
 *
 *   transform  one virtual processor per polygon: the two vertex
 *              transforms and Gouraud vertex shading (steps 1-3);
 *   scan       for i = 0 .. tallest polygon - 1: every polygon finds the
 *              intersections of scan line i with its edges (a step over
 *              the whole polygon array: masked processors still take
 *              their turn) and sends the segment to a segment buffer
 *              with the general router;
 *   pixel      whenever the buffer would overflow, and at the end, the
 *              buffered segments are broken into pixels in a loop over
 *              the longest buffered segment: iteration j interpolates
 *              pixel j of every segment (a step over the whole buffer);
 *   router     ... and sends the live pixels with send-with-max to the
 *              processor that owns the screen location (the z-buffer);
 *   display    the z-buffer is cleared before and the image extracted
 *              after (one virtual processor per screen pixel).
 *
 * The router phase holds the segment sends of the scan loop and the
 * pixel sends of the pixel loop.  Everything is counted from the real
 * segment lengths; nothing is sampled.  O(segments + flushes * longest
 * segment) time, O(longest segment) memory.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_FRAME_H
#define PGSIM_WORKLOAD_DPSCAN_DP_FRAME_H

#include "sim/workload/dpscan/dp_cost.h"
#include "sim/workload/dpscan/dp_geom.h"

typedef enum {
    WL_DP_PH_TRANSFORM,
    WL_DP_PH_SCAN,
    WL_DP_PH_PIXEL,
    WL_DP_PH_ROUTER,
    WL_DP_PH_DISPLAY,
    WL_DP_N_PHASES
} WlDpPhase;

/* Operation counts of the algorithm's steps (per element) and the
 * number of data-parallel steps each loop body issues.  Algorithm
 * properties, not machine ones: the same on every machine. */
typedef struct {
    uint32_t transform_ops, transform_steps; /* per polygon, once */
    uint32_t scan_ops, scan_steps;           /* per polygon, per scan line */
    uint32_t pixel_ops, pixel_steps;         /* per segment, per pixel */
    uint32_t display_ops, display_steps;     /* per screen pixel, once */
    double buffer_factor;   /* buffer capacity / polygons, > 0 */
    uint32_t segment_bytes; /* a segment's end points and colours */
    uint32_t pixel_bytes;   /* z and colour packed in a double (§4) */
} WlDpAlgo;

typedef struct {
    SimTime phase[WL_DP_N_PHASES];
    SimTime total;
    WlDpCoef coef;          /* linear coefficients (SIMD calibration) */
    uint64_t scan_iters;    /* scan-line iterations (tallest polygon) */
    uint64_t flushes;       /* segment-buffer flushes */
    uint64_t pixel_iters;   /* pixel-loop iterations, all flushes */
    uint64_t segments;      /* segments sent to the buffer */
    uint64_t messages;      /* segment and pixel messages */
    uint64_t bytes;         /* their bytes */
    double util;            /* useful element steps / element slots */
} WlDpFrame;

/* Defaults documented in docs/validation.md ("ortega93"). */
WlDpAlgo wl_dp_algo_defaults(void);
const char *wl_dp_phase_name(WlDpPhase ph);

/* Schedules one frame of geometry g on machine m; fills *out. */
void wl_dp_frame_run(const WlDpGeom *g, const WlDpMachine *m,
                     const WlDpAlgo *a, WlDpFrame *out);

#endif
