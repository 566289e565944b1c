/* pn_triangles.h — curved PN triangles (Vlachos, Peters, Boyd and
 * Mitchell, I3D 2001; seed 002, slides "Curved PN Triangles" to
 * "Hardware Performance").
 *
 * A flat triangle with vertex positions P1..P3 and normals N1..N3 becomes
 * one cubic Bezier patch b(u, v) (ten control points b_ijk, i + j + k = 3)
 * and a linear or quadratic normal field n(u, v), built from the three
 * vertices alone:
 *   b300 = P1, b030 = P2, b003 = P3;
 *   b210 = (2 P1 + P2 - w12 N1) / 3, w_ij = (Pj - Pi) . Ni, and likewise
 *   b120, b021, b012, b102, b201 (each edge point projected onto the
 *   tangent plane of its nearest corner);
 *   E = mean of those six, V = (P1 + P2 + P3) / 3, b111 = E + (E - V) / 2;
 *   n200 = N1, n020 = N2, n002 = N3;
 *   n110 = h110 / |h110|, h110 = N1 + N2 - v12 (P2 - P1),
 *   v_ij = 2 (Pj - Pi) . (Ni + Nj) / |Pj - Pi|^2, and n011, n101 alike.
 * Barycentric convention: (w, u, v) = (1 - u - v, u, v) weight P1, P2,
 * P3.  The quadratic normal is n200 w^2 + n020 u^2 + n002 v^2 +
 * n110 w u + n011 u v + n101 w v, renormalised (the paper's form, without
 * binomial factors).
 *
 * Level L divides each edge into L + 1 segments: a triangle becomes
 * (L + 1)^2 flat triangles on (L + 2)(L + 3) / 2 grid points.  A point on
 * an edge depends only on that edge's two vertices (positions and
 * normals), and is evaluated with the edge's endpoints in a canonical
 * order, so two triangles that share an edge and its vertex normals
 * produce bit-identical edge points: no cracks.  Where the two sides
 * have different normals (a crease) the edge is built from its crease
 * directions instead (below), which both sides share.  O((L + 1)^2) per
 * triangle.
 */
#ifndef PGSIM_SCENE_PN_TRIANGLES_H
#define PGSIM_SCENE_PN_TRIANGLES_H

#include "sim/scene/scene.h"

typedef enum { SCENE_PN_LINEAR, SCENE_PN_QUADRATIC } ScenePnNormals;

typedef struct {
    guint level; /* L >= 0; 0 leaves a triangle's shape flat */
    ScenePnNormals normals;
    gboolean ignore_creases; /* TRUE: each side of a crease curves the
                                edge by its own normals (cracks open);
                                FALSE: the crease treatment below */
} ScenePnParams;

/* Curved sharp edges (the paper's "two normals per vertex" on a crease):
 * an edge whose two triangles meet at the same positions with different
 * normals at an end is a crease.  Its cubic is built from the positions
 * and the crease direction t = n_A x n_B (the two sides' normals, in a
 * canonical order) alone: the inner control point near Pi is Pi +
 * ((Pj - Pi) . ti) ti / 3, the projection of the edge onto the crease
 * line, so both sides build the same curve and the seam stays closed;
 * each side keeps its own normals for shading (the edge looks sharp).
 * At an end where both sides share the normal, t is zero and the
 * tangent plane of that normal is used, as on a smooth edge.
 * Edge e of a triangle joins corner e and corner (e + 1) % 3. */
typedef struct {
    gboolean crease[3];
    Vec3 t[3][2]; /* edge e's unit crease direction at corner e, e + 1 */
} ScenePnCreases;

/* The control net of one PN triangle. */
typedef struct {
    Vec3 p[3], n[3]; /* input corners (normals unit length) */
    Vec3 b210, b120, b021, b012, b102, b201, b111;
    Vec3 n110, n011, n101; /* quadratic normal mid-edge coefficients */
    ScenePnCreases cr;     /* the crease edges (none: all FALSE) */
} ScenePnPatch;

/* Builds the patch of (P, N) by the construction above; normals are
 * normalised first.  g_assert()s non-degenerate edges. */
void scene_pn_patch(ScenePnPatch *pt, const Vec3 P[3], const Vec3 N[3]);
/* The same with crease edges c (NULL: none): a crease edge's two inner
 * control points come from its crease directions. */
void scene_pn_patch_creased(ScenePnPatch *pt, const Vec3 P[3],
                            const Vec3 N[3], const ScenePnCreases *c);
/* b(u, v) and the unit normal at (u, v), with w = 1 - u - v >= 0. */
Vec3 scene_pn_point(const ScenePnPatch *pt, double u, double v);
Vec3 scene_pn_normal(const ScenePnPatch *pt, ScenePnNormals kind, double u,
                     double v);

/* Triangles and grid points one input triangle becomes at level L. */
static inline uint64_t scene_pn_tris_per_tri(guint level)
{
    return (uint64_t)(level + 1) * (level + 1);
}
static inline uint64_t scene_pn_verts_per_tri(guint level)
{
    return (uint64_t)(level + 2) * (level + 3) / 2;
}

/* Returns a new mesh: every polygon of m fan-triangulated, each triangle
 * tessellated at p->level (its own (L+2)(L+3)/2 vertices with normals;
 * colour and tag copied).  Vertex normals come from m, or are computed
 * by scene_mesh_compute_normals() on a copy when m has none.  Free with
 * scene_mesh_free(). */
SceneMesh *scene_pn_tessellate(const SceneMesh *m, const ScenePnParams *p);
/* Replaces every mesh of s by its tessellation (instances keep their
 * indices).  A hierarchical form (s->db) no longer matches the meshes
 * and is dropped. */
void scene_pn_apply(Scene *s, const ScenePnParams *p);

#endif
