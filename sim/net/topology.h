/* topology.h — interconnect topologies behind one small ops table.
 *
 * A topology is a NetTopo: a const ops table plus its private state.  It
 * answers, without allocating, how many nodes there are, the route from
 * one node to another as a sequence of directed link ids, what a link
 * joins, what it is called and how fast one channel of it is.  Link ids
 * are 64-bit and topology-defined; they are keys, never array indices, so
 * a topology's state is O(1) or O(dimensions) in size whatever its node
 * count ("model only what is touched": links get state in NetNet only
 * when a message uses them).
 *
 * Topologies (one .c each):
 *   hypercube  d dimensions, e-cube routing: differing address bits are
 *              corrected lowest dimension first (Sullivan & Bashkow 1977;
 *              the iPSC/2 DCM, Nugent, Proc. 3rd Conf. Hypercube
 *              Concurrent Computers, 1988).
 *   ring       unidirectional ring of stations (Pixel-Planes 5, Fuchs et
 *              al., SIGGRAPH 1989); parallel channels come from
 *              NetParams.channels.
 *   fat tree   k-ary fat tree with one aggregated link per subtree and
 *              level, up/down routing through the least common ancestor
 *              (Leiserson, IEEE Trans. Comput. 1985; CM-5 data network,
 *              Leiserson et al., SPAA 1992).
 *   cm200      hypercube of routers, each serving a group of processors,
 *              plus the NEWS grid for nearest-neighbour moves
 *              (Thinking Machines, CM-200 Technical Summary, 1991).
 *   mesh/torus dimension-order routing, up to 3 dimensions.
 *   crossbar   one input and one output port per node.
 *   bus        one shared link.
 *   group      endpoints in groups (the GPUs or processes of one node)
 *              joined by the group's switch, over any of the above
 *              between groups (group.c).
 *
 * Bandwidth numbers are never here: link_bw() derives a link's channel
 * bandwidth from NetParams, which the machine layer fills from YAML.
 */
#ifndef PGSIM_NET_TOPOLOGY_H
#define PGSIM_NET_TOPOLOGY_H

#include <glib.h>
#include <stdint.h>

typedef uint64_t NetLinkId;

#define NET_MAX_LEVELS 8

/* How a packet-level transport moves data on this machine. */
typedef enum {
    NET_SW_CIRCUIT,       /* whole path reserved before data (iPSC/2 DCM) */
    NET_SW_CUT_THROUGH,   /* packets, per-link FIFO, pipelined across hops */
    NET_SW_STORE_FORWARD, /* packets, per-link FIFO, whole packet per hop */
    NET_SW_RING_SLOTS     /* ring channels held station to station */
} NetSwitching;

/* Machine parameters of an interconnect, filled by the machine layer from
 * models/ YAML files (tests use their own values).  Plain data, copied by
 * net_new(). */
typedef struct {
    double bandwidth;  /* B/s of one channel of a base link */
    uint32_t channels; /* parallel channels per link (ring); >= 1 */
    /* Fat tree: B/s per node at each level (0 = leaves); 0 = bandwidth.
     * CM-200: level_bw[0] router cube links, level_bw[1] NEWS links. */
    double level_bw[NET_MAX_LEVELS];
    uint64_t startup; /* ps, per-message software start-up */
    /* Long-message protocol (iPSC/2 NX: request/acknowledge above a size,
     * Bomans & Roose 1989): a message of more than long_threshold bytes
     * pays startup_long instead of startup; startup_long 0 = none. */
    uint64_t startup_long;   /* ps */
    uint64_t long_threshold; /* bytes */
    uint64_t per_hop;        /* ps, per router / station traversed */
    uint32_t packet_bytes;   /* packet payload for packet transports */
    NetSwitching switching;
    /* Control network (CM-5): 0 = none; see collective.h. */
    uint64_t ctrl_latency; /* ps per combine / broadcast / barrier */
    double ctrl_bandwidth; /* B/s for the payload; 0 = latency only */
    /* Group topology (group.c): B/s of one channel of a link between an
     * endpoint and its group's switch; 0 = bandwidth. */
    double node_bw;
} NetParams;

typedef struct {
    const char *name; /* "hypercube", "ring" ... */
    uint32_t (*nodes)(const void *st);
    /* Upper bound on route length (size for route()'s out array). */
    guint (*max_hops)(const void *st);
    /* Writes the directed links from src to dst (src != dst) into out;
     * returns the hop count (>= 1). */
    guint (*route)(const void *st, uint32_t src, uint32_t dst, NetLinkId *out);
    /* Vertex ids (topology-defined: nodes, then routers/switches) that a
     * link joins. */
    void (*link_ends)(const void *st, NetLinkId l, uint64_t *from,
                      uint64_t *to);
    /* Human-readable name ("n3->n7", "up1.4"); writes at most n bytes. */
    void (*link_name)(const void *st, NetLinkId l, char *buf, size_t n);
    /* B/s of one channel of link l under parameters p. */
    double (*link_bw)(const void *st, NetLinkId l, const NetParams *p);
    void (*free)(void *st);
} NetTopologyOps;

typedef struct {
    const NetTopologyOps *ops;
    void *state;
    size_t state_bytes; /* size of *state, for memory accounting */
} NetTopo;

extern const NetTopologyOps net_hypercube_ops;
extern const NetTopologyOps net_ring_ops;
extern const NetTopologyOps net_fattree_ops;
extern const NetTopologyOps net_cm200_ops;
extern const NetTopologyOps net_mesh_ops;
extern const NetTopologyOps net_crossbar_ops;
extern const NetTopologyOps net_bus_ops;
extern const NetTopologyOps net_group_ops;

/* Constructors: each returns a new topology; free with net_topo_free(). */
NetTopo *net_hypercube_new(unsigned dims); /* 2^dims nodes */
NetTopo *net_ring_new(uint32_t stations);
/* arity-ary fat tree over `nodes` leaves (rounded up to a power). */
NetTopo *net_fattree_new(uint32_t nodes, unsigned arity);
/* 2^cube_dims routers x group processors; NEWS grid news_x x news_y
 * (news_x * news_y == processors), torus wrap. */
NetTopo *net_cm200_new(unsigned cube_dims, uint32_t group, uint32_t news_x,
                       uint32_t news_y);
/* ndims (1..3) extents; wrap: torus. */
NetTopo *net_mesh_new(unsigned ndims, const uint32_t *extent, gboolean wrap);
NetTopo *net_crossbar_new(uint32_t nodes);
NetTopo *net_bus_new(uint32_t nodes);
/* n endpoints in groups of `group` over `outer` (taken): per_endpoint,
 * outer has one node per endpoint (n of them); otherwise one per group,
 * ceil(n / group), the last possibly partial (group.c). */
NetTopo *net_group_new(NetTopo *outer, uint32_t group, gboolean per_endpoint,
                       uint32_t n);
/* The outer topology of a group topology (borrowed). */
const NetTopo *net_group_outer(const NetTopo *t);
void net_topo_free(NetTopo *t);

/* The start-up a message of `bytes` pays under p. */
static inline uint64_t net_startup(const NetParams *p, uint64_t bytes)
{
    return p->startup_long && bytes > p->long_threshold ? p->startup_long
                                                        : p->startup;
}

/* Convenience wrappers over the ops. */
static inline uint32_t net_topo_nodes(const NetTopo *t)
{
    return t->ops->nodes(t->state);
}

/* Wraps ops + state (taken) into a new NetTopo; for constructors. */
NetTopo *net_topo_wrap(const NetTopologyOps *ops, void *state,
                       size_t state_bytes);

#endif
