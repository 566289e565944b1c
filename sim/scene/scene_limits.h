/* scene_limits.h — the largest values a scene may hold, one limit per
 * quantity, shared by the YAML scene section, the OBJ/PLY loaders and the
 * CLI shortcuts (`pgsim render --teapots N`).  docs/config.md ("Limits")
 * states each and why.
 *
 * Coordinates and normals: |x|, |y|, |z| <= SCENE_COORD_MAX after the OBJ
 * w division.  2^53 (9.0e15) is where a double stops resolving whole
 * units; 1e15 keeps a camera fitted at 100 radii (fill 0.01, fov 1
 * degree: about 1.1e4 radii) below 2e19 and every product the view and
 * projection matrices form below 1e40, far from overflow, so the fit's
 * near < far and the clipper's arithmetic stay finite.  Colours are
 * linear RGB in [0, 1] (what rast_channel() maps to 0..255).
 *
 * Sizes: the teapot count and the isosurface grid bound the work of one
 * scene; the memory a scene will take is checked against sim_mem_limit()
 * (sim/core/memlimit.h) before it is built.
 */
#ifndef PGSIM_SCENE_SCENE_LIMITS_H
#define PGSIM_SCENE_SCENE_LIMITS_H

#include "sim/scene/vec.h"

#define SCENE_COORD_MAX 1e15
#define SCENE_COLOR_MIN 0.0
#define SCENE_COLOR_MAX 1.0
#define SCENE_TEAPOTS_MAX 4096
#define SCENE_ISO_GRID_MAX 1024

/* Bytes a scene and the workload rendering it hold per polygon (triangle
 * or quad): the mesh (positions, normals and colours per vertex, indices,
 * offsets, colour and tag per polygon: about 150 B with shared vertices,
 * 250 B without) plus a transformed copy a workload keeps per frame.
 * Assumption, checked against peak RSS in docs/config.md (Limits). */
#define SCENE_POLY_BYTES 512.0

static inline gboolean scene_coord_ok(double v)
{
    return isfinite(v) && fabs(v) <= SCENE_COORD_MAX;
}

static inline gboolean scene_color_ok(double v)
{
    return isfinite(v) && v >= SCENE_COLOR_MIN && v <= SCENE_COLOR_MAX;
}

#endif
