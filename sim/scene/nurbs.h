/* nurbs.h — the Nurbs test scene of Argus (seed 002; Igehy, Stoll and
 * Hanrahan, "The Design of a Parallel Graphics Interface", SIGGRAPH 1998).
 *
 * The paper tessellates the armadillo as 102 patches of 196 (14 x 14)
 * control points into 117,504 stripped triangles.  The data are not
 * public; this generator makes a closed organic shape of the same
 * structure: a bumpy torus given by one periodic uniform bicubic
 * B-spline control net of (11 pu) x (11 pv) points, cut into pu x pv
 * patches; patch (a, b) is the 14 x 14 window of control points starting
 * at (11 a, 11 b) (wrapping), i.e. 11 x 11 knot spans, so neighbouring
 * patches meet with C2 continuity and the surface is closed.  The
 * control points sit on a torus (major radius 1, minor 0.45) whose tube
 * radius is modulated by a seeded sum of `bumps` sinusoids.
 *
 * Each patch is evaluated on a (tess + 1)^2 grid and emitted as `tess`
 * triangle strips of 2 tess triangles, in strip order: triangle k of a
 * strip uses strip vertices k, k+1, k+2 (so it shares two vertices with
 * triangle k-1); polygon tags are patch numbers.  With pu x pv = 6 x 17
 * = 102 and tess = 24: 102 x 24 x 48 = 117,504 triangles, 122,400 strip
 * vertices.  Cost O(patches tess^2).
 */
#ifndef PGSIM_SCENE_NURBS_H
#define PGSIM_SCENE_NURBS_H

#include "sim/scene/scene.h"

#define SCENE_NURBS_CONTROL 14 /* control points per patch side */

typedef struct {
    guint patches_u, patches_v; /* around the tube, around the ring */
    guint tess;                 /* quads per patch side */
    guint bumps;                /* sinusoids in the radius */
    double amplitude;           /* relative radius modulation */
    uint64_t seed;
    SceneColor color;
} SceneNurbsParams;

/* 6 x 17 patches, tess 24, 6 bumps, amplitude 0.25, seed 1. */
SceneNurbsParams scene_nurbs_defaults(void);
/* Control point (i, j) of the periodic net (indices wrap). */
Vec3 scene_nurbs_control(const SceneNurbsParams *p, guint i, guint j);
/* Point of patch (a, b) at local parameters s, t in [0, 11]. */
Vec3 scene_nurbs_eval(const SceneNurbsParams *p, guint a, guint b, double s,
                      double t);
/* A new mesh (free with scene_mesh_free()) of strip-ordered triangles. */
SceneMesh *scene_nurbs_mesh(const SceneNurbsParams *p);
/* A new scene "nurbs" with the mesh and a three-quarter view. */
Scene *scene_nurbs_new(const SceneNurbsParams *p);

#endif
