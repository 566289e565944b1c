/* teapot.c — the Utah teapot from Newell's Bézier patches.
 *
 * Implements teapot.h: bicubic Bézier evaluation in Bernstein form
 * (Foley, van Dam et al., "Computer Graphics", 2nd ed., §11.3), a
 * uniform n x n grid per patch, exact vertex welding through a hash on
 * the coordinates, pole quads emitted as triangles, and an evenly spread
 * set of quads split in two to reach the exact polygon count (the rule is
 * in teapot.h).  O(T) time and memory for T polygons.
 */
#include "sim/scene/teapot.h"

#include <string.h>

typedef struct {
    SceneMesh *m;
    GHashTable *weld; /* Vec3 bytes -> index + 1 */
    SceneColor color;
    guint split, splittable, k; /* split-quad distribution state */
} Tess;

static void bernstein(double t, double b[4])
{
    double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
}

/* Rounds to a multiple of 2^-24 (error <= 3e-8 on a teapot 6.4 wide):
 * Bernstein weights do not sum to exactly 1 in floating point, so points
 * that coincide on paper (the poles, shared patch edges evaluated in
 * opposite directions) differ in the last bits; snapping makes them
 * bit-identical for welding.  + 0.0 turns -0 into +0. */
static double snap(double x)
{
    return nearbyint(x * 16777216.0) / 16777216.0 + 0.0;
}

Vec3 scene_teapot_eval(guint patch, double u, double v)
{
    g_assert(patch < SCENE_TEAPOT_PATCHES);
    double bu[4], bv[4], p[3] = {0, 0, 0};
    bernstein(u, bu);
    bernstein(v, bv);
    for (int i = 0; i < 4; i++) {
        double row[3] = {0, 0, 0};
        for (int j = 0; j < 4; j++) {
            const double *c =
                scene_teapot_points[scene_teapot_patches[patch][4 * i + j] - 1];
            for (int k = 0; k < 3; k++)
                row[k] += bv[j] * c[k];
        }
        for (int k = 0; k < 3; k++)
            p[k] += bu[i] * row[k];
    }
    /* z-up to y-up, snapped (see snap()). */
    return vec3(snap(p[0]), snap(p[2]), snap(-p[1]));
}

gboolean scene_teapot_tess_for(uint64_t polygons, const char *what,
                               SceneTeapotTess *out, GError **err)
{
    if (polygons < SCENE_TEAPOT_MIN_POLYS || polygons > (1u << 26)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found %" G_GUINT64_FORMAT " polygons per teapot, "
                    "expected %d to %u",
                    what, polygons, SCENE_TEAPOT_MIN_POLYS, 1u << 26);
        return FALSE;
    }
    guint n = (guint)floor(sqrt((double)polygons / SCENE_TEAPOT_PATCHES));
    while ((uint64_t)SCENE_TEAPOT_PATCHES * (n + 1) * (n + 1) <= polygons)
        n++;
    while ((uint64_t)SCENE_TEAPOT_PATCHES * n * n > polygons)
        n--;
    out->n = n;
    out->split = (guint)(polygons - (uint64_t)SCENE_TEAPOT_PATCHES * n * n);
    return TRUE;
}

static guint weld_guint(gconstpointer k)
{
    const guint32 *w = k;
    guint h = 2166136261u;
    for (guint i = 0; i < sizeof(Vec3) / 4; i++)
        h = (h ^ w[i]) * 16777619u;
    return h;
}

static gboolean weld_equal(gconstpointer a, gconstpointer b)
{
    return memcmp(a, b, sizeof(Vec3)) == 0;
}

static uint32_t weld_vertex(Tess *t, Vec3 p)
{
    gpointer v = g_hash_table_lookup(t->weld, &p);
    if (v)
        return GPOINTER_TO_UINT(v) - 1;
    uint32_t i = scene_mesh_add_vertex(t->m, p);
    g_hash_table_insert(t->weld, g_memdup2(&p, sizeof p),
                        GUINT_TO_POINTER(i + 1));
    return i;
}

static gboolean take_split(Tess *t)
{
    uint64_t k = t->k++;
    return (k + 1) * t->split / t->splittable > k * t->split / t->splittable;
}

static double dist2(const SceneMesh *m, uint32_t a, uint32_t b)
{
    Vec3 d = vec3_sub(scene_mesh_vertex(m, a), scene_mesh_vertex(m, b));
    return vec3_dot(d, d);
}

/* Emits the cell with corners q[0..3] (counter-clockwise from outside). */
static void emit_cell(Tess *t, const uint32_t q[4], uint32_t tag)
{
    uint32_t v[4];
    guint n = 0;
    for (int i = 0; i < 4; i++)
        if (q[i] != q[(i + 3) % 4])
            v[n++] = q[i];
    g_assert(n >= 3); /* Newell's patches collapse at most one edge */
    if (n == 3) {
        scene_mesh_add_poly(t->m, v, 3, t->color, tag);
    } else if (!take_split(t)) {
        scene_mesh_add_poly(t->m, v, 4, t->color, tag);
    } else if (dist2(t->m, v[0], v[2]) <= dist2(t->m, v[1], v[3])) {
        scene_mesh_add_tri(t->m, v[0], v[1], v[2], t->color, tag);
        scene_mesh_add_tri(t->m, v[0], v[2], v[3], t->color, tag);
    } else {
        scene_mesh_add_tri(t->m, v[0], v[1], v[3], t->color, tag);
        scene_mesh_add_tri(t->m, v[1], v[2], v[3], t->color, tag);
    }
}

/* Grid vertex indices of patch p: (n+1)^2, row-major in (u, v). */
static uint32_t *patch_grid(Tess *t, guint p, guint n)
{
    uint32_t *g = g_new(uint32_t, (n + 1) * (n + 1));
    for (guint i = 0; i <= n; i++)
        for (guint j = 0; j <= n; j++)
            g[i * (n + 1) + j] = weld_vertex(
                t, scene_teapot_eval(p, (double)i / n, (double)j / n));
    return g;
}

static guint count_collapsed(const uint32_t *g, guint n)
{
    guint c = 0;
    for (guint i = 0; i < n; i++)
        for (guint j = 0; j < n; j++) {
            uint32_t a = g[i * (n + 1) + j], b = g[i * (n + 1) + j + 1];
            uint32_t cc = g[(i + 1) * (n + 1) + j + 1];
            uint32_t d = g[(i + 1) * (n + 1) + j];
            c += a == b || b == cc || cc == d || d == a;
        }
    return c;
}

static void emit_patch(Tess *t, const uint32_t *g, guint n, guint p)
{
    for (guint i = 0; i < n; i++)
        for (guint j = 0; j < n; j++) {
            /* (u, v) = (i, j) runs counter-clockwise seen from outside
             * in Newell's data (checked: positive signed volume). */
            uint32_t q[4] = {g[i * (n + 1) + j], g[i * (n + 1) + j + 1],
                             g[(i + 1) * (n + 1) + j + 1],
                             g[(i + 1) * (n + 1) + j]};
            emit_cell(t, q, p);
        }
}

SceneMesh *scene_teapot_mesh(SceneTeapotTess ts, SceneColor c)
{
    g_assert(ts.n >= 1);
    Tess t = {scene_mesh_new(), NULL, c, ts.split, 0, 0};
    t.weld = g_hash_table_new_full(weld_guint, weld_equal, g_free, NULL);
    guint n = ts.n;
    uint32_t *grids[SCENE_TEAPOT_PATCHES];
    guint collapsed = 0;
    for (guint p = 0; p < SCENE_TEAPOT_PATCHES; p++) {
        grids[p] = patch_grid(&t, p, n);
        collapsed += count_collapsed(grids[p], n);
    }
    t.splittable = SCENE_TEAPOT_PATCHES * n * n - collapsed;
    g_assert(ts.split <= t.splittable);
    for (guint p = 0; p < SCENE_TEAPOT_PATCHES; p++) {
        emit_patch(&t, grids[p], n, p);
        g_free(grids[p]);
    }
    g_hash_table_destroy(t.weld);
    scene_mesh_compute_normals(t.m);
    return t.m;
}
