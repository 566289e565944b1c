/* test_whatif.c — what-ifs that are true (issue 34, point 4).
 *
 * For every workload that records a trace (shipped configs, made small):
 * record the run once on its own machine, then change one thing of the
 * machine — link bandwidth over 0.1x .. 100x, a latency x10, a clock x2
 * — and run the config with that change and replay the trace with the
 * same change.  Each frame's time must agree within TOL_REL, or the
 * pair (workload, quantity) is in `known` with the mechanism the trace
 * cannot carry (docs/traces.md, "What-ifs"); a known pair must still
 * differ somewhere, so the table cannot outlive its reason.
 *
 * And a sweep of link bandwidth never makes a frame slower as links get
 * faster, in the run or in the replay.
 *
 * The bandwidth of each model is given here at 1x; the 1x run with it
 * set explicitly must equal the run without it (so this table follows
 * the models).  Fails without the pixel-merging joins: the pair merge's
 * replay at 10x was 1.077 s against the run's 0.989 s and not monotone.
 */
#include "sim/app/replay/rpl_replay.h"
#include "tests/app/replay/rpl_fixture.h"
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

/* Frames agree when |run - replay| <= TOL_REL x run (rounding only). */
#define TOL_REL 1e-9

enum { Q_BANDWIDTH, Q_LATENCY, Q_CLOCK, N_Q };
static const char *const q_names[N_Q] = {"bandwidth", "latency", "clock"};

/* A machine's what-if keys: its link bandwidth at 1x (up to three
 * levels, in `unit`), under run_key in the run and replay_key in the
 * replay; a latency and a clock change as whole overrides (NULL: the
 * machine has none that its runs use). */
typedef struct {
    const char *model;
    const char *run_key, *replay_key;
    double bw[3];
    guint levels;
    const char *unit;
    const char *latency_run, *latency_replay;
    const char *clock;
} Machine;

static const Machine machines[] = {
    {"ipsc2", "machine.network.bandwidth", NULL, {2.8}, 1, "MB/s",
     "machine.network.startup_long=7000 us", NULL,
     "machine.nodes.node.clock=32 MHz"},
    {"pixel-planes-5", "machine.network.bandwidth", NULL, {80}, 1, "MB/s",
     "machine.network.startup=50 us", NULL, "machine.nodes.gp.clock=80 MHz"},
    {"cluster-ib", "machine.network.level_bandwidth", NULL, {12.5, 12.5}, 2,
     "GB/s", "machine.network.startup=10 us", NULL,
     "machine.nodes.node.clock=4.5 GHz"},
    /* the CM-200's router is its dpscan: constants, not the network */
    {"cm200", "machine.network.router_link_bandwidth", NULL, {1.25}, 1,
     "MB/s", NULL, NULL, "machine.nodes.array.clock=20 MHz"},
    {"cm5", "machine.network.level_bandwidth", NULL, {20, 10, 5}, 3, "MB/s",
     "machine.network.startup=100 us", NULL,
     "machine.nodes.node.clock=64 MHz"},
    {"origin2000", "machine.network.bandwidth", NULL, {9600}, 1, "MB/s",
     "machine.network.startup=3150 ns", NULL,
     "machine.nodes.cpu.clock=390 MHz"},
    {"sgi-onyx", "machine.network.bandwidth", NULL, {100}, 1, "MB/s",
     "machine.network.startup=20 us", NULL,
     "machine.nodes.cpu.clock=300 MHz"},
    /* the token ring's link is the workload's own; ring-8 restates it */
    {"ring-8", "workload.link.bandwidth", "machine.network.bandwidth", {20},
     1, "MB/s", "workload.link.latency=50 us", "machine.network.startup=50 us",
     NULL},
};

typedef struct {
    const char *name, *config, *model;
    const char *sets[8];
} Case;

static const Case cases[] = {
    {"pixelmerge pair", "configs/pixelmerge-2pot.yaml", "ipsc2",
     {"workload.resolution=200", NULL}},
    {"pixelmerge pair hbp", "configs/pixelmerge-2pot.yaml", "ipsc2",
     {"workload.resolution=200", "workload.balance=hbp", NULL}},
    {"pixelmerge aapc", "configs/pixelmerge-2pot.yaml", "ipsc2",
     {"workload.resolution=200", "workload.scheme=aapc", NULL}},
    {"pixelmerge zbuf_exc", "configs/pixelmerge-2pot.yaml", "ipsc2",
     {"workload.resolution=200", "workload.scheme=zbuf_exc", NULL}},
    {"pphigs", "configs/pphigs-flock.yaml", "pixel-planes-5",
     {"run.frames=2", NULL}},
    {"sortfirst", "configs/sortfirst-vehicle.yaml", "cluster-ib",
     {"run.frames=2", "scene.triangles=8000", "scene.structures=60", NULL}},
    {"dpscan cm200", "configs/dpscan-cm200.yaml", "cm200",
     {"scene.grid=16", "workload.width=256", "workload.height=256", NULL}},
    {"dpscan cm5", "configs/dpscan-cm200.yaml", "cm5",
     {"machine.model=cm5", "workload.processors=32", "workload.wire=formula",
      "scene.grid=16", "workload.width=256", "workload.height=256", NULL}},
    {"argus", "configs/argus-march.yaml", "origin2000",
     {"workload.processors=8", NULL}},
    {"pn", "configs/pn-onyx.yaml", "sgi-onyx", {NULL}},
    {"performer", "configs/performer-town.yaml", "sgi-onyx",
     {"run.frames=12", NULL}},
    {"tokenring", "configs/tokenring.yaml", "ring-8", {"run.frames=5", NULL}},
};

/* What a trace cannot carry, by workload and quantity (docs/traces.md,
 * "What-ifs"). */
typedef struct {
    const char *name;
    int q;
    const char *mechanism;
} Known;

static const Known known[] = {
    {"pphigs", Q_BANDWIDTH,
     "a join of many completions: a renderer finishes its regions when "
     "every GP's stream has ended (rend_check_gp); the trace names only the "
     "arrival that came last in the recording"},
    {"argus", Q_BANDWIDTH,
     "shared-memory traffic not recorded: Argus's command blocks through "
     "the memory (mach_shmem_transfer) are `at` groups at recorded times"},
    {"argus", Q_LATENCY, "the same: its memory traffic's startup"},
    {"performer", Q_BANDWIDTH,
     "DRAW's bus term priced on an idle memory: on a bus slow enough that "
     "the previous frame's stream has not ended, the run queues and the "
     "refresh-locked frames fall differently"},
    {"tokenring", Q_BANDWIDTH,
     "serialisation recorded as the sender's work: the ring charges it to "
     "the sending node as `tick` counts at the recorded bandwidth, so a "
     "replay's link bandwidth moves the token's message but not that work"},
};

static const double mults[] = {0.1, 0.5, 1, 2, 10, 100};

static const Known *known_for(const char *name, int q)
{
    for (guint i = 0; i < G_N_ELEMENTS(known); i++)
        if (!strcmp(known[i].name, name) && known[i].q == q)
            return &known[i];
    return NULL;
}

static const Machine *machine_of(const char *model)
{
    for (guint i = 0; i < G_N_ELEMENTS(machines); i++)
        if (!strcmp(machines[i].model, model))
            return &machines[i];
    fail_msg("no what-if keys for model %s", model);
    return NULL;
}

/* KEY=VALUE for the machine's bandwidth times x (a list for levels). */
static char *bw_set(const Machine *m, const char *key, double x)
{
    GString *s = g_string_new(key);
    g_string_append_c(s, '=');
    if (m->levels > 1)
        g_string_append_c(s, '[');
    for (guint i = 0; i < m->levels; i++)
        g_string_append_printf(s, "%s%.6g %s", i ? ", " : "", m->bw[i] * x,
                               m->unit);
    if (m->levels > 1)
        g_string_append_c(s, ']');
    return g_string_free(s, FALSE);
}

/* The case's sets plus `extra` (may be NULL), NULL-ended (g_free). */
static const char **with(const Case *c, const char *extra)
{
    const char **v = g_new0(const char *, 10);
    guint n = 0;
    for (; c->sets[n]; n++)
        v[n] = c->sets[n];
    v[n] = extra;
    return v;
}

static GArray *run_frames(const Case *c, const char *extra)
{
    const char **sets = with(c, extra);
    GError *e = NULL;
    CfgRun *r = cfg_run_load(c->config, sets, &e);
    g_assert_no_error(e);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = cfg_run_exec(r, &o, &e);
    g_assert_no_error(e);
    GArray *f = g_array_copy(res->frame_times);
    sim_result_free(res);
    cfg_run_free(r);
    g_free(sets);
    return f;
}

static GArray *replay_frames(const char *trace, const char *model,
                             const char *set)
{
    const char *sets[] = {set, NULL};
    RplReplayOpts o = {.trace = trace, .machine = model, .sets = sets};
    GError *e = NULL;
    SimResult *res = rpl_replay(&o, &e);
    g_assert_no_error(e);
    GArray *f = g_array_copy(res->frame_times);
    sim_result_free(res);
    return f;
}

static SimTime frame(const GArray *f, guint i)
{
    return g_array_index(f, SimTime, i);
}

/* TRUE when every frame agrees within TOL_REL. */
static gboolean agree(const GArray *run, const GArray *rep)
{
    if (run->len != rep->len)
        return FALSE;
    for (guint i = 0; i < run->len; i++) {
        double a = (double)frame(run, i), b = (double)frame(rep, i);
        if (fabs(a - b) > TOL_REL * a)
            return FALSE;
    }
    return TRUE;
}

/* Compares run and replay under one change; returns whether they
 * differed, failing the test when that is not a known mechanism.  The
 * frames go to *run_out and *rep_out when given (g_array_free). */
static gboolean check_change(const Case *c, const char *trace, int q,
                             const char *run_set, const char *replay_set,
                             GArray **run_out, GArray **rep_out)
{
    GArray *run = run_frames(c, run_set);
    GArray *rep = replay_frames(trace, c->model, replay_set);
    gboolean same = agree(run, rep);
    if (!same && !known_for(c->name, q))
        fail_msg("%s, %s: run %.9f s, replay %.9f s (frame 0) differ and no "
                 "mechanism is named",
                 c->name, run_set, sim_time_to_s(frame(run, 0)),
                 rep->len ? sim_time_to_s(frame(rep, 0)) : -1.0);
    if (run_out) {
        *run_out = run;
        *rep_out = rep;
    } else {
        g_array_free(run, TRUE);
        g_array_free(rep, TRUE);
    }
    return !same;
}

/* Each frame of `next` (faster links) no slower than of `prev`. */
static void no_slower(const Case *c, const char *what, double x,
                      const GArray *prev, const GArray *next)
{
    assert_int_equal(prev->len, next->len);
    for (guint i = 0; i < prev->len; i++)
        if (frame(next, i) > frame(prev, i))
            fail_msg("%s (%s): frame %u takes %.9f s at %gx bandwidth, "
                     "%.9f s at the slower step before",
                     c->name, what, i, sim_time_to_s(frame(next, i)), x,
                     sim_time_to_s(frame(prev, i)));
}

/* The bandwidth sweep: run and replay agree at each point (or differ by
 * a known mechanism), and neither slows a frame as links get faster.
 * *differed counts the points that differed. */
static void sweep(const Case *c, const Machine *m, const char *trace,
                  guint *differed)
{
    GArray *prev_run = NULL, *prev_rep = NULL;
    for (guint k = 0; k < G_N_ELEMENTS(mults); k++) {
        char *rs = bw_set(m, m->run_key, mults[k]);
        char *ps = bw_set(m, m->replay_key ? m->replay_key : m->run_key,
                          mults[k]);
        GArray *run, *rep;
        *differed += check_change(c, trace, Q_BANDWIDTH, rs, ps, &run, &rep);
        if (mults[k] == 1) { /* the table's 1x is the model's own */
            GArray *plain = run_frames(c, NULL);
            if (!agree(plain, run))
                fail_msg("%s: %s is not the model's own bandwidth", c->name,
                         rs);
            g_array_free(plain, TRUE);
        }
        if (prev_run) {
            no_slower(c, "run", mults[k], prev_run, run);
            no_slower(c, "replay", mults[k], prev_rep, rep);
            g_array_free(prev_run, TRUE);
            g_array_free(prev_rep, TRUE);
        }
        prev_run = run;
        prev_rep = rep;
        g_free(rs);
        g_free(ps);
    }
    g_array_free(prev_run, TRUE);
    g_array_free(prev_rep, TRUE);
}

static void whatif_case(const Case *c)
{
    const Machine *m = machine_of(c->model);
    RplFixture f;
    rpl_fixture_record(&f, c->config, c->sets, "t.pgt");
    guint differed[N_Q] = {0};
    sweep(c, m, f.path, &differed[Q_BANDWIDTH]);
    if (m->latency_run)
        differed[Q_LATENCY] += check_change(
            c, f.path, Q_LATENCY, m->latency_run,
            m->latency_replay ? m->latency_replay : m->latency_run, NULL,
            NULL);
    if (m->clock)
        differed[Q_CLOCK] += check_change(c, f.path, Q_CLOCK, m->clock,
                                          m->clock, NULL, NULL);
    for (int q = 0; q < N_Q; q++)
        if (known_for(c->name, q) && !differed[q])
            fail_msg("%s: %s changes now replay as they run; the mechanism "
                     "'%s' no longer shows: remove it from `known` and "
                     "docs/traces.md",
                     c->name, q_names[q], known_for(c->name, q)->mechanism);
    rpl_fixture_clear(&f);
}

static void test_whatif(void **state)
{
    const Case *c = *state;
    whatif_case(c);
}

int main(void)
{
    struct CMUnitTest t[G_N_ELEMENTS(cases)];
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++)
        t[i] = (struct CMUnitTest){cases[i].name, test_whatif, NULL, NULL,
                                   (void *)&cases[i]};
    return cmocka_run_group_tests_name("whatif", t, NULL, NULL);
}
