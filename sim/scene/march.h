/* march.h — the March test scene of Argus (seed 002; Igehy, Stoll and
 * Hanrahan, SIGGRAPH 1998): marching cubes over a 64^3 volume extracted
 * cell by cell (16^3-cube cells), 53,346 independent triangles in the
 * paper (a skull CT, not public).
 *
 * The volume here is procedural: the metaballs field of isosurface.h
 * (seeded centres) on a grid^3 lattice over [-1, 1]^3, polygonised by
 * scene_iso_mesh_cells(), so each cell's triangles are consecutive and
 * tagged with the cell index cx + nc (cy + nc cz).  The iso level of
 * the defaults is chosen so that grid 64 gives 53,346 triangles within
 * 1 % (docs/scenes.md).  The camera looks from the (+x, +y, +z) side
 * (azimuth 45, elevation 35.26 degrees), with the eye beyond the
 * volume's maximum corner, so drawing cells in increasing index order
 * (z slowest) is back to front: any cell that can cover another along a
 * view ray has no smaller index in any axis (seed 002 Figure 3's
 * ordered loop relies on this).  O(grid^3).
 */
#ifndef PGSIM_SCENE_MARCH_H
#define PGSIM_SCENE_MARCH_H

#include "sim/scene/isosurface.h"

typedef struct {
    SceneIsoParams iso; /* field, grid, level, balls, seed, colour */
    guint cell;         /* cubes per cell side; divides iso.grid */
    double fill;        /* view: fraction of the viewport the vertices fill */
} SceneMarchParams;

/* metaballs, 10 balls, seed 2, level 1.67, grid 64, cell 16: 53,340
 * triangles (the paper: 53,346). */
SceneMarchParams scene_march_defaults(void);
/* Cells per axis (grid / cell). */
guint scene_march_cells(const SceneMarchParams *p);
/* A new scene "march" (one mesh, tags = cells, view above). */
Scene *scene_march_new(const SceneMarchParams *p);

#endif
