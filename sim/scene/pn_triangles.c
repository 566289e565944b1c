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

#include "sim/scene/pn_crease.h"

/* ---- control net ------------------------------------------------------- */

/* (2 Pi + Pj - w_ij Ni) / 3: the edge point nearest Pi, projected onto
 * Pi's tangent plane. */
static Vec3 tangent_point(Vec3 pi, Vec3 ni, Vec3 pj)
{
    double w = vec3_dot(vec3_sub(pj, pi), ni);
    Vec3 s = vec3_add(vec3_scale(pi, 2), pj);
    return vec3_scale(vec3_sub(s, vec3_scale(ni, w)), 1.0 / 3.0);
}

/* Pi + ((Pj - Pi) . ti) ti / 3: the edge point nearest Pi on a crease,
 * from the positions and the crease direction ti alone; a zero ti (both
 * sides share Pi's normal) falls back to Pi's tangent plane. */
static Vec3 crease_point(Vec3 pi, Vec3 ni, Vec3 ti, Vec3 pj)
{
    if (ti.x == 0 && ti.y == 0 && ti.z == 0)
        return tangent_point(pi, ni, pj);
    Vec3 d = vec3_sub(pj, pi);
    return vec3_add(pi, vec3_scale(ti, vec3_dot(d, ti) / 3.0));
}

/* The inner control point of edge e (corners e, e + 1) nearest corner
 * `end` of the edge (0: corner e, 1: corner e + 1). */
static Vec3 edge_point(const ScenePnPatch *pt, guint e, guint end)
{
    guint i = (e + end) % 3, j = (e + 1 - end) % 3;
    if (pt->cr.crease[e])
        return crease_point(pt->p[i], pt->n[i], pt->cr.t[e][end], pt->p[j]);
    return tangent_point(pt->p[i], pt->n[i], pt->p[j]);
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
    scene_pn_patch_creased(pt, P, N, NULL);
}

void scene_pn_patch_creased(ScenePnPatch *pt, const Vec3 P[3],
                            const Vec3 N[3], const ScenePnCreases *c)
{
    for (int i = 0; i < 3; i++) {
        pt->p[i] = P[i];
        pt->n[i] = vec3_norm(N[i]);
    }
    if (c)
        pt->cr = *c;
    else
        memset(&pt->cr, 0, sizeof pt->cr);
    const Vec3 *p = pt->p, *n = pt->n;
    pt->b210 = edge_point(pt, 0, 0);
    pt->b120 = edge_point(pt, 0, 1);
    pt->b021 = edge_point(pt, 1, 0);
    pt->b012 = edge_point(pt, 1, 1);
    pt->b102 = edge_point(pt, 2, 0);
    pt->b201 = edge_point(pt, 2, 1);
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

/* One end of an edge: its corner, the corner's normal and, on a crease,
 * the crease direction there. */
typedef struct {
    Vec3 p, n, t;
} EdgeEnd;

/* The point `sb` steps of `steps` from end a towards end b on the
 * edge's cubic, and its normal: computed from the edge alone. */
static void edge_eval(EdgeEnd a, EdgeEnd b, gboolean crease, guint sb,
                      guint steps, ScenePnNormals kind, Vec3 *pos, Vec3 *nrm)
{
    if (scene_pn_vec_after(a.p, b.p)) {
        edge_eval(b, a, crease, steps - sb, steps, kind, pos, nrm);
        return;
    }
    Vec3 pa = a.p, na = a.n, pb = b.p, nb = b.n;
    double t = (double)sb / steps, s = 1 - t;
    Vec3 bab = crease ? crease_point(pa, na, a.t, pb)
                      : tangent_point(pa, na, pb);
    Vec3 bba = crease ? crease_point(pb, nb, b.t, pa)
                      : tangent_point(pb, nb, pa);
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

/* Point `sb` of `steps` along edge e of the patch (from corner e). */
static void edge_of(const ScenePnPatch *pt, guint e, guint sb, guint steps,
                    ScenePnNormals kind, Vec3 *pos, Vec3 *nrm)
{
    guint f = (e + 1) % 3;
    EdgeEnd a = {pt->p[e], pt->n[e], pt->cr.t[e][0]};
    EdgeEnd b = {pt->p[f], pt->n[f], pt->cr.t[e][1]};
    edge_eval(a, b, pt->cr.crease[e], sb, steps, kind, pos, nrm);
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
        edge_of(pt, 0, j, steps, kind, pos, nrm);
    } else if (i == 0) {
        edge_of(pt, 1, k, steps, kind, pos, nrm);
    } else if (j == 0) {
        edge_of(pt, 2, i, steps, kind, pos, nrm);
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

/* The PN patch of fan triangle (a, b, c) of a mesh with normals, with
 * its crease edges c (NULL: none). */
static void mesh_patch(const SceneMesh *m, const uint32_t ix[3],
                       const ScenePnCreases *c, ScenePnPatch *pt)
{
    Vec3 P[3], N[3];
    for (int i = 0; i < 3; i++) {
        P[i] = scene_mesh_vertex(m, ix[i]);
        N[i] = g_array_index(m->normals, Vec3, ix[i]);
    }
    scene_pn_patch_creased(pt, P, N, c);
}

SceneMesh *scene_pn_tessellate(const SceneMesh *m, const ScenePnParams *p)
{
    SceneMesh *own = NULL;
    if (m->normals->len != scene_mesh_n_vertices(m)) {
        own = scene_mesh_copy(m);
        scene_mesh_compute_normals(own);
        m = own;
    }
    GArray *cr = p->ignore_creases ? NULL : scene_pn_find_creases(m);
    guint fan = 0;
    SceneMesh *out = scene_mesh_new();
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *ix = scene_mesh_poly(m, i);
        SceneColor col = g_array_index(m->poly_color, SceneColor, i);
        uint32_t tag = g_array_index(m->poly_tag, uint32_t, i);
        for (guint t = 1; t + 1 < scene_mesh_poly_len(m, i); t++) {
            uint32_t tri[3] = {ix[0], ix[t], ix[t + 1]};
            ScenePnPatch pt;
            mesh_patch(m, tri,
                       cr ? &g_array_index(cr, ScenePnCreases, fan) : NULL,
                       &pt);
            fan++;
            tessellate_tri(out, &pt, p, col, tag);
        }
    }
    if (cr)
        g_array_free(cr, TRUE);
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
