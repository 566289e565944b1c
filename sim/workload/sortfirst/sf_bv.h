/* sf_bv.h — the kinds of bounding volume around a chunk (seed 000
 * §3.3.1: "spheres, axis-aligned boxes, oriented boxes, and multiple
 * slab intersection [1].  These are listed in order of increasing
 * complexity and tightness of fit"), their screen rectangles, the cost
 * of one test and their tightness.
 *
 *   aabb    the chunk's axis-aligned box in its structure's coordinates
 *           (sf_db.h; 8 corners transformed: 8 x transform_vertex);
 *   sphere  centre the box's centre, radius the farthest vertex from
 *           it; its screen rectangle is exact: the planes through the
 *           eye tangent to the sphere, x = k w and y = k w in clip space,
 *           solve a quadratic in k (the sphere as a dual quadric); the
 *           six clip planes cull it when it lies wholly outside one; a
 *           sphere reaching w <= 0 covers the whole plane, as a box
 *           with a corner there does.  One test: 1 x transform_vertex
 *           (its centre) + 1 x sphere_bound (the tangents, models/);
 *   obb     the box along the principal axes of the chunk's vertices
 *           (eigenvectors of their covariance, Jacobi), its 8 corners
 *           projected: 8 x transform_vertex;
 *   slabs   the intersection of 7 slabs (Kay and Kajiya's normals: the
 *           3 axes and the 4 cube diagonals, a 14-DOP), each tight
 *           around the vertices; its vertices (each 3 planes meeting
 *           inside all the others) are found once per chunk and
 *           projected as the box's corners are: one test costs
 *           transform_vertex x the mean vertex count over the chunks
 *           (rounded; a polytope's projection lies in the rectangle of
 *           its projected vertices when all are in front of the eye).
 *
 * Every kind contains the chunk's primitives, so the bucket sort stays
 * conservative (the frame check of sf_frame.h would fail otherwise).
 * Tightness (WlSfBvFit): over the chunk instances on the screen, the
 * screen area of the volume's rectangle against the area of the
 * rectangle of the chunk's projected vertices (both clamped to the
 * screen), and the regions the volume reaches that the vertices do not
 * (false-positive overlaps), per polygon.  Building O(vertices) per
 * chunk (slabs: 364 plane triples per chunk); a test O(1) but slabs
 * O(polytope vertices); the fit O(vertices of the instances).
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_BV_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_BV_H

#include "sim/workload/sortfirst/sf_db.h"
#include "sim/workload/sortfirst/sf_regions.h"

typedef enum {
    WL_SF_BV_AABB,
    WL_SF_BV_SPHERE,
    WL_SF_BV_OBB,
    WL_SF_BV_SLABS
} WlSfBvKind;

/* "aabb", "sphere", "obb", "slabs" */
extern const char *const wl_sf_bv_names[];

/* Slab normals of the `slabs` kind. */
#define WL_SF_BV_SLAB_NORMALS 7

typedef struct {
    Vec3 centre;
    double radius;    /* sphere */
    guint first, n;   /* obb, slabs: range of WlSfDb.bv_verts */
} WlSfBv;

/* One test's work as counts of the node's costs. */
typedef struct {
    uint64_t verts;   /* transform_vertex */
    uint64_t spheres; /* sphere_bound */
} WlSfBvCost;

/* Sets d's kind and builds the volumes of its chunks from db. */
void wl_sf_bv_set(WlSfDb *d, const SceneDb *db, WlSfBvKind kind);
/* Rebuilds the volumes for d's chunks (after they changed; nothing for
 * boxes). */
void wl_sf_bv_build(WlSfDb *d, const SceneDb *db);
/* Chunk c's volume's screen rectangle under clip_from_obj. */
WlSfScreen wl_sf_bv_screen(const WlSfDb *d, const WlSfRegions *r, guint c,
                           Mat4 clip_from_obj);
/* The work of one volume test of d's kind. */
WlSfBvCost wl_sf_bv_cost(const WlSfDb *d);

typedef struct {
    uint64_t insts;       /* instances whose vertices are on the screen */
    double bv_area;       /* Σ volume rectangle areas (px², clamped) */
    double exact_area;    /* Σ vertex rectangle areas (px², clamped) */
    double polys;         /* Σ polygons of those instances */
    double false_regions; /* Σ polygons x regions reached falsely */
} WlSfBvFit;

/* Adds the fit of every chunk instance of d under view_proj. */
void wl_sf_bv_fit(const WlSfDb *d, const SceneDb *db, const WlSfRegions *r,
                  Mat4 view_proj, WlSfBvFit *fit);

#endif
