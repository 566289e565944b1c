/* test_group.c — two-level networks (sim/net/group.c): endpoints of one
 * group meet at the group's switch in two hops at node_bw; others take
 * the outer topology between groups (shared ports) or between endpoints
 * (per-endpoint ports); link names, ends and bandwidths; and, under
 * contention, a group's endpoints sharing one outer port (shared) where
 * per-endpoint ports keep them apart. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/net/net.h"
#include "tests/support.h"

#define INNER ((NetLinkId)1 << 63)

static void test_shared_routes(void **state)
{
    (void)state;
    /* 4 groups of 3 on a ring of 4: 12 endpoints. */
    NetTopo *t = net_group_new(net_ring_new(4), 3, FALSE, 12);
    NetLinkId r[8];
    char name[32];
    assert_string_equal(t->ops->name, "group");
    assert_int_equal(net_topo_nodes(t), 12);
    assert_int_equal(t->ops->route(t->state, 4, 5, r), 2); /* group 1 */
    assert_true(r[0] == INNER + 8 && r[1] == INNER + 11);
    t->ops->link_name(t->state, r[0], name, sizeof name);
    assert_string_equal(name, "e4->sw1");
    t->ops->link_name(t->state, r[1], name, sizeof name);
    assert_string_equal(name, "sw1->e5");
    /* Endpoint 2 (group 0) to 7 (group 2): the ring route 0 -> 2. */
    NetLinkId o[8];
    const NetTopo *ring = net_group_outer(t);
    guint h = ring->ops->route(ring->state, 0, 2, o);
    assert_int_equal(t->ops->route(t->state, 2, 7, r), h);
    assert_memory_equal(r, o, h * sizeof *r);
    uint64_t a, b;
    t->ops->link_ends(t->state, INNER + 8, &a, &b);
    assert_true(a == INNER + 4 && b == INNER + ((uint64_t)1 << 62) + 1);
    t->ops->link_ends(t->state, INNER + 11, &a, &b);
    assert_true(b == INNER + 5 && a == INNER + ((uint64_t)1 << 62) + 1);
    assert_true(t->ops->max_hops(t->state) >= 2);
    NetParams p = {.bandwidth = 1e6, .node_bw = 5e6, .channels = 1};
    assert_true(t->ops->link_bw(t->state, INNER + 8, &p) == 5e6);
    assert_true(t->ops->link_bw(t->state, r[0], &p) == 1e6);
    p.node_bw = 0; /* absent: the base bandwidth */
    assert_true(t->ops->link_bw(t->state, INNER + 8, &p) == 1e6);
    net_topo_free(t);
}

static void test_per_endpoint_routes(void **state)
{
    (void)state;
    /* 16 endpoints in groups of 4, each with its own fat-tree leaf. */
    NetTopo *t = net_group_new(net_fattree_new(16, 4), 4, TRUE, 16);
    NetLinkId r[8], o[8];
    assert_int_equal(net_topo_nodes(t), 16);
    assert_int_equal(t->ops->route(t->state, 0, 3, r), 2);
    assert_true(r[0] >= INNER); /* inside the node: the switch */
    const NetTopo *ft = net_group_outer(t);
    guint h = ft->ops->route(ft->state, 1, 14, o);
    assert_int_equal(t->ops->route(t->state, 1, 14, r), h);
    assert_memory_equal(r, o, h * sizeof *r);
    char name[32];
    t->ops->link_name(t->state, r[0], name, sizeof name);
    assert_string_equal(name, "up0.1");
    net_topo_free(t);
}

/* 10 endpoints in groups of 4 over a ring of 3: the last group holds
 * endpoints 8 and 9 only; 9 reaches 8 through its switch and 0 over the
 * ring (groups 2 -> 0). */
static void test_partial_group(void **state)
{
    (void)state;
    NetTopo *t = net_group_new(net_ring_new(3), 4, FALSE, 10);
    NetLinkId r[8];
    char name[32];
    assert_int_equal(net_topo_nodes(t), 10);
    assert_int_equal(t->ops->route(t->state, 9, 8, r), 2);
    t->ops->link_name(t->state, r[1], name, sizeof name);
    assert_string_equal(name, "sw2->e8");
    assert_int_equal(t->ops->route(t->state, 9, 0, r), 1);
    assert_true(r[0] < INNER);
    net_topo_free(t);
}

typedef struct {
    SimTime last;
} Done;

static void on_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Done *x = ctx;
    if (d->arrived > x->last)
        x->last = d->arrived;
}

/* Endpoints 0 and 1 (one group) each send 1 MB to 2 and 3 (the other
 * group) at once: with one shared port per group the two messages share
 * the outer link (twice the time of one); per-endpoint ports on a
 * crossbar keep them apart (the time of one). */
static SimTime two_sends(gboolean per_endpoint)
{
    SimEngine *eng = sim_engine_new(1);
    NetTopo *outer = per_endpoint ? net_crossbar_new(4) : net_ring_new(2);
    NetTopo *t = net_group_new(outer, 2, per_endpoint, 4);
    NetParams p = {.bandwidth = 1e6, .node_bw = 1e9, .channels = 1};
    NetNet *net = net_new(eng, t, &p, NET_FLOW);
    Done d = {0};
    net_send(net, 0, 2, 1000000, NULL, on_arrive, &d);
    net_send(net, 1, 3, 1000000, NULL, on_arrive, &d);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
    return d.last;
}

static void test_shared_port_contends(void **state)
{
    (void)state;
    SimTime shared = two_sends(FALSE), own = two_sends(TRUE);
    assert_int_equal(shared, 2 * SIM_S);
    assert_int_equal(own, SIM_S);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shared_routes),
        cmocka_unit_test(test_per_endpoint_routes),
        cmocka_unit_test(test_partial_group),
        cmocka_unit_test(test_shared_port_contends),
    };
    return cmocka_run_group_tests_name("group", tests, NULL, NULL);
}
