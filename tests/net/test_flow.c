/* test_flow.c — the incremental flow transport against a slow reference.
 *
 * The reference is a from-scratch fluid simulation written for this test:
 * at every start or end it recomputes max-min rates of all active flows by
 * naive progressive filling (scan every link for the least fair share,
 * O(flows x links) per round) and steps to the next event in doubles.
 * The transport (lazy bottleneck heap, component-local recomputation, an
 * end heap and one engine timer) must give the same arrival time for every
 * message, to within a nanosecond, on random traffic with staggered
 * starts, on a hypercube with one and with two channels per link, and on
 * a fat tree whose levels have different bandwidths (different bounds).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <math.h>

#include "sim/core/rng.h"
#include "sim/net/net.h"
#include "tests/support.h"

#define NMSG 60
#define MAXH 16

typedef struct {
    uint32_t src, dst;
    uint64_t bytes;
    SimTime start; /* net_send() time */
    NetLinkId path[MAXH];
    guint hops;
    double bound;     /* B/s: least channel bandwidth on the path */
    double active_at; /* s: start + latency */
    double rem, rate; /* reference state */
    double ref_end;   /* s */
    SimTime got;      /* arrival in the transport */
    gboolean live, over;
} Msg;

typedef struct {
    NetNet *net;
    Msg *m;
} SendCtx;

static void arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    ((Msg *)ctx)->got = d->arrived;
    assert_true(((Msg *)d->payload) == ctx);
}

static void send_at(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Msg *m = arg;
    net_send(ctx, m->src, m->dst, m->bytes, m, arrived, m);
}

/* ---- the reference ---- */

typedef struct {
    NetLinkId id;
    double cap, rem;
    guint unfixed;
} RefLink;

static RefLink *ref_link(GArray *links, NetLinkId id)
{
    for (guint i = 0; i < links->len; i++)
        if (g_array_index(links, RefLink, i).id == id)
            return &g_array_index(links, RefLink, i);
    return NULL;
}

static void ref_fix(GArray *links, Msg *m, double rate)
{
    m->rate = rate;
    m->over = TRUE;
    for (guint h = 0; h < m->hops; h++) {
        RefLink *l = ref_link(links, m->path[h]);
        l->rem -= rate;
        l->unfixed--;
    }
}

/* Naive progressive filling over the live messages. */
static void ref_rates(Msg *ms, guint n, GArray *links)
{
    for (guint i = 0; i < links->len; i++) {
        RefLink *l = &g_array_index(links, RefLink, i);
        l->rem = l->cap;
        l->unfixed = 0;
    }
    for (guint i = 0; i < n; i++) {
        ms[i].over = !ms[i].live;
        for (guint h = 0; ms[i].live && h < ms[i].hops; h++)
            ref_link(links, ms[i].path[h])->unfixed++;
    }
    for (;;) {
        double share = INFINITY, bound = INFINITY;
        RefLink *best = NULL;
        for (guint i = 0; i < links->len; i++) {
            RefLink *l = &g_array_index(links, RefLink, i);
            if (l->unfixed && l->rem / l->unfixed < share) {
                share = l->rem / l->unfixed;
                best = l;
            }
        }
        for (guint i = 0; i < n; i++)
            if (!ms[i].over && ms[i].bound < bound)
                bound = ms[i].bound;
        if (!best && bound == INFINITY)
            return;
        for (guint i = 0; i < n; i++) {
            Msg *m = &ms[i];
            if (m->over)
                continue;
            if (bound <= share && m->bound == bound) {
                ref_fix(links, m, bound);
                continue;
            }
            for (guint h = 0; bound > share && h < m->hops; h++)
                if (m->path[h] == best->id) {
                    ref_fix(links, m, share);
                    break;
                }
        }
    }
}

/* Steps the reference from event to event; fills ref_end. */
static void ref_run(Msg *ms, guint n, GArray *links)
{
    double t = 0.0;
    guint left = n;
    while (left > 0) {
        ref_rates(ms, n, links);
        double next = INFINITY;
        for (guint i = 0; i < n; i++) {
            if (ms[i].live)
                next = fmin(next, t + ms[i].rem / ms[i].rate);
            else if (ms[i].ref_end < 0 && ms[i].active_at > t)
                next = fmin(next, ms[i].active_at);
        }
        for (guint i = 0; i < n; i++) {
            Msg *m = &ms[i];
            if (m->live) {
                m->rem -= m->rate * (next - t);
                if (m->rem <= 1e-6 * (double)m->bytes) {
                    m->live = FALSE;
                    m->ref_end = next;
                    left--;
                }
            } else if (m->ref_end < 0 && m->active_at == next) {
                m->live = TRUE;
            }
        }
        t = next;
    }
}

/* ---- the comparison ---- */

static void fill_msgs(Msg *ms, const NetTopo *t, const NetParams *p,
                      uint64_t seed)
{
    SimRng rng;
    sim_rng_init(&rng, seed, 0);
    uint32_t n = net_topo_nodes(t);
    for (guint i = 0; i < NMSG; i++) {
        Msg *m = &ms[i];
        *m = (Msg){.ref_end = -1.0};
        m->src = (uint32_t)sim_rng_below(&rng, n);
        m->dst = (m->src + 1 + (uint32_t)sim_rng_below(&rng, n - 1)) % n;
        m->bytes = 200 + sim_rng_below(&rng, 5000);
        /* starts on a 100 us grid, so many begin together */
        m->start = sim_rng_below(&rng, 40) * 100 * SIM_US;
        m->hops = t->ops->route(t->state, m->src, m->dst, m->path);
        g_assert(m->hops <= MAXH);
        m->bound = INFINITY;
        for (guint h = 0; h < m->hops; h++)
            m->bound = fmin(m->bound, t->ops->link_bw(t->state, m->path[h], p));
        m->rem = (double)m->bytes;
        m->active_at =
            sim_time_to_s(m->start + p->startup + m->hops * p->per_hop);
    }
}

static GArray *ref_links(const Msg *ms, const NetTopo *t, const NetParams *p)
{
    GArray *links = g_array_new(FALSE, FALSE, sizeof(RefLink));
    for (guint i = 0; i < NMSG; i++)
        for (guint h = 0; h < ms[i].hops; h++) {
            if (ref_link(links, ms[i].path[h]))
                continue;
            double bw = t->ops->link_bw(t->state, ms[i].path[h], p);
            RefLink l = {ms[i].path[h], bw * p->channels, 0, 0};
            g_array_append_val(links, l);
        }
    return links;
}

static void compare(const NetTopo *t, const NetParams *p, uint64_t seed)
{
    Msg ms[NMSG];
    fill_msgs(ms, t, p, seed);
    SimEngine *eng = sim_engine_new(1);
    NetNet *net = net_new(eng, t, p, NET_FLOW);
    for (guint i = 0; i < NMSG; i++)
        sim_schedule_at(eng, ms[i].start, send_at, net, &ms[i]);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(net_delivered(net), NMSG);
    GArray *links = ref_links(ms, t, p);
    ref_run(ms, NMSG, links);
    for (guint i = 0; i < NMSG; i++) {
        double got = sim_time_to_s(ms[i].got);
        if (fabs(got - ms[i].ref_end) > 1e-9)
            fail_msg(
                "seed %" G_GUINT64_FORMAT " msg %u (%u->%u, %" G_GUINT64_FORMAT
                " B): flow %.12f s, reference %.12f s",
                seed, i, ms[i].src, ms[i].dst, ms[i].bytes, got, ms[i].ref_end);
    }
    g_array_free(links, TRUE);
    net_free(net);
    sim_engine_free(eng);
}

static NetParams params(uint32_t channels)
{
    NetParams p = {0};
    p.bandwidth = 1e6;
    p.channels = channels;
    p.startup = 30 * SIM_US;
    p.per_hop = 2 * SIM_US;
    p.switching = NET_SW_CUT_THROUGH;
    return p;
}

static void test_hypercube_one_channel(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(4);
    NetParams p = params(1);
    for (uint64_t seed = 1; seed <= 8; seed++)
        compare(t, &p, seed);
    net_topo_free(t);
}

/* Two channels: a link carries 2 bw, a message at most bw (its bound). */
static void test_hypercube_two_channels(void **state)
{
    (void)state;
    NetTopo *t = net_hypercube_new(4);
    NetParams p = params(2);
    for (uint64_t seed = 11; seed <= 18; seed++)
        compare(t, &p, seed);
    net_topo_free(t);
}

/* Per-level bandwidths: flows have different bounds. */
static void test_fattree_levels(void **state)
{
    (void)state;
    NetTopo *t = net_fattree_new(16, 4);
    NetParams p = params(1);
    p.level_bw[0] = 2e6;
    p.level_bw[1] = 0.5e6;
    for (uint64_t seed = 21; seed <= 28; seed++)
        compare(t, &p, seed);
    net_topo_free(t);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hypercube_one_channel),
        cmocka_unit_test(test_hypercube_two_channels),
        cmocka_unit_test(test_fattree_levels),
    };
    return cmocka_run_group_tests_name("net_flow", tests, NULL, NULL);
}
