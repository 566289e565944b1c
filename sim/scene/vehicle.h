/* vehicle.h — a procedural vehicle as a structure hierarchy (seed 000).
 *
 * Seed 000's sort-first test database is a Ford Bronco of 466 structures
 * and 74,647 triangles, instanced three times around a circle, with the
 * camera revolving about the circle and seeing about half of its area.
 * The model itself is not public, so this generator builds a
 * vehicle-like model procedurally with exactly the requested numbers of
 * structures and triangles (both come from YAML, configs/scenes/
 * bronco.yaml):
 *
 *   1 root "vehicle" executing 5 group structures (body, chassis,
 *   wheels, interior, trim), which execute L = structures - 6 leaf part
 *   structures, each holding only triangles.  Leaves are split 35 / 25 /
 *   20 / 10 / 10 % among the groups (wheels rounded to a multiple of 4).
 *   Every structure is executed exactly once, so the min-set and max-set
 *   triangle counts are equal.  Each leaf is one parametric patch (panel
 *   of a body box, tube, ellipsoid or tyre-torus sector) tessellated
 *   row by row on a grid, stopping after exactly its budget of
 *   triangles; budgets are proportional to a per-kind weight with
 *   largest-remainder rounding, at least 2 each, summing to `triangles`.
 *
 * The vehicle is about 4.2 x 1.9 x 1.8 (x forward, y up, z left),
 * wheels on the ground plane y = 0.  Cost O(triangles + structures).
 */
#ifndef PGSIM_SCENE_VEHICLE_H
#define PGSIM_SCENE_VEHICLE_H

#include "sim/scene/scene.h"

#define SCENE_VEHICLE_GROUPS 5

typedef struct {
    guint structures;     /* in the vehicle, root included */
    uint64_t triangles;   /* in the vehicle */
    guint instances;      /* copies around the circle */
    double circle_radius; /* of the copies' centres */
    /* camera: eye at camera_radius from the circle's centre, camera_height
     * above the ground, looking at the centre; fov in degrees; the path
     * revolves the eye about +y by degrees_per_frame for `frames`. */
    double camera_radius, camera_height, fov_deg, degrees_per_frame;
    guint frames;
    /* How many copies execute one vehicle tree (how many times each of
     * its structures is executed): 1 builds a tree per copy (no
     * instancing), 0 (or >= instances) one tree for all (the default,
     * seed 000's database); in between, copy k executes tree
     * k / instancing.  The picture does not change, only the sharing. */
    guint instancing;
} SceneVehicleParams;

/* Defaults: 106 structures, 20000 triangles, 3 instances, radius 6,
 * camera radius 14, height 4, fov 40, 3 degrees per frame, 120 frames,
 * instancing 0 (configs/scenes/bronco.yaml sets the paper's numbers). */
SceneVehicleParams scene_vehicle_defaults(void);

/* Adds the vehicle's structures to db (not posted); *root receives the
 * root's id.  Input error (naming `what`) unless structures >= 10 and
 * triangles >= 2 * (structures - 6) and <= 2^28. */
gboolean scene_vehicle_build(SceneDb *db, guint structures, uint64_t triangles,
                             const char *what, guint *root, GError **err);
/* A new scene named "vehicle": the vehicle flattened into one mesh
 * (polygon tag = structure id), `instances` copies facing along the
 * circle, an orbit camera path, and s->db holding the vehicle (one tree
 * per `instancing` copies) plus a posted "world" structure executing a
 * tree's root once per copy (matrix element in REPLACE mode before each
 * execute). */
Scene *scene_vehicle_new(const SceneVehicleParams *p, const char *what,
                         GError **err);

#endif
