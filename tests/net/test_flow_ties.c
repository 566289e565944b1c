/* test_flow_ties.c — the flow transport's invariant "flows with equal end
 * times complete in send order" (sim/net/flow.c): messages of one size on
 * disjoint crossbar paths, sent at one instant in a scrambled source
 * order, end at the same picosecond and are delivered in the order they
 * were sent, as the analytic transport delivers them; and a flow whose
 * bytes are done to rounding when a recompute comes ends then, not at its
 * predicted end. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/net/net.h"
#include "tests/support.h"

typedef struct {
    uint32_t src[8];
    SimTime at[8];
    guint n;
} Order;

static void arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Order *o = ctx;
    o->src[o->n] = d->src;
    o->at[o->n++] = d->arrived;
}

static void check(NetFidelity fid)
{
    static const uint32_t from[] = {5, 2, 7, 0, 3, 6, 1, 4};
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_crossbar_new(8);
    NetParams p = {0};
    p.bandwidth = 1e6;
    p.startup = 3 * SIM_US;
    p.switching = NET_SW_CUT_THROUGH; /* the flow transport */
    NetNet *net = net_new(eng, t, &p, fid);
    Order o = {0};
    for (guint i = 0; i < 8; i++) /* i -> i ^ 1 would share links; +4 not */
        net_send(net, from[i], (from[i] + 4) % 8, 1000, NULL, arrived, &o);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(o.n, 8);
    for (guint i = 0; i < 8; i++) {
        assert_int_equal(o.src[i], from[i]);
        assert_int_equal(o.at[i], 3 * SIM_US + 1000 * SIM_US);
    }
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
}

/* A tie between a flow that began early and one sent before it that
 * began later (more hops, so a longer latency): on a line of 8 nodes at
 * 2^20 B/s (256 B take 5^12 ps exactly), 0 -> 3 (3 hops, 1024 B) is sent
 * first and 5 -> 6 (1 hop, 1536 B) second; with 244140625 ps a hop both
 * end at 3 us + 1708984375 ps, and the first sent is delivered first. */
static void check_late_starter(NetFidelity fid)
{
    SimEngine *eng = sim_engine_new(1);
    uint32_t ext[1] = {8};
    NetTopo *t = net_mesh_new(1, ext, FALSE);
    NetParams p = {0};
    p.bandwidth = 1048576;
    p.startup = 3 * SIM_US;
    p.switching = NET_SW_CUT_THROUGH; /* the flow transport */
    p.per_hop = 244140625;
    NetNet *net = net_new(eng, t, &p, fid);
    Order o = {0};
    net_send(net, 0, 3, 1024, NULL, arrived, &o);
    net_send(net, 5, 6, 1536, NULL, arrived, &o);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(o.n, 2);
    assert_int_equal(o.src[0], 0);
    assert_int_equal(o.src[1], 5);
    assert_int_equal(o.at[0], 3 * SIM_US + 1708984375);
    assert_int_equal(o.at[1], 3 * SIM_US + 1708984375);
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
}

/* A recompute 1 ps before a flow's predicted end: the flow is brought up
 * to now at its rate, which in doubles can overshoot its bytes (1e9 + 3
 * B at 3000 B/s: 3000 x (T - 1) x 1e-12 exceeds them by 1.2e-7 B), and
 * it must then end at once, at the recompute, not carry a remainder
 * onto the shared link.  One link (0 -> 1), no start-up. */
static void send_second(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    net_send(ctx, 0, 1, 1000, NULL, arrived, arg);
}

static void check_recompute_at_end(void)
{
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_hypercube_new(1);
    NetParams p = {0};
    p.bandwidth = 3000;
    p.switching = NET_SW_CUT_THROUGH; /* the flow transport */
    NetNet *net = net_new(eng, t, &p, NET_FLOW);
    Order o = {0};
    SimTime end = net_ideal_time(net, 0, 1, 1000000003);
    assert_true(sim_schedule_at(eng, end - 1, send_second, net, &o));
    net_send(net, 0, 1, 1000000003, NULL, arrived, &o);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(o.n, 2);
    assert_int_equal(o.at[0], end - 1); /* done at the recompute */
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
}

static void test_equal_ends_in_send_order(void **state)
{
    (void)state;
    check(NET_FLOW);
    check(NET_ANALYTIC);
    check_late_starter(NET_FLOW);
    check_late_starter(NET_ANALYTIC);
    check_recompute_at_end();
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_equal_ends_in_send_order),
    };
    return cmocka_run_group_tests_name("flow_ties", tests, NULL, NULL);
}
