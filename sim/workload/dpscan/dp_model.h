/* dp_model.h — the data-parallel cost model of a machine: the `dpscan:`
 * section of a machine model (models/cm200.yaml, models/cm5.yaml), read
 * from the machine the runner built (mach_model_cfg), which found the
 * model on the search path and checked each entry's value and provenance
 * (sim/machine/model.h).  It holds the constants of dp_cost.h:
 *
 *   dpscan:
 *     arch:          {value: simd | spmd, source: ...}
 *     op:            {value: 2.3 us, ...}    # one element op, one proc
 *     step:          {value: 10 us, ...}     # issue of one step
 *     scan_slice:    {value: 50 us, ...}     # parallel prefix per VP slice
 *     vp_pow2:       {value: true, ...}      # optional, default false
 *     send_setup:    {value: 100 us, ...}    # simd
 *     send_slice:    {value: 500 us, ...}    # simd
 *     net_latency:   {value: 5 us, ...}      # spmd
 *     msg_overhead:  {value: 3.3 us, ...}    # spmd
 *     msg_bytes:     {value: 20 B, ...}      # spmd
 *     arity:         {value: 4, ...}         # spmd
 *     level_bandwidth: {value: [20 MB/s, 10 MB/s, 5 MB/s], ...}  # spmd
 *
 * The processor count is the machine's partition: the lanes of its
 * `array` processor (simd) or the count of its `node` processors (spmd).
 * O(keys).
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_MODEL_H
#define PGSIM_WORKLOAD_DPSCAN_DP_MODEL_H

#include "sim/core/cfg.h"
#include "sim/workload/dpscan/dp_cost.h"
#include "sim/workload/workload.h"

/* The dpscan: keys each architecture requires (`pgsim help run`). */
extern const WlNeedAlt wl_dp_model_needs[];

/* Fills *m (procs left alone) from a `dpscan:` section; FALSE with a
 * located *err on a missing or malformed parameter. */
gboolean wl_dp_machine_from_cfg(const CfgNode *sec, WlDpMachine *m,
                                GError **err);

/* The node kind whose size is the partition: "array" (its lanes) for a
 * SIMD machine, "node" (its count) for an SPMD one. */
const char *wl_dp_partition_kind(WlDpArch arch);

/* Fills *m (procs left alone) from the dpscan: section of a machine
 * model tree; a model without one is refused at `at` (NULL: the tree). */
gboolean wl_dp_machine_from_model(const CfgNode *model, const CfgNode *at,
                                  WlDpMachine *m, GError **err);

/* Fills *m from a built machine: its model's dpscan: section and its
 * partition (procs).  FALSE with a located *err when the machine lacks
 * either. */
gboolean wl_dp_machine_from_mach(const MachMachine *mach, WlDpMachine *m,
                                 GError **err);

#endif
