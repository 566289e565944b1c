/* prerender.h — a mesh rasterised once for a view, kept per polygon.
 *
 * Polygons are rasterised independently (pipeline.h: nothing is cached
 * between them), so the spans a polygon makes for a view do not depend
 * on which other polygons are drawn with it.  A RastPrerender draws a
 * whole mesh once and keeps each polygon's spans (row and pixel range
 * only: no depth, no colour), so a workload that renders many subsets of
 * the same mesh for the same view (sort-first: each processor its region's
 * polygons, in case after case over one animation) counts what each
 * subset's render would do, inside a screen rectangle, by reading the
 * kept spans instead of transforming, clipping and scanning again.
 *
 * What a count gives equals what rast_draw_mesh() of the subset with a
 * sink clipping spans to the rectangle would count: verts, prims, spans
 * and pixels of the whole render (as the scan converter counts them),
 * and the spans and pixels inside the rectangle (each one z-compare).
 * It does not give what needs the pixels' depths or the clip decisions
 * (zwrites, winners, culled, clipped, rejected, degenerate): a workload
 * that needs the image renders for real.
 *
 * A RastPrerenderSet keeps one RastPrerender per key (a frame number),
 * built on first use, for callers that revisit the same frames.  Memory:
 * 4 B per polygon and 6 B per span of each kept view.  Building is one
 * rast_draw_mesh(); a count is O(subset + its spans).
 */
#ifndef PGSIM_RASTER_PRERENDER_H
#define PGSIM_RASTER_PRERENDER_H

#include "sim/raster/pipeline.h"

typedef struct RastPrerender RastPrerender;

/* Draws every polygon of mesh `m` (placed by the identity, ids = polygon
 * indices) for view v and keeps the spans.  Free with
 * rast_prerender_free(). */
RastPrerender *rast_prerender_new(const RastView *v, const SceneMesh *m);
void rast_prerender_free(RastPrerender *p);

/* Spans kept (over all polygons). */
guint64 rast_prerender_n_spans(const RastPrerender *p);

/* A screen rectangle: pixels x0 <= x < x1, y0 <= y < y1. */
typedef struct {
    int x0, y0, x1, y1;
} RastRect;

/* Counts, for the polygons subset[0..n) of the mesh p was made from,
 * what drawing them would: into *c verts, prims, spans, pixels and one
 * zcompare per pixel inside r; *spans and *pixels get the spans (parts
 * of spans) and pixels inside r. */
void rast_prerender_count(const RastPrerender *p, const SceneMesh *m,
                          const uint32_t *subset, guint n, RastRect r,
                          RastCounters *c, uint64_t *spans, uint64_t *pixels);

typedef struct RastPrerenderSet RastPrerenderSet;

RastPrerenderSet *rast_prerender_set_new(void);
void rast_prerender_set_free(RastPrerenderSet *s);

/* The prerender of `key` (borrowed; valid until the set is freed),
 * built from (v, m) on first use.  Every call with one key must pass the
 * same view and the same polygons (e.g. one database's flattened mesh);
 * the view and the polygon count are checked (g_assert). */
const RastPrerender *rast_prerender_set_get(RastPrerenderSet *s, guint key,
                                            const RastView *v,
                                            const SceneMesh *m);

#endif
