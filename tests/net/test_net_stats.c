/* test_net_stats.c — what sim/net/net.c counts, exactly: net_new's
 * defaults (0 channels means 1, a packet size of 0 means 1024 B; other
 * values kept), each link's bytes, messages and busy time after two
 * messages share a link, the totals, the busiest link and the
 * contention-free time, at a bandwidth of 2^20 B/s where 512 B take
 * 5^12 x 2 ps exactly. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/net/net.h"
#include "tests/support.h"

static void test_defaults(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_crossbar_new(2);
    NetParams p = {0};
    p.bandwidth = 1e6;
    NetNet *net = net_new(eng, t, &p, NET_PACKET);
    assert_int_equal(net_params(net)->channels, 1);
    assert_int_equal(net_params(net)->packet_bytes, 1024);
    net_free(net);
    p.channels = 3;
    p.packet_bytes = 1;
    net = net_new(eng, t, &p, NET_PACKET);
    assert_int_equal(net_params(net)->channels, 3);
    assert_int_equal(net_params(net)->packet_bytes, 1);
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
}

static void test_link_stats(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    uint32_t ext[1] = {4};
    NetTopo *t = net_mesh_new(1, ext, FALSE);
    NetParams p = {0};
    p.bandwidth = 1048576;
    p.startup = 5 * SIM_US;
    p.per_hop = 7;
    p.switching = NET_SW_CUT_THROUGH;
    NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
    NetLinkId l01[4], l12[4];
    assert_int_equal(t->ops->route(t->state, 0, 1, l01), 1);
    assert_int_equal(t->ops->route(t->state, 1, 2, l12), 1);
    assert_int_equal(net_ideal_time(net, 0, 2, 1024),
                     5 * SIM_US + 2 * 7 + 976562500);
    assert_int_equal(net_ideal_time(net, 1, 1, 1024), 5 * SIM_US);
    net_send(net, 0, 2, 1024, NULL, NULL, NULL);
    net_send(net, 1, 2, 512, NULL, NULL, NULL);
    assert_int_equal(net_links_touched(net), 2);
    assert_int_equal(net_total_bytes(net), 1536);
    assert_int_equal(net_total_messages(net), 2);
    const SimLinkStats *a = net_link_stats(net, l01[0]);
    const SimLinkStats *b = net_link_stats(net, l12[0]);
    assert_int_equal(a->bytes, 1024);
    assert_int_equal(a->messages, 1);
    assert_int_equal(a->busy, 976562500);
    assert_int_equal(b->bytes, 1536);
    assert_int_equal(b->messages, 2);
    assert_int_equal(b->busy, 976562500 + 488281250);
    NetLinkId busiest = 0;
    assert_true(net_busiest_link(net, &busiest));
    assert_true(busiest == l12[0]);
    assert_int_equal(net_delivered(net), 0);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(net_delivered(net), 2);
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_link_stats),
    };
    return cmocka_run_group_tests_name("net_stats", tests, NULL, NULL);
}
