/* test_pphigs_mutants.c — claims of the PPHIGS workload that mutation
 * testing (make mutate, docs/testing.md) found unchecked: the
 * non-primitive cost sums every colour, matrix and execute element of
 * every instance in the max-set view, the posted root's included; the
 * first element of a distributed list draws on the far plane (its id is
 * at least 1); a polygon's depth plane and shade come from its fan
 * triangle (0, i, i+1) of largest screen area; modify reaches every
 * holder up to the 64th GP. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pphigs/pphigs_distrib.h"
#include "sim/workload/pphigs/pphigs_metrics.h"
#include "sim/workload/pphigs/pphigs_pixels.h"
#include <math.h>

static void add(SceneDb *db, guint sid, SceneElem e)
{
    assert_true(scene_db_append(db, sid, &e, NULL));
}

/* root: colour, replace matrix, triangle, execute child; child: concat
 * matrix, triangle.  Non-primitives: 1 colour, 1 matrix, 1 execute in
 * the root and 1 concat in the child. */
static void test_nonprim_cost(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    guint child = scene_db_add_struct(db, "child");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    add(db, root, scene_elem_color(vec3(1, 0, 0)));
    add(db, root, scene_elem_matrix(mat4_identity(), SCENE_MAT_REPLACE));
    add(db, root, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    add(db, root, scene_elem_execute(child));
    add(db, child, scene_elem_matrix(mat4_identity(), SCENE_MAT_CONCAT));
    add(db, child, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    scene_db_post(db, root);
    WlPphigsCosts c = {.poly = 1000, .vertex = 100, .reject_vertex = 10,
                       .color = 1, .matrix = 20, .concat = 300,
                       .execute = 4000};
    assert_int_equal(wl_pphigs_nonprim_cost(db, &c), 1 + 20 + 4000 + 300);
    scene_db_free(db);
}

/* pphigs_pixels.h: "the inherited colour, flat, times 0.3 + 0.7 |n_z| of
 * the polygon's normal in normalised device coordinates". */
static WlPphigsCmd command(const Vec3 *v)
{
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 3);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 0.5, 0.25), .depth = 1};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 100, 80, out), 1);
    WlPphigsCmd c = g_array_index(out, WlPphigsCmd, 0);
    g_array_free(out, TRUE);
    /* e borrows v (scene_elem_prim does not copy) */
    return c;
}

static uint32_t shaded(const Vec3 *v)
{
    return command(v).rgba;
}

static uint32_t rgba_of(double s)
{
    return 0xff000000u | (uint32_t)lrint(255 * s) |
           (uint32_t)lrint(255 * 0.5 * s) << 8 |
           (uint32_t)lrint(255 * 0.25 * s) << 16;
}

static void test_shading(void **state)
{
    (void)state;
    Vec3 flat[3] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0, 0.5, 0)};
    assert_int_equal(shaded(flat), rgba_of(1)); /* facing the eye: n_z = 1 */
    /* u = (1, 0, 0), v = (0.5, 1, 0.5): n = (0, -0.5, 1), n_z = 1/sqrt 1.25 */
    Vec3 tilt[3] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0, 0.5, 0.5)};
    assert_int_equal(shaded(tilt), rgba_of(0.3 + 0.7 / sqrt(1.25)));
    /* u = (1, 0, 0.5), v = (0.5, 1, 0): n = (-0.5, 0.25, 1) */
    Vec3 tilt2[3] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0.5), vec3(0, 0.5, 0)};
    assert_int_equal(shaded(tilt2), rgba_of(0.3 + 0.7 / sqrt(1.3125)));
}

/* A polygon over the whole screen (and past it) draws from pixel (0, 0)
 * to (width - 1, height - 1): its box is clamped to the screen, not
 * inside it. */
static void test_box_clamped_to_screen(void **state)
{
    (void)state;
    Vec3 big[3] = {vec3(-3, -3, 0), vec3(3, -3, 0), vec3(0, 3, 0)};
    WlPphigsCmd c = command(big);
    assert_int_equal(c.x0, 0);
    assert_int_equal(c.y0, 0);
    assert_int_equal(c.x1, 99);
    assert_int_equal(c.y1, 79);
}

/* A primitive on the far plane (NDC z = 1, inside [-1, 1]) has depth 0,
 * so its pixel key is its tag alone (pphigs_pixels.c pixel_key) and it
 * wins over the cleared key 0 only with a tag of at least 1: the ids the
 * distribution gives (pphigs_distrib.c retag) start at 1, so the host
 * list's very first element draws too. */
static void test_far_plane_first_element_draws(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    Vec3 v[3] = {vec3(-1, -1, 1), vec3(1, -1, 1), vec3(0, 1, 1)};
    add(db, root, scene_elem_prim(SCENE_EL_POLYGON, v, 3));
    scene_db_post(db, root);
    WlPphigsWeights w;
    WlPphigsCosts c = {.poly = 1000, .vertex = 100};
    wl_pphigs_weights_from_costs(&c, 1, &w);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 1, WL_PPHIGS_COMPLEX, &w);
    const SceneElem *e = scene_db_elem(wl_pphigs_dist_gp(d, 0), root, 0);
    ScenePrimInst pi = {.el = e, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1), .depth = 1};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 8, 8, out), 1);
    /* as many pixels as the same triangle at z = 0 (tag 0, depth > 0) */
    Vec3 near[3] = {vec3(-1, -1, 0), vec3(1, -1, 0), vec3(0, 1, 0)};
    SceneElem ne = scene_elem_prim(SCENE_EL_POLYGON, near, 3);
    pi.el = &ne;
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 8, 8, out), 1);
    uint64_t won[2];
    for (guint k = 0; k < 2; k++) {
        WlPphigsRegion *r = wl_pphigs_region_new(0, 0, 8, 8, 0);
        won[k] = wl_pphigs_region_draw(r, &g_array_index(out, WlPphigsCmd, k));
        wl_pphigs_region_free(r);
    }
    assert_true(won[1] > 0);
    assert_int_equal(won[0], won[1]);
    g_array_free(out, TRUE);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* A quad that is not planar, (-0.5, -0.5, 0) (0.5, -0.5, 0) (0.5, 0.2, 0)
 * (0, 0.9, 0.5): its fan triangles (0, 1, 2) and (0, 2, 3) have NDC
 * areas 0.35 and 0.525 (and (1, 2, 3), not a fan triangle, 0.175), so
 * (0, 2, 3) sets the plane and the shade: u = (1, 0.7, 0),
 * v = (0.5, 1.4, 0.5), n = (0.35, -0.5, 1.05); the plane has z = 0.5 at
 * vertex 3 (screen (50, 4) on 100 x 80), where (0, 1, 2)'s has z = 0. */
static void test_largest_fan_triangle(void **state)
{
    (void)state;
    Vec3 v[4] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0.5, 0.2, 0),
                 vec3(0, 0.9, 0.5)};
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 4);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 0.5, 0.25), .depth = 1};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 100, 80, out), 1);
    WlPphigsCmd c = g_array_index(out, WlPphigsCmd, 0);
    assert_int_equal(c.nedges, 4);
    assert_int_equal(c.rgba, rgba_of(0.3 + 0.7 * 1.05 / sqrt(1.475)));
    assert_true(fabs(c.z.a * 50 + c.z.b * 4 + c.z.c - 0.5) < 1e-12);
    assert_true(fabs(c.z.a * 25 + c.z.b * 60 + c.z.c) < 1e-12); /* vertex 0 */
    g_array_free(out, TRUE);
}

/* On 64 GPs (the most a distribution takes) a modified colour, held by
 * every GP (simple algorithm), is sent to each of the 64 once and every
 * copy changes. */
static void test_modify_64_gps(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    add(db, root, scene_elem_color(vec3(1, 0, 0)));
    add(db, root, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    scene_db_post(db, root);
    WlPphigsWeights w = {.w = {[SCENE_EL_TRIANGLE] = 1}, .cluster = 1};
    WlPphigsDist *d = wl_pphigs_dist_new(db, 64, WL_PPHIGS_SIMPLE, &w);
    uint64_t sent = wl_pphigs_dist_traffic(d)->elements_sent;
    assert_int_equal(sent, 64 + 1);
    SceneElem c = scene_elem_color(vec3(0, 0, 1));
    assert_true(wl_pphigs_dist_modify(d, root, 0, &c, NULL));
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(d);
    assert_int_equal(t->elements_sent, sent + 64);
    for (guint g = 0; g < 64; g++) {
        assert_int_equal(t->sent_to[g], g == 0 ? 3 : 2);
        const SceneElem *e = scene_db_elem(wl_pphigs_dist_gp(d, g), root, 0);
        assert_true(e->kind == SCENE_EL_COLOR && e->color.z == 1 &&
                    e->color.x == 0);
    }
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nonprim_cost),
        cmocka_unit_test(test_shading),
        cmocka_unit_test(test_box_clamped_to_screen),
        cmocka_unit_test(test_far_plane_first_element_draws),
        cmocka_unit_test(test_largest_fan_triangle),
        cmocka_unit_test(test_modify_64_gps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
