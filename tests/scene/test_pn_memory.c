/* test_pn_memory.c — the counting rule behind the slides' "models for
 * LOD 0-4 would require 70 times the amount of memory" (pn_memory.h):
 * each layout's vertex count is what scene_pn_tessellate() really
 * produces (GRIDS: its vertices; INDEXED: its distinct positions on a
 * closed cube whose corners share one normal), the list layout gives
 * sum (L + 1)^2 = 55 for levels 0..4 and 30 for 0..3, and control data
 * in the PN store lowers the ratio.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/pn_memory.h"
#include "sim/scene/pn_triangles.h"
#include "tests/scene/pn_cube.h"

/* Distinct vertex positions (bitwise) of m. */
static guint distinct_positions(const SceneMesh *m)
{
    GHashTable *h = g_hash_table_new_full(g_bytes_hash, g_bytes_equal,
                                          (GDestroyNotify)g_bytes_unref, NULL);
    for (guint i = 0; i < scene_mesh_n_vertices(m); i++) {
        Vec3 p = scene_mesh_vertex(m, i);
        g_hash_table_add(h, g_bytes_new(&p, sizeof p));
    }
    guint n = g_hash_table_size(h);
    g_hash_table_destroy(h);
    return n;
}

static void test_counts_match_the_tessellation(void **st)
{
    (void)st;
    SceneMesh *cube = pn_cube_smooth();
    for (guint L = 0; L <= 4; L++) {
        ScenePnParams p = {L, SCENE_PN_QUADRATIC, FALSE};
        SceneMesh *fine = scene_pn_tessellate(cube, &p);
        assert_int_equal(scene_pn_level_vertices(cube, L, SCENE_PN_MEM_GRIDS),
                         scene_mesh_n_vertices(fine));
        assert_int_equal(
            scene_pn_level_vertices(cube, L, SCENE_PN_MEM_INDEXED),
            distinct_positions(fine));
        assert_int_equal(scene_pn_level_vertices(cube, L, SCENE_PN_MEM_LIST),
                         3 * scene_mesh_n_triangles(fine));
        scene_mesh_free(fine);
    }
    scene_mesh_free(cube);
}

static void test_ratios(void **st)
{
    (void)st;
    SceneMesh *cube = pn_cube_smooth();
    ScenePnMemRule r = {SCENE_PN_MEM_LIST, 32, 4, 0, 0, 4};
    assert_float_equal(scene_pn_lod_memory_ratio(cube, &r), 55, 1e-12);
    r.hi = 3;
    assert_float_equal(scene_pn_lod_memory_ratio(cube, &r), 30, 1e-12);
    r = (ScenePnMemRule){SCENE_PN_MEM_GRIDS, 32, 0, 0, 0, 4};
    assert_float_equal(scene_pn_lod_memory_ratio(cube, &r), 55.0 / 3, 1e-12);
    /* indexed: V + E L + T L (L - 1) / 2 = T (L + 1)^2 / 2 + 2 on a closed
     * mesh (Euler); indices 3 T (L + 1)^2: (55 T / 2 + 10) Bv + 165 T Bi
     * over (T / 2 + 2) Bv + 3 T Bi, T = 12 */
    r = (ScenePnMemRule){SCENE_PN_MEM_INDEXED, 32, 4, 0, 0, 4};
    double want = (340.0 * 32 + 165 * 12 * 4) / (8.0 * 32 + 36 * 4);
    assert_float_equal(scene_pn_lod_memory_ratio(cube, &r), want, 1e-12);
    /* precomputed control nets in the PN store lower the ratio */
    double before = scene_pn_lod_memory_ratio(cube, &r);
    r.control_bytes = 13 * 12;
    assert_true(scene_pn_lod_memory_ratio(cube, &r) < before);
    assert_int_equal(scene_pn_base_store_bytes(cube, &r),
                     8 * 32 + 36 * 4 + 12 * 13 * 12);
    scene_mesh_free(cube);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts_match_the_tessellation),
        cmocka_unit_test(test_ratios),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
