/* dp_sched.h — the data-parallel steps of one frame, one at a time.
 *
 * Ortega, Hansen and Ahrens' renderer (seed 004, §4) as the sequence of
 * data-parallel operations a CM Fortran program issues, on the geometry
 * measured by dp_geom.h.  Each call of wl_dp_sched_next() yields the next
 * operation; executors (dp_frame.h: closed form; dp_exec.h: engine events
 * on a machine) cost it.  The steps, in the paper's words:
 *
 *   clear      the z-buffer (one element per screen pixel, a double);
 *   transform  "the vertex data for all the polygons is transformed
 *              simultaneously", then Gouraud vertex shading (steps 1-3);
 *   scan loop  "iterates over the maximum number of scan lines through
 *              any polygon": every polygon (active or masked) finds the
 *              intersections of scan line i with its sides, sorts them
 *              in x and pairs them (even-odd rule); an enumerate (scan)
 *              gives each new segment its slot in the buffer and the
 *              segment's end points and colours are sent there "with
 *              generalized router communication", one array per send;
 *   pixel loop when the buffer would overflow, and at the end: a global
 *              maximum gives the longest buffered segment; iteration j
 *              interpolates pixel j of every buffered segment (a step
 *              over the whole buffer) and sends it with send-with-max
 *              into the z-buffer ("combining the z values and the color
 *              value into a double precision array": two words);
 *   extract    the image array is extracted from the z-buffer.
 *
 * A SEND step carries its message count; for z-buffer sends the live
 * pixels themselves are available (wl_dp_sched_pixel_at) so an executor
 * can count what each processor receives.  Everything is counted from
 * the real segments; nothing is sampled.
 *
 * Complexity: O(V log V) to order polygons by height (V visible), O(1)
 * amortised per step, O(segments) per flush (counting sort by length);
 * memory O(V + buffer capacity).
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_SCHED_H
#define PGSIM_WORKLOAD_DPSCAN_DP_SCHED_H

#include "sim/workload/dpscan/dp_geom.h"

typedef enum {
    WL_DP_PH_TRANSFORM,
    WL_DP_PH_SCAN,
    WL_DP_PH_PIXEL,
    WL_DP_PH_ROUTER,
    WL_DP_PH_DISPLAY,
    WL_DP_N_PHASES
} WlDpPhase;

typedef enum { WL_DP_COMPUTE, WL_DP_SCAN, WL_DP_SEND } WlDpKind;

/* Operation counts per element and words per message.  Algorithm
 * properties (the same on every machine); defaults are assumptions
 * documented in docs/validation.md ("ortega93"). */
typedef struct {
    uint32_t clear_ops;                      /* per screen pixel */
    uint32_t transform_ops, transform_steps; /* per polygon, once */
    uint32_t scan_ops, scan_steps;           /* per polygon, per scan line */
    uint32_t scan_scans;                     /* enumerates per scan line */
    uint32_t pixel_ops, pixel_steps;         /* per buffer slot, per pixel */
    uint32_t extract_ops;                    /* per screen pixel */
    uint32_t segment_words; /* arrays sent per segment (32-bit words) */
    uint32_t pixel_words;   /* z and colour packed in a double: 2 */
    double buffer_factor;   /* buffer capacity / polygons, > 0 */
} WlDpAlgo;

typedef struct {
    WlDpKind kind;
    WlDpPhase phase;
    uint64_t n;      /* elements of the array the step runs over */
    uint32_t ops;    /* COMPUTE: operations per element */
    uint32_t words;  /* SEND: arrays sent, one 32-bit word each */
    uint64_t active; /* SEND: messages per array */
    gboolean zbuf;   /* SEND: into the z-buffer (pixels available) */
} WlDpStep;

typedef struct {
    uint64_t scan_iters, flushes, pixel_iters, segments;
    uint64_t messages; /* segment and pixel messages (per array) */
    uint64_t words;    /* 32-bit words sent */
} WlDpCounts;

typedef struct WlDpSched WlDpSched;

WlDpAlgo wl_dp_algo_defaults(void);
const char *wl_dp_phase_name(WlDpPhase ph);

/* A new schedule over g (borrowed, must outlive it); free with
 * wl_dp_sched_free(). */
WlDpSched *wl_dp_sched_new(const WlDpGeom *g, const WlDpAlgo *a);
void wl_dp_sched_free(WlDpSched *s);
/* The next step into *out; FALSE when the frame is done. */
gboolean wl_dp_sched_next(WlDpSched *s, WlDpStep *out);
const WlDpCounts *wl_dp_sched_counts(const WlDpSched *s);
const WlDpGeom *wl_dp_sched_geom(const WlDpSched *s);

/* A buffered segment: its left end, row, length and buffer slot. */
typedef struct {
    uint32_t x0, y, len;
    uint32_t slot;
    uint32_t poly; /* visible polygon it came from */
} WlDpSeg;

/* During a z-buffer SEND: the live segments (step.active of them; live
 * pixel k lands at (segs[k].x0 + *j, segs[k].y) and comes from buffer
 * slot segs[k].slot).  Borrowed until the next step. */
const WlDpSeg *wl_dp_sched_live(const WlDpSched *s, uint32_t *j);
/* After a segment SEND (zbuf FALSE): the segments it sent (step.active
 * of them), in buffer-slot order.  Borrowed until the next step. */
const WlDpSeg *wl_dp_sched_sent(const WlDpSched *s);

#endif
