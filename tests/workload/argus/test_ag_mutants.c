/* test_ag_mutants.c — claims of the Argus command streams (ag_stream.h)
 * that mutation testing (make mutate, docs/testing.md) found unchecked:
 * every triangle of the scene is issued exactly once, batches of a
 * single triangle included. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/argus/ag_stream.h"

/* n separate triangles, triangle i tagged tags[i]. */
static SceneMesh *tagged_mesh(const guint *tags, guint n)
{
    SceneMesh *m = scene_mesh_new();
    for (guint i = 0; i < n; i++) {
        uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(i, 0, 0)),
                         scene_mesh_add_vertex(m, vec3(i + 1, 0, 0)),
                         scene_mesh_add_vertex(m, vec3(i, 1, 0))};
        scene_mesh_add_poly(m, v, 3, scene_color(1, 1, 1), tags[i]);
    }
    return m;
}

static void check_each_once(const guint *tags, guint n, guint contexts,
                            guint block)
{
    SceneMesh *m = tagged_mesh(tags, n);
    GError *err = NULL;
    AgStreams *s = wl_ag_streams_new(m, contexts, WL_AG_ORDER_FRAME,
                                     WL_AG_PRIM_TRIANGLES, block, 0, &err);
    assert_non_null(s);
    guint seen[16] = {0};
    for (guint c = 0; c < contexts; c++) {
        GArray *b = wl_ag_ctx_blocks(s, c);
        for (guint k = 0; k < b->len; k++) {
            const AgBlock *x = &g_array_index(b, AgBlock, k);
            for (guint t = x->first; t < x->first + x->n; t++)
                seen[t]++;
        }
    }
    for (guint t = 0; t < n; t++)
        if (seen[t] != 1)
            fail_msg("%u contexts: triangle %u issued %u times", contexts, t,
                     seen[t]);
    wl_ag_streams_free(s);
    scene_mesh_free(m);
}

static void test_every_triangle_once(void **state)
{
    (void)state;
    const guint singles[5] = {0, 1, 2, 3, 4};
    const guint mixed[7] = {0, 0, 0, 1, 2, 2, 3};
    check_each_once(singles, 5, 1, 4);
    check_each_once(singles, 5, 2, 4);
    check_each_once(mixed, 7, 1, 2);
    check_each_once(mixed, 7, 3, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_triangle_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
