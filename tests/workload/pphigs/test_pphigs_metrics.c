/* test_pphigs_metrics.c — seed 001's metrics on generated databases:
 * one GP is the serial traversal; the speed-up identity; the complex
 * algorithm beats the simple one where attributes are dense.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/workload/pphigs/pphigs_metrics.h"
#include "tests/workload/pphigs/pphigs_rig.h"
#include <string.h>

/* Test costs: a 4-vertex polygon 1 us on-screen, 0.3 us rejected. */
static const WlPphigsCosts C = {.poly = 600 * SIM_NS,
                                .vertex = 100 * SIM_NS,
                                .reject_vertex = 75 * SIM_NS,
                                .color = 100 * SIM_NS,
                                .matrix = 300 * SIM_NS,
                                .concat = SIM_US,
                                .execute = 500 * SIM_NS};

static ScenePphigsSpec flock(void)
{
    ScenePphigsSpec s = {.kind = SCENE_PPHIGS_FLOCK,
                         .seed = 9,
                         .verts = 4,
                         .size = 10,
                         .boids = 30,
                         .boid_polygons = 5,
                         .boid_colors = 4,
                         .well_structs = 10,
                         .well_polygons = 60,
                         .well_attributes = 5};
    return s;
}

static void test_one_gp_is_serial(void **st)
{
    (void)st;
    ScenePphigsSpec s = flock();
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    WlPphigsMetrics a, b;
    pphigs_rig_analytic(&db, 1, &C, 8, &a, &b);
    assert_true(fabs(a.efficiency - 1) < 1e-12);
    assert_true(fabs(b.efficiency - 1) < 1e-12);
    assert_true(fabs(b.utilisation - 1) < 1e-12);
    pphigs_rig_analytic(&db, 4, &C, 8, &a, &b);
    assert_true(fabs(b.speedup - b.t1 / b.max) < 1e-9);
    assert_true(a.efficiency < 0.9); /* attributes copied to every GP */
    assert_true(b.efficiency > a.efficiency + 0.1);
    scene_pphigs_db_clear(&db);
}

static void test_offscreen_is_cheaper(void **st)
{
    (void)st;
    ScenePphigsSpec s = {.kind = SCENE_PPHIGS_LOBBY,
                         .seed = 2,
                         .polygons = 400,
                         .attributes = 50,
                         .verts = 4,
                         .size = 100,
                         .fov_deg = 51};
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    Mat4 vp = scene_camera_view_proj(&db.camera);
    WlPphigsCosts full = C; /* rejected costs as much as on-screen */
    full.reject_vertex = (C.poly + 4 * C.vertex) / 4;
    SimTime t = wl_pphigs_traversal_cost(db.db, vp, &C);
    SimTime tf = wl_pphigs_traversal_cost(db.db, vp, &full);
    double off = scene_pphigs_offscreen_share(db.db, vp);
    assert_true(off > 0.3 && off < 0.8);
    uint64_t n_off = (uint64_t)llround(400 * off);
    assert_int_equal(tf - t,
                     n_off * (C.poly + 4 * C.vertex - 4 * C.reject_vertex));
    scene_pphigs_db_clear(&db);
}

/* The formulas on values worked out by hand: T1 12 us over GPs of 2, 4
 * and 6 us: efficiency T1 / sum = 1, utilisation sum / (n max) = 2/3,
 * speed-up n x efficiency x utilisation = 2; all-zero GPs give zeros. */
static void test_formulas(void **st)
{
    (void)st;
    WlPphigsMetrics m;
    const double gp[] = {2, 4, 6}, z[] = {0, 0};
    wl_pphigs_metrics_from(12, gp, 3, &m);
    assert_true(m.t1 == 12 && m.sum == 12 && m.max == 6);
    assert_true(m.efficiency == 1);
    assert_true(fabs(m.utilisation - 2.0 / 3) < 1e-15);
    assert_true(fabs(m.speedup - 2) < 1e-12);
    wl_pphigs_metrics_from(5, z, 2, &m);
    assert_true(m.sum == 0 && m.max == 0 && m.efficiency == 0 &&
                m.utilisation == 0 && m.speedup == 0);
    /* element costs: polygon + vertex each; replace vs concat; rejected
     * polygons pay reject_vertex per vertex only */
    Vec3 v[4] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(0, 1, 0)};
    SceneElem q = scene_elem_prim(SCENE_EL_POLYGON, v, 4);
    assert_int_equal(wl_pphigs_elem_cost(&C, &q), 600 * SIM_NS + 400 * SIM_NS);
    assert_int_equal(wl_pphigs_prim_cost(&C, &q, FALSE), SIM_US);
    assert_int_equal(wl_pphigs_prim_cost(&C, &q, TRUE), 300 * SIM_NS);
    SceneElem r = scene_elem_matrix(mat4_identity(), SCENE_MAT_REPLACE);
    SceneElem k = scene_elem_matrix(mat4_identity(), SCENE_MAT_CONCAT);
    SceneElem c = scene_elem_color(vec3(1, 0, 0));
    SceneElem x = scene_elem_execute(0);
    assert_int_equal(wl_pphigs_elem_cost(&C, &r), 300 * SIM_NS);
    assert_int_equal(wl_pphigs_elem_cost(&C, &k), SIM_US);
    assert_int_equal(wl_pphigs_elem_cost(&C, &c), 100 * SIM_NS);
    assert_int_equal(wl_pphigs_elem_cost(&C, &x), 500 * SIM_NS);
    /* weights in us: every primitive kind the polygon's, attributes and
     * executes their own, the vertex weight, the cluster as given */
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(&C, 2.5, &w);
    static const struct {
        int k;
        double us;
    } want[] = {{SCENE_EL_TRIANGLE, 0.6}, {SCENE_EL_POLYGON, 0.6},
                {SCENE_EL_TRISTRIP, 0.6}, {SCENE_EL_POLYGON2D, 0.6},
                {SCENE_EL_COLOR, 0.1},    {SCENE_EL_MATRIX, 0.3},
                {SCENE_EL_EXECUTE, 0.5}};
    for (guint i = 0; i < G_N_ELEMENTS(want); i++)
        assert_true(fabs(w.w[want[i].k] - want[i].us) < 1e-12);
    assert_true(fabs(w.w_vertex - 0.1) < 1e-12);
    assert_true(w.cluster == 2.5 && w.strip_split == 0);
}

/* The count of name in o (0 if absent). */
static uint64_t ops_of(const MachOps *o, const char *name)
{
    for (guint i = 0; i < o->n; i++)
        if (strcmp(o->op[i].name, name) == 0)
            return o->op[i].count;
    return 0;
}

/* a = C M(replace) X(b) X(b) T; b = M(concat) T C: the attributes and
 * executes of every instance, attributes first in each structure and a
 * first in the max-set, are all counted:
 * a: 100 + 300 + 2 x 500 ns; each of b's 2 instances 1000 + 100 ns. */
static void test_nonprim_exact(void **st)
{
    (void)st;
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    SceneDb *db = scene_db_new();
    guint a = scene_db_add_struct(db, "a"), b = scene_db_add_struct(db, "b");
    SceneElem ea[] = {scene_elem_color(vec3(1, 0, 0)),
                      scene_elem_matrix(mat4_identity(), SCENE_MAT_REPLACE),
                      scene_elem_execute(b), scene_elem_execute(b),
                      scene_elem_prim(SCENE_EL_TRIANGLE, v, 3)};
    SceneElem eb[] = {scene_elem_matrix(mat4_identity(), SCENE_MAT_CONCAT),
                      scene_elem_prim(SCENE_EL_TRIANGLE, v, 3),
                      scene_elem_color(vec3(0, 1, 0))};
    for (guint i = 0; i < G_N_ELEMENTS(ea); i++)
        assert_true(scene_db_append(db, a, &ea[i], NULL));
    for (guint i = 0; i < G_N_ELEMENTS(eb); i++)
        assert_true(scene_db_append(db, b, &eb[i], NULL));
    scene_db_post(db, a);
    assert_int_equal(wl_pphigs_nonprim_cost(db, &C),
                     (100 + 300 + 2 * 500 + 2 * (1000 + 100)) * SIM_NS);
    MachOps o = {0};
    wl_pphigs_nonprim_ops(db, &o);
    assert_int_equal(ops_of(&o, "color"), 3);
    assert_int_equal(ops_of(&o, "matrix_replace"), 1);
    assert_int_equal(ops_of(&o, "matrix_concat"), 2);
    assert_int_equal(ops_of(&o, "execute"), 2);
    assert_int_equal(ops_of(&o, "polygon"), 0);
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_gp_is_serial),
        cmocka_unit_test(test_offscreen_is_cheaper),
        cmocka_unit_test(test_formulas),
        cmocka_unit_test(test_nonprim_exact),
    };
    return cmocka_run_group_tests_name("pphigs_metrics", tests, NULL, NULL);
}
