/* pm_scene.h — the `scene` section of a pixel-merging config: teapot
 * scenes (sim/scene/teapots.h) under one view rule (scene.h SceneView).
 *
 *   scene:
 *     generator: teapots          # the only generator here
 *     teapots: 2                  # count
 *     polygons_per_teapot: 3751   # seed 003 Table 1
 *     layout: spread              # spread (arrangement _1) | depth (_2)
 *     spacing: 1.1                # see teapots.h
 *     shift: 0.5
 *     yaw_step: 0                 # degrees per teapot
 *     view: {azimuth: 30, elevation: 20, fov: 45, fill: 1.0}
 *
 * Every key but `generator` and `teapots` is optional (teapots.h
 * defaults, view azimuth 0, elevation 0, fov 45, fill 1).  Errors are
 * located input errors.  Cost O(polygons).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_SCENE_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_SCENE_H

#include "sim/core/cfg.h"
#include "sim/scene/scene.h"

/* Returns a new scene (free with scene_free()) or NULL with *err.  When
 * the section has no `view`, `view` (a map, may be NULL) is used. */
Scene *wl_pm_scene_from_cfg(const CfgNode *section, const CfgNode *view,
                            GError **err);

#endif
