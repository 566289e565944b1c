/* test_net_mutants.c — claims of sim/net that mutation testing (make
 * mutate, docs/testing.md) found unchecked: the flow rung builds a
 * circuit without per-hop events (circuit.c), and an empty message
 * travels as one empty packet (packet.c), in the analytic time. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/net/net.h"

static void arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    *(SimTime *)ctx = d->arrived;
}

static NetParams params(NetSwitching sw)
{
    NetParams p = {0};
    p.bandwidth = 1e6; /* 1 us a byte */
    p.channels = 1;
    p.startup = 50 * SIM_US;
    p.per_hop = 7 * SIM_US;
    p.packet_bytes = 100;
    p.switching = sw;
    return p;
}

/* One message src -> dst on a 5-cube; its events and arrival time. */
static uint64_t lone(NetSwitching sw, NetFidelity f, uint32_t dst,
                     uint64_t bytes, SimTime *at)
{
    NetTopo *t = net_hypercube_new(5);
    NetParams p = params(sw);
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, f);
    net_send(net, 0, dst, bytes, NULL, arrived, at);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    uint64_t ev = sim_engine_events(eng);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
    return ev;
}

/* Flow: the circuit is set up without an event a hop, so a 1-hop and a
 * 5-hop message take as many events; the packet rung moves its header
 * hop by hop and takes more events for more hops.  Both take the
 * analytic time. */
static void test_circuit_flow_no_hop_events(void **state)
{
    (void)state;
    SimTime a1 = 0, a5 = 0, p1 = 0, p5 = 0;
    uint64_t f1 = lone(NET_SW_CIRCUIT, NET_FLOW, 1, 300, &a1);
    uint64_t f5 = lone(NET_SW_CIRCUIT, NET_FLOW, 31, 300, &a5);
    uint64_t k1 = lone(NET_SW_CIRCUIT, NET_PACKET, 1, 300, &p1);
    uint64_t k5 = lone(NET_SW_CIRCUIT, NET_PACKET, 31, 300, &p5);
    assert_int_equal(f1, f5);
    assert_true(k5 > k1);
    assert_true(f5 < k5);
    assert_int_equal(a1, 50 * SIM_US + 7 * SIM_US + 300 * SIM_US);
    assert_int_equal(a5, 50 * SIM_US + 5 * 7 * SIM_US + 300 * SIM_US);
    assert_int_equal(p1, a1);
    assert_int_equal(p5, a5);
}

/* An empty message is one empty packet: as many events as a 1-byte one
 * (also one packet), and the analytic time startup + hops x per_hop. */
static void test_empty_message_one_packet(void **state)
{
    (void)state;
    for (int sw = NET_SW_CIRCUIT; sw <= NET_SW_RING_SLOTS; sw++) {
        if (sw == NET_SW_STORE_FORWARD)
            continue;
        SimTime t0 = 0, t1 = 0, ta = 0;
        uint64_t e0 = lone((NetSwitching)sw, NET_PACKET, 31, 0, &t0);
        uint64_t e1 = lone((NetSwitching)sw, NET_PACKET, 31, 1, &t1);
        lone((NetSwitching)sw, NET_ANALYTIC, 31, 0, &ta);
        if (e0 != e1)
            fail_msg("switching %d: %" G_GUINT64_FORMAT " events empty, %"
                     G_GUINT64_FORMAT " with 1 byte", sw, e0, e1);
        assert_int_equal(t0, ta);
        assert_int_equal(t1, ta + SIM_US);
    }
}

static void count_arrival(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    (void)d;
    (*(guint *)ctx)++;
}

/* Flow fidelity with hundreds of flows coupled through shared links:
 * every message of three overlapping shifts on a 7-cube arrives, the
 * last later than a lone message would. */
static void test_flow_many_links(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(7);
    NetParams p = params(NET_SW_CUT_THROUGH);
    p.per_hop = 0; /* every flow starts at once, after the startup */
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_FLOW);
    guint got = 0;
    for (uint32_t i = 0; i < 128; i++)
        for (uint32_t k = 1; k <= 5; k += 2)
            net_send(net, i, (i + k) % 128, 1000, NULL, count_arrival, &got);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(got, 3 * 128);
    /* shared links: the last arrival is later than a lone message's */
    assert_true(sim_now(eng) > 50 * SIM_US + 1000 * SIM_US);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_circuit_flow_no_hop_events),
        cmocka_unit_test(test_empty_message_one_packet),
        cmocka_unit_test(test_flow_many_links),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
