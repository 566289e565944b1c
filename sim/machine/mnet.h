/* mnet.h — building a machine's network (sim/net) from its model.
 *
 * The `network` section of a checked model (model.h) becomes a NetTopo
 * and NetParams for net_new().  Endpoints are the machine's processors in
 * id order, except for the CM-200 router topology, whose endpoints are
 * router_nodes x procs_per_router SIMD processors.
 *
 * Topology words: hypercube (2^d endpoints, optional `dimension` check),
 * ring (stations = processors; `channels` parallel channels), fat-tree
 * (`arity`, per-level `level_bandwidth`), cm-router (lanes = router_nodes
 * x procs_per_router, NEWS grid as square as possible), mesh and torus
 * (`extents`: 1 to 3 counts whose product is the processor count;
 * dimension-order routing), crossbar, bus.  Cost: O(1).
 */
#ifndef PGSIM_MACHINE_MNET_H
#define PGSIM_MACHINE_MNET_H

#include "sim/core/cfg.h"
#include "sim/net/net.h"

/* Fills *out from the network section; FALSE with a located *err if a
 * value is unusable (no bandwidth, unknown switching word ...). */
gboolean mach_net_params(const CfgNode *network, NetParams *out, GError **err);

/* Whether mach_topo_new() can build this topology word yet. */
gboolean mach_topo_supported(const char *topology);

/* A new topology (net_topo_free) for `endpoints` processors, or NULL with
 * a located *err; an unusable endpoint count is reported at `count_at`
 * (the processor count that set it; NULL: at the topology). */
NetTopo *mach_topo_new(const CfgNode *network, guint endpoints,
                       const CfgNode *count_at, GError **err);

#endif
