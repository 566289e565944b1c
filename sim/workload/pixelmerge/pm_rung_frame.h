/* pm_rung_frame.h — one compositing frame at the runs or counts rung
 * (pm_rung.h), for workload.image_fidelity: runs | counts.
 *
 * The frame is the compositing alone: the processes' images are made at
 * the rung and composited, and the merge is replayed on the network from
 * the engine's current time (no local rendering phase is timed: span_ms
 * and zbuf_ms are 0, frame_ms is merge_ms).  Images: at the runs rung
 * the runs of the pixel images the frame would composite (block, volume
 * or scene images: exact, as tested); at the counts rung, block images
 * only (images: blocks), each process's footprint rectangle
 * (wl_pm_block_rect) holding the fraction of its 8 x 8 sample rays that
 * meet its block, in the blocks' visibility order; nothing is O(image)
 * and nothing is checked against a serial image.
 * Cost: O(P x stages + rectangles x stages) at counts; the pixel
 * images' at runs.
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_RUNG_FRAME_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_RUNG_FRAME_H

#include "sim/workload/pixelmerge/pm_frame.h"

/* As wl_pm_frame_run_procs(), for s->rung runs or counts (s->scheme a
 * compositing one; counts: s->images.kind blocks). */
gboolean wl_pm_rung_frame_run(NetNet *net, MachProc *const *procs, guint frame,
                              const Scene *scene, const WlPmSetup *s,
                              const WlPmCosts *c, WlPmFrameOut *out,
                              GError **err);

#endif
