/* scan.h — viewport mapping, triangle set-up and scan conversion.
 *
 * Screen space has its origin at the top-left corner of the image, y
 * pointing down; pixel (x, y) has its centre at (x + 0.5, y + 0.5).
 * Vertex positions are snapped to fixed point with RAST_SUBPIX_BITS
 * fractional bits; coverage is decided exactly in 64-bit integers, so
 * two triangles sharing an edge never both cover, nor both miss, a pixel
 * centre on it (watertight, no double cover).
 *
 * Fill rule (top-left, as Direct3D and OpenGL implementations use): a
 * pixel centre strictly inside a triangle is covered; one exactly on an
 * edge is covered only if that edge is a top edge (horizontal, interior
 * below it) or a left edge (interior to its right).
 *
 * A triangle becomes at most one span per row: pixels x0 <= x < x1 on
 * row y, with depth and colour as affine functions of x (plane equations
 * evaluated at the pixel centre; depth is clamped to the triangle's
 * vertex range so slivers cannot extrapolate).  Gouraud shading is
 * screen-linear, as in Gouraud (1971); flat shading is the special case
 * of equal vertex colours.
 *
 * Depth-tie rule: the smaller depth wins; on equal depth the smaller
 * primitive id wins (rast_depth_wins).  With distinct ids the winner at
 * every pixel is therefore independent of drawing order.
 *
 * Pineda, "A parallel algorithm for polygon rasterization", SIGGRAPH
 * 1988 (edge functions).  Cost: O(rows) set-up divisions plus O(1) per
 * emitted span; pixels are not touched here.
 */
#ifndef PGSIM_RASTER_SCAN_H
#define PGSIM_RASTER_SCAN_H

#include "sim/raster/clip.h"
#include "sim/raster/counters.h"
#include <stdint.h>

#define RAST_SUBPIX_BITS 8
#define RAST_SUBPIX (1 << RAST_SUBPIX_BITS)
/* Largest image side: keeps guard-band coordinates within 2^17 pixels,
 * so every edge-function product fits in int64. */
#define RAST_MAX_SIDE 16384
/* Primitive id of an empty pixel. */
#define RAST_NO_PRIM UINT32_MAX

typedef struct {
    int64_t x, y; /* fixed point, RAST_SUBPIX_BITS fractional bits */
    double z;     /* depth in [0, 1]: 0 at the near plane */
    RastColor col;
} RastScreenVert;

typedef struct {
    int32_t y, x0, x1; /* pixels x0 <= x < x1 on row y */
    uint32_t prim;
    double z0, dzdx; /* depth at pixel x0 and its change per pixel */
    double zlo, zhi; /* depth clamp range */
    float c0[3], dcdx[3];
} RastSpan;

/* Where spans go: a span list (spanlist.h), a full z-buffer (zbuffer.h)
 * or a test's own collector. */
typedef void (*RastSpanFn)(void *ctx, const RastSpan *s, RastCounters *c);
typedef struct {
    RastSpanFn fn;
    void *ctx;
} RastSpanSink;

/* The guard band factor g (clip.h) for a width x height viewport. */
double rast_guard_band(int width, int height);

/* Maps a clipped vertex (w >= RAST_CLIP_WMIN, inside the guard band) to
 * screen space and snaps it to fixed point. */
RastScreenVert rast_viewport(const RastVert *v, int width, int height);

/* Twice the signed area in 1/RAST_SUBPIX^2 pixel units; exact.  Positive
 * when the triangle is counter-clockwise in normalised device coordinates
 * (y up), i.e. front facing under the OpenGL convention. */
int64_t rast_area2(const RastScreenVert *a, const RastScreenVert *b,
                   const RastScreenVert *c);

/* Scan converts one front-or-back facing triangle with non-zero area
 * into spans clipped to the width x height image, sends each to `sink`
 * and counts spans and pixels (TPG) in *c.  Returns the span count. */
uint64_t rast_scan_triangle(const RastScreenVert v[3], uint32_t prim, int width,
                            int height, RastSpanSink sink, RastCounters *c);

/* Depth of span pixel x (x0 <= x < x1). */
static inline double rast_span_z(const RastSpan *s, int x)
{
    double z = s->z0 + s->dzdx * (double)(x - s->x0);
    return z < s->zlo ? s->zlo : (z > s->zhi ? s->zhi : z);
}

static inline uint32_t rast_channel(float v)
{
    /* !(v > 0) also maps NaN to 0: no undefined float-to-int cast */
    return !(v > 0.0f) ? 0u
                       : (v >= 1.0f ? 255u : (uint32_t)(v * 255.0f + 0.5f));
}

/* Colour of span pixel x packed as 0xAABBGGRR (opaque). */
static inline uint32_t rast_span_rgba(const RastSpan *s, int x)
{
    float t = (float)(x - s->x0);
    return rast_channel(s->c0[0] + s->dcdx[0] * t) |
           rast_channel(s->c0[1] + s->dcdx[1] * t) << 8 |
           rast_channel(s->c0[2] + s->dcdx[2] * t) << 16 | 0xff000000u;
}

/* TRUE when fragment (z, prim) beats the stored (zold, primold). */
static inline gboolean rast_depth_wins(double z, uint32_t prim, double zold,
                                       uint32_t primold)
{
    return z < zold || (z == zold && prim < primold);
}

#endif
