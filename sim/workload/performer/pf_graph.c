/* pf_graph.c — the Performer-style scene graph: building, bounding
 * spheres and pfFlatten (see pf_graph.h).
 *
 * Invariant: the graph is a tree (a node has one parent, a geoset one
 * node), which flatten relies on to transform geometry in place; the
 * town generator builds trees.  Bounds are exact for geosets (sphere
 * about the box centre through the farthest vertex) and conservative
 * unions above.
 */
#include "sim/workload/performer/pf_graph.h"

WlPfGraph *wl_pf_graph_new(void)
{
    WlPfGraph *g = g_new0(WlPfGraph, 1);
    g->nodes = g_array_new(FALSE, TRUE, sizeof(WlPfNode));
    g->geosets = g_ptr_array_new();
    g->gstates = g_array_new(FALSE, TRUE, sizeof(WlPfGeoState));
    g->root = wl_pf_add_node(g, G_MAXUINT, WL_PF_GROUP);
    return g;
}

void wl_pf_graph_free(WlPfGraph *g)
{
    if (!g)
        return;
    for (guint i = 0; i < g->nodes->len; i++) {
        WlPfNode *n = wl_pf_node(g, i);
        g_array_free(n->children, TRUE);
        g_array_free(n->geosets, TRUE);
        g_array_free(n->ranges, TRUE);
        if (n->cells)
            g_ptr_array_free(n->cells, TRUE);
    }
    for (guint i = 0; i < g->geosets->len; i++) {
        g_array_free(wl_pf_geoset(g, i)->verts, TRUE);
        g_free(wl_pf_geoset(g, i));
    }
    g_array_free(g->nodes, TRUE);
    g_ptr_array_free(g->geosets, TRUE);
    g_array_free(g->gstates, TRUE);
    g_free(g);
}

guint wl_pf_add_node(WlPfGraph *g, guint parent, WlPfKind kind)
{
    WlPfNode n = {.kind = kind,
                  .mask = WL_PF_MASK_CULL | WL_PF_MASK_DRAW | WL_PF_MASK_ISECT,
                  .xf = mat4_identity(),
                  .which = WL_PF_SWITCH_ALL,
                  .radius = -1};
    n.children = g_array_new(FALSE, FALSE, sizeof(guint));
    n.geosets = g_array_new(FALSE, FALSE, sizeof(guint));
    n.ranges = g_array_new(FALSE, FALSE, sizeof(double));
    guint id = g->nodes->len;
    g_array_append_val(g->nodes, n);
    if (parent != G_MAXUINT)
        g_array_append_val(wl_pf_node(g, parent)->children, id);
    return id;
}

guint wl_pf_add_gstate(WlPfGraph *g, WlPfGeoState gs)
{
    g_array_append_val(g->gstates, gs);
    return g->gstates->len - 1;
}

static void geoset_bound(WlPfGeoSet *gs)
{
    Vec3 lo = vec3(HUGE_VAL, HUGE_VAL, HUGE_VAL), hi = vec3_scale(lo, -1);
    for (guint i = 0; i < gs->verts->len; i++) {
        Vec3 v = g_array_index(gs->verts, Vec3, i);
        lo = vec3(fmin(lo.x, v.x), fmin(lo.y, v.y), fmin(lo.z, v.z));
        hi = vec3(fmax(hi.x, v.x), fmax(hi.y, v.y), fmax(hi.z, v.z));
    }
    gs->center = vec3_scale(vec3_add(lo, hi), 0.5);
    gs->radius = 0;
    for (guint i = 0; i < gs->verts->len; i++)
        gs->radius = fmax(
            gs->radius,
            vec3_len(vec3_sub(g_array_index(gs->verts, Vec3, i), gs->center)));
}

guint wl_pf_add_geoset(WlPfGraph *g, guint node, const Vec3 *tris, guint n,
                       guint gstate)
{
    WlPfNode *nd = wl_pf_node(g, node);
    g_assert(nd->kind == WL_PF_GEODE || nd->kind == WL_PF_BILLBOARD);
    g_assert(n > 0 && gstate < g->gstates->len);
    WlPfGeoSet *gs = g_new0(WlPfGeoSet, 1);
    gs->verts = g_array_sized_new(FALSE, FALSE, sizeof(Vec3), 3 * n);
    g_array_append_vals(gs->verts, tris, 3 * n);
    gs->gstate = gstate;
    geoset_bound(gs);
    guint id = g->geosets->len;
    g_ptr_array_add(g->geosets, gs);
    g_array_append_val(nd->geosets, id);
    return id;
}

/* ---- bounds ------------------------------------------------------------ */

static void sphere_union(Vec3 *c, double *r, Vec3 c2, double r2)
{
    if (r2 < 0)
        return;
    if (*r < 0) {
        *c = c2;
        *r = r2;
        return;
    }
    double d = vec3_len(vec3_sub(c2, *c));
    if (d + r2 <= *r)
        return;
    if (d + *r <= r2) {
        *c = c2;
        *r = r2;
        return;
    }
    double nr = (d + *r + r2) / 2;
    *c = vec3_add(*c, vec3_scale(vec3_sub(c2, *c), (nr - *r) / d));
    *r = nr;
}

void wl_pf_sphere_xform(Mat4 m, Vec3 c, double r, Vec3 *oc, double *or_)
{
    Vec4 p = mat4_apply_point(m, c);
    double s = 0;
    for (int j = 0; j < 3; j++)
        s = fmax(s, sqrt(m.m[0][j] * m.m[0][j] + m.m[1][j] * m.m[1][j] +
                         m.m[2][j] * m.m[2][j]));
    *oc = vec3(p.x, p.y, p.z);
    *or_ = r < 0 ? r : r * s;
}

static void bounds_of(WlPfGraph *g, guint node, gboolean deep)
{
    WlPfNode *n = wl_pf_node(g, node);
    Vec3 c = vec3(0, 0, 0);
    double r = -1;
    for (guint i = 0; i < n->geosets->len; i++) {
        const WlPfGeoSet *gs =
            wl_pf_geoset(g, g_array_index(n->geosets, guint, i));
        sphere_union(&c, &r, gs->center, gs->radius);
    }
    for (guint i = 0; i < n->children->len; i++) {
        guint ch = wl_pf_child(n, i);
        if (deep)
            bounds_of(g, ch, TRUE);
        const WlPfNode *cn = wl_pf_node(g, ch);
        sphere_union(&c, &r, cn->center, cn->radius);
    }
    n = wl_pf_node(g, node); /* the array did not move, but be plain */
    if (n->kind == WL_PF_SCS || n->kind == WL_PF_DCS)
        wl_pf_sphere_xform(n->xf, c, r, &c, &r);
    n->center = c;
    n->radius = r;
}

void wl_pf_update_bounds(WlPfGraph *g, guint node)
{
    bounds_of(g, node, TRUE);
}

void wl_pf_update_bounds_shallow(WlPfGraph *g, guint node)
{
    bounds_of(g, node, FALSE);
}

/* ---- pfFlatten --------------------------------------------------------- */

/* Whether the subtree holds a DCS or a billboard (flatten stops there:
 * their matrices change per frame). */
static gboolean has_dynamic(const WlPfGraph *g, guint node)
{
    const WlPfNode *n = wl_pf_node(g, node);
    if (n->kind == WL_PF_DCS || n->kind == WL_PF_BILLBOARD)
        return TRUE;
    for (guint i = 0; i < n->children->len; i++)
        if (has_dynamic(g, wl_pf_child(n, i)))
            return TRUE;
    return FALSE;
}

/* Applies m and every SCS below node to the geometry; returns the
 * number of SCS nodes turned into groups. */
static guint apply_xform(WlPfGraph *g, guint node, Mat4 m)
{
    WlPfNode *n = wl_pf_node(g, node);
    guint removed = n->kind == WL_PF_SCS;
    if (n->kind == WL_PF_SCS) {
        m = mat4_mul(m, n->xf);
        n->kind = WL_PF_GROUP;
        n->xf = mat4_identity();
        n->flattened = TRUE;
    }
    for (guint i = 0; i < n->geosets->len; i++) {
        WlPfGeoSet *gs = wl_pf_geoset(g, g_array_index(n->geosets, guint, i));
        for (guint v = 0; v < gs->verts->len; v++) {
            Vec3 *p = &g_array_index(gs->verts, Vec3, v);
            Vec4 q = mat4_apply_point(m, *p);
            *p = vec3(q.x, q.y, q.z);
        }
        geoset_bound(gs);
    }
    for (guint i = 0; i < n->children->len; i++)
        removed += apply_xform(g, wl_pf_child(n, i), m);
    return removed;
}

static guint flatten_node(WlPfGraph *g, guint node)
{
    WlPfNode *n = wl_pf_node(g, node);
    if (n->kind == WL_PF_SCS && !has_dynamic(g, node))
        return apply_xform(g, node, mat4_identity());
    guint removed = 0;
    for (guint i = 0; i < n->children->len; i++)
        removed += flatten_node(g, wl_pf_child(wl_pf_node(g, node), i));
    return removed;
}

guint wl_pf_flatten(WlPfGraph *g)
{
    guint removed = flatten_node(g, g->root);
    wl_pf_update_bounds(g, g->root);
    return removed;
}

guint wl_pf_count_kind(const WlPfGraph *g, WlPfKind kind)
{
    guint c = 0;
    for (guint i = 0; i < g->nodes->len; i++)
        c += wl_pf_node(g, i)->kind == kind;
    return c;
}

void wl_pf_partition_build(WlPfGraph *g, guint node, guint grid)
{
    WlPfNode *n = wl_pf_node(g, node);
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    for (guint i = 0; i < n->children->len; i++) {
        const WlPfNode *c = wl_pf_node(g, wl_pf_child(n, i));
        if (c->radius < 0)
            continue;
        lo[0] = fmin(lo[0], c->center.x - c->radius);
        lo[1] = fmin(lo[1], c->center.z - c->radius);
        hi[0] = fmax(hi[0], c->center.x + c->radius);
        hi[1] = fmax(hi[1], c->center.z + c->radius);
    }
    if (n->cells)
        g_ptr_array_free(n->cells, TRUE);
    n->cells = g_ptr_array_new_with_free_func((GDestroyNotify)g_array_unref);
    n->grid = MAX(grid, 1);
    n->x0 = lo[0];
    n->z0 = lo[1];
    n->cell = fmax(fmax(hi[0] - lo[0], hi[1] - lo[1]) / n->grid, 1e-9);
    for (guint k = 0; k < n->grid * n->grid; k++)
        g_ptr_array_add(n->cells, g_array_new(FALSE, FALSE, sizeof(guint)));
    for (guint i = 0; i < n->children->len; i++) {
        const WlPfNode *c = wl_pf_node(g, wl_pf_child(n, i));
        if (c->radius < 0)
            continue;
        guint a[2], b[2];
        double cc[2] = {c->center.x - n->x0, c->center.z - n->z0};
        for (int d = 0; d < 2; d++) {
            a[d] = (guint)fmax(0, floor((cc[d] - c->radius) / n->cell));
            b[d] = MIN((guint)fmax(0, floor((cc[d] + c->radius) / n->cell)),
                       n->grid - 1);
        }
        for (guint u = a[0]; u <= b[0]; u++)
            for (guint v = a[1]; v <= b[1]; v++)
                g_array_append_val(n->cells->pdata[u * n->grid + v], i);
    }
}
