/* dp_workload.h — workload `dpscan`: seed 004's data-parallel renderer.
 *
 *   machine: {model: cm200}   # a model with a dpscan: section (dp_model.h)
 *   workload:
 *     type: dpscan
 *     model: cm200            # optional shorthand for machine.model (the
 *                             # default machine); both given must agree
 *     processors: 16384       # partition: nodes.array.lanes (and
 *                             # network.router_nodes = /16) on a SIMD
 *                             # model, nodes.node.count on an SPMD one;
 *                             # default: the machine's own, 16384 on the
 *                             # default machine
 *     width: 1280
 *     height: 1024
 *     buffer_factor: 0.25     # segment buffer slots / polygons
 *     mode: gouraud           # flat | gouraud | wireframe | hidden_line
 *                             # | contour | points | lines (seed 004 §5)
 *     wire: network           # SPMD sends: network | formula (below)
 *     partitions: [16384, 65536] # optional: the same render also costed
 *                             # at these processor counts (SPMD: with
 *                             # wire: formula); metrics time_s@P and
 *                             # KEY_count@P per model constant KEY
 *     palette: [...]          # optional: 15 colours, [r, g, b] in 0..1
 *                             # or "#rrggbb" (dp_color.h)
 *   scene: {...}              # sim/scene/scene_cfg.h
 *
 * With `pgsim run --out DIR` the last frame's image is written as
 * DIR/frame.png (`--frames all`: DIR/frame-NNNN.png for every frame)
 * through the generic hook wl_emit_frame(), in the 8-bit colour table of
 * §5.  Metrics per run (mean over frames): time per phase
 * (transform_s, scan_s, pixel_s, router_s, display_s), polygons,
 * polygons_per_s,
 * steps, scan_iters, pixel_iters, flushes, segments, pixels, collisions,
 * messages, max_load; on an SPMD machine also router_wire_s and
 * router_soft_s (the data network's and the per-message software's time
 * of the sends, summed: each send costs the larger).
 *
 * The wire (SPMD, the CM-5): with `wire: network` (the default) each
 * array sent is handed to the machine's own network at the run's
 * fidelity (`run.fidelity`: analytic, flow or packet), one message per
 * node pair of its real sources and destinations, on a private engine;
 * the time to the last delivery, less the network's start-up (in the
 * model's net_latency), is the send's wire time.  `wire: formula` uses
 * the analytic fat tree of dp_cost.h instead (what `reproduce ortega93`
 * uses to cost fifteen partitions at once).  The SIMD router (CM-200) is
 * the fitted per-router-node cost of the model at every fidelity.
 * O(render) per frame (dp_render.h) plus the network's events.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_WORKLOAD_H
#define PGSIM_WORKLOAD_DPSCAN_DP_WORKLOAD_H

#include "sim/workload/workload.h"

extern const WlOps wl_dpscan_ops;

#endif
