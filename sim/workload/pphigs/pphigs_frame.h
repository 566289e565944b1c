/* pphigs_frame.h — one PPHIGS frame on the Pixel-Planes 5 machine, event-driven.
 *
 * Seed 001 §1.1: the GPs traverse their portions of the display list and
 * transform the primitives; each on-screen primitive becomes one command
 * per 128x128 screen region its screen box overlaps; commands go over the
 * ring to the renderer that owns the region; renderers rasterise; the
 * frame buffer collects the finished regions.
 *
 * The machine (sim/machine/machine.h) supplies everything hardware: its
 * `gp`, `renderer` and `frame_buffer` processors (FIFO, busy time per
 * phase), their cost tables, and the ring (mach_net(), at the run's
 * fidelity; stations are processor ids).  Regions are row-major over
 * the screen.  Static assignment: region k belongs to renderer k mod R.
 * Dynamic (spec.dynamic_regions): renderer r starts with region r; the
 * GPs keep the other regions' batches in bins; once every GP has ended,
 * a renderer that has rasterised its region takes the next one and asks
 * every GP for its bin (end_bytes each way at least), the request and
 * the bins travelling while it shades (seed 001 §1.1; fuchs89: renderers
 * "can be independently reassigned to any part of the screen").
 *
 *   GP g      phase "traverse": its attributes and executes (the max-set
 *             walk), then its primitives in traversal order, phase
 *             "transform" (metrics.h: on-screen or trivially rejected),
 *             plus `send_primitive` per command (phase "send").  A
 *             region's buffer is sent when it holds `batch` commands; at
 *             the end every partial buffer is sent, then one end marker
 *             per renderer carrying the number of messages sent.
 *   renderer  draws each arriving batch of its current region into that
 *             region's pixels (pphigs_pixels.h: `expression` per linear
 *             expression evaluated, `compare` per command, `region_begin`
 *             when a region is begun; phase "rasterise"); batches for its other regions
 *             wait.  When every GP has finished with it, it completes its
 *             regions in order (static) or its one region (dynamic, then
 *             takes the next): begin, rasterise, `region_shade` (phase
 *             "shade"), send the pixels to the frame buffer.
 *   frame buf `store_region` per region (phase "store"), copying the
 *             region's pixels into the frame; the frame ends with the
 *             last region.
 *   host      before the frame, the elements edits and rebalancing sent
 *             to each GP: `send_element` each (phase "edit"), one ring
 *             message of element_bytes each per GP; a GP with such a
 *             message starts when it arrives.
 *
 * A GP's processor time of a frame (seed 001 §6) is its "traverse" plus
 * "transform" busy time during the frame; it equals
 * wl_pphigs_traversal_cost() of its portion exactly (integer ps).
 *
 * Cost: O(max-set of every portion + commands) per frame; events
 * O(messages + regions).  Borrowed: the machine and the distribution.
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_PPHIGS_FRAME_H
#define PGSIM_WORKLOAD_PPHIGS_PPHIGS_FRAME_H

#include "sim/core/result.h"
#include "sim/machine/machine.h"
#include "sim/raster/image.h"
#include "sim/workload/pphigs/pphigs_metrics.h"

/* The frame's own sizes (configs/pphigs/frame.yaml). */
typedef struct {
    guint cmd_bytes;     /* one renderer command on the ring */
    guint end_bytes;     /* an end marker */
    guint batch;         /* commands per region buffer before a send */
    guint pixel_bytes;   /* per pixel sent to the frame buffer */
    guint width, height; /* screen, pixels */
    guint region;        /* region side, pixels (128 on Pixel-Planes 5) */
    guint element_bytes; /* one display-list element, host to GP */
    gboolean dynamic_regions; /* TRUE: a renderer takes the next region
                                 when it finishes one; FALSE: region k is
                                 renderer k mod R's (frame.c) */
} WlPphigsFrameSpec;

typedef struct WlPphigsFrame WlPphigsFrame;

/* Per-frame figures (the frame just run). */
typedef struct {
    SimTime time;           /* start to the last region stored */
    double *gp_time_us;     /* ngp entries: processor time (borrowed) */
    uint64_t commands;      /* renderer commands sent */
    uint64_t offscreen;     /* primitive instances trivially rejected */
    uint64_t primitives;    /* primitive instances traversed */
    uint64_t host_elements; /* elements the host sent before the frame */
    uint64_t expressions;   /* linear expressions the renderers evaluated */
} WlPphigsFrameStats;

/* The costs a frame reads, per kind (WlOps.needs; costs.h). */
extern const MachNeed wl_pphigs_needs[];

/* The GP cost table and the send cost from a cost set that declared
 * wl_pphigs_needs' gp costs (pphigs_costs.c). */
void wl_pphigs_costs_fill(const MachCosts *set, WlPphigsCosts *c,
                          SimTime *send);
/* The GP cost table and the per-command send cost of machine m (its
 * `gp` kind); FALSE with a located *err if one is missing. */
gboolean wl_pphigs_costs_from_machine(const MachMachine *m, WlPphigsCosts *c,
                                      SimTime *send, GError **err);

/* A frame driver on machine m (borrowed; needs kinds gp (1..64),
 * renderer and frame_buffer with their costs, and a network).  Returns a
 * new frame (wl_pphigs_frame_free) or NULL with a located *err. */
WlPphigsFrame *wl_pphigs_frame_new(MachMachine *m,
                                   const WlPphigsFrameSpec *spec, GError **err);
void wl_pphigs_frame_free(WlPphigsFrame *f);
guint wl_pphigs_frame_gps(const WlPphigsFrame *f);
const WlPphigsCosts *wl_pphigs_frame_costs(const WlPphigsFrame *f);

/* Runs one frame of `d` (as many GPs as the machine) under view `vp`
 * from the engine's current time to its end.  `host_elems` (NULL: none)
 * gives per GP the display-list elements the host sent it since the last
 * frame (edits, rebalancing moves: WlPphigsTraffic.sent_to deltas): the
 * host packs each (`send_element`, phase "edit") and sends them in one
 * message per GP, which starts its frame when they arrive.  FALSE with
 * *err if the engine failed. */
gboolean wl_pphigs_frame_run(WlPphigsFrame *f, const WlPphigsDist *d, Mat4 vp,
                             const uint64_t *host_elems,
                             WlPphigsFrameStats *out, GError **err);

/* Host elements examined since the last frame by step 2's backward
 * scans and the attribute-state cache's walks (§3.4-3.5,
 * WlPphigsTraffic total_scan + cache_walk deltas): the next frame
 * charges the host `scan_element` each (phase "edit") before it packs
 * the elements it sends. */
void wl_pphigs_frame_host_scan(WlPphigsFrame *f, uint64_t elements);

/* Utilisation over `elapsed`: mean of busy / elapsed over GPs and over
 * renderers. */
void wl_pphigs_frame_util(const WlPphigsFrame *f, SimTime elapsed,
                          double *gp_util, double *rend_util);

/* The least and the most busy / elapsed over the renderers (the
 * renderers' balance, region_assignment). */
void wl_pphigs_frame_rend_range(const WlPphigsFrame *f, SimTime elapsed,
                                double *lo, double *hi);

/* The frame buffer's image after the last frame run (the regions the
 * renderers drew and sent over the ring).  Borrowed. */
const RastImage *wl_pphigs_frame_image(const WlPphigsFrame *f);

#endif
