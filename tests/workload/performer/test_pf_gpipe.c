/* test_pf_gpipe.c — the graphics pipe as a process fed through a bounded
 * FIFO (pf_gpipe.c) under Performer's frame pipeline (issue 36, point 1):
 *   - DRAW of frame n issues while the pipe still renders frame n - 1,
 *     and DRAW's CPU is busy for its own work only;
 *   - each of CPU, bus and pipe sets the frame time when it is the
 *     slowest, and raising one that does not bind leaves it unchanged;
 *   - a full FIFO blocks DRAW's CPU; a FIFO that holds whole frames never
 *     does.
 * Stage times are fixed (ms); the bus is 100 MB/s with no latency, so
 * 1 MB of commands is 10 ms of bus.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/machine/machine.h"
#include "sim/workload/performer/pf_pipeline.h"

typedef struct {
    double cpu, bus, pipe; /* ms per frame */
    uint64_t depth;        /* FIFO bytes */
} Work;

static SimTime ms_t(double ms)
{
    return (SimTime)(ms * (double)SIM_MS + 0.5);
}

static SimTime s_app(void *ctx, guint n)
{
    (void)ctx;
    (void)n;
    return SIM_MS / 2;
}
static SimTime s_cull(void *ctx, guint n, double stress)
{
    (void)ctx;
    (void)n;
    (void)stress;
    return SIM_MS / 2;
}
static SimTime s_draw(void *ctx, guint n)
{
    (void)n;
    return ms_t(((Work *)ctx)->cpu);
}
static void s_work(void *ctx, guint n, WlPfDrawWork *w)
{
    (void)n;
    const Work *x = ctx;
    *w = (WlPfDrawWork){.cpu = ms_t(x->cpu),
                        .bytes = (uint64_t)(x->bus * 1e5 + 0.5),
                        .pipe = ms_t(x->pipe)};
}

#define FRAMES 24

typedef struct {
    GArray *recs;
    SimTime end[FRAMES]; /* the pipe's end of each frame */
    SimTime cpu_busy, pipe_busy;
    WlPfGpipeStats st;
} Run;

/* Three processes, floating DRAW, V = 1 us (swaps barely wait): the
 * frame time is the pipeline's own. */
static Run run(Work w)
{
    SimEngine *eng = sim_engine_new(1);
    GError *err = NULL;
    MachMachine *m = mach_new_from_model(eng, "sgi-onyx", "analytic", &err);
    if (!m)
        fail_msg("%s", err->message);
    MachProc *procs[3];
    for (guint i = 0; i < 3; i++)
        procs[i] = mach_proc(m, "cpu", i);
    MachProc *pipe = mach_proc(m, "pipe", 0);
    MachShmem bus;
    mach_shmem_init_with(&bus, 1e8, 0);
    WlPfGpipe *gp = wl_pf_gpipe_new(eng, procs[2], pipe, &bus,
                                    w.depth ? w.depth : 64 * 1024, 8 * 1024);
    WlPfStageFns f = {.app = s_app, .cull = s_cull, .draw = s_draw,
                      .draw_work = s_work};
    WlPfPipeParams p = {.mode = WL_PF_MP_APP_CULL_DRAW,
                        .video = SIM_MS / 1000,
                        .per_frame = 1,
                        .frames = FRAMES,
                        .gpipe = gp};
    Run r = {.recs = g_array_new(FALSE, TRUE, sizeof(WlPfFrameRec))};
    assert_true(wl_pf_pipe_run(eng, procs, &p, &f, &w, r.recs, SIM_TIME_MAX,
                               &err));
    assert_int_equal(r.recs->len, FRAMES);
    for (guint n = 0; n < FRAMES; n++)
        r.end[n] = wl_pf_gpipe_frame_end(gp, n);
    r.cpu_busy = mach_proc_busy(procs[2]);
    r.pipe_busy = mach_proc_busy(pipe);
    r.st = *wl_pf_gpipe_stats(gp);
    wl_pf_gpipe_free(gp);
    mach_free(m);
    sim_engine_free(eng);
    return r;
}

/* Mean ms between the pipe's frame ends, after 8 frames of warm-up. */
static double interval(Work w)
{
    Run r = run(w);
    g_array_free(r.recs, TRUE);
    return (double)(r.end[FRAMES - 1] - r.end[7]) / (FRAMES - 8) / SIM_MS;
}

static void test_draw_overlaps_previous_pipe(void **st)
{
    (void)st;
    Run r = run((Work){.cpu = 6, .bus = 2, .pipe = 9});
    guint overlapped = 0;
    for (guint n = 1; n < FRAMES; n++) {
        const WlPfFrameRec *x = &g_array_index(r.recs, WlPfFrameRec, n);
        overlapped += x->draw_start < r.end[n - 1];
        assert_true(x->swap >= r.end[n]); /* swapped after its commands */
    }
    assert_true(overlapped >= FRAMES - 4);
    /* busy only while it works: 6 ms a frame, not the pipe's 9 */
    assert_int_equal(r.cpu_busy, FRAMES * ms_t(6));
    assert_int_equal(r.pipe_busy, FRAMES * ms_t(9));
    assert_true(r.st.cpu_blocked > 0);
    g_array_free(r.recs, TRUE);
}

/* Raising a stage that binds moves the frame to its time; raising one
 * that does not leaves the frame where the binding one holds it. */
static void test_each_bottleneck_binds_alone(void **st)
{
    (void)st;
    const Work base = {.cpu = 4, .bus = 4, .pipe = 4};
    double t0 = interval(base);
    assert_true(t0 < 4.5);
    for (int k = 0; k < 3; k++) {
        Work hi = base, hi2 = base, other = base;
        double *stage[3] = {&hi.cpu, &hi.bus, &hi.pipe};
        double *stage2[3] = {&hi2.cpu, &hi2.bus, &hi2.pipe};
        *stage[k] = 10;
        *stage2[k] = 12;
        double t1 = interval(hi), t2 = interval(hi2);
        assert_true(fabs(t1 - 10) < 0.3); /* binds: the frame is its time */
        assert_true(fabs(t2 - 12) < 0.3);
        /* the others raised from 4 to 8 ms while stage k binds at 10 */
        double *others[3] = {&other.cpu, &other.bus, &other.pipe};
        for (int j = 0; j < 3; j++)
            *others[j] = j == k ? 10 : 8;
        assert_true(fabs(interval(other) - t1) < 0.3);
    }
}

static void test_full_fifo_blocks_draw(void **st)
{
    (void)st;
    Run a = run((Work){.cpu = 2, .bus = 1, .pipe = 10});
    assert_true(a.st.cpu_blocked > ms_t(5) * (FRAMES - 4));
    assert_true(a.st.max_used <= 64 * 1024);
    Run b = run((Work){.cpu = 2, .bus = 1, .pipe = 10, .depth = 64 << 20});
    assert_int_equal(b.st.cpu_blocked, 0);
    g_array_free(a.recs, TRUE);
    g_array_free(b.recs, TRUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_draw_overlaps_previous_pipe),
        cmocka_unit_test(test_each_bottleneck_binds_alone),
        cmocka_unit_test(test_full_fifo_blocks_draw),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
