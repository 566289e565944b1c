/* test_traffic.c — the traffic patterns are the same traffic at every
 * fidelity: the same messages, each node sending in the same order, and a
 * node's next message sent only once its previous one was delivered (at
 * packet level on the iPSC/2: once its circuit was released).  Only the
 * times differ.  Messages are observed through the trace hook.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <string.h>

#include "sim/core/trace.h"
#include "sim/net/traffic.h"
#include "tests/support.h"
#include <sys/resource.h>

#define N 16

typedef struct {
    uint32_t dst;
    uint64_t bytes;
    SimTime sent, arrived;
} Sent;

typedef struct {
    GArray *by_src[N]; /* Sent, in delivery order */
} Log;

static void on_flow(SimTrace *tr, uint32_t src, const char *sn, uint32_t dst,
                    const char *dn, uint64_t b, SimTime sent, SimTime arrived)
{
    (void)sn;
    (void)dn;
    Log *lg = tr->state;
    Sent s = {dst, b, sent, arrived};
    g_array_append_val(lg->by_src[src], s);
}

static const SimTraceOps log_ops = {.flow = on_flow};

static NetParams params(void)
{
    NetParams p = {0};
    p.bandwidth = 2.8e6;
    p.channels = 1;
    p.startup = 350 * SIM_US;
    p.per_hop = 10 * SIM_US;
    p.switching = NET_SW_CIRCUIT;
    return p;
}

static void run(Log *lg, NetTraffic t, NetFidelity f)
{
    NetTopo *topo = net_hypercube_new(4);
    NetParams p = params();
    SimEngine *eng = sim_engine_new(1);
    SimTrace tr = {&log_ops, lg};
    sim_engine_set_trace(eng, &tr);
    for (int i = 0; i < N; i++)
        lg->by_src[i] = g_array_new(FALSE, FALSE, sizeof(Sent));
    NetNet *net = net_new(eng, topo, &p, f);
    net_traffic_start(net, t, 10240, 5, NULL, NULL);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(net_delivered(net), net_traffic_messages(t, N));
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(topo);
}

static void log_free(Log *lg)
{
    for (int i = 0; i < N; i++)
        g_array_free(lg->by_src[i], TRUE);
}

/* Node i's k-th message: equal at every fidelity; sent after the
 * previous one arrived (one message in flight per node). */
static void check_same_traffic(NetTraffic t)
{
    Log lg[3];
    for (int f = NET_ANALYTIC; f <= NET_PACKET; f++)
        run(&lg[f], t, (NetFidelity)f);
    for (int i = 0; i < N; i++) {
        GArray *ref = lg[NET_PACKET].by_src[i];
        for (int f = NET_ANALYTIC; f <= NET_PACKET; f++) {
            GArray *a = lg[f].by_src[i];
            assert_int_equal(a->len, ref->len);
            for (guint k = 0; k < a->len; k++) {
                Sent *s = &g_array_index(a, Sent, k);
                assert_int_equal(s->dst, g_array_index(ref, Sent, k).dst);
                assert_int_equal(s->bytes, g_array_index(ref, Sent, k).bytes);
                if (k > 0)
                    assert_true(s->sent >=
                                g_array_index(a, Sent, k - 1).arrived);
            }
        }
    }
    for (int f = NET_ANALYTIC; f <= NET_PACKET; f++)
        log_free(&lg[f]);
}

static void test_same_traffic_every_pattern(void **state)
{
    (void)state;
    for (int t = NET_TRAFFIC_ALLTOALL; t <= NET_TRAFFIC_HOTSPOT; t++)
        check_same_traffic((NetTraffic)t);
}

/* The naive all-to-all: node i sends to 0, 1, 2 ... skipping itself, all
 * starting at time 0 on node 0; shift starts at i+1. */
static void test_pattern_orders(void **state)
{
    (void)state;
    Log lg;
    run(&lg, NET_TRAFFIC_ALLTOALL, NET_PACKET);
    for (uint32_t i = 0; i < N; i++) {
        GArray *a = lg.by_src[i];
        assert_int_equal(a->len, N - 1);
        for (guint k = 0; k < a->len; k++)
            assert_int_equal(g_array_index(a, Sent, k).dst, k < i ? k : k + 1);
        assert_int_equal(g_array_index(a, Sent, 0).sent, 0);
    }
    log_free(&lg);
    run(&lg, NET_TRAFFIC_SHIFT, NET_FLOW);
    for (uint32_t i = 0; i < N; i++)
        for (guint k = 0; k < N - 1; k++)
            assert_int_equal(g_array_index(lg.by_src[i], Sent, k).dst,
                             (i + k + 1) % N);
    log_free(&lg);
}

/* XOR: message k of node i goes to i ^ (k + 1).  Pairwise: step s swaps
 * with i ^ 2^(3 - s), n / 2^(s + 1) messages' worth of bytes (a
 * recursive-halving exchange: 8, 4, 2, 1 x 10240 on 16 nodes). */
static void test_xor_and_pairwise_contents(void **state)
{
    (void)state;
    Log lg;
    run(&lg, NET_TRAFFIC_XOR, NET_ANALYTIC);
    for (uint32_t i = 0; i < N; i++)
        for (guint k = 0; k < N - 1; k++) {
            const Sent *s = &g_array_index(lg.by_src[i], Sent, k);
            assert_int_equal(s->dst, i ^ (k + 1));
            assert_int_equal(s->bytes, 10240);
        }
    log_free(&lg);
    run(&lg, NET_TRAFFIC_PAIRWISE, NET_ANALYTIC);
    for (uint32_t i = 0; i < N; i++) {
        assert_int_equal(lg.by_src[i]->len, 4);
        for (guint s = 0; s < 4; s++) {
            const Sent *m = &g_array_index(lg.by_src[i], Sent, s);
            assert_int_equal(m->dst, i ^ (1u << (3 - s)));
            assert_int_equal(m->bytes, 10240 * (N >> (s + 1)));
        }
    }
    log_free(&lg);
}

/* Random: N - 1 messages a node, never to itself, spread over the nodes.
 * Hotspot with the same seed: the same lists, but that each message of a
 * node other than 0 goes to node 0 instead with probability 1/4 (node
 * 0's own list unchanged). */
static void test_random_and_hotspot(void **state)
{
    (void)state;
    Log r, h;
    run(&r, NET_TRAFFIC_RANDOM, NET_ANALYTIC);
    run(&h, NET_TRAFFIC_HOTSPOT, NET_ANALYTIC);
    guint into[N] = {0}, moved = 0, msgs = 0;
    for (uint32_t i = 0; i < N; i++) {
        assert_int_equal(r.by_src[i]->len, N - 1);
        assert_int_equal(h.by_src[i]->len, N - 1);
        for (guint k = 0; k < N - 1; k++) {
            const Sent *a = &g_array_index(r.by_src[i], Sent, k);
            const Sent *b = &g_array_index(h.by_src[i], Sent, k);
            assert_true(a->dst != i && a->dst < N && a->bytes == 10240);
            into[a->dst]++;
            assert_true(b->dst == a->dst || (i != 0 && b->dst == 0));
            moved += b->dst != a->dst;
            msgs += i != 0 && a->dst != 0;
        }
    }
    for (uint32_t j = 0; j < N; j++)
        assert_true(into[j] >= 5 && into[j] <= 30); /* 15 each on average */
    /* 1/4 of the 211 or so movable messages, well inside 1/8 .. 3/8 */
    assert_true(moved * 8 > msgs && moved * 8 < 3 * msgs);
    log_free(&r);
    log_free(&h);
}

static void test_names_and_checks(void **state)
{
    (void)state;
    NetTraffic t;
    assert_true(net_traffic_parse("hotspot", &t));
    assert_int_equal(t, NET_TRAFFIC_HOTSPOT);
    assert_string_equal(net_traffic_name(NET_TRAFFIC_ALLTOALL), "all-to-all");
    assert_false(net_traffic_parse("all2all", &t));
    for (int k = 0; k <= NET_TRAFFIC_HOTSPOT; k++) /* every name is listed */
        assert_non_null(
            strstr(net_traffic_words(), net_traffic_name((NetTraffic)k)));
    assert_true(net_traffic_check(NET_TRAFFIC_RANDOM, 34, NULL));
    GError *err = NULL;
    assert_false(net_traffic_check(NET_TRAFFIC_PAIRWISE, 34, &err));
    assert_non_null(err);
    g_error_free(err);
    assert_false(net_traffic_check(NET_TRAFFIC_SHIFT, 1, NULL));
    assert_true(net_traffic_check(NET_TRAFFIC_SHIFT, 2, NULL));
    assert_true(net_traffic_check(NET_TRAFFIC_XOR, NET_TRAFFIC_MAX_NODES, NULL));
    assert_false(
        net_traffic_check(NET_TRAFFIC_RANDOM, NET_TRAFFIC_MAX_NODES + 1, NULL));
    assert_int_equal(net_traffic_messages(NET_TRAFFIC_PAIRWISE, 16), 64);
    assert_int_equal(net_traffic_messages(NET_TRAFFIC_HOTSPOT, 16), 240);
}

static size_t peak_rss_bytes(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (size_t)ru.ru_maxrss * 1024; /* Linux: kB */
}

/* A 65,536-node naive all-to-all (4.3 G messages) run through its first
 * round: every node's first message delivered, analytic fidelity.  The
 * pattern is generated lazily, so peak memory stays under 256 MB of
 * resident set for the whole test process and the network holds under
 * 1 KB per node; the n x n byte matrix of the old generator alone was
 * 34 GB.  Runs first in this binary so the process peak is its own. */
static void test_first_round_memory_65536(void **state)
{
    (void)state;
    const uint32_t n = 65536;
    NetTopo *topo = net_hypercube_new(16);
    NetParams p = params();
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, topo, &p, NET_ANALYTIC);
    assert_true(net_traffic_check(NET_TRAFFIC_ALLTOALL, n, NULL));
    net_traffic_start(net, NET_TRAFFIC_ALLTOALL, 10240, 1, NULL, NULL);
    SimTime round = net_ideal_time(net, n - 1, 0, 10240);
    assert_true(sim_engine_run(eng, round, NULL));
    assert_true(net_delivered(net) >= n);     /* the first round is in */
    assert_true(net_total_messages(net) >= 2 * (uint64_t)n - 1);
    size_t held = net_tracked_bytes(net), rss = peak_rss_bytes();
    print_message("65,536-node all-to-all, round 1: net %zu B, peak RSS %zu "
                  "MB\n",
                  held, rss >> 20);
    assert_true(held < (size_t)n * 1024);
    assert_true(rss < (size_t)256 << 20);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(topo);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_first_round_memory_65536),
        cmocka_unit_test(test_same_traffic_every_pattern),
        cmocka_unit_test(test_pattern_orders),
        cmocka_unit_test(test_xor_and_pairwise_contents),
        cmocka_unit_test(test_random_and_hotspot),
        cmocka_unit_test(test_names_and_checks),
    };
    return cmocka_run_group_tests_name("net_traffic", tests, NULL, NULL);
}
