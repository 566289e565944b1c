/* ag_tile.h — the Argus frame buffer, cut into square tiles, and the
 * pixel work of its rasterisation threads (seed 002: "Sort-Middle tiled
 * parallel graphics system"; each rasteriser owns a set of tiles).
 *
 * The frame buffer holds float RGB, depth and primitive id per pixel
 * (the back buffer the threads draw into) and a front buffer of RGB:
 * glClear clears one tile of the back buffer, glXSwapBuffers presents
 * one tile (copies it to the front), so a frame's picture is what each
 * tile held when its swap command reached it.
 * Two pixel modes: OPAQUE z-buffers (smaller depth wins, ties by
 * primitive id: order-independent, Nurbs) and BLEND composites
 * c = alpha src + (1 - alpha) c without a depth test (the transparent,
 * back-to-front March: order-dependent, so the image shows whether the
 * ordering commands were honoured).  Drawing a list of triangles into
 * one tile runs the real pipeline (sim/raster: transform, light, clip,
 * scan) and crops its spans to the tile.
 *
 * Bucketing (the geometry threads' sort): a triangle goes to every tile
 * its screen bounding box overlaps (vertices behind the eye: every tile).
 * O(pixels) per draw, O(tiles touched) per bucketed triangle.
 */
#ifndef PGSIM_WORKLOAD_ARGUS_AG_TILE_H
#define PGSIM_WORKLOAD_ARGUS_AG_TILE_H

#include "sim/raster/image.h"
#include "sim/raster/pipeline.h"

typedef enum { WL_AG_OPAQUE, WL_AG_BLEND } AgPixelMode;
extern const char *const wl_ag_pixel_names[]; /* "opaque" "blend" */

typedef struct {
    int width, height, tile;
    guint tiles_x, tiles_y;
    AgPixelMode mode;
    float alpha;
    float *rgb;     /* 3 per pixel */
    double *depth;  /* +inf when empty */
    uint32_t *prim; /* RAST_NO_PRIM when empty */
    float *front;   /* 3 per pixel: the presented picture */
    RastColor bg;
} AgFrame;

/* A new cleared frame buffer (free with wl_ag_frame_free()). */
AgFrame *wl_ag_frame_new(int width, int height, int tile, AgPixelMode mode,
                         float alpha, RastColor bg);
void wl_ag_frame_free(AgFrame *f);
void wl_ag_frame_clear(AgFrame *f);
/* glClear at tile t (G_MAXUINT: the whole frame): returns its pixels. */
uint64_t wl_ag_frame_clear_tile(AgFrame *f, guint t);
/* glXSwapBuffers at tile t: the tile's back buffer becomes its front. */
void wl_ag_frame_present_tile(AgFrame *f, guint t);
static inline guint wl_ag_n_tiles(const AgFrame *f)
{
    return f->tiles_x * f->tiles_y;
}

/* Draws triangles `tris` (mesh polygon indices, in order) into tile t
 * (t == G_MAXUINT: the whole frame); returns pixels touched. */
uint64_t wl_ag_draw(AgFrame *f, guint t, const RastView *v, const SceneMesh *m,
                    const uint32_t *tris, guint n);

/* Calls fn(tile, ctx) for every tile the screen box of triangle i
 * overlaps; returns how many. */
guint wl_ag_bucket(const AgFrame *f, const Mat4 *view_proj, const SceneMesh *m,
                   guint i, void (*fn)(guint tile, void *ctx), void *ctx);

/* The rasteriser (of R) that owns tile t: (tx + ty) mod R, so that
 * neighbouring tiles along a row and along a column have different
 * owners (a screen-space object spreads over all rasterisers; t mod R
 * would give each one a column of tiles when R divides tiles_x). */
static inline guint wl_ag_tile_owner(const AgFrame *f, guint t, guint R)
{
    return (t % f->tiles_x + t / f->tiles_x) % R;
}

/* The back buffer, or the presented front buffer, as an 8-bit image
 * (new; rast_image_free()). */
RastImage *wl_ag_frame_image(const AgFrame *f);
RastImage *wl_ag_frame_front_image(const AgFrame *f);

#endif
