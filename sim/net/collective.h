/* collective.h — collective operations over a NetNet, with completion
 * callbacks.
 *
 * Every collective is a per-node step machine: at each step a node sends
 * at most one message (to a partner the schedule names, with the byte
 * count the caller gives) and waits for the messages the schedule says it
 * receives at that step; it moves to the next step when its own send has
 * been delivered and those receipts are in.  All nodes start when the
 * collective is called (per-node entry times are not modelled: put a
 * barrier or call it when every node is ready).  Messages go through
 * net_send(), so every fidelity applies; payload contents are the
 * caller's business, sizes are real.
 *
 * Schedules (n nodes; d = log2 n where a power of two is required):
 *   broadcast     binomial tree from root: at step k, nodes holding the
 *                 data send across dimension k (relative to root).
 *   allreduce     global sum by recursive doubling: at step k, exchange
 *                 with i ^ 2^k (n power of two).
 *   prefix sum    the same exchanges (Hillis & Steele on the hypercube:
 *                 Kumar et al., Introduction to Parallel Computing, 1994,
 *                 sec. 4.3); the local combine is the caller's.
 *   barrier       a zero-byte allreduce.
 *   all-to-all    personalized, one message at a time per node;
 *                 NET_A2A_NAIVE: node i sends to 0, 1, ... n-1 (skipping
 *                 itself), so all start on node 0; NET_A2A_SHIFT: to i+1,
 *                 i+2, ... (mod n); NET_A2A_XOR: at step
 *                 k = 1 .. n-1 node i exchanges with i ^ k, whose e-cube
 *                 routes are link-disjoint (Bokhari, "Complete exchange
 *                 on the iPSC-860", ICASE 91-4, 1991).
 *   pairwise      recursive halving: at step s, exchange with
 *                 i ^ 2^(d-1-s) the caller's bytes[i * d + s].
 *   send lists    each node sends its own list of (dst, bytes) messages
 *                 one after another (random, hotspot traffic).
 * If NetParams.ctrl_latency > 0 (the CM-5 control network, Leiserson et
 * al., SPAA 1992), broadcast, allreduce, prefix sum and barrier complete
 * after ctrl_latency + bytes / ctrl_bandwidth without touching the data
 * network (a fixed-latency tree).
 *
 * Memory: O(n) node state plus the messages in flight and the receipts
 * that arrived before their step (no n x n table unless the caller
 * passes one: net_alltoall_uniform and net_send_generated compute each
 * step's message when it starts).
 */
#ifndef PGSIM_NET_COLLECTIVE_H
#define PGSIM_NET_COLLECTIVE_H

#include "sim/net/net.h"

typedef enum { NET_A2A_NAIVE, NET_A2A_SHIFT, NET_A2A_XOR } NetA2ASchedule;

/* Called once when every node has finished. */
typedef void (*NetCollDone)(NetNet *net, void *ctx);

/* Node i's k-th message of a generated send list: writes *dst (!= i) and
 * *bytes.  Must be a pure function of (ctx, i, k): it may be called more
 * than once for the same message. */
typedef void (*NetGenFn)(void *ctx, uint32_t i, guint k, uint32_t *dst,
                         uint64_t *bytes);

void net_broadcast(NetNet *net, uint32_t root, uint64_t bytes, NetCollDone done,
                   void *ctx);
void net_allreduce(NetNet *net, uint64_t bytes, NetCollDone done, void *ctx);
void net_prefix_sum(NetNet *net, uint64_t bytes, NetCollDone done, void *ctx);
void net_barrier(NetNet *net, NetCollDone done, void *ctx);
/* bytes[i * n + j]: bytes from i to j (copied; zero entries still send a
 * zero-byte message under NET_A2A_XOR, none otherwise). */
void net_alltoall(NetNet *net, const uint64_t *bytes, NetA2ASchedule sched,
                  NetCollDone done, void *ctx);
/* The same with `bytes` between every pair (no matrix). */
void net_alltoall_uniform(NetNet *net, uint64_t bytes, NetA2ASchedule sched,
                          NetCollDone done, void *ctx);
/* Each node sends per_node messages gen(gen_ctx, i, 0 ..), one after
 * another (gen_ctx borrowed until done runs). */
void net_send_generated(NetNet *net, guint per_node, NetGenFn gen,
                        void *gen_ctx, NetCollDone done, void *ctx);
/* bytes[i * d + s]: what node i sends at step s (copied). */
void net_pairwise_exchange(NetNet *net, const uint64_t *bytes, NetCollDone done,
                           void *ctx);
/* Node i sends count[i] messages dst[off[i] + k], size[off[i] + k], in
 * order, each after the previous one is delivered (arrays copied;
 * off[i] = count[0] + ... + count[i-1]). */
void net_send_lists(NetNet *net, const uint32_t *count, const uint32_t *dst,
                    const uint64_t *size, NetCollDone done, void *ctx);

#endif
