/* test_pf_pipe.c — Performer's frame pipeline (pf_pipeline.c) frame by
 * frame: every timestamp of every frame record in each process mode,
 * worked out by hand from fixed stage times (ms) with V = 10 ms and two
 * retraces a frame (T = 20 ms).  The cases:
 *   - three processes, DRAW longer than CULL: DRAW runs back to back
 *     after its double buffer frees, CULL waits for DRAW of frame n - 2;
 *   - APP+CULL and DRAW, floating: the APP process syncs after CULL;
 *   - one process: pfSync after the whole frame;
 *   - locked DRAW starts on frame boundaries;
 *   - ISECT runs beside APP when it is free, skipped when busy;
 *   - a frame ending on a boundary or 1 ps after it;
 *   - what a recording writes of the waits (refresh periods).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/record.h"
#include "sim/machine/machine.h"
#include "sim/workload/performer/pf_pipeline.h"

typedef struct {
    guint app, cull, draw, isect; /* ms */
    const guint *draws;           /* DRAW of each frame, or NULL: draw */
    SimTime draw_ps;              /* added to every DRAW (ps) */
} Times;

static SimTime s_app(void *ctx, guint n)
{
    (void)n;
    return ((Times *)ctx)->app * SIM_MS;
}
static SimTime s_cull(void *ctx, guint n, double stress)
{
    (void)n;
    (void)stress;
    return ((Times *)ctx)->cull * SIM_MS;
}
static SimTime s_draw(void *ctx, guint n)
{
    const Times *t = ctx;
    return (t->draws ? t->draws[n] : t->draw) * SIM_MS + t->draw_ps;
}
static SimTime s_isect(void *ctx, guint n)
{
    (void)n;
    return ((Times *)ctx)->isect * SIM_MS;
}

static WlPfPipeParams stress_params; /* stress, low, high, gain, max */
static SimTime busy[4];              /* the last run's processors' work */
static SimRecorder *recorder;        /* given to run()'s engine when set */

static GArray *run(WlPfMpMode mode, gboolean locked, Times *t, guint frames)
{
    SimEngine *eng = sim_engine_new(1);
    sim_engine_set_recorder(eng, recorder);
    GError *err = NULL;
    MachMachine *m = mach_new_from_model(eng, "sgi-onyx", "analytic", &err);
    if (!m)
        fail_msg("%s", err->message);
    MachProc *procs[4];
    for (guint i = 0; i < 4; i++)
        procs[i] = mach_proc(m, "cpu", i);
    WlPfStageFns f = {.app = s_app, .cull = s_cull, .draw = s_draw,
                      .isect = t->isect ? s_isect : NULL};
    WlPfPipeParams p = {.mode = mode,
                        .video = 10 * SIM_MS,
                        .per_frame = 2,
                        .locked = locked,
                        .frames = frames,
                        .stress = stress_params.stress,
                        .low = stress_params.low,
                        .high = stress_params.high,
                        .gain = stress_params.gain,
                        .max_stress = stress_params.max_stress};
    GArray *recs = g_array_new(FALSE, TRUE, sizeof(WlPfFrameRec));
    assert_true(
        wl_pf_pipe_run(eng, procs, &p, &f, t, recs, SIM_TIME_MAX, &err));
    for (guint i = 0; i < 4; i++)
        busy[i] = mach_proc_busy(procs[i]);
    mach_free(m);
    sim_engine_free(eng);
    return recs;
}

/* Frame n's app start, app end, cull start, cull end, draw start, draw
 * end and swap, in ms. */
static void frame_is(const GArray *r, guint n, const guint want[7])
{
    const WlPfFrameRec *x = &g_array_index(r, WlPfFrameRec, n);
    const SimTime got[7] = {x->app_start, x->app_end,    x->cull_start,
                            x->cull_end,  x->draw_start, x->draw_end,
                            x->swap};
    for (int i = 0; i < 7; i++)
        if (got[i] != want[i] * SIM_MS)
            fail_msg("frame %u field %d: %.3f ms, expected %u", n, i,
                     got[i] / 1e9, want[i]);
}

/* Runs the case and checks every frame against want[n]. */
static void frames_are(WlPfMpMode mode, gboolean locked, Times t, guint n,
                       const guint want[][7], const guint *isect)
{
    GArray *r = run(mode, locked, &t, n);
    assert_int_equal(r->len, n);
    SimTime work = 0;
    for (guint i = 0; i < n; i++) {
        frame_is(r, i, want[i]);
        const WlPfFrameRec *x = &g_array_index(r, WlPfFrameRec, i);
        assert_true(x->stress == 1.0);
        assert_int_equal(x->isect, (isect ? isect[i] : 0) * SIM_MS);
        work += (t.app + t.cull + t.draw) * SIM_MS + x->isect;
    }
    /* the processors did the n frames' stages, no more: busy[0] APP (and
     * CULL, and DRAW as the mode shares them), then the others in turn */
    assert_int_equal(busy[0] + busy[1] + busy[2] + busy[3], work);
    assert_int_equal(busy[0], n * (t.app + (mode != WL_PF_MP_APP_CULL_DRAW
                                                ? t.cull
                                                : 0) +
                                   (mode == WL_PF_MP_APPCULLDRAW ? t.draw : 0)) *
                                  SIM_MS);
    g_array_free(r, TRUE);
}

/* Three processes, DRAW 25 ms: frame n's DRAW waits for frame n - 1's
 * swap (double buffer), swaps at the next retrace; frame 3's CULL waits
 * until frame 1's DRAW ends (65 ms), and APP syncs to the boundary
 * after CULL took its frame. */
static void test_three_processes(void **st)
{
    (void)st;
    const guint want[5][7] = {{0, 3, 3, 7, 7, 32, 40},
                              {20, 23, 23, 27, 40, 65, 70},
                              {40, 43, 43, 47, 70, 95, 100},
                              {60, 63, 65, 69, 100, 125, 130},
                              {80, 83, 95, 99, 130, 155, 160}};
    frames_are(WL_PF_MP_APP_CULL_DRAW, FALSE, (Times){3, 4, 25, 0, NULL, 0}, 5,
               want, NULL);
}

/* DRAW of frame 0 takes 45 ms: CULL of frame 2 (APP done at 43 ms)
 * waits for it (52 ms): at most two frames between CULL and DRAW. */
static void test_cull_waits_for_draw(void **st)
{
    (void)st;
    const guint want[3][7] = {{0, 3, 3, 7, 7, 52, 60},
                              {20, 23, 23, 27, 60, 105, 110},
                              {40, 43, 52, 56, 110, 155, 160}};
    frames_are(WL_PF_MP_APP_CULL_DRAW, FALSE, (Times){3, 4, 45, 0, NULL, 0}, 3,
               want, NULL);
}

/* APP+CULL on one process, DRAW on another: pfSync after CULL (14 ms:
 * the boundary at 20), DRAW at once after CULL. */
static void test_two_processes(void **st)
{
    (void)st;
    const guint want[4][7] = {{0, 6, 6, 14, 14, 23, 30},
                              {20, 26, 26, 34, 34, 43, 50},
                              {40, 46, 46, 54, 54, 63, 70},
                              {60, 66, 66, 74, 74, 83, 90}};
    frames_are(WL_PF_MP_APPCULL_DRAW, FALSE, (Times){6, 8, 9, 0, NULL, 0}, 4, want,
               NULL);
}

/* One process: 23 ms of work, pfSync after DRAW finds the boundary at
 * 40: every other boundary. */
static void test_one_process(void **st)
{
    (void)st;
    const guint want[4][7] = {{0, 6, 6, 14, 14, 23, 30},
                              {40, 46, 46, 54, 54, 63, 70},
                              {80, 86, 86, 94, 94, 103, 110},
                              {120, 126, 126, 134, 134, 143, 150}};
    frames_are(WL_PF_MP_APPCULLDRAW, FALSE, (Times){6, 8, 9, 0, NULL, 0}, 4, want,
               NULL);
}

/* One process whose frame ends exactly on a boundary (20 ms) starts the
 * next frame there; one that ends a picosecond after it waits for the
 * following boundary (40 ms): pfSync rounds up to the boundary. */
static void test_one_process_at_boundary(void **st)
{
    (void)st;
    const SimTime start[2][3] = {{0, 20, 40}, {0, 40, 80}};
    for (SimTime late = 0; late < 2; late++) {
        Times t = {6, 8, 6, 0, NULL, late};
        GArray *r = run(WL_PF_MP_APPCULLDRAW, FALSE, &t, 3);
        for (guint n = 0; n < 3; n++) {
            const WlPfFrameRec *x = &g_array_index(r, WlPfFrameRec, n);
            assert_int_equal(x->app_start, start[late][n] * SIM_MS);
            assert_int_equal(x->draw_end, x->app_start + 20 * SIM_MS + late);
        }
        g_array_free(r, TRUE);
    }
}

/* A recorder that numbers every action and writes the refresh waits
 * down as "now/period;" (ps). */
typedef struct {
    uint64_t id;
    GString *waits;
} Rec;

static uint64_t r_compute(SimRecorder *r, SimTime now, uint32_t node,
                          unsigned phase, SimTime cost, SimTime end,
                          const SimWork *w, gboolean handled)
{
    const SimOp *ops = w->ops;
    unsigned n_ops = w->n_ops;
    const SimOpTerm *terms = w->terms;
    unsigned n_terms = w->n_terms;
    (void)now, (void)node, (void)phase, (void)cost, (void)end, (void)ops;
    (void)n_ops, (void)terms, (void)n_terms, (void)handled;
    return ++((Rec *)r->state)->id;
}

static uint64_t r_refresh(SimRecorder *r, SimTime now, uint32_t node,
                          SimTime period)
{
    (void)node;
    Rec *k = r->state;
    g_string_append_printf(k->waits, "%" G_GUINT64_FORMAT "/%" G_GUINT64_FORMAT
                           ";", (guint64)now, (guint64)period);
    return ++k->id;
}

static void r_begin(SimRecorder *r, uint64_t id, SimTime t)
{
    (void)r, (void)id, (void)t;
}

static void r_end(SimRecorder *r, uint64_t id)
{
    (void)r, (void)id;
}

/* What a recording writes of the waits: DRAW starting at once off a
 * retrace waits 1 ps (a refresh of period 1: now), pfSync exactly on a
 * frame boundary waits for that boundary (period T = 20 ms), and each
 * swap waits for the next retrace (V = 10 ms).  One process, frames of
 * 6 + 8 + 6 ms: DRAW at 14, 34 and 54 ms, frames end at 20, 40, 60. */
static void test_recorded_waits(void **st)
{
    (void)st;
    static const SimRecorderOps ops = {.compute = r_compute,
                                       .refresh = r_refresh,
                                       .begin = r_begin,
                                       .end = r_end};
    Rec k = {0, g_string_new(NULL)};
    SimRecorder r = {&ops, &k};
    recorder = &r;
    Times t = {6, 8, 6, 0, NULL, 0};
    GArray *recs = run(WL_PF_MP_APPCULLDRAW, FALSE, &t, 3);
    recorder = NULL;
    GString *want = g_string_new(NULL);
    const SimTime w[8][2] = {{14, 0}, {20, 20}, {20, 10}, {34, 0},
                             {40, 20}, {40, 10}, {54, 0}, {60, 10}};
    for (int i = 0; i < 8; i++)
        g_string_append_printf(
            want, "%" G_GUINT64_FORMAT "/%" G_GUINT64_FORMAT ";",
            (guint64)(w[i][0] * SIM_MS),
            (guint64)(w[i][1] ? w[i][1] * SIM_MS : 1));
    assert_string_equal(k.waits->str, want->str);
    g_string_free(want, TRUE);
    g_string_free(k.waits, TRUE);
    g_array_free(recs, TRUE);
}

/* Locked DRAW starts on a frame boundary and swaps on the next one. */
static void test_locked(void **st)
{
    (void)st;
    const guint want[4][7] = {{0, 3, 3, 7, 20, 35, 40},
                              {20, 23, 23, 27, 40, 55, 60},
                              {40, 43, 43, 47, 60, 75, 80},
                              {60, 63, 63, 67, 80, 95, 100}};
    frames_are(WL_PF_MP_APP_CULL_DRAW, TRUE, (Times){3, 4, 15, 0, NULL, 0}, 4,
               want, NULL);
}

/* ISECT (30 ms) starts with a frame's APP when it is free: frames 0 and
 * 2, not 1 and 3. */
static void test_isect(void **st)
{
    (void)st;
    const guint want[4][7] = {{0, 3, 3, 7, 7, 12, 20},
                              {20, 23, 23, 27, 27, 32, 40},
                              {40, 43, 43, 47, 47, 52, 60},
                              {60, 63, 63, 67, 67, 72, 80}};
    const guint isect[4] = {30, 0, 30, 0};
    frames_are(WL_PF_MP_APP_CULL_DRAW, FALSE, (Times){3, 4, 5, 30, NULL, 0}, 4,
               want, isect);
}

/* Stress feedback: after each DRAW, a load (DRAW time / T) outside
 * [low, high] moves the stress by gain x (load - (low + high) / 2),
 * clamped to [1, max_stress]; CULL takes the stress of its start. */
static double stress_of(Times t, double gain, double max, guint n, guint i)
{
    stress_params = (WlPfPipeParams){.stress = TRUE,
                                     .low = 0.4,
                                     .high = 0.6,
                                     .gain = gain,
                                     .max_stress = max};
    GArray *r = run(WL_PF_MP_APP_CULL_DRAW, FALSE, &t, n);
    double s = g_array_index(r, WlPfFrameRec, i).stress;
    g_array_free(r, TRUE);
    stress_params = (WlPfPipeParams){0};
    return s;
}

static void test_stress(void **st)
{
    (void)st;
    /* DRAW 15 ms: load 0.75, +0.25 a DRAW.  DRAWs end at 22, 45 and
     * 65 ms (each starts at the previous swap: 30, 50); CULLs start at
     * 3, 23, 43 and 63 ms */
    Times busy = {3, 4, 15, 0, NULL, 0};
    assert_true(stress_of(busy, 1, 8, 4, 0) == 1.0);
    assert_true(stress_of(busy, 1, 8, 4, 1) == 1.25);
    assert_true(stress_of(busy, 1, 8, 4, 2) == 1.25);
    assert_true(stress_of(busy, 1, 8, 4, 3) == 1.5);
    assert_true(stress_of(busy, 2, 8, 4, 3) == 2.0);
    assert_true(stress_of(busy, 1, 1.4, 4, 3) == 1.4); /* clamped */
    /* DRAW 5 ms: load 0.25, below the band: stress stays at its floor */
    assert_true(stress_of((Times){3, 4, 5, 0, NULL, 0}, 1, 8, 4, 3) == 1.0);
    /* DRAW 10 and 12 ms: loads 0.5 and 0.6, inside the band */
    assert_true(stress_of((Times){3, 4, 10, 0, NULL, 0}, 1, 8, 4, 3) == 1.0);
    assert_true(stress_of((Times){3, 4, 12, 0, NULL, 0}, 1, 8, 4, 3) == 1.0);
    /* DRAW 8 ms: load 0.4, on the band's edge: inside */
    assert_true(stress_of((Times){3, 4, 8, 0, NULL, 0}, 1, 8, 4, 3) == 1.0);
    /* and from a raised stress: frame 0's DRAW (15 ms) raises it to 1.25
     * for frame 1's CULL (23 ms); frame 1's DRAW (30 to 38 ms) at load
     * 0.4 leaves it there for frame 2's CULL (43 ms); frame 2's at 0.6
     * (the upper edge) too */
    const guint seq[4] = {15, 8, 12, 8};
    Times varied = {3, 4, 0, 0, seq, 0};
    assert_true(stress_of(varied, 1, 8, 4, 1) == 1.25);
    assert_true(stress_of(varied, 1, 8, 4, 2) == 1.25);
    assert_true(stress_of(varied, 1, 8, 4, 3) == 1.25);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_three_processes),
        cmocka_unit_test(test_two_processes),
        cmocka_unit_test(test_cull_waits_for_draw),
        cmocka_unit_test(test_one_process),
        cmocka_unit_test(test_one_process_at_boundary),
        cmocka_unit_test(test_recorded_waits),
        cmocka_unit_test(test_locked),
        cmocka_unit_test(test_isect),
        cmocka_unit_test(test_stress),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
