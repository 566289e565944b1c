/* test_vehicle_instancing.c — scene.vehicle.instancing (vehicle.h, issue
 * 37 point 3): how many copies execute one vehicle tree.  The picture is
 * the same at every level (the flattened meshes are equal), the min-set
 * grows as the sharing falls (none: one tree per copy, every structure
 * executed once; heavy: one tree), and a bad value is a located error.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/cfg.h"
#include "sim/scene/scene_cfg.h"
#include "sim/scene/structdb.h"
#include "sim/scene/vehicle.h"

static Scene *fleet(guint instancing)
{
    SceneVehicleParams p = scene_vehicle_defaults();
    p.structures = 20;
    p.triangles = 400;
    p.instances = 6;
    p.instancing = instancing;
    Scene *s = scene_vehicle_new(&p, "test", NULL);
    assert_non_null(s);
    return s;
}

static void test_levels(void **state)
{
    (void)state;
    Scene *heavy = fleet(0), *none = fleet(1), *two = fleet(2);
    SceneDbStats h, n, t;
    scene_db_stats(heavy->db, &h);
    scene_db_stats(none->db, &n);
    scene_db_stats(two->db, &t);
    /* the max-set is the same, the min-set follows the trees */
    assert_int_equal(h.primitives, 6 * 400);
    assert_int_equal(n.primitives, h.primitives);
    assert_int_equal(t.primitives, h.primitives);
    assert_int_equal(h.min_primitives, 400);
    assert_int_equal(t.min_primitives, 3 * 400);
    assert_int_equal(n.min_primitives, 6 * 400);
    assert_int_equal(h.structures, 20 + 1);
    assert_int_equal(n.structures, 6 * 20 + 1);
    /* no instancing: every structure below the world executed once */
    GArray *max = scene_db_maxset(none->db);
    assert_int_equal(max->len, n.structures);
    g_array_unref(max);
    /* the same picture: equal flattened meshes */
    SceneMesh *mh = scene_db_flatten(heavy->db),
              *mn = scene_db_flatten(none->db);
    assert_int_equal(mh->pos->len, mn->pos->len);
    assert_memory_equal(mh->pos->data, mn->pos->data,
                        mh->pos->len * sizeof(Vec3));
    assert_int_equal(mh->idx->len, mn->idx->len);
    assert_memory_equal(mh->idx->data, mn->idx->data,
                        mh->idx->len * sizeof(uint32_t));
    scene_mesh_free(mh);
    scene_mesh_free(mn);
    scene_free(heavy);
    scene_free(none);
    scene_free(two);
}

static Scene *from_text(const char *inst, GError **err)
{
    char *text = g_strdup_printf("generator: vehicle\nstructures: 20\n"
                                 "triangles: 400\ninstances: 6\n"
                                 "instancing: %s\n",
                                 inst);
    CfgNode *root = cfg_load_string(text, "fleet.yaml", err);
    Scene *s = root ? scene_from_cfg(root, err) : NULL;
    cfg_free(root);
    g_free(text);
    return s;
}

static void test_config(void **state)
{
    (void)state;
    static const char *const ok[] = {"none", "moderate", "heavy", "1", "6"};
    static const guint trees[] = {6, 2, 1, 6, 1};
    for (guint i = 0; i < G_N_ELEMENTS(ok); i++) {
        GError *e = NULL;
        Scene *s = from_text(ok[i], &e);
        assert_non_null(s);
        SceneDbStats st;
        scene_db_stats(s->db, &st);
        assert_int_equal(st.min_primitives, trees[i] * 400);
        scene_free(s);
    }
    static const char *const bad[] = {"7", "0", "lots", "[1]"};
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        GError *e = NULL;
        assert_null(from_text(bad[i], &e));
        assert_non_null(e);
        assert_non_null(strstr(e->message, "fleet.yaml:5:"));
        assert_non_null(strstr(e->message, "1 .. instances (6)"));
        g_error_free(e);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_levels),
        cmocka_unit_test(test_config),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
