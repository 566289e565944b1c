/* clip.h — clip-space vertices and homogeneous polygon clipping.
 *
 * A RastVert is a vertex after the model-view-projection transform: a
 * homogeneous position (OpenGL conventions: visible when -w <= x, y, z
 * <= w) and a colour.  rast_clip_polygon() clips a convex polygon against
 * the near plane (z >= -w), the far plane (z <= w), a positive-w plane
 * (w >= RAST_CLIP_WMIN, so nothing is ever divided by w <= 0) and a
 * guard band |x|, |y| <= g w that keeps screen coordinates small enough
 * for exact fixed-point scan conversion (scan.h).  Because the guard band
 * lies outside the viewport, its cuts never show; near and far cuts do.
 *
 * Watertightness: an edge shared by two polygons is cut at bit-identical
 * points in both, because the intersection is always computed from the
 * lexicographically smaller endpoint towards the larger one, whatever the
 * direction in which the polygon traverses the edge.
 *
 * Sutherland and Hodgman, "Reentrant polygon clipping", CACM 17(1), 1974;
 * Blinn and Newell, "Clipping using homogeneous coordinates", SIGGRAPH
 * 1978.  O(n) per plane for an n-vertex polygon.
 */
#ifndef PGSIM_RASTER_CLIP_H
#define PGSIM_RASTER_CLIP_H

#include "sim/scene/vec.h"
#include <glib.h>

typedef struct {
    float r, g, b; /* linear, nominally in [0, 1] */
} RastColor;

typedef struct {
    Vec4 pos; /* clip space */
    RastColor col;
} RastVert;

/* Seven planes, each adding at most one vertex to a convex polygon: a
 * triangle ends with at most 10 vertices. */
#define RAST_CLIP_MAX 16
/* Smallest w kept: points with w below it are behind (or at) the eye. */
#define RAST_CLIP_WMIN 1e-9

/* Outcode bits, one per plane. */
enum {
    RAST_OUT_NEAR = 1,
    RAST_OUT_FAR = 2,
    RAST_OUT_W = 4,
    RAST_OUT_LEFT = 8,
    RAST_OUT_RIGHT = 16,
    RAST_OUT_BOTTOM = 32,
    RAST_OUT_TOP = 64
};

/* The planes a clip-space point lies outside of (0: inside all). */
unsigned rast_clip_outcode(Vec4 p, double guard);

/* Clips the convex polygon in[0..n-1] (3 <= n <= RAST_CLIP_MAX - 7;
 * n == 3 is the usual case) and writes the result to out,
 * which must hold RAST_CLIP_MAX vertices.  `guard` (>= 1) is the guard
 * band factor g.  Returns the number of output vertices: 0 when nothing
 * is left, otherwise >= 3.  Vertex order (winding) is preserved. */
int rast_clip_polygon(const RastVert *in, int n, double guard, RastVert *out);

#endif
