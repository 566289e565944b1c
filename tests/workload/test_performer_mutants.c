/* test_performer_mutants.c — claims of the Performer town (pf_town.h) that
 * mutation testing (make mutate, docs/testing.md) found unchecked: each
 * block's terrain covers the block exactly, and cars drive in two lanes
 * 1.5 m either side of their street, on the terrain. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/workload/performer/pf_cull.h"
#include "sim/workload/performer/pf_stages.h"
#include "sim/workload/performer/pf_town.h"

/* Area of the triangle's projection on the ground plane (x, z). */
static double ground_area(const Vec3 *t)
{
    return fabs((t[1].x - t[0].x) * (t[2].z - t[0].z) -
                (t[2].x - t[0].x) * (t[1].z - t[0].z)) / 2;
}

/* A block's terrain: one geoset of 8 x 8 quads (128 triangles), none
 * degenerate, covering block x block metres of ground. */
static void test_terrain_covers_blocks(void **state)
{
    (void)state;
    WlPfTownParams p = wl_pf_town_defaults();
    p.blocks = 2;
    WlPfTown *t = wl_pf_town_new(&p);
    guint terrains = 0;
    for (guint i = 0; i < t->g->geosets->len; i++) {
        const WlPfGeoSet *gs = g_ptr_array_index(t->g->geosets, i);
        const Vec3 *v = (const Vec3 *)gs->verts->data;
        guint n = gs->verts->len / 3;
        gboolean on_ground = n == 128;
        for (guint k = 0; on_ground && k < gs->verts->len; k++)
            on_ground = fabs(v[k].y - wl_pf_town_height(v[k].x, v[k].z)) < 1e-9;
        if (!on_ground)
            continue;
        double area = 0;
        for (guint k = 0; k < n; k++) {
            assert_true(ground_area(v + 3 * k) > 0);
            area += ground_area(v + 3 * k);
        }
        assert_true(fabs(area - p.block * p.block) < 1e-6);
        terrains++;
    }
    assert_int_equal(terrains, p.blocks * p.blocks);
    wl_pf_town_free(t);
}

/* Car c drives on street c mod blocks, odd cars 1.5 m on one side, even
 * cars 1.5 m on the other, at the terrain's height. */
static void test_car_lanes(void **state)
{
    (void)state;
    WlPfTownParams p = wl_pf_town_defaults();
    WlPfTown *t = wl_pf_town_new(&p);
    assert_int_equal(t->cars->len, p.cars);
    for (guint frame = 0; frame < 3; frame++) {
        wl_pf_town_update(t, frame);
        for (guint c = 0; c < t->cars->len; c++) {
            Mat4 xf = wl_pf_node(t->g, g_array_index(t->cars, guint, c))->xf;
            double x = xf.m[0][3], y = xf.m[1][3], z = xf.m[2][3];
            double street = (c % p.blocks) * p.block;
            assert_true(fabs(z - street - (c % 2 ? 1.5 : -1.5)) < 1e-9);
            assert_true(fabs(y - wl_pf_town_height(x, z)) < 1e-9);
        }
    }
    wl_pf_town_free(t);
}

/* A machine without the Performer costs (the iPSC/2 has no cpu kind's
 * app_frame) is refused: FALSE, with the error. */
static void test_costs_missing(void **state)
{
    (void)state;
    GError *err = NULL;
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m = mach_new_from_model(eng, "ipsc2", "analytic", &err);
    assert_non_null(m);
    WlPfCosts c;
    assert_false(wl_pf_costs_read(m, 32, &c, &err));
    assert_non_null(err);
    g_clear_error(&err);
    mach_free(m);
    sim_engine_free(eng);
}

/* An LOD node with three children for ranges [0, 10), [10, 20), [20, 30)
 * about the origin, seen from distance d: the chosen child's index adds
 * to lod_sum, and a node out of every range adds its child count. */
static uint64_t lod_sum_at(double d)
{
    WlPfGraph *g = wl_pf_graph_new();
    guint lod = wl_pf_add_node(g, g->root, WL_PF_LOD);
    double r[4] = {0, 10, 20, 30};
    g_array_append_vals(wl_pf_node(g, lod)->ranges, r, 4);
    Vec3 tri[3] = {vec3(-1, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    guint gs = wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    for (int k = 0; k < 3; k++)
        wl_pf_add_geoset(g, wl_pf_add_node(g, lod, WL_PF_GEODE), tri, 1, gs);
    wl_pf_update_bounds(g, g->root);
    SceneCamera c = scene_camera_default();
    c.eye = vec3(0, 0.5, d);
    c.target = vec3(0, 0.5, 0);
    c.far = 1000;
    WlPfView v = wl_pf_view(&c, 1, FALSE);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfCullStats st = {0};
    wl_pf_cull(g, &v, dl, &st);
    assert_int_equal(st.lods, 1);
    g_array_free(dl, TRUE);
    wl_pf_graph_free(g);
    return st.lod_sum;
}

static void test_lod_sum(void **state)
{
    (void)state;
    assert_int_equal(lod_sum_at(5), 0);
    assert_int_equal(lod_sum_at(15), 1);
    assert_int_equal(lod_sum_at(25), 2);
    assert_int_equal(lod_sum_at(50), 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_terrain_covers_blocks),
        cmocka_unit_test(test_car_lanes),
        cmocka_unit_test(test_costs_missing),
        cmocka_unit_test(test_lod_sum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
