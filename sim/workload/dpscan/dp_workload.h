/* dp_workload.h — workload `dpscan`: seed 004's data-parallel renderer.
 *
 *   workload:
 *     type: dpscan
 *     model: cm200            # models/<model>.yaml, section dpscan:
 *     processors: 16384       # partition: lanes (SIMD) or nodes (SPMD)
 *     width: 1280
 *     height: 1024
 *     buffer_factor: 1.0      # segment buffer / polygons
 *   scene: {...}              # sim/scene/scene_cfg.h
 *
 * Metrics per run (mean over frames): time per phase (transform_s,
 * scan_s, pixel_s, router_s, display_s), polygons_per_s, steps,
 * scan_iters, pixel_iters, flushes, pixels, collisions, messages and
 * comm bytes.  O(spans + segments) per frame.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_WORKLOAD_H
#define PGSIM_WORKLOAD_DPSCAN_DP_WORKLOAD_H

#include "sim/workload/workload.h"

extern const WlOps wl_dpscan_ops;

#endif
