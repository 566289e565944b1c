/* pf_pnlod.h — curved PN triangles as a level of detail chosen by
 * Performer's LOD and stress control (seed 002, slides "Hardware
 * Performance": PN "acts as a level of detail mechanism, higher LODs
 * obtained on the fly").
 *
 * With `pn: {lod: {levels: [4, 3, 2, 1, 0], ranges: [0, r1, ..., r5],
 * from: D0, to: D1}}` the performer workload builds a Performer scene
 * graph of one pfLOD node whose child i is a geode holding the config's
 * scene tessellated at PN level levels[i] (real triangles,
 * sim/scene/pn_triangles.h), and runs Performer's frame pipeline
 * (pf_pipeline.h: the workload's mode, frame rate and `stress:` filter)
 * with the eye moving from distance D0 to D1 over the frames.  CULL is
 * Performer's traversal (pf_cull.h): it picks the child whose range
 * holds distance x stress, i.e. the PN level; DRAW sends that level to
 * the pipe as in pf_pn.h — coarse triangles the pipe tessellates (send:
 * coarse) or the stored fine mesh (send: fine) — through the graphics
 * pipe process (pf_gpipe.h): the DRAW CPU issues (draw_vertex per
 * vertex) into the bounded FIFO over the bus (vertex_bytes per vertex),
 * the pipe tessellates (pn_vertex per grid point) and draws (triangle
 * per fine triangle).  So the triangles drawn per frame fall
 * with distance, and under overload the stress filter raises the stress
 * until a coarser level fits the frame.  O(frames + triangles).
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_PNLOD_H
#define PGSIM_WORKLOAD_PERFORMER_PF_PNLOD_H

#include "sim/workload/performer/pf_pn.h"

struct WlPfPnLod {
    GArray *levels;  /* guint: the PN level of LOD child i */
    GArray *ranges;  /* double: levels->len + 1 switch distances */
    double from, to; /* eye distance at the first and the last frame */
};

/* Reads the `lod:` map; NULL with a located error. */
WlPfPnLod *wl_pf_pnlod_parse(const CfgNode *lod, GError **err);
void wl_pf_pnlod_free(WlPfPnLod *l);
/* Runs ctx->frames frames of p (p->lod set) on a cpu + pipe machine. */
gboolean wl_pf_pnlod_run(const WlContext *ctx, MachMachine *m,
                         const WlPfPnParams *p, SimResult *out, GError **err);

#endif
