/* dp_render.h — seed 004's data-parallel renderer on the array layer.
 *
 * Ortega, Hansen and Ahrens §4, executed on real geometry (dp_poly.h)
 * with every operation a dp_array.h operation, so the frame time of each
 * target is the sum of the work counted:
 *
 *   1-3  transform, world to screen, vertex shading: elementwise over the
 *        polygon array (kmax vertices per polygon, padded);
 *   4    scan conversion: a loop over the tallest polygon's scan lines;
 *        in iteration i every polygon (finished ones masked off) crosses
 *        its row i with its edges, sorts the crossings in x and pairs
 *        them by the even-odd rule; an enumerate (add-scan) gives each
 *        pair a slot and the router sends the pairs' end points and
 *        colours (7 words) into the segment buffer; the buffer is
 *        flushed into pixels when the next scan line would overflow it,
 *        and at the end;
 *        pixel loop (a flush): a global max gives the longest buffered
 *        segment; iteration j interpolates pixel j of every buffered
 *        segment (shorter ones masked);
 *   5    pixels outside the viewport are masked off (clipping after scan
 *        conversion);
 *   6    send-with-max of the packed z+id+colour key (2 words) into the
 *        z-buffer array (one element per screen pixel); the image is
 *        extracted from the z-buffer at the end.
 *
 * The other modes of §5: wireframe and z-buffered lines (a loop over
 * the longest edge, pixel k of every edge sent with max), points (one
 * send of every vertex), hidden-line wireframe (a filled pass, then four
 * NEWS moves find the pixels whose neighbour shows another polygon or
 * nothing), contour (the fill with the contour colour of the vertex
 * value).  The image equals the serial renderer's (dp_serial.h).
 *
 * Operation counts per element (WlDpOps) are assumptions stated in
 * docs/validation.md ("ortega93").  Complexity: O(polygons log polygons +
 * scan lines x active polygons + pixels x targets); memory O(polygons +
 * buffer + screen).
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_RENDER_H
#define PGSIM_WORKLOAD_DPSCAN_DP_RENDER_H

#include "sim/workload/dpscan/dp_array.h"
#include "sim/workload/dpscan/dp_poly.h"

/* Operations per element of each statement (32-bit operations). */
typedef struct {
    uint32_t transform; /* per vertex: 4x4 point transform, divide, viewport */
    uint32_t shade;     /* per vertex (Gouraud) or polygon (flat) */
    uint32_t cross;     /* per edge and scan line: test and interpolate */
    uint32_t swap;      /* per compare-exchange of the crossing sort */
    uint32_t pair;      /* per pair of crossings */
    uint32_t pixel;     /* per buffered segment and pixel iteration */
    uint32_t line;      /* per edge and line pixel */
    uint32_t clear;     /* per screen pixel */
    uint32_t extract;   /* per screen pixel */
    uint32_t edge;      /* per screen pixel, hidden-line test */
} WlDpOps;

WlDpOps wl_dp_ops_defaults(void);

typedef struct {
    WlDpMode mode;
    double buffer_factor; /* segment buffer slots / polygons, > 0 */
    WlDpOps ops;
} WlDpRenderOpts;

typedef struct {
    int width, height;
    uint64_t *zbuf;  /* width * height keys; 0 = empty */
    uint8_t *index;  /* extracted image: colour-table indices */
    uint64_t scan_iters, flushes, pixel_iters, segments;
    uint64_t pixels;  /* pixel messages into the z-buffer */
    uint64_t clipped; /* pixels masked off outside the viewport */
    uint32_t max_rows, max_len;
} WlDpImage;

/* Renders p on vm (whose screen must be p's width x height); returns
 * the image; free with wl_dp_image_free(). */
WlDpImage *wl_dp_render(WlDpVm *vm, const WlDpPolys *p, int width, int height,
                        const WlDpRenderOpts *o);
WlDpImage *wl_dp_image_new(int width, int height);
void wl_dp_image_free(WlDpImage *img);
/* The image array from the z-buffer (§5's utility): the key's colour
 * index, 0 (background) where empty. */
void wl_dp_image_extract(WlDpImage *img);

#endif
