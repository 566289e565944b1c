/* mesh_check.c — test helpers: topology and volume checks on meshes.
 * Edges are 64-bit keys (from << 32 | to) in a GHashTable; O(indices).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/scene/mesh_check.h"

static GArray *edge_keys(const SceneMesh *m)
{
    GArray *keys = g_array_sized_new(FALSE, FALSE, sizeof(gint64), m->idx->len);
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        guint n = scene_mesh_poly_len(m, i);
        const uint32_t *v = scene_mesh_poly(m, i);
        for (guint k = 0; k < n; k++) {
            gint64 key = ((gint64)v[k] << 32) | v[(k + 1) % n];
            g_array_append_val(keys, key);
        }
    }
    return keys;
}

guint mesh_check_open_edges(const SceneMesh *m)
{
    GArray *keys = edge_keys(m);
    GHashTable *h = g_hash_table_new(g_int64_hash, g_int64_equal);
    for (guint i = 0; i < keys->len; i++) {
        gint64 *k = &g_array_index(keys, gint64, i);
        assert_false(g_hash_table_contains(h, k));
        g_hash_table_add(h, k);
    }
    guint open = 0;
    for (guint i = 0; i < keys->len; i++) {
        gint64 k = g_array_index(keys, gint64, i);
        gint64 rev = ((k & 0xffffffff) << 32) | (k >> 32);
        open += !g_hash_table_contains(h, &rev);
    }
    g_hash_table_destroy(h);
    g_array_free(keys, TRUE);
    return open;
}

guint mesh_check_edges(const SceneMesh *m)
{
    GArray *keys = edge_keys(m);
    GHashTable *h = g_hash_table_new(g_int64_hash, g_int64_equal);
    for (guint i = 0; i < keys->len; i++) {
        gint64 *k = &g_array_index(keys, gint64, i);
        gint64 a = *k >> 32, b = *k & 0xffffffff;
        *k = a < b ? (a << 32) | b : (b << 32) | a;
        g_hash_table_add(h, k);
    }
    guint n = g_hash_table_size(h);
    g_hash_table_destroy(h);
    g_array_free(keys, TRUE);
    return n;
}

double mesh_check_volume(const SceneMesh *m)
{
    double vol = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *v = scene_mesh_poly(m, i);
        Vec3 a = scene_mesh_vertex(m, v[0]);
        for (guint k = 1; k + 1 < scene_mesh_poly_len(m, i); k++)
            vol += vec3_dot(a, vec3_cross(scene_mesh_vertex(m, v[k]),
                                          scene_mesh_vertex(m, v[k + 1]))) /
                   6;
    }
    return vol;
}

guint mesh_check_count_kind(const SceneDb *db, guint sid, SceneElemKind k)
{
    guint n = 0;
    for (guint i = 0; i < scene_db_len(db, sid); i++)
        n += scene_db_elem(db, sid, i)->kind == k;
    return n;
}
