/* pn_triangles.c — curved PN triangles: control nets, evaluation and
 * tessellation (see pn_triangles.h for the construction and citation).
 *
 * Invariants: a corner of the grid returns the input position and unit
 * normal exactly; a point on an edge is computed from that edge's two
 * vertices only, with the endpoints in a canonical (lexicographic)
 * order, so neighbours agree bit for bit.  Interior points use the whole
 * patch.  O((L + 1)^2) per input triangle.
 */
#include "sim/scene/pn_triangles.h"

#include <string.h>

/* ---- control net ------------------------------------------------------- */

/* (2 Pi + Pj - w_ij Ni) / 3: the edge point nearest Pi, projected onto
 * Pi's tangent plane. */
static Vec3 tangent_point(Vec3 pi, Vec3 ni, Vec3 pj)
{
    double w = vec3_dot(vec3_sub(pj, pi), ni);
    Vec3 s = vec3_add(vec3_scale(pi, 2), pj);
    return vec3_scale(vec3_sub(s, vec3_scale(ni, w)), 1.0 / 3.0);
}

/* n_ij = h / |h|, h = Ni + Nj - v_ij (Pj - Pi). */
static Vec3 mid_normal(Vec3 pi, Vec3 ni, Vec3 pj, Vec3 nj)
{
    Vec3 d = vec3_sub(pj, pi);
    double dd = vec3_dot(d, d);
    g_assert(dd > 0);
    double v = 2 * vec3_dot(d, vec3_add(ni, nj)) / dd;
    return vec3_norm(vec3_sub(vec3_add(ni, nj), vec3_scale(d, v)));
}

void scene_pn_patch(ScenePnPatch *pt, const Vec3 P[3], const Vec3 N[3])
{
    for (int i = 0; i < 3; i++) {
        pt->p[i] = P[i];
        pt->n[i] = vec3_norm(N[i]);
    }
    const Vec3 *p = pt->p, *n = pt->n;
    pt->b210 = tangent_point(p[0], n[0], p[1]);
    pt->b120 = tangent_point(p[1], n[1], p[0]);
    pt->b021 = tangent_point(p[1], n[1], p[2]);
    pt->b012 = tangent_point(p[2], n[2], p[1]);
    pt->b102 = tangent_point(p[2], n[2], p[0]);
    pt->b201 = tangent_point(p[0], n[0], p[2]);
    Vec3 e = vec3_add(vec3_add(pt->b210, pt->b120), pt->b021);
    e = vec3_add(vec3_add(e, pt->b012), vec3_add(pt->b102, pt->b201));
    e = vec3_scale(e, 1.0 / 6.0);
    Vec3 v = vec3_scale(vec3_add(vec3_add(p[0], p[1]), p[2]), 1.0 / 3.0);
    pt->b111 = vec3_add(e, vec3_scale(vec3_sub(e, v), 0.5));
    pt->n110 = mid_normal(p[0], n[0], p[1], n[1]);
    pt->n011 = mid_normal(p[1], n[1], p[2], n[2]);
    pt->n101 = mid_normal(p[2], n[2], p[0], n[0]);
}

/* ---- evaluation -------------------------------------------------------- */

static Vec3 madd(Vec3 acc, Vec3 a, double s)
{
    return vec3_add(acc, vec3_scale(a, s));
}

Vec3 scene_pn_point(const ScenePnPatch *pt, double u, double v)
{
    double w = 1 - u - v;
    Vec3 r = vec3_scale(pt->p[0], w * w * w);
    r = madd(r, pt->p[1], u * u * u);
    r = madd(r, pt->p[2], v * v * v);
    r = madd(r, pt->b210, 3 * w * w * u);
    r = madd(r, pt->b120, 3 * w * u * u);
    r = madd(r, pt->b201, 3 * w * w * v);
    r = madd(r, pt->b021, 3 * u * u * v);
    r = madd(r, pt->b102, 3 * w * v * v);
    r = madd(r, pt->b012, 3 * u * v * v);
    return madd(r, pt->b111, 6 * w * u * v);
}

Vec3 scene_pn_normal(const ScenePnPatch *pt, ScenePnNormals kind, double u,
                     double v)
{
    double w = 1 - u - v;
    if (kind == SCENE_PN_LINEAR) {
        Vec3 r = vec3_scale(pt->n[0], w);
        return vec3_norm(madd(madd(r, pt->n[1], u), pt->n[2], v));
    }
    Vec3 r = vec3_scale(pt->n[0], w * w);
    r = madd(r, pt->n[1], u * u);
    r = madd(r, pt->n[2], v * v);
    r = madd(r, pt->n110, w * u);
    r = madd(r, pt->n011, u * v);
    return vec3_norm(madd(r, pt->n101, w * v));
}

/* ---- edges in canonical order ------------------------------------------ */

/* Whether a comes after b in (x, y, z) order; a != b (a patch has no
 * zero-length edge: scene_pn_patch asserts it in mid_normal). */
static gboolean after(Vec3 a, Vec3 b)
{
    if (a.x != b.x)
        return a.x > b.x;
    if (a.y != b.y)
        return a.y > b.y;
    return a.z > b.z;
}

/* One end of an edge: its corner and the corner's normal. */
typedef struct {
    Vec3 p, n;
} EdgeEnd;

/* The point `sb` steps of `steps` from end a towards end b on the
 * edge's cubic, and its normal: computed from the edge alone. */
static void edge_eval(EdgeEnd a, EdgeEnd b, guint sb, guint steps,
                      ScenePnNormals kind, Vec3 *pos, Vec3 *nrm)
{
    if (after(a.p, b.p)) {
        edge_eval(b, a, steps - sb, steps, kind, pos, nrm);
        return;
    }
    Vec3 pa = a.p, na = a.n, pb = b.p, nb = b.n;
    double t = (double)sb / steps, s = 1 - t;
    Vec3 bab = tangent_point(pa, na, pb), bba = tangent_point(pb, nb, pa);
    Vec3 r = vec3_scale(pa, s * s * s);
    r = madd(madd(r, bab, 3 * s * s * t), bba, 3 * s * t * t);
    *pos = madd(r, pb, t * t * t);
    if (kind == SCENE_PN_LINEAR) {
        *nrm = vec3_norm(madd(vec3_scale(na, s), nb, t));
        return;
    }
    Vec3 m = mid_normal(pa, na, pb, nb);
    *nrm = vec3_norm(madd(madd(vec3_scale(na, s * s), nb, t * t), m, s * t));
}

/* Grid point (i, j, k), i + j + k = steps, weights (w, u, v) = (i, j, k)
 * / steps of (P1, P2, P3). */
static void grid_eval(const ScenePnPatch *pt, ScenePnNormals kind, guint i,
                      guint j, guint k, Vec3 *pos, Vec3 *nrm)
{
    guint steps = i + j + k, c = i == steps ? 0 : j == steps ? 1 : 2;
    if (i == steps || j == steps || k == steps) {
        *pos = pt->p[c];
        *nrm = pt->n[c];
    } else if (k == 0) {
        edge_eval((EdgeEnd){pt->p[0], pt->n[0]}, (EdgeEnd){pt->p[1], pt->n[1]},
                  j, steps, kind, pos, nrm);
    } else if (i == 0) {
        edge_eval((EdgeEnd){pt->p[1], pt->n[1]}, (EdgeEnd){pt->p[2], pt->n[2]},
                  k, steps, kind, pos, nrm);
    } else if (j == 0) {
        edge_eval((EdgeEnd){pt->p[2], pt->n[2]}, (EdgeEnd){pt->p[0], pt->n[0]},
                  i, steps, kind, pos, nrm);
    } else {
        double u = (double)j / steps, v = (double)k / steps;
        *pos = scene_pn_point(pt, u, v);
        *nrm = scene_pn_normal(pt, kind, u, v);
    }
}

/* ---- tessellation ------------------------------------------------------ */

/* Index of grid point (j, k) in a triangle's block of vertices. */
static uint32_t grid_index(uint32_t base, guint steps, guint j, guint k)
{
    /* rows by k: row k holds steps - k + 1 points */
    guint before = k * (steps + 1) - k * (k - 1) / 2;
    return base + before + j;
}

static void tessellate_tri(SceneMesh *out, const ScenePnPatch *pt,
                           const ScenePnParams *p, SceneColor col, uint32_t tag)
{
    guint n = p->level + 1;
    uint32_t base = scene_mesh_n_vertices(out);
    for (guint k = 0; k <= n; k++)
        for (guint j = 0; j + k <= n; j++) {
            Vec3 pos, nrm;
            grid_eval(pt, p->normals, n - j - k, j, k, &pos, &nrm);
            scene_mesh_add_vertex(out, pos);
            g_array_append_val(out->normals, nrm);
        }
    for (guint k = 0; k < n; k++)
        for (guint j = 0; j + k < n; j++) {
            scene_mesh_add_tri(out, grid_index(base, n, j, k),
                               grid_index(base, n, j + 1, k),
                               grid_index(base, n, j, k + 1), col, tag);
            if (j + k + 1 < n)
                scene_mesh_add_tri(out, grid_index(base, n, j + 1, k),
                                   grid_index(base, n, j + 1, k + 1),
                                   grid_index(base, n, j, k + 1), col, tag);
        }
}

/* The PN patch of fan triangle (a, b, c) of a mesh with normals. */
static void mesh_patch(const SceneMesh *m, const uint32_t ix[3],
                       ScenePnPatch *pt)
{
    Vec3 P[3], N[3];
    for (int i = 0; i < 3; i++) {
        P[i] = scene_mesh_vertex(m, ix[i]);
        N[i] = g_array_index(m->normals, Vec3, ix[i]);
    }
    scene_pn_patch(pt, P, N);
}

SceneMesh *scene_pn_tessellate(const SceneMesh *m, const ScenePnParams *p)
{
    SceneMesh *own = NULL;
    if (m->normals->len != scene_mesh_n_vertices(m)) {
        own = scene_mesh_copy(m);
        scene_mesh_compute_normals(own);
        m = own;
    }
    SceneMesh *out = scene_mesh_new();
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *ix = scene_mesh_poly(m, i);
        SceneColor col = g_array_index(m->poly_color, SceneColor, i);
        uint32_t tag = g_array_index(m->poly_tag, uint32_t, i);
        for (guint t = 1; t + 1 < scene_mesh_poly_len(m, i); t++) {
            uint32_t tri[3] = {ix[0], ix[t], ix[t + 1]};
            ScenePnPatch pt;
            mesh_patch(m, tri, &pt);
            tessellate_tri(out, &pt, p, col, tag);
        }
    }
    scene_mesh_free(own);
    return out;
}

void scene_pn_apply(Scene *s, const ScenePnParams *p)
{
    for (guint i = 0; i < s->meshes->len; i++) {
        SceneMesh *m = g_ptr_array_index(s->meshes, i);
        g_ptr_array_index(s->meshes, i) = scene_pn_tessellate(m, p);
        scene_mesh_free(m);
    }
    scene_set_db(s, NULL);
}
