/* pf_pn.h — curved PN triangles as geometry compression (seed 002,
 * slides "Hardware Performance": "if the graphics processor is
 * sufficiently fast and the bus is busy, curved PN triangles render at
 * the same speed as flat triangles").
 *
 * The `performer` workload with a `pn:` section runs this instead of the
 * frame pipeline.  The config's scene is the coarse mesh; it is really
 * tessellated at `level` (sim/scene/pn_triangles.h) and every frame
 * moves either the coarse triangles (send: coarse; the receiving
 * processors tessellate) or the fine ones (send: fine; the sender
 * tessellated once, the link carries (L+1)^2 as many):
 *
 *   shared-memory machine (kinds cpu, pipe): the CPU running DRAW issues
 *   the vertices (cpu draw_vertex each) and the bus carries them
 *   (vertex_bytes each) to the pipe, which tessellates (pipe pn_vertex
 *   per grid point) and draws (pipe triangle per fine triangle), through
 *   the graphics pipe process of the town's DRAW (pf_gpipe.h: chunks
 *   into a bounded FIFO), so a frame lasts about as long as the slowest
 *   of the three, plus filling and draining the FIFO.
 *
 *   Pixel-Planes 5 (kinds host, gp, renderer): the host sends each GP
 *   its share of the triangles over the ring; a GP tessellates (gp
 *   pn_vertex per point), transforms (gp polygon + 3 vertex per fine
 *   triangle) and sends each renderer its share of renderer commands
 *   (command_bytes each, gp send_primitive to pack); renderers draw (per
 *   fine triangle: renderer primitive).  A frame ends when the last
 *   renderer is done.
 *
 * With `memory: {from, to, layout, index_bytes, control_bytes}` the run
 * also reports what storing the pre-tessellated levels from..to would
 * take against the base mesh (pn_memory.h; vertex_bytes per vertex):
 * the slides' "models for LOD 0-4 would require 70 times the memory".
 *
 * With `lod:` the level is chosen each frame by Performer's LOD node and
 * stress control instead (pf_pnlod.h).
 *
 * Level 0 is the flat mesh: nothing is tessellated, coarse = fine.
 * The messages go through the machine's network (mach_net), so bytes
 * and times are the transport's.  O(frames x processors) events.
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_PN_H
#define PGSIM_WORKLOAD_PERFORMER_PF_PN_H

#include "sim/machine/machine.h"
#include "sim/scene/pn_memory.h"
#include "sim/scene/pn_triangles.h"
#include "sim/workload/performer/pf_pipeline.h"
#include "sim/workload/workload.h"

typedef struct WlPfPnLod WlPfPnLod; /* pf_pnlod.h */

typedef struct {
    ScenePnParams pn;
    gboolean send_fine;
    uint64_t vertex_bytes;  /* per vertex over the link */
    uint64_t command_bytes; /* Pixel-Planes 5 renderer command */
    uint64_t fifo_depth, fifo_chunk; /* the pipe's FIFO (the workload's
                                        `fifo`, pf_gpipe.h) */
    gboolean memory;     /* `memory:` given: the LOD-memory metrics */
    ScenePnMemRule mem;  /* its counting rule (pn_memory.h) */
    WlPfPnLod *lod;      /* `lod:` given: PN as Performer's LOD
                            (pf_pnlod.h); NULL: one fixed level */
    WlPfPipeParams pipe; /* the workload's frame pipeline (mode, rates,
                            stress), for lod */
} WlPfPnParams;

/* Reads the `pn:` map; NULL with a located error. */
WlPfPnParams *wl_pf_pn_params_parse(const CfgNode *pn, GError **err);
void wl_pf_pn_params_free(WlPfPnParams *p);
/* Runs ctx->frames frames on m (shared-memory or Pixel-Planes 5). */
/* The costs of the PN measurement on each machine it runs on. */
extern const WlNeedAlt wl_pf_pn_needs[];

/* One frame's DRAW work on the shared-memory machine at PN level
 * `level`: the CPU issues 3 vertices per sent triangle (coarse, or fine
 * with send: fine; cpu draw_vertex), the bus carries vertex_bytes each,
 * the pipe tessellates (pn_vertex per grid point, coarse sending and
 * level > 0) and draws (triangle per fine triangle). */
void wl_pf_pn_draw_work(const WlPfPnParams *p, guint level, uint64_t coarse,
                        uint64_t fine, uint64_t points, WlPfDrawWork *w);

gboolean wl_pf_pn_run(const WlContext *ctx, MachMachine *m,
                      const WlPfPnParams *p, SimResult *out, GError **err);

#endif
