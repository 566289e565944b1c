/* pn_cube.h — test helpers: cubes for the PN-triangle tests, one with 8
 * shared vertices (smooth normals), one with creases (each face its own
 * vertices and normals). */
#ifndef PGSIM_TESTS_SCENE_PN_CUBE_H
#define PGSIM_TESTS_SCENE_PN_CUBE_H

#include "sim/scene/mesh.h"

/* The 6 quads of the cube's corners 0..7 (bits x, y, z), outward. */
extern const uint32_t pn_cube_quads[6][4];
/* Corner c of the cube [-1, 1]^3. */
Vec3 pn_cube_corner(guint c);
/* 8 shared vertices, 6 quads, each normal along its corner's diagonal. */
SceneMesh *pn_cube_smooth(void);

#endif
