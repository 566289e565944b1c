/* dp_model.h — the data-parallel cost model of a machine, from YAML.
 *
 * The `dpscan:` section of a machine model (models/cm200.yaml,
 * models/cm5.yaml) holds the constants of dp_cost.h.  Every parameter is
 * a map {value: ..., source | assumption | calibrated: ...} as in the
 * rest of models/: a value without its provenance is an input error.
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
 * The processor count is not here: it is the partition size of a run.
 * O(keys).
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_MODEL_H
#define PGSIM_WORKLOAD_DPSCAN_DP_MODEL_H

#include "sim/core/cfg.h"
#include "sim/workload/dpscan/dp_cost.h"
#include "sim/workload/workload.h"

/* Fills *m (procs left alone) from a `dpscan:` section; FALSE with a
 * located *err on a missing, malformed or unsourced parameter. */
/* The dpscan: keys each architecture requires (`pgsim help run`). */
extern const WlNeedAlt wl_dp_model_needs[];

gboolean wl_dp_machine_from_cfg(const CfgNode *sec, WlDpMachine *m,
                                GError **err);

/* Loads models/<name>.yaml (relative to `models_dir`) and reads its
 * `dpscan:` section. */
gboolean wl_dp_machine_load(const char *models_dir, const char *name,
                            WlDpMachine *m, GError **err);

#endif
