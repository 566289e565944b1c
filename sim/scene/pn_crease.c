/* pn_crease.c — crease edges of a mesh by position, with their crease
 * directions (see pn_crease.h).
 */
#include "sim/scene/pn_crease.h"

#include <string.h>

gboolean scene_pn_vec_after(Vec3 a, Vec3 b)
{
    if (a.x != b.x)
        return a.x > b.x;
    if (a.y != b.y)
        return a.y > b.y;
    return a.z > b.z;
}

/* An edge's ends in canonical order. */
typedef struct {
    Vec3 a, b;
} EdgeKey;

/* The first side's normals at a and b, and another side's where it
 * differs. */
typedef struct {
    Vec3 na, nb, oa, ob;
    gboolean other_a, other_b;
} EdgeSides;

static gboolean same(Vec3 a, Vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

/* The unit crease direction of two normals, the same bits in either
 * order; zero when they are parallel. */
static Vec3 crease_dir(Vec3 n1, Vec3 n2)
{
    Vec3 c = scene_pn_vec_after(n1, n2) ? vec3_cross(n2, n1)
                                        : vec3_cross(n1, n2);
    return vec3_len(c) < 1e-12 ? (Vec3){0, 0, 0} : vec3_norm(c);
}

/* Visits every fan triangle of m with its corner positions and unit
 * normals. */
typedef void (*TriFn)(const Vec3 P[3], const Vec3 N[3], void *ctx);

static void each_tri(const SceneMesh *m, TriFn fn, void *ctx)
{
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *ix = scene_mesh_poly(m, i);
        for (guint t = 1; t + 1 < scene_mesh_poly_len(m, i); t++) {
            uint32_t tri[3] = {ix[0], ix[t], ix[t + 1]};
            Vec3 P[3], N[3];
            for (int c = 0; c < 3; c++) {
                P[c] = scene_mesh_vertex(m, tri[c]);
                N[c] = vec3_norm(g_array_index(m->normals, Vec3, tri[c]));
            }
            fn(P, N, ctx);
        }
    }
}

/* Edge e's key; *swapped when corner e is the key's b. */
static GBytes *edge_key(const Vec3 P[3], guint e, gboolean *swapped)
{
    Vec3 p = P[e], q = P[(e + 1) % 3];
    *swapped = scene_pn_vec_after(p, q);
    EdgeKey k = *swapped ? (EdgeKey){q, p} : (EdgeKey){p, q};
    return g_bytes_new(&k, sizeof k);
}

static void collect(const Vec3 P[3], const Vec3 N[3], void *ctx)
{
    GHashTable *edges = ctx;
    for (guint e = 0; e < 3; e++) {
        gboolean sw;
        GBytes *key = edge_key(P, e, &sw);
        Vec3 na = N[sw ? (e + 1) % 3 : e], nb = N[sw ? e : (e + 1) % 3];
        EdgeSides *s = g_hash_table_lookup(edges, key);
        if (!s) {
            s = g_new0(EdgeSides, 1);
            s->na = na, s->nb = nb;
            g_hash_table_insert(edges, key, s);
            continue;
        }
        g_bytes_unref(key);
        if (!s->other_a && !same(na, s->na))
            s->oa = na, s->other_a = TRUE;
        if (!s->other_b && !same(nb, s->nb))
            s->ob = nb, s->other_b = TRUE;
    }
}

typedef struct {
    GHashTable *edges;
    GArray *out;
} Fill;

static void fill(const Vec3 P[3], const Vec3 N[3], void *ctx)
{
    (void)N;
    Fill *f = ctx;
    ScenePnCreases c;
    memset(&c, 0, sizeof c);
    for (guint e = 0; e < 3; e++) {
        gboolean sw;
        GBytes *key = edge_key(P, e, &sw);
        const EdgeSides *s = g_hash_table_lookup(f->edges, key);
        g_bytes_unref(key);
        c.crease[e] = s->other_a || s->other_b;
        if (!c.crease[e])
            continue;
        Vec3 ta = s->other_a ? crease_dir(s->na, s->oa) : (Vec3){0, 0, 0};
        Vec3 tb = s->other_b ? crease_dir(s->nb, s->ob) : (Vec3){0, 0, 0};
        c.t[e][0] = sw ? tb : ta;
        c.t[e][1] = sw ? ta : tb;
    }
    g_array_append_val(f->out, c);
}

GArray *scene_pn_find_creases(const SceneMesh *m)
{
    g_assert(m->normals->len == scene_mesh_n_vertices(m));
    GHashTable *edges = g_hash_table_new_full(
        g_bytes_hash, g_bytes_equal, (GDestroyNotify)g_bytes_unref, g_free);
    each_tri(m, collect, edges);
    Fill f = {edges, g_array_new(FALSE, FALSE, sizeof(ScenePnCreases))};
    each_tri(m, fill, &f);
    g_hash_table_destroy(edges);
    return f.out;
}
