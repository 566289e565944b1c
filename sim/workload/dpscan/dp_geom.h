/* dp_geom.h — the screen-space work of a data-parallel frame (seed 004).
 *
 * Ortega, Hansen and Ahrens' renderer (seed 004, §4) scan converts all
 * polygons at once: iteration i handles scan line i of every polygon
 * that has one, and each scan line becomes one segment whose pixels are
 * then generated in a loop over the longest segment.  Its cost therefore
 * depends on, per polygon, the number of scan lines and the length of
 * each scan-line segment; and the router's combining work on how many
 * pixels land on the same screen location.  WlDpGeom holds exactly that,
 * measured on real geometry: the scene is transformed, clipped and scan
 * converted by sim/raster (rast_draw_scene), whose spans are merged per
 * (polygon, row) into one segment.
 *
 * Positions (seg_x0, poly_y0) say where each segment's pixels land on
 * the screen, so the router's receive side (how many pixels one
 * processor's part of the z-buffer gets in one send) is measured, not
 * assumed.
 *
 * End points: sim/raster samples pixel centres (a span [x0, x1) holds
 * the pixels whose centre is inside), so a polygon smaller than a pixel
 * may produce nothing.  Seed 004's scan converter works the other way
 * round: it intersects each scan line with the polygon's sides ("there
 * must be at least two intersections") and fills from one intersection
 * to the other, end points included.  With `inclusive` a segment covers
 * x0 .. x1 inclusive (one more pixel) and a polygon one more scan line
 * (its last row repeated), which is what an integer loop from the first
 * to the last scan line and pixel of each polygon visits.  ASSUMPTION:
 * the paper does not print its rounding rule; docs/validation.md
 * ("ortega93") shows what it changes.
 *
 * Invariants: polygons with no pixel are dropped (they still count in
 * n_polys and in the transform phase); for every kept polygon its rows
 * are consecutive screen rows from top to bottom, and seg_len[k] is the
 * extent max(x1) - min(x0) of that row's spans (+1 if inclusive);
 * pixels is the sum of span widths and equals the raster library's TPG
 * counter; seg_pixels is the sum of seg_len.  For convex
 * polygons (all the generators make) extent and pixel sum agree.
 *
 * Complexity: O(spans) time plus O(width * height) for the coverage
 * counts; memory O(segments + width * height / 2^16 ...) — one 16-bit
 * coverage counter per pixel during the build only.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_GEOM_H
#define PGSIM_WORKLOAD_DPSCAN_DP_GEOM_H

#include "sim/raster/pipeline.h"
#include "sim/scene/scene.h"

typedef struct {
    int width, height;
    uint64_t n_polys;      /* polygons submitted (transform / shade work) */
    uint64_t n_visible;    /* polygons with at least one pixel */
    GArray *seg_start;     /* uint32_t, n_visible + 1 entries (CSR) */
    GArray *seg_len;       /* uint32_t, one per (polygon, row) */
    GArray *seg_x0;        /* uint32_t, left end of each segment (screen x) */
    GArray *poly_y0;       /* uint32_t, top row of each visible polygon */
    uint64_t pixels;       /* TPG: pixels the raster library generated */
    uint64_t seg_pixels;   /* sum of segment lengths (what dpscan sends) */
    unsigned inclusive;    /* 1: end points inclusive (see above) */
    uint64_t covered;      /* distinct screen pixels covered */
    uint32_t max_rows;     /* scan lines of the tallest polygon */
    uint32_t max_len;      /* longest segment */
    uint32_t max_depth;    /* most pixels landing on one screen location */
    RastCounters counters; /* the raster library's own counts */
} WlDpGeom;

/* Measures the frame-`frame` view of `scene` at width x height (back
 * faces kept: the paper renders every polygon), end points inclusive or
 * not (above).  Returns a new geometry; free with wl_dp_geom_free(). */
WlDpGeom *wl_dp_geom_new(const Scene *scene, double frame, int width,
                         int height, gboolean inclusive);
void wl_dp_geom_free(WlDpGeom *g);

/* Rows (segments) of visible polygon p. */
static inline uint32_t wl_dp_geom_rows(const WlDpGeom *g, uint64_t p)
{
    return g_array_index(g->seg_start, uint32_t, p + 1) -
           g_array_index(g->seg_start, uint32_t, p);
}
/* Length of row r (0 = top) of visible polygon p. */
static inline uint32_t wl_dp_geom_x0(const WlDpGeom *g, uint64_t p, uint32_t r)
{
    return g_array_index(g->seg_x0, uint32_t,
                         g_array_index(g->seg_start, uint32_t, p) + r);
}
static inline uint32_t wl_dp_geom_y0(const WlDpGeom *g, uint64_t p)
{
    return g_array_index(g->poly_y0, uint32_t, p);
}
static inline uint32_t wl_dp_geom_len(const WlDpGeom *g, uint64_t p, uint32_t r)
{
    return g_array_index(g->seg_len, uint32_t,
                         g_array_index(g->seg_start, uint32_t, p) + r);
}
/* Collisions: pixels that meet an earlier pixel at the same location. */
static inline uint64_t wl_dp_geom_collisions(const WlDpGeom *g)
{
    return g->pixels - g->covered;
}

#endif
