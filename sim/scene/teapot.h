/* teapot.h — the Utah teapot from Newell's Bézier patches.
 *
 * The 32 bicubic patches over 306 control points (data/teapot.txt,
 * embedded as sim/scene/teapot_data.c by scripts/gen-teapot-data.sh) are
 * tessellated to an exact polygon count T by one documented rule:
 *
 *   n = floor(sqrt(T / 32)); every patch is an n x n grid of quads in
 *   (u, v); a quad with a collapsed edge (the 4n quads at the lid-knob
 *   pole and the 4n at the bottom pole) is emitted as a triangle; the
 *   r = T - 32 n^2 remaining polygons come from splitting r of the other
 *   quads into two triangles along their shorter diagonal, spread evenly
 *   (quad k of the Q splittable quads, in patch / row / column order, is
 *   split iff floor((k+1) r / Q) > floor(k r / Q)).
 *
 * For T = 3751 (seed 003, Table 1): n = 10, 3200 grid cells of which 80
 * are pole triangles, 551 quads split: 2569 quads + 1182 triangles.
 * Valid for T >= 288 (n >= 3, so that r <= Q).  Vertices along shared
 * patch edges are welded (evaluation at u, v in {0, 1} is exact), so the
 * mesh is closed except where Newell's model is open (spout tip, lid
 * seam); polygons are wound counter-clockwise seen from outside.
 * The result is y-up: Newell's (x, y, z) becomes (x, z, -y); it spans
 * x in [-3, 3.43], y in [0, 3.15].  Polygon tags are patch numbers 0..31.
 * Cost O(T).  Newell's data: F. Crow, "The Origins of the Teapot", IEEE
 * CG&A 7(1), 1987.
 */
#ifndef PGSIM_SCENE_TEAPOT_H
#define PGSIM_SCENE_TEAPOT_H

#include "sim/scene/mesh.h"

#define SCENE_TEAPOT_PATCHES 32
#define SCENE_TEAPOT_POINTS 306
#define SCENE_TEAPOT_MIN_POLYS 288

/* The embedded tables (1-based indices into the points, z up). */
extern const uint16_t scene_teapot_patches[SCENE_TEAPOT_PATCHES][16];
extern const double scene_teapot_points[SCENE_TEAPOT_POINTS][3];

typedef struct {
    guint n;     /* grid cells per patch side */
    guint split; /* quads split into two triangles */
} SceneTeapotTess;

/* The rule above for `polygons`; an input error (naming `what`) if it is
 * below SCENE_TEAPOT_MIN_POLYS or above 2^26. */
gboolean scene_teapot_tess_for(uint64_t polygons, const char *what,
                               SceneTeapotTess *out, GError **err);
/* A new teapot mesh (free with scene_mesh_free()), one colour, per-vertex
 * normals. */
SceneMesh *scene_teapot_mesh(SceneTeapotTess t, SceneColor c);
/* Point P(u, v) of patch p (0-based), y-up. */
Vec3 scene_teapot_eval(guint patch, double u, double v);

#endif
