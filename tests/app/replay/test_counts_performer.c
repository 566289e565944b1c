/* test_counts_performer.c — Performer's DRAW is recorded as named counts
 * on overlapping resources (a `c` line with `|` terms: the CPU's counts,
 * the pipe's counts, the bus stream) and a replay prices it as the
 * longest term on the target: change the pipe's triangle cost and DRAW
 * moves by exactly the recorded triangles x the change when the pipe is
 * the bottleneck, and not at all when the CPU or the bus is.  Every
 * DRAW cost the test uses is set on the command line (--set), so the
 * expected busy time is worked out here from the trace's counts.  A
 * reader test shows `|` terms need a version-3 trace. */
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

/* One DRAW line of the trace: the CPU's counts and the terms. */
typedef struct {
    uint64_t geosets, states, matrices, vertices; /* the CPU's */
    uint64_t tris, pipe_states;                   /* the pipe's term */
    uint64_t bytes;                               /* the bus term */
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

static Draw draw_of(const RplItem *it)
{
    Draw d = {0};
    d.geosets = count_of(it->op, it->count, it->n_ops, "draw_geoset");
    d.states = count_of(it->op, it->count, it->n_ops, "draw_state");
    d.matrices = count_of(it->op, it->count, it->n_ops, "draw_matrix");
    d.vertices = count_of(it->op, it->count, it->n_ops, "draw_vertex");
    for (guint k = 0; k < it->n_terms; k++) {
        const RplTerm *t = &it->term[k];
        if (t->bus)
            d.bytes = t->bytes;
        else {
            d.tris = count_of(t->op, t->count, t->n_ops, "triangle");
            d.pipe_states = count_of(t->op, t->count, t->n_ops, "state");
        }
    }
    return d;
}

/* The DRAW lines of the trace (phase "draw", with `|` terms). */
static GArray *draws(void)
{
    GError *e = NULL;
    RplReader *r = rpl_reader_open(fx.path, &e);
    g_assert_no_error(e);
    const RplHeader *h = rpl_reader_header(r);
    unsigned ph = G_MAXUINT;
    for (guint i = 0; i < h->phases->len; i++)
        if (!strcmp(h->phases->pdata[i], "draw"))
            ph = i;
    GArray *a = g_array_new(FALSE, FALSE, sizeof(Draw));
    RplItem it;
    while (rpl_reader_next(r, &it, &e))
        if (it.type == RPL_COMPUTE && it.phase == ph) {
            assert_int_equal(it.n_terms, 2); /* pipe counts, bus stream */
            Draw d = draw_of(&it);
            g_array_append_val(a, d);
        }
    g_assert_no_error(e);
    rpl_reader_free(r);
    assert_true(a->len >= 30); /* 40 frames, the first few still empty */
    return a;
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

static SimTime bus_time(const Draw *d, const Costs *c)
{
    return sim_time_for_bytes((double)d->bytes, c->bandwidth) + c->startup;
}

/* Which term is the longest: 0 cpu, 1 pipe, 2 bus (strictly). */
static int bottleneck(const Draw *d, const Costs *c)
{
    SimTime t[3] = {cpu_time(d, c), pipe_time(d, c), bus_time(d, c)};
    int b = t[1] > t[0] ? 1 : 0;
    b = t[2] > t[b] ? 2 : b;
    for (int i = 0; i < 3; i++)
        assert_true(i == b || t[i] < t[b]);
    return b;
}

/* The test's own sum over DRAW lines of the longest term. */
static SimTime expected_draw(const GArray *a, const Costs *c)
{
    SimTime sum = 0;
    for (guint i = 0; i < a->len; i++) {
        const Draw *d = &g_array_index(a, Draw, i);
        sum += MAX(cpu_time(d, c), MAX(pipe_time(d, c), bus_time(d, c)));
    }
    return sum;
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

/* Every DRAW line has resource b as its bottleneck under both costs. */
static void all_bound_by(const GArray *a, const Costs *x, const Costs *y, int b)
{
    for (guint i = 0; i < a->len; i++) {
        const Draw *d = &g_array_index(a, Draw, i);
        if (d->tris == 0)
            continue; /* an empty frame: no term dominates */
        assert_int_equal(bottleneck(d, x), b);
        assert_int_equal(bottleneck(d, y), b);
    }
}

static uint64_t total_tris(const GArray *a)
{
    uint64_t n = 0;
    for (guint i = 0; i < a->len; i++)
        n += g_array_index(a, Draw, i).tris;
    return n;
}

/* The pipe is the bottleneck (the model's costs: 1 us a triangle, 4 us a
 * state change, against 0.96 us of bus and ~0.5 us of CPU a triangle):
 * 1 us -> 1.5 us a triangle moves DRAW by the triangles x 0.5 us. */
static void test_pipe_bound(void **s)
{
    (void)s;
    GArray *a = draws();
    Costs slow = base;
    slow.triangle = 1500 * SIM_NS;
    all_bound_by(a, &base, &slow, 1);
    SimTime d0 = replay_busy(&base, "draw"), d1 = replay_busy(&slow, "draw");
    assert_int_equal(d0, expected_draw(a, &base));
    assert_int_equal(d1, expected_draw(a, &slow));
    assert_true(total_tris(a) > 0);
    assert_int_equal(d1 - d0, total_tris(a) * 500 * SIM_NS);
    g_array_free(a, TRUE);
}

/* The CPU is the bottleneck (2 us a vertex, 6 us a triangle): the same
 * change of the pipe's cost leaves DRAW unchanged, while the pipe's own
 * work moves by the triangles x 0.5 us. */
static void test_cpu_bound(void **s)
{
    (void)s;
    GArray *a = draws();
    Costs fast = base, slow;
    fast.vertex = 2 * SIM_US;
    slow = fast;
    slow.triangle = 1500 * SIM_NS;
    all_bound_by(a, &fast, &slow, 0);
    SimTime d0 = replay_busy(&fast, "draw"), d1 = replay_busy(&slow, "draw");
    assert_int_equal(d0, expected_draw(a, &fast));
    assert_int_equal(d1, d0);
    SimTime p0 = replay_busy(&fast, "pipe"), p1 = replay_busy(&slow, "pipe");
    assert_int_equal(p1 - p0, total_tris(a) * 500 * SIM_NS);
    g_array_free(a, TRUE);
}

/* The bus is the bottleneck at 10 MB/s (9.6 us a triangle): the pipe's
 * cost does not move DRAW; halving the bandwidth moves it by each
 * stream's extra transfer time. */
static void test_bus_bound(void **s)
{
    (void)s;
    GArray *a = draws();
    Costs bus = base, pipe, half;
    bus.bandwidth = 10e6;
    pipe = bus;
    pipe.triangle = 1500 * SIM_NS;
    half = bus;
    half.bandwidth = 5e6;
    all_bound_by(a, &bus, &pipe, 2);
    all_bound_by(a, &bus, &half, 2);
    SimTime d0 = replay_busy(&bus, "draw");
    assert_int_equal(d0, expected_draw(a, &bus));
    assert_int_equal(replay_busy(&pipe, "draw"), d0);
    SimTime extra = 0;
    for (guint i = 0; i < a->len; i++)
        extra += bus_time(&g_array_index(a, Draw, i), &half) -
                 bus_time(&g_array_index(a, Draw, i), &bus);
    assert_true(extra > 0);
    assert_int_equal(replay_busy(&half, "draw") - d0, extra);
    g_array_free(a, TRUE);
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
        cmocka_unit_test(test_pipe_bound),
        cmocka_unit_test(test_cpu_bound),
        cmocka_unit_test(test_bus_bound),
        cmocka_unit_test(test_terms_syntax),
    };
    return cmocka_run_group_tests(tests, record, cleanup);
}
