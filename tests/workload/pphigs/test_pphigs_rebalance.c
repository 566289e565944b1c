/* test_pphigs_rebalance.c — seed 001 §5: a balanced distribution is never
 * touched; an imperfect one (primitives piled on one GP) and one with
 * invalidated weights (strips of a coherent model, half off-screen)
 * converge under the threshold, act only after `frames` frames over it,
 * move at most `max_moves` per frame, and stay converged; an exchange
 * needs a gain strictly below the gap (worked out by hand).  Per-frame GP
 * times are the real traversal's (off-screen primitives cheaper).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>

#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/pphigs_rebalance.h"

/* Test costs: a 4-vertex polygon 1 us on-screen, 0.3 us rejected. */
static const WlPphigsCosts C = {.poly = 600 * SIM_NS,
                                .vertex = 100 * SIM_NS,
                                .reject_vertex = 75 * SIM_NS,
                                .color = 100 * SIM_NS,
                                .matrix = 300 * SIM_NS,
                                .concat = SIM_US,
                                .execute = 500 * SIM_NS};
static const WlPphigsRebalParams P = {.threshold = 0.10,
                                      .frames = 3,
                                      .fraction = 0.5,
                                      .max_moves = 16,
                                      .seed = 11};

#define NGP 4

typedef struct {
    ScenePphigsDb db;
    WlPphigsDist *d;
    Mat4 vp;
} Fix;

static void fix_new(Fix *x, ScenePphigsKind k, double cluster)
{
    ScenePphigsSpec s = {.kind = k,
                         .seed = 5,
                         .polygons = 800,
                         .attributes = 40,
                         .verts = 4,
                         .size = 100,
                         .fov_deg = 51};
    assert_true(scene_pphigs_generate(&s, &x->db, NULL));
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(&C, cluster, &w);
    x->d = wl_pphigs_dist_new(x->db.db, NGP, WL_PPHIGS_COMPLEX, &w);
    x->vp = scene_camera_view_proj(&x->db.camera);
}

static void fix_free(Fix *x)
{
    wl_pphigs_dist_free(x->d);
    scene_pphigs_db_clear(&x->db);
}

/* One frame: measured times, then the rebalancer. */
static void frame(Fix *x, WlPphigsRebal *rb, WlPphigsRebalStep *st)
{
    double us[NGP];
    WlPphigsMetrics m;
    wl_pphigs_metrics(x->d, x->vp, &C, us, &m);
    wl_pphigs_rebal_frame(rb, x->d, x->vp, &C, us, st);
    assert_true(fabs(st->imbalance - (1 - m.utilisation)) < 1e-12);
    assert_true(st->moves <= P.max_moves);
}

/* Runs frames until converged; checks hysteresis and that it stays. */
static void converge(Fix *x, WlPphigsRebalCause want)
{
    WlPphigsRebal *rb = wl_pphigs_rebal_new(&P);
    WlPphigsRebalStep st;
    int k, conv = -1;
    for (k = 0; k < 200 && conv < 0; k++) {
        frame(x, rb, &st);
        assert_true(st.imbalance > P.threshold || k > 0);
        if (k < (int)P.frames - 1)
            assert_int_equal(st.moves, 0); /* not before `frames` frames */
        if (k == (int)P.frames - 1) {
            assert_int_equal(st.cause, want);
            assert_true(st.moves > 0);
        }
        if (st.imbalance <= P.threshold)
            conv = k;
    }
    assert_true(conv > 0);
    uint64_t moved = st.total_moves;
    for (k = 0; k < 30; k++) {
        frame(x, rb, &st);
        assert_true(st.imbalance <= P.threshold);
        assert_int_equal(st.moves, 0);
    }
    assert_int_equal(st.total_moves, moved);
    wl_pphigs_rebal_free(rb);
}

static void test_balanced_never_moves(void **s)
{
    (void)s;
    for (int k = SCENE_PPHIGS_STATION; k <= SCENE_PPHIGS_LOBBY; k++) {
        Fix x;
        fix_new(&x, (ScenePphigsKind)k, 8);
        WlPphigsRebal *rb = wl_pphigs_rebal_new(&P);
        WlPphigsRebalStep st;
        for (int f = 0; f < 30; f++) {
            frame(&x, rb, &st);
            assert_true(st.imbalance < P.threshold);
            assert_int_equal(st.moves, 0);
        }
        assert_int_equal(st.total_moves, 0);
        wl_pphigs_rebal_free(rb);
        fix_free(&x);
    }
}

static void test_imperfect_converges(void **s)
{
    (void)s;
    Fix x;
    fix_new(&x, SCENE_PPHIGS_STATION, 8);
    const SceneDb *h = wl_pphigs_dist_host(x.d);
    guint k = 0;
    for (guint i = 0; i < scene_db_len(h, 0); i++) /* pile onto GP 0 */
        if (wl_pphigs_dist_owner(x.d, 0, i) > 0 && k++ % 3 != 0)
            assert_true(wl_pphigs_dist_move(x.d, 0, i, 0));
    converge(&x, WL_PPHIGS_REBAL_IMPERFECT);
    fix_free(&x);
}

static void test_invalidated_converges(void **s)
{
    (void)s;
    Fix x; /* clusters of ~200 polygons: each GP holds a strip (§5.2) */
    fix_new(&x, SCENE_PPHIGS_LOBBY, 200);
    converge(&x, WL_PPHIGS_REBAL_INVALIDATED);
    fix_free(&x);
}

/* The first acting frame with a tight cap and a whole-gap budget moves
 * exactly max_moves primitives: 3 single moves for an imperfect
 * distribution, one exchange (2 moves) for invalidated weights. */
static void test_cap_reached_exactly(void **s)
{
    (void)s;
    for (int inval = 0; inval < 2; inval++) {
        Fix x;
        fix_new(&x, inval ? SCENE_PPHIGS_LOBBY : SCENE_PPHIGS_STATION,
                inval ? 200 : 8);
        if (!inval)
            for (guint i = 0; i < scene_db_len(wl_pphigs_dist_host(x.d), 0);
                 i++)
                if (wl_pphigs_dist_owner(x.d, 0, i) > 0)
                    assert_true(wl_pphigs_dist_move(x.d, 0, i, 0));
        WlPphigsRebalParams p = P;
        p.fraction = 1;
        p.max_moves = inval ? 2 : 3;
        WlPphigsRebal *rb = wl_pphigs_rebal_new(&p);
        WlPphigsRebalStep st;
        for (guint f = 0; f < p.frames; f++)
            frame(&x, rb, &st);
        assert_int_equal(st.cause, inval ? WL_PPHIGS_REBAL_INVALIDATED
                                         : WL_PPHIGS_REBAL_IMPERFECT);
        assert_string_equal(wl_pphigs_rebal_cause_name(st.cause),
                            inval ? "invalidated" : "imperfect");
        /* a budget next to nothing still makes the first move (or
         * exchange), and only that */
        WlPphigsRebalStep z;
        p.fraction = 1e-9;
        WlPphigsRebal *r0 = wl_pphigs_rebal_new(&p);
        for (guint f = 0; f < p.frames; f++)
            frame(&x, r0, &z);
        assert_int_equal(z.moves, inval ? 2 : 1);
        wl_pphigs_rebal_free(r0);
        assert_int_equal(st.moves, p.max_moves);
        assert_int_equal(st.total_moves, p.max_moves);
        wl_pphigs_rebal_free(rb);
        fix_free(&x);
    }
}

/* Detection worked out by hand on 4 GPs: imbalance (max - mean) / max;
 * a frame counts over the threshold only strictly above it; the count
 * resets on a frame at or under it; nothing moves before `frames`
 * consecutive frames over it. */
static void test_detection_counter(void **s)
{
    (void)s;
    static const double even[NGP] = {1, 1, 1, 1}, half[NGP] = {2, 0, 1, 1},
                        zero[NGP] = {0, 0, 0, 0}, third[NGP] = {3, 1, 2, 2};
    assert_true(wl_pphigs_imbalance(even, NGP) == 0);
    assert_true(wl_pphigs_imbalance(half, NGP) == 0.5); /* (2 - 1) / 2 */
    assert_true(wl_pphigs_imbalance(zero, NGP) == 0);
    assert_true(fabs(wl_pphigs_imbalance(third, NGP) - 1.0 / 3) < 1e-15);
    Fix x;
    fix_new(&x, SCENE_PPHIGS_STATION, 2);
    WlPphigsRebalParams p = P;
    p.threshold = 0.5;
    p.frames = 2;
    WlPphigsRebal *rb = wl_pphigs_rebal_new(&p);
    static const double *const seq[] = {half, third, half, even};
    static const guint over[] = {0, 0, 0, 0};
    WlPphigsRebalStep st;
    for (guint f = 0; f < 4; f++) {
        wl_pphigs_rebal_frame(rb, x.d, x.vp, &C, seq[f], &st);
        assert_int_equal(st.over, over[f]);
        assert_int_equal(st.cause, WL_PPHIGS_REBAL_NONE);
        assert_int_equal(st.moves, 0);
    }
    assert_true(st.imbalance == 0);
    wl_pphigs_rebal_free(rb);
    p.threshold = 0.49;
    rb = wl_pphigs_rebal_new(&p);
    static const double *const seq2[] = {half, half, third, half};
    static const guint over2[] = {1, 2, 0, 1};
    for (guint f = 0; f < 4; f++) {
        wl_pphigs_rebal_frame(rb, x.d, x.vp, &C, seq2[f], &st);
        assert_int_equal(st.over, over2[f]);
        assert_true(st.imbalance == wl_pphigs_imbalance(seq2[f], NGP));
        assert_int_equal(st.cause == WL_PPHIGS_REBAL_NONE, f != 1);
        if (f == 1) { /* made-up times: the nominal loads are even, every
                       * primitive on screen: no exchange to make */
            assert_int_equal(st.cause, WL_PPHIGS_REBAL_INVALIDATED);
            assert_int_equal(st.moves, 0);
        }
    }
    wl_pphigs_rebal_free(rb);
    fix_free(&x);
}

/* §5.2 exchange worked out by hand on 2 GPs, view = identity: GP 0 holds
 * an on-screen quad (actual 1 us), GP 1 an equal-nominal quad off to the
 * right (rejected, 0.3 us).  The exchange gains 1 - 0.3 us; it is made
 * only when that is strictly less than the measured gap: at a gain equal
 * to the gap the two GPs would just trade places. */
static guint exchange_moves(double gp0_us)
{
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    Vec3 on[4] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0.5, 0.5, 0),
                  vec3(-0.5, 0.5, 0)};
    Vec3 off[4] = {vec3(2, -0.5, 0), vec3(3, -0.5, 0), vec3(3, 0.5, 0),
                   vec3(2, 0.5, 0)};
    SceneElem a = scene_elem_prim(SCENE_EL_POLYGON, on, 4),
              b = scene_elem_prim(SCENE_EL_POLYGON, off, 4);
    assert_true(scene_db_append(db, root, &a, NULL));
    assert_true(scene_db_append(db, root, &b, NULL));
    scene_db_post(db, root);
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(&C, 1, &w);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
    for (guint i = 0; i < 2; i++)
        if (wl_pphigs_dist_owner(d, root, i) != (gint)i)
            assert_true(wl_pphigs_dist_move(d, root, i, i));
    WlPphigsRebalParams p = P;
    p.frames = 1;
    WlPphigsRebal *rb = wl_pphigs_rebal_new(&p);
    const double us[2] = {gp0_us, 0.3};
    WlPphigsRebalStep st;
    wl_pphigs_rebal_frame(rb, d, mat4_identity(), &C, us, &st);
    assert_int_equal(st.cause, WL_PPHIGS_REBAL_INVALIDATED);
    assert_int_equal(wl_pphigs_dist_owner(d, root, 0), st.moves ? 1 : 0);
    assert_int_equal(wl_pphigs_dist_owner(d, root, 1), st.moves ? 0 : 1);
    wl_pphigs_rebal_free(rb);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
    return st.moves;
}

static void test_exchange_needs_gain_below_gap(void **s)
{
    (void)s;
    assert_int_equal(exchange_moves(1.25), 2); /* gap 0.95 > gain 0.7 */
    assert_int_equal(exchange_moves(1.0), 0);  /* gap = gain, bit for bit */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_balanced_never_moves),
        cmocka_unit_test(test_imperfect_converges),
        cmocka_unit_test(test_invalidated_converges),
        cmocka_unit_test(test_cap_reached_exactly),
        cmocka_unit_test(test_detection_counter),
        cmocka_unit_test(test_exchange_needs_gain_below_gap),
    };
    return cmocka_run_group_tests_name("pphigs_rebalance", tests, NULL, NULL);
}
