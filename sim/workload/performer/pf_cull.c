/* pf_cull.c — CULL, DRAW and ISECT traversals (see pf_cull.h).
 *
 * Frustum planes are extracted from the view-projection matrix (Gribb
 * and Hartmann, "Fast extraction of viewing frustum planes from the
 * world-view-projection matrix", 2001).  A sphere is outside when it is
 * farther than its radius behind any plane; spheres straddling a plane
 * are kept (conservative).  Cost: O(nodes visited + display list).
 */
#include "sim/workload/performer/pf_cull.h"
#include <string.h>

WlPfView wl_pf_view(const SceneCamera *c, double stress, gboolean cull)
{
    WlPfView v = {.eye = c->eye, .stress = stress, .cull = cull};
    Mat4 m = scene_camera_view_proj(c);
    for (int p = 0; p < 6; p++) {
        int row = p / 2;
        double sign = p % 2 ? -1 : 1;
        double len = 0;
        for (int j = 0; j < 4; j++) {
            v.planes[p][j] = m.m[3][j] + sign * m.m[row][j];
            if (j < 3)
                len += v.planes[p][j] * v.planes[p][j];
        }
        for (int j = 0; j < 4; j++)
            v.planes[p][j] /= sqrt(len);
    }
    return v;
}

static gboolean sphere_outside(const WlPfView *v, Vec3 c, double r)
{
    for (int p = 0; p < 6; p++) {
        const double *q = v->planes[p];
        if (q[0] * c.x + q[1] * c.y + q[2] * c.z + q[3] < -r)
            return TRUE;
    }
    return FALSE;
}

/* ---- selection shared by CULL and the culled-triangle count ------------ */

/* The LOD child drawn at world centre wc, or -1 for none. */
static int lod_child(const WlPfNode *n, const WlPfView *v, Vec3 wc)
{
    double d = vec3_len(vec3_sub(v->eye, wc)) * v->stress;
    for (guint i = 0; i + 1 < n->ranges->len && i < n->children->len; i++)
        if (d >= g_array_index(n->ranges, double, i) &&
            d < g_array_index(n->ranges, double, i + 1))
            return (int)i;
    return -1;
}

static gboolean switch_takes(const WlPfNode *n, guint i)
{
    return n->which == WL_PF_SWITCH_ALL || n->which == (int)i;
}

/* pfSequence: the child shown at the view's frame. */
static guint seq_child(const WlPfNode *n, const WlPfView *v)
{
    return v->frame / MAX(n->seq_frames, 1) % MAX(n->children->len, 1);
}

typedef struct {
    const WlPfGraph *g;
    const WlPfView *v;
    GArray *dl; /* NULL: count triangles only */
    WlPfCullStats *st;
    uint64_t tris; /* counting mode */
} Walk;

static void walk(Walk *w, guint node, Mat4 m, gboolean test);

static void emit(Walk *w, guint op, guint geoset)
{
    if (!w->dl)
        return;
    WlPfDlItem it = {op, geoset};
    g_array_append_val(w->dl, it);
}

static void emit_geosets(Walk *w, const WlPfNode *n)
{
    gboolean bb = n->kind == WL_PF_BILLBOARD;
    for (guint i = 0; i < n->geosets->len; i++) {
        guint gs = g_array_index(n->geosets, guint, i);
        if (!w->dl) {
            w->tris += wl_pf_geoset_tris(wl_pf_geoset(w->g, gs));
            continue;
        }
        if (bb) {
            w->st->billboards++;
            emit(w, WL_PF_DL_PUSH, 0);
        }
        emit(w, WL_PF_DL_GEOSET, gs);
        if (bb)
            emit(w, WL_PF_DL_POP, 0);
    }
}

static void walk_children(Walk *w, const WlPfNode *n, Mat4 m, Vec3 wc)
{
    int lod = -1;
    if (n->kind == WL_PF_LOD) {
        lod = lod_child(n, w->v, wc);
        if (w->dl) {
            w->st->lods++;
            w->st->lod_sum += lod < 0 ? n->children->len : (guint)lod;
        }
    } /* lod < 0 (no child in range): the loop below takes no child */
    for (guint i = 0; i < n->children->len; i++) {
        if ((n->kind == WL_PF_LOD && (int)i != lod) ||
            (n->kind == WL_PF_SWITCH && !switch_takes(n, i)) ||
            (n->kind == WL_PF_SEQUENCE && i != seq_child(n, w->v)))
            continue;
        walk(w, wl_pf_child(n, i), m, TRUE);
    }
}

/* Number of triangles the selection would draw below node (no frustum
 * test): what culling node saves. */
static uint64_t count_below(Walk *w, guint node, Mat4 m)
{
    Walk c = {w->g, w->v, NULL, w->st, 0};
    walk(&c, node, m, FALSE);
    return c.tris;
}

static void walk(Walk *w, guint node, Mat4 m, gboolean test)
{
    const WlPfNode *n = wl_pf_node(w->g, node);
    if (!(n->mask & WL_PF_MASK_CULL) || n->radius < 0)
        return;
    Vec3 wc;
    double wr;
    wl_pf_sphere_xform(m, n->center, n->radius, &wc, &wr);
    if (w->dl) {
        w->st->nodes_visited++;
        if (w->v->cull && test) {
            w->st->sphere_tests++;
            if (sphere_outside(w->v, wc, wr)) {
                w->st->nodes_culled++;
                w->st->tris_culled += count_below(w, node, m);
                return;
            }
        }
    }
    gboolean xf = n->kind == WL_PF_SCS || n->kind == WL_PF_DCS;
    Mat4 cm = xf ? mat4_mul(m, n->xf) : m;
    if ((n->callbacks & WL_PF_CB_CULL) && w->dl)
        w->st->callbacks += 2; /* pre- and post-cull */
    if (n->callbacks & WL_PF_CB_DRAW)
        emit(w, WL_PF_DL_CALLBACK, 0);
    if (xf)
        emit(w, WL_PF_DL_PUSH, 0);
    if (n->flattened && w->dl)
        w->st->matrix_saved += 2;
    if (n->mask & WL_PF_MASK_DRAW)
        emit_geosets(w, n);
    walk_children(w, n, cm, wc);
    if (xf)
        emit(w, WL_PF_DL_POP, 0);
    if (n->callbacks & WL_PF_CB_DRAW)
        emit(w, WL_PF_DL_CALLBACK, 0);
}

void wl_pf_cull(const WlPfGraph *g, const WlPfView *v, GArray *dl,
                WlPfCullStats *st)
{
    Walk w = {g, v, dl, st, 0};
    walk(&w, g->root, mat4_identity(), TRUE);
}

/* ---- DRAW -------------------------------------------------------------- */

static guint state_diff(const WlPfGeoState *a, const WlPfGeoState *b)
{
    return (a->texture != b->texture) + (a->material != b->material) +
           (a->modes != b->modes);
}

void wl_pf_draw(const WlPfGraph *g, const GArray *dl, WlPfDrawStats *st)
{
    WlPfGeoState cur = {G_MAXUINT, G_MAXUINT, G_MAXUINT};
    for (guint i = 0; i < dl->len; i++) {
        const WlPfDlItem *it = &g_array_index(dl, WlPfDlItem, i);
        if (it->op == WL_PF_DL_CALLBACK) {
            st->callbacks++;
            continue;
        }
        if (it->op != WL_PF_DL_GEOSET) {
            st->matrix_ops++;
            continue;
        }
        const WlPfGeoSet *gs = wl_pf_geoset(g, it->geoset);
        const WlPfGeoState *s =
            &g_array_index(g->gstates, WlPfGeoState, gs->gstate);
        st->geosets++;
        st->tris += wl_pf_geoset_tris(gs);
        st->state_changes += state_diff(&cur, s);
        st->state_naive += 3;
        cur = *s;
    }
}

/* ---- ISECT ------------------------------------------------------------- */

/* Height of the vertical line (x, z) through triangle abc, if it hits. */
static gboolean tri_hit(Vec3 a, Vec3 b, Vec3 c, double x, double z, double *y)
{
    double d = (b.z - c.z) * (a.x - c.x) + (c.x - b.x) * (a.z - c.z);
    if (fabs(d) < 1e-12)
        return FALSE;
    double l1 = ((b.z - c.z) * (x - c.x) + (c.x - b.x) * (z - c.z)) / d;
    double l2 = ((c.z - a.z) * (x - c.x) + (a.x - c.x) * (z - c.z)) / d;
    double l3 = 1 - l1 - l2;
    if (l1 < 0 || l2 < 0 || l3 < 0)
        return FALSE;
    *y = l1 * a.y + l2 * b.y + l3 * c.y;
    return TRUE;
}

static Vec3 xpt(Mat4 m, Vec3 p)
{
    Vec4 q = mat4_apply_point(m, p);
    return vec3(q.x, q.y, q.z);
}

static void isect_geosets(const WlPfGraph *g, const WlPfNode *n, Mat4 m,
                          double x, double z, double y0, double y1,
                          WlPfIsectStats *st)
{
    for (guint i = 0; i < n->geosets->len; i++) {
        const WlPfGeoSet *gs =
            wl_pf_geoset(g, g_array_index(n->geosets, guint, i));
        for (guint t = 0; t + 2 < gs->verts->len; t += 3) {
            const Vec3 *v = &g_array_index(gs->verts, Vec3, t);
            double y;
            st->tris_tested++;
            if (tri_hit(xpt(m, v[0]), xpt(m, v[1]), xpt(m, v[2]), x, z, &y) &&
                y >= y0 && y <= y1 && (!st->hit || y > st->height)) {
                st->hit = TRUE;
                st->height = y;
            }
        }
    }
}

static void isect_walk(const WlPfGraph *g, guint node, Mat4 m, double x,
                       double z, double y0, double y1, WlPfIsectStats *st);

/* pfPartition: only the children indexed in the cell (x, z) lies in (the
 * grid is in the partition's coordinates, here the world's). */
static void isect_cell(const WlPfGraph *g, const WlPfNode *n, double x,
                       double z, double y0, double y1, WlPfIsectStats *st)
{
    double u = floor((x - n->x0) / n->cell), v = floor((z - n->z0) / n->cell);
    if (u < 0 || v < 0 || u >= n->grid || v >= n->grid)
        return; /* outside every child's square */
    const GArray *c = n->cells->pdata[(guint)u * n->grid + (guint)v];
    for (guint i = 0; i < c->len; i++)
        isect_walk(g, wl_pf_child(n, g_array_index(c, guint, i)),
                   mat4_identity(), x, z, y0, y1, st);
}

static void isect_walk(const WlPfGraph *g, guint node, Mat4 m, double x,
                       double z, double y0, double y1, WlPfIsectStats *st)
{
    const WlPfNode *n = wl_pf_node(g, node);
    if (!(n->mask & WL_PF_MASK_ISECT) || n->radius < 0)
        return;
    Vec3 wc;
    double wr;
    wl_pf_sphere_xform(m, n->center, n->radius, &wc, &wr);
    st->nodes_tested++;
    double dx = wc.x - x, dz = wc.z - z;
    if (dx * dx + dz * dz > wr * wr || wc.y + wr < y0 || wc.y - wr > y1)
        return;
    if (n->kind == WL_PF_SCS || n->kind == WL_PF_DCS)
        m = mat4_mul(m, n->xf);
    if (n->kind != WL_PF_BILLBOARD)
        isect_geosets(g, n, m, x, z, y0, y1, st);
    Mat4 id = mat4_identity();
    if (n->kind == WL_PF_PARTITION && n->cells &&
        !memcmp(&m, &id, sizeof m)) { /* else every child, below */
        isect_cell(g, n, x, z, y0, y1, st);
        return;
    }
    for (guint i = 0; i < n->children->len; i++)
        if (n->kind != WL_PF_LOD || i == 0) /* finest LOD for picking */
            isect_walk(g, wl_pf_child(n, i), m, x, z, y0, y1, st);
}

void wl_pf_isect(const WlPfGraph *g, double x, double z, double y0, double y1,
                 WlPfIsectStats *st)
{
    isect_walk(g, g->root, mat4_identity(), x, z, y0, y1, st);
}
