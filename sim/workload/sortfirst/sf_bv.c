/* sf_bv.c — spheres, oriented boxes and slab sets around chunks, their
 * screen rectangles, test costs and fit (sf_bv.h; seed 000 §3.3.1).
 *
 * The slab normals are Kay and Kajiya's ("Ray tracing complex scenes",
 * SIGGRAPH 1986, the paper's reference [1]): the three axes and the
 * four diagonals of the cube.
 */
#include "sim/workload/sortfirst/sf_bv.h"
#include <math.h>
#include <string.h>

const char *const wl_sf_bv_names[] = {"aabb", "sphere", "obb", "slabs", NULL};

static const Vec3 slab_normal[WL_SF_BV_SLAB_NORMALS] = {
    {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1},
    {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};

/* Calls fn on every vertex of chunk c's primitives. */
typedef void (*VertFn)(Vec3 v, void *ud);

static void each_vert(const WlSfDb *d, const SceneDb *db, guint c, VertFn fn,
                      void *ud)
{
    const WlSfChunk *ch = wl_sf_chunk(d, c);
    for (guint k = 0; k < ch->n_prims; k++) {
        guint pos = g_array_index(d->prims, guint, ch->prim_first + k);
        const SceneElem *e = scene_db_elem(db, ch->sid, pos);
        for (guint v = 0; v < e->nverts; v++)
            fn(e->verts[v], ud);
    }
}

/* ---- building ------------------------------------------------------------ */

typedef struct {
    Vec3 centre;
    double r2;
} Far;

static void far_vert(Vec3 v, void *ud)
{
    Far *f = ud;
    Vec3 dv = vec3_sub(v, f->centre);
    f->r2 = MAX(f->r2, vec3_dot(dv, dv));
}

typedef struct {
    double n, s[3], ss[3][3];
} Moments;

static void moment_vert(Vec3 v, void *ud)
{
    Moments *m = ud;
    double p[3] = {v.x, v.y, v.z};
    m->n++;
    for (int i = 0; i < 3; i++) {
        m->s[i] += p[i];
        for (int j = 0; j < 3; j++)
            m->ss[i][j] += p[i] * p[j];
    }
}

/* Eigenvectors of the symmetric a (columns of v) by Jacobi rotations. */
static void jacobi(double a[3][3], double v[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            v[i][j] = i == j;
    for (int sweep = 0; sweep < 32; sweep++) {
        double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        if (off < 1e-15)
            return;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                if (fabs(a[p][q]) < 1e-300)
                    continue;
                double th = (a[q][q] - a[p][p]) / (2 * a[p][q]);
                double t = (th >= 0 ? 1 : -1) / (fabs(th) + sqrt(th * th + 1));
                double c = 1 / sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 3; k++) { /* a = J^T a J */
                    double kp = a[k][p], kq = a[k][q];
                    a[k][p] = c * kp - s * kq;
                    a[k][q] = s * kp + c * kq;
                }
                for (int k = 0; k < 3; k++) {
                    double pk = a[p][k], qk = a[q][k];
                    a[p][k] = c * pk - s * qk;
                    a[q][k] = s * pk + c * qk;
                }
                for (int k = 0; k < 3; k++) {
                    double kp = v[k][p], kq = v[k][q];
                    v[k][p] = c * kp - s * kq;
                    v[k][q] = s * kp + c * kq;
                }
            }
    }
}

/* Extents of the vertices along n axes: lo[i], hi[i]. */
typedef struct {
    const Vec3 *axis;
    guint n;
    double lo[WL_SF_BV_SLAB_NORMALS], hi[WL_SF_BV_SLAB_NORMALS];
} Extent;

static void extent_vert(Vec3 v, void *ud)
{
    Extent *x = ud;
    for (guint i = 0; i < x->n; i++) {
        double t = vec3_dot(v, x->axis[i]);
        x->lo[i] = MIN(x->lo[i], t);
        x->hi[i] = MAX(x->hi[i], t);
    }
}

static void extent_of(const WlSfDb *d, const SceneDb *db, guint c,
                      Extent *x)
{
    for (guint i = 0; i < x->n; i++) {
        x->lo[i] = INFINITY;
        x->hi[i] = -INFINITY;
    }
    each_vert(d, db, c, extent_vert, x);
}

static void add_vert(WlSfDb *d, Vec3 v)
{
    g_array_append_val(d->bv_verts, v);
}

static void build_obb(WlSfDb *d, const SceneDb *db, guint c, WlSfBv *bv)
{
    Moments m = {0};
    each_vert(d, db, c, moment_vert, &m);
    double cov[3][3], ev[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            cov[i][j] = m.ss[i][j] / m.n - m.s[i] * m.s[j] / (m.n * m.n);
    jacobi(cov, ev);
    Vec3 axis[3];
    for (int k = 0; k < 3; k++)
        axis[k] = vec3(ev[0][k], ev[1][k], ev[2][k]);
    Extent x = {axis, 3, {0}, {0}};
    extent_of(d, db, c, &x);
    for (int k = 0; k < 8; k++) {
        Vec3 p = vec3(0, 0, 0);
        for (int a = 0; a < 3; a++)
            p = vec3_add(p, vec3_scale(axis[a], k >> a & 1 ? x.hi[a] : x.lo[a]));
        add_vert(d, p);
    }
    bv->n = 8;
}

/* Solves rows n[0..2] . p = w[0..2]; FALSE when singular. */
static gboolean solve3(const Vec3 n[3], const double w[3], Vec3 *p)
{
    Vec3 c12 = vec3_cross(n[1], n[2]), c20 = vec3_cross(n[2], n[0]),
         c01 = vec3_cross(n[0], n[1]);
    double det = vec3_dot(n[0], c12);
    if (fabs(det) < 1e-12)
        return FALSE;
    *p = vec3_scale(vec3_add(vec3_add(vec3_scale(c12, w[0]),
                                      vec3_scale(c20, w[1])),
                             vec3_scale(c01, w[2])),
                    1 / det);
    return TRUE;
}

/* Plane k of the slab set: normal and offset (outward). */
static void slab_plane(const Extent *x, guint k, Vec3 *n, double *w)
{
    guint i = k / 2;
    *n = k & 1 ? vec3_scale(x->axis[i], -1) : x->axis[i];
    *w = k & 1 ? -x->lo[i] : x->hi[i];
}

static gboolean inside(const Extent *x, Vec3 p, double tol)
{
    for (guint i = 0; i < x->n; i++) {
        double t = vec3_dot(p, x->axis[i]);
        if (t < x->lo[i] - tol || t > x->hi[i] + tol)
            return FALSE;
    }
    return TRUE;
}

static gboolean seen(const WlSfDb *d, guint first, Vec3 p, double tol)
{
    for (guint k = first; k < d->bv_verts->len; k++) {
        Vec3 q = g_array_index(d->bv_verts, Vec3, k);
        if (fabs(q.x - p.x) <= tol && fabs(q.y - p.y) <= tol &&
            fabs(q.z - p.z) <= tol)
            return TRUE;
    }
    return FALSE;
}

/* The slab set's vertices: every three planes meeting inside the rest.
 * The slabs are widened by a hair (1e-9 of the box's size) so that the
 * polytope contains the vertices despite rounding. */
static void build_slabs(WlSfDb *d, const SceneDb *db, guint c, WlSfBv *bv)
{
    Extent x = {slab_normal, WL_SF_BV_SLAB_NORMALS, {0}, {0}};
    extent_of(d, db, c, &x);
    double size = vec3_len(scene_box_size(wl_sf_chunk(d, c)->box));
    double hair = 1e-9 * MAX(size, 1e-300), tol = 1e-7 * MAX(size, 1e-300);
    for (guint i = 0; i < x.n; i++) {
        double len = vec3_len(slab_normal[i]);
        x.lo[i] -= hair * len;
        x.hi[i] += hair * len;
    }
    guint np = 2 * WL_SF_BV_SLAB_NORMALS;
    for (guint a = 0; a < np; a++)
        for (guint b = a + 1; b < np; b++)
            for (guint e = b + 1; e < np; e++) {
                Vec3 n[3];
                double w[3];
                Vec3 p;
                slab_plane(&x, a, &n[0], &w[0]);
                slab_plane(&x, b, &n[1], &w[1]);
                slab_plane(&x, e, &n[2], &w[2]);
                if (solve3(n, w, &p) && inside(&x, p, tol) &&
                    !seen(d, bv->first, p, tol))
                    add_vert(d, p);
            }
    bv->n = d->bv_verts->len - bv->first;
    if (bv->n < 4) { /* degenerate: the box's corners, which hold it */
        g_array_set_size(d->bv_verts, bv->first);
        SceneBox bx = wl_sf_chunk(d, c)->box;
        for (int k = 0; k < 8; k++)
            add_vert(d, vec3(k & 1 ? bx.max.x : bx.min.x,
                             k & 2 ? bx.max.y : bx.min.y,
                             k & 4 ? bx.max.z : bx.min.z));
        bv->n = 8;
    }
}

void wl_sf_bv_build(WlSfDb *d, const SceneDb *db)
{
    if (d->bvs)
        g_array_unref(d->bvs);
    if (d->bv_verts)
        g_array_unref(d->bv_verts);
    d->bvs = d->bv_verts = NULL;
    if (d->bv == WL_SF_BV_AABB)
        return;
    d->bvs = g_array_sized_new(FALSE, TRUE, sizeof(WlSfBv), d->chunks->len);
    d->bv_verts = g_array_new(FALSE, FALSE, sizeof(Vec3));
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        WlSfBv bv = {.first = d->bv_verts->len};
        if (d->bv == WL_SF_BV_SPHERE) {
            Far f = {scene_box_center(wl_sf_chunk(d, c)->box), 0};
            each_vert(d, db, c, far_vert, &f);
            bv.centre = f.centre;
            /* a hair more, so the vertices lie inside despite rounding */
            bv.radius = sqrt(f.r2) * (1 + 1e-9);
        } else if (d->bv == WL_SF_BV_OBB) {
            build_obb(d, db, c, &bv);
        } else {
            build_slabs(d, db, c, &bv);
        }
        g_array_append_val(d->bvs, bv);
    }
}

void wl_sf_bv_set(WlSfDb *d, const SceneDb *db, WlSfBvKind kind)
{
    d->bv = (int)kind;
    wl_sf_bv_build(d, db);
}

WlSfBvCost wl_sf_bv_cost(const WlSfDb *d)
{
    WlSfBvCost c = {8, 0};
    if (d->bv == WL_SF_BV_SPHERE) {
        c.verts = 1;
        c.spheres = 1;
    } else if (d->bv == WL_SF_BV_SLABS && d->bvs && d->bvs->len) {
        c.verts = (d->bv_verts->len + d->bvs->len / 2) / d->bvs->len;
    }
    return c;
}

/* ---- screen rectangles -------------------------------------------------- */

/* The rectangle of n projected points (wl_sf_box_screen()'s rules). */
static WlSfScreen points_screen(const WlSfRegions *r, const Vec3 *p, guint n,
                                Mat4 m)
{
    WlSfScreen s = {INFINITY, INFINITY, -INFINITY, -INFINITY, FALSE};
    unsigned all = 0x3f;
    gboolean behind = FALSE;
    for (guint k = 0; k < n; k++)
        all &= wl_sf_screen_point(r, mat4_apply_point(m, p[k]), &s, &behind);
    s.on = n > 0 && !all;
    if (behind) {
        s.x0 = s.y0 = -INFINITY;
        s.x1 = s.y1 = INFINITY;
    }
    return s;
}

/* A plane of clip space pulled back to object space: n . p + d. */
typedef struct {
    Vec3 n;
    double d;
} Plane;

static Plane row(Mat4 m, int i)
{
    return (Plane){vec3(m.m[i][0], m.m[i][1], m.m[i][2]), m.m[i][3]};
}

static Plane comb(Plane a, double s, Plane b)
{
    return (Plane){vec3_add(a.n, vec3_scale(b.n, s)), a.d + s * b.d};
}

/* The k of the two planes a - k w tangent to the sphere (k0 <= k1). */
static void tangents(Plane a, Plane w, Vec3 c, double r, double *k0,
                     double *k1)
{
    double sa = vec3_dot(a.n, c) + a.d, sw = vec3_dot(w.n, c) + w.d;
    double r2 = r * r;
    double qa = sw * sw - r2 * vec3_dot(w.n, w.n);
    double qb = sa * sw - r2 * vec3_dot(a.n, w.n);
    double qc = sa * sa - r2 * vec3_dot(a.n, a.n);
    double disc = sqrt(MAX(qb * qb - qa * qc, 0));
    *k0 = (qb - disc) / qa;
    *k1 = (qb + disc) / qa;
}

static WlSfScreen sphere_screen(const WlSfRegions *r, Vec3 c, double rad,
                                Mat4 m)
{
    WlSfScreen s = {0};
    Plane px = row(m, 0), py = row(m, 1), pz = row(m, 2), pw = row(m, 3);
    Plane clip[6] = {comb(pw, 1, px), comb(pw, -1, px), comb(pw, 1, py),
                     comb(pw, -1, py), comb(pw, 1, pz), comb(pw, -1, pz)};
    for (int k = 0; k < 6; k++) /* wholly outside one plane: culled */
        if (vec3_dot(clip[k].n, c) + clip[k].d <
            -rad * vec3_len(clip[k].n))
            return s;
    s.on = TRUE;
    double sw = vec3_dot(pw.n, c) + pw.d;
    if (sw <= rad * vec3_len(pw.n)) { /* reaches w <= 0 */
        s.x0 = s.y0 = -INFINITY;
        s.x1 = s.y1 = INFINITY;
        return s;
    }
    double k0, k1;
    tangents(px, pw, c, rad, &k0, &k1);
    s.x0 = (k0 + 1) * 0.5 * r->width;
    s.x1 = (k1 + 1) * 0.5 * r->width;
    tangents(py, pw, c, rad, &k0, &k1);
    s.y0 = (1 - k1) * 0.5 * r->height;
    s.y1 = (1 - k0) * 0.5 * r->height;
    return s;
}

WlSfScreen wl_sf_bv_screen(const WlSfDb *d, const WlSfRegions *r, guint c,
                           Mat4 clip_from_obj)
{
    const WlSfChunk *ch = wl_sf_chunk(d, c);
    if (d->bv == WL_SF_BV_AABB || !d->bvs || scene_box_is_empty(ch->box))
        return wl_sf_screen_of(r, ch->box, clip_from_obj);
    const WlSfBv *bv = &g_array_index(d->bvs, WlSfBv, c);
    if (d->bv == WL_SF_BV_SPHERE)
        return sphere_screen(r, bv->centre, bv->radius, clip_from_obj);
    return points_screen(r, &g_array_index(d->bv_verts, Vec3, bv->first),
                         bv->n, clip_from_obj);
}

/* ---- fit ------------------------------------------------------------------ */

typedef struct {
    Mat4 m;
    GArray *pts; /* Vec3 */
} Gather;

static void gather_vert(Vec3 v, void *ud)
{
    g_array_append_val(((Gather *)ud)->pts, v);
}

/* The rectangle's area clamped to the screen. */
static double area(const WlSfRegions *r, const WlSfScreen *s)
{
    double w = MIN(s->x1, r->width) - MAX(s->x0, 0);
    double h = MIN(s->y1, r->height) - MAX(s->y0, 0);
    return w > 0 && h > 0 ? w * h : 0;
}

void wl_sf_bv_fit(const WlSfDb *d, const SceneDb *db, const WlSfRegions *r,
                  Mat4 view_proj, WlSfBvFit *fit)
{
    Gather g = {mat4_identity(), g_array_new(FALSE, FALSE, sizeof(Vec3))};
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        g_array_set_size(g.pts, 0);
        each_vert(d, db, c, gather_vert, &g);
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
            Mat4 m = mat4_mul(view_proj, wl_sf_inst(d, i)->matrix);
            WlSfScreen ex = points_screen(r, (const Vec3 *)(void *)g.pts->data,
                                          g.pts->len, m);
            if (!ex.on)
                continue;
            WlSfScreen bv = wl_sf_bv_screen(d, r, c, m);
            uint64_t want = wl_sf_screen_regions(r, &ex);
            uint64_t got = wl_sf_screen_regions(r, &bv);
            fit->insts++;
            fit->bv_area += area(r, &bv);
            fit->exact_area += area(r, &ex);
            fit->polys += ch->polys;
            fit->false_regions +=
                (double)ch->polys * __builtin_popcountll(got & ~want);
        }
    }
    g_array_unref(g.pts);
}
