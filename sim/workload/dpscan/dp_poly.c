/* dp_poly.c — screen-space polygons and the pixel rule (dp_poly.h).
 *
 * The contour value of a vertex is its world height (y) scaled to
 * [0, 1] over the scene: the scenes carry no scalar field of their own
 * (ASSUMPTION; a data set with vertex data would use it instead).
 * O(vertices) to build, O(k^2) per polygon scan line.
 */
#include "sim/workload/dpscan/dp_poly.h"
#include <math.h>

static const char *const mode_names[WL_DP_N_MODES] = {
    "flat",    "gouraud", "wireframe", "hidden_line",
    "contour", "points",  "lines",
};

const char *wl_dp_mode_name(WlDpMode m)
{
    g_assert(m < WL_DP_N_MODES);
    return mode_names[m];
}

gboolean wl_dp_mode_parse(const char *name, WlDpMode *out)
{
    for (int m = 0; m < WL_DP_N_MODES; m++)
        if (g_strcmp0(name, mode_names[m]) == 0) {
            *out = (WlDpMode)m;
            return TRUE;
        }
    return FALSE;
}

gboolean wl_dp_mode_fills(WlDpMode m)
{
    return m == WL_DP_MODE_FLAT || m == WL_DP_MODE_GOURAUD ||
           m == WL_DP_MODE_HIDDEN_LINE || m == WL_DP_MODE_CONTOUR;
}

static uint8_t nearest_color(SceneColor c, const float pal[][3])
{
    uint8_t best = 0;
    double bd = INFINITY;
    for (uint8_t k = 0; k < WL_DP_COLORS; k++) {
        double dr = c.r - pal[k][0], dg = c.g - pal[k][1], db = c.b - pal[k][2];
        double d = dr * dr + dg * dg + db * db;
        if (d < bd)
            bd = d, best = k;
    }
    return best;
}

static WlDpPolys *polys_alloc(const SceneMesh *m, WlDpMode mode)
{
    WlDpPolys *p = g_new0(WlDpPolys, 1);
    p->n = scene_mesh_n_polys(m);
    p->n_verts = m->idx->len;
    p->mode = mode;
    p->start = g_new(uint32_t, p->n + 1);
    p->x = g_new(double, MAX(p->n_verts, 1));
    p->y = g_new(double, MAX(p->n_verts, 1));
    p->z = g_new(double, MAX(p->n_verts, 1));
    p->val = g_new(double, MAX(p->n_verts, 1));
    p->color = g_new(uint8_t, MAX(p->n, 1));
    p->ok = g_new(uint8_t, MAX(p->n, 1));
    return p;
}

/* World -> screen of one vertex; FALSE when behind the eye. */
static gboolean to_screen(Mat4 vp, Vec3 w, int width, int height, double *x,
                          double *y, double *z)
{
    Vec4 c = mat4_apply_point(vp, w);
    if (c.w <= 1e-12)
        return FALSE;
    *x = (c.x / c.w + 1.0) * 0.5 * width;
    *y = (1.0 - c.y / c.w) * 0.5 * height;
    *z = CLAMP((c.z / c.w + 1.0) * 0.5, 0.0, 1.0);
    /* Far outside the window: not drawable in int32 pixel coordinates. */
    return fabs(*x) < 1e7 && fabs(*y) < 1e7;
}

typedef struct {
    Mat4 vp;
    Vec3 fwd;
    double ylo, yspan;
    int width, height;
} PolyView;

static double vertex_value(const PolyView *v, const SceneMesh *m, WlDpMode md,
                           uint32_t vi, double flat)
{
    if (md == WL_DP_MODE_CONTOUR)
        return (scene_mesh_vertex(m, vi).y - v->ylo) / v->yspan;
    if (md != WL_DP_MODE_GOURAUD)
        return flat;
    Vec3 n = g_array_index(m->normals, Vec3, vi);
    return fabs(vec3_dot(vec3_norm(n), v->fwd));
}

static void fill_poly(WlDpPolys *p, const PolyView *v, const SceneMesh *m,
                      guint i, const float pal[][3])
{
    const uint32_t *idx = scene_mesh_poly(m, i);
    guint k = scene_mesh_poly_len(m, i);
    uint32_t s = p->start[i];
    double flat = p->mode == WL_DP_MODE_HIDDEN_LINE
                      ? 1.0
                      : fabs(vec3_dot(scene_mesh_poly_normal(m, i), v->fwd));
    p->ok[i] = 1;
    for (guint j = 0; j < k; j++) {
        Vec3 w = scene_mesh_vertex(m, idx[j]);
        if (!to_screen(v->vp, w, v->width, v->height, &p->x[s + j],
                       &p->y[s + j], &p->z[s + j]))
            p->ok[i] = 0;
        p->val[s + j] = vertex_value(v, m, p->mode, idx[j], flat);
    }
    p->color[i] = nearest_color(g_array_index(m->poly_color, SceneColor, i),
                                pal);
}

WlDpPolys *wl_dp_polys_new(const Scene *scene, double frame, int width,
                           int height, WlDpMode mode, const float pal[][3])
{
    SceneMesh *m = scene_flatten(scene);
    if (mode == WL_DP_MODE_GOURAUD && m->normals->len == 0)
        scene_mesh_compute_normals(m);
    SceneCamera cam = scene_camera_at(scene, frame);
    cam.aspect = (double)width / height;
    SceneBox b = scene_mesh_bbox(m);
    PolyView v = {.vp = scene_camera_view_proj(&cam),
                  .fwd = vec3_norm(vec3_sub(cam.target, cam.eye)),
                  .ylo = b.min.y,
                  .yspan = MAX(b.max.y - b.min.y, 1e-12),
                  .width = width,
                  .height = height};
    WlDpPolys *p = polys_alloc(m, mode);
    p->start[0] = 0;
    for (guint i = 0; i < p->n; i++) {
        uint32_t k = scene_mesh_poly_len(m, i);
        g_assert(k <= WL_DP_MAX_VERTS);
        p->start[i + 1] = p->start[i] + k;
        p->kmax = MAX(p->kmax, k);
        fill_poly(p, &v, m, i, pal);
        p->n_ok += p->ok[i];
    }
    scene_mesh_free(m);
    return p;
}

void wl_dp_polys_free(WlDpPolys *p)
{
    if (!p)
        return;
    g_free(p->start);
    g_free(p->x);
    g_free(p->y);
    g_free(p->z);
    g_free(p->val);
    g_free(p->color);
    g_free(p->ok);
    g_free(p);
}

/* The polygon's vertical extent. */
static void y_range(const WlDpPolys *p, uint64_t i, double *lo, double *hi)
{
    *lo = INFINITY, *hi = -INFINITY;
    for (uint32_t v = p->start[i]; v < p->start[i + 1]; v++)
        *lo = MIN(*lo, p->y[v]), *hi = MAX(*hi, p->y[v]);
}

uint32_t wl_dp_poly_rows(const WlDpPolys *p, uint64_t i, int32_t *y0)
{
    *y0 = 0;
    double lo, hi;
    if (!p->ok[i])
        return 0;
    y_range(p, i, &lo, &hi);
    if (!(hi > lo))
        return 0; /* no area: no two crossings on any line */
    /* Every row the polygon touches, end rows included. */
    double first = floor(lo), last = floor(hi);
    *y0 = (int32_t)first;
    return (uint32_t)(last - first) + 1;
}

/* The line row y is sampled on: its centre, moved inside the polygon's
 * extent when the polygon starts or ends within the row. */
static double sample_line(const WlDpPolys *p, uint64_t i, int32_t y)
{
    double lo, hi;
    y_range(p, i, &lo, &hi);
    double d = (hi - lo) * 1e-6;
    return CLAMP(y + 0.5, lo + d, hi - d);
}

typedef struct {
    double x, z, v;
} Cross;

/* Crossings of row y's centre with the polygon's edges, sorted. */
static guint crossings(const WlDpPolys *p, uint64_t i, int32_t y, Cross *c)
{
    double yc = sample_line(p, i, y);
    uint32_t s = p->start[i], k = wl_dp_poly_len(p, i);
    guint n = 0;
    for (uint32_t e = 0; e < k; e++) {
        uint32_t a = s + e, b = s + (e + 1) % k;
        double ya = p->y[a], yb = p->y[b];
        if (!((ya <= yc && yc < yb) || (yb <= yc && yc < ya)))
            continue;
        double t = (yc - ya) / (yb - ya);
        Cross x = {p->x[a] + t * (p->x[b] - p->x[a]),
                   p->z[a] + t * (p->z[b] - p->z[a]),
                   p->val[a] + t * (p->val[b] - p->val[a])};
        guint j = n++;
        while (j > 0 && (c[j - 1].x > x.x ||
                         (c[j - 1].x == x.x && c[j - 1].z > x.z))) {
            c[j] = c[j - 1];
            j--;
        }
        c[j] = x;
    }
    return n;
}

guint wl_dp_poly_spans(const WlDpPolys *p, uint64_t i, int32_t y,
                       WlDpSpan *out)
{
    Cross c[WL_DP_MAX_VERTS];
    guint n = crossings(p, i, y, c), m = 0;
    for (guint k = 0; k + 1 < n; k += 2) {
        double first = floor(c[k].x), end = floor(c[k + 1].x) + 1;
        out[m++] = (WlDpSpan){.xl = c[k].x,
                              .xr = c[k + 1].x,
                              .zl = c[k].z,
                              .zr = c[k + 1].z,
                              .vl = c[k].v,
                              .vr = c[k + 1].v,
                              .y = y,
                              .x0 = (int32_t)first,
                              .len = (uint32_t)(end - first),
                              .poly = (uint32_t)i};
    }
    return m;
}

uint64_t wl_dp_key(double z, uint32_t id, uint8_t index)
{
    double d = (1.0 - CLAMP(z, 0.0, 1.0)) * 4294967295.0;
    return ((uint64_t)d << 32) | ((uint64_t)(id & 0xffffff) << 8) | index;
}

uint8_t wl_dp_color_index(uint8_t color, double shade)
{
    int s = (int)floor(CLAMP(shade, 0.0, 1.0) * (WL_DP_SHADES - 1) + 0.5);
    return (uint8_t)(WL_DP_TABLE_BASE + color * WL_DP_SHADES + s);
}

uint8_t wl_dp_contour_index(double v)
{
    int band = (int)floor(CLAMP(v, 0.0, 1.0) * WL_DP_COLORS);
    band = MIN(band, WL_DP_COLORS - 1);
    return (uint8_t)(WL_DP_TABLE_BASE + band * WL_DP_SHADES + WL_DP_SHADES - 1);
}

static uint8_t pixel_index(const WlDpPolys *p, uint32_t poly, double v)
{
    if (p->mode == WL_DP_MODE_CONTOUR)
        return wl_dp_contour_index(v);
    return wl_dp_color_index(p->color[poly], v);
}

uint64_t wl_dp_span_key(const WlDpPolys *p, const WlDpSpan *s, uint32_t j)
{
    g_assert(j < s->len);
    double w = s->xr - s->xl;
    double t = w > 0 ? (s->x0 + j + 0.5 - s->xl) / w : 0.0;
    t = CLAMP(t, 0.0, 1.0);
    double z = s->zl + t * (s->zr - s->zl), v = s->vl + t * (s->vr - s->vl);
    return wl_dp_key(z, s->poly, pixel_index(p, s->poly, v));
}

static void edge_ends(const WlDpPolys *p, uint64_t i, uint32_t e, uint32_t *a,
                      uint32_t *b)
{
    uint32_t k = wl_dp_poly_len(p, i);
    g_assert(e < k);
    *a = p->start[i] + e;
    *b = p->start[i] + (e + 1) % k;
}

uint32_t wl_dp_edge_pixels(const WlDpPolys *p, uint64_t i, uint32_t e)
{
    if (!p->ok[i])
        return 0;
    uint32_t a, b;
    edge_ends(p, i, e, &a, &b);
    double dx = fabs(floor(p->x[b]) - floor(p->x[a]));
    double dy = fabs(floor(p->y[b]) - floor(p->y[a]));
    double n = MAX(dx, dy);
    return n > 1e7 ? 0 : (uint32_t)n + 1;
}

/* Key of a line pixel: depth only where lines hide each other. */
static uint64_t line_key(const WlDpPolys *p, uint64_t i, double z)
{
    uint8_t idx = wl_dp_color_index(p->color[i], 1.0);
    return wl_dp_key(p->mode == WL_DP_MODE_WIREFRAME ? 1.0 : z, (uint32_t)i,
                     idx);
}

void wl_dp_edge_pixel(const WlDpPolys *p, uint64_t i, uint32_t e, uint32_t k,
                      int64_t *x, int64_t *y, uint64_t *key)
{
    uint32_t a, b, n = wl_dp_edge_pixels(p, i, e);
    g_assert(k < n);
    edge_ends(p, i, e, &a, &b);
    double t = n > 1 ? (double)k / (n - 1) : 0.0;
    double xa = floor(p->x[a]) + 0.5, ya = floor(p->y[a]) + 0.5;
    double xb = floor(p->x[b]) + 0.5, yb = floor(p->y[b]) + 0.5;
    *x = (int64_t)floor(xa + t * (xb - xa));
    *y = (int64_t)floor(ya + t * (yb - ya));
    *key = line_key(p, i, p->z[a] + t * (p->z[b] - p->z[a]));
}

void wl_dp_point_pixel(const WlDpPolys *p, uint64_t i, uint32_t v, int64_t *x,
                       int64_t *y, uint64_t *key)
{
    g_assert(v < wl_dp_poly_len(p, i));
    uint32_t a = p->start[i] + v;
    *x = (int64_t)floor(p->x[a]);
    *y = (int64_t)floor(p->y[a]);
    *key = line_key(p, i, p->z[a]);
}
