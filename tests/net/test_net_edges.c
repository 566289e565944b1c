/* test_net_edges.c — boundaries of sim/net that mutation testing (make
 * mutate, docs/testing.md) showed unchecked: every route of every
 * topology (small and odd shapes, both directions) is a walk from src to
 * dst of the documented hop count over distinct links; the contention-
 * free time of a message to itself, of 0 and 1 bytes; fat-tree levels
 * past the last configured one; the hotspot pattern's skew; traffic
 * checks at their limits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "sim/net/net.h"
#include "sim/net/traffic.h"
#include "tests/support.h"

static guint popcount(uint32_t x)
{
    guint n = 0;
    for (; x; x &= x - 1)
        n++;
    return n;
}

/* Checks the route src -> dst: h hops (want, unless want < 0) within
 * max_hops, a walk over distinct links with a name and a bandwidth. */
static void check_route(const NetTopo *t, uint32_t src, uint32_t dst, int want)
{
    NetLinkId r[64];
    guint max = t->ops->max_hops(t->state);
    assert_true(max <= G_N_ELEMENTS(r));
    guint h = t->ops->route(t->state, src, dst, r);
    if (want >= 0 && h != (guint)want)
        fail_msg("%s %u -> %u: %u hops, want %d", t->ops->name, src, dst, h,
                 want);
    assert_true(h >= 1 && h <= max);
    NetParams p = {0};
    p.bandwidth = 1e6;
    uint64_t at = src, a, b;
    for (guint i = 0; i < h; i++) {
        t->ops->link_ends(t->state, r[i], &a, &b);
        if (a != at)
            fail_msg("%s %u -> %u: hop %u leaves %" G_GUINT64_FORMAT
                     ", not %" G_GUINT64_FORMAT,
                     t->ops->name, src, dst, i, a, at);
        assert_true(a != b);
        at = b;
        for (guint j = 0; j < i; j++)
            assert_true(r[j] != r[i]);
        char name[64] = "";
        t->ops->link_name(t->state, r[i], name, sizeof name);
        assert_true(name[0] != '\0');
        assert_true(t->ops->link_bw(t->state, r[i], &p) > 0.0);
    }
    if (at != dst)
        fail_msg("%s %u -> %u ends at %" G_GUINT64_FORMAT, t->ops->name, src,
                 dst, at);
}

/* Distance along one mesh dimension, a -> b of extent e. */
static guint steps(uint32_t a, uint32_t b, uint32_t e, gboolean wrap)
{
    guint fwd = (b + e - a) % e, back = (a + e - b) % e;
    if (!wrap)
        return a <= b ? b - a : a - b;
    return MIN(fwd, back);
}

static void check_mesh(guint nd, const uint32_t *e, gboolean wrap)
{
    NetTopo *t = net_mesh_new(nd, e, wrap);
    uint32_t n = net_topo_nodes(t);
    uint32_t want_n = 1, sum = 0;
    for (guint k = 0; k < nd; k++) {
        want_n *= e[k];
        sum += e[k];
    }
    assert_int_equal(n, want_n);
    assert_int_equal(t->ops->max_hops(t->state), sum);
    char name[32];
    t->ops->link_name(t->state, 0, name, sizeof name); /* 0 -> +x */
    assert_string_equal(name, e[0] > 1 ? "n0->n1" : "n0->n0");
    for (uint32_t s = 0; s < n; s++)
        for (uint32_t d = 0; d < n; d++) {
            if (s == d)
                continue;
            guint want = 0, stride = 1, dir[3];
            for (guint k = 0; k < nd; k++) {
                uint32_t a = s / stride % e[k], b = d / stride % e[k];
                want += steps(a, b, e[k], wrap);
                /* forward on a tie round the torus */
                dir[k] = wrap ? (b + e[k] - a) % e[k] > (a + e[k] - b) % e[k]
                              : b < a;
                stride *= e[k];
            }
            check_route(t, s, d, (int)want);
            /* dimension order, each dimension in its one direction:
             * link id = node * 2 nd + 2 k + dir */
            NetLinkId r[64];
            guint h = t->ops->route(t->state, s, d, r);
            guint last_k = 0;
            for (guint i = 0; i < h; i++) {
                guint k = (guint)(r[i] % (2 * nd)) / 2;
                assert_true(k >= last_k);
                assert_int_equal(r[i] % 2, dir[k]);
                last_k = k;
            }
        }
    net_topo_free(t);
}

static void test_mesh_routes(void **state)
{
    (void)state;
    static const uint32_t shapes[][3] = {
        {2, 1, 1}, {5, 1, 1}, {4, 3, 1}, {1, 4, 1}, {3, 2, 2}, {2, 1, 3},
        {4, 1, 1}, {6, 2, 1},
    };
    static const guint dims[] = {1, 1, 2, 2, 3, 3, 1, 2};
    for (guint i = 0; i < G_N_ELEMENTS(dims); i++) {
        check_mesh(dims[i], shapes[i], FALSE);
        check_mesh(dims[i], shapes[i], TRUE);
    }
}

/* Every link of the route src -> dst is named "<p>from-><p>to". */
static void check_names(const NetTopo *t, uint32_t src, uint32_t dst,
                        const char *p)
{
    NetLinkId r[64];
    guint h = t->ops->route(t->state, src, dst, r);
    for (guint i = 0; i < h; i++) {
        uint64_t a, b;
        char name[48];
        t->ops->link_ends(t->state, r[i], &a, &b);
        t->ops->link_name(t->state, r[i], name, sizeof name);
        char *want = g_strdup_printf("%s%" G_GUINT64_FORMAT "->%s%"
                                     G_GUINT64_FORMAT, p, a, p, b);
        assert_string_equal(name, want);
        g_free(want);
    }
}

static void test_hypercube_ring_routes(void **state)
{
    (void)state;
    for (unsigned d = 1; d <= 4; d++) {
        NetTopo *t = net_hypercube_new(d);
        assert_int_equal(net_topo_nodes(t), 1u << d);
        assert_int_equal(t->ops->max_hops(t->state), d);
        for (uint32_t s = 0; s < (1u << d); s++)
            for (uint32_t x = 1; x < (1u << d); x++) {
                check_route(t, s, s ^ x, (int)popcount(x));
                check_names(t, s, s ^ x, "n");
            }
        net_topo_free(t);
    }
    for (uint32_t n = 2; n <= 5; n++) {
        NetTopo *t = net_ring_new(n);
        assert_int_equal(net_topo_nodes(t), n);
        assert_int_equal(t->ops->max_hops(t->state), n - 1);
        for (uint32_t s = 0; s < n; s++)
            for (uint32_t d = 0; d < n; d++)
                if (s != d) {
                    check_route(t, s, d, (int)((d + n - s) % n));
                    check_names(t, s, d, "s");
                }
        net_topo_free(t);
    }
}

/* Fat trees whose leaf count is and is not a power of the arity. */
static void test_fattree_routes(void **state)
{
    (void)state;
    static const uint32_t nodes[] = {2, 3, 4, 5, 9, 10, 17};
    static const unsigned arity[] = {2, 2, 2, 2, 3, 3, 4};
    for (guint i = 0; i < G_N_ELEMENTS(nodes); i++) {
        NetTopo *t = net_fattree_new(nodes[i], arity[i]);
        guint levels = 0;
        for (uint64_t span = 1; span < nodes[i]; span *= arity[i])
            levels++;
        assert_int_equal(t->ops->max_hops(t->state), 2 * levels);
        for (uint32_t s = 0; s < nodes[i]; s++)
            for (uint32_t d = 0; d < nodes[i]; d++) {
                if (s == d)
                    continue;
                int m = 0;
                for (uint64_t span = 1; s / span != d / span; span *= arity[i])
                    m++;
                check_route(t, s, d, 2 * m);
            }
        net_topo_free(t);
    }
}


/* CM-200 hops: one NEWS link to a grid neighbour, else injection, the
 * routers' e-cube hops and ejection; link names and bandwidths by class
 * (ports at the base bandwidth, cube links level_bw[0], NEWS links
 * level_bw[1], 0 meaning the base). */
static void check_cm200(unsigned d, uint32_t g, uint32_t nx, uint32_t ny)
{
    NetTopo *c = net_cm200_new(d, g, nx, ny);
    uint32_t n = (1u << d) * g;
    assert_int_equal(net_topo_nodes(c), n);
    assert_int_equal(c->ops->max_hops(c->state), d + 2);
    NetParams p = {0}, q = {0};
    p.bandwidth = q.bandwidth = 1e6;
    p.level_bw[0] = 3e6;
    p.level_bw[1] = 5e6;
    for (uint32_t s = 0; s < n; s++)
        for (uint32_t t = 0; t < n; t++) {
            if (s == t)
                continue;
            uint32_t sx = s % nx, sy = s / nx, tx = t % nx, ty = t / nx;
            gboolean news = (sy == ty && (tx == (sx + 1) % nx ||
                                          sx == (tx + 1) % nx)) ||
                             (sx == tx && (ty == (sy + 1) % ny ||
                                           sy == (ty + 1) % ny));
            int want = news ? 1 : 2 + (int)popcount((s / g) ^ (t / g));
            check_route(c, s, t, want);
            NetLinkId r[32];
            guint h = c->ops->route(c->state, s, t, r);
            for (guint i = 0; i < h; i++) {
                char name[48];
                c->ops->link_name(c->state, r[i], name, sizeof name);
                const char *cls = news                  ? "news:"
                                  : i == 0 || i + 1 == h ? "port:"
                                                         : "cube:";
                double bw = news                  ? 5e6
                            : i == 0 || i + 1 == h ? 1e6
                                                   : 3e6;
                if (!g_str_has_prefix(name, cls))
                    fail_msg("%u -> %u hop %u: %s, want %s", s, t, i, name,
                             cls);
                assert_true(c->ops->link_bw(c->state, r[i], &p) == bw);
                assert_true(c->ops->link_bw(c->state, r[i], &q) == 1e6);
            }
        }
    net_topo_free(c);
}

static void test_crossbar_bus_cm200_routes(void **state)
{
    (void)state;
    NetTopo *x = net_crossbar_new(2), *b = net_bus_new(3);
    check_route(x, 0, 1, 2);
    check_route(x, 1, 0, 2);
    /* the bus is one shared link, vertex n to itself */
    NetLinkId r[1];
    uint64_t from, to;
    assert_int_equal(b->ops->max_hops(b->state), 1);
    assert_int_equal(b->ops->route(b->state, 2, 0, r), 1);
    assert_int_equal(r[0], 0);
    b->ops->link_ends(b->state, r[0], &from, &to);
    assert_int_equal(from, 3);
    assert_int_equal(to, 3);
    char name[8];
    b->ops->link_name(b->state, r[0], name, sizeof name);
    assert_string_equal(name, "bus");
    net_topo_free(x);
    net_topo_free(b);
    check_cm200(1, 4, 4, 2);
    check_cm200(3, 4, 8, 4);
    check_cm200(2, 1, 2, 2);
    /* NEWS grids whose sides are not powers of two: the -x and -y
     * neighbours wrap modulo 3 */
    check_cm200(1, 3, 3, 2);
    check_cm200(1, 3, 2, 3);
}

/* Exact link names and classes of a CM-200 of 2 routers x 4 processors on
 * a 4 x 2 NEWS grid: ports end at router 0 (vertex P) as "r0", cube links
 * join routers, NEWS links join grid neighbours; a level bandwidth of
 * exactly 1 B/s is used as given (only 0 means the base bandwidth). */
static void test_cm200_names(void **state)
{
    (void)state;
    NetTopo *c = net_cm200_new(1, 4, 4, 2);
    NetLinkId r[4];
    char name[48];
    const char *want[] = {"port:p0->r0", "cube:r0->r1", "port:r1->p5"};
    assert_int_equal(c->ops->route(c->state, 0, 5, r), 3);
    for (guint i = 0; i < 3; i++) {
        c->ops->link_name(c->state, r[i], name, sizeof name);
        assert_string_equal(name, want[i]);
    }
    assert_int_equal(c->ops->route(c->state, 5, 0, r), 3);
    c->ops->link_name(c->state, r[2], name, sizeof name);
    assert_string_equal(name, "port:r0->p0");
    /* 0 -> 3 is the -x NEWS neighbour (wrap), 0 -> 4 the +y one */
    assert_int_equal(c->ops->route(c->state, 0, 3, r), 1);
    c->ops->link_name(c->state, r[0], name, sizeof name);
    assert_string_equal(name, "news:p0->p3");
    assert_int_equal(r[0], 2 * 8 + 2 * 1 + 4 * 0 + 1);
    assert_int_equal(c->ops->route(c->state, 0, 4, r), 1);
    assert_int_equal(r[0], 18 + 2);
    NetParams p = {0};
    p.bandwidth = 1e6;
    p.level_bw[0] = 1.0;
    p.level_bw[1] = 1.0;
    assert_true(c->ops->link_bw(c->state, 18 + 2, &p) == 1.0);
    assert_true(c->ops->link_bw(c->state, 16, &p) == 1.0); /* cube r0->r1 */
    assert_true(c->ops->link_bw(c->state, 15, &p) == 1e6); /* ejection p7 */
    net_topo_free(c);
}

static NetParams params(void)
{
    NetParams p = {0};
    p.bandwidth = 1e6; /* 1 us a byte */
    p.channels = 1;
    p.startup = 50 * SIM_US;
    p.per_hop = 7 * SIM_US;
    p.packet_bytes = 100;
    p.switching = NET_SW_CUT_THROUGH;
    return p;
}

typedef struct {
    SimTime at; /* arrival - sending */
    guint hops;
    guint n;
} Got;

static void got(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Got *g = ctx;
    g->at = d->arrived - d->sent;
    g->hops = d->hops;
    g->n++;
}

/* A message to itself costs the start-up only, whatever the topology
 * (a crossbar or bus route would otherwise take hops), at every
 * fidelity; a 1-byte message pays its byte, a 0-byte one none. */
static void test_self_and_tiny_messages(void **state)
{
    (void)state;
    NetTopo *topos[] = {net_crossbar_new(4), net_bus_new(4),
                        net_fattree_new(4, 2), net_cm200_new(1, 2, 2, 2),
                        net_hypercube_new(2), net_ring_new(4)};
    NetParams p = params();
    for (guint i = 0; i < G_N_ELEMENTS(topos); i++) {
        for (NetFidelity f = NET_ANALYTIC; f <= NET_PACKET; f++) {
            SimEngine *eng = sim_engine_new(1);
            NetNet *net = net_new(eng, topos[i], &p, f);
            assert_int_equal(net_ideal_time(net, 2, 2, 1000), 50 * SIM_US);
            Got g = {0};
            net_send(net, 2, 2, 1000, NULL, got, &g);
            assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
            assert_int_equal(g.n, 1);
            assert_int_equal(g.at, 50 * SIM_US);
            assert_int_equal(g.hops, 0);
            NetLinkId r[16];
            guint h = topos[i]->ops->route(topos[i]->state, 0, 3, r);
            SimTime base = 50 * SIM_US + h * 7 * SIM_US;
            assert_int_equal(net_ideal_time(net, 0, 3, 0), base);
            double bw = topos[i]->ops->link_bw(topos[i]->state, r[0], &p);
            for (guint k = 1; k < h; k++)
                bw = MIN(bw, topos[i]->ops->link_bw(topos[i]->state, r[k], &p));
            assert_int_equal(net_ideal_time(net, 0, 3, 1),
                             base + sim_time_for_bytes(1.0, bw));
            assert_true(net_ideal_time(net, 0, 3, 1) > base);
            g = (Got){0};
            net_send(net, 0, 3, 1, NULL, got, &g);
            assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
            assert_int_equal(g.at, base + sim_time_for_bytes(1.0, bw));
            assert_int_equal(g.hops, h);
            net_free(net);
            sim_engine_free(eng);
        }
        net_topo_free(topos[i]);
    }
}

/* Levels at and past NET_MAX_LEVELS take the last configured level's
 * per-node bandwidth (times arity^level), or the base bandwidth when
 * that is 0.  A binary tree of 1,024 leaves has 10 levels. */
static void test_fattree_deep_levels(void **state)
{
    (void)state;
    NetTopo *t = net_fattree_new(1024, 2);
    NetParams p = params();
    for (guint l = 0; l < NET_MAX_LEVELS; l++)
        p.level_bw[l] = 1000.0 * (l + 1);
    NetLinkId r[32];
    guint h = t->ops->route(t->state, 0, 1023, r);
    assert_int_equal(h, 20);
    for (guint l = 0; l < 10; l++) { /* up links are r[0 .. 9] */
        double want = (l < NET_MAX_LEVELS ? 1000.0 * (l + 1) : 8000.0) *
                      (double)(1u << l);
        assert_true(t->ops->link_bw(t->state, r[l], &p) == want);
        assert_true(t->ops->link_bw(t->state, r[19 - l], &p) == want);
    }
    p.level_bw[NET_MAX_LEVELS - 1] = 0.0;
    assert_true(t->ops->link_bw(t->state, r[9], &p) == 1e6 * 512);
    assert_true(t->ops->link_bw(t->state, r[7], &p) == 1e6 * 128);
    assert_true(t->ops->link_bw(t->state, r[6], &p) == 7000.0 * 64);
    net_topo_free(t);
}

/* Messages delivered to node d on a crossbar: its output port's count. */
static uint64_t received(const NetNet *net, uint32_t d)
{
    const SimLinkStats *s = net_link_stats(net, 2 * (NetLinkId)d + 1);
    return s ? s->messages : 0;
}

static void run_lists(NetTraffic t, uint64_t *to0, uint64_t *max_other)
{
    NetTopo *x = net_crossbar_new(16);
    NetParams p = params();
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, x, &p, NET_ANALYTIC);
    net_traffic_start(net, t, 10, 7, NULL, NULL);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(net_delivered(net), 16 * 15);
    *to0 = received(net, 0);
    *max_other = 0;
    uint64_t all = *to0;
    for (uint32_t d = 1; d < 16; d++) {
        *max_other = MAX(*max_other, received(net, d));
        all += received(net, d);
    }
    /* no message is to its sender: each crosses its sender's input port
     * (link 2s), 15 a node, and its receiver's output port */
    assert_int_equal(all, 16 * 15);
    for (uint32_t s = 0; s < 16; s++)
        assert_int_equal(net_link_stats(net, 2 * (NetLinkId)s)->messages, 15);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(x);
}

/* Hotspot sends about a quarter of the messages to node 0 (15 x 15 x
 * 0.3, about 67); random spreads them (about 15 a node). */
static void test_hotspot_skew(void **state)
{
    (void)state;
    uint64_t hot0, hot_max, rnd0, rnd_max;
    run_lists(NET_TRAFFIC_HOTSPOT, &hot0, &hot_max);
    run_lists(NET_TRAFFIC_RANDOM, &rnd0, &rnd_max);
    assert_true(hot0 > 45 && hot0 > 2 * hot_max);
    assert_true(rnd0 < 30 && rnd_max < 30);
}

static void test_traffic_limits(void **state)
{
    (void)state;
    for (int t = 0; t <= NET_TRAFFIC_HOTSPOT; t++) {
        NetTraffic k = (NetTraffic)t, back;
        gboolean pow2 = k == NET_TRAFFIC_XOR || k == NET_TRAFFIC_PAIRWISE;
        assert_true(net_traffic_parse(net_traffic_name(k), &back));
        assert_int_equal(back, k);
        assert_false(net_traffic_check(k, 0, NULL));
        assert_false(net_traffic_check(k, 1, NULL));
        assert_true(net_traffic_check(k, 2, NULL));
        assert_int_equal(net_traffic_check(k, 3, NULL), !pow2);
        assert_true(net_traffic_check(k, 4, NULL));
        assert_true(net_traffic_check(k, NET_TRAFFIC_MAX_NODES, NULL));
        assert_int_equal(net_traffic_check(k, NET_TRAFFIC_MAX_NODES - 1, NULL),
                         !pow2);
        GError *err = NULL;
        assert_false(net_traffic_check(k, NET_TRAFFIC_MAX_NODES + 1, &err));
        char *want = g_strdup_printf(
            "found pattern %s on 65537 nodes, expected %s from 2 to 65536 "
            "nodes",
            net_traffic_name(k), pow2 ? "a power of two" : "a node count");
        assert_string_equal(err->message, want);
        g_free(want);
        g_error_free(err);
    }
    NetTraffic out = NET_TRAFFIC_SHIFT;
    assert_false(net_traffic_parse(NULL, &out));
    assert_false(net_traffic_parse("", &out));
    assert_false(net_traffic_parse("hotspots", &out));
    assert_int_equal(out, NET_TRAFFIC_SHIFT);
    assert_int_equal(net_traffic_messages(NET_TRAFFIC_PAIRWISE, 2), 2);
    assert_int_equal(net_traffic_messages(NET_TRAFFIC_PAIRWISE, 65536),
                     65536ull * 16);
    assert_int_equal(net_traffic_messages(NET_TRAFFIC_SHIFT, 2), 2);
    assert_int_equal(net_traffic_messages(NET_TRAFFIC_ALLTOALL, 65536),
                     65536ull * 65535);
}


static void done_at(NetNet *net, void *ctx)
{
    *(SimTime *)ctx = sim_now(net_engine(net));
}

/* With a control network (CM-5) every collective it takes costs its
 * latency plus the payload at its bandwidth, or the latency alone when
 * it has no bandwidth or the payload is empty. */
static void test_control_network(void **state)
{
    (void)state;
    NetTopo *t = net_fattree_new(8, 2);
    NetParams p = params();
    p.ctrl_latency = 5 * SIM_US;
    p.ctrl_bandwidth = 1e6;
    for (int bw = 0; bw < 2; bw++) {
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, NET_FLOW);
        SimTime a = 0, b = 0, c = 0, d = 0, e = 0;
        net_broadcast(net, 3, 100, done_at, &a);
        net_allreduce(net, 1, done_at, &b);
        net_prefix_sum(net, 10, done_at, &c);
        net_barrier(net, done_at, &d);
        net_broadcast(net, 0, 0, done_at, &e);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        SimTime per_byte = bw ? 0 : SIM_US;
        assert_int_equal(a, 5 * SIM_US + 100 * per_byte);
        assert_int_equal(b, 5 * SIM_US + 1 * per_byte);
        assert_int_equal(c, 5 * SIM_US + 10 * per_byte);
        assert_int_equal(d, 5 * SIM_US);
        assert_int_equal(e, 5 * SIM_US);
        assert_int_equal(net_total_messages(net), 0);
        net_free(net);
        sim_engine_free(eng);
        p.ctrl_bandwidth = 0.0;
    }
    net_topo_free(t);
    net_topo_free(NULL);
}

/* Max-min with flows of different bounds on a shared link: on a binary
 * fat tree with 10 MB/s leaves and 1 MB/s a node at level 1 (2 MB/s a
 * link), 0 -> 2 is held to 2 MB/s by its level-1 links and 0 -> 1 takes
 * the leaf link's other 8 MB/s; 3 -> 1 (2 MB/s at level 1 too) shares
 * 1's down link with 0 -> 1, which has 8 MB/s left there as well.
 * Rates: 0->2 2, 0->1 8, 3->1 2 (MB/s): all end at 1 s. */
static void test_flow_mixed_bounds(void **state)
{
    (void)state;
    NetTopo *t = net_fattree_new(4, 2);
    NetParams p = {0};
    p.bandwidth = 10e6;
    p.channels = 1;
    p.level_bw[0] = 10e6;
    p.level_bw[1] = 1e6;
    p.switching = NET_SW_CUT_THROUGH; /* max-min (circuits serialise) */
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_FLOW);
    Got a = {0}, b = {0}, c = {0};
    net_send(net, 0, 2, 2000000, NULL, got, &a);
    net_send(net, 0, 1, 8000000, NULL, got, &b);
    net_send(net, 3, 1, 2000000, NULL, got, &c);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_true(llabs((long long)a.at - (long long)SIM_S) < 10);
    assert_true(llabs((long long)b.at - (long long)SIM_S) < 10);
    assert_true(llabs((long long)c.at - (long long)SIM_S) < 10);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

/* A net freed with messages still in flight frees them (the leak
 * checker of make check and make mutate sees one left behind), at every
 * rung; at packet level under each switching, packets queued on links
 * included (packet.c's block of a message's packets).  Freed at 60 us,
 * in their start-up (71 us for 3 hops), and at 200 us, moving (the flow
 * rung's flows in its end heap). */
static void test_free_in_flight(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(3);
    NetParams p = params();
    for (int j = 0; j < 2 * (2 + 4); j++) {
        int k = j / 2;
        SimTime until = (j % 2 ? 200 : 60) * SIM_US;
        NetFidelity f = k < 2 ? (NetFidelity)k : NET_PACKET;
        const NetSwitching sw[] = {NET_SW_CUT_THROUGH, NET_SW_STORE_FORWARD,
                                   NET_SW_CIRCUIT, NET_SW_RING_SLOTS};
        p.switching = k < 2 ? NET_SW_CUT_THROUGH : sw[k - 2];
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, f);
        Got g = {0};
        for (uint32_t i = 0; i < 8; i++)
            net_send(net, i, 7 - i, 100000, NULL, got, &g);
        assert_true(sim_engine_run(eng, until, NULL));
        assert_int_equal(g.n, 0);
        net_free(net);
        sim_engine_free(eng);
    }
    net_topo_free(t);
}

/* The busiest link: most bytes, the lowest id on ties, a link that
 * carried only empty messages still counts; the result gets its name. */
static void test_busiest_and_result(void **state)
{
    (void)state;
    NetTopo *t = net_ring_new(6);
    NetParams p = params();
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
    NetLinkId l = 99;
    assert_false(net_busiest_link(net, &l));
    SimResult *r = sim_result_new("w", "m");
    r->busiest_link = g_strdup("stale");
    r->busiest_link_bytes = 7;
    net_fill_result(net, r);
    assert_null(r->busiest_link);
    assert_int_equal(r->busiest_link_bytes, 0);
    assert_string_equal(r->fidelity, "analytic");
    net_send(net, 4, 5, 0, NULL, NULL, NULL);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_true(net_busiest_link(net, &l));
    assert_int_equal(l, 4);
    net_send(net, 3, 4, 100, NULL, NULL, NULL); /* links 3 */
    net_send(net, 1, 2, 100, NULL, NULL, NULL); /* and 1: a tie */
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_true(net_busiest_link(net, &l));
    assert_int_equal(l, 1);
    net_send(net, 3, 4, 1, NULL, NULL, NULL);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_true(net_busiest_link(net, &l));
    assert_int_equal(l, 3);
    net_fill_result(net, r);
    assert_string_equal(r->busiest_link, "s3->s4");
    assert_int_equal(r->busiest_link_bytes, 101);
    assert_int_equal(r->comm_bytes, 201);
    assert_int_equal(r->comm_messages, 4);
    assert_int_equal(net_delivered(net), 4);
    assert_int_equal(net_links_touched(net), 3);
    assert_null(net_link_stats(net, 0));
    assert_int_equal(net_link_stats(net, 4)->messages, 1);
    assert_int_equal(net_link_stats(net, 4)->bytes, 0);
    sim_result_free(r);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

static void test_fidelity_names(void **state)
{
    (void)state;
    for (NetFidelity f = NET_ANALYTIC; f <= NET_PACKET; f++) {
        NetFidelity back = NET_PACKET - f;
        assert_true(net_fidelity_parse(net_fidelity_name(f), &back));
        assert_int_equal(back, f);
    }
    NetFidelity x = NET_FLOW;
    assert_false(net_fidelity_parse("packets", &x));
    assert_false(net_fidelity_parse("", &x));
    assert_int_equal(x, NET_FLOW);
    assert_string_equal(net_fidelity_name(NET_PACKET), "packet");
}

/* The long-message start-up applies strictly above the threshold. */
static void test_long_threshold_edge(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(1);
    NetParams p = params();
    p.startup_long = 500 * SIM_US;
    p.long_threshold = 1000;
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
    assert_int_equal(net_ideal_time(net, 0, 1, 1000),
                     50 * SIM_US + 7 * SIM_US + 1000 * SIM_US);
    assert_int_equal(net_ideal_time(net, 0, 1, 1001),
                     500 * SIM_US + 7 * SIM_US + 1001 * SIM_US);
    assert_int_equal(net_ideal_time(net, 1, 1, 1001), 500 * SIM_US);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
}

static SimTime collective_done;
static int collective_calls;

static void coll_done(NetNet *net, void *ctx)
{
    (void)ctx;
    collective_done = sim_now(net_engine(net));
    collective_calls++;
}

/* Messages a node sent / received on a crossbar: its in / out port. */
static uint64_t port(const NetNet *net, uint32_t node, int out)
{
    const SimLinkStats *st = net_link_stats(net, 2 * (NetLinkId)node + out);
    return st ? st->messages : 0;
}

/* Binomial broadcast on a crossbar (every message the same time T):
 * ceil(log2 n) rounds, n - 1 messages; relative rank r receives once,
 * from r - 2^hb(r), and sends to r + 2^k for every k above its highest
 * bit with r + 2^k < n (the root: every k). */
static void test_broadcast_exact(void **state)
{
    (void)state;
    static const uint32_t ns[] = {2, 3, 5, 8, 13};
    for (guint a = 0; a < G_N_ELEMENTS(ns); a++) {
        uint32_t n = ns[a];
        guint rounds = 0;
        while ((1u << rounds) < n)
            rounds++;
        uint32_t roots[] = {0, n / 2, n - 1};
        for (guint b = 0; b < 3; b++) {
            NetTopo *t = net_crossbar_new(n);
            NetParams p = params();
            SimEngine *eng = sim_engine_new(1);
            NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
            SimTime T = net_ideal_time(net, 0, 1, 40);
            collective_calls = 0;
            net_broadcast(net, roots[b], 40, coll_done, NULL);
            assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
            assert_int_equal(collective_calls, 1);
            assert_int_equal(collective_done, rounds * T);
            assert_int_equal(net_total_messages(net), n - 1);
            for (uint32_t i = 0; i < n; i++) {
                uint32_t r = (i + n - roots[b]) % n;
                guint hb = 0, sends = 0;
                while (r >> (hb + 1))
                    hb++;
                for (guint k = r ? hb + 1 : 0; k < rounds; k++)
                    sends += r + (1u << k) < n;
                assert_int_equal(port(net, i, 1), r ? 1 : 0);
                assert_int_equal(port(net, i, 0), sends);
            }
            net_free(net);
            sim_engine_free(eng);
            net_topo_free(t);
        }
    }
}

/* Recursive doubling on a crossbar: log2 n rounds, every node sends and
 * receives one message a round; a barrier sends empty ones. */
static void test_doubling_exact(void **state)
{
    (void)state;
    for (unsigned d = 1; d <= 4; d++) {
        uint32_t n = 1u << d;
        NetTopo *t = net_crossbar_new(n);
        NetParams p = params();
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, NET_FLOW);
        SimTime T = net_ideal_time(net, 0, 1, 16);
        net_allreduce(net, 16, coll_done, NULL);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(collective_done, d * T);
        assert_int_equal(net_total_messages(net), (uint64_t)n * d);
        assert_int_equal(net_total_bytes(net), (uint64_t)n * d * 16);
        for (uint32_t i = 0; i < n; i++) {
            assert_int_equal(port(net, i, 0), d);
            assert_int_equal(port(net, i, 1), d);
        }
        SimTime t0 = sim_now(eng);
        net_barrier(net, coll_done, NULL);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(collective_done - t0,
                         d * net_ideal_time(net, 0, 1, 0));
        assert_int_equal(net_total_bytes(net), (uint64_t)n * d * 16);
        t0 = sim_now(eng);
        net_prefix_sum(net, 3, coll_done, NULL);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(collective_done - t0,
                         d * net_ideal_time(net, 0, 1, 3));
        net_free(net);
        sim_engine_free(eng);
        net_topo_free(t);
    }
}

/* All-to-all schedules on n = 5 (not a power of two for naive and
 * shift): every ordered pair once, zero-byte entries skipped; xor on 8
 * sends its zero entries as empty messages. */
static void test_alltoall_counts(void **state)
{
    (void)state;
    for (int sched = 0; sched < 3; sched++) {
        NetA2ASchedule sc = (NetA2ASchedule)sched;
        uint32_t n = sc == NET_A2A_XOR ? 8 : 5;
        NetTopo *t = net_crossbar_new(n);
        NetParams p = params();
        SimEngine *eng = sim_engine_new(1);
        NetNet *net = net_new(eng, t, &p, NET_ANALYTIC);
        uint64_t *b = g_new0(uint64_t, (gsize)n * n);
        uint64_t sum = 0, nonzero = 0;
        for (uint32_t i = 0; i < n; i++)
            for (uint32_t j = 0; j < n; j++) {
                b[i * n + j] = i == j || (i + j) % 3 == 0 ? 0 : 10 + i + j;
                sum += b[i * n + j];
                nonzero += b[i * n + j] > 0;
            }
        collective_calls = 0;
        net_alltoall(net, b, sc, coll_done, NULL);
        assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
        assert_int_equal(collective_calls, 1);
        assert_int_equal(net_total_bytes(net), sum);
        assert_int_equal(net_total_messages(net),
                         sc == NET_A2A_XOR ? (uint64_t)n * (n - 1) : nonzero);
        for (uint32_t j = 0; j < n; j++) {
            uint64_t in = 0;
            for (uint32_t i = 0; i < n; i++)
                in += sc == NET_A2A_XOR ? i != j : b[i * n + j] > 0;
            assert_int_equal(port(net, j, 1), in);
        }
        g_free(b);
        net_free(net);
        sim_engine_free(eng);
        net_topo_free(t);
    }
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mesh_routes),
        cmocka_unit_test(test_hypercube_ring_routes),
        cmocka_unit_test(test_fattree_routes),
        cmocka_unit_test(test_crossbar_bus_cm200_routes),
        cmocka_unit_test(test_cm200_names),
        cmocka_unit_test(test_self_and_tiny_messages),
        cmocka_unit_test(test_fattree_deep_levels),
        cmocka_unit_test(test_hotspot_skew),
        cmocka_unit_test(test_traffic_limits),
        cmocka_unit_test(test_control_network),
        cmocka_unit_test(test_flow_mixed_bounds),
        cmocka_unit_test(test_free_in_flight),
        cmocka_unit_test(test_busiest_and_result),
        cmocka_unit_test(test_fidelity_names),
        cmocka_unit_test(test_long_threshold_edge),
        cmocka_unit_test(test_broadcast_exact),
        cmocka_unit_test(test_doubling_exact),
        cmocka_unit_test(test_alltoall_counts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
