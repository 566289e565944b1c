/* pn_crease.h — finding the crease edges of a mesh for curved PN
 * triangles (Vlachos, Peters, Boyd and Mitchell, I3D 2001, "curved sharp
 * edges"; the construction on a crease is in pn_triangles.h).
 *
 * An edge is keyed by its two end positions (bitwise, in a canonical
 * order), not by vertex index, so the sides of a crease, which carry
 * their own vertices with the same positions and different normals, meet
 * on one key.  An edge is a crease when two of its sides have different
 * (unit) normals at an end; the crease direction at that end is the unit
 * cross product of the two normals, taken in a canonical order so that
 * every side computes the same bits.  O(triangles) with a hash.
 */
#ifndef PGSIM_SCENE_PN_CREASE_H
#define PGSIM_SCENE_PN_CREASE_H

#include "sim/scene/pn_triangles.h"

/* Whether a comes after b in (x, y, z) order (the canonical order of an
 * edge's ends and of a crease's two normals). */
gboolean scene_pn_vec_after(Vec3 a, Vec3 b);

/* One ScenePnCreases per triangle of m's fan triangulation, in the order
 * polygon by polygon, fan (ix[0], ix[t], ix[t + 1]) by fan; m has one
 * normal per vertex.  Free with g_array_free(.., TRUE). */
GArray *scene_pn_find_creases(const SceneMesh *m);

#endif
