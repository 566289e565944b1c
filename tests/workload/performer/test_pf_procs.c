/* test_pf_procs.c — every process model of Performer's multiprocessing
 * (pf_pipeline.c; issue 36, point 2) on fixed stage times (ms), V = 10
 * ms, two retraces a frame (T = 20 ms), DRAW locked, the update list on
 * (APP's changes reach a CULL process at the frame boundary).  Each case
 * shows a property that fails without the model:
 *   - APPCULLDRAW: the frame is the sum of the stages (rounded up to
 *     frame boundaries), latency 1 frame;
 *   - APPCULL_DRAW: the frame is max(APP + CULL, DRAW), latency 2;
 *   - APP_CULLDRAW: the frame is max(APP, CULL + DRAW), latency 2;
 *   - APP_CULL_DRAW: the frame is the largest stage, latency 3: two
 *     frames more than APPCULLDRAW on the same stages;
 *   - the update list: a CULL process pays its cost per frame, and the
 *     hand-off at the boundary is one frame of latency (without it CULL
 *     starts at once);
 *   - ISECT in the APP process adds to APP's frame every frame, a forked
 *     ISECT does not;
 *   - two pipes, each with its own CULL and DRAW, double the frame rate
 *     only when the pipes' stages bind, and never beyond two.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/core/cfg.h"
#include "sim/machine/machine.h"

#include <math.h>
#include "sim/workload/performer/pf_pipeline.h"

typedef struct {
    double app, cull, draw, isect, update; /* ms; cull, draw per pipe */
    guint pipe;                             /* the channel named last */
    double mb;                              /* arena MB every stage moves */
} Times;

static SimTime ms_t(double ms)
{
    return (SimTime)(ms * (double)SIM_MS + 0.5);
}

static SimTime s_app(void *ctx, guint n)
{
    (void)n;
    return ms_t(((Times *)ctx)->app);
}
static SimTime s_cull(void *ctx, guint n, double stress)
{
    (void)n, (void)stress;
    return ms_t(((Times *)ctx)->cull);
}
static SimTime s_draw(void *ctx, guint n)
{
    (void)n;
    return ms_t(((Times *)ctx)->draw);
}
static SimTime s_isect(void *ctx, guint n)
{
    (void)n;
    return ms_t(((Times *)ctx)->isect);
}
static SimTime s_update(void *ctx, guint n)
{
    (void)n;
    return ms_t(((Times *)ctx)->update);
}
static void s_channel(void *ctx, guint pipe)
{
    ((Times *)ctx)->pipe = pipe;
}
static uint64_t s_bytes(void *ctx)
{
    return (uint64_t)(((Times *)ctx)->mb * 1e6 + 0.5);
}

typedef struct {
    double interval, latency; /* ms, after 4 frames */
    SimTime busy[8];          /* the processors' work */
    guint isects;             /* frames that ran ISECT */
    SimTime waited, bus_busy; /* the arena's: waits for the bus, use */
} Out;

typedef struct {
    WlPfMpMode mode;
    guint pipes;
    gboolean update_list, isect_in_app;
    double arena_bw; /* > 0: an arena bus of this many bytes/s */
} Model;

#define FRAMES 16

static Out run(Model md, Times t)
{
    SimEngine *eng = sim_engine_new(1);
    GError *err = NULL;
    /* enough processors for two pipes of three processes and ISECT */
    CfgNode *root = cfg_load_string(
        "machine: {model: sgi-onyx, nodes: {cpu: {count: 8}}}\n", "m.yaml",
        &err);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    if (!m)
        fail_msg("%s", err->message);
    MachProc *procs[8];
    for (guint i = 0; i < 8; i++)
        procs[i] = mach_proc(m, "cpu", i);
    assert_true(wl_pf_mp_procs(md.mode, md.pipes) + 1 <= 8);
    WlPfStageFns f = {s_app,  s_cull,    s_draw,   t.isect ? s_isect : NULL,
                      NULL,   NULL,      s_channel, s_update, s_bytes};
    WlPfArenaParams ap = {.pieces = 4};
    WlPfArena arena;
    assert_true(wl_pf_arena_init(&arena, eng, m, &ap, &err));
    mach_shmem_init_with(&arena.bus, md.arena_bw, 0);
    WlPfPipeParams p = {.mode = md.mode,
                        .video = 10 * SIM_MS,
                        .per_frame = 2,
                        .locked = TRUE,
                        .frames = FRAMES,
                        .pipes = md.pipes,
                        .update_list = md.update_list,
                        .isect_in_app = md.isect_in_app,
                        .arena = md.arena_bw > 0 ? &arena : NULL};
    GArray *recs = g_array_new(FALSE, TRUE, sizeof(WlPfFrameRec));
    assert_true(
        wl_pf_pipe_run(eng, procs, &p, &f, &t, recs, SIM_TIME_MAX, &err));
    assert_int_equal(recs->len, FRAMES);
    Out o = {.interval = wl_pf_mean_interval_s(recs, 4) * 1e3,
             .latency = wl_pf_mean_latency_s(recs, 4) * 1e3};
    for (guint i = 0; i < 8; i++)
        o.busy[i] = mach_proc_busy(procs[i]);
    for (guint n = 0; n < FRAMES; n++)
        o.isects += g_array_index(recs, WlPfFrameRec, n).isect > 0;
    o.waited = arena.queued, o.bus_busy = arena.bus.busy;
    wl_pf_arena_clear(&arena);
    g_array_free(recs, TRUE);
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
    return o;
}

static void near(double got, double want)
{
    if (fabs(got - want) > 1e-6)
        fail_msg("%.6f ms, expected %.6f", got, want);
}

static Model model(WlPfMpMode mode)
{
    return (Model){.mode = mode, .pipes = 1, .update_list = TRUE};
}

/* One process: APP + CULL + DRAW = 15 ms fits a 20 ms frame; 24 ms
 * (each stage alone < T) takes two: the frame is the sum. */
static void test_appculldraw_sum(void **st)
{
    (void)st;
    Out a = run(model(WL_PF_MP_APPCULLDRAW), (Times){4, 5, 6, 0, 0, 0, 0});
    near(a.interval, 20);
    near(a.latency, 20); /* swap at the boundary after the frame's start */
    Out b = run(model(WL_PF_MP_APPCULLDRAW), (Times){8, 7, 9, 0, 0, 0, 0});
    near(b.interval, 40);
    /* the update list is not applied in the APP process */
    Out c = run(model(WL_PF_MP_APPCULLDRAW), (Times){4, 5, 6, 0, 30, 0, 0});
    near(c.interval, 20);
}

/* In `mode`, the stages `fit` share a 20 ms frame at `latency` and
 * `over` take two. */
static Out fits(WlPfMpMode mode, Times fit, double latency, Times over)
{
    Out a = run(model(mode), fit);
    near(a.interval, 20);
    near(a.latency, latency);
    near(run(model(mode), over).interval, 40);
    return a;
}

/* APP+CULL, DRAW: 8 + 7 and 9 fit where their sum 24 did not; APP +
 * CULL = 24 does not fit, although each is below T.  DRAW at the next
 * boundary, swap at the one after: latency 2 frames. */
static void test_appcull_draw(void **st)
{
    (void)st;
    fits(WL_PF_MP_APPCULL_DRAW, (Times){8, 7, 9, 0, 0, 0, 0}, 40,
         (Times){12, 12, 5, 0, 0, 0, 0});
}

/* APP, CULL+DRAW: CULL and DRAW (7 + 9) share a frame after APP's hand-
 * off; 12 + 12 do not.  CULL at the next boundary, DRAW after it. */
static void test_app_culldraw(void **st)
{
    (void)st;
    Out a = fits(WL_PF_MP_APP_CULLDRAW, (Times){12, 7, 9, 0, 0, 0, 0}, 40,
                 (Times){5, 12, 12, 0, 0, 0, 0});
    /* the CULL process applies the update list: 3 ms more a frame */
    Out c = run(model(WL_PF_MP_APP_CULLDRAW), (Times){5, 7, 9, 0, 3, 0, 0});
    near(c.interval, 20);
    assert_int_equal(c.busy[1] - a.busy[1], FRAMES * ms_t(3));
}

/* Three processes: the largest stage sets the frame (18 ms each, sum
 * 54); on stages that one process runs in a frame, two frames more
 * latency than APPCULLDRAW. */
static void test_app_cull_draw(void **st)
{
    (void)st;
    Out a = run(model(WL_PF_MP_APP_CULL_DRAW), (Times){18, 18, 18, 0, 0, 0, 0});
    near(a.interval, 20);
    near(a.latency, 60);
    Out one = run(model(WL_PF_MP_APPCULLDRAW), (Times){6, 6, 6, 0, 0, 0, 0});
    Out three = run(model(WL_PF_MP_APP_CULL_DRAW), (Times){6, 6, 6, 0, 0, 0, 0});
    near(one.interval, three.interval);
    near(three.latency - one.latency, 2 * 20);
    /* a DRAW over T (locked) takes two boundaries: 40 ms, not 25 */
    Out b = run(model(WL_PF_MP_APP_CULL_DRAW), (Times){5, 5, 25, 0, 0, 0, 0});
    near(b.interval, 40);
}

/* The hand-off at the boundary is one frame of latency: without the
 * update list CULL takes the frame at once after APP. */
static void test_update_list_latency(void **st)
{
    (void)st;
    Model m = model(WL_PF_MP_APP_CULL_DRAW);
    Out with = run(m, (Times){4, 4, 4, 0, 1, 0, 0});
    m.update_list = FALSE;
    Out without = run(m, (Times){4, 4, 4, 0, 1, 0, 0});
    near(with.interval, without.interval);
    near(with.latency - without.latency, 20);
    /* CULL's process pays the update list only with it */
    assert_int_equal(with.busy[1] - without.busy[1], FRAMES * ms_t(1));
}

/* ISECT in the APP process (9 ms) makes a 15 ms one-process frame 24
 * ms, two boundaries; forked, it runs beside APP (every other frame when
 * it is longer than T). */
static void test_isect_in_app(void **st)
{
    (void)st;
    Model m = model(WL_PF_MP_APPCULLDRAW);
    Out forked = run(m, (Times){4, 5, 6, 9, 0, 0, 0});
    m.isect_in_app = TRUE;
    Out in_app = run(m, (Times){4, 5, 6, 9, 0, 0, 0});
    near(forked.interval, 20);
    near(in_app.interval, 40);
    assert_int_equal(in_app.isects, FRAMES);
    assert_int_equal(in_app.busy[0], FRAMES * ms_t(4 + 5 + 6 + 9));
    assert_int_equal(forked.busy[0], FRAMES * ms_t(4 + 5 + 6));
    m.isect_in_app = FALSE;
    Out slow = run(m, (Times){4, 5, 6, 30, 0, 0, 0});
    assert_int_equal(slow.isects, FRAMES / 2);
}

/* Two pipes, each with its own CULL and DRAW processes, each drawing
 * half the scene: a DRAW-bound frame (30 ms on one pipe, locked: 40)
 * doubles its rate (15 ms each: 20); an APP-bound one (30 ms) does not
 * move.  One process (APPCULLDRAW) serves both pipes in turn: the sum. */
static void test_two_pipes(void **st)
{
    (void)st;
    Model m = model(WL_PF_MP_APP_CULL_DRAW);
    Out one = run(m, (Times){5, 6, 30, 0, 0, 0, 0});
    m.pipes = 2;
    Out two = run(m, (Times){5, 3, 15, 0, 0, 0, 0});
    near(one.interval, 40);
    near(two.interval, 20);
    Out app_one = run(model(WL_PF_MP_APP_CULL_DRAW), (Times){30, 6, 8, 0, 0, 0, 0});
    Out app_two = run(m, (Times){30, 3, 4, 0, 0, 0, 0});
    near(app_one.interval, app_two.interval);
    Model single = model(WL_PF_MP_APPCULLDRAW);
    single.pipes = 2;
    Out s = run(single, (Times){4, 3, 4, 0, 0, 0, 0}); /* 4 + 2 (3 + 4) = 18 */
    near(s.interval, 20);
    Out s2 = run(single, (Times){4, 3, 5, 0, 0, 0, 0}); /* 4 + 2 (3 + 5) = 20 */
    near(s2.interval, 20);
    Out s3 = run(single, (Times){5, 3, 5, 0, 0, 0, 0}); /* 21 */
    near(s3.interval, 40);
}

/* The shared arena: every stage moves 0.5 MB on a 100 MB/s bus (5 ms).
 * One process never waits for the bus but pays every transfer: 2 ms of
 * work a stage becomes 21 ms a frame, two boundaries (6 without the
 * arena).  Three processes: APP and the locked DRAW start together at a
 * boundary and wait for each other's transfers (1.5 MB each: 34 ms of
 * bus for stages of 17 ms alone, two boundaries or more; on a fast bus,
 * one);
 * the bus carries every byte once (its busy time is the frames' bytes /
 * bandwidth). */
static void test_arena_contention(void **st)
{
    (void)st;
    Model one = model(WL_PF_MP_APPCULLDRAW), three = model(WL_PF_MP_APP_CULL_DRAW);
    three.update_list = FALSE; /* CULL after APP, not at the boundary */
    Times t = {2, 2, 2, 0, 0, 0, 0.5};
    near(run(one, t).interval, 20);
    one.arena_bw = three.arena_bw = 1e8;
    Out a = run(one, t);
    near(a.interval, 40);
    assert_int_equal(a.waited, 0);
    assert_int_equal(a.bus_busy, 3 * FRAMES * 5 * SIM_MS);
    Out b = run(three, t);
    near(b.interval, 20);
    assert_true(b.waited > 0);
    assert_int_equal(b.bus_busy, 3 * FRAMES * 5 * SIM_MS);
    /* waiting, a stage takes longer than its work and its own bytes */
    Out c = run(three, (Times){2, 2, 2, 0, 0, 0, 1.5}); /* 17 ms alone */
    assert_true(c.interval >= 40);
    three.arena_bw = 1e12; /* a fast bus: the contention is gone */
    near(run(three, (Times){2, 2, 2, 0, 0, 0, 1.5}).interval, 20);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_appculldraw_sum),
        cmocka_unit_test(test_appcull_draw),
        cmocka_unit_test(test_app_culldraw),
        cmocka_unit_test(test_app_cull_draw),
        cmocka_unit_test(test_update_list_latency),
        cmocka_unit_test(test_isect_in_app),
        cmocka_unit_test(test_two_pipes),
        cmocka_unit_test(test_arena_contention),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
