/* test_roundtrip_tokenring.c — the token ring, which has no machine
 * model, records its own actions (`tick` counts of compute and
 * serialisation, the token as messages, frame marks); replayed on
 * models/ring-8.yaml (the ring's link model as a machine) it gives
 * the run's frame times, elapsed time, every node's busy time per phase
 * and the volume exactly, jitter included; a slower link or dearer
 * tick shows the comparison can fail. */
#include "sim/app/replay/rpl_replay.h"
#include "tests/app/replay/rpl_fixture.h"
#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

/* The first difference between a and b (frames, elapsed, volume, each
 * node's name and busy time per phase), or NULL when they agree. */
static char *differs(const SimResult *a, const SimResult *b)
{
    if (a->frame_times->len != b->frame_times->len ||
        a->elapsed != b->elapsed || a->comm_bytes != b->comm_bytes ||
        a->comm_messages != b->comm_messages ||
        a->nodes->len != b->nodes->len || a->phases->len != b->phases->len)
        return g_strdup("frame count, elapsed time, volume or sizes");
    for (guint f = 0; f < a->frame_times->len; f++)
        if (g_array_index(a->frame_times, SimTime, f) !=
            g_array_index(b->frame_times, SimTime, f))
            return g_strdup_printf("frame %u", f);
    for (guint i = 0; i < a->nodes->len; i++) {
        const SimNodeResult *x = a->nodes->pdata[i], *y = b->nodes->pdata[i];
        if (strcmp(x->name, y->name))
            return g_strdup_printf("node %u's name", i);
        for (guint k = 0; k < a->phases->len; k++)
            if (sim_busy_phase(&x->busy, k) != sim_busy_phase(&y->busy, k))
                return g_strdup_printf("%s busy in phase %u", x->name, k);
    }
    return NULL;
}

static RplFixture fx;   /* the recorded run and its trace */
static SimResult *orig; /* the run without a recorder */

/* Runs configs/tokenring.yaml with and without a recorder (the figures
 * must agree) and writes the trace. */
static int record(void **s)
{
    (void)s;
    GError *e = NULL;
    CfgRun *r = cfg_run_load("configs/tokenring.yaml", NULL, &e);
    g_assert_no_error(e);
    CfgRunOpts plain = {.quiet = TRUE};
    orig = cfg_run_exec(r, &plain, &e);
    g_assert_no_error(e);
    cfg_run_free(r);
    rpl_fixture_record(&fx, "configs/tokenring.yaml", NULL, "tr.pgt");
    assert_null(differs(orig, fx.res));
    assert_int_equal(fx.actions, 3 * 8 * 20); /* c, c and s per visit */
    assert_int_equal(fx.unplaced, 0);
    return 0;
}

static int cleanup(void **s)
{
    (void)s;
    sim_result_free(orig);
    rpl_fixture_clear(&fx);
    return 0;
}

static SimResult *replay_with(const char *set)
{
    const char *sets[] = {set, NULL};
    RplReplayOpts o = {.trace = fx.path, .machine = "ring-8", .sets = sets};
    GError *e = NULL;
    SimResult *res = rpl_replay(&o, &e);
    g_assert_no_error(e);
    return res;
}

static void test_round_trip(void **s)
{
    (void)s;
    SimResult *rep = replay_with(NULL);
    char *d = differs(orig, rep);
    if (d)
        fail_msg("the replay differs from the run: %s", d);
    assert_int_equal(rep->frame_times->len, 20);
    assert_int_equal(rep->comm_messages, 160);
    sim_result_free(rep);
}

/* A slower link moves the frames; a dearer tick moves the busy times
 * (by exactly 1 ps per recorded picosecond: twice the run's busy). */
static void test_other_ring_differs(void **s)
{
    (void)s;
    SimResult *slow = replay_with("machine.network.bandwidth=10 MB/s");
    char *d = differs(orig, slow);
    assert_non_null(d);
    g_free(d);
    assert_true(slow->elapsed > orig->elapsed);
    assert_int_equal(slow->comm_bytes, orig->comm_bytes);
    sim_result_free(slow);
    SimResult *dear = replay_with("machine.nodes.node.costs.tick=2 ps");
    for (guint i = 0; i < orig->nodes->len; i++) {
        const SimNodeResult *x = orig->nodes->pdata[i];
        const SimNodeResult *y = dear->nodes->pdata[i];
        assert_true(x->busy.total > 0);
        assert_int_equal(y->busy.total, 2 * x->busy.total);
    }
    sim_result_free(dear);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_other_ring_differs),
    };
    return cmocka_run_group_tests(tests, record, cleanup);
}
