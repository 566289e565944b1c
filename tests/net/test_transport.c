/* test_transport.c — the three transports against each other and against
 * hand-computed times. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "sim/net/net.h"
#include "tests/support.h"

typedef struct {
    SimTime at[64];
    uint32_t order[64];
    guint n;
} Log;

static void log_arrival(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Log *lg = ctx;
    g_assert(lg->n < 64);
    lg->at[lg->n] = d->arrived;
    lg->order[lg->n] = GPOINTER_TO_UINT(d->payload);
    lg->n++;
}

static NetParams params(SimTime startup, SimTime per_hop)
{
    NetParams p = {0};
    p.bandwidth = 1e6; /* 1 us per byte */
    p.channels = 1;
    p.startup = startup;
    p.per_hop = per_hop;
    p.packet_bytes = 100;
    p.switching = NET_SW_CIRCUIT;
    return p;
}

/* A test topology: a line of 3 nodes whose links differ in speed.  Link
 * 2i goes i -> i + 1, 2i + 1 the other way; link i's bandwidth is
 * base * (1 + 3 * (i / 2)), so a path from node 0 starts on its slowest
 * link and a path to node 0 ends on it. */
static uint32_t line_nodes(const void *st)
{
    (void)st;
    return 3;
}

static guint line_max_hops(const void *st)
{
    (void)st;
    return 2;
}

static guint line_route(const void *st, uint32_t src, uint32_t dst,
                        NetLinkId *out)
{
    (void)st;
    guint h = 0;
    for (uint32_t i = src; i != dst; i = src < dst ? i + 1 : i - 1)
        out[h++] = src < dst ? 2 * i : 2 * (i - 1) + 1;
    return h;
}

static void line_ends(const void *st, NetLinkId l, uint64_t *from,
                      uint64_t *to)
{
    (void)st;
    *from = l / 2 + (l & 1);
    *to = l / 2 + !(l & 1);
}

static void line_name(const void *st, NetLinkId l, char *buf, size_t n)
{
    (void)st;
    g_snprintf(buf, n, "l%u", (unsigned)l);
}

static double line_bw(const void *st, NetLinkId l, const NetParams *p)
{
    (void)st;
    return p->bandwidth * (double)(1 + 3 * (l / 2));
}

static const NetTopologyOps line_ops = {.name = "line",
                                        .nodes = line_nodes,
                                        .max_hops = line_max_hops,
                                        .route = line_route,
                                        .link_ends = line_ends,
                                        .link_name = line_name,
                                        .link_bw = line_bw,
                                        .free = g_free};

/* A message runs at its slowest link's bandwidth wherever on the path
 * that link lies: first (0 -> 2) or last (2 -> 0). */
static void test_bottleneck_first_or_last(void **state)
{
    (void)state;
    NetTopo *t = net_topo_wrap(&line_ops, g_new0(char, 1), 1);
    NetParams p = params(0, 0);
    for (int back = 0; back < 2; back++) {
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
        Log lg = {0};
        uint32_t a = back ? 2 : 0, b = back ? 0 : 2;
        assert_int_equal(net_ideal_time(net, a, b, 1000), 1000 * SIM_US);
        net_send(net, a, b, 1000, NULL, log_arrival, &lg);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(lg.n, 1);
        assert_int_equal(lg.at[0], 1000 * SIM_US); /* 1 MB/s, not 4 */
        net_free(net);
        sim_engine_free(eng);
    }
    net_topo_free(t);
}

static void test_lone_message_all_fidelities(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(5);
    NetParams p = params(50 * SIM_US, 7 * SIM_US);
    for (int sw = NET_SW_CIRCUIT; sw <= NET_SW_RING_SLOTS; sw++) {
        if (sw == NET_SW_STORE_FORWARD)
            continue;
        p.switching = (NetSwitching)sw;
        for (int f = NET_ANALYTIC; f <= NET_PACKET; f++) {
            SimEngine *eng = sim_engine_new(1);
            NetNet *net = net_new(eng, t, &p, (NetFidelity)f);
            Log lg = {0};
            net_send(net, 3, 28, 1200, NULL, log_arrival, &lg);
            assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
            assert_int_equal(lg.n, 1);
            /* 3 ^ 28 = 31: five hops */
            assert_int_equal(lg.at[0],
                             50 * SIM_US + 5 * 7 * SIM_US + 1200 * SIM_US);
            net_free(net);
            sim_engine_free(eng);
        }
    }
    net_topo_free(t);
}

/* The long-message protocol: above long_threshold bytes a message pays
 * startup_long instead of startup, at every fidelity and switching. */
static void test_long_message_startup(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(3);
    NetParams p = params(50 * SIM_US, 7 * SIM_US);
    p.startup_long = 120 * SIM_US;
    p.long_threshold = 200;
    static const uint64_t sizes[] = {0, 100, 200, 201, 1200};
    for (int sw = NET_SW_CIRCUIT; sw <= NET_SW_RING_SLOTS; sw++) {
        if (sw == NET_SW_STORE_FORWARD)
            continue;
        p.switching = (NetSwitching)sw;
        for (int f = NET_ANALYTIC; f <= NET_PACKET; f++) {
            for (guint i = 0; i < G_N_ELEMENTS(sizes); i++) {
                SimEngine *eng = sim_engine_new(1);
                NetNet *net = net_new(eng, t, &p, (NetFidelity)f);
                Log lg = {0};
                net_send(net, 1, 6, sizes[i], NULL, log_arrival, &lg);
                assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
                SimTime s = sizes[i] > 200 ? 120 * SIM_US : 50 * SIM_US;
                /* 1 ^ 6 = 7: three hops */
                assert_int_equal(lg.at[0],
                                 s + 3 * 7 * SIM_US + sizes[i] * SIM_US);
                assert_int_equal(net_ideal_time(net, 1, 6, sizes[i]), lg.at[0]);
                net_free(net);
                sim_engine_free(eng);
            }
        }
    }
    net_topo_free(t);
}

/* Store-and-forward pays the packet time on every hop but the last is
 * pipelined: startup + hops * (per_hop) + (hops - 1 + packets) * tau. */
static void test_store_and_forward(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(3);
    NetParams p = params(0, 5 * SIM_US);
    p.switching = NET_SW_STORE_FORWARD;
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_PACKET);
    Log lg = {0};
    net_send(net, 0, 7, 300, NULL, log_arrival, &lg);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(lg.at[0], 3 * 5 * SIM_US + (2 + 3) * 100 * SIM_US);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

static void test_two_flows_share_link(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(2);
    NetParams p = params(0, 0);
    p.switching = NET_SW_CUT_THROUGH; /* max-min: not a circuit machine */
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_FLOW);
    Log lg = {0};
    /* 0->1 and 0->3 both cross n0->n1. */
    net_send(net, 0, 1, 1000, GUINT_TO_POINTER(1), log_arrival, &lg);
    net_send(net, 0, 3, 1000, GUINT_TO_POINTER(2), log_arrival, &lg);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(lg.n, 2);
    assert_int_equal(lg.at[0], 2000 * SIM_US);
    assert_int_equal(lg.at[1], 2000 * SIM_US);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

static void send_later(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    net_send(ctx, 0, 3, 1000, GUINT_TO_POINTER(2), log_arrival, arg);
}

/* A alone for 500 us, then shared: A ends at 1500 us, B at 2000 us. */
static void test_flow_incremental(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(2);
    NetParams p = params(0, 0);
    p.switching = NET_SW_CUT_THROUGH;
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_FLOW);
    Log lg = {0};
    net_send(net, 0, 1, 1000, GUINT_TO_POINTER(1), log_arrival, &lg);
    sim_schedule_at(eng, 500 * SIM_US, send_later, net, &lg);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(lg.n, 2);
    assert_int_equal(lg.order[0], 1);
    assert_true(lg.at[0] >= 1500 * SIM_US && lg.at[0] <= 1500 * SIM_US + 2);
    assert_true(lg.at[1] >= 2000 * SIM_US && lg.at[1] <= 2000 * SIM_US + 2);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

/* Every XOR permutation is link-disjoint: all fidelities give the
 * analytic time for each message. */
static void test_xor_permutation_contention_free(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(4);
    NetParams p = params(20 * SIM_US, 3 * SIM_US);
    for (uint32_t k = 1; k < 16; k++) {
        for (int f = NET_ANALYTIC; f <= NET_PACKET; f++) {
            SimEngine *eng = sim_engine_new(1);
            NetNet *net = net_new(eng, t, &p, (NetFidelity)f);
            Log lg = {0};
            for (uint32_t i = 0; i < 16; i++)
                net_send(net, i, i ^ k, 500, NULL, log_arrival, &lg);
            assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
            assert_int_equal(lg.n, 16);
            SimTime ideal = net_ideal_time(net, 0, k, 500);
            for (guint i = 0; i < 16; i++)
                assert_int_equal(lg.at[i], ideal);
            net_free(net);
            sim_engine_free(eng);
        }
    }
    net_topo_free(t);
}

/* Circuit switching: 0->3 holds n0->n1 then waits for n1->n3, held by
 * 1->3; 0->1 queues behind 0->3 on n0->n1.  Order and times are fixed. */
static void test_circuit_blocking_order(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(2);
    NetParams p = params(10 * SIM_US, 0);
    for (int f = NET_FLOW; f <= NET_PACKET; f++) { /* both circuit rungs */
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, (NetFidelity)f);
        Log lg = {0};
        net_send(net, 1, 3, 100, GUINT_TO_POINTER(1), log_arrival, &lg);
        net_send(net, 0, 3, 100, GUINT_TO_POINTER(2), log_arrival, &lg);
        net_send(net, 0, 1, 100, GUINT_TO_POINTER(3), log_arrival, &lg);
        net_send(net, 0, 1, 100, GUINT_TO_POINTER(4), log_arrival, &lg);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(lg.n, 4);
        uint32_t want[4] = {1, 2, 3, 4};
        SimTime at[4] = {110, 210, 310, 410};
        for (guint i = 0; i < 4; i++) {
            assert_int_equal(lg.order[i], want[i]);
            assert_int_equal(lg.at[i], at[i] * SIM_US);
        }
        net_free(net);
        sim_engine_free(eng);
    }
    net_topo_free(t);
}

/* A newcomer to a link whose channels are all held queues behind the
 * headers already waiting there.  One link of 2 channels (hypercube of
 * dimension 1), 1000 B = 1000 us each: 1-5 at 0, 6 at 1500 us while 5
 * waits.  1, 2 end at 1000; 3, 4 take the channels then and end at 2000;
 * 5 and then 6 take them at 2000 and end at 3000. */
static void send_six(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    net_send(ctx, 0, 1, 1000, GUINT_TO_POINTER(6), log_arrival, arg);
}

static void test_circuit_fifo_newcomer(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(1);
    NetParams p = params(0, 0);
    p.channels = 2;
    for (int f = NET_FLOW; f <= NET_PACKET; f++) { /* both circuit rungs */
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, (NetFidelity)f);
        Log lg = {0};
        for (guint i = 1; i <= 5; i++)
            net_send(net, 0, 1, 1000, GUINT_TO_POINTER(i), log_arrival, &lg);
        sim_schedule_at(eng, 1500 * SIM_US, send_six, net, &lg);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(lg.n, 6);
        SimTime at[6] = {1000, 1000, 2000, 2000, 3000, 3000};
        for (guint i = 0; i < 6; i++) {
            assert_int_equal(lg.order[i], i + 1);
            assert_int_equal(lg.at[i], at[i] * SIM_US);
        }
        net_free(net);
        sim_engine_free(eng);
    }
    net_topo_free(t);
}

/* The flow rung on a circuit machine serialises a shared channel (first
 * come, first served) where max-min would share it: 0->1 and 0->3 both
 * cross n0->n1; circuits give 1000 and 2000 us, sharing 2000 and 2000. */
static void test_circuit_flow_serialises(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(2);
    NetParams p = params(0, 0);
    SimTime want[2][2] = {{2000, 2000}, {1000, 2000}};
    for (int k = 0; k < 2; k++) {
        p.switching = k ? NET_SW_CIRCUIT : NET_SW_CUT_THROUGH;
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, NET_FLOW);
        Log lg = {0};
        net_send(net, 0, 1, 1000, GUINT_TO_POINTER(1), log_arrival, &lg);
        net_send(net, 0, 3, 1000, GUINT_TO_POINTER(2), log_arrival, &lg);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(lg.n, 2);
        assert_int_equal(lg.order[0], 1);
        assert_int_equal(lg.at[0], want[k][0] * SIM_US);
        assert_int_equal(lg.at[1], want[k][1] * SIM_US);
        net_free(net);
        sim_engine_free(eng);
    }
    net_topo_free(t);
}

/* Why max-min is far off packet level on the CM-5's naive all-to-all
 * (docs/net.md): a FIFO link shares itself in proportion to what arrives,
 * max-min in equal parts.  16-node 4-ary fat tree (20, 10, 5 MB/s per
 * node at levels 0-2, 20-B packets), nodes 1-15 each send 10,240 B to
 * node 0 at once.  Node 0's down link (20 MB/s) is fed by nodes 1-3 at
 * 20 MB/s each and by the other 12 through their subtree's down link
 * (4 x 10 MB/s): 60 + 40 MB/s offered.  Packets give nodes 1-3 three
 * fifths of it, so they finish at 3 x 10,240 B / 12 MB/s = 2.56 ms;
 * max-min gives each of the 15 flows a fifteenth, so all finish at
 * 15 x 10,240 B / 20 MB/s = 7.68 ms.  The link is busy until 7.68 ms at
 * both rungs. */
static void test_fifo_sharing_favours_near_senders(void **state)
{
    (void)state;
    NetTopo *t = net_fattree_new(16, 4);
    NetParams p = params(10 * SIM_US, SIM_US / 5);
    p.bandwidth = 20e6;
    p.level_bw[0] = 20e6, p.level_bw[1] = 10e6, p.level_bw[2] = 5e6;
    p.packet_bytes = 20;
    p.switching = NET_SW_CUT_THROUGH;
    SimTime near_end[2], last[2];
    for (int k = 0; k < 2; k++) {
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, k ? NET_PACKET : NET_FLOW);
        Log lg = {0};
        for (uint32_t i = 1; i < 16; i++)
            net_send(net, i, 0, 10240, GUINT_TO_POINTER(i), log_arrival, &lg);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(lg.n, 15);
        near_end[k] = last[k] = 0;
        for (guint j = 0; j < lg.n; j++) {
            if (lg.order[j] <= 3 && lg.at[j] > near_end[k])
                near_end[k] = lg.at[j];
            last[k] = lg.at[j] > last[k] ? lg.at[j] : last[k];
        }
        net_free(net);
        sim_engine_free(eng);
    }
    double ms = (double)SIM_MS;
    assert_true(near_end[1] / ms > 2.55 && near_end[1] / ms < 2.58);
    assert_true(near_end[0] / ms > 7.68 && near_end[0] / ms < 7.70);
    assert_true(last[0] / ms > 7.68 && last[0] / ms < 7.70);
    assert_true(last[1] / ms > 7.68 && last[1] / ms < 7.70);
    net_topo_free(t);
}

/* Packets of a message that fills its packets exactly (200 bytes, 100 a
 * packet: two, no empty third) over the line 0 -> 2, slow link then one
 * four times faster, per hop 10 us, no startup.  Injected at 10 us, p1
 * holds link 0 over [10, 110), p2 over [110, 210); on link 2 a packet
 * cannot end before it ended on link 0 (cut-through), so p1 arrives at
 * 110 and p2, on link 2 from 120, at 210: the message at 210 us.  A
 * trailing empty packet would leave link 0 at 210 and arrive at 220. */
static void test_packet_exact_multiple(void **state)
{
    (void)state;
    NetTopo *t = net_topo_wrap(&line_ops, g_new0(char, 1), 1);
    NetParams p = params(0, 10 * SIM_US);
    p.switching = NET_SW_CUT_THROUGH;
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_PACKET);
    Log lg = {0};
    net_send(net, 0, 2, 200, NULL, log_arrival, &lg);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(lg.n, 1);
    assert_int_equal(lg.at[0], 210 * SIM_US);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

/* Nothing leaks: tracked memory returns to its idle level. */
static void test_memory_returns(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(4);
    NetParams p = params(1 * SIM_US, 1 * SIM_US);
    for (int sw = NET_SW_CIRCUIT; sw <= NET_SW_RING_SLOTS; sw++) {
        p.switching = (NetSwitching)sw;
        for (int f = NET_ANALYTIC; f <= NET_PACKET; f++) {
            SimEngine *eng = sim_engine_new(1);
            NetNet *net = net_new(eng, t, &p, (NetFidelity)f);
            size_t idle[2], busy[2];
            for (int round = 0; round < 2; round++) {
                Log lg = {0};
                for (uint32_t i = 0; i < 16; i++)
                    net_send(net, i, 15 - i, 250, NULL, log_arrival, &lg);
                busy[round] = net_tracked_bytes(net);
                assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
                idle[round] = net_tracked_bytes(net);
            }
            assert_true(idle[0] < busy[1]);
            assert_int_equal(idle[0], idle[1]);
            assert_int_equal(net_delivered(net), 32);
            net_free(net);
            sim_engine_free(eng);
        }
    }
    net_topo_free(t);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lone_message_all_fidelities),
        cmocka_unit_test(test_bottleneck_first_or_last),
        cmocka_unit_test(test_long_message_startup),
        cmocka_unit_test(test_store_and_forward),
        cmocka_unit_test(test_packet_exact_multiple),
        cmocka_unit_test(test_two_flows_share_link),
        cmocka_unit_test(test_flow_incremental),
        cmocka_unit_test(test_xor_permutation_contention_free),
        cmocka_unit_test(test_circuit_blocking_order),
        cmocka_unit_test(test_circuit_fifo_newcomer),
        cmocka_unit_test(test_circuit_flow_serialises),
        cmocka_unit_test(test_fifo_sharing_favours_near_senders),
        cmocka_unit_test(test_memory_returns),
    };
    return cmocka_run_group_tests_name("net_transport", tests, NULL, NULL);
}
