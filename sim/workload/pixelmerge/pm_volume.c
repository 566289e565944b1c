/* pm_volume.c — the scalar field on its lattice, emission-absorption
 * ray casting of one block, and the isosurface's triangles by block
 * (pm_volume.h).
 *
 * A block walks the pixels of its footprint (pm_blocks.h); for a ray it
 * takes the samples k between the ray's entry into and exit from the
 * block's box, one more each side against rounding, and keeps those
 * whose point the grid gives to the block (wl_pm_grid_block_of): the
 * one test every process count applies, so the samples partition.
 */
#include "sim/workload/pixelmerge/pm_volume.h"
#include <string.h>

struct WlPmField {
    guint n;     /* lattice points per axis (grid + 1) */
    double *val; /* n^3, x fastest */
};

WlPmVolume wl_pm_volume_defaults(void)
{
    return (WlPmVolume){scene_iso_defaults(), 0.02, 20.0, 0.25};
}

static const char *const fields[] = {"gyroid", "metaballs", NULL};

gboolean wl_pm_volume_parse(const CfgNode *map, WlPmVolume *v, GError **err)
{
    int field = v->iso.field;
    uint64_t grid = v->iso.grid, balls = v->iso.balls, seed = v->iso.seed;
    if (!cfg_get_enum(map, "field", FALSE, fields, &field, err) ||
        !cfg_get_count(map, "grid", FALSE, 2, 256, &grid, err) ||
        !cfg_get_double(map, "iso", FALSE, -1e6, 1e6, &v->iso.iso, err) ||
        !cfg_get_double(map, "periods", FALSE, 0, 1e3, &v->iso.periods, err) ||
        !cfg_get_count(map, "balls", FALSE, 1, 4096, &balls, err) ||
        !cfg_get_count(map, "seed", FALSE, 0, UINT64_MAX, &seed, err) ||
        !cfg_get_double(map, "step", FALSE, 1e-4, 1.0, &v->step, err) ||
        !cfg_get_double(map, "density", FALSE, 0, 1e6, &v->density, err) ||
        !cfg_get_double(map, "width", FALSE, 1e-9, 1e6, &v->width, err))
        return FALSE;
    v->iso.field = (SceneFieldKind)field;
    v->iso.grid = (guint)grid;
    v->iso.balls = (guint)balls;
    v->iso.seed = seed;
    return TRUE;
}

WlPmField *wl_pm_field_new(const SceneIsoParams *iso)
{
    WlPmField *f = g_new0(WlPmField, 1);
    guint n = f->n = iso->grid + 1;
    f->val = g_new(double, (gsize)n *n *n);
    Vec3 *centres = scene_iso_centres(iso);
    double h = 2.0 / iso->grid;
    for (guint z = 0; z < n; z++)
        for (guint y = 0; y < n; y++)
            for (guint x = 0; x < n; x++)
                f->val[x + (gsize)n * (y + (gsize)n * z)] = scene_iso_field(
                    iso, centres, vec3(-1 + h * x, -1 + h * y, -1 + h * z));
    g_free(centres);
    return f;
}

void wl_pm_field_free(WlPmField *f)
{
    if (!f)
        return;
    g_free(f->val);
    g_free(f);
}

/* Lattice cell and fraction of coordinate c on an axis of n points. */
static guint cell(double c, guint n, double *frac)
{
    double u = (c + 1.0) * 0.5 * (n - 1);
    u = CLAMP(u, 0.0, (double)(n - 1));
    guint i = MIN((guint)u, n - 2);
    *frac = u - i;
    return i;
}

double wl_pm_field_at(const WlPmField *f, Vec3 x)
{
    double fx, fy, fz;
    guint n = f->n, i = cell(x.x, n, &fx), j = cell(x.y, n, &fy),
          k = cell(x.z, n, &fz);
    const double *v = &f->val[i + (gsize)n * (j + (gsize)n * k)];
    gsize sy = n, sz = (gsize)n * n;
    double c00 = v[0] + fx * (v[1] - v[0]);
    double c10 = v[sy] + fx * (v[sy + 1] - v[sy]);
    double c01 = v[sz] + fx * (v[sz + 1] - v[sz]);
    double c11 = v[sy + sz] + fx * (v[sy + sz + 1] - v[sy + sz]);
    double c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
    return c0 + fz * (c1 - c0);
}

/* One sample's premultiplied colour and opacity into s[4]; FALSE when
 * it is transparent. */
static gboolean transfer(const WlPmVolume *v, double val, double *s)
{
    double d = fabs(val - v->iso.iso) / v->width;
    if (d >= 1.0)
        return FALSE;
    double a = 1.0 - exp(-v->density * (1.0 - d) * v->step);
    double k = CLAMP(0.7 + 0.3 * (val - v->iso.iso) / v->width, 0.0, 1.0);
    const float rgb[3] = {v->iso.color.r, v->iso.color.g, v->iso.color.b};
    for (int i = 0; i < 3; i++)
        s[i] = CLAMP(rgb[i] * k, 0.0, 1.0) * a;
    s[3] = a;
    return a > 0;
}

typedef struct {
    const WlPmField *f;
    const WlPmVolume *v;
    const WlPmGrid *g;
    guint p;
    Vec3 lo, hi; /* the block's box, widened a little */
} Cast;

/* The ray's samples in the block, front to back, into rgba[4]; *z the
 * first contributing one's t; a "pixel" per sample taken. */
static gboolean cast(void *ctx, Vec3 o, Vec3 d, double *z, double *rgba,
                     WlPmCounts *cnt)
{
    const Cast *c = ctx;
    double t0, t1;
    memset(rgba, 0, 4 * sizeof *rgba);
    if (!wl_pm_ray_box(o, d, c->lo, c->hi, &t0, &t1))
        return FALSE;
    double step = c->v->step, k0 = floor(t0 / step) - 1;
    for (double k = MAX(k0, 0.0); k * step <= t1 + step; k++) {
        double t = k * step, s[4];
        Vec3 x = vec3_add(o, vec3_scale(d, t));
        if (!wl_pm_grid_inside(c->g, x) || wl_pm_grid_block_of(c->g, x) != c->p)
            continue;
        cnt->rc.pixels++;
        if (!transfer(c->v, wl_pm_field_at(c->f, x), s))
            continue;
        if (rgba[3] == 0)
            *z = t;
        double rest = 1.0 - rgba[3];
        for (int i = 0; i < 4; i++)
            rgba[i] += rest * s[i];
    }
    return rgba[3] > 0;
}

WlPmWpa *wl_pm_volume_image(const WlPmField *f, const WlPmVolume *v,
                            const WlPmGrid *g, const WlPmRays *r, guint p,
                            WlPmCounts *c)
{
    Cast k = {.f = f, .v = v, .g = g, .p = p};
    wl_pm_grid_block(g, p, &k.lo, &k.hi);
    Vec3 pad = vec3_scale(vec3_sub(k.hi, k.lo), 1e-9);
    k.lo = vec3_sub(k.lo, pad);
    k.hi = vec3_add(k.hi, pad);
    return wl_pm_block_cast(g, r, p, cast, &k, c);
}

guint *wl_pm_volume_owners(const SceneMesh *m, const WlPmGrid *g)
{
    guint n = scene_mesh_n_polys(m);
    guint *own = g_new(guint, MAX(n, 1u));
    for (guint i = 0; i < n; i++) {
        const uint32_t *ix = scene_mesh_poly(m, i);
        guint len = scene_mesh_poly_len(m, i);
        Vec3 s = vec3(0, 0, 0);
        for (guint j = 0; j < len; j++)
            s = vec3_add(s, scene_mesh_vertex(m, ix[j]));
        own[i] = wl_pm_grid_block_of(g, vec3_scale(s, 1.0 / len));
    }
    return own;
}
