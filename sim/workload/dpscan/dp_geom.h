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
 * Invariants: polygons with no pixel are dropped (they still count in
 * n_polys and in the transform phase); for every kept polygon its rows
 * are consecutive screen rows from top to bottom, and seg_len[k] is the
 * extent max(x1) - min(x0) of that row's spans; pixels is the sum of span
 * widths and equals the raster library's TPG counter.  For convex
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
    uint64_t n_polys;     /* polygons submitted (transform / shade work) */
    uint64_t n_visible;   /* polygons with at least one pixel */
    GArray *seg_start;    /* uint32_t, n_visible + 1 entries (CSR) */
    GArray *seg_len;      /* uint32_t, one per (polygon, row) */
    uint64_t pixels;      /* TPG: pixels generated */
    uint64_t covered;     /* distinct screen pixels covered */
    uint32_t max_rows;    /* scan lines of the tallest polygon */
    uint32_t max_len;     /* longest segment */
    uint32_t max_depth;   /* most pixels landing on one screen location */
    RastCounters counters;/* the raster library's own counts */
} WlDpGeom;

/* Measures the frame-`frame` view of `scene` at width x height (back
 * faces kept: the paper renders every polygon).  Returns a new geometry;
 * free with wl_dp_geom_free(). */
WlDpGeom *wl_dp_geom_new(const Scene *scene, double frame, int width,
                         int height);
void wl_dp_geom_free(WlDpGeom *g);

/* Rows (segments) of visible polygon p. */
static inline uint32_t wl_dp_geom_rows(const WlDpGeom *g, uint64_t p)
{
    return g_array_index(g->seg_start, uint32_t, p + 1) -
           g_array_index(g->seg_start, uint32_t, p);
}
/* Length of row r (0 = top) of visible polygon p. */
static inline uint32_t wl_dp_geom_len(const WlDpGeom *g, uint64_t p,
                                      uint32_t r)
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
