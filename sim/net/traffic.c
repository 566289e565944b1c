/* traffic.c — synthetic traffic patterns over the collectives (traffic.h).
 *
 * Each pattern starts one collective that computes a node's next message
 * when the node needs it: no n x n table.  Random destinations are a
 * counter-based hash of (seed, node, message index) (splitmix64, the
 * finaliser of sim/core/rng.h), so a seed gives the same lists whatever
 * the fidelity and the order in which nodes ask.  Memory: O(n) plus the
 * messages in flight (pairwise keeps its O(n log n) per-step table).
 */
#include "sim/net/traffic.h"
#include "sim/core/error.h"
#include "sim/core/rng.h"
#include <string.h>

static const char *const names[] = {"all-to-all", "shift",  "xor",
                                    "pairwise",   "random", "hotspot"};

const char *net_traffic_name(NetTraffic t)
{
    g_assert((unsigned)t < G_N_ELEMENTS(names));
    return names[t];
}

gboolean net_traffic_parse(const char *s, NetTraffic *out)
{
    for (unsigned i = 0; s && i < G_N_ELEMENTS(names); i++) {
        if (strcmp(s, names[i]) == 0) {
            *out = (NetTraffic)i;
            return TRUE;
        }
    }
    return FALSE;
}

const char *net_traffic_words(void)
{
    return "all-to-all, shift, xor, pairwise, random or hotspot";
}

static gboolean power_of_two(uint32_t n)
{
    return n > 0 && (n & (n - 1)) == 0;
}

gboolean net_traffic_check(NetTraffic t, uint32_t n, GError **err)
{
    gboolean pow2 = t == NET_TRAFFIC_XOR || t == NET_TRAFFIC_PAIRWISE;
    if (n >= 2 && n <= NET_TRAFFIC_MAX_NODES && (!pow2 || power_of_two(n)))
        return TRUE;
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "found pattern %s on %u nodes, expected %s from 2 to %u "
                "nodes",
                net_traffic_name(t), n,
                pow2 ? "a power of two" : "a node count",
                NET_TRAFFIC_MAX_NODES);
    return FALSE;
}

uint64_t net_traffic_messages(NetTraffic t, uint32_t n)
{
    if (t == NET_TRAFFIC_PAIRWISE)
        return (uint64_t)n * (g_bit_storage(n) - 1);
    return (uint64_t)n * (n - 1);
}

static void start_alltoall(NetNet *net, NetTraffic t, uint64_t bytes,
                           NetCollDone done, void *ctx)
{
    NetA2ASchedule s = t == NET_TRAFFIC_XOR     ? NET_A2A_XOR
                       : t == NET_TRAFFIC_SHIFT ? NET_A2A_SHIFT
                                                : NET_A2A_NAIVE;
    net_alltoall_uniform(net, bytes, s, done, ctx);
}

static void start_pairwise(NetNet *net, uint64_t bytes, NetCollDone done,
                           void *ctx)
{
    uint32_t n = net_nodes(net);
    unsigned d = (unsigned)g_bit_storage(n) - 1;
    uint64_t *b = g_new(uint64_t, (gsize)n * d);
    for (uint32_t i = 0; i < n; i++)
        for (unsigned s = 0; s < d; s++)
            b[(gsize)i * d + s] = bytes * (n >> (s + 1));
    net_pairwise_exchange(net, b, done, ctx);
    g_free(b);
}

/* Random and hotspot lists, generated when a node needs its next message. */
typedef struct {
    uint32_t n;
    gboolean hot;
    uint64_t bytes, seed;
    NetCollDone done;
    void *ctx;
} ListGen;

/* Uniform in [0, m) from one 64-bit hash (bias below m / 2^64). */
static uint32_t hash_below(uint64_t h, uint32_t m)
{
    return (uint32_t)(((unsigned __int128)h * m) >> 64);
}

/* Counter-based: message k of node i depends on (seed, i, k) only. */
static void list_next(void *ctx, uint32_t i, guint k, uint32_t *dst,
                      uint64_t *bytes)
{
    const ListGen *g = ctx;
    uint64_t h = sim_rng_mix(g->seed ^ sim_rng_mix(((uint64_t)i << 32) | k));
    uint32_t d = hash_below(h, g->n - 1);
    d = d >= i ? d + 1 : d; /* never self */
    if (g->hot && i != 0 && hash_below(sim_rng_mix(h), 4) == 0)
        d = 0;
    *dst = d;
    *bytes = g->bytes;
}

static void list_done(NetNet *net, void *ctx)
{
    ListGen g = *(ListGen *)ctx;
    g_free(ctx);
    if (g.done)
        g.done(net, g.ctx);
}

static void start_lists(NetNet *net, gboolean hot, uint64_t bytes,
                        uint64_t seed, NetCollDone done, void *ctx)
{
    ListGen *g = g_new(ListGen, 1);
    *g = (ListGen){net_nodes(net), hot, bytes, seed, done, ctx};
    net_send_generated(net, g->n - 1, list_next, g, list_done, g);
}

void net_traffic_start(NetNet *net, NetTraffic t, uint64_t bytes, uint64_t seed,
                       NetCollDone done, void *ctx)
{
    g_assert(net_traffic_check(t, net_nodes(net), NULL));
    switch (t) {
    case NET_TRAFFIC_PAIRWISE:
        start_pairwise(net, bytes, done, ctx);
        break;
    case NET_TRAFFIC_RANDOM:
    case NET_TRAFFIC_HOTSPOT:
        start_lists(net, t == NET_TRAFFIC_HOTSPOT, bytes, seed, done, ctx);
        break;
    default:
        start_alltoall(net, t, bytes, done, ctx);
    }
}
