/* test_collective.c — collective schedules against hand-computed times,
 * and who sends what to whom (read off a crossbar's links). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "sim/net/collective.h"
#include "tests/support.h"

typedef struct {
    SimEngine *eng;
    NetTopo *topo;
    NetNet *net;
    SimTime done_at;
    int done;
} Fx;

static NetParams params(void)
{
    NetParams p = {0};
    p.bandwidth = 1e6; /* 1 us per byte */
    p.channels = 1;
    p.startup = 10 * SIM_US;
    p.per_hop = 1 * SIM_US;
    p.packet_bytes = 100;
    p.switching = NET_SW_CIRCUIT;
    return p;
}

/* Takes topo. */
static void fx_open(Fx *f, NetTopo *topo, const NetParams *p, NetFidelity fid)
{
    f->eng = sim_engine_new(1);
    f->topo = topo;
    f->net = net_new(f->eng, f->topo, p, fid);
    f->done = 0;
}

static void fx_close(Fx *f)
{
    net_free(f->net);
    net_topo_free(f->topo);
    sim_engine_free(f->eng);
}

static void on_done(NetNet *net, void *ctx)
{
    Fx *f = ctx;
    f->done_at = sim_now(net_engine(net));
    f->done++;
}

/* XOR all-to-all: n-1 link-disjoint steps of one message; each step
 * costs the ideal time of its hop count, at every fidelity. */
static void test_xor_alltoall(void **state)
{
    (void)state;
    NetParams p = params();
    for (int fid = NET_ANALYTIC; fid <= NET_PACKET; fid++) {
        Fx f;
        fx_open(&f, net_hypercube_new(3), &p, (NetFidelity)fid);
        uint64_t b[64];
        for (int i = 0; i < 64; i++)
            b[i] = i / 8 == i % 8 ? 0 : 100;
        net_alltoall(f.net, b, NET_A2A_XOR, on_done, &f);
        assert_true(sim_engine_run(f.eng, SIM_TIME_MAX, NULL));
        SimTime want = 0;
        for (uint32_t k = 1; k < 8; k++)
            want += net_ideal_time(f.net, 0, k, 100);
        assert_int_equal(f.done, 1);
        assert_int_equal(f.done_at, want);
        assert_int_equal(net_total_messages(f.net), 56);
        fx_close(&f);
    }
}

static void test_broadcast_binomial(void **state)
{
    (void)state;
    NetParams p = params();
    Fx f;
    fx_open(&f, net_hypercube_new(4), &p, NET_ANALYTIC);
    net_broadcast(f.net, 5, 50, on_done, &f);
    assert_true(sim_engine_run(f.eng, SIM_TIME_MAX, NULL));
    assert_int_equal(net_total_messages(f.net), 15);
    /* 4 rounds; the critical path crosses at most 4 hops in total but
     * each round's time depends on the partner distance: bounded by
     * 4 * ideal(4 hops) and at least 4 * ideal(1 hop). */
    SimTime one = net_ideal_time(f.net, 0, 1, 50);
    SimTime far = net_ideal_time(f.net, 0, 15, 50);
    assert_true(f.done_at >= 4 * one && f.done_at <= 4 * far);
    fx_close(&f);
}

static void test_allreduce_and_barrier(void **state)
{
    (void)state;
    NetParams p = params();
    Fx f;
    fx_open(&f, net_hypercube_new(4), &p, NET_FLOW);
    net_allreduce(f.net, 8, on_done, &f);
    assert_true(sim_engine_run(f.eng, SIM_TIME_MAX, NULL));
    /* 4 exchange steps across one dimension each. */
    assert_int_equal(f.done_at, 4 * net_ideal_time(f.net, 0, 1, 8));
    assert_int_equal(net_total_messages(f.net), 64);
    net_barrier(f.net, on_done, &f);
    SimTime t0 = sim_now(f.eng);
    assert_true(sim_engine_run(f.eng, SIM_TIME_MAX, NULL));
    assert_int_equal(f.done, 2);
    assert_int_equal(f.done_at - t0, 4 * net_ideal_time(f.net, 0, 1, 0));
    fx_close(&f);
    /* With a control network: fixed latency, no data-network traffic. */
    p.ctrl_latency = 5 * SIM_US;
    fx_open(&f, net_hypercube_new(4), &p, NET_PACKET);
    net_prefix_sum(f.net, 4, on_done, &f);
    assert_true(sim_engine_run(f.eng, SIM_TIME_MAX, NULL));
    assert_int_equal(f.done_at, 5 * SIM_US);
    assert_int_equal(net_total_messages(f.net), 0);
    fx_close(&f);
}

/* Recursive halving: step s crosses dimension d-1-s, so each message is
 * one hop, with the caller's sizes. */
static void test_pairwise_exchange(void **state)
{
    (void)state;
    NetParams p = params();
    Fx f;
    fx_open(&f, net_hypercube_new(3), &p, NET_PACKET);
    uint64_t b[8 * 3];
    for (int i = 0; i < 8; i++) {
        b[i * 3 + 0] = 400;
        b[i * 3 + 1] = 200;
        b[i * 3 + 2] = 100;
    }
    net_pairwise_exchange(f.net, b, on_done, &f);
    assert_true(sim_engine_run(f.eng, SIM_TIME_MAX, NULL));
    SimTime want = net_ideal_time(f.net, 0, 4, 400) +
                   net_ideal_time(f.net, 0, 2, 200) +
                   net_ideal_time(f.net, 0, 1, 100);
    assert_int_equal(f.done_at, want);
    assert_int_equal(net_total_bytes(f.net), 8 * 700);
    fx_close(&f);
}

/* Send lists: one node's messages go one after another; a hot spot
 * under circuit switching serialises on the shared last link. */
static void test_send_lists(void **state)
{
    (void)state;
    NetParams p = params();
    Fx f;
    fx_open(&f, net_hypercube_new(2), &p, NET_PACKET);
    uint32_t count[4] = {0, 2, 0, 1};
    uint32_t dst[3] = {0, 0, 2};
    uint64_t size[3] = {100, 100, 100};
    net_send_lists(f.net, count, dst, size, on_done, &f);
    assert_true(sim_engine_run(f.eng, SIM_TIME_MAX, NULL));
    /* 1->0 twice in a row: 2 * (10 + 1 + 100); 3->2 alone overlaps. */
    assert_int_equal(f.done_at, 2 * 111 * SIM_US);
    assert_int_equal(f.done, 1);
    fx_close(&f);
}

/* ---- who sends what to whom, read off a crossbar's links: node j's
 * down link (id 2j + 1) carries exactly the messages sent to j, its up
 * link (2j) those sent by j.  Node counts that are not powers of two, a
 * root other than 0, matrices with distinct and zero entries; times from
 * net_ideal_time (test_transport.c) and the schedule. ---- */

#define N 6

static void xb_open(Fx *x, uint32_t n, NetFidelity fid)
{
    NetParams p = params();
    p.switching = NET_SW_CUT_THROUGH;
    fx_open(x, net_crossbar_new(n), &p, fid);
}

static void xb_run(Fx *x)
{
    assert_true(sim_engine_run(x->eng, SIM_TIME_MAX, NULL));
    assert_int_equal(x->done, 1);
}

/* Bytes and messages on node j's down (dir 1) or up (dir 0) link. */
static uint64_t link_bytes(const Fx *x, uint32_t j, int dir)
{
    const SimLinkStats *s = net_link_stats(x->net, 2 * (NetLinkId)j + dir);
    return s ? s->bytes : 0;
}

static uint64_t link_msgs(const Fx *x, uint32_t j, int dir)
{
    const SimLinkStats *s = net_link_stats(x->net, 2 * (NetLinkId)j + dir);
    return s ? s->messages : 0;
}

/* Binomial broadcast from root 4 of 6: ceil(log2 6) = 3 rounds, each one
 * message time (distinct senders and receivers: no sharing); every node
 * but the root receives once; the root sends in every round (to relative
 * ranks 1, 2, 4: nodes 5, 0, 2), rank 1 (node 5) twice (ranks 3, 5:
 * nodes 1, 3), and no one else (rank 2's partner, rank 6, does not
 * exist). */
static void test_broadcast_ranks(void **state)
{
    (void)state;
    for (NetFidelity f = NET_ANALYTIC; f <= NET_PACKET; f++) {
        Fx x;
        xb_open(&x, N, f);
        net_broadcast(x.net, 4, 100, on_done, &x);
        xb_run(&x);
        assert_int_equal(x.done_at, 3 * net_ideal_time(x.net, 0, 1, 100));
        const uint64_t sent[N] = {0, 0, 0, 0, 3, 2};
        for (uint32_t j = 0; j < N; j++) {
            assert_int_equal(link_msgs(&x, j, 1), j == 4 ? 0 : 1);
            assert_int_equal(link_bytes(&x, j, 1), j == 4 ? 0 : 100);
            assert_int_equal(link_msgs(&x, j, 0), sent[j]);
        }
        assert_int_equal(net_total_messages(x.net), N - 1);
        fx_close(&x);
    }
}

/* A matrix with distinct entries (and zeros on a diagonal and at
 * [1][3]): the down link of j carries column j, the up link of i row i,
 * under every schedule; a zero entry sends nothing under NAIVE and
 * SHIFT (a zero-byte message under XOR, which needs a power of two). */
static void fill_matrix(uint64_t *b, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = 0; j < n; j++)
            b[i * n + j] = i == j || (i == 1 && j == 3) ? 0 : 10 * i + j + 1;
}

static void check_matrix_links(const Fx *x, const uint64_t *b, uint32_t n,
                               gboolean zero_sends)
{
    for (uint32_t j = 0; j < n; j++) {
        uint64_t col = 0, row = 0, in = 0, out = 0;
        for (uint32_t i = 0; i < n; i++) {
            col += b[i * n + j];
            row += b[j * n + i];
            in += i != j && (b[i * n + j] || zero_sends);
            out += i != j && (b[j * n + i] || zero_sends);
        }
        assert_int_equal(link_bytes(x, j, 1), col);
        assert_int_equal(link_bytes(x, j, 0), row);
        assert_int_equal(link_msgs(x, j, 1), in);
        assert_int_equal(link_msgs(x, j, 0), out);
    }
}

/* Analytic: each node's messages go one after another, so the collective
 * ends with the node whose row takes longest (sum of ideal times). */
static SimTime slowest_row(const Fx *x, const uint64_t *b, uint32_t n,
                           gboolean zero_sends)
{
    SimTime worst = 0;
    for (uint32_t i = 0; i < n; i++) {
        SimTime t = 0;
        for (uint32_t j = 0; j < n; j++)
            if (j != i && (b[i * n + j] || zero_sends))
                t += net_ideal_time(x->net, i, j, b[i * n + j]);
        worst = MAX(worst, t);
    }
    return worst;
}

static void test_alltoall_matrix(void **state)
{
    (void)state;
    uint64_t b[8 * 8];
    for (int s = NET_A2A_NAIVE; s <= NET_A2A_XOR; s++) {
        uint32_t n = s == NET_A2A_XOR ? 8 : N;
        gboolean zs = s == NET_A2A_XOR;
        fill_matrix(b, n);
        Fx x;
        xb_open(&x, n, NET_ANALYTIC);
        net_alltoall(x.net, b, (NetA2ASchedule)s, on_done, &x);
        xb_run(&x);
        check_matrix_links(&x, b, n, zs);
        if (s != NET_A2A_XOR) /* XOR steps wait for their partner */
            assert_int_equal(x.done_at, slowest_row(&x, b, n, zs));
        fx_close(&x);
    }
}

/* Uniform: every ordered pair once, `bytes` each. */
static void test_alltoall_uniform_pairs(void **state)
{
    (void)state;
    for (int s = NET_A2A_NAIVE; s <= NET_A2A_SHIFT; s++) {
        Fx x;
        xb_open(&x, N, NET_ANALYTIC);
        net_alltoall_uniform(x.net, 7, (NetA2ASchedule)s, on_done, &x);
        xb_run(&x);
        for (uint32_t j = 0; j < N; j++) {
            assert_int_equal(link_msgs(&x, j, 1), N - 1);
            assert_int_equal(link_bytes(&x, j, 0), 7 * (N - 1));
        }
        assert_int_equal(x.done_at,
                         (N - 1) * net_ideal_time(x.net, 0, 1, 7));
        fx_close(&x);
    }
}

/* Send lists: node i sends count[i] messages in order; the longest list
 * sets the time (analytic: one message time each). */
static void test_send_lists_routes(void **state)
{
    (void)state;
    const uint32_t count[N] = {2, 0, 1, 0, 0, 3};
    const uint32_t dst[] = {1, 2, 0, 0, 1, 2};
    const uint64_t size[] = {5, 6, 7, 8, 9, 10};
    Fx x;
    xb_open(&x, N, NET_ANALYTIC);
    net_send_lists(x.net, count, dst, size, on_done, &x);
    xb_run(&x);
    /* into 0: 7 (from 2) + 8 (from 5); 1: 5 + 9; 2: 6 + 10 */
    assert_int_equal(link_bytes(&x, 0, 1), 15);
    assert_int_equal(link_bytes(&x, 1, 1), 14);
    assert_int_equal(link_bytes(&x, 2, 1), 16);
    assert_int_equal(link_bytes(&x, 5, 0), 27);
    assert_int_equal(x.done_at, net_ideal_time(x.net, 5, 0, 8) +
                                    net_ideal_time(x.net, 5, 1, 9) +
                                    net_ideal_time(x.net, 5, 2, 10));
    fx_close(&x);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_xor_alltoall),
        cmocka_unit_test(test_broadcast_binomial),
        cmocka_unit_test(test_allreduce_and_barrier),
        cmocka_unit_test(test_pairwise_exchange),
        cmocka_unit_test(test_send_lists),
        cmocka_unit_test(test_broadcast_ranks),
        cmocka_unit_test(test_alltoall_matrix),
        cmocka_unit_test(test_alltoall_uniform_pairs),
        cmocka_unit_test(test_send_lists_routes),
    };
    return cmocka_run_group_tests_name("net_collective", tests, NULL, NULL);
}
