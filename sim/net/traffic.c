/* traffic.c — synthetic traffic patterns over the collectives (traffic.h).
 *
 * Each pattern fills the byte matrix, per-step byte table or per-node
 * message lists of one collective and starts it.  Random destinations are
 * drawn node by node, message by message, from one stream, so a seed
 * gives the same lists whatever the fidelity.  Cost: O(n^2) to build the
 * tables, then the collective's own.
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
    uint32_t n = net_nodes(net);
    uint64_t *b = g_new(uint64_t, (gsize)n * n);
    for (gsize i = 0; i < (gsize)n * n; i++)
        b[i] = i / n == i % n ? 0 : bytes;
    NetA2ASchedule s = t == NET_TRAFFIC_XOR     ? NET_A2A_XOR
                       : t == NET_TRAFFIC_SHIFT ? NET_A2A_SHIFT
                                                : NET_A2A_NAIVE;
    net_alltoall(net, b, s, done, ctx);
    g_free(b);
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

static void start_lists(NetNet *net, gboolean hot, uint64_t bytes,
                        uint64_t seed, NetCollDone done, void *ctx)
{
    uint32_t n = net_nodes(net), per = n - 1;
    uint32_t *count = g_new(uint32_t, n), *dst = g_new(uint32_t, n * per);
    uint64_t *size = g_new(uint64_t, (gsize)n * per);
    SimRng rng;
    sim_rng_init(&rng, seed, 0);
    for (uint32_t i = 0; i < n; i++) {
        count[i] = per;
        for (uint32_t k = 0; k < per; k++) {
            uint32_t d = (uint32_t)sim_rng_below(&rng, n - 1);
            d = d >= i ? d + 1 : d; /* never self */
            if (hot && i != 0 && sim_rng_below(&rng, 4) == 0)
                d = 0;
            dst[(gsize)i * per + k] = d;
            size[(gsize)i * per + k] = bytes;
        }
    }
    net_send_lists(net, count, dst, size, done, ctx);
    g_free(count);
    g_free(dst);
    g_free(size);
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
