/* pm_blocks.h — sort-last images as the compositing literature makes
 * them (issue 35, point 3): a volume (an axis-aligned box) cut into a
 * regular 3-D grid of blocks, one per process; process p's partial image
 * is its block's screen footprint, and the blocks' visibility order comes
 * from the view.
 *
 * Grid.  n processes: dims[0] x dims[1] x dims[2] = n, the most cubic
 * factorisation (smallest dims[0] + dims[1] + dims[2]; ties: the larger
 * counts on the earlier axes), so 8 -> 2 x 2 x 2, 12 -> 3 x 2 x 2,
 * 64 -> 4 x 4 x 4, a prime n -> n x 1 x 1.  Block p = i + dims[0] (j +
 * dims[1] k).  Cells are half-open, [lo, hi) on every axis: a point
 * belongs to exactly one block (wl_pm_grid_block_of), so samples taken
 * at points split among the blocks without overlap or gap.
 *
 * Visibility order (nearest first).  A ray from the eye crosses the
 * grid's slabs monotonically on each axis, so a block that can hide
 * another is no farther from the eye's slab on any axis and nearer on
 * one: sorting by the sum over axes of |i - e| (e the eye's slab index,
 * clamped into the grid; orthographic: the slab index counted along the
 * view direction) is a front-to-back order; ties go to the lower block.
 *
 * Rays.  Pixel (x, y)'s ray goes through its centre, as the raster's
 * viewport maps NDC (rast_viewport: row 0 at the top): from the eye
 * (perspective) or from the eye's plane (orthographic), unit direction.
 *
 * Footprint.  The bounding rectangle of the block's 8 projected corners
 * (the whole screen when a corner is not in front of the eye), as pixel
 * rectangle [x0, x1) x [y0, y1): every pixel whose ray meets the block is
 * inside it.  O(1), no pixels: what a model of 32,768 processes needs.
 *
 * Block image (wl_pm_block_image): the pixels of the footprint whose ray
 * meets the block (slab test); depth z = the entry distance along the
 * ray, poly = the block (the depth tie-break), and a per-pixel
 * premultiplied colour (the block's hue) whose
 * opacity is 1 - exp(-density x the ray's length inside the block)
 * (a homogeneous block of that extinction).  O(footprint pixels).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_BLOCKS_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_BLOCKS_H

#include "sim/scene/camera.h"
#include "sim/workload/pixelmerge/pm_render.h"

typedef struct {
    guint dims[3];       /* blocks per axis; their product is the processes */
    double lo[3], hi[3]; /* the volume's box */
} WlPmGrid;

/* The grid of n >= 1 blocks over the box lo .. hi. */
void wl_pm_grid_init(WlPmGrid *g, guint n, Vec3 lo, Vec3 hi);
guint wl_pm_grid_count(const WlPmGrid *g);
/* Block p's box. */
void wl_pm_grid_block(const WlPmGrid *g, guint p, Vec3 *lo, Vec3 *hi);
/* TRUE when x is inside the volume (lo <= x < hi on every axis). */
gboolean wl_pm_grid_inside(const WlPmGrid *g, Vec3 x);
/* The block holding x (x inside the volume). */
guint wl_pm_grid_block_of(const WlPmGrid *g, Vec3 x);
/* The blocks nearest first for this camera, into order[count]. */
void wl_pm_grid_order(const WlPmGrid *g, const SceneCamera *cam, guint *order);

typedef struct {
    SceneProjection proj;
    Vec3 eye, fwd;  /* fwd: unit, towards the target */
    Vec3 right, up; /* NDC x = 1 and y = 1: at distance 1 (perspective)
                     * or from the eye (orthographic) */
    guint width, height;
} WlPmRays;

/* The rays of a width x height view of cam (aspect = width / height, as
 * rast_view_for_camera). */
void wl_pm_rays_init(WlPmRays *r, const SceneCamera *cam, guint width,
                     guint height);
/* Pixel (x, y)'s ray: origin and unit direction. */
void wl_pm_ray(const WlPmRays *r, guint x, guint y, Vec3 *org, Vec3 *dir);
/* The parameters [*t0, *t1] where the ray org + t dir is inside the box
 * lo .. hi, t >= 0; FALSE when it misses (or only touches) it. */
gboolean wl_pm_ray_box(Vec3 org, Vec3 dir, Vec3 lo, Vec3 hi, double *t0,
                       double *t1);

typedef struct {
    guint x0, y0, x1, y1; /* pixels x0 <= x < x1, y0 <= y < y1 */
} WlPmRect;

/* Block p's footprint (above); FALSE when it is off the screen. */
gboolean wl_pm_block_rect(const WlPmGrid *g, const WlPmRays *r, guint p,
                          WlPmRect *rect);

/* What a block's process computes for one ray (org, unit dir): FALSE
 * when the pixel stays empty, else its depth *z and premultiplied
 * colour rgba[4]; work goes into *c. */
typedef gboolean (*WlPmRayFn)(void *ctx, Vec3 org, Vec3 dir, double *z,
                              double *rgba, WlPmCounts *c);

/* Block p's partial image: fn on every pixel of its footprint, row by
 * row (poly = p, colour rgba's colour in 8 bits); *c (cleared first) gets
 * fn's work, one polygon (the block), a span per row with a pixel and a
 * winner per pixel (fn returns TRUE only with rgba[3] > 0).  Free with
 * wl_pm_wpa_free(). */
WlPmWpa *wl_pm_block_cast(const WlPmGrid *g, const WlPmRays *r, guint p,
                          WlPmRayFn fn, void *ctx, WlPmCounts *c);

/* Block p's partial image (above) at extinction density (per unit of
 * length); the work in *c: one polygon (the block), a span per row and
 * a pixel per ray that meets it.  Free with wl_pm_wpa_free(). */
WlPmWpa *wl_pm_block_image(const WlPmGrid *g, const WlPmRays *r, guint p,
                           double density, WlPmCounts *c);

/* Block p's hue (a golden-ratio walk around the colour wheel), as
 * doubles in [0, 1] into rgb[3]. */
void wl_pm_block_color(guint p, double *rgb);

#endif
