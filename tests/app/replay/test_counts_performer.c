/* test_counts_performer.c — Performer's DRAW runs through the graphics
 * pipe process (pf_gpipe.h) and is recorded as named counts per FIFO
 * chunk: `c` lines of the CPU's counts in phase "draw" and of the pipe's
 * in phase "pipe", with the bus transfers between them.  A replay prices
 * each on the target: DRAW's CPU is busy exactly its counts x the CPU
 * costs, however slow the pipe or the bus, and the pipe moves by exactly
 * the recorded triangles x a change of its triangle cost.  Every DRAW
 * cost the test uses is set on the command line (--set), so the
 * expected busy time is worked out here from the trace's counts.  A
 * reader test shows `|` terms (overlapped work, sim/machine/overlap.h)
 * need a version-3 trace. */
#include "sim/app/replay/rpl_format.h"
#include "sim/app/replay/rpl_replay.h"
#include "tests/app/replay/rpl_fixture.h"
#include <glib/gstdio.h>
#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

/* The trace's DRAW counts, summed over its chunks. */
typedef struct {
    uint64_t geosets, states, matrices, vertices; /* the CPU's */
    uint64_t tris, pipe_states;                   /* the pipe's */
    guint cpu_lines, pipe_lines;
} Draw;

/* DRAW's costs on the target, in ps (set with --set), and the bus. */
typedef struct {
    SimTime geoset, state, matrix, vertex; /* cpu */
    SimTime triangle, pipe_state;          /* pipe */
    double bandwidth;                      /* bytes/s */
    SimTime startup;
} Costs;

static const Costs base = {4 * SIM_US, 3 * SIM_US, 1500 * SIM_NS, 150 * SIM_NS,
                           1 * SIM_US, 4 * SIM_US, 100e6,         2 * SIM_US};

static RplFixture fx; /* the trace, recorded once */

static int record(void **s)
{
    (void)s;
    const char *sets[] = {"run.frames=40", NULL};
    rpl_fixture_record(&fx, "configs/performer-town.yaml", sets, "pf.pgt");
    return 0;
}

static int cleanup(void **s)
{
    (void)s;
    rpl_fixture_clear(&fx);
    return 0;
}

static uint64_t count_of(const char *const *op, const uint64_t *count, guint n,
                         const char *name)
{
    for (guint i = 0; i < n; i++)
        if (!strcmp(op[i], name))
            return count[i];
    return 0;
}

/* The sums of the trace's DRAW (phase "draw") and pipe (phase "pipe")
 * lines, which carry no `|` terms. */
static Draw draws(void)
{
    GError *e = NULL;
    RplReader *r = rpl_reader_open(fx.path, &e);
    g_assert_no_error(e);
    const RplHeader *h = rpl_reader_header(r);
    unsigned ph = G_MAXUINT, pp = G_MAXUINT;
    for (guint i = 0; i < h->phases->len; i++) {
        if (!strcmp(h->phases->pdata[i], "draw"))
            ph = i;
        if (!strcmp(h->phases->pdata[i], "pipe"))
            pp = i;
    }
    Draw d = {0};
    RplItem it;
    while (rpl_reader_next(r, &it, &e)) {
        if (it.type != RPL_COMPUTE || (it.phase != ph && it.phase != pp))
            continue;
        assert_int_equal(it.n_terms, 0);
        const char *const *op = (const char *const *)it.op;
        if (it.phase == ph) {
            d.geosets += count_of(op, it.count, it.n_ops, "draw_geoset");
            d.states += count_of(op, it.count, it.n_ops, "draw_state");
            d.matrices += count_of(op, it.count, it.n_ops, "draw_matrix");
            d.vertices += count_of(op, it.count, it.n_ops, "draw_vertex");
            d.cpu_lines++;
        } else {
            d.tris += count_of(op, it.count, it.n_ops, "triangle");
            d.pipe_states += count_of(op, it.count, it.n_ops, "state");
            d.pipe_lines++;
        }
    }
    g_assert_no_error(e);
    rpl_reader_free(r);
    /* 40 frames of many chunks each, one pipe line per CPU line */
    assert_true(d.cpu_lines > 40 && d.cpu_lines == d.pipe_lines);
    assert_true(d.tris > 0 && d.vertices == 3 * d.tris);
    return d;
}

static SimTime cpu_time(const Draw *d, const Costs *c)
{
    return d->geosets * c->geoset + d->states * c->state +
           d->matrices * c->matrix + d->vertices * c->vertex;
}

static SimTime pipe_time(const Draw *d, const Costs *c)
{
    return d->tris * c->triangle + d->pipe_states * c->pipe_state;
}

/* Replays the trace on the Onyx with the costs c; the busy time of
 * phase `phase` summed over all processors. */
static SimTime replay_busy(const Costs *c, const char *phase)
{
    char *s[9] = {
        g_strdup_printf("machine.nodes.cpu.costs.draw_geoset=%" PRIu64 " ps",
                        c->geoset),
        g_strdup_printf("machine.nodes.cpu.costs.draw_state=%" PRIu64 " ps",
                        c->state),
        g_strdup_printf("machine.nodes.cpu.costs.draw_matrix=%" PRIu64 " ps",
                        c->matrix),
        g_strdup_printf("machine.nodes.cpu.costs.draw_vertex=%" PRIu64 " ps",
                        c->vertex),
        g_strdup_printf("machine.nodes.pipe.costs.triangle=%" PRIu64 " ps",
                        c->triangle),
        g_strdup_printf("machine.nodes.pipe.costs.state=%" PRIu64 " ps",
                        c->pipe_state),
        g_strdup_printf("machine.network.bandwidth=%.0f B/s", c->bandwidth),
        g_strdup_printf("machine.network.startup=%" PRIu64 " ps", c->startup),
        NULL};
    RplReplayOpts o = {.trace = fx.path,
                       .machine = "sgi-onyx",
                       .sets = (const char *const *)s};
    GError *e = NULL;
    SimResult *res = rpl_replay(&o, &e);
    g_assert_no_error(e);
    guint ph = G_MAXUINT;
    for (guint i = 0; i < res->phases->len; i++)
        if (!strcmp(res->phases->pdata[i], phase))
            ph = i;
    assert_int_not_equal(ph, G_MAXUINT);
    SimTime busy = 0;
    for (guint i = 0; i < res->nodes->len; i++)
        busy += sim_busy_phase(
            &((const SimNodeResult *)res->nodes->pdata[i])->busy, ph);
    sim_result_free(res);
    for (int i = 0; s[i]; i++)
        g_free(s[i]);
    return busy;
}

/* The pipe binds (the model's costs: 1 us a triangle, 4 us a state
 * change, against 0.96 us of bus and ~0.5 us of CPU a triangle): 1 us ->
 * 1.5 us a triangle moves the pipe by the triangles x 0.5 us and leaves
 * DRAW's CPU, which is busy only for its own counts, where it was. */
static void test_pipe_cost_moves_pipe_only(void **s)
{
    (void)s;
    Draw d = draws();
    Costs slow = base;
    slow.triangle = 1500 * SIM_NS;
    SimTime d0 = replay_busy(&base, "draw"), d1 = replay_busy(&slow, "draw");
    assert_int_equal(d0, cpu_time(&d, &base));
    assert_int_equal(d1, d0);
    SimTime p0 = replay_busy(&base, "pipe"), p1 = replay_busy(&slow, "pipe");
    assert_int_equal(p0, pipe_time(&d, &base));
    assert_int_equal(p1 - p0, d.tris * 500 * SIM_NS);
}

/* The CPU's costs (2 us a vertex) move DRAW's CPU by the recorded
 * vertices, and neither a slow pipe nor a slow bus (10 MB/s) adds to
 * it: waiting on the FIFO is not work. */
static void test_cpu_cost_moves_draw(void **s)
{
    (void)s;
    Draw d = draws();
    Costs fast = base, bus = base;
    fast.vertex = 2 * SIM_US;
    bus.bandwidth = 10e6;
    assert_int_equal(replay_busy(&fast, "draw"), cpu_time(&d, &fast));
    assert_int_equal(replay_busy(&bus, "draw"), cpu_time(&d, &bus));
    assert_int_equal(replay_busy(&bus, "pipe"), pipe_time(&d, &bus));
}

/* Reads text as a trace; the error message, or NULL when it reads. */
static char *read_error(const char *text)
{
    char *tmp = g_build_filename(fx.dir, "bad.pgt", NULL);
    g_file_set_contents(tmp, text, -1, NULL);
    GError *e = NULL;
    RplReader *r = rpl_reader_open(tmp, &e);
    RplItem it;
    while (r && rpl_reader_next(r, &it, &e))
        ;
    rpl_reader_free(r);
    g_remove(tmp);
    g_free(tmp);
    char *msg = e ? g_strdup(e->message) : NULL;
    g_clear_error(&e);
    return msg;
}

#define HEAD(v) "pgsim-trace " v "\nprocs 3\nat 0\n"

/* `|` terms read in a version-3 trace and are located errors elsewhere
 * or when malformed. */
static void test_terms_syntax(void **s)
{
    (void)s;
    assert_null(read_error(HEAD("3") "c 0 0 a=1 | @2 b=3 c=4 | b 2 99 +\n"
                                     "on 0\nw 1 0 5\n"));
    static const struct {
        const char *text, *where, *what;
    } bad[] = {
        {HEAD("2") "c 0 0 a=1 | @2 b=3\n", ":4:11:", "pgsim-trace 3"},
        {HEAD("3") "c 0 0 a=1 | @3 b=3\n", ":4:13:", "@PROC"},
        {HEAD("3") "c 0 0 a=1 | x b=3\n", ":4:13:", "after '|'"},
        {HEAD("3") "c 0 0 a=1 | @1\n", ":4:15:", "OP=COUNT"},
        {HEAD("3") "c 0 0 a=1 | b 1\n", ":4:16:", "byte count"},
        {HEAD("3") "c 0 0 a=1 | @1 b=1 | @1 b=1 | @1 b=1 | @1 b=1\n",
         ":4:38:", "at most 3"},
    };
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        char *msg = read_error(bad[i].text);
        if (!msg || !strstr(msg, bad[i].where) || !strstr(msg, bad[i].what))
            fail_msg("case %u: got '%s', expected %s ... %s", i,
                     msg ? msg : "(no error)", bad[i].where, bad[i].what);
        g_free(msg);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pipe_cost_moves_pipe_only),
        cmocka_unit_test(test_cpu_cost_moves_draw),
        cmocka_unit_test(test_terms_syntax),
    };
    return cmocka_run_group_tests(tests, record, cleanup);
}
