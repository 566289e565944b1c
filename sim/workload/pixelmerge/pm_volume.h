/* pm_volume.h — a volume-rendering workload on a real scalar field for
 * sort-last compositing (issue 35, point 3): the isosurface data sets'
 * fields (sim/scene/isosurface.h: gyroid or metaballs over [-1, 1]^3)
 * sampled on their grid^3 lattice, the volume cut into blocks
 * (pm_blocks.h), each process rendering its block.
 *
 * Over: emission-absorption ray casting.  Every pixel's ray (pm_blocks.h
 * rays) is sampled at t = k x step, k = 0, 1, ... (the same points for
 * every process count); a sample belongs to the block holding its point
 * (half-open cells), so each sample is taken by exactly one process.  At
 * a sample the field value v (trilinear on the lattice) gives extinction
 * density x max(0, 1 - |v - iso| / width) (a fuzzy shell about the iso
 * level), opacity a = 1 - exp(-extinction x step) and colour the field's
 * colour x (0.7 + 0.3 (v - iso) / width), clamped to [0, 1]; a block
 * accumulates its samples front to back, C += (1 - A) a c, A += (1 - A)
 * a, into one premultiplied pixel (active when A > 0; z the first
 * sample's t, poly the block).  A ray enters a block once, so its samples
 * in a block are consecutive and the blocks' pieces, composited with
 * over in their visibility order, give the serial front-to-back sum
 * regrouped: equal to the whole volume cast by one process up to
 * floating-point rounding (wl_pm_over_diff's 1e-9 is the tolerance).
 * Work: a "pixel" operation per sample.
 *
 * Z: the isosurface's triangles (scene_iso_mesh, the field's level set),
 * each given to the block holding its centroid, drawn by the raster's
 * scanline z-buffer (pm_render.h); with distinct global ids the z
 * composite equals the whole surface drawn by one process exactly.
 *
 *   volume: {field: gyroid, grid: 32, iso: 0, periods: 2, balls: 12,
 *            seed: 1, step: 0.02, density: 20, width: 0.25}
 *
 * Cost: O(grid^3) for the lattice, O(samples) a frame (over), the
 * raster's for the surface (z).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_VOLUME_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_VOLUME_H

#include "sim/core/cfg.h"
#include "sim/scene/isosurface.h"
#include "sim/workload/pixelmerge/pm_blocks.h"

typedef struct {
    SceneIsoParams iso; /* field, lattice grid, level, periods, balls ... */
    double step;        /* sample spacing along a ray */
    double density;     /* extinction at the level, per unit length */
    double width;       /* the shell's half-width in field units */
} WlPmVolume;

/* gyroid, grid 32, iso 0, 2 periods (scene_iso_defaults), step 0.02,
 * density 20, width 0.25. */
WlPmVolume wl_pm_volume_defaults(void);
/* Reads the map's field, grid, iso, periods, balls, seed, step, density
 * and width (map may be NULL: the defaults stay); located errors. */
gboolean wl_pm_volume_parse(const CfgNode *map, WlPmVolume *v, GError **err);

/* The field sampled on the lattice. */
typedef struct WlPmField WlPmField;
WlPmField *wl_pm_field_new(const SceneIsoParams *iso);
void wl_pm_field_free(WlPmField *f);
/* The trilinear value at x (clamped into [-1, 1]^3). */
double wl_pm_field_at(const WlPmField *f, Vec3 x);

/* Block p's ray-cast partial image (above); work into *c (a "pixel" per
 * sample, a span per row with an active pixel).  A grid of one block is
 * the serial render. */
WlPmWpa *wl_pm_volume_image(const WlPmField *f, const WlPmVolume *v,
                            const WlPmGrid *g, const WlPmRays *r, guint p,
                            WlPmCounts *c);

/* The block of each of the mesh's polygons (its centroid's), a new
 * array (g_free). */
guint *wl_pm_volume_owners(const SceneMesh *m, const WlPmGrid *g);

#endif
