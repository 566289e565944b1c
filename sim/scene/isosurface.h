/* isosurface.h — isosurfaces of procedural fields, and large polygons,
 * for the data-parallel renderer (seed 004).
 *
 * Seed 004 renders an isosurface of 355,948 small polygons (its Figure 2,
 * an oil-well perforator from a hydrodynamics code; Table 1's data set
 * implies about 228,000) and a set of large polygons "which covered over
 * 3/4 of the image" (Table 2 implies about 218,000 of them).  The data
 * are not public; these generators produce sets with the same character:
 *
 * Isosurface: the level set f = iso of a procedural field sampled on a
 * grid x grid x grid lattice over [-1, 1]^3, polygonised by marching
 * cubes (Lorensen & Cline, SIGGRAPH 1987) with every cube split into six
 * tetrahedra around its main diagonal (Doi & Koide, IEICE Trans. E74(1),
 * 1991): no 256-case table, no ambiguous cases, and neighbouring cubes
 * split their shared faces the same way, so the surface is watertight.
 * Vertices on lattice edges are shared (welded by edge id); triangles
 * are wound counter-clockwise seen from the low side (f < iso).  Fields:
 *   gyroid     sin(kx)cos(ky) + sin(ky)cos(kz) + sin(kz)cos(kx), k =
 *              2 pi periods / 2 (a triply periodic minimal-like surface);
 *   metaballs  sum over `balls` centres (rng stream from `seed`) of
 *              r^2 / |p - c|^2, radius r = 0.25.
 * The triangle count grows as grid^2; configs/scenes/isosurface.yaml
 * picks the grid for the paper's count.  O(grid^3) time, O(triangles)
 * memory.
 *
 * Large polygons: `count` random convex polygons facing an orthographic
 * camera that sees [-1, 1]^2; a fraction `huge_fraction` are randomly
 * turned regular 4- to 8-gons about the screen centre (radius 0.95 to
 * 1.25, centre within 0.2), drawn again until the part inside the
 * screen covers over 3/4 of it (seed 004: "polygons which covered over
 * 3/4 of the image"; they may reach past the edges, which the renderer
 * clips), the rest regular 3- to max_sides-gons of
 * radius uniform in [min_size, max_size] (fractions of the half-screen)
 * centred anywhere on screen.  Depths uniform in (-1, 1).  Seeded from
 * sim/core/rng.h.  O(count).
 */
#ifndef PGSIM_SCENE_ISOSURFACE_H
#define PGSIM_SCENE_ISOSURFACE_H

#include "sim/scene/scene.h"

typedef enum { SCENE_FIELD_GYROID, SCENE_FIELD_METABALLS } SceneFieldKind;

typedef struct {
    SceneFieldKind field;
    guint grid;     /* cells per axis, >= 2 */
    double iso;     /* level */
    double periods; /* gyroid: periods across the cube */
    guint balls;    /* metaballs */
    uint64_t seed;  /* metaballs */
    SceneColor color;
} SceneIsoParams;

/* gyroid, grid 32, iso 0, 2 periods, 12 balls, seed 1, light blue. */
SceneIsoParams scene_iso_defaults(void);
double scene_iso_field(const SceneIsoParams *p, const Vec3 *centres, Vec3 x);
/* The metaballs' centres (p->balls of them, from p->seed), a new array
 * for scene_iso_field (g_free). */
Vec3 *scene_iso_centres(const SceneIsoParams *p);
/* A new mesh of triangles (free with scene_mesh_free()). */
SceneMesh *scene_iso_mesh(const SceneIsoParams *p);
/* The same surface polygonised cell by cell: the lattice is cut into
 * cells of cell^3 cubes (cell divides grid), visited z slowest, then y,
 * then x; each cell's triangles are consecutive and tagged with the cell
 * index cx + nc (cy + nc cz), nc = grid / cell (seed 002's March:
 * 64^3 in 16^3 cells).  cell == grid gives scene_iso_mesh(). */
SceneMesh *scene_iso_mesh_cells(const SceneIsoParams *p, guint cell);
/* A new scene "isosurface" with the mesh and the default view rule. */
Scene *scene_iso_new(const SceneIsoParams *p);
/* Checks the grid (2..SCENE_ISO_GRID_MAX) and the memory the field and
 * the surface will take against sim_mem_limit(); `what` locates the grid
 * in errors ("file:line:col" or a flag name). */
gboolean scene_iso_check(const SceneIsoParams *p, const char *what,
                         GError **err);

typedef struct {
    guint count;
    guint max_sides;           /* 3 .. 16 */
    double huge_fraction;      /* [0, 1] */
    double min_size, max_size; /* fractions of the half-screen */
    uint64_t seed;
} SceneBigPolyParams;

/* 1000 polygons, up to 6 sides, 0.05 huge, sizes 0.1 .. 0.5, seed 1. */
SceneBigPolyParams scene_bigpoly_defaults(void);
/* A new scene "large_polygons" with an orthographic camera looking down
 * -z at [-1, 1]^2. */
Scene *scene_bigpoly_new(const SceneBigPolyParams *p);
/* The memory of `count` polygons of up to max_sides against
 * sim_mem_limit(). */
gboolean scene_bigpoly_check(const SceneBigPolyParams *p, const char *what,
                             GError **err);

#endif
