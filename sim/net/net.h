/* net.h — message transport over an interconnect, at three fidelities.
 *
 * A NetNet moves messages between the nodes of a topology (topology.h)
 * inside a SimEngine.  net_send() returns at once; the arrive callback
 * runs at the simulated arrival time with the caller's payload.  The
 * caller never knows which fidelity runs:
 *
 *   NET_ANALYTIC  startup + hops * per_hop + bytes / bottleneck bandwidth;
 *                 no contention.  One event per message.
 *   NET_FLOW      the same latency, then max-min fair sharing of link
 *                 bandwidth among the messages in flight (the fluid model
 *                 of SimGrid: Velho et al., "On the validity of flow-level
 *                 TCP network models for grid and cloud simulations", ACM
 *                 TOMACS 23(4), 2013).  Rates are recomputed only when a
 *                 message starts or ends, and only over the connected
 *                 component of links and flows it touches.
 *   NET_PACKET    the machine's own switching (NetParams.switching):
 *                 circuit switching (iPSC/2 DCM), packets with per-link
 *                 FIFOs (cut-through or store-and-forward), ring slots
 *                 (Pixel-Planes 5).
 *
 * Invariants: a lone message takes the same time at every fidelity; links
 * get state (stats, queues, flows) only when a message first uses them;
 * with the same inputs every run makes the same events in the same order.
 *
 * Ownership: the engine and topology are borrowed and must outlive the
 * NetNet; params are copied; payloads are borrowed and handed back.
 */
#ifndef PGSIM_NET_NET_H
#define PGSIM_NET_NET_H

#include "sim/core/engine.h"
#include "sim/core/result.h"
#include "sim/core/stats.h"
#include "sim/net/topology.h"

typedef enum { NET_ANALYTIC, NET_FLOW, NET_PACKET } NetFidelity;

typedef struct NetNet NetNet;

/* What the arrive callback receives (borrowed for the call only). */
typedef struct {
    uint32_t src, dst;
    uint64_t bytes;
    void *payload;
    SimTime sent;    /* when net_send() was called */
    SimTime arrived; /* now */
    guint hops;
} NetDelivery;

typedef void (*NetArriveFn)(NetNet *net, const NetDelivery *d, void *ctx);

/* Returns a new network; free with net_free(). */
NetNet *net_new(SimEngine *eng, const NetTopo *topo, const NetParams *params,
                NetFidelity fid);
void net_free(NetNet *net);
/* obj is freed by free_fn when the net is freed, unless net_disown()
 * took it back first: for objects (collectives) that a run stopped early
 * leaves unfinished.  Messages in flight are freed by the net itself. */
void net_own(NetNet *net, void *obj, GDestroyNotify free_fn);
void net_disown(NetNet *net, void *obj);

/* Sends `bytes` from src to dst; cb(net, delivery, ctx) runs at arrival.
 * src == dst delivers after the start-up only.  cb may be NULL. */
void net_send(NetNet *net, uint32_t src, uint32_t dst, uint64_t bytes,
              void *payload, NetArriveFn cb, void *ctx);

SimEngine *net_engine(const NetNet *net);
const NetTopo *net_topo(const NetNet *net);
const NetParams *net_params(const NetNet *net);
NetFidelity net_fidelity(const NetNet *net);
uint32_t net_nodes(const NetNet *net);

/* The contention-free time of one message (the analytic model). */
SimTime net_ideal_time(const NetNet *net, uint32_t src, uint32_t dst,
                       uint64_t bytes);

/* "analytic" / "flow" / "packet"; parse returns FALSE on other words. */
const char *net_fidelity_name(NetFidelity f);
gboolean net_fidelity_parse(const char *s, NetFidelity *out);

/* Statistics.  Per-link stats exist only for links that carried traffic:
 * net_link_stats() returns NULL for the others.  Borrowed. */
const SimLinkStats *net_link_stats(const NetNet *net, NetLinkId l);
guint net_links_touched(const NetNet *net);
uint64_t net_total_bytes(const NetNet *net);
uint64_t net_total_messages(const NetNet *net);
uint64_t net_delivered(const NetNet *net);
/* Busiest link by bytes (lowest id on ties); FALSE if none carried any. */
gboolean net_busiest_link(const NetNet *net, NetLinkId *l);
/* Writes the link's name into buf (n bytes). */
void net_link_name(const NetNet *net, NetLinkId l, char *buf, size_t n);
/* Copies comm_bytes, comm_messages, busiest_link(+bytes) into r. */
void net_fill_result(const NetNet *net, SimResult *r);
/* Bytes of memory held by the network's own structures (links, flows,
 * queues, messages in flight, topology state). */
size_t net_tracked_bytes(const NetNet *net);

#endif
