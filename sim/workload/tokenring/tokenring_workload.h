/* tokenring_workload.h — the token-ring test workload (configs/tokenring.yaml): a token passed around a ring.
 *
 *     workload:
 *       type: tokenring
 *       nodes: 8              # ring size, 2 .. 1M
 *       token: 1 KB           # bytes carried per hop
 *       compute: 20 us        # work a node does before passing it on
 *       jitter: 0.25          # compute time uniform in c*(1 +- jitter)
 *       link: {latency: 5 us, bandwidth: 2.8 MB/s}
 *
 * One frame is one round of the token (run.frames rounds).  Needs only
 * the engine; no machine or network layer.
 */
#ifndef PGSIM_WORKLOAD_TOKENRING_TOKENRING_WORKLOAD_H
#define PGSIM_WORKLOAD_TOKENRING_TOKENRING_WORKLOAD_H

#include "sim/workload/workload.h"

extern const WlOps wl_tokenring_ops;

#endif
