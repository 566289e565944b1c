/* pipeline.c — transform, shade, clip, cull and scan (see pipeline.h).
 *
 * Each polygon is handled in a small stack buffer; nothing is cached
 * between polygons, so work (and the counters) depend only on the
 * polygons drawn, never on the rest of the mesh.  Culling and the
 * zero-area test use the exact fixed-point area of the whole clipped
 * polygon, so they agree with what the scan converter would cover.
 * Fan triangles whose snapped area has the opposite sign to the polygon
 * (a tiny concavity created by snapping clipped vertices) are skipped.
 * Polygons that need no clipping are culled before they are shaded, so
 * back faces cost no lighting; clipped ones are shaded first because
 * clipping interpolates colours.  Normals go to world space by the
 * model's normal matrix (cofactors of its 3x3: the inverse transpose up
 * to scale, vec.h), so lighting stays right under non-uniform scaling.
 * O(n) per n-gon, plus the scan conversion.
 */
#include "sim/raster/pipeline.h"
#include <string.h>

RastView rast_view_make(Mat4 view_proj, int width, int height)
{
    g_assert(width > 0 && height > 0);
    g_assert(width <= RAST_MAX_SIDE && height <= RAST_MAX_SIDE);
    RastView v = {0};
    v.view_proj = view_proj;
    v.width = width;
    v.height = height;
    v.cull_back = TRUE;
    v.span_rule = RAST_SPAN_EXACT;
    v.lighting = TRUE;
    v.shading = RAST_SHADE_GOURAUD;
    v.light_dir = vec3(0, 0, 1);
    v.ambient = 0.25f;
    v.diffuse = 0.75f;
    return v;
}

RastView rast_view_for_camera(const SceneCamera *cam, int width, int height)
{
    SceneCamera c = *cam;
    c.aspect = (double)width / height;
    RastView v = rast_view_make(scene_camera_view_proj(&c), width, height);
    Vec3 back = vec3_norm(vec3_sub(c.eye, c.target));
    Vec3 right = vec3_norm(vec3_cross(c.up, back));
    Vec3 up = vec3_cross(back, right);
    v.light_dir = vec3_norm(
        vec3_add(back, vec3_add(vec3_scale(right, 0.5), vec3_scale(up, 0.6))));
    return v;
}

static RastColor shade(const RastView *v, SceneColor base, Vec3 n)
{
    if (!v->lighting)
        return (RastColor){base.r, base.g, base.b};
    double d = fabs(vec3_dot(vec3_norm(n), v->light_dir));
    float k = (float)(v->ambient + v->diffuse * d);
    return (RastColor){base.r * k, base.g * k, base.b * k};
}

static Vec3 xform_dir(Mat4 m, Vec3 d)
{
    Vec4 r = mat4_apply(m, (Vec4){d.x, d.y, d.z, 0.0});
    return vec3(r.x, r.y, r.z);
}

static SceneColor mul(SceneColor a, SceneColor b)
{
    return scene_color(a.r * b.r, a.g * b.g, a.b * b.b);
}

static int64_t poly_area2(const RastScreenVert *s, int n)
{
    int64_t a = 0;
    for (int i = 1; i + 1 < n; i++)
        a += rast_area2(&s[0], &s[i], &s[i + 1]);
    return a;
}

static gboolean finite4(Vec4 p)
{
    return isfinite(p.x) && isfinite(p.y) && isfinite(p.z) && isfinite(p.w);
}

/* Trivial reject: FALSE (counted) when the polygon is non-finite or
 * outside one plane; *any gets the planes some vertex is outside of. */
static gboolean trivial(const RastVert *in, int n, double guard, unsigned *any,
                        RastCounters *c)
{
    unsigned all = ~0u;
    *any = 0;
    for (int i = 0; i < n; i++) {
        if (!finite4(in[i].pos)) {
            c->rejected++;
            return FALSE;
        }
        unsigned code = rast_clip_outcode(in[i].pos, guard);
        all &= code;
        *any |= code;
    }
    if (all) {
        c->rejected++;
        return FALSE;
    }
    return TRUE;
}

/* Fills the colours of in[0..n) (the polygon's unclipped vertices). */
typedef void (*ShadeFn)(void *ctx, RastVert *in, int n);

static void scan_polygon(const RastView *v, RastScreenVert *s, int m,
                         int64_t area, uint32_t prim, RastSpanSink sink,
                         RastCounters *c)
{
    if (v->span_rule != RAST_SPAN_EXACT) {
        rast_scan_polygon(s, m, prim, v->width, v->height, v->span_rule, sink,
                          c);
        return;
    }
    for (int i = 1; i + 1 < m; i++) {
        RastScreenVert t[3] = {s[0], s[i], s[i + 1]};
        int64_t a = rast_area2(&t[0], &t[1], &t[2]);
        if (a != 0 && (a > 0) == (area > 0))
            rast_scan_triangle(t, prim, v->width, v->height, sink, c);
    }
}

/* Zero-area and back-facing polygons stop here (counted). */
static gboolean visible(const RastView *v, int64_t area, RastCounters *c)
{
    if (area == 0) {
        c->degenerate++;
        return FALSE;
    }
    if (v->cull_back && area < 0) {
        c->culled++;
        return FALSE;
    }
    return TRUE;
}

/* The common case: inside every plane, so cull before shading. */
static void draw_unclipped(const RastView *v, RastVert *in, int n,
                           uint32_t prim, ShadeFn shade_fn, void *ctx,
                           RastSpanSink sink, RastCounters *c)
{
    RastScreenVert s[RAST_POLY_MAX];
    for (int i = 0; i < n; i++)
        s[i] = rast_viewport(&in[i], v->width, v->height);
    int64_t area = poly_area2(s, n);
    if (!visible(v, area, c))
        return;
    if (shade_fn) {
        shade_fn(ctx, in, n);
        for (int i = 0; i < n; i++)
            s[i].col = in[i].col;
    }
    scan_polygon(v, s, n, area, prim, sink, c);
}

static void draw_polygon(const RastView *v, RastVert *in, int n, uint32_t prim,
                         ShadeFn shade_fn, void *ctx, RastSpanSink sink,
                         RastCounters *c)
{
    g_assert(n >= 3 && n <= RAST_POLY_MAX);
    c->prims++;
    double guard = rast_guard_band(v->width, v->height);
    unsigned any = 0;
    if (!trivial(in, n, guard, &any, c))
        return;
    if (!any) {
        draw_unclipped(v, in, n, prim, shade_fn, ctx, sink, c);
        return;
    }
    if (shade_fn)
        shade_fn(ctx, in, n); /* clipping interpolates colours */
    RastVert buf[RAST_CLIP_MAX];
    int m = rast_clip_polygon(in, n, guard, buf);
    if (m == 0) {
        c->rejected++;
        return;
    }
    c->clipped++;
    RastScreenVert s[RAST_CLIP_MAX];
    for (int i = 0; i < m; i++)
        s[i] = rast_viewport(&buf[i], v->width, v->height);
    int64_t area = poly_area2(s, m);
    if (visible(v, area, c))
        scan_polygon(v, s, m, area, prim, sink, c);
}

void rast_draw_clip_polygon(const RastView *v, const RastVert *in, int n,
                            uint32_t prim, RastSpanSink sink, RastCounters *c)
{
    g_assert(n >= 3 && n <= RAST_POLY_MAX);
    RastVert vs[RAST_POLY_MAX];
    memcpy(vs, in, sizeof(RastVert) * (size_t)n);
    draw_polygon(v, vs, n, prim, NULL, NULL, sink, c);
}

typedef struct {
    const RastView *v;
    const SceneMesh *m;
    Mat4 mvp, normal; /* normal: mat4_normal_matrix(model) */
    SceneColor tint;
    gboolean vnormals, vcolors;
} MeshCtx;

/* What a polygon's shading callback needs. */
typedef struct {
    const MeshCtx *k;
    guint poly;
    const uint32_t *idx;
} PolyCtx;

static SceneColor vertex_base(const MeshCtx *k, guint poly, uint32_t vi)
{
    SceneColor b = k->vcolors && k->v->shading == RAST_SHADE_GOURAUD
                       ? g_array_index(k->m->colors, SceneColor, vi)
                       : g_array_index(k->m->poly_color, SceneColor, poly);
    return mul(b, k->tint);
}

static void shade_poly(void *ctx, RastVert *out, int n)
{
    const PolyCtx *pc = ctx;
    const MeshCtx *k = pc->k;
    const RastView *v = k->v;
    Vec3 fn = vec3(0, 0, 1);
    if (v->lighting && (v->shading == RAST_SHADE_FLAT || !k->vnormals))
        fn = xform_dir(k->normal, scene_mesh_poly_normal(k->m, pc->poly));
    if (v->shading == RAST_SHADE_FLAT) {
        SceneColor flat =
            mul(g_array_index(k->m->poly_color, SceneColor, pc->poly), k->tint);
        RastColor fc = shade(v, flat, fn);
        for (int i = 0; i < n; i++)
            out[i].col = fc;
        return;
    }
    for (int i = 0; i < n; i++) {
        uint32_t vi = pc->idx[i];
        Vec3 nn =
            k->vnormals && v->lighting
                ? xform_dir(k->normal, g_array_index(k->m->normals, Vec3, vi))
                : fn;
        out[i].col = shade(v, vertex_base(k, pc->poly, vi), nn);
    }
}

/* Transforms the vertices idx[0..n) of a polygon (colours come later). */
static void load_verts(const MeshCtx *k, const uint32_t *idx, int n,
                       RastVert *out, RastCounters *c)
{
    for (int i = 0; i < n; i++) {
        out[i].pos = mat4_apply_point(k->mvp, scene_mesh_vertex(k->m, idx[i]));
        c->verts++;
    }
}

static void draw_poly(const MeshCtx *k, guint poly, uint32_t prim,
                      RastSpanSink sink, RastCounters *c)
{
    const uint32_t *idx = scene_mesh_poly(k->m, poly);
    int n = (int)scene_mesh_poly_len(k->m, poly);
    RastVert vs[RAST_POLY_MAX];
    if (n <= RAST_POLY_MAX) {
        PolyCtx pc = {k, poly, idx};
        load_verts(k, idx, n, vs, c);
        draw_polygon(k->v, vs, n, prim, shade_poly, &pc, sink, c);
        return;
    }
    for (int i = 1; i + 1 < n; i++) {
        uint32_t tri[3] = {idx[0], idx[i], idx[i + 1]};
        PolyCtx pc = {k, poly, tri};
        load_verts(k, tri, 3, vs, c);
        draw_polygon(k->v, vs, 3, prim, shade_poly, &pc, sink, c);
    }
}

void rast_draw_mesh(const RastView *v, const SceneMesh *m, Mat4 model,
                    SceneColor tint, uint32_t id_base, const RastSubset *subset,
                    RastSpanSink sink, RastCounters *c)
{
    MeshCtx k = {v,
                 m,
                 mat4_mul(v->view_proj, model),
                 mat4_normal_matrix(model),
                 tint,
                 m->normals->len == m->pos->len && m->pos->len > 0,
                 m->colors->len == m->pos->len && m->pos->len > 0};
    guint np = scene_mesh_n_polys(m);
    if (subset && !subset->ids)
        subset = NULL; /* no list: every polygon */
    guint count = subset ? subset->n : np;
    for (guint i = 0; i < count; i++) {
        guint poly = subset ? subset->ids[i] : i;
        g_assert(poly < np);
        draw_poly(&k, poly, id_base + poly, sink, c);
    }
}

void rast_draw_scene(const RastView *v, const Scene *s, RastSpanSink sink,
                     RastCounters *c)
{
    uint32_t base = 0;
    for (guint i = 0; i < scene_n_instances(s); i++) {
        const SceneInstance *in = scene_instance(s, i);
        const SceneMesh *m = scene_instance_mesh(s, i);
        rast_draw_mesh(v, m, in->xform, in->color, base, NULL, sink, c);
        base += scene_mesh_n_polys(m);
    }
}
