/* net_internal.h — shared between net.c and the transports (not public).
 *
 * NetLink is the lazily created state of one directed link: its traffic
 * statistics plus the fields each transport needs (flows crossing it for
 * the fluid model; holder and FIFO of waiters for circuits; free time for
 * packet FIFOs; per-channel holders for ring slots).  NetMsg is one
 * message in flight; it owns its path array (links borrowed from the
 * net's table) and a transport-private pointer.
 */
#ifndef PGSIM_NET_NET_INTERNAL_H
#define PGSIM_NET_NET_INTERNAL_H

#include "sim/net/net.h"

typedef struct NetMsg NetMsg;
typedef struct NetFlow NetFlow;

typedef struct {
    NetFlow *f;
    guint hop; /* index of this link in f's path */
} NetFlowRef;

typedef struct {
    NetLinkId id;
    SimLinkStats st;
    double bw; /* B/s per channel */
    uint32_t channels;
    /* flow transport */
    NetFlowRef *flows; /* active flows crossing the link */
    guint n_flows, cap_flows;
    uint64_t mark; /* component-search epoch */
    double rem;    /* max-min scratch: capacity left */
    guint unfixed; /* max-min scratch: flows not yet fixed */
    /* circuit / ring-slot / packet transports */
    NetMsg **holder; /* per channel, NULL when free (lazily allocated) */
    GQueue wait;     /* NetMsg * waiting for a channel, FIFO */
    SimTime free_at; /* packet FIFO: when the link is next free */
} NetLink;

struct NetMsg {
    NetNet *net;
    uint64_t seq;
    uint64_t rec_id; /* the recorder's id (sim/core/record.h), if any */
    uint32_t src, dst;
    uint64_t bytes;
    void *payload;
    NetArriveFn cb;
    void *ctx;
    SimTime sent;
    guint hops;
    double bw;      /* bottleneck channel bandwidth along the path */
    NetLink **path; /* hops links, borrowed from the net's table */
    guint step;     /* transport progress (links held, packets left) */
    uint32_t *chan; /* ring slots: channel held on each hop */
    void *tp;       /* transport-private state */
    NetMsg *live_prev, *live_next; /* messages in flight (net_free) */
};

/* A transport: started once per message after route lookup. */
typedef struct {
    const char *name;
    void (*start)(NetNet *net, NetMsg *m);
    void (*free)(NetNet *net);
} NetTransportOps;

extern const NetTransportOps net_analytic_transport;
extern const NetTransportOps net_flow_transport;
extern const NetTransportOps net_circuit_transport;
extern const NetTransportOps net_circuit_flow_transport;
extern const NetTransportOps net_packet_transport;
extern const NetTransportOps net_ringslot_transport;

/* Engine and parameters, for transports. */
SimEngine *net_eng(NetNet *net);
const NetParams *net_par(NetNet *net);
/* Transport-private state of the net (one pointer). */
void **net_tp_slot(NetNet *net);
/* Delivers m now: callback, trace, frees m. */
void net_msg_deliver(NetNet *net, NetMsg *m);
/* Latency part of the ideal time: startup (net_startup) + hops * per_hop. */
SimTime net_msg_latency(const NetNet *net, const NetMsg *m);
/* Adds n bytes to the net's memory accounting (negative to release). */
void net_account(NetNet *net, gssize n);

#endif
