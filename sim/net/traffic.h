/* traffic.h — synthetic traffic patterns for comparing fidelities.
 *
 * Every pattern is a collective (collective.h), so it is traffic a
 * workload could send, and it is the same traffic at every fidelity: the
 * same messages, and on each node the same order, a node sending its next
 * message only when its previous one has been delivered.  Only the
 * transport differs (analytic, flow, packet).  Patterns on n nodes, B
 * bytes per message:
 *   all-to-all  naive personalized all-to-all: node i sends to 0, 1, 2 ...
 *               (skipping itself), so every node starts on node 0;
 *   shift       node i sends to i+1, i+2 ... (mod n);
 *   xor         at step k node i exchanges with i XOR k (link-disjoint
 *               under e-cube: Bokhari, ICASE 91-4, 1991); n = 2^d;
 *   pairwise    recursive halving, n * B / 2^(s+1) bytes at step s;
 *               n = 2^d;
 *   random      n-1 messages per node to uniform other nodes;
 *   hotspot     the same, but each message goes to node 0 with
 *               probability 1/4 (node 0's own go elsewhere).
 * Random draws: a hash of (seed, node, message index), so any node's k-th
 * destination is computed when it is needed.
 * Memory: O(n) plus the messages in flight; nothing grows with n^2.
 */
#ifndef PGSIM_NET_TRAFFIC_H
#define PGSIM_NET_TRAFFIC_H

#include "sim/net/collective.h"

typedef enum {
    NET_TRAFFIC_ALLTOALL,
    NET_TRAFFIC_SHIFT,
    NET_TRAFFIC_XOR,
    NET_TRAFFIC_PAIRWISE,
    NET_TRAFFIC_RANDOM,
    NET_TRAFFIC_HOTSPOT
} NetTraffic;

/* Largest node count a pattern accepts (a 16-cube; node ids and message
 * indices fit in 32 bits). */
#define NET_TRAFFIC_MAX_NODES 65536u

const char *net_traffic_name(NetTraffic t);
/* FALSE on an unknown word. */
gboolean net_traffic_parse(const char *s, NetTraffic *out);
/* "all-to-all, shift, xor, pairwise, random or hotspot" (static). */
const char *net_traffic_words(void);

/* Whether t can run on n nodes; FALSE with "found ..., expected ..." in
 * *err (a power of two for xor and pairwise, 2 .. 65,536 nodes). */
gboolean net_traffic_check(NetTraffic t, uint32_t n, GError **err);
/* Messages the pattern sends on n nodes. */
uint64_t net_traffic_messages(NetTraffic t, uint32_t n);

/* Starts the pattern on every node of net; done(net, ctx) runs when the
 * last message has been delivered.  Asserts net_traffic_check(). */
void net_traffic_start(NetNet *net, NetTraffic t, uint64_t bytes, uint64_t seed,
                       NetCollDone done, void *ctx);

#endif
