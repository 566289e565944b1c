/* dp_poly.h — screen-space polygons and the pixel rule of seed 004's
 * renderer, shared by the data-parallel renderer (dp_render.h) and the
 * serial reference (dp_serial.h).
 *
 * Steps 1-3 of seed 004 §4 (transform, world to screen, vertex shading)
 * are per-vertex arithmetic; wl_dp_polys_new() does it once for a frame
 * and keeps, per polygon, its screen vertices (x, y in pixels, z the
 * depth in [0, 1], 0 at the near plane) and one value per vertex: the
 * shade (flat: the polygon's, Gouraud: the vertex's), or the contour
 * value of the vertex data.  Lighting is the paper's: "parallel white
 * rays normal to the window", shade = |n . view direction|.  A polygon
 * with a vertex behind the eye is dropped (n_ok counts the others):
 * clipping is against the viewport only, after scan conversion (§4).
 *
 * The pixel rule (what both renderers must agree on):
 *   - a polygon is scan converted on every row it touches, from
 *     floor(ymin) to floor(ymax) (seed 004: each polygon is processed on
 *     its scan lines, "there must be at least two intersections"); row
 *     y is sampled on the line y + 0.5, moved just inside the polygon's
 *     extent in its first and last row, so even a polygon smaller than
 *     a pixel has its two crossings; an edge (a, b) crosses the line iff
 *     min(ya, yb) <= line < max(ya, yb) (half-open: a vertex on the line
 *     counts once);
 *   - the crossings are sorted by x and paired first-second,
 *     third-fourth ... (the even-odd rule, Foley et al. §3.6): any
 *     polygon, convex or not, self-overlapping or not;
 *   - a pair (xl, xr) covers pixels floor(xl) .. floor(xr), both ends
 *     included (so every pair gives a pixel); z and value are linear
 *     along the pair, sampled at pixel centres and clamped to it.
 *     ASSUMPTION: the paper prints no rounding rule; inclusive ends are
 *     what an integer loop over each segment's end pixels visits;
 *   - lines (wireframe, edges, points): pixel k of an edge is the
 *     rounded point k / n of the way, n = the larger pixel extent.
 *
 * The z-buffer key packs, high to low, the depth (32 bits, nearer is
 * larger), the polygon id (24 bits) and the colour index (8 bits), so
 * the send-with-max combiner keeps the nearest pixel, and ties resolve
 * the same way in any order (the paper packs z and colour into one
 * double; the id is our addition for order independence and the
 * hidden-line pass).  Key 0 is an empty pixel.
 *
 * Complexity: O(vertices) to build; O(k log k)... O(k^2) per polygon
 * scan line (insertion sort of k crossings); O(1) per pixel.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_POLY_H
#define PGSIM_WORKLOAD_DPSCAN_DP_POLY_H

#include "sim/scene/scene.h"
#include <stdint.h>

/* The rendering modes of the paper's library (§5). */
typedef enum {
    WL_DP_MODE_FLAT,
    WL_DP_MODE_GOURAUD,
    WL_DP_MODE_WIREFRAME,
    WL_DP_MODE_HIDDEN_LINE,
    WL_DP_MODE_CONTOUR,
    WL_DP_MODE_POINTS,
    WL_DP_MODE_LINES,
    WL_DP_N_MODES
} WlDpMode;

#define WL_DP_COLORS 15   /* colours of the table (§5) */
#define WL_DP_SHADES 15   /* shades of each colour */
#define WL_DP_TABLE_BASE 30 /* first index of the shaded colours */
#define WL_DP_MAX_VERTS 64  /* most vertices of one polygon */

typedef struct {
    uint64_t n;       /* polygons */
    uint64_t n_ok;    /* polygons in front of the eye */
    uint32_t kmax;    /* most vertices of one polygon (array padding) */
    uint32_t *start;  /* n + 1 entries, CSR into the vertex arrays */
    double *x, *y, *z, *val;
    uint8_t *color;   /* palette colour 0..14 of each polygon */
    uint8_t *ok;      /* 1: every vertex in front of the eye */
    uint64_t n_verts;
    WlDpMode mode;
} WlDpPolys;

/* One pair of crossings on one scan line of one polygon. */
typedef struct {
    double xl, xr, zl, zr, vl, vr;
    int32_t y, x0;   /* row; first covered pixel */
    uint32_t len;    /* covered pixels (>= 1) */
    uint32_t poly;
} WlDpSpan;

const char *wl_dp_mode_name(WlDpMode m);
/* The mode called `name`; FALSE if unknown. */
gboolean wl_dp_mode_parse(const char *name, WlDpMode *out);
/* TRUE for the modes drawn by scan conversion (not lines or points). */
gboolean wl_dp_mode_fills(WlDpMode m);

/* Transforms and shades frame `frame` of `scene` at width x height;
 * polygon colours map to the nearest of the 15 palette colours.
 * Returns new polygons; free with wl_dp_polys_free(). */
WlDpPolys *wl_dp_polys_new(const Scene *scene, double frame, int width,
                           int height, WlDpMode mode, const float pal[][3]);
void wl_dp_polys_free(WlDpPolys *p);
static inline uint32_t wl_dp_poly_len(const WlDpPolys *p, uint64_t i)
{
    return p->start[i + 1] - p->start[i];
}

/* Scan lines of polygon i: *y0 the first row, returns the count (0 for
 * a polygon that covers no row centre or is not ok). */
uint32_t wl_dp_poly_rows(const WlDpPolys *p, uint64_t i, int32_t *y0);
/* The covered pairs of polygon i on row y, left to right, into out
 * (room for WL_DP_MAX_VERTS / 2); returns how many. */
guint wl_dp_poly_spans(const WlDpPolys *p, uint64_t i, int32_t y,
                       WlDpSpan *out);
/* Key of pixel j of span s (x = s->x0 + j). */
uint64_t wl_dp_span_key(const WlDpPolys *p, const WlDpSpan *s, uint32_t j);

/* Pixels of edge e (from vertex e to e + 1) of polygon i. */
uint32_t wl_dp_edge_pixels(const WlDpPolys *p, uint64_t i, uint32_t e);
/* Pixel k of that edge: its position and key. */
void wl_dp_edge_pixel(const WlDpPolys *p, uint64_t i, uint32_t e, uint32_t k,
                      int64_t *x, int64_t *y, uint64_t *key);
/* Vertex v of polygon i as a point: position and key. */
void wl_dp_point_pixel(const WlDpPolys *p, uint64_t i, uint32_t v, int64_t *x,
                       int64_t *y, uint64_t *key);

/* Key layout. */
uint64_t wl_dp_key(double z, uint32_t id, uint8_t index);
static inline uint8_t wl_dp_key_index(uint64_t key)
{
    return (uint8_t)(key & 0xff);
}
static inline uint32_t wl_dp_key_id(uint64_t key)
{
    return (uint32_t)((key >> 8) & 0xffffff);
}
/* Hidden-line rule: a drawn pixel whose neighbour (north, south, east,
 * west; 0 off the grid) shows another polygon or nothing is an edge
 * pixel and keeps its colour; every other pixel is background (0). */
static inline uint8_t wl_dp_edge_index(uint64_t self, const uint64_t nb[4])
{
    if (self == 0)
        return 0;
    for (int k = 0; k < 4; k++)
        if (nb[k] == 0 || wl_dp_key_id(nb[k]) != wl_dp_key_id(self))
            return wl_dp_key_index(self);
    return 0;
}
/* Colour index of a shaded colour: WL_DP_TABLE_BASE + 15 c + s. */
uint8_t wl_dp_color_index(uint8_t color, double shade);
/* Index of an unshaded contour band of value v in [0, 1]. */
uint8_t wl_dp_contour_index(double v);

#endif
