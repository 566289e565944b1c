/* test_pf_multipipe.c — the performer workload's process models on the
 * town (configs/performer-procs.yaml: 8 CPUs, two pipes; issue 36,
 * point 2):
 *   - two pipes, each culling and drawing its half of the view, raise a
 *     pipe-bound frame rate by more than 1.4 and at most 2, and leave an
 *     APP-bound one where it was;
 *   - no process model runs faster than one process times the CPUs it
 *     uses (no speed-up without a processor to give it);
 *   - the stages' shared-arena traffic waits for the bus only when
 *     processes run at once;
 *   - the update list's hand-off at the boundary adds a frame of latency
 *     to a three-process run.
 * Runs of 60 frames, means over frames 4..59.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/core/cfg.h"
#include "tests/support.h"

static double metric(const SimResult *r, const char *name)
{
    double v = NAN;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}

/* configs/performer-procs.yaml with the overrides (NULL-terminated);
 * the metrics asked for, in `names` order. */
static void run(const char *const *sets, const char *const *names,
                double *out)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_file("configs/performer-procs.yaml", &err);
    if (!root)
        fail_msg("%s", err->message);
    SupportRun o = {.fidelity = "analytic", .frames = 60, .overrides = sets};
    SimResult *r = support_run_tree(root, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    for (guint i = 0; names[i]; i++)
        out[i] = metric(r, names[i]);
    sim_result_free(r);
}

static const char *const rate[] = {"frame_rate_hz", "processes", NULL};

/* Frame boundaries every 1/600 s, floating DRAW: the rate is the
 * slowest stage's, not a divisor of 30 Hz. */
static double rate_of(const char *mode, const char *pipes, const char *app)
{
    const char *sets[] = {mode, pipes, app, "workload.phase=floating",
                          "workload.video_rate=600",
                          "workload.frame_rate=600", NULL};
    double v[2];
    run(sets, rate, v);
    return v[0];
}

static void test_two_pipes_when_the_pipe_binds(void **st)
{
    (void)st;
    const char *m = "workload.mode=app_cull_draw";
    double one = rate_of(m, "workload.pipes=1", "workload.app_work=1 ms");
    double two = rate_of(m, "workload.pipes=2", "workload.app_work=1 ms");
    if (!(two / one > 1.4 && two / one <= 2))
        fail_msg("pipe-bound: %.2f -> %.2f Hz", one, two);
    /* APP of 60 ms binds: a second pipe changes nothing */
    double a1 = rate_of(m, "workload.pipes=1", "workload.app_work=60 ms");
    double a2 = rate_of(m, "workload.pipes=2", "workload.app_work=60 ms");
    if (fabs(a2 / a1 - 1) > 0.01)
        fail_msg("APP-bound: %.2f -> %.2f Hz", a1, a2);
}

static void test_no_speedup_beyond_processors(void **st)
{
    (void)st;
    const char *modes[] = {"workload.mode=appculldraw",
                           "workload.mode=appcull_draw",
                           "workload.mode=app_culldraw",
                           "workload.mode=app_cull_draw"};
    const char *pipes[] = {"workload.pipes=1", "workload.pipes=2"};
    double base = 0;
    for (guint i = 0; i < 4; i++)
        for (guint k = 0; k < 2; k++) {
            const char *sets[] = {modes[i], pipes[k],
                                  "workload.phase=floating",
                                  "workload.fork_isect=false", NULL};
            double v[2];
            run(sets, rate, v);
            if (!base)
                base = v[0]; /* one process, one pipe */
            if (v[0] > base * v[1] + 1e-9)
                fail_msg("%s %s: %.2f Hz on %.0f CPUs, one CPU %.2f Hz",
                         modes[i], pipes[k], v[0], v[1], base);
        }
}

static void test_arena_waits_only_in_parallel(void **st)
{
    (void)st;
    static const char *const wait[] = {"arena_wait_ms", "arena_util_pct",
                                       NULL};
    const char *one[] = {"workload.mode=appculldraw",
                         "workload.fork_isect=false", NULL};
    const char *three[] = {"workload.mode=app_cull_draw", NULL};
    double a[2], b[2];
    run(one, wait, a);
    run(three, wait, b);
    assert_true(a[0] == 0 && a[1] > 0);
    assert_true(b[0] > 0);
}

static void test_update_list_adds_a_frame(void **st)
{
    (void)st;
    static const char *const lat[] = {"latency_ms", "frame_rate_hz", NULL};
    /* two pipes: not pipe-bound, the rate stays at 30 Hz */
    const char *with[] = {"workload.pipes=2", NULL};
    const char *without[] = {"workload.pipes=2", "workload.update_list=false",
                             NULL};
    double a[2], b[2];
    run(with, lat, a);
    run(without, lat, b);
    assert_true(fabs(a[1] - 30) < 1e-6 && fabs(b[1] - 30) < 1e-6);
    if (fabs(a[0] - b[0] - 1000.0 / 30) > 1e-6)
        fail_msg("latency %.3f ms with the update list, %.3f without", a[0],
                 b[0]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_pipes_when_the_pipe_binds),
        cmocka_unit_test(test_no_speedup_beyond_processors),
        cmocka_unit_test(test_arena_waits_only_in_parallel),
        cmocka_unit_test(test_update_list_adds_a_frame),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
