/* mesh.c — polygon meshes and axis-aligned bounding boxes.
 *
 * Implements mesh.h.  Polygons are stored CSR-style (start/idx arrays) so
 * that a mesh of any polygon mix costs 4 bytes per index plus 4 per
 * polygon.  Normals use Newell's method (robust for non-planar polygons;
 * Sutherland, Sproull & Schumacker, "A characterization of ten hidden-
 * surface algorithms", 1974).  All operations are O(size of the mesh).
 */
#include "sim/scene/mesh.h"

#include <float.h>
#include <string.h>

SceneBox scene_box_empty(void)
{
    SceneBox b = {{DBL_MAX, DBL_MAX, DBL_MAX}, {-DBL_MAX, -DBL_MAX, -DBL_MAX}};
    return b;
}

gboolean scene_box_is_empty(SceneBox b)
{
    return b.min.x > b.max.x || b.min.y > b.max.y || b.min.z > b.max.z;
}

SceneBox scene_box_add_point(SceneBox b, Vec3 p)
{
    b.min = vec3(fmin(b.min.x, p.x), fmin(b.min.y, p.y), fmin(b.min.z, p.z));
    b.max = vec3(fmax(b.max.x, p.x), fmax(b.max.y, p.y), fmax(b.max.z, p.z));
    return b;
}

SceneBox scene_box_union(SceneBox a, SceneBox b)
{
    if (scene_box_is_empty(a))
        return b;
    if (scene_box_is_empty(b))
        return a;
    return scene_box_add_point(scene_box_add_point(a, b.min), b.max);
}

SceneBox scene_box_transform(SceneBox b, Mat4 m)
{
    SceneBox r = scene_box_empty();
    if (scene_box_is_empty(b))
        return r;
    for (int i = 0; i < 8; i++) {
        Vec3 c = vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y,
                      i & 4 ? b.max.z : b.min.z);
        Vec4 h = mat4_apply_point(m, c);
        double w = (h.w != 0.0 && h.w != 1.0) ? 1.0 / h.w : 1.0;
        r = scene_box_add_point(r, vec3(h.x * w, h.y * w, h.z * w));
    }
    return r;
}

Vec3 scene_box_center(SceneBox b)
{
    if (scene_box_is_empty(b))
        return vec3(0, 0, 0);
    return vec3_scale(vec3_add(b.min, b.max), 0.5);
}

Vec3 scene_box_size(SceneBox b)
{
    if (scene_box_is_empty(b))
        return vec3(0, 0, 0);
    return vec3_sub(b.max, b.min);
}

double scene_box_radius(SceneBox b)
{
    return 0.5 * vec3_len(scene_box_size(b));
}

gboolean scene_box_contains(SceneBox b, Vec3 p)
{
    return p.x >= b.min.x && p.x <= b.max.x && p.y >= b.min.y &&
           p.y <= b.max.y && p.z >= b.min.z && p.z <= b.max.z;
}

gboolean scene_box_overlaps(SceneBox a, SceneBox b)
{
    if (scene_box_is_empty(a) || scene_box_is_empty(b))
        return FALSE;
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y &&
           b.min.y <= a.max.y && a.min.z <= b.max.z && b.min.z <= a.max.z;
}

SceneMesh *scene_mesh_new(void)
{
    SceneMesh *m = g_new0(SceneMesh, 1);
    uint32_t zero = 0;
    m->pos = g_array_new(FALSE, FALSE, sizeof(Vec3));
    m->normals = g_array_new(FALSE, FALSE, sizeof(Vec3));
    m->colors = g_array_new(FALSE, FALSE, sizeof(SceneColor));
    m->start = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    m->idx = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    m->poly_color = g_array_new(FALSE, FALSE, sizeof(SceneColor));
    m->poly_tag = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g_array_append_val(m->start, zero);
    return m;
}

void scene_mesh_free(SceneMesh *m)
{
    if (!m)
        return;
    g_array_free(m->pos, TRUE);
    g_array_free(m->normals, TRUE);
    g_array_free(m->colors, TRUE);
    g_array_free(m->start, TRUE);
    g_array_free(m->idx, TRUE);
    g_array_free(m->poly_color, TRUE);
    g_array_free(m->poly_tag, TRUE);
    g_free(m);
}

static GArray *array_copy(const GArray *a)
{
    guint es = g_array_get_element_size((GArray *)a);
    GArray *r = g_array_sized_new(FALSE, FALSE, es, a->len);
    g_array_append_vals(r, a->data, a->len);
    return r;
}

SceneMesh *scene_mesh_copy(const SceneMesh *m)
{
    SceneMesh *r = g_new0(SceneMesh, 1);
    r->pos = array_copy(m->pos);
    r->normals = array_copy(m->normals);
    r->colors = array_copy(m->colors);
    r->start = array_copy(m->start);
    r->idx = array_copy(m->idx);
    r->poly_color = array_copy(m->poly_color);
    r->poly_tag = array_copy(m->poly_tag);
    return r;
}

uint32_t scene_mesh_add_vertex(SceneMesh *m, Vec3 p)
{
    g_array_append_val(m->pos, p);
    return m->pos->len - 1;
}

uint32_t scene_mesh_add_poly(SceneMesh *m, const uint32_t *idx, guint n,
                             SceneColor c, uint32_t tag)
{
    g_assert(n >= 3);
    g_array_append_vals(m->idx, idx, n);
    uint32_t end = m->idx->len;
    g_array_append_val(m->start, end);
    g_array_append_val(m->poly_color, c);
    g_array_append_val(m->poly_tag, tag);
    return m->poly_color->len - 1;
}

uint32_t scene_mesh_add_tri(SceneMesh *m, uint32_t a, uint32_t b, uint32_t c,
                            SceneColor col, uint32_t tag)
{
    uint32_t v[3] = {a, b, c};
    return scene_mesh_add_poly(m, v, 3, col, tag);
}

uint32_t scene_mesh_add_quad(SceneMesh *m, uint32_t a, uint32_t b, uint32_t c,
                             uint32_t d, SceneColor col, uint32_t tag)
{
    uint32_t v[4] = {a, b, c, d};
    return scene_mesh_add_poly(m, v, 4, col, tag);
}

uint64_t scene_mesh_n_triangles(const SceneMesh *m)
{
    uint64_t t = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++)
        t += scene_mesh_poly_len(m, i) - 2;
    return t;
}

guint scene_mesh_count_ngons(const SceneMesh *m, guint k)
{
    guint c = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++)
        c += scene_mesh_poly_len(m, i) == k;
    return c;
}

SceneBox scene_mesh_bbox(const SceneMesh *m)
{
    SceneBox b = scene_box_empty();
    for (guint i = 0; i < m->pos->len; i++)
        b = scene_box_add_point(b, g_array_index(m->pos, Vec3, i));
    return b;
}

/* Unnormalised Newell normal: twice the polygon's area vector. */
static Vec3 newell(const SceneMesh *m, guint i)
{
    guint n = scene_mesh_poly_len(m, i);
    const uint32_t *v = scene_mesh_poly(m, i);
    Vec3 s = vec3(0, 0, 0);
    for (guint k = 0; k < n; k++) {
        Vec3 a = scene_mesh_vertex(m, v[k]);
        Vec3 b = scene_mesh_vertex(m, v[(k + 1) % n]);
        s.x += (a.y - b.y) * (a.z + b.z);
        s.y += (a.z - b.z) * (a.x + b.x);
        s.z += (a.x - b.x) * (a.y + b.y);
    }
    return s;
}

Vec3 scene_mesh_poly_normal(const SceneMesh *m, guint i)
{
    return vec3_norm(newell(m, i));
}

void scene_mesh_compute_normals(SceneMesh *m)
{
    g_array_set_size(m->normals, m->pos->len);
    memset(m->normals->data, 0, sizeof(Vec3) * m->pos->len);
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        Vec3 nrm = newell(m, i);
        const uint32_t *v = scene_mesh_poly(m, i);
        for (guint k = 0; k < scene_mesh_poly_len(m, i); k++) {
            Vec3 *d = &g_array_index(m->normals, Vec3, v[k]);
            *d = vec3_add(*d, nrm);
        }
    }
    for (guint i = 0; i < m->normals->len; i++) {
        Vec3 *d = &g_array_index(m->normals, Vec3, i);
        *d = vec3_norm(*d);
    }
}

static Vec3 xform_point(Mat4 m, Vec3 p)
{
    Vec4 h = mat4_apply_point(m, p);
    if (h.w != 1.0 && h.w != 0.0)
        return vec3(h.x / h.w, h.y / h.w, h.z / h.w);
    return vec3(h.x, h.y, h.z);
}

static void append_vertices(SceneMesh *dst, const SceneMesh *src, Mat4 xf)
{
    guint base = dst->pos->len;
    gboolean want_n =
        src->normals->len > 0 && (base == 0 || dst->normals->len == base);
    gboolean want_c =
        src->colors->len > 0 && (base == 0 || dst->colors->len == base);
    Mat4 nm = mat4_normal_matrix(xf);
    for (guint i = 0; i < src->pos->len; i++)
        scene_mesh_add_vertex(dst, xform_point(xf, scene_mesh_vertex(src, i)));
    if (want_n)
        for (guint i = 0; i < src->normals->len; i++) {
            Vec3 n = g_array_index(src->normals, Vec3, i);
            Vec4 h = mat4_apply(nm, (Vec4){n.x, n.y, n.z, 0});
            Vec3 r = vec3_norm(vec3(h.x, h.y, h.z));
            g_array_append_val(dst->normals, r);
        }
    else
        g_array_set_size(dst->normals, 0);
    if (want_c)
        g_array_append_vals(dst->colors, src->colors->data, src->colors->len);
    else
        g_array_set_size(dst->colors, 0);
}

void scene_mesh_append(SceneMesh *dst, const SceneMesh *src, Mat4 xf)
{
    g_assert(dst != src);
    uint32_t base = dst->pos->len;
    append_vertices(dst, src, xf);
    for (guint i = 0; i < src->idx->len; i++) {
        uint32_t v = g_array_index(src->idx, uint32_t, i) + base;
        g_array_append_val(dst->idx, v);
    }
    uint32_t off = g_array_index(dst->start, uint32_t, dst->start->len - 1);
    for (guint i = 1; i < src->start->len; i++) {
        uint32_t s = g_array_index(src->start, uint32_t, i) + off;
        g_array_append_val(dst->start, s);
    }
    g_array_append_vals(dst->poly_color, src->poly_color->data,
                        src->poly_color->len);
    g_array_append_vals(dst->poly_tag, src->poly_tag->data, src->poly_tag->len);
}

static gboolean fail(GError **err, const char *what, const char *msg, guint i)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "%s: polygon %u: found %s, expected a valid polygon", what, i,
                msg);
    return FALSE;
}

gboolean scene_mesh_validate(const SceneMesh *m, const char *what, GError **err)
{
    guint nv = m->pos->len, np = scene_mesh_n_polys(m);
    g_assert(m->start->len == np + 1 && m->poly_tag->len == np);
    g_assert(m->normals->len == 0 || m->normals->len == nv);
    g_assert(m->colors->len == 0 || m->colors->len == nv);
    for (guint i = 0; i < np; i++) {
        if (scene_mesh_poly_len(m, i) < 3)
            return fail(err, what, "fewer than 3 vertices", i);
        const uint32_t *v = scene_mesh_poly(m, i);
        for (guint k = 0; k < scene_mesh_poly_len(m, i); k++)
            if (v[k] >= nv)
                return fail(err, what, "a vertex index out of range", i);
    }
    return TRUE;
}
