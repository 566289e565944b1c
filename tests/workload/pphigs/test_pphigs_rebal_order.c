/* test_pphigs_rebal_order.c — the order of seed 001 §5's random picks,
 * worked out by hand: the rebalancer draws a start in the candidate list
 * of the most-loaded GP (its own stream, seeded by
 * WlPphigsRebalParams.seed: sim_rng_init(seed, 0x5eba1) in
 * pphigs_rebalance.c) and takes the first fitting candidate scanning
 * FORWARD from there, cyclically.  The lists put the only two fitting
 * candidates at both ends of the most-loaded GP's list, so a start
 * strictly between them tells a forward scan (the last one) from a
 * backward one (the first); the seeds are checked to give such a start.
 * Candidates are listed in host order (pphigs_rebalance.c pool_init).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/core/rng.h"
#include "sim/workload/pphigs/pphigs_rebalance.h"

/* Test costs: a triangle 0.9 us on screen, 0.225 us rejected. */
static const WlPphigsCosts C = {.poly = 600 * SIM_NS,
                                .vertex = 100 * SIM_NS,
                                .reject_vertex = 75 * SIM_NS};

/* Host list spelled t (on-screen triangle), o (off-screen, x = 5) or
 * p (order-dependent polygon); all dealt to GP 0 of 2 (one cluster),
 * then positions from `to1` on moved to GP 1. */
static WlPphigsDist *two_gps(const char *list, guint to1,
                             const WlPphigsWeights *w)
{
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    for (const char *c = list; *c; c++) {
        double x = *c == 'o' ? 5 : 0;
        Vec3 v[3] = {vec3(x, 0, 0), vec3(x + 0.5, 0, 0), vec3(x, 0.5, 0)};
        SceneElem e = scene_elem_prim(
            *c == 'p' ? SCENE_EL_POLYGON2D : SCENE_EL_TRIANGLE, v, 3);
        assert_true(scene_db_append(db, root, &e, NULL));
    }
    scene_db_post(db, root);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, w);
    scene_db_free(db);
    for (guint i = 0; list[i]; i++) {
        assert_int_equal(wl_pphigs_dist_owner(d, root, i), 0);
        if (i >= to1)
            assert_true(wl_pphigs_dist_move(d, root, i, 1));
    }
    return d;
}

/* The start the rebalancer draws first, in a list of n candidates. */
static guint first_start(uint64_t seed, guint n)
{
    SimRng r;
    sim_rng_init(&r, seed, 0x5eba1);
    return (guint)sim_rng_below(&r, n);
}

static WlPphigsRebalStep act_once(WlPphigsDist *d, uint64_t seed,
                                  guint max_moves, const double *us)
{
    WlPphigsRebalParams p = {.threshold = 0.1, .frames = 1, .fraction = 1,
                             .max_moves = max_moves, .seed = seed};
    WlPphigsRebal *rb = wl_pphigs_rebal_new(&p);
    WlPphigsRebalStep st;
    wl_pphigs_rebal_frame(rb, d, mat4_identity(), &C, us, &st);
    wl_pphigs_rebal_free(rb);
    return st;
}

/* §5.2: GP 0 holds t o*10 t (12 candidates; only the t's are on screen,
 * so only they can go), GP 1 twelve off-screen triangles (nominal loads
 * even).  One exchange (cap 2): GP 0's on-screen triangle found first
 * from the start goes to GP 1 and GP 1's first candidate, host
 * position 12, comes back: position 0 for start 0, else position 11. */
static void test_exchange_scans_forward(void **st)
{
    (void)st;
    static const double us[] = {10, 0};
    guint between = 0;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        WlPphigsWeights w;
        wl_pphigs_weights_from_costs(&C, 100, &w);
        WlPphigsDist *d = two_gps("tooooooooooto" "ooooooooooo", 12, &w);
        WlPphigsRebalStep s = act_once(d, seed, 2, us);
        assert_int_equal(s.cause, WL_PPHIGS_REBAL_INVALIDATED);
        assert_int_equal(s.moves, 2);
        guint start = first_start(seed, 12), mover = start == 0 ? 0 : 11;
        between += start > 0 && start < 11;
        assert_int_equal(wl_pphigs_dist_owner(d, 0, mover), 1);
        assert_int_equal(wl_pphigs_dist_owner(d, 0, 11 - mover), 0);
        assert_int_equal(wl_pphigs_dist_owner(d, 0, 12), 0);
        for (guint i = 1; i < 11; i++)
            assert_int_equal(wl_pphigs_dist_owner(d, 0, i), 0);
        for (guint i = 13; i < 24; i++)
            assert_int_equal(wl_pphigs_dist_owner(d, 0, i), 1);
        wl_pphigs_dist_free(d);
    }
    assert_true(between > 0);
}

/* §5.1 with unit triangles and order-dependent polygons of weight 10:
 * GP 0 holds t p p p t (32), GP 1 p p t t t t (24); the gap 8 lets only
 * a triangle move (a polygon, 10, is not lighter than the gap).  One
 * move (cap 1): position 0 for start 0, else position 4. */
static void test_imperfect_scans_forward(void **st)
{
    (void)st;
    static const double us[] = {9, 0};
    WlPphigsWeights w = {.w = {[SCENE_EL_TRIANGLE] = 1,
                               [SCENE_EL_POLYGON2D] = 10},
                         .cluster = 100};
    guint between = 0;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        WlPphigsDist *d = two_gps("tppptpptttt", 5, &w);
        WlPphigsRebalStep s = act_once(d, seed, 1, us);
        assert_int_equal(s.cause, WL_PPHIGS_REBAL_IMPERFECT);
        assert_int_equal(s.moves, 1);
        guint start = first_start(seed, 5), mover = start == 0 ? 0 : 4;
        between += start > 0 && start < 4;
        assert_int_equal(wl_pphigs_dist_owner(d, 0, mover), 1);
        assert_int_equal(wl_pphigs_dist_owner(d, 0, 4 - mover), 0);
        for (guint i = 1; i < 4; i++)
            assert_int_equal(wl_pphigs_dist_owner(d, 0, i), 0);
        double load[2];
        wl_pphigs_dist_loads(d, load);
        assert_true(load[0] == 31 && load[1] == 25);
        wl_pphigs_dist_free(d);
    }
    assert_true(between > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exchange_scans_forward),
        cmocka_unit_test(test_imperfect_scans_forward),
    };
    return cmocka_run_group_tests_name("pphigs_rebal_order", tests, NULL,
                                       NULL);
}
