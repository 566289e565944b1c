/* test_hypercube.c — e-cube routes, link naming, lazy state at 64K nodes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "sim/net/net.h"
#include "tests/support.h"

static void test_ecube_bit_order(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(4);
    NetLinkId out[4];
    /* 0b0000 -> 0b1011: dims 0, 1, 3 in that order. */
    guint h = t->ops->route(t->state, 0, 11, out);
    assert_int_equal(h, 3);
    uint64_t a, b;
    t->ops->link_ends(t->state, out[0], &a, &b);
    assert_int_equal(a, 0);
    assert_int_equal(b, 1);
    t->ops->link_ends(t->state, out[1], &a, &b);
    assert_int_equal(a, 1);
    assert_int_equal(b, 3);
    t->ops->link_ends(t->state, out[2], &a, &b);
    assert_int_equal(a, 3);
    assert_int_equal(b, 11);
    char name[32];
    t->ops->link_name(t->state, out[2], name, sizeof name);
    assert_string_equal(name, "n3->n11");
    net_topo_free(t);
}

static void test_ecube_hops_hamming(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(6);
    NetLinkId out[6];
    for (uint32_t s = 0; s < 64; s++) {
        for (uint32_t d = 0; d < 64; d++) {
            if (s == d)
                continue;
            guint h = t->ops->route(t->state, s, d, out);
            assert_int_equal(h, (guint)__builtin_popcount(s ^ d));
            uint64_t a, b, prev = s, last_dim = 0;
            for (guint i = 0; i < h; i++) {
                t->ops->link_ends(t->state, out[i], &a, &b);
                assert_int_equal(a, prev);
                assert_int_equal(__builtin_popcountll(a ^ b), 1);
                assert_true((a ^ b) > last_dim); /* lowest dim first */
                last_dim = a ^ b;
                prev = b;
            }
            assert_int_equal(prev, d);
        }
    }
    net_topo_free(t);
}

static void test_xor_permutation_link_disjoint(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(5);
    NetLinkId out[5];
    for (uint32_t k = 1; k < 32; k++) {
        GHashTable *seen = g_hash_table_new(g_int64_hash, g_int64_equal);
        NetLinkId *ids = g_new(NetLinkId, 32 * 5);
        guint n = 0;
        for (uint32_t i = 0; i < 32; i++) {
            guint h = t->ops->route(t->state, i, i ^ k, out);
            for (guint j = 0; j < h; j++) {
                ids[n] = out[j];
                assert_false(g_hash_table_contains(seen, &ids[n]));
                g_hash_table_add(seen, &ids[n]);
                n++;
            }
        }
        g_hash_table_destroy(seen);
        g_free(ids);
    }
    net_topo_free(t);
}

static void count_arrival(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    SimTime *at = ctx;
    *at = d->arrived;
}

static NetParams cube_params(void)
{
    NetParams p = {0};
    p.bandwidth = 1e6; /* 1 us per byte: exact picoseconds */
    p.channels = 1;
    p.startup = 100 * SIM_US;
    p.per_hop = 10 * SIM_US;
    p.packet_bytes = 256;
    p.switching = NET_SW_CIRCUIT;
    return p;
}

static void test_analytic_lone_message(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_hypercube_new(4);
    NetParams p = cube_params();
    NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
    SimTime at = 0;
    net_send(net, 0, 15, 1000, NULL, count_arrival, &at);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(at, 100 * SIM_US + 4 * 10 * SIM_US + 1000 * SIM_US);
    assert_int_equal(net_ideal_time(net, 0, 15, 1000), at);
    assert_int_equal(net_total_bytes(net), 1000);
    assert_int_equal(net_links_touched(net), 4);
    NetLinkId busiest;
    assert_true(net_busiest_link(net, &busiest));
    SimResult *r = sim_result_new("test", "cube");
    net_fill_result(net, r);
    assert_int_equal(r->comm_messages, 1);
    assert_string_equal(r->busiest_link, "n0->n1");
    sim_result_free(r);
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
}

/* 65,536 nodes, one message: memory must be kilobytes. */
static void test_lazy_state_64k(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_hypercube_new(16);
    NetParams p = cube_params();
    for (int f = NET_ANALYTIC; f <= NET_PACKET; f++) {
        NetNet *net = net_new(eng, t, &p, (NetFidelity)f);
        SimTime at = 0;
        net_send(net, 0, 65535, 4096, NULL, count_arrival, &at);
        assert_int_equal(net_links_touched(net), 16);
        assert_true(net_tracked_bytes(net) < 8192);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_true(at > 0);
        assert_null(net_link_stats(net, 12345));
        net_free(net);
    }
    net_topo_free(t);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ecube_bit_order),
        cmocka_unit_test(test_ecube_hops_hamming),
        cmocka_unit_test(test_xor_permutation_link_disjoint),
        cmocka_unit_test(test_analytic_lone_message),
        cmocka_unit_test(test_lazy_state_64k),
    };
    return cmocka_run_group_tests_name("net_hypercube", tests, NULL, NULL);
}
