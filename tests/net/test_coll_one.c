/* test_coll_one.c — collectives on a machine of one node
 * (sim/net/collective.c): log2 of 1 is 0 steps, so a broadcast, an
 * all-reduce, a prefix sum, a barrier and an all-to-all finish at once
 * without a message; on two nodes the all-reduce takes one exchange. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/net/collective.h"
#include "tests/support.h"

static void done(NetNet *net, void *ctx)
{
    (void)net;
    (*(int *)ctx)++;
}

static void test_one_node(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_hypercube_new(0);
    NetParams p = {0};
    p.bandwidth = 1e6;
    p.startup = 5 * SIM_US;
    NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
    int n = 0;
    net_broadcast(net, 0, 100, done, &n);
    net_allreduce(net, 100, done, &n);
    net_prefix_sum(net, 100, done, &n);
    net_barrier(net, done, &n);
    net_alltoall_uniform(net, 100, NET_A2A_XOR, done, &n);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(n, 5);
    assert_int_equal(sim_now(eng), 0);
    assert_int_equal(net_total_messages(net), 0);
    net_free(net);
    net_topo_free(t);
    /* two nodes: one exchange each way */
    t = net_hypercube_new(1);
    net = net_new(eng, t, &p, NET_ANALYTIC);
    net_allreduce(net, 100, done, &n);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(n, 6);
    assert_int_equal(net_total_messages(net), 2);
    assert_int_equal(sim_now(eng), 5 * SIM_US + 100 * SIM_US);
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_node),
    };
    return cmocka_run_group_tests_name("coll_one", tests, NULL, NULL);
}
