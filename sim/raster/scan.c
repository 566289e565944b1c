/* scan.c — viewport mapping, triangle set-up and exact scan conversion.
 *
 * Coverage: for edge a->b of a triangle with positive area, the edge
 * function E(p) = dx (p.y - a.y) - dy (p.x - a.x) is positive inside.  On
 * the row whose centre is py, E is C - dy px with C = dx (py - a.y) +
 * dy a.x, so each non-horizontal edge bounds the pixel index from one
 * side; the bound is found with one exact integer (floor/ceil) division.
 * Left edges (dy < 0) and top edges (dy == 0, dx > 0) include E == 0.
 * Magnitudes: |coordinates| < 2^26 (guard band, 8 fractional bits), so
 * |C| < 2^56 and everything fits in int64.
 *
 * Attributes: depth and colour planes are set up in doubles from the
 * snapped positions and evaluated at pixel centres; a span carries the
 * value at its first pixel and the x increment.
 *
 * Pineda (SIGGRAPH 1988) edge functions; top-left rule as in the
 * Direct3D 10 rasterisation rules.  O(rows) per triangle.
 */
#include "sim/raster/scan.h"

double rast_guard_band(int width, int height)
{
    g_assert(width > 0 && height > 0);
    g_assert(width <= RAST_MAX_SIDE && height <= RAST_MAX_SIDE);
    int side = width > height ? width : height;
    return 65536.0 / side;
}

static int64_t snap(double v)
{
    return (int64_t)llround(v * RAST_SUBPIX);
}

RastScreenVert rast_viewport(const RastVert *v, int width, int height)
{
    g_assert(v->pos.w >= RAST_CLIP_WMIN);
    double iw = 1.0 / v->pos.w;
    RastScreenVert s;
    s.x = snap((v->pos.x * iw + 1.0) * 0.5 * width);
    s.y = snap((1.0 - v->pos.y * iw) * 0.5 * height);
    double z = (v->pos.z * iw + 1.0) * 0.5;
    s.z = z < 0.0 ? 0.0 : (z > 1.0 ? 1.0 : z);
    s.col = v->col;
    return s;
}

int64_t rast_area2(const RastScreenVert *a, const RastScreenVert *b,
                   const RastScreenVert *c)
{
    /* Screen y points down, so NDC counter-clockwise is negative here. */
    return -((b->x - a->x) * (c->y - a->y) - (b->y - a->y) * (c->x - a->x));
}

static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

static int64_t ceil_div(int64_t a, int64_t b)
{
    return -floor_div(-a, b);
}

typedef struct {
    int64_t ax, ay, dx, dy;
} Edge;

typedef struct {
    double x, y; /* vertex 0 in pixels */
    double z, dzdx, dzdy, zlo, zhi;
    double c[3], dcdx[3], dcdy[3];
} Planes;

/* A triangle's pixel-unit edge vectors from vertex 0 and the inverse of
 * their cross product. */
typedef struct {
    double e1x, e1y, e2x, e2y, inv;
} Basis;

/* The value of one attribute plane: gradients from the three vertex
 * values f0, f1, f2 over basis b. */
static void plane(double f0, double f1, double f2, const Basis *b, double *dx,
                  double *dy)
{
    *dx = ((f1 - f0) * b->e2y - (f2 - f0) * b->e1y) * b->inv;
    *dy = ((f2 - f0) * b->e1x - (f1 - f0) * b->e2x) * b->inv;
}

static void setup_planes(const RastScreenVert v[3], Planes *p)
{
    const double s = 1.0 / RAST_SUBPIX;
    p->x = v[0].x * s;
    p->y = v[0].y * s;
    Basis b = {(v[1].x - v[0].x) * s, (v[1].y - v[0].y) * s,
               (v[2].x - v[0].x) * s, (v[2].y - v[0].y) * s, 0};
    b.inv = 1.0 / (b.e1x * b.e2y - b.e1y * b.e2x);
    p->z = v[0].z;
    plane(v[0].z, v[1].z, v[2].z, &b, &p->dzdx, &p->dzdy);
    p->zlo = fmin(v[0].z, fmin(v[1].z, v[2].z));
    p->zhi = fmax(v[0].z, fmax(v[1].z, v[2].z));
    const float *c0 = &v[0].col.r, *c1 = &v[1].col.r, *c2 = &v[2].col.r;
    for (int k = 0; k < 3; k++) {
        p->c[k] = c0[k];
        plane(c0[k], c1[k], c2[k], &b, &p->dcdx[k], &p->dcdy[k]);
    }
}

/* Narrows [*lo, *hi) to the pixels of row centre py inside edge e;
 * returns FALSE if the row is empty.  RAST_SPAN_EXACT: pixel centres
 * inside (top-left rule); RAST_SPAN_ENDPOINTS: every pixel from the one
 * holding the left intersection to the one holding the right one. */
static gboolean edge_bound(const Edge *e, int64_t py, RastSpanRule rule,
                           int64_t *lo, int64_t *hi)
{
    const int64_t half = RAST_SUBPIX / 2;
    if (e->dy == 0) {
        int64_t E = e->dx * (py - e->ay);
        return E > 0 || (E == 0 && e->dx > 0);
    }
    int64_t C = e->dx * (py - e->ay) + e->dy * e->ax;
    gboolean ends = rule == RAST_SPAN_ENDPOINTS;
    if (e->dy < 0) { /* left edge: E >= 0, crossing at x = -C / k */
        int64_t k = -e->dy;
        int64_t b = ends ? floor_div(-C, RAST_SUBPIX * k)
                         : ceil_div(-C - half * k, RAST_SUBPIX * k);
        if (b > *lo)
            *lo = b;
    } else { /* right edge: E > 0, crossing at x = C / dy */
        int64_t b = ends ? floor_div(C, RAST_SUBPIX * e->dy) + 1
                         : ceil_div(C - half * e->dy, RAST_SUBPIX * e->dy);
        if (b < *hi)
            *hi = b;
    }
    return *lo < *hi;
}

static void emit_span(const Planes *p, int y, int64_t lo, int64_t hi,
                      uint32_t prim, RastSpanSink sink, RastCounters *c)
{
    RastSpan s;
    s.y = y;
    s.x0 = (int32_t)lo;
    s.x1 = (int32_t)hi;
    s.prim = prim;
    double px = lo + 0.5 - p->x, py = y + 0.5 - p->y;
    s.z0 = p->z + p->dzdx * px + p->dzdy * py;
    s.dzdx = p->dzdx;
    s.zlo = p->zlo;
    s.zhi = p->zhi;
    for (int k = 0; k < 3; k++) {
        s.c0[k] = (float)(p->c[k] + p->dcdx[k] * px + p->dcdy[k] * py);
        s.dcdx[k] = (float)p->dcdx[k];
    }
    c->spans++;
    c->pixels += (uint64_t)(hi - lo);
    sink.fn(sink.ctx, &s, c);
}

/* Rows whose centres lie within [ymin, ymax] (fixed point), clamped. */
static void row_range(int64_t ymin, int64_t ymax, int height, int64_t *r0,
                      int64_t *r1)
{
    const int64_t half = RAST_SUBPIX / 2;
    *r0 = ceil_div(ymin - half, RAST_SUBPIX);
    *r1 = floor_div(ymax - half, RAST_SUBPIX) + 1;
    if (*r0 < 0)
        *r0 = 0;
    if (*r1 > height)
        *r1 = height;
}

/* A convex polygon's edges e[0..ne) (E > 0 inside) and its fixed-point
 * height range. */
typedef struct {
    Edge e[RAST_SCAN_MAX];
    int ne;
    int64_t ymin, ymax;
} Outline;

/* Emits the rows of the convex polygon o. */
static uint64_t scan_rows(const Outline *o, const Planes *p, uint32_t prim,
                          int width, int height, RastSpanRule rule,
                          RastSpanSink sink, RastCounters *c)
{
    const Edge *e = o->e;
    int ne = o->ne;
    int64_t r0, r1;
    row_range(o->ymin, o->ymax, height, &r0, &r1);
    uint64_t n = 0;
    for (int64_t y = r0; y < r1; y++) {
        int64_t py = y * RAST_SUBPIX + RAST_SUBPIX / 2, lo = 0, hi = width;
        gboolean in = TRUE;
        for (int i = 0; in && i < ne; i++)
            in = edge_bound(&e[i], py, rule, &lo, &hi);
        if (in) {
            emit_span(p, (int)y, lo, hi, prim, sink, c);
            n++;
        }
    }
    return n;
}

/* The outline of t[0..n) into o.  A corner repeated next to itself
 * (clipping emits a corner lying on a plane twice, and snapping can merge
 * close ones) makes an edge of length zero, which bounds nothing: it is
 * left out (as an edge it would empty every row). */
static void outline_of(const RastScreenVert *t, int n, Outline *o)
{
    o->ne = 0;
    o->ymin = o->ymax = t[0].y;
    for (int i = 0; i < n; i++) {
        const RastScreenVert *a = &t[i], *b = &t[(i + 1) % n];
        if (a->x != b->x || a->y != b->y)
            o->e[o->ne++] = (Edge){a->x, a->y, b->x - a->x, b->y - a->y};
        o->ymin = MIN(o->ymin, a->y);
        o->ymax = MAX(o->ymax, a->y);
    }
}

uint64_t rast_scan_triangle(const RastScreenVert v[3], uint32_t prim, int width,
                            int height, RastSpanSink sink, RastCounters *c)
{
    /* Order the vertices so that E > 0 inside (negative rast_area2). */
    RastScreenVert t[3] = {v[0], v[1], v[2]};
    int64_t a2 = rast_area2(&t[0], &t[1], &t[2]);
    g_assert(a2 != 0);
    if (a2 > 0) {
        t[1] = v[2];
        t[2] = v[1];
    }
    Outline o;
    outline_of(t, 3, &o);
    Planes p;
    setup_planes(t, &p);
    return scan_rows(&o, &p, prim, width, height, RAST_SPAN_EXACT, sink, c);
}

/* Index i of the fan triangle (0, i, i+1) of largest |area|: the best
 * conditioned vertices for the attribute planes. */
static int widest_fan(const RastScreenVert *t, int n)
{
    int best = 1;
    int64_t best_a = -1;
    for (int i = 1; i + 1 < n; i++) {
        int64_t a = rast_area2(&t[0], &t[i], &t[i + 1]);
        a = a < 0 ? -a : a;
        if (a > best_a) {
            best_a = a;
            best = i;
        }
    }
    return best;
}

uint64_t rast_scan_polygon(const RastScreenVert *v, int n, uint32_t prim,
                           int width, int height, RastSpanRule rule,
                           RastSpanSink sink, RastCounters *c)
{
    g_assert(n >= 3 && n <= RAST_SCAN_MAX);
    if (n == 3 && rule == RAST_SPAN_EXACT)
        return rast_scan_triangle(v, prim, width, height, sink, c);
    int64_t a2 = 0;
    for (int i = 1; i + 1 < n; i++)
        a2 += rast_area2(&v[0], &v[i], &v[i + 1]);
    g_assert(a2 != 0);
    RastScreenVert t[RAST_SCAN_MAX];
    for (int i = 0; i < n; i++) /* reversed when counter-clockwise */
        t[i] = a2 > 0 ? v[(n - i) % n] : v[i];
    Outline o;
    outline_of(t, n, &o);
    int k = widest_fan(t, n);
    RastScreenVert tri[3] = {t[0], t[k], t[k + 1]};
    Planes p;
    setup_planes(tri, &p);
    for (int i = 0; i < n; i++) {
        p.zlo = fmin(p.zlo, t[i].z);
        p.zhi = fmax(p.zhi, t[i].z);
    }
    return scan_rows(&o, &p, prim, width, height, rule, sink, c);
}
