/* dp_workload.h — workload `dpscan`: seed 004's data-parallel renderer.
 *
 *   workload:
 *     type: dpscan
 *     model: cm200            # models/<model>.yaml, section dpscan:
 *     processors: 16384       # partition: lanes (SIMD) or nodes (SPMD)
 *     width: 1280
 *     height: 1024
 *     buffer_factor: 0.25     # segment buffer slots / polygons
 *     mode: gouraud           # flat | gouraud | wireframe | hidden_line
 *                             # | contour | points | lines (seed 004 §5)
 *     palette: [...]          # optional: 15 colours, [r, g, b] in 0..1
 *                             # or "#rrggbb" (dp_color.h)
 *   scene: {...}              # sim/scene/scene_cfg.h
 *
 * With `pgsim run --out DIR` the last frame's image is written as
 * DIR/frame.png (`--frames all`: DIR/frame-NNNN.png for every frame)
 * through the generic hook wl_emit_frame(), in the 8-bit colour table of
 * §5.  Metrics per run (mean over frames): time per phase
 * (transform_s, scan_s, pixel_s, router_s, display_s), polygons_per_s,
 * steps, scan_iters, pixel_iters, flushes, segments, pixels, collisions,
 * messages, max_load.  O(render) per frame (dp_render.h).
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_WORKLOAD_H
#define PGSIM_WORKLOAD_DPSCAN_DP_WORKLOAD_H

#include "sim/workload/workload.h"

extern const WlOps wl_dpscan_ops;

#endif
