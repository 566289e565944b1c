/* sf_regions.h — screen regions and the bucket sort of bounding boxes
 * (seed 000 §1.2, §3.3.2.1, §4.1).
 *
 * Sort-first gives each processor one region of the screen.  The regions
 * here are a static grid of rows x cols = P rectangles (cols the divisor
 * of P nearest sqrt(P) from above, so 4 = 2x2, 8 = 2x4, 12 = 3x4,
 * 20 = 4x5), processor p owning region p in row-major order; pixel
 * columns are split as x0 = col W / cols (integers), rows likewise.
 * Adaptive regions (seed 000 §1.2, [12]) overwrite `rect` each frame
 * (sf_adapt.h); everything below reads the regions through `rect`.
 *
 * The bucket sort (§4.1): "these bounding boxes are transformed into
 * screen space, and their bounding rectangles are computed.  These data
 * are used to perform both view-frustum culling and bucket-sorting of
 * the primitive chunks."  A box is transformed by its 8 corners into
 * clip space; it is culled when all corners lie outside one clip plane;
 * when a corner lies at or behind the eye (w <= 0) its rectangle is the
 * whole screen; otherwise the rectangle of the projected corners, grown
 * by one pixel (fixed-point snapping and rounding), is tested against
 * each region's pixel centres.  The result is a bit mask of regions
 * (P <= 64), conservative: every region holding a pixel that a primitive
 * in the box covers is in it.  Cost O(P) per box.
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_REGIONS_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_REGIONS_H

#include "sim/scene/mesh.h"
#include <stdint.h>

#define WL_SF_MAX_PROCS 64

typedef struct {
    int x0, y0, x1, y1; /* pixels x0 <= x < x1, y0 <= y < y1 */
} WlSfRect;

typedef struct {
    guint procs, rows, cols;
    int width, height;
    WlSfRect rect[WL_SF_MAX_PROCS]; /* region p; they tile the screen */
} WlSfRegions;

/* procs in 1 .. WL_SF_MAX_PROCS; width, height >= procs' grid. */
void wl_sf_regions_init(WlSfRegions *r, guint procs, int width, int height);
WlSfRect wl_sf_region_rect(const WlSfRegions *r, guint p);
/* The box's screen rectangle in pixels (y down, not clamped; the whole
 * plane when a corner is at or behind the eye); FALSE when culled. */
gboolean wl_sf_box_screen(const WlSfRegions *r, SceneBox box,
                          Mat4 clip_from_obj, double *x0, double *y0,
                          double *x1, double *y1);
/* The regions the box (object coordinates) overlaps under clip_from_obj
 * (view-projection x model), as a mask of bits 1 << p; 0 when culled. */
uint64_t wl_sf_box_regions(const WlSfRegions *r, SceneBox box,
                           Mat4 clip_from_obj);

/* A box's screen rectangle (wl_sf_box_screen()); on is FALSE when the
 * box is empty or culled.  It depends on the screen's size, not on the
 * regions, so it serves every region split of one view. */
typedef struct {
    double x0, y0, x1, y1;
    gboolean on;
} WlSfScreen;

WlSfScreen wl_sf_screen_of(const WlSfRegions *r, SceneBox box,
                           Mat4 clip_from_obj);
/* wl_sf_box_regions() of the box whose screen rectangle is s. */
uint64_t wl_sf_screen_regions(const WlSfRegions *r, const WlSfScreen *s);

/* Screen rectangles of n boxes kept per key (a frame number), for runs
 * that revisit the frames of one view sequence with the same boxes
 * (one chunk database, scene and resolution). */
typedef struct WlSfScreenSet WlSfScreenSet;

WlSfScreenSet *wl_sf_screen_set_new(void);
void wl_sf_screen_set_free(WlSfScreenSet *s);
/* Forgets every key (the boxes changed). */
void wl_sf_screen_set_clear(WlSfScreenSet *s);
/* The n rectangles of `key` (borrowed, until clear or free); *fresh is
 * TRUE when they were just made and the caller must fill them.  Every
 * call with one key passes the same n and view_proj (g_assert). */
WlSfScreen *wl_sf_screen_set_get(WlSfScreenSet *s, guint key, guint n,
                                 Mat4 view_proj, gboolean *fresh);

/* Adds clip-space point c to the rectangle s being made (x0, y0 from
 * +inf, x1, y1 from -inf) by wl_sf_box_screen()'s rules: a point at or
 * behind the eye (w <= 0) sets *behind instead.  Returns its outcode
 * (bit k: outside the k-th clip plane), which the caller ANDs. */
static inline unsigned wl_sf_screen_point(const WlSfRegions *r, Vec4 c,
                                          WlSfScreen *s, gboolean *behind)
{
    unsigned out = (c.x < -c.w) | (c.x > c.w) << 1 | (c.y < -c.w) << 2 |
                   (c.y > c.w) << 3 | (c.z < -c.w) << 4 | (c.z > c.w) << 5;
    if (c.w <= 0) {
        *behind = TRUE;
        return out;
    }
    double sx = (c.x / c.w + 1) * 0.5 * r->width;
    double sy = (1 - c.y / c.w) * 0.5 * r->height;
    s->x0 = MIN(s->x0, sx);
    s->x1 = MAX(s->x1, sx);
    s->y0 = MIN(s->y0, sy);
    s->y1 = MAX(s->y1, sy);
    return out;
}

static inline uint64_t wl_sf_bit(guint p)
{
    return (uint64_t)1 << p;
}

#endif
