/* test_simgrid.c — importing SimGrid time-independent traces: a small
 * hand-written trace (tests/data/traces/simgrid-4ranks.txt) replays with
 * the message count, bytes and busy times worked out by hand below;
 * a receive waits for its message; bad traces give located errors. */
#include "sim/app/replay/rpl_replay.h"
#include "sim/core/error.h"
#include <glib/gstdio.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static const char *flop50[] = {"machine.nodes.node.costs.flop=50 ns", NULL};

static SimResult *play(const char *path, const char *fid, GError **e)
{
    RplReplayOpts o = {.trace = path,
                       .machine = "ipsc2",
                       .nodes = 4,
                       .fidelity = fid,
                       .sets = flop50};
    return rpl_replay(&o, e);
}

static SimTime busy_of(const SimResult *r, const char *name)
{
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = r->nodes->pdata[i];
        if (!strcmp(n->name, name))
            return n->busy.total;
    }
    return 0;
}

/* Messages: send 1 + isend 1 + barrier (a 0-byte allreduce: 2 steps x
 * 4) 8 + bcast 3 + reduce (a bcast tree) 3 + allreduce 8 + alltoall
 * 4 x 3 = 36.  Bytes: 4096 + 8192 + 0 + 3 x 1024 + 3 x 1024 + 8 x 2048
 * + 12 x 512 = 40960.  Busy of rank 1: (2e6 + 1e4 + 5e3) flops x 50 ns
 * = 100.75 ms. */
static void test_hand_trace(void **s)
{
    (void)s;
    GError *e = NULL;
    SimResult *r = play("tests/data/traces/simgrid-4ranks.txt", NULL, &e);
    g_assert_no_error(e);
    assert_int_equal(r->comm_messages, 36);
    assert_int_equal(r->comm_bytes, 40960);
    assert_int_equal(busy_of(r, "node1"), 100750 * SIM_US);
    assert_int_equal(busy_of(r, "node3"), 25750 * SIM_US); /* 515e3 flops */
    assert_true(r->elapsed > busy_of(r, "node1")); /* + the collectives */
    assert_int_equal(r->frame_times->len, 1);
    sim_result_free(r);
}

static char *put(const char *dir, const char *text)
{
    char *p = g_build_filename(dir, "t.txt", NULL);
    assert_true(g_file_set_contents(p, text, -1, NULL));
    return p;
}

/* p1's receive waits for p0's 1 ms of work and the message: the run
 * lasts longer than p0's work, and longer still with a slower link. */
static void test_recv_waits(void **s)
{
    (void)s;
    char *dir = g_dir_make_tmp("pgsim-sg-XXXXXX", NULL);
    char *p = put(dir, "0 compute 20000\n0 send 1 100000\n1 recv 0 100000\n"
                       "2 compute 1\n3 compute 1\n");
    GError *e = NULL;
    SimResult *r = play(p, "analytic", &e);
    g_assert_no_error(e);
    /* 100 kB over the iPSC/2's 2.8 MB/s alone takes 35.7 ms */
    assert_true(r->elapsed > SIM_MS + 35 * SIM_MS);
    assert_int_equal(busy_of(r, "node1"), 0);
    sim_result_free(r);
    g_remove(p);
    g_free(p);
    g_rmdir(dir);
    g_free(dir);
}

typedef struct {
    const char *text, *want;
} Bad;

static const Bad bads[] = {
    {"0 compute 5\n0 jump 3\n", "t.txt:2:3: found 'jump'"},
    {"0 send 1\n", "t.txt:1:9: found the end of the line"},
    {"0 compute -4\n", "t.txt:1:11: found '-4'"},
    {"0 recv 1 0 64\n1 compute 5\n", "found rank 0 blocked"},
    {"0 barrier\n1 bcast 5\n2 barrier\n3 barrier\n",
     "t.txt:2:2: found a different collective"},
    {"0 barrier\n1 barrier\n", "t.txt:1:1: found a collective over 2 ranks"},
};

static void test_errors(void **s)
{
    (void)s;
    char *dir = g_dir_make_tmp("pgsim-sg-XXXXXX", NULL);
    for (guint i = 0; i < G_N_ELEMENTS(bads); i++) {
        char *p = put(dir, bads[i].text);
        GError *e = NULL;
        SimResult *r = play(p, NULL, &e);
        if (r || !e || !strstr(e->message, bads[i].want))
            fail_msg("case %u: got '%s'", i, e ? e->message : "no error");
        g_clear_error(&e);
        sim_result_free(r);
        g_remove(p);
        g_free(p);
    }
    g_rmdir(dir);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hand_trace),
        cmocka_unit_test(test_recv_waits),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
