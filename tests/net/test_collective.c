/* test_collective.c — collective schedules against hand-computed times. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "sim/net/collective.h"

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

static void fx_open(Fx *f, unsigned dims, const NetParams *p, NetFidelity fid)
{
    f->eng = sim_engine_new(1);
    f->topo = net_hypercube_new(dims);
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
        fx_open(&f, 3, &p, (NetFidelity)fid);
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
    fx_open(&f, 4, &p, NET_ANALYTIC);
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
    fx_open(&f, 4, &p, NET_FLOW);
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
    fx_open(&f, 4, &p, NET_PACKET);
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
    fx_open(&f, 3, &p, NET_PACKET);
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
    fx_open(&f, 2, &p, NET_PACKET);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_xor_alltoall),
        cmocka_unit_test(test_broadcast_binomial),
        cmocka_unit_test(test_allreduce_and_barrier),
        cmocka_unit_test(test_pairwise_exchange),
        cmocka_unit_test(test_send_lists),
    };
    return cmocka_run_group_tests_name("net_collective", tests, NULL, NULL);
}
