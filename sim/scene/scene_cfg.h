/* scene_cfg.h — scenes from a YAML `scene:` section.
 *
 *   scene:
 *     generator: teapots | vehicle | isosurface | large_polygons |
 *                space_station | building_lobby | flock_old_well |
 *                two_human_figures
 *     file: model.obj | model.ply      # instead of a generator
 *     ...generator parameters (docs/scenes.md)...
 *     view:   {azimuth: 30, elevation: 20, fov: 45, fill: 0.9,
 *              projection: perspective, aspect: 1,
 *              fit: sphere|box|vertices}
 *     camera: {eye: [x, y, z], target: [...], up: [...], fov: 45,
 *              height: 2, near: 0.1, far: 100, aspect: 1,
 *              projection: orthographic}
 *     path:   {kind: orbit, center: [0, 0, 0], axis: [0, 1, 0],
 *              start: 0, degrees_per_frame: 3, frames: 120}
 *           | {kind: keyframes, interp: linear | catmull_rom,
 *              keys: [{frame: 0, eye: [...], target: [...], up: [...],
 *                      fov: 45}, ...]}
 *     background: [r, g, b]
 *     two_sided: false                 # true: renderers should not cull
     pn_triangles: {level: 2, normals: linear | quadratic}
                                      # curved PN tessellation of every
                                      # mesh, (L+1)^2 triangles each
 *
 * Order: the generator (or file) builds the scene with its own camera;
 * `pn_triangles` tessellates its meshes (before the view is fitted);
 * `view` then re-fits the camera by the view rule (scene.h), `camera`
 * sets it explicitly (unset fields keep their values), `path` replaces
 * any path (orbit: the frame-0 camera rotated about center / axis).  A
 * relative `file` is resolved against the YAML file's directory.
 * Every key is checked: an unknown one is an error (cfg_check_unused).
 * Errors are located: "file:line:column: found ..., expected ...".
 */
#ifndef PGSIM_SCENE_SCENE_CFG_H
#define PGSIM_SCENE_SCENE_CFG_H

#include "sim/core/cfg.h"
#include "sim/scene/scene.h"

/* Returns a new scene (free with scene_free()) or NULL with *err set. */
Scene *scene_from_cfg(const CfgNode *scene_section, GError **err);
/* A new scene of one mesh loaded from an OBJ or PLY file (by extension,
 * case-insensitive), camera by the default view rule. */
Scene *scene_from_file(const char *path, GError **err);
/* A scene from any file a user names: .yaml / .yml is a scene file
 * (configs/scenes/: a map with only a `scene:` section) or a run config
 * (it has `schema_version:`; its other sections are ignored), whose
 * scene section goes through scene_from_cfg(); .obj / .ply go through
 * scene_from_file().  Located errors as above; NULL on error. */
Scene *scene_load(const char *path, GError **err);
/* The generator names scene_from_cfg() accepts, NULL-terminated. */
const char *const *scene_generator_names(void);

#endif
