/* pn_memory.c — the memory of pre-tessellated PN levels of detail
 * against the base mesh (see pn_memory.h for the counting rule).
 */
#include "sim/scene/pn_memory.h"

/* Distinct undirected edges of m's fan triangulation, by vertex index. */
static uint64_t n_edges(const SceneMesh *m)
{
    GHashTable *seen = g_hash_table_new(g_int64_hash, g_int64_equal);
    GArray *keys = g_array_new(FALSE, FALSE, sizeof(gint64));
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *ix = scene_mesh_poly(m, i);
        guint n = scene_mesh_poly_len(m, i);
        for (guint t = 1; t + 1 < n; t++) {
            uint32_t tri[3] = {ix[0], ix[t], ix[t + 1]};
            for (int e = 0; e < 3; e++) {
                uint32_t a = tri[e], b = tri[(e + 1) % 3];
                gint64 k = ((gint64)MIN(a, b) << 32) | MAX(a, b);
                g_array_append_val(keys, k);
            }
        }
    }
    /* keys is not resized from here on: the table may point into it */
    for (guint i = 0; i < keys->len; i++)
        g_hash_table_add(seen, &g_array_index(keys, gint64, i));
    uint64_t e = g_hash_table_size(seen);
    g_hash_table_destroy(seen);
    g_array_free(keys, TRUE);
    return e;
}

uint64_t scene_pn_level_vertices(const SceneMesh *m, guint level,
                                 ScenePnMemLayout layout)
{
    uint64_t t = scene_mesh_n_triangles(m), L = level;
    switch (layout) {
    case SCENE_PN_MEM_LIST:
        return 3 * t * (L + 1) * (L + 1);
    case SCENE_PN_MEM_GRIDS:
        return t * (L + 2) * (L + 3) / 2;
    case SCENE_PN_MEM_INDEXED:
        return scene_mesh_n_vertices(m) + n_edges(m) * L +
               t * L * (L ? L - 1 : 0) / 2;
    }
    g_assert_not_reached();
}

uint64_t scene_pn_level_bytes(const SceneMesh *m, guint level,
                              const ScenePnMemRule *r)
{
    uint64_t v = scene_pn_level_vertices(m, level, r->layout) * r->vertex_bytes;
    if (r->layout == SCENE_PN_MEM_LIST)
        return v;
    uint64_t tris = scene_mesh_n_triangles(m) * (level + 1) * (level + 1);
    return v + 3 * tris * r->index_bytes;
}

uint64_t scene_pn_lod_store_bytes(const SceneMesh *m, const ScenePnMemRule *r)
{
    uint64_t sum = 0;
    for (guint l = r->lo; l <= r->hi; l++)
        sum += scene_pn_level_bytes(m, l, r);
    return sum;
}

uint64_t scene_pn_base_store_bytes(const SceneMesh *m,
                                   const ScenePnMemRule *r)
{
    return scene_pn_level_bytes(m, 0, r) +
           scene_mesh_n_triangles(m) * r->control_bytes;
}

double scene_pn_lod_memory_ratio(const SceneMesh *m, const ScenePnMemRule *r)
{
    uint64_t base = scene_pn_base_store_bytes(m, r);
    return base ? (double)scene_pn_lod_store_bytes(m, r) / base : 0;
}

const char *const scene_pn_mem_layouts[] = {"list", "grids", "indexed", NULL};
