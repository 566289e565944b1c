/* pphigs_pixels.c — renderer commands and the region pixel array
 * (pphigs_pixels.h).  Invariant: a command's expressions are computed
 * once, by the GP, in absolute screen coordinates; a region only
 * evaluates them, so a pixel's coverage, depth and colour do not depend
 * on which region or renderer evaluates it.
 */
#include "sim/workload/pphigs/pphigs_pixels.h"
#include <math.h>

#define W_EPS 1e-6 /* near clip: keep w > W_EPS */
#define MAX_CLIP (2 * WL_PPHIGS_MAX_EDGES) /* each vertex adds <= 2 */
#define KEY_ODP (UINT64_C(1) << 63)

typedef struct {
    double x, y, z; /* screen x, y (pixels, y down); NDC z */
} ScreenPt;

/* ---- building commands ------------------------------------------------ */

static Vec4 lerp4(Vec4 a, Vec4 b, double t)
{
    return (Vec4){a.x + t * (b.x - a.x), a.y + t * (b.y - a.y),
                  a.z + t * (b.z - a.z), a.w + t * (b.w - a.w)};
}

/* Sutherland-Hodgman against w > W_EPS; returns the clipped count
 * (n <= WL_PPHIGS_MAX_EDGES in, at most 2 n out: never truncated, so an
 * outline past WL_PPHIGS_MAX_EDGES is refused whole by the caller). */
static guint clip_near(const Vec4 *in, guint n, Vec4 *out)
{
    guint k = 0;
    for (guint i = 0; i < n; i++) {
        Vec4 p = in[i], q = in[(i + 1) % n];
        gboolean pin = p.w > W_EPS, qin = q.w > W_EPS;
        if (pin)
            out[k++] = p;
        if (pin != qin)
            out[k++] = lerp4(p, q, (W_EPS - p.w) / (q.w - p.w));
    }
    return k;
}

static ScreenPt to_screen(Vec4 q, guint width, guint height)
{
    return (ScreenPt){(q.x / q.w + 1) / 2 * width,
                      (1 - q.y / q.w) / 2 * height, q.z / q.w};
}

/* Twice the signed area of the triangle (a, b, c) in screen space. */
static double area2(ScreenPt a, ScreenPt b, ScreenPt c)
{
    return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

/* The fan triangle (0, i, i+1) of largest area: a stable plane. */
static guint best_fan(const ScreenPt *p, guint n)
{
    guint best = 1;
    for (guint i = 2; i + 1 < n; i++)
        if (fabs(area2(p[0], p[i], p[i + 1])) >
            fabs(area2(p[0], p[best], p[best + 1])))
            best = i;
    return best;
}

/* z = a x + b y + c through the triangle (p0, p1, p2), area2 d != 0. */
static WlPphigsLin z_plane(ScreenPt p0, ScreenPt p1, ScreenPt p2, double d)
{
    double a = ((p1.z - p0.z) * (p2.y - p0.y) - (p2.z - p0.z) * (p1.y - p0.y)) / d;
    double b = ((p2.z - p0.z) * (p1.x - p0.x) - (p1.z - p0.z) * (p2.x - p0.x)) / d;
    return (WlPphigsLin){a, b, p0.z - a * p0.x - b * p0.y};
}

/* colour x s, clamped, as 0xAABBGGRR. */
static uint32_t rgba_of(Vec3 color, double s)
{
    double c[3] = {color.x * s, color.y * s, color.z * s};
    uint32_t out = 0xff000000u;
    for (int i = 0; i < 3; i++) {
        double x = c[i] < 0 ? 0 : c[i] > 1 ? 1 : c[i];
        out |= (uint32_t)lrint(x * 255) << (8 * i);
    }
    return out;
}

static uint32_t shade_rgba(Vec3 color, ScreenPt p0, ScreenPt p1, ScreenPt p2,
                           guint width, guint height)
{
    /* Normal in NDC: rescale screen x, y back to [-1, 1]. */
    Vec3 u = vec3(2 * (p1.x - p0.x) / width, -2 * (p1.y - p0.y) / height,
                  p1.z - p0.z);
    Vec3 v = vec3(2 * (p2.x - p0.x) / width, -2 * (p2.y - p0.y) / height,
                  p2.z - p0.z);
    Vec3 n = vec3_cross(u, v); /* n.z = -4 d / (width height), d != 0 */
    return rgba_of(color, 0.3 + 0.7 * fabs(n.z) / vec3_len(n));
}

static void edges(WlPphigsCmd *c, const ScreenPt *p, guint n, double sign)
{
    c->nedges = n;
    for (guint i = 0; i < n; i++) {
        ScreenPt s = p[i], t = p[(i + 1) % n];
        c->edge[i] = (WlPphigsLin){sign * (s.y - t.y), sign * (t.x - s.x),
                                   sign * (s.x * t.y - t.x * s.y)};
    }
}

static int clampi(double v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : (int)v;
}

/* Pixel centres x + 0.5 inside [min, max] along each axis. */
static gboolean pixel_box(WlPphigsCmd *c, const ScreenPt *p, guint n,
                          guint width, guint height)
{
    double x0 = p[0].x, x1 = p[0].x, y0 = p[0].y, y1 = p[0].y;
    for (guint i = 1; i < n; i++) {
        x0 = MIN(x0, p[i].x), x1 = MAX(x1, p[i].x);
        y0 = MIN(y0, p[i].y), y1 = MAX(y1, p[i].y);
    }
    if (x1 < 0.5 || y1 < 0.5 || x0 > width - 0.5 || y0 > height - 0.5)
        return FALSE;
    c->x0 = clampi(ceil(x0 - 0.5), 0, (int)width - 1);
    c->x1 = clampi(floor(x1 - 0.5), 0, (int)width - 1);
    c->y0 = clampi(ceil(y0 - 0.5), 0, (int)height - 1);
    c->y1 = clampi(floor(y1 - 0.5), 0, (int)height - 1);
    return c->x0 <= c->x1 && c->y0 <= c->y1;
}

/* What every command carries besides its geometry: visibility order. */
static void cmd_order(WlPphigsCmd *c, const ScenePrimInst *pi)
{
    c->odp = pi->el->kind == SCENE_EL_POLYGON2D;
    c->priority = pi->priority;
    c->tag = (uint32_t)(pi->el->tag & 0x7fffffffu);
    c->sphere = FALSE;
}

/* One convex polygon of n clip-space vertices; FALSE if it draws nothing. */
static gboolean polygon_cmd(const ScenePrimInst *pi, const Vec4 *clip, guint n,
                            guint width, guint height, WlPphigsCmd *c)
{
    Vec4 cv[MAX_CLIP];
    ScreenPt p[MAX_CLIP];
    n = clip_near(clip, n, cv);
    if (n < 3 || n > WL_PPHIGS_MAX_EDGES)
        return FALSE;
    for (guint i = 0; i < n; i++)
        p[i] = to_screen(cv[i], width, height);
    guint f = best_fan(p, n);
    double d = area2(p[0], p[f], p[f + 1]);
    if (!(fabs(d) > 1e-12) || !pixel_box(c, p, n, width, height))
        return FALSE;
    edges(c, p, n, d > 0 ? 1 : -1);
    c->z = z_plane(p[0], p[f], p[f + 1], d);
    c->rgba = shade_rgba(pi->color, p[0], p[f], p[f + 1], width, height);
    cmd_order(c, pi);
    return TRUE;
}

/* A line: the quad one pixel wide about its projected segment. */
static gboolean line_cmd(const ScenePrimInst *pi, Mat4 m, guint width,
                         guint height, WlPphigsCmd *c)
{
    Vec4 a = mat4_apply_point(m, pi->el->verts[0]);
    Vec4 b = mat4_apply_point(m, pi->el->verts[1]);
    if (a.w <= W_EPS && b.w <= W_EPS)
        return FALSE;
    if (a.w <= W_EPS)
        a = lerp4(a, b, (W_EPS - a.w) / (b.w - a.w));
    else if (b.w <= W_EPS)
        b = lerp4(b, a, (W_EPS - b.w) / (a.w - b.w));
    ScreenPt p = to_screen(a, width, height), q = to_screen(b, width, height);
    double dx = q.x - p.x, dy = q.y - p.y, len2 = dx * dx + dy * dy;
    if (!(len2 > 1e-18))
        return FALSE;
    double h = 0.5 / sqrt(len2), nx = -dy * h, ny = dx * h;
    ScreenPt quad[4] = {{p.x + nx, p.y + ny, p.z}, {q.x + nx, q.y + ny, q.z},
                        {q.x - nx, q.y - ny, q.z}, {p.x - nx, p.y - ny, p.z}};
    if (!pixel_box(c, quad, 4, width, height))
        return FALSE;
    edges(c, quad, 4, area2(quad[0], quad[1], quad[2]) > 0 ? 1 : -1);
    double gx = (q.z - p.z) * dx / len2, gy = (q.z - p.z) * dy / len2;
    c->z = (WlPphigsLin){gx, gy, p.z - gx * p.x - gy * p.y};
    c->rgba = rgba_of(pi->color, 1);
    cmd_order(c, pi);
    return TRUE;
}

/* A sphere: its disc and quadratic z and shading (pphigs_pixels.h). */
static gboolean sphere_cmd(const ScenePrimInst *pi, Mat4 m, guint width,
                           guint height, WlPphigsCmd *c)
{
    Vec3 o = pi->el->verts[0];
    double r = vec3_len(vec3_sub(pi->el->verts[1], o));
    Vec4 h = mat4_apply_point(m, o);
    if (h.w <= W_EPS)
        return FALSE;
    ScreenPt pc = to_screen(h, width, height);
    double rs = 0, dz = 0;
    for (int k = 0; k < 6; k++) {
        double d = k & 1 ? r : -r;
        Vec3 end = vec3_add(o, vec3(k / 2 == 0 ? d : 0, k / 2 == 1 ? d : 0,
                                    k / 2 == 2 ? d : 0));
        Vec4 e = mat4_apply_point(m, end);
        if (e.w <= W_EPS)
            return FALSE;
        ScreenPt p = to_screen(e, width, height);
        rs = MAX(rs, hypot(p.x - pc.x, p.y - pc.y));
        dz = MAX(dz, fabs(p.z - pc.z));
    }
    if (!(rs > 1e-9))
        return FALSE;
    ScreenPt box[2] = {{pc.x - rs, pc.y - rs, 0}, {pc.x + rs, pc.y + rs, 0}};
    if (!pixel_box(c, box, 2, width, height))
        return FALSE;
    cmd_order(c, pi);
    c->nedges = 0;
    c->sphere = TRUE;
    c->cx = pc.x, c->cy = pc.y, c->r2 = rs * rs;
    c->zc = pc.z, c->dz = dz;
    c->color = pi->color;
    c->rgba = 0;
    return TRUE;
}

guint wl_pphigs_cmds(const ScenePrimInst *pi, Mat4 vp, guint width,
                     guint height, GArray *out)
{
    const SceneElem *e = pi->el;
    Mat4 m = mat4_mul(vp, pi->matrix);
    if (e->kind == SCENE_EL_LINE || e->kind == SCENE_EL_SPHERE) {
        WlPphigsCmd c;
        if (e->nverts < 2 ||
            !(e->kind == SCENE_EL_LINE ? line_cmd(pi, m, width, height, &c)
                                       : sphere_cmd(pi, m, width, height, &c)))
            return 0;
        g_array_append_val(out, c);
        return 1;
    }
    gboolean strip = e->kind == SCENE_EL_TRISTRIP;
    guint n = strip ? 3 : e->nverts, count = 0;
    guint polys = strip ? (e->nverts >= 3 ? e->nverts - 2 : 0) : 1;
    if (n < 3 || n > WL_PPHIGS_MAX_EDGES)
        return 0;
    for (guint t = 0; t < polys; t++) {
        Vec4 clip[WL_PPHIGS_MAX_EDGES];
        for (guint i = 0; i < n; i++)
            clip[i] = mat4_apply_point(m, e->verts[t + i]);
        WlPphigsCmd c;
        if (polygon_cmd(pi, clip, n, width, height, &c)) {
            g_array_append_val(out, c);
            count++;
        }
    }
    return count;
}

guint wl_pphigs_cmd_exprs(const WlPphigsCmd *c)
{
    return c->sphere ? 0 : c->nedges + 1 + 3;
}

guint wl_pphigs_cmd_quads(const WlPphigsCmd *c)
{
    return c->sphere ? 5 : 0;
}

/* ---- the region's pixel array ----------------------------------------- */

WlPphigsRegion *wl_pphigs_region_new(int x0, int y0, int w, int h,
                                     uint32_t bg)
{
    WlPphigsRegion *r = g_new0(WlPphigsRegion, 1);
    *r = (WlPphigsRegion){x0, y0, w, h, g_new0(uint64_t, (gsize)w * h),
                          g_new(uint32_t, (gsize)w * h)};
    for (gsize i = 0; i < (gsize)w * h; i++)
        r->rgba[i] = bg;
    return r;
}

void wl_pphigs_region_free(WlPphigsRegion *r)
{
    if (!r)
        return;
    g_free(r->key);
    g_free(r->rgba);
    g_free(r);
}

/* A centre on an edge is inside for left and top edges only; the edge
 * of a repeated vertex (a = b = c = 0) excludes nothing. */
static gboolean inside(const WlPphigsLin *e, double x, double y)
{
    double v = e->a * x + e->b * y + e->c;
    return v > 0 || (v == 0 && (e->a > 0 || (e->a == 0 && e->b >= 0)));
}

/* A sphere's quadratic Q / r^2 at (x, y): in [0, 1] inside its disc. */
static double sphere_q(const WlPphigsCmd *c, double x, double y)
{
    double dx = x - c->cx, dy = y - c->cy;
    return (c->r2 - dx * dx - dy * dy) / c->r2;
}

/* The pixel's key, 0 when it does not draw (z outside [-1, 1]). */
static uint64_t pixel_key(const WlPphigsCmd *c, double x, double y)
{
    if (c->odp)
        return KEY_ODP | ((uint64_t)c->priority & (KEY_ODP - 1));
    double z = c->sphere ? c->zc - c->dz * sphere_q(c, x, y)
                         : c->z.a * x + c->z.b * y + c->z.c;
    if (!(z >= -1 && z <= 1))
        return 0;
    uint64_t depth = (uint64_t)llrint((1 - z) / 2 * (double)UINT32_MAX);
    return depth << 31 | c->tag;
}

static gboolean pixel_covered(const WlPphigsCmd *c, double x, double y)
{
    if (c->sphere)
        return sphere_q(c, x, y) >= 0;
    for (guint i = 0; i < c->nedges; i++)
        if (!inside(&c->edge[i], x, y))
            return FALSE;
    return TRUE;
}

uint64_t wl_pphigs_region_draw(WlPphigsRegion *r, const WlPphigsCmd *c)
{
    int x0 = MAX(c->x0, r->x0), x1 = MIN(c->x1, r->x0 + r->w - 1);
    int y0 = MAX(c->y0, r->y0), y1 = MIN(c->y1, r->y0 + r->h - 1);
    uint64_t won = 0;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            double px = x + 0.5, py = y + 0.5;
            if (!pixel_covered(c, px, py))
                continue;
            uint64_t k = pixel_key(c, px, py);
            gsize i = (gsize)(y - r->y0) * r->w + (x - r->x0);
            if (k > r->key[i]) {
                r->key[i] = k;
                r->rgba[i] = c->sphere ? rgba_of(c->color,
                                                 0.3 + 0.7 * sphere_q(c, px, py))
                                       : c->rgba;
                won++;
            }
        }
    return won;
}

void wl_pphigs_region_store(const WlPphigsRegion *r, RastImage *img)
{
    for (int y = 0; y < r->h; y++)
        for (int x = 0; x < r->w; x++)
            rast_image_set(img, r->x0 + x, r->y0 + y,
                           r->rgba[(gsize)y * r->w + x]);
}

/* ---- the serial reference --------------------------------------------- */

typedef struct {
    Mat4 vp;
    guint width, height;
    GArray *cmds;
    WlPphigsRegion *screen;
} Serial;

static void serial_prim(const ScenePrimInst *pi, void *ud)
{
    Serial *s = ud;
    g_array_set_size(s->cmds, 0);
    wl_pphigs_cmds(pi, s->vp, s->width, s->height, s->cmds);
    for (guint i = 0; i < s->cmds->len; i++)
        wl_pphigs_region_draw(s->screen,
                              &g_array_index(s->cmds, WlPphigsCmd, i));
}

RastImage *wl_pphigs_render_serial(const SceneDb *db, Mat4 vp, guint width,
                                   guint height)
{
    Serial s = {vp, width, height, g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd)),
                wl_pphigs_region_new(0, 0, (int)width, (int)height,
                                     0xff000000u)};
    scene_db_traverse(db, serial_prim, &s);
    RastImage *img = rast_image_new((int)width, (int)height);
    wl_pphigs_region_store(s.screen, img);
    wl_pphigs_region_free(s.screen);
    g_array_unref(s.cmds);
    return img;
}
