/* camera.h — perspective and orthographic cameras, and camera paths.
 *
 * Conventions (OpenGL's, so the raster stage can use textbook clipping):
 * right-handed world; the view matrix maps the eye to the origin looking
 * down -z with `up` projected to +y (gluLookAt); the projection maps the
 * view volume to clip space with -w <= x, y, z <= w, NDC z = -1 at the
 * near plane and +1 at the far plane (glFrustum / glOrtho).  `fov_deg` is
 * the full vertical field of view; `height` the full vertical extent of
 * an orthographic volume; aspect = width / height of the viewport.
 *
 * A camera path gives the camera of frame f (a double so that sub-frames
 * interpolate): fixed, orbit (the eye, target and up rotated about an
 * axis through a centre by a constant angle per frame), or keyframes
 * (linear or Catmull-Rom interpolation of eye and target, linear for up,
 * fov, extent and clip planes; clamped outside the keyed range).
 * Everything is O(1) except keyframe lookup, O(log k).
 */
#ifndef PGSIM_SCENE_CAMERA_H
#define PGSIM_SCENE_CAMERA_H

#include "sim/scene/mesh.h"

typedef enum { SCENE_PERSPECTIVE, SCENE_ORTHOGRAPHIC } SceneProjection;

typedef struct {
    SceneProjection proj;
    Vec3 eye, target, up;
    double fov_deg; /* perspective: full vertical field of view */
    double height;  /* orthographic: full vertical extent */
    double near, far;
    double aspect; /* viewport width / height */
} SceneCamera;

/* A perspective camera at (0, 0, 5) looking at the origin, +y up, 45°,
 * near 0.1, far 100, aspect 1. */
SceneCamera scene_camera_default(void);
Mat4 scene_camera_view(const SceneCamera *c);
Mat4 scene_camera_projection(const SceneCamera *c);
/* projection * view. */
Mat4 scene_camera_view_proj(const SceneCamera *c);
/* Largest `fill`: above 1 the fitted scene overflows the viewport by that
 * factor and is clipped at its edges (a close-up). */
#define SCENE_FILL_MAX 4.0

/* The view rule used by the generators: keeps the viewing direction
 * (eye - target) and up, aims at the centre of `box` and moves the eye so
 * that the box's bounding sphere just fits the smaller of the vertical and
 * horizontal fields of view (scaled by 1/fill, fill in (0, SCENE_FILL_MAX];
 * fill = 1 touches the viewport edges); near/far bracket the sphere.  Orthographic
 * cameras get height = 2 r / fill (divided by aspect when aspect < 1). */
void scene_camera_fit(SceneCamera *c, SceneBox box, double fill);
/* Tighter: same direction and target (the box centre), but the eye is
 * placed so that the box's 8 corners project inside [-fill, fill] in both
 * x and y (exact for a fixed direction: the closest such eye).
 * Orthographic: the smallest height that holds the corners. */
void scene_camera_fit_box(SceneCamera *c, SceneBox box, double fill);
/* The same for any n >= 1 points (target: the centre of their box). */
void scene_camera_fit_points(SceneCamera *c, const Vec3 *pts, guint n,
                             double fill);

typedef enum {
    SCENE_PATH_FIXED,
    SCENE_PATH_ORBIT,
    SCENE_PATH_KEYFRAMES
} ScenePathKind;

typedef enum { SCENE_INTERP_LINEAR, SCENE_INTERP_CATMULL_ROM } SceneInterp;

typedef struct SceneCameraPath SceneCameraPath;

/* Each returns a new path (free with scene_path_free()); the camera is
 * copied.  `frames` is the animation length a runner should use (>= 1). */
SceneCameraPath *scene_path_new_fixed(const SceneCamera *c, guint frames);
/* Frame f rotates `base` about the line through `center` along `axis` by
 * deg0 + f * deg_per_frame degrees (right-handed). */
SceneCameraPath *scene_path_new_orbit(const SceneCamera *base, Vec3 center,
                                      Vec3 axis, double deg0,
                                      double deg_per_frame, guint frames);
/* Keyframed path; add keys with scene_path_add_key() in increasing frame
 * order (asserted).  frames = last key's frame + 1 unless set larger. */
SceneCameraPath *scene_path_new_keyframes(SceneInterp interp);
void scene_path_add_key(SceneCameraPath *p, double frame, const SceneCamera *c);
void scene_path_free(SceneCameraPath *p);

ScenePathKind scene_path_kind(const SceneCameraPath *p);
guint scene_path_n_frames(const SceneCameraPath *p);
void scene_path_set_n_frames(SceneCameraPath *p, guint frames);
/* Makes `c` the camera of frame 0 of a fixed or orbit path (an orbit
 * keeps its centre, axis and angles: its base becomes c rotated back by
 * the start angle).  Keyframed paths cannot be re-based (asserted). */
void scene_path_set_base(SceneCameraPath *p, const SceneCamera *c);
guint scene_path_n_keys(const SceneCameraPath *p);
SceneCamera scene_path_camera(const SceneCameraPath *p, double frame);

#endif
