/* test_net_mutants.c — claims of sim/net that mutation testing (make
 * mutate, docs/testing.md) found unchecked: the flow rung builds a
 * circuit without per-hop events (circuit.c), and an empty message
 * travels as one empty packet (packet.c), in the analytic time; the
 * parts of net_tracked_bytes; a control network slower than 1 B/s; the
 * packet rung's trace of holds and waits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/net/collective.h"
#include "sim/net/net.h"
#include "sim/core/trace.h"
#include "tests/support.h"

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

/* `copies` messages 0 -> dst of `bytes` on a 5-cube, all sent at 0,
 * under trace tr (or none); the run's events and the last arrival. */
static uint64_t run_msgs(NetSwitching sw, NetFidelity f, uint32_t dst,
                         uint64_t bytes, int copies, SimTrace *tr, SimTime *at)
{
    NetTopo *t = net_hypercube_new(5);
    NetParams p = params(sw);
    SimEngine *eng = sim_engine_new(1);
    sim_engine_set_trace(eng, tr);
    NetNet *net = net_new(eng, t, &p, f);
    for (int i = 0; i < copies; i++)
        net_send(net, 0, dst, bytes, NULL, arrived, at);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    uint64_t ev = sim_engine_events(eng);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
    return ev;
}

/* One message 0 -> dst on a 5-cube; its events and arrival time. */
static uint64_t lone(NetSwitching sw, NetFidelity f, uint32_t dst,
                     uint64_t bytes, SimTime *at)
{
    return run_msgs(sw, f, dst, bytes, 1, NULL, at);
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

/* net_tracked_bytes of a fresh net: the net's own record, its
 * topology's state (state_bytes) and the route scratch (max_hops link
 * ids), plus the 16-slot link table.  Two nets that differ only in
 * state_bytes differ by exactly that; a 4-cube's scratch holds one more
 * id than a 3-cube's. */
static size_t fresh_tracked(const NetTopo *t)
{
    NetParams p = params(NET_SW_CUT_THROUGH);
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
    size_t b = net_tracked_bytes(net);
    net_free(net);
    sim_engine_free(eng);
    return b;
}

static void test_tracked_bytes_parts(void **state)
{
    (void)state;
    NetTopo *c3 = net_hypercube_new(3), *c4 = net_hypercube_new(4);
    NetTopo big = *c3;
    big.state_bytes += 1000;
    size_t b3 = fresh_tracked(c3), b4 = fresh_tracked(c4);
    assert_int_equal(fresh_tracked(&big) - b3, 1000);
    assert_int_equal(b4 - b3, sizeof(NetLinkId));
    /* at least the parameters, the state, 3 ids and 16 two-word slots */
    assert_true(b3 >= sizeof(NetParams) + c3->state_bytes +
                          3 * sizeof(NetLinkId) + 16 * 2 * sizeof(void *));
    net_topo_free(c3);
    net_topo_free(c4);
}

static void ignore_arrival(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    (void)d;
    (void)ctx;
}

/* Tracked bytes when the link table grows: a message i -> i ^ 1 on a
 * 5-cube crosses one link no message crossed before, so each adds one
 * link record d.  The 16-slot table (load <= 1/2) doubles at the 9th
 * link and again at the 17th: those steps add d plus 16 and 32 slots,
 * all others d alone (the idle level, messages delivered). */
static void test_tracked_bytes_table_growth(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(5);
    NetParams p = params(NET_SW_CUT_THROUGH);
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
    size_t idle[21];
    idle[0] = net_tracked_bytes(net);
    for (uint32_t k = 1; k <= 20; k++) {
        net_send(net, k - 1, (k - 1) ^ 1, 10, NULL, ignore_arrival, NULL);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        idle[k] = net_tracked_bytes(net);
    }
    size_t d = idle[1] - idle[0];
    assert_true(d >= sizeof(GQueue) && d < 4096); /* a link has a queue */
    for (uint32_t k = 1; k <= 20; k++)
        if (k != 9 && k != 17)
            assert_int_equal(idle[k] - idle[k - 1], d);
    assert_true(idle[9] > idle[8] + d && idle[17] > idle[16] + d);
    size_t slots16 = idle[9] - idle[8] - d;
    assert_true(slots16 >= 16 * 2 * sizeof(void *));
    assert_int_equal(idle[17] - idle[16] - d, 2 * slots16);
    net_free(net);
    net_free(NULL); /* frees nothing */
    sim_engine_free(eng);
    net_topo_free(t);
}

static void coll_done(NetNet *net, void *ctx)
{
    *(SimTime *)ctx = sim_now(net_engine(net));
}

/* A control network of 1 B/s (any bandwidth above zero counts): a
 * 2-byte broadcast takes the latency plus 2 s; 0.5 B/s doubles it. */
static void test_control_network_slow(void **state)
{
    (void)state;
    NetTopo *t = net_fattree_new(4, 2);
    const double bw[] = {1.0, 0.5};
    for (int i = 0; i < 2; i++) {
        NetParams p = params(NET_SW_CUT_THROUGH);
        p.ctrl_latency = 3 * SIM_US;
        p.ctrl_bandwidth = bw[i];
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, NET_FLOW);
        SimTime at = 0;
        net_broadcast(net, 1, 2, coll_done, &at);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(at, 3 * SIM_US + (SimTime)(i + 1) * 2 * SIM_S);
        net_free(net);
        sim_engine_free(eng);
    }
    net_topo_free(t);
}

/* What a trace saw of the packet rung: holds (count, bytes) and waits. */
typedef struct {
    guint holds, waits;
    uint64_t held_bytes;
    SimTime waited;
} Seen;

static void seen_hold(SimTrace *tr, uint64_t link, const char *name,
                      uint64_t bytes, SimTime start, SimTime end)
{
    (void)link;
    (void)name;
    Seen *s = tr->state;
    assert_true(end > start);
    s->holds++;
    s->held_bytes += bytes;
}

static void seen_wait(SimTrace *tr, uint64_t link, const char *name,
                      SimTime from, SimTime to)
{
    (void)link;
    (void)name;
    Seen *s = tr->state;
    s->waits++;
    s->waited += to - from;
}

static const SimTraceOps seen_ops = {.hold = seen_hold, .wait = seen_wait};

/* Cut-through packets of 100 bytes: `copies` messages of 250 bytes (100,
 * 100, 50) from 0 to dst, all sent at time 0. */
static Seen traced(uint32_t dst, int copies)
{
    Seen s = {0};
    SimTrace tr = {&seen_ops, &s};
    SimTime at = 0;
    run_msgs(NET_SW_CUT_THROUGH, NET_PACKET, dst, 250, copies, &tr, &at);
    return s;
}

/* A lone message's head never waits (a free link is not a wait, even of
 * zero length); each packet holds each link once.  A second message on
 * the same one-hop path waits once, for the first's 250 bytes (250 us). */
static void test_packet_trace_waits(void **state)
{
    (void)state;
    Seen lone5 = traced(31, 1), two = traced(1, 2);
    assert_int_equal(lone5.waits, 0);
    assert_int_equal(lone5.holds, 3 * 5);
    assert_int_equal(lone5.held_bytes, 250 * 5);
    assert_int_equal(two.waits, 1);
    assert_int_equal(two.waited, 250 * SIM_US);
    assert_int_equal(two.holds, 2 * 3);
    assert_int_equal(two.held_bytes, 2 * 250);
}

/* Flow: the last byte.  Two flows 0 -> 1 share one 1 B/us link from
 * 10 + 1 = 11 us at 0.5 B/us each; the 100-byte one ends at 11 + 200 =
 * 211 us with exactly 1 byte of the 101-byte one left, which then moves
 * at 1 B/us and ends at 212 us. */
static void last_byte_arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    ((SimTime *)ctx)[d->bytes == 101] = d->arrived;
}

static void test_flow_last_byte(void **state)
{
    (void)state;
    NetParams p = params(NET_SW_CUT_THROUGH);
    p.startup = 10 * SIM_US;
    p.per_hop = 1 * SIM_US;
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_ring_new(4);
    NetNet *net = net_new(eng, t, &p, NET_FLOW);
    SimTime at[2] = {0, 0};
    net_send(net, 0, 1, 100, NULL, last_byte_arrived, at);
    net_send(net, 0, 1, 101, NULL, last_byte_arrived, at);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(at[0], 211 * SIM_US);
    assert_int_equal(at[1], 212 * SIM_US);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_circuit_flow_no_hop_events),
        cmocka_unit_test(test_empty_message_one_packet),
        cmocka_unit_test(test_flow_many_links),
        cmocka_unit_test(test_tracked_bytes_parts),
        cmocka_unit_test(test_tracked_bytes_table_growth),
        cmocka_unit_test(test_control_network_slow),
        cmocka_unit_test(test_packet_trace_waits),
        cmocka_unit_test(test_flow_last_byte),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
