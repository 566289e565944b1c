/* pm_blocks.c — the regular block decomposition of a volume, its
 * visibility order, primary rays, footprints and block images
 * (pm_blocks.h).
 *
 * Block boundaries are lo + (hi - lo) i / d on each axis, computed one
 * way everywhere (edge()), and wl_pm_grid_block_of() corrects its first
 * guess against those same boundaries, so a point's block and the
 * blocks' boxes agree to the last bit.
 */
#include "sim/workload/pixelmerge/pm_blocks.h"
#include <stdlib.h>
#include <string.h>

static double axis(Vec3 v, int i)
{
    return i == 0 ? v.x : i == 1 ? v.y : v.z;
}

void wl_pm_grid_init(WlPmGrid *g, guint n, Vec3 lo, Vec3 hi)
{
    g_assert(n >= 1);
    guint best[3] = {n, 1, 1};
    uint64_t best_sum = (uint64_t)n + 2;
    for (guint a = n; a >= 1; a--) {
        if (n % a)
            continue;
        for (guint b = n / a; b >= 1; b--) {
            if ((n / a) % b)
                continue;
            guint c = n / a / b;
            uint64_t sum = (uint64_t)a + b + c;
            if (sum < best_sum) {
                best_sum = sum;
                best[0] = a, best[1] = b, best[2] = c;
            }
        }
    }
    for (int i = 0; i < 3; i++) {
        g->dims[i] = best[i];
        g->lo[i] = axis(lo, i);
        g->hi[i] = axis(hi, i);
    }
}

guint wl_pm_grid_count(const WlPmGrid *g)
{
    return g->dims[0] * g->dims[1] * g->dims[2];
}

/* Boundary k (0 .. dims) of axis i. */
static double edge(const WlPmGrid *g, int i, guint k)
{
    if (k == g->dims[i])
        return g->hi[i];
    return g->lo[i] + (g->hi[i] - g->lo[i]) * k / g->dims[i];
}

static void index3(const WlPmGrid *g, guint p, guint *ijk)
{
    ijk[0] = p % g->dims[0];
    ijk[1] = p / g->dims[0] % g->dims[1];
    ijk[2] = p / g->dims[0] / g->dims[1];
}

void wl_pm_grid_block(const WlPmGrid *g, guint p, Vec3 *lo, Vec3 *hi)
{
    guint k[3];
    index3(g, p, k);
    *lo = vec3(edge(g, 0, k[0]), edge(g, 1, k[1]), edge(g, 2, k[2]));
    *hi =
        vec3(edge(g, 0, k[0] + 1), edge(g, 1, k[1] + 1), edge(g, 2, k[2] + 1));
}

gboolean wl_pm_grid_inside(const WlPmGrid *g, Vec3 x)
{
    for (int i = 0; i < 3; i++)
        if (!(axis(x, i) >= g->lo[i] && axis(x, i) < g->hi[i]))
            return FALSE;
    return TRUE;
}

/* The slab of axis i holding coordinate v, clamped into the grid. */
static guint slab(const WlPmGrid *g, int i, double v)
{
    double f = (v - g->lo[i]) / (g->hi[i] - g->lo[i]) * g->dims[i];
    guint k = f <= 0 ? 0 : f >= g->dims[i] ? g->dims[i] - 1 : (guint)f;
    while (k > 0 && v < edge(g, i, k))
        k--;
    while (k + 1 < g->dims[i] && v >= edge(g, i, k + 1))
        k++;
    return k;
}

guint wl_pm_grid_block_of(const WlPmGrid *g, Vec3 x)
{
    return slab(g, 0, x.x) +
           g->dims[0] * (slab(g, 1, x.y) + g->dims[1] * slab(g, 2, x.z));
}

typedef struct {
    uint64_t key;
    guint block;
} Rank;

static int rank_cmp(const void *a, const void *b)
{
    const Rank *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->block < y->block ? -1 : x->block > y->block;
}

void wl_pm_grid_order(const WlPmGrid *g, const SceneCamera *cam, guint *order)
{
    guint n = wl_pm_grid_count(g);
    Vec3 fwd = vec3_sub(cam->target, cam->eye);
    Rank *r = g_new(Rank, n);
    for (guint p = 0; p < n; p++) {
        guint k[3];
        index3(g, p, k);
        r[p] = (Rank){0, p};
        for (int i = 0; i < 3; i++) {
            guint d = g->dims[i], e;
            if (cam->proj == SCENE_PERSPECTIVE)
                e = slab(g, i, axis(cam->eye, i));
            else
                e = axis(fwd, i) > 0 ? 0 : axis(fwd, i) < 0 ? d - 1 : k[i];
            r[p].key += k[i] > e ? k[i] - e : e - k[i];
        }
    }
    qsort(r, n, sizeof *r, rank_cmp);
    for (guint p = 0; p < n; p++)
        order[p] = r[p].block;
    g_free(r);
}

void wl_pm_rays_init(WlPmRays *r, const SceneCamera *cam, guint width,
                     guint height)
{
    double aspect = (double)width / height;
    Vec3 f = vec3_norm(vec3_sub(cam->target, cam->eye));
    Vec3 s = vec3_norm(vec3_cross(f, cam->up));
    Vec3 u = vec3_cross(s, f);
    double half = cam->proj == SCENE_PERSPECTIVE
                      ? tan(cam->fov_deg * G_PI / 360.0)
                      : cam->height / 2;
    *r = (WlPmRays){
        cam->proj,           cam->eye, f,     vec3_scale(s, half * aspect),
        vec3_scale(u, half), width,    height};
}

void wl_pm_ray(const WlPmRays *r, guint x, guint y, Vec3 *org, Vec3 *dir)
{
    double nx = 2.0 * (x + 0.5) / r->width - 1.0;
    double ny = 1.0 - 2.0 * (y + 0.5) / r->height;
    Vec3 off = vec3_add(vec3_scale(r->right, nx), vec3_scale(r->up, ny));
    if (r->proj == SCENE_PERSPECTIVE) {
        *org = r->eye;
        *dir = vec3_norm(vec3_add(r->fwd, off));
    } else {
        *org = vec3_add(r->eye, off);
        *dir = r->fwd;
    }
}

gboolean wl_pm_ray_box(Vec3 org, Vec3 dir, Vec3 lo, Vec3 hi, double *t0,
                       double *t1)
{
    double a = 0, b = INFINITY;
    for (int i = 0; i < 3; i++) {
        double o = axis(org, i), d = axis(dir, i);
        double l = axis(lo, i), h = axis(hi, i);
        if (d == 0) {
            if (o < l || o > h)
                return FALSE;
            continue;
        }
        double ta = (l - o) / d, tb = (h - o) / d;
        a = fmax(a, fmin(ta, tb));
        b = fmin(b, fmax(ta, tb));
    }
    *t0 = a;
    *t1 = b;
    return b > a;
}

/* Pixel range [*a, *b) of the centres inside [lo, hi] on a side of n
 * pixels, widened by a millionth of a pixel against rounding. */
static void centres(double lo, double hi, guint n, guint *a, guint *b)
{
    double x0 = ceil(lo - 0.5 - 1e-6), x1 = floor(hi - 0.5 + 1e-6) + 1;
    *a = x0 <= 0 ? 0 : x0 >= n ? n : (guint)x0;
    *b = x1 <= 0 ? 0 : x1 >= n ? n : (guint)x1;
}

gboolean wl_pm_block_rect(const WlPmGrid *g, const WlPmRays *r, guint p,
                          WlPmRect *rect)
{
    Vec3 lo, hi;
    wl_pm_grid_block(g, p, &lo, &hi);
    double sx = vec3_dot(r->right, r->right), sy = vec3_dot(r->up, r->up);
    double px[2] = {INFINITY, -INFINITY}, py[2] = {INFINITY, -INFINITY};
    for (int c = 0; c < 8; c++) {
        Vec3 q =
            vec3(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
        Vec3 v = vec3_sub(q, r->eye);
        double d = r->proj == SCENE_PERSPECTIVE ? vec3_dot(v, r->fwd) : 1.0;
        if (!(d > 1e-12)) { /* a corner at or behind the eye */
            *rect = (WlPmRect){0, 0, r->width, r->height};
            return TRUE;
        }
        double x = (vec3_dot(v, r->right) / (sx * d) + 1) * 0.5 * r->width;
        double y = (1 - vec3_dot(v, r->up) / (sy * d)) * 0.5 * r->height;
        px[0] = fmin(px[0], x), px[1] = fmax(px[1], x);
        py[0] = fmin(py[0], y), py[1] = fmax(py[1], y);
    }
    centres(px[0], px[1], r->width, &rect->x0, &rect->x1);
    centres(py[0], py[1], r->height, &rect->y0, &rect->y1);
    return rect->x0 < rect->x1 && rect->y0 < rect->y1;
}

void wl_pm_block_color(guint p, double *rgb)
{
    double h = fmod(0.13 + p * 0.6180339887498949, 1.0) * 6.0;
    double f = h - floor(h), v = 0.9, s = 0.6;
    double q[6][3] = {{1, f, 0},     {1 - f, 1, 0}, {0, 1, f},
                      {0, 1 - f, 1}, {f, 0, 1},     {1, 0, 1 - f}};
    for (int i = 0; i < 3; i++)
        rgb[i] = v * (1 - s + s * q[(int)h % 6][i]);
}

static guint8 byte_of(double v)
{
    return (guint8)CLAMP(v * 255.0 + 0.5, 0.0, 255.0);
}

WlPmWpa *wl_pm_block_cast(const WlPmGrid *g, const WlPmRays *r, guint p,
                          WlPmRayFn fn, void *ctx, WlPmCounts *c)
{
    memset(c, 0, sizeof *c);
    c->polygons = c->rc.prims = 1;
    WlPmWpa *w = wl_pm_wpa_new(r->width, r->height);
    WlPmRect rc;
    gboolean on = wl_pm_block_rect(g, r, p, &rc);
    for (guint y = rc.y0; on && y < rc.y1; y++) {
        uint64_t before = c->rc.winners;
        for (guint x = rc.x0; x < rc.x1; x++) {
            Vec3 o, d;
            double z = 0, v[4];
            wl_pm_ray(r, x, y, &o, &d);
            if (!fn(ctx, o, d, &z, v, c))
                continue;
            uint32_t col = 0; /* the colour itself, not premultiplied */
            for (int i = 0; i < 3; i++)
                col = col << 8 | byte_of(v[i] / v[3]);
            WlPmPixel px = {(uint16_t)x, (uint16_t)y, z, p, col};
            wl_pm_wpa_push_rgba(w, &px, v);
            c->rc.winners++;
        }
        if (c->rc.winners > before)
            c->rc.spans++, c->span_rows++;
    }
    wl_pm_wpa_finish(w);
    return w;
}

/* A homogeneous block: its box, hue and extinction. */
typedef struct {
    Vec3 lo, hi;
    double rgb[3], density;
} Slab;

static gboolean slab_ray(void *ctx, Vec3 o, Vec3 d, double *z, double *rgba,
                         WlPmCounts *c)
{
    const Slab *s = ctx;
    double t0, t1;
    if (!wl_pm_ray_box(o, d, s->lo, s->hi, &t0, &t1))
        return FALSE;
    double a = 1.0 - exp(-s->density * (t1 - t0));
    for (int i = 0; i < 3; i++)
        rgba[i] = s->rgb[i] * a;
    rgba[3] = a;
    *z = t0;
    c->rc.pixels++;
    return a > 0;
}

WlPmWpa *wl_pm_block_image(const WlPmGrid *g, const WlPmRays *r, guint p,
                           double density, WlPmCounts *c)
{
    Slab s = {.density = density};
    wl_pm_grid_block(g, p, &s.lo, &s.hi);
    wl_pm_block_color(p, s.rgb);
    return wl_pm_block_cast(g, r, p, slab_ray, &s, c);
}
