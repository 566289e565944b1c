/* teapots.h — the teapot scenes of the active-pixel-merging paper.
 *
 * Seed 003 (Table 1) renders scenes of 1, 2, 4 and 8 teapots of 3,751
 * polygons each (1POT, 2POT, 4POT_1, 4POT_2, 8POT_1, 8POT_2: 3751, 7502,
 * 15004, 15004, 30008, 30008 polygons).  The paper does not give the
 * placements or the camera, so this generator offers two documented
 * layouts, all of whose numbers come from the scene's YAML
 * (configs/scenes/ *.yaml):
 *
 *   spread  teapots on a cols x rows grid in the x-y plane (cols =
 *           ceil(sqrt(count))), centre distances `spacing` teapot widths
 *           and heights apart: with spacing >= 1 no two overlap on screen
 *           when seen from the front (arrangement "_1");
 *   depth   `columns` rows receding from the viewer side by side, centres
 *           `across` teapot widths apart; teapot i is in column
 *           i mod columns, at depth step r = i / columns: z = -r * spacing
 *           teapot depths, and each step moves `shift` teapot widths to
 *           the side; a diagonal block that overlaps on screen when
 *           shift < 1 (with columns 1: one diagonal row, arrangement "_2").
 *
 * Teapot i is turned by yaw + i * yaw_step degrees about its own vertical
 * axis before placement.  Explicit placements override the layout.  Every
 * teapot is one instance of one shared mesh (tag = teapot number); with
 * vary_color each gets a colour from a fixed 8-hue wheel.  Teapots are
 * centred on their bounding box, so a layout is symmetric about the
 * origin.  The camera is set by the view rule (scene.h).
 * Cost O(polygons_per_teapot + count).
 */
#ifndef PGSIM_SCENE_TEAPOTS_H
#define PGSIM_SCENE_TEAPOTS_H

#include "sim/scene/scene.h"

typedef enum { SCENE_TEAPOTS_SPREAD, SCENE_TEAPOTS_DEPTH } SceneTeapotLayout;

typedef struct {
    Vec3 at;        /* bounding-box centre of the teapot */
    double yaw_deg; /* about +y */
    double scale;
} SceneTeapotPlacement;

typedef struct {
    uint64_t polygons_per_teapot;
    guint count;
    SceneTeapotLayout layout;
    double spacing;                         /* see above */
    double shift;                           /* depth layout only */
    double yaw_step;                        /* degrees per teapot */
    const SceneTeapotPlacement *placements; /* NULL: use the layout */
    guint n_placements;                     /* == count when set */
    SceneColor color;
    gboolean vary_color;
    guint columns; /* depth layout: rows side by side (>= 1) */
    double across; /* depth layout: column spacing, teapot widths */
    double yaw;    /* degrees, every teapot */
} SceneTeapotsParams;

/* Defaults: 3200 polygons (configs/scenes/ set the paper's 3751), 1
 * teapot, spread, spacing 1.1, shift 0.5, yaw 0, yaw_step 0, no
 * placements, white, vary_color TRUE, columns 1, across 1.1. */
SceneTeapotsParams scene_teapots_defaults(void);
/* A new scene named "teapots" (free with scene_free()); an input error
 * (naming `what`) for a polygon count the rule cannot meet. */
/* The size checks alone (count 1..SCENE_TEAPOTS_MAX, memory against
 * sim_mem_limit()), so a caller can check before building. */
gboolean scene_teapots_check(const SceneTeapotsParams *p, const char *what,
                             GError **err);
Scene *scene_teapots_new(const SceneTeapotsParams *p, const char *what,
                         GError **err);

#endif
