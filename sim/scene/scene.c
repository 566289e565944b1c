/* scene.c — a renderable scene: mesh instances, a camera, a background.
 *
 * Implements scene.h.  Instances reference meshes by index, so a mesh is
 * stored once however often it is drawn; scene_flatten() expands them
 * for consumers that want one world-space list.  O(instances) bookkeeping
 * plus O(vertices) for bounds and flattening.
 */
#include "sim/scene/scene.h"

Scene *scene_new(const char *name)
{
    Scene *s = g_new0(Scene, 1);
    s->name = g_strdup(name ? name : "scene");
    s->meshes = g_ptr_array_new_with_free_func((GDestroyNotify)scene_mesh_free);
    s->instances = g_array_new(FALSE, FALSE, sizeof(SceneInstance));
    s->camera = scene_camera_default();
    s->background = scene_color(0, 0, 0);
    return s;
}

Scene *scene_new_app(const char *name, SceneMesh *m, double azimuth_deg,
                     double elevation_deg, double fill)
{
    Scene *s = scene_new(name);
    guint id = scene_add_mesh(s, m);
    scene_add_instance(s, id, mat4_identity(), scene_color(1, 1, 1), 0);
    s->width = 1200;
    s->height = 1000;
    s->two_sided = TRUE;
    SceneView v = scene_view_default();
    v.azimuth_deg = azimuth_deg;
    v.elevation_deg = elevation_deg;
    v.aspect = 1.2;
    v.fill = fill;
    v.fit_vertices = TRUE;
    scene_apply_view(s, &v);
    return s;
}

void scene_free(Scene *s)
{
    if (!s)
        return;
    g_free(s->name);
    g_ptr_array_free(s->meshes, TRUE);
    g_array_free(s->instances, TRUE);
    scene_path_free(s->path);
    scene_db_free(s->db);
    g_free(s);
}

guint scene_add_mesh(Scene *s, SceneMesh *m)
{
    g_assert(m);
    g_ptr_array_add(s->meshes, m);
    return s->meshes->len - 1;
}

guint scene_add_instance(Scene *s, guint mesh, Mat4 xform, SceneColor color,
                         uint32_t tag)
{
    g_assert(mesh < s->meshes->len);
    SceneInstance in = {mesh, xform, color, tag};
    g_array_append_val(s->instances, in);
    return s->instances->len - 1;
}

void scene_set_db(Scene *s, SceneDb *db)
{
    if (db != s->db)
        scene_db_free(s->db);
    s->db = db;
}

SceneView scene_view_default(void)
{
    SceneView v = {SCENE_PERSPECTIVE, 0, 0, 45, 1, 1, FALSE, FALSE};
    return v;
}

/* Fits the corners of every instance's box (tighter than the scene box
 * when instances lie along a diagonal). */
static void fit_instance_boxes(const Scene *s, SceneCamera *c, double fill)
{
    guint n = scene_n_instances(s);
    Vec3 *pts = g_new(Vec3, 8 * n);
    for (guint i = 0; i < n; i++) {
        SceneBox b =
            scene_box_transform(scene_mesh_bbox(scene_instance_mesh(s, i)),
                                scene_instance(s, i)->xform);
        for (int k = 0; k < 8; k++)
            pts[8 * i + k] =
                vec3(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y,
                     k & 4 ? b.max.z : b.min.z);
    }
    scene_camera_fit_points(c, pts, 8 * n, fill);
    g_free(pts);
}

/* Fits every vertex of every instance (the silhouette).  O(vertices x
 * instances). */
static void fit_instance_vertices(const Scene *s, SceneCamera *c, double fill)
{
    GArray *pts = g_array_new(FALSE, FALSE, sizeof(Vec3));
    for (guint i = 0; i < scene_n_instances(s); i++) {
        const SceneMesh *m = scene_instance_mesh(s, i);
        Mat4 x = scene_instance(s, i)->xform;
        for (guint k = 0; k < scene_mesh_n_vertices(m); k++) {
            Vec4 p = mat4_apply_point(x, scene_mesh_vertex(m, k));
            Vec3 q = vec3(p.x / p.w, p.y / p.w, p.z / p.w);
            g_array_append_val(pts, q);
        }
    }
    if (pts->len > 0)
        scene_camera_fit_points(c, (Vec3 *)pts->data, pts->len, fill);
    g_array_free(pts, TRUE);
}

void scene_apply_view(Scene *s, const SceneView *v)
{
    double az = v->azimuth_deg * G_PI / 180, el = v->elevation_deg * G_PI / 180;
    Vec3 dir = vec3(cos(el) * sin(az), sin(el), cos(el) * cos(az));
    SceneCamera c = scene_camera_default();
    c.proj = v->proj;
    c.fov_deg = v->fov_deg;
    c.aspect = v->aspect;
    c.target = vec3(0, 0, 0);
    c.eye = dir;
    c.up = fabs(dir.y) > 0.999 ? vec3(0, 0, -1) : vec3(0, 1, 0);
    if (v->fit_vertices && scene_n_instances(s) > 0)
        fit_instance_vertices(s, &c, v->fill);
    else if (v->fit_box && scene_n_instances(s) > 0)
        fit_instance_boxes(s, &c, v->fill);
    else
        scene_camera_fit(&c, scene_bbox(s), v->fill);
    s->camera = c;
}

void scene_set_path(Scene *s, SceneCameraPath *path)
{
    if (path != s->path)
        scene_path_free(s->path);
    s->path = path;
}

SceneCamera scene_camera_at(const Scene *s, double frame)
{
    return s->path ? scene_path_camera(s->path, frame) : s->camera;
}

uint64_t scene_n_polys(const Scene *s)
{
    uint64_t n = 0;
    for (guint i = 0; i < scene_n_instances(s); i++)
        n += scene_mesh_n_polys(scene_instance_mesh(s, i));
    return n;
}

uint64_t scene_n_triangles(const Scene *s)
{
    uint64_t n = 0;
    for (guint i = 0; i < scene_n_instances(s); i++)
        n += scene_mesh_n_triangles(scene_instance_mesh(s, i));
    return n;
}

uint64_t scene_n_vertices(const Scene *s)
{
    uint64_t n = 0;
    for (guint i = 0; i < scene_n_instances(s); i++)
        n += scene_mesh_n_vertices(scene_instance_mesh(s, i));
    return n;
}

SceneBox scene_bbox(const Scene *s)
{
    SceneBox b = scene_box_empty();
    for (guint i = 0; i < scene_n_instances(s); i++) {
        SceneBox mb = scene_mesh_bbox(scene_instance_mesh(s, i));
        Mat4 xf = scene_instance(s, i)->xform;
        b = scene_box_union(b, scene_box_transform(mb, xf));
    }
    return b;
}

SceneBox scene_instance_bbox(const Scene *s, guint i)
{
    const SceneMesh *m = scene_instance_mesh(s, i);
    Mat4 xf = scene_instance(s, i)->xform;
    SceneBox b = scene_box_empty();
    for (guint v = 0; v < scene_mesh_n_vertices(m); v++) {
        Vec4 h = mat4_apply_point(xf, scene_mesh_vertex(m, v));
        double w = h.w != 0 ? 1.0 / h.w : 1.0;
        b = scene_box_add_point(b, vec3(h.x * w, h.y * w, h.z * w));
    }
    return b;
}

SceneMesh *scene_flatten(const Scene *s)
{
    SceneMesh *out = scene_mesh_new();
    for (guint i = 0; i < scene_n_instances(s); i++) {
        const SceneInstance *in = scene_instance(s, i);
        guint p0 = scene_mesh_n_polys(out);
        scene_mesh_append(out, scene_instance_mesh(s, i), in->xform);
        for (guint p = p0; p < scene_mesh_n_polys(out); p++) {
            SceneColor *c = &g_array_index(out->poly_color, SceneColor, p);
            c->r *= in->color.r;
            c->g *= in->color.g;
            c->b *= in->color.b;
        }
    }
    return out;
}
