/* pm_images.h — where the compositing workload's local images come
 * from (workload.images): the scene's polygons split among the processes
 * (pm_render.h, the default), or the images the compositing literature
 * runs on: a volume cut into a regular grid of blocks, one a process
 * (pm_blocks.h), each block's footprint ("blocks") or its part of a
 * volume rendering of a real scalar field ("volume", pm_volume.h).  The
 * block images come with their visibility order from the view.
 *
 *   workload:
 *     images: blocks          # scene | blocks | volume
 *     volume:                 # blocks and volume (over [-1, 1]^3)
 *       density: 1.5          # blocks: extinction per unit length
 *       ...                   # volume: pm_volume.h
 *
 * The camera is the scene's, so a scene whose box is about [-1, 1]^3
 * (an isosurface) frames the volume.  Cost: a frame's images are
 * O(footprint pixels) (blocks), O(samples) (volume, over) or the
 * raster's (volume, z); nothing is O(processes x image).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_IMAGES_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_IMAGES_H

#include "sim/core/cfg.h"
#include "sim/workload/pixelmerge/pm_blocks.h"
#include "sim/workload/pixelmerge/pm_composite.h"
#include "sim/workload/pixelmerge/pm_volume.h"

typedef enum {
    WL_PM_IMAGES_SCENE,
    WL_PM_IMAGES_BLOCKS,
    WL_PM_IMAGES_VOLUME
} WlPmImageKind;

/* NULL-terminated, indexed by WlPmImageKind. */
extern const char *const wl_pm_image_names[];

typedef struct {
    WlPmImageKind kind;
    double density; /* blocks: extinction per unit length */
    WlPmVolume vol; /* volume: the field and its rendering */
} WlPmImages;

/* Reads workload.images and workload.volume into *im (defaults: scene;
 * density 1.5; pm_volume.h's).  compose: the scheme composites (block
 * images need a compositing scheme); has_order: workload.visibility is
 * given (the blocks' order comes from the view instead).  Located
 * errors. */
gboolean wl_pm_images_parse(const CfgNode *sec, gboolean compose,
                            gboolean has_order, WlPmImages *im, GError **err);

/* The bytes block images add to the workload's own memory for n
 * processes on an N x N screen (0 for the scene's images): their local
 * images together hold up to L = ceil(cbrt(n)) layers of the screen
 * (the blocks along a ray), each pixel a WlPmPixel and its 4 doubles
 * (N^2 L (sizeof(WlPmPixel) + 32)), and the volume its lattice ((grid +
 * 1)^3 doubles). */
double wl_pm_images_mem_bytes(const WlPmImages *im, guint n, guint N);

/* One frame's block images. */
typedef struct {
    guint n;
    WlPmWpa **local;    /* process p's partial image */
    WlPmCounts *counts; /* its work */
    guint *order;       /* the blocks nearest first */
    SceneMesh *mesh;    /* volume with z: the isosurface drawn, else NULL */
    WlPmGrid grid;
} WlPmImageSet;

/* The images of n processes (im->kind not scene) for camera cam on view
 * v (its size the image's) with operator op.  Free with
 * wl_pm_images_free(). */
WlPmImageSet *wl_pm_images_make(const WlPmImages *im, const SceneCamera *cam,
                                const RastView *v, guint n, WlPmOperator op);
void wl_pm_images_free(WlPmImageSet *set);

/* TRUE when the composited image is the serial one: z, the z-buffer of
 * the block images (blocks) or the isosurface drawn whole by one process
 * (volume), exactly; over with volume, the whole volume ray-cast by one
 * process, to wl_pm_over_diff's tolerance (the blocks' over blend is
 * checked against the images' serial blend by the frame, pm_frame.c). */
gboolean wl_pm_images_match(const WlPmImages *im, const WlPmImageSet *set,
                            const SceneCamera *cam, const RastView *v,
                            WlPmOperator op, const WlPmComposite *comp);

#endif
