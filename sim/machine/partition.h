/* partition.h — sizing a machine model to a number of network endpoints.
 *
 * `pgsim bench net --nodes N` (and any tool that wants "this machine, but
 * N nodes") asks for a partition: the same model with the node counts
 * that give its network N endpoints.  mach_partition() writes those
 * counts into a run config's `machine` section as --set-style overrides,
 * so the machine layer builds and checks the result as usual and reports
 * the overridden values as overrides (model.h).
 *
 * Rules, by topology:
 *   cm-router   endpoints are the SIMD lanes of the widest kind: lanes = N
 *               and router_nodes = N / procs_per_router, which must be a
 *               power of two;
 *   mesh/torus  N must equal the product of `extents` (the shape is the
 *               user's: --set machine.network.extents=[x, y]);
 *   otherwise   kinds of one processor (a host, a frame buffer) keep it;
 *               the others share the rest in proportion to their model
 *               counts, at least one each (Pixel-Planes 5, 32 stations:
 *               host 1, gp 15, renderer 15, frame buffer 1); a
 *               hypercube's optional `dimension` follows N.
 * Whether N suits the topology (a power of two on a hypercube ...) is
 * checked when the machine is built, with the override located.
 * Cost: O(size of the model).
 */
#ifndef PGSIM_MACHINE_PARTITION_H
#define PGSIM_MACHINE_PARTITION_H

#include "sim/core/cfg.h"

/* Adds to root's `machine` section (a map with model: or a whole model)
 * the overrides for `nodes` endpoints.  *desc (g_free; desc may be NULL)
 * gets the resulting counts ("host 1, gp 15, renderer 15, frame_buffer
 * 1"; "array lanes 256 = 16 routers x 16").
 * FALSE with *err if the section is unusable or N cannot be met. */
gboolean mach_partition(CfgNode *root, guint nodes, char **desc, GError **err);

/* A new run-config tree holding only `machine: {model: <model>}` with the
 * user's overrides `sets` (NULL-terminated, each "machine.KEY=VALUE",
 * applied in order) and, when nodes > 0, the partition for `nodes`
 * endpoints (*desc as for mach_partition()); for tools that run a machine
 * without a workload (`pgsim bench net`, `pgsim replay`).  `who` names
 * the tool in the error for an override outside machine.  NULL with *err
 * on an unknown model or a bad override (free with cfg_free()). */
CfgNode *mach_partition_root(const char *who, const char *model,
                             const char *const *sets, guint nodes,
                             char **desc, GError **err);

#endif
