/* test_topology.c — fat tree, ring, mesh/torus, crossbar, bus, CM-200. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "sim/net/net.h"
#include "tests/support.h"

/* Follows a route's link ends: returns FALSE if it is not a walk from
 * src to dst. */
static gboolean is_walk(const NetTopo *t, uint32_t src, uint32_t dst,
                        const NetLinkId *r, guint h)
{
    uint64_t a, b, at = src;
    for (guint i = 0; i < h; i++) {
        t->ops->link_ends(t->state, r[i], &a, &b);
        if (a != at)
            return FALSE;
        at = b;
    }
    return at == dst;
}

static void test_fattree_up_down(void **state)
{
    (void)state;
    NetTopo *t = net_fattree_new(64, 4);
    NetLinkId r[8];
    char name[32];
    /* siblings under one level-1 switch: up0, down0 */
    guint h = t->ops->route(t->state, 1, 2, r);
    assert_int_equal(h, 2);
    t->ops->link_name(t->state, r[0], name, sizeof name);
    assert_string_equal(name, "up0.1");
    t->ops->link_name(t->state, r[1], name, sizeof name);
    assert_string_equal(name, "down0.2");
    /* 5 and 60: LCA is the root (level 3): up0.5 up1.1 up2.0, then down */
    h = t->ops->route(t->state, 5, 60, r);
    assert_int_equal(h, 6);
    const char *want[6] = {"up0.5",   "up1.1",    "up2.0",
                           "down2.3", "down1.15", "down0.60"};
    for (guint i = 0; i < 6; i++) {
        t->ops->link_name(t->state, r[i], name, sizeof name);
        assert_string_equal(name, want[i]);
    }
    for (uint32_t s = 0; s < 64; s++)
        for (uint32_t d = 0; d < 64; d++)
            if (s != d) {
                h = t->ops->route(t->state, s, d, r);
                assert_true(h % 2 == 0 && is_walk(t, s, d, r, h));
            }
    /* Per-node bandwidth per level times the subtree size. */
    NetParams p = {0};
    p.bandwidth = 20e6;
    p.level_bw[0] = 20e6;
    p.level_bw[1] = 10e6;
    p.level_bw[2] = 5e6;
    h = t->ops->route(t->state, 5, 60, r);
    assert_true(t->ops->link_bw(t->state, r[0], &p) == 20e6);
    assert_true(t->ops->link_bw(t->state, r[1], &p) == 40e6);
    assert_true(t->ops->link_bw(t->state, r[2], &p) == 80e6);
    net_topo_free(t);
}

typedef struct {
    uint32_t order[16];
    SimTime at[16];
    guint n;
} Log;

static void log_arrival(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Log *lg = ctx;
    lg->at[lg->n] = d->arrived;
    lg->order[lg->n++] = GPOINTER_TO_UINT(d->payload);
}

/* Ring: two channels.  Messages 1 and 2 (0->3) take channels 0 and 1;
 * message 3 (1->2) overlaps both and waits; message 4 (3->0) is disjoint
 * and runs at once.  Same-pair messages arrive in send order. */
static void test_ring_slots_order(void **state)
{
    (void)state;
    NetTopo *t = net_ring_new(6);
    NetLinkId r[5];
    assert_int_equal(t->ops->route(t->state, 4, 1, r), 3);
    assert_true(is_walk(t, 4, 1, r, 3));
    NetParams p = {0};
    p.bandwidth = 1e6;
    p.channels = 2;
    p.per_hop = 1 * SIM_US;
    p.switching = NET_SW_RING_SLOTS;
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_PACKET);
    Log lg = {0};
    net_send(net, 0, 3, 100, GUINT_TO_POINTER(1), log_arrival, &lg);
    net_send(net, 0, 3, 200, GUINT_TO_POINTER(2), log_arrival, &lg);
    net_send(net, 1, 2, 10, GUINT_TO_POINTER(3), log_arrival, &lg);
    net_send(net, 3, 0, 10, GUINT_TO_POINTER(4), log_arrival, &lg);
    net_send(net, 0, 3, 10, GUINT_TO_POINTER(5), log_arrival, &lg);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    uint32_t want[5] = {4, 1, 3, 5, 2};
    SimTime at[5] = {13, 103, 114, 127, 203};
    for (guint i = 0; i < 5; i++) {
        assert_int_equal(lg.order[i], want[i]);
        assert_int_equal(lg.at[i], at[i] * SIM_US);
    }
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

static void test_torus_and_mesh(void **state)
{
    (void)state;
    uint32_t e[2] = {8, 4};
    NetTopo *torus = net_mesh_new(2, e, TRUE);
    NetTopo *mesh = net_mesh_new(2, e, FALSE);
    NetLinkId r[16];
    /* (0,0) -> (7,3): torus wraps both ways (1 + 1 hops), mesh 7 + 3 */
    assert_int_equal(torus->ops->route(torus->state, 0, 31, r), 2);
    assert_true(is_walk(torus, 0, 31, r, 2));
    assert_int_equal(mesh->ops->route(mesh->state, 0, 31, r), 10);
    assert_true(is_walk(mesh, 0, 31, r, 10));
    for (uint32_t s = 0; s < 32; s++)
        for (uint32_t d = 0; d < 32; d++)
            if (s != d) {
                guint h = torus->ops->route(torus->state, s, d, r);
                assert_true(h <= 6 && is_walk(torus, s, d, r, h));
            }
    net_topo_free(torus);
    net_topo_free(mesh);
}

static void test_crossbar_bus(void **state)
{
    (void)state;
    NetTopo *x = net_crossbar_new(8), *b = net_bus_new(8);
    NetLinkId r[2];
    assert_int_equal(x->ops->route(x->state, 3, 5, r), 2);
    assert_true(is_walk(x, 3, 5, r, 2)); /* via the switch vertex */
    uint64_t a, z;
    x->ops->link_ends(x->state, r[0], &a, &z);
    assert_int_equal(a, 3);
    x->ops->link_ends(x->state, r[1], &a, &z);
    assert_int_equal(z, 5);
    assert_int_equal(b->ops->route(b->state, 3, 5, r), 1);
    /* On a bus everything contends: 4 messages of 100 B back to back. */
    NetParams p = {0};
    p.bandwidth = 1e6;
    p.switching = NET_SW_CUT_THROUGH;
    p.packet_bytes = 100;
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, b, &p, NET_PACKET);
    Log lg = {0};
    for (uint32_t i = 0; i < 4; i++)
        net_send(net, i, 7 - i, 100, GUINT_TO_POINTER(i), log_arrival, &lg);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    for (guint i = 0; i < 4; i++)
        assert_int_equal(lg.at[i], (i + 1) * 100 * SIM_US);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(x);
    net_topo_free(b);
}

static void test_cm200_routes(void **state)
{
    (void)state;
    /* 4 routers x 16 processors = 64, NEWS grid 8 x 8 */
    NetTopo *t = net_cm200_new(2, 16, 8, 8);
    NetLinkId r[4];
    char name[48];
    /* NEWS neighbour (+x): one hop */
    assert_int_equal(t->ops->route(t->state, 9, 10, r), 1);
    t->ops->link_name(t->state, r[0], name, sizeof name);
    assert_string_equal(name, "news:p9->p10");
    /* -y wraps: 3 -> 59 */
    assert_int_equal(t->ops->route(t->state, 3, 59, r), 1);
    assert_true(is_walk(t, 3, 59, r, 1));
    /* router 0 -> router 3: inject, 2 cube hops, eject */
    assert_int_equal(t->ops->route(t->state, 0, 63, r), 4);
    t->ops->link_name(t->state, r[1], name, sizeof name);
    assert_string_equal(name, "cube:r0->r1");
    assert_true(is_walk(t, 0, 63, r, 4));
    /* same router, not neighbours: inject + eject */
    assert_int_equal(t->ops->route(t->state, 0, 13, r), 2);
    assert_true(is_walk(t, 0, 13, r, 2));
    net_topo_free(t);
}

/* max_hops sizes the route scratch: it must bound every route (a walk
 * from src to dst, but on the bus, one shared medium) and, for these
 * topologies, equal the longest one. */
static void expect_tight(NetTopo *t)
{
    gboolean walks = t->ops != &net_bus_ops;
    uint32_t n = net_topo_nodes(t);
    guint bound = t->ops->max_hops(t->state), longest = 0;
    NetLinkId *r = g_new(NetLinkId, bound + 1);
    for (uint32_t a = 0; a < n; a++)
        for (uint32_t b = 0; b < n; b++) {
            if (a == b)
                continue;
            guint h = t->ops->route(t->state, a, b, r);
            if (h < 1 || h > bound || (walks && !is_walk(t, a, b, r, h)))
                fail_msg("%s: route %u -> %u of %u hops", t->ops->name, a, b, h);
            longest = MAX(longest, h);
        }
    if (longest != bound)
        fail_msg("%s of %u nodes: max_hops %u, longest route %u",
                 t->ops->name, n, bound, longest);
    g_free(r);
    net_topo_free(t);
}

static void test_max_hops_tight(void **state)
{
    (void)state;
    for (unsigned d = 1; d <= 5; d++)
        expect_tight(net_hypercube_new(d));
    for (uint32_t n = 2; n <= 7; n++)
        expect_tight(net_ring_new(n));
    for (uint32_t n = 2; n <= 10; n++)
        for (unsigned k = 2; k <= 3; k++)
            expect_tight(net_fattree_new(n, k));
    expect_tight(net_crossbar_new(3));
    expect_tight(net_bus_new(3));
    expect_tight(net_cm200_new(2, 16, 8, 8));
    /* one node: no route, no scratch */
    NetTopo *one = net_hypercube_new(0);
    assert_int_equal(net_topo_nodes(one), 1);
    assert_int_equal(one->ops->max_hops(one->state), 0);
    net_topo_free(one);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fattree_up_down),
        cmocka_unit_test(test_ring_slots_order),
        cmocka_unit_test(test_torus_and_mesh),
        cmocka_unit_test(test_crossbar_bus),
        cmocka_unit_test(test_cm200_routes),
        cmocka_unit_test(test_max_hops_tight),
    };
    return cmocka_run_group_tests_name("net_topology", tests, NULL, NULL);
}
