/* mesh.h — polygon meshes and axis-aligned bounding boxes.
 *
 * A SceneMesh is an indexed polygon list: vertex positions (Vec3), optional
 * per-vertex normals and colours (either empty or one per vertex), and
 * polygons stored CSR-style: polygon i uses indices
 * idx[start[i] .. start[i+1]) and has colour poly_color[i] and a tag
 * poly_tag[i] (a part / structure id; 0 when unused).  Polygons are
 * planar-ish and convex as generated; consumers that need triangles
 * fan-triangulate (a polygon of n vertices counts n - 2 triangles).
 *
 * Invariants: start has n_polys + 1 entries, start[0] == 0, every polygon
 * has >= 3 indices, every index < n_vertices (checked by
 * scene_mesh_validate()).  Fields are public for fast read access by the
 * rasteriser; mutate through the functions so the invariants hold.
 * Appends are amortised O(1); bounds O(n).
 */
#ifndef PGSIM_SCENE_MESH_H
#define PGSIM_SCENE_MESH_H

#include "sim/core/error.h"
#include "sim/scene/vec.h"
#include <stdint.h>

/* Linear RGB in [0, 1]. */
typedef struct {
    float r, g, b;
} SceneColor;

static inline SceneColor scene_color(float r, float g, float b)
{
    return (SceneColor){r, g, b};
}

/* Axis-aligned box; empty when min > max on any axis. */
typedef struct {
    Vec3 min, max;
} SceneBox;

SceneBox scene_box_empty(void);
gboolean scene_box_is_empty(SceneBox b);
SceneBox scene_box_add_point(SceneBox b, Vec3 p);
SceneBox scene_box_union(SceneBox a, SceneBox b);
/* Box of the 8 transformed corners (w-divided when w != 1): a conservative
 * bound of the transformed contents.  Empty stays empty. */
SceneBox scene_box_transform(SceneBox b, Mat4 m);
Vec3 scene_box_center(SceneBox b);
Vec3 scene_box_size(SceneBox b);
/* Radius of the sphere about the centre through the corners (0 if empty). */
double scene_box_radius(SceneBox b);
gboolean scene_box_contains(SceneBox b, Vec3 p);
gboolean scene_box_overlaps(SceneBox a, SceneBox b);

typedef struct {
    GArray *pos;        /* Vec3 */
    GArray *normals;    /* Vec3: empty or one per vertex */
    GArray *colors;     /* SceneColor: empty or one per vertex */
    GArray *start;      /* uint32_t, n_polys + 1 entries */
    GArray *idx;        /* uint32_t vertex indices */
    GArray *poly_color; /* SceneColor per polygon */
    GArray *poly_tag;   /* uint32_t per polygon */
} SceneMesh;

/* Returns a new empty mesh; free with scene_mesh_free(). */
SceneMesh *scene_mesh_new(void);
void scene_mesh_free(SceneMesh *m);
SceneMesh *scene_mesh_copy(const SceneMesh *m);

/* Appends a vertex; returns its index. */
uint32_t scene_mesh_add_vertex(SceneMesh *m, Vec3 p);
/* Appends a polygon of n >= 3 indices (copied); returns its index. */
uint32_t scene_mesh_add_poly(SceneMesh *m, const uint32_t *idx, guint n,
                             SceneColor c, uint32_t tag);
uint32_t scene_mesh_add_tri(SceneMesh *m, uint32_t a, uint32_t b, uint32_t c,
                            SceneColor col, uint32_t tag);
uint32_t scene_mesh_add_quad(SceneMesh *m, uint32_t a, uint32_t b, uint32_t c,
                             uint32_t d, SceneColor col, uint32_t tag);

static inline guint scene_mesh_n_vertices(const SceneMesh *m)
{
    return m->pos->len;
}
static inline guint scene_mesh_n_polys(const SceneMesh *m)
{
    return m->poly_color->len;
}
static inline Vec3 scene_mesh_vertex(const SceneMesh *m, guint i)
{
    return g_array_index(m->pos, Vec3, i);
}
static inline guint scene_mesh_poly_len(const SceneMesh *m, guint i)
{
    return g_array_index(m->start, uint32_t, i + 1) -
           g_array_index(m->start, uint32_t, i);
}
/* The polygon's indices (borrowed, valid until the next append). */
static inline const uint32_t *scene_mesh_poly(const SceneMesh *m, guint i)
{
    return &g_array_index(m->idx, uint32_t,
                          g_array_index(m->start, uint32_t, i));
}

/* Sum over polygons of (n - 2): the triangle count after fan splitting. */
uint64_t scene_mesh_n_triangles(const SceneMesh *m);
/* Polygons with exactly k vertices. */
guint scene_mesh_count_ngons(const SceneMesh *m, guint k);
SceneBox scene_mesh_bbox(const SceneMesh *m);
/* Newell-method normal of polygon i (unit, or 0 if degenerate). */
Vec3 scene_mesh_poly_normal(const SceneMesh *m, guint i);
/* Fills per-vertex normals as the area-weighted mean of adjacent polygon
 * normals (replacing any present). */
void scene_mesh_compute_normals(SceneMesh *m);
/* Appends src transformed by xf (normals by the inverse transpose of the
 * upper 3x3, renormalised); per-vertex arrays are kept only if both meshes
 * have them (or dst is empty). */
void scene_mesh_append(SceneMesh *dst, const SceneMesh *src, Mat4 xf);
/* Checks the invariants; an input error names `what` (a file name). */
gboolean scene_mesh_validate(const SceneMesh *m, const char *what,
                             GError **err);

#endif
