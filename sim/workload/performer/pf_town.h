/* pf_town.h — a procedural town for the Performer workload: terrain
 * tiles, houses under static transforms with three levels of detail,
 * billboarded trees, street lamps behind switches and cars on dynamic
 * transforms, with a camera driving down the main street.
 *
 * Layout: blocks x blocks square blocks of `block` metres; each block
 * holds one terrain geode (8 x 8 quads on a gentle height field), an SCS
 * per house (LOD: boxes of 12 k^2 triangles, k = 4, 2, 1, switching at
 * `lod_ranges` metres), a billboard of trees (not in the ISECT mask) and
 * a switch of lamps (every other block's lamps off).  Cars are DCS nodes
 * moved by APP every frame.  Geostates cycle over a few textures,
 * materials and mode words so that lazy state management has something
 * to save.  Deterministic: all placement comes from `seed`.
 * Hierarchy (the slides' "efficiency depends on the depth and balance of
 * the scene graph"): flat, every block a child of the root (shallow), or
 * `deep`, the blocks under a balanced quadtree of groups (each group
 * halves its range of blocks in both directions until one block), the
 * same blocks with the same placement, so CULL can reject a quadrant at
 * one sphere test.
 * Partition (pfPartition, for ISECT): with `partition` > 0 the blocks
 * (or their quadtree) hang under a partition node, not the root, whose
 * grid of partition x partition cells lets ISECT's segment under the
 * eye test only the blocks of its cell; the cars stay outside it.
 * Size O(blocks^2 * (houses + trees)).
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_TOWN_H
#define PGSIM_WORKLOAD_PERFORMER_PF_TOWN_H

#include "sim/scene/camera.h"
#include "sim/workload/performer/pf_graph.h"

typedef struct {
    guint blocks, houses, trees, cars;
    double block;         /* metres */
    double lod_ranges[3]; /* switch distances LOD0->1, 1->2, 2->none */
    double speed;         /* camera metres per frame */
    double eye_height;    /* metres above the terrain */
    double fov_deg;
    uint64_t seed;
    gboolean deep; /* blocks under a quadtree of groups (else flat) */
    guint32 callbacks; /* WL_PF_CB_* on every house's SCS (0: none) */
    guint partition;   /* > 0: the blocks under a pfPartition of
                        * partition x partition cells (0: none) */
} WlPfTownParams;

typedef struct {
    WlPfTownParams p;
    WlPfGraph *g;
    GArray *cars; /* guint DCS node indices */
    guint car_group;
    guint blocks_node; /* the blocks' (or quadtree's) parent */
} WlPfTown;

WlPfTownParams wl_pf_town_defaults(void);
/* Returns a new town; free with wl_pf_town_free(). */
WlPfTown *wl_pf_town_new(const WlPfTownParams *p);
void wl_pf_town_free(WlPfTown *t);
/* APP's work for frame f: moves every car (DCS) and refreshes the bounds
 * above them; returns the number of DCS nodes updated. */
guint wl_pf_town_update(WlPfTown *t, guint frame);
/* The camera of frame f (driving down the main street; the eye height
 * is above `ground`, the terrain height ISECT found). */
SceneCamera wl_pf_town_camera(const WlPfTown *t, guint frame, double ground);
/* The terrain height at (x, z) (what ISECT should find under the eye). */
double wl_pf_town_height(double x, double z);

#endif
