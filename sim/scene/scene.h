/* scene.h — a renderable scene: mesh instances, a camera, a background.
 *
 * A Scene owns a list of meshes and a list of instances; an instance
 * names a mesh by index, places it with a model matrix and modulates the
 * mesh's polygon colours by its colour (white leaves them unchanged).
 * Several instances may share one mesh (the vehicle scene instances one
 * model three times).  The camera path (optional, NULL = fixed camera)
 * animates the camera over frames.  A tag on each instance carries the
 * generator's grouping (teapot number, structure id ...).
 * Adding is amortised O(1); counts and bounds are O(instances + vertices).
 */
#ifndef PGSIM_SCENE_SCENE_H
#define PGSIM_SCENE_SCENE_H

#include "sim/scene/camera.h"
#include "sim/scene/structdb.h"

typedef struct {
    guint mesh;       /* index into Scene.meshes */
    Mat4 xform;       /* model -> world */
    SceneColor color; /* multiplies polygon colours */
    uint32_t tag;
} SceneInstance;

typedef struct {
    char *name;            /* generator or file name */
    GPtrArray *meshes;     /* SceneMesh *, owned */
    GArray *instances;     /* SceneInstance */
    SceneCamera camera;    /* frame-0 camera */
    SceneCameraPath *path; /* owned, may be NULL (fixed camera) */
    SceneColor background;
    guint width, height; /* suggested viewport in pixels (0 = unset) */
    gboolean two_sided;  /* open surfaces whose back faces show: a quick
                            look should not cull them (default FALSE) */
    SceneDb *db;         /* optional hierarchical form (owned), or NULL */
} Scene;

/* The view rule shared by the generators: the eye looks at the scene's
 * bounding-box centre from direction (azimuth about +y from +z, elevation
 * above the x-z plane, degrees) and is fitted with scene_camera_fit() so
 * the bounding sphere fills `fill` of the smaller viewport extent (or,
 * with fit_box, the corners of every instance's box project inside
 * [-fill, fill]; with fit_vertices, every vertex of every instance does:
 * the silhouette touches the scaled viewport). */
typedef struct {
    SceneProjection proj;
    double azimuth_deg, elevation_deg;
    double fov_deg;        /* perspective */
    double fill;           /* (0, 1] */
    double aspect;         /* width / height */
    gboolean fit_box;      /* fit the instances' box corners instead of
                              the bounding sphere */
    gboolean fit_vertices; /* fit every instance vertex (tightest) */
} SceneView;

/* azimuth 0, elevation 0, perspective 45°, fill 1, aspect 1, sphere. */
SceneView scene_view_default(void);
/* Sets s->camera by the view rule (keeps any path). */
void scene_apply_view(Scene *s, const SceneView *v);

/* Returns a new empty scene (default camera, black background); free with
 * scene_free().  `name` is copied. */
Scene *scene_new(const char *name);
void scene_free(Scene *s);
/* The scene of an Argus application (seed 002: march, nurbs): mesh m
 * (taken) drawn once, white, two-sided, on a 1200 x 1000 screen, seen
 * from azimuth_deg and elevation_deg with the view fitted to its
 * vertices to cover `fill` of it. */
Scene *scene_new_app(const char *name, SceneMesh *m, double azimuth_deg,
                     double elevation_deg, double fill);

/* Takes ownership of m; returns its index. */
guint scene_add_mesh(Scene *s, SceneMesh *m);
/* Returns the instance index. */
guint scene_add_instance(Scene *s, guint mesh, Mat4 xform, SceneColor color,
                         uint32_t tag);
/* Takes ownership of db (frees any previous one). */
void scene_set_db(Scene *s, SceneDb *db);
/* Takes ownership of path (frees any previous one). */
void scene_set_path(Scene *s, SceneCameraPath *path);

static inline guint scene_n_instances(const Scene *s)
{
    return s->instances->len;
}
static inline const SceneInstance *scene_instance(const Scene *s, guint i)
{
    return &g_array_index(s->instances, SceneInstance, i);
}
static inline const SceneMesh *scene_instance_mesh(const Scene *s, guint i)
{
    return g_ptr_array_index(s->meshes, scene_instance(s, i)->mesh);
}

/* The camera of frame f: the path's if any, else s->camera. */
SceneCamera scene_camera_at(const Scene *s, double frame);
/* Polygons / fan triangles / vertices over all instances. */
uint64_t scene_n_polys(const Scene *s);
uint64_t scene_n_triangles(const Scene *s);
uint64_t scene_n_vertices(const Scene *s);
/* World-space bounds of all instances (each mesh's box transformed). */
SceneBox scene_bbox(const Scene *s);
/* Exact world-space box of one instance (transforms every vertex). */
SceneBox scene_instance_bbox(const Scene *s, guint i);
/* One world-space mesh of every instance (colours modulated, tags from
 * the polygons); a new mesh, free with scene_mesh_free(). */
SceneMesh *scene_flatten(const Scene *s);

#endif
