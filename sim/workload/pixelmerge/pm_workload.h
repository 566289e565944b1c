/* pm_workload.h — the `pixelmerge` workload (WlOps row) and the pieces
 * the kurc96 reproduction shares with it: node costs from a machine
 * model, the workload's section parser and a multi-frame run that fills
 * a SimResult (Kurç, Aykanat, Özgüç, seed 003).
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

/* The peak bytes of a node with these counts: base + polygons x
 * polygon + spans x span (the span lists are complete before z-buffering
 * starts), plus for ZBUF-EXC a full z-buffer (N^2 x location) and the
 * send and receive buffers of the first halving (N^2 / 2 locations each
 * at bytes_per_location), for the active schemes the WPA (active x
 * pixel), the MSA (N x index) and two merge buffers (received pixels and
 * the merged output, active x bytes_per_pixel each). */
WlPmMemUse wl_pm_memory_use(const WlPmMemory *mem, const WlPmSetup *s,
                            uint64_t polygons, uint64_t spans, uint64_t active);
/* "* out of memory: 4.21 of 4.00 MiB (base ..., z-buffer ...)" or
 * "fits: ...": the verdict of use against `memory` bytes; g_free(). */
char *wl_pm_memory_verdict(const WlPmMemUse *use, uint64_t memory);

/* Runs `frames` frames of sc (frame f with the scene's camera of frame f)
 * with setup s on machine m (processors node0 .. node{P-1}, its network
 * and engine) and fills out (mach_fill_result plus the metrics listed in
 * docs/workloads.md).  FALSE with *err on failure (SIM_ERROR_INTERNAL if
 * the merged image differs from the serial render). */
gboolean wl_pm_run_frames(MachMachine *m, const Scene *sc, const WlPmParams *p,
                          const WlPmCosts *c, int frames, SimResult *out,
                          GError **err);
/* The same; a processor count the machine cannot hold is reported at
 * procs_at (the config's processors key; NULL: not located); ctx, when
 * not NULL, receives the merged frames the run wants as images
 * (wl_emit_frame). */
gboolean wl_pm_run_frames_at(MachMachine *m, const Scene *sc,
                             const WlPmParams *p, const WlPmCosts *c,
                             int frames, const CfgNode *procs_at,
                             const WlContext *ctx,
                             SimResult *out, GError **err);

#endif
