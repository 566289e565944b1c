/* zbuffer.h — the full z-buffer.
 *
 * A width x height array of (depth, primitive id, colour).  Spans are
 * resolved pixel by pixel with rast_depth_wins() (smaller depth wins,
 * equal depth: smaller primitive id), so the final image does not depend
 * on the order of the spans when primitive ids are distinct.  Clearing
 * touches every pixel (O(W H)), which is what the modified scanline
 * z-buffer (scanzbuf.h) avoids.  Each pixel of a span costs one depth
 * comparison.  Catmull (1974), Straßer (1974).
 *
 * For full z-buffer merging a workload reads the arrays directly: depth
 * (+inf when empty), prim (RAST_NO_PRIM when empty) and rgba.
 */
#ifndef PGSIM_RASTER_ZBUFFER_H
#define PGSIM_RASTER_ZBUFFER_H

#include "sim/raster/spanlist.h"

typedef struct {
    int width, height;
    double *depth;  /* row-major, +inf when empty */
    uint32_t *prim; /* RAST_NO_PRIM when empty */
    uint32_t *rgba; /* 0xAABBGGRR; 0 when empty */
} RastZBuffer;

/* Returns a new cleared z-buffer; free with rast_zbuffer_free(). */
RastZBuffer *rast_zbuffer_new(int width, int height);
void rast_zbuffer_free(RastZBuffer *zb);
void rast_zbuffer_clear(RastZBuffer *zb);

/* Z-buffers one span: counts z-comparisons and writes in *c. */
void rast_zbuffer_span(RastZBuffer *zb, const RastSpan *s, RastCounters *c);
/* The same for the span's pixels x0 <= x < x1 only (a region's part of
 * it: sort-first), with the same formulas, so the pixels are the same. */
void rast_zbuffer_span_part(RastZBuffer *zb, const RastSpan *s, int x0,
                            int x1, RastCounters *c);
/* A sink that z-buffers spans as they are generated (immediate mode). */
RastSpanSink rast_zbuffer_sink(RastZBuffer *zb);
/* Z-buffers every span of a sorted list, row by row. */
void rast_zbuffer_spans(RastZBuffer *zb, const RastSpanList *sl,
                        RastCounters *c);

/* Number of covered pixels (the TPF of the picture). */
uint64_t rast_zbuffer_covered(const RastZBuffer *zb);

/* Merges `src` into `dst` pixel by pixel with the depth-tie rule (full
 * z-buffer merging); counts one comparison per pixel where src is
 * covered.  Both must have the same size. */
void rast_zbuffer_merge(RastZBuffer *dst, const RastZBuffer *src,
                        RastCounters *c);

#endif
