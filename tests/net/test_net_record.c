/* test_net_record.c — what a trace and `pgsim run --record` hear from the
 * network (tests/core/rec_log.h logs every call): each send once, with
 * whether a handler waits for it; each delivery around its handler; the
 * flow and its per-link view at arrival (analytic); holds and waits as
 * circuits are taken and torn down, and as ring slots are claimed.  Times
 * are worked out by hand in each test's comment. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/net/net.h"
#include "tests/core/rec_log.h"
#include "tests/support.h"

static void noted(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    rec_log_note(ctx, "arrive %u->%u %" G_GUINT64_FORMAT " B @%" G_GUINT64_FORMAT
                      " hops=%u",
                 d->src, d->dst, d->bytes, d->arrived, d->hops);
}

/* 1 B/us, 10 us start-up, 1 us per hop, one channel. */
static NetParams params(NetSwitching sw)
{
    NetParams p = {0};
    p.bandwidth = 1e6;
    p.channels = 1;
    p.startup = 10 * SIM_US;
    p.per_hop = 1 * SIM_US;
    p.packet_bytes = 1000;
    p.switching = sw;
    return p;
}

typedef struct {
    uint32_t src, dst;
    uint64_t bytes;
    gboolean handled;
} Send;

/* Runs the sends (all at time 0) on topo t; the log's text (owned). */
static char *run(NetTopo *t, NetSwitching sw, NetFidelity f, gboolean trace,
                 gboolean record, const Send *s, guint n)
{
    RecLog log;
    rec_log_init(&log);
    NetParams p = params(sw);
    SimEngine *eng = sim_engine_new(1);
    if (trace)
        sim_engine_set_trace(eng, &log.tr);
    if (record)
        sim_engine_set_recorder(eng, &log.rec);
    NetNet *net = net_new(eng, t, &p, f);
    for (guint i = 0; i < n; i++)
        net_send(net, s[i].src, s[i].dst, s[i].bytes, NULL,
                 s[i].handled ? noted : NULL, &log);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(net_delivered(net), n);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
    return g_string_free(log.text, FALSE);
}

static void expect(char *got, const char *want)
{
    if (strcmp(got, want) != 0)
        fail_msg("got:\n%s\nwant:\n%s", got, want);
    g_free(got);
}

/* Analytic on a 4-ring: 0 -> 2 is 2 hops, 10 + 2 x 1 + 100 us = 112 us;
 * 1 -> 1 pays the start-up only (10 us) and has no handler (h=0), yet its
 * delivery is still recorded; the trace sees each flow at its arrival and
 * each link of the route (none for the message to itself). */
static void test_analytic_recorded(void **state)
{
    (void)state;
    const Send s[] = {{0, 2, 100, TRUE}, {1, 1, 5, FALSE}};
    expect(run(net_ring_new(4), NET_SW_CUT_THROUGH, NET_ANALYTIC, TRUE, TRUE,
               s, 2),
           "send @0 0->2 100 B h=1 -> 1\n"
           "send @0 1->1 5 B h=0 -> 2\n"
           "flow 1(-)->1(-) 5 B [0,10000000)\n"
           "begin 2 @10000000\n"
           "end 2\n"
           "flow 0(-)->2(-) 100 B [0,112000000)\n"
           "link L0 s0->s1 100 B [0,112000000)\n"
           "link L1 s1->s2 100 B [0,112000000)\n"
           "begin 1 @112000000\n"
           "arrive 0->2 100 B @112000000 hops=2\n"
           "end 1\n");
    /* neither trace nor recorder: only the handler speaks */
    expect(run(net_ring_new(4), NET_SW_CUT_THROUGH, NET_ANALYTIC, FALSE, FALSE,
               s, 2),
           "arrive 0->2 100 B @112000000 hops=2\n");
}

/* Circuits: B (1 -> 2, 50 B) takes s1->s2 at 10 + 1 = 11 us and holds it
 * to 11 + 50 = 61 us.  A (0 -> 2, 100 B) takes s0->s1 at 11 us, reaches
 * s1->s2 at 12 us and waits for it until 61 us, then holds both links to
 * 61 + 100 = 161 us; the holds are reported at the tear-down. */
static void test_circuit_traced(void **state)
{
    (void)state;
    const Send s[] = {{0, 2, 100, TRUE}, {1, 2, 50, TRUE}};
    expect(run(net_ring_new(4), NET_SW_CIRCUIT, NET_PACKET, TRUE, FALSE, s, 2),
           "hold L1 s1->s2 50 B [11000000,61000000)\n"
           "wait L1 s1->s2 [12000000,61000000)\n"
           "flow 1(-)->2(-) 50 B [0,61000000)\n"
           "link L1 s1->s2 50 B [0,61000000)\n"
           "arrive 1->2 50 B @61000000 hops=1\n"
           "hold L0 s0->s1 100 B [11000000,161000000)\n"
           "hold L1 s1->s2 100 B [61000000,161000000)\n"
           "flow 0(-)->2(-) 100 B [0,161000000)\n"
           "link L0 s0->s1 100 B [0,161000000)\n"
           "link L1 s1->s2 100 B [0,161000000)\n"
           "arrive 0->2 100 B @161000000 hops=2\n");
}

/* Ring slots: A claims its whole path at its start-up (10 us) until
 * 10 + 2 + 100 = 112 us; B asked for s1->s2 at 10 us, waits to 112 us,
 * then holds it to 112 + 1 + 50 = 163 us. */
static void test_ring_slots_traced(void **state)
{
    (void)state;
    const Send s[] = {{0, 2, 100, TRUE}, {1, 2, 50, TRUE}};
    expect(run(net_ring_new(4), NET_SW_RING_SLOTS, NET_PACKET, TRUE, FALSE, s,
               2),
           "hold L0 s0->s1 100 B [10000000,112000000)\n"
           "hold L1 s1->s2 100 B [10000000,112000000)\n"
           "flow 0(-)->2(-) 100 B [0,112000000)\n"
           "link L0 s0->s1 100 B [0,112000000)\n"
           "link L1 s1->s2 100 B [0,112000000)\n"
           "arrive 0->2 100 B @112000000 hops=2\n"
           "wait L1 s1->s2 [10000000,112000000)\n"
           "hold L1 s1->s2 50 B [112000000,163000000)\n"
           "flow 1(-)->2(-) 50 B [0,163000000)\n"
           "link L1 s1->s2 50 B [0,163000000)\n"
           "arrive 1->2 50 B @163000000 hops=1\n");
}

/* net_ideal_time: a message to itself pays the start-up only, whatever its
 * size (as the analytic transport delivers it); elsewhere the slowest link
 * of the route sets the rate (a fat tree's level-l link carries 2^l times
 * its per-node bandwidth). */
static void test_ideal_time(void **state)
{
    (void)state;
    NetParams p = params(NET_SW_CUT_THROUGH);
    p.level_bw[0] = 4e6; /* per node: leaf links 4 B/us */
    p.level_bw[1] = 1e6; /* per node: level-1 links 2 x 1 = 2 B/us */
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_fattree_new(4, 2);
    NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
    assert_int_equal(net_ideal_time(net, 2, 2, 1000), 10 * SIM_US);
    assert_int_equal(net_ideal_time(net, 2, 2, 0), 10 * SIM_US);
    /* 0 -> 1 under one switch: 2 leaf links at 4 B/us, 400 B = 100 us */
    assert_int_equal(net_ideal_time(net, 0, 1, 400),
                     10 * SIM_US + 2 * SIM_US + 100 * SIM_US);
    /* 0 -> 3 climbs a level: 4 links, the level-1 ones at 2 B/us */
    assert_int_equal(net_ideal_time(net, 0, 3, 400),
                     10 * SIM_US + 4 * SIM_US + 200 * SIM_US);
    assert_int_equal(net_ideal_time(net, 0, 3, 0), 14 * SIM_US);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_analytic_recorded),
        cmocka_unit_test(test_circuit_traced),
        cmocka_unit_test(test_ring_slots_traced),
        cmocka_unit_test(test_ideal_time),
    };
    return cmocka_run_group_tests_name("net_record", tests, NULL, NULL);
}
