/* pm_workload.h — the `pixelmerge` workload (WlOps row; Kurç, Aykanat,
 * Özgüç, seed 003): its parameters, node costs from a machine model and
 * the per-node memory model behind its memory metrics.  Everything else
 * runs it through the runner (sim/run/run.h).
 *
 * Section keys and metrics: docs/workloads.md ("pixelmerge").
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_WORKLOAD_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_WORKLOAD_H

#include "sim/machine/machine.h"
#include "sim/workload/pixelmerge/pm_frame.h"
#include "sim/workload/workload.h"

extern const WlOps wl_pixelmerge_ops;

/* Per-node memory footprint, bytes per item (assumptions, set in the
 * workload section `memory:`); see wl_pm_memory_use(). */
typedef struct {
    uint64_t base;     /* program, C library, NX/2, stack and system buffers */
    uint64_t polygon;  /* one local polygon (vertices, normals, colour) */
    uint64_t span;     /* one span record in a scanline list */
    uint64_t location; /* one entry of a full N x N z-buffer (ZBUF-EXC) */
    uint64_t pixel;    /* one WPA entry (x, z, shade) */
    uint64_t index;    /* one MSA entry (a WPA index) */
} WlPmMemory;

/* What one node holds at its peak, bytes, by part. */
typedef struct {
    uint64_t base, polygons, spans;
    uint64_t zbuffer; /* ZBUF-EXC: N^2 locations; active: WPA + MSA */
    uint64_t buffers; /* message buffers of the largest exchange */
    uint64_t total;
} WlPmMemUse;

/* What wl_pixelmerge_ops.parse() returns (free with its free_params). */
typedef struct {
    WlPmSetup setup;      /* setup.procs == 0: all of the machine's nodes */
    uint32_t count_bytes; /* global-sum element */
    WlPmMemory mem;
    guint *order;  /* workload.visibility (setup.comp.order points here) */
    guint n_order; /* its length; 0: processor order */
} WlPmParams;

/* The node cost operations, NULL-terminated (models/ipsc2.yaml
 * nodes.node.costs). */
extern const char *const wl_pm_cost_ops[];
/* The same, declared for the machine (WlOps.needs; costs.h). */
extern const MachNeed wl_pm_needs[];

/* Reads the costs of node kind "node" from the set the machine fills
 * for wl_pm_needs; every missing op in one located input error naming
 * the model. */
gboolean wl_pm_costs_from_machine(const MachMachine *m, uint32_t count_bytes,
                                  WlPmCosts *c, GError **err);
/* Only the costs compositing spends, pack and compare of node kind
 * "node" (the rest of *c zero): what a frame at the runs or counts rung
 * (pm_rung_frame.h) and `pgsim bench composite` read. */
gboolean wl_pm_composite_costs_from_machine(const MachMachine *m,
                                            uint32_t count_bytes,
                                            WlPmCosts *c, GError **err);

/* The peak bytes of a node with these counts: base + polygons x
 * polygon + spans x span (the span lists are complete before z-buffering
 * starts), plus for ZBUF-EXC a full z-buffer (N^2 x location) and the
 * send and receive buffers of the first halving (N^2 / 2 locations each
 * at bytes_per_location), for the active schemes the WPA (active x
 * pixel), the MSA (N x index) and two merge buffers (received pixels and
 * the merged output, active x bytes_per_pixel each).  A compositing
 * scheme counts as ZBUF-EXC (a full local image and at most the image's
 * locations in flight) unless it run-length encodes, then as an active
 * scheme. */
WlPmMemUse wl_pm_memory_use(const WlPmMemory *mem, const WlPmSetup *s,
                            uint64_t polygons, uint64_t spans, uint64_t active);

#endif
