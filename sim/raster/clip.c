/* clip.c — homogeneous polygon clipping (Sutherland–Hodgman).
 *
 * The polygon is clipped against one plane at a time, ping-ponging
 * between two small arrays.  A plane is a linear function d(p) of the
 * clip-space position; a vertex is inside when d >= 0.  Intersections
 * are computed from the lexicographically smaller endpoint, so a shared
 * edge is cut at the same point in both polygons (see clip.h).
 * Invariant: a convex polygon gains at most one vertex per plane, so an
 * input of up to 9 vertices fits RAST_CLIP_MAX = 16 after seven planes.
 * O(n) per plane.
 */
#include "sim/raster/clip.h"

typedef double (*PlaneFn)(Vec4 p, double guard);

static double d_near(Vec4 p, double g)
{
    (void)g;
    return p.z + p.w;
}
static double d_far(Vec4 p, double g)
{
    (void)g;
    return p.w - p.z;
}
static double d_w(Vec4 p, double g)
{
    (void)g;
    return p.w - RAST_CLIP_WMIN;
}
static double d_left(Vec4 p, double g)
{
    return g * p.w + p.x;
}
static double d_right(Vec4 p, double g)
{
    return g * p.w - p.x;
}
static double d_bottom(Vec4 p, double g)
{
    return g * p.w + p.y;
}
static double d_top(Vec4 p, double g)
{
    return g * p.w - p.y;
}

/* In the order of the outcode bits. */
static const PlaneFn planes[] = {d_near,  d_far,    d_w,  d_left,
                                 d_right, d_bottom, d_top};
#define N_PLANES ((int)(sizeof planes / sizeof planes[0]))

unsigned rast_clip_outcode(Vec4 p, double guard)
{
    unsigned code = 0;
    for (int i = 0; i < N_PLANES; i++)
        if (!(planes[i](p, guard) >= 0))
            code |= 1u << i;
    return code;
}

static gboolean vert_less(const RastVert *a, const RastVert *b)
{
    if (a->pos.x != b->pos.x)
        return a->pos.x < b->pos.x;
    if (a->pos.y != b->pos.y)
        return a->pos.y < b->pos.y;
    if (a->pos.z != b->pos.z)
        return a->pos.z < b->pos.z;
    return a->pos.w < b->pos.w;
}

static float lerpf(float a, float b, double t)
{
    return (float)(a + (b - a) * t);
}

/* The point where edge (a, b) crosses the plane, computed from the
 * smaller endpoint so the result does not depend on the edge direction. */
static RastVert intersect(const RastVert *a, const RastVert *b, PlaneFn d,
                          double g)
{
    if (vert_less(b, a)) {
        const RastVert *t = a;
        a = b;
        b = t;
    }
    double da = d(a->pos, g), db = d(b->pos, g);
    double t = da / (da - db);
    RastVert v;
    v.pos.x = a->pos.x + (b->pos.x - a->pos.x) * t;
    v.pos.y = a->pos.y + (b->pos.y - a->pos.y) * t;
    v.pos.z = a->pos.z + (b->pos.z - a->pos.z) * t;
    v.pos.w = a->pos.w + (b->pos.w - a->pos.w) * t;
    /* Rounding may leave a point cut by the w plane a hair below it;
     * the viewport divides by w, so put it on the plane. */
    if (d == d_w && v.pos.w < RAST_CLIP_WMIN)
        v.pos.w = RAST_CLIP_WMIN;
    v.col.r = lerpf(a->col.r, b->col.r, t);
    v.col.g = lerpf(a->col.g, b->col.g, t);
    v.col.b = lerpf(a->col.b, b->col.b, t);
    return v;
}

static int clip_plane(const RastVert *in, int n, PlaneFn d, double g,
                      RastVert *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const RastVert *a = &in[i], *b = &in[(i + 1) % n];
        gboolean ain = d(a->pos, g) >= 0, bin = d(b->pos, g) >= 0;
        if (ain)
            out[m++] = *a;
        if (ain != bin) {
            g_assert(m < RAST_CLIP_MAX);
            out[m++] = intersect(a, b, d, g);
        }
    }
    return m;
}

int rast_clip_polygon(const RastVert *in, int n, double guard, RastVert *out)
{
    g_assert(n >= 3 && n <= RAST_CLIP_MAX - N_PLANES);
    g_assert(guard >= 1.0);
    RastVert buf[2][RAST_CLIP_MAX];
    unsigned any = 0;
    for (int i = 0; i < n; i++)
        any |= rast_clip_outcode(in[i].pos, guard);
    const RastVert *cur = in;
    int k = 0;
    for (int p = 0; p < N_PLANES && n >= 3; p++) {
        if (!(any & (1u << p)))
            continue;
        n = clip_plane(cur, n, planes[p], guard, buf[k]);
        cur = buf[k];
        k ^= 1;
    }
    if (n < 3)
        return 0;
    for (int i = 0; i < n; i++)
        out[i] = cur[i];
    return n;
}
