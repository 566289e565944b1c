/* pm_render.h — the local rendering phases of object-space parallel
 * rendering (seed 003 §2): each processor turns its share of the polygons
 * into scanline span lists and runs the modified scanline z-buffer on
 * them (real pixels, sim/raster), yielding its local foremost pixels and
 * the counted operations that the cost model turns into time.
 *
 * Polygon partition: "cyclic" gives polygon i to processor i mod P
 * (every processor draws a sample of the whole scene), "block" gives
 * processor p the p-th run of consecutive polygons.  The paper says only
 * that polygons are partitioned among processors (§1).
 *
 * insert_steps estimates the comparisons of building the span lists by
 * sorted insertion into linked lists (§2): a row that receives s spans in
 * arbitrary order costs s (s - 1) / 4 steps on average.  The raster
 * library sorts once instead; the count models the paper's method.
 * Cost: O(polygons + spans + pixels + N) per processor.
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_RENDER_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_RENDER_H

#include "sim/raster/pipeline.h"
#include "sim/workload/pixelmerge/pm_pixels.h"

typedef enum { WL_PM_SPLIT_CYCLIC, WL_PM_SPLIT_BLOCK } WlPmSplit;

/* NULL-terminated names indexed by WlPmSplit: "cyclic", "block". */
extern const char *const wl_pm_split_names[];

typedef struct {
    uint64_t polygons;     /* polygons assigned */
    RastCounters rc;       /* raster work: prims, verts, spans, pixels ... */
    uint64_t insert_steps; /* sorted-insertion steps (see above) */
    uint64_t span_rows;    /* scanlines with at least one span */
} WlPmCounts;

/* Renders processor p's share (of n) of `flat` (a world-space mesh from
 * scene_flatten(), polygon i has primitive id i) with view v; returns its
 * active pixels (free with wl_pm_wpa_free()) and fills *c. */
WlPmWpa *wl_pm_render_local(const RastView *v, const SceneMesh *flat, guint p,
                            guint n, WlPmSplit split, WlPmCounts *c);

/* The same for the polygons ids[k] of `flat` (any subset, e.g. a
 * block's, pm_images.h). */
WlPmWpa *wl_pm_render_ids(const RastView *v, const SceneMesh *flat,
                          const uint32_t *ids, guint k, WlPmCounts *c);

#endif
