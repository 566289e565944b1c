/* frame.h — one PPHIGS frame on the Pixel-Planes 5 model, event-driven.
 *
 * Seed 001 §1.1: the GPs traverse their portions of the display list and
 * transform the primitives; each on-screen primitive becomes one command
 * per 128x128 screen region its screen box overlaps; commands go over the
 * ring to the renderer that owns the region; renderers rasterise; the
 * frame buffer collects the finished regions.
 *
 * Stations on the ring: host 0, GPs 1..G, renderers G+1..G+R, frame
 * buffer G+R+1 (wl_pphigs_frame_stations() of them).  Region k (row-major
 * over the screen) belongs to renderer k mod R.
 *
 *   GP g      one "traverse" compute for its attributes and executes
 *             (the max-set walk), then its primitives in traversal order:
 *             each costs the GP cost table (metrics.h; off-screen ones a
 *             fraction) plus `gp_send` per command ("send" phase).  A
 *             region's buffer is sent when it holds `batch` commands;
 *             at the end every partial buffer is sent, then one end
 *             marker per renderer carrying the number of messages sent.
 *   renderer  rasterises each arriving batch of its current region
 *             (`rend_prim` per command, `rend_begin` when a region is
 *             begun); batches for its other regions wait.  When every GP
 *             has finished with it, it completes its regions in order:
 *             begin, rasterise, shade, send the pixels to the frame
 *             buffer.
 *   frame buf `fb_store` per region; the frame ends with the last region.
 *
 * Processors are FIFO: work submitted to a busy one starts when it
 * frees.  The GP "traverse" busy time of a frame equals
 * wl_pphigs_traversal_us() of its portion (to the picosecond rounding of
 * each element) — the paper's processor time (§6).
 *
 * Cost: O(max-set of every portion + commands) per frame; events
 * O(messages + regions).  Borrowed: engine, network, distribution.
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_FRAME_H
#define PGSIM_WORKLOAD_PPHIGS_FRAME_H

#include "sim/core/result.h"
#include "sim/net/net.h"
#include "sim/workload/pphigs/metrics.h"

typedef struct {
    WlPphigsCosts gp;     /* traversal/transform cost table (us) */
    SimTime gp_send;      /* GP: pack one renderer command */
    SimTime rend_prim;    /* renderer: one command */
    SimTime rend_begin;   /* renderer: start (clear) a region */
    SimTime rend_shade;   /* renderer: finish (shade) a region */
    SimTime fb_store;     /* frame buffer: one region */
    guint cmd_bytes;      /* one renderer command on the ring */
    guint end_bytes;      /* an end marker */
    guint batch;          /* commands per region buffer before a send */
    guint pixel_bytes;    /* per pixel sent to the frame buffer */
    guint width, height;  /* screen, pixels */
    guint region;         /* region side, pixels (128 on Pixel-Planes 5) */
    guint renderers;      /* R >= 1 */
} WlPphigsFrameSpec;

typedef struct WlPphigsFrame WlPphigsFrame;

/* Per-frame figures (the frame just run). */
typedef struct {
    SimTime time;           /* start to the last region stored */
    double *gp_traverse_us; /* ngp entries: traverse busy time (borrowed) */
    uint64_t commands;      /* renderer commands sent */
    uint64_t offscreen;     /* primitive instances trivially rejected */
    uint64_t primitives;    /* primitive instances traversed */
} WlPphigsFrameStats;

guint wl_pphigs_frame_stations(guint ngp, guint renderers);

/* A frame driver for `ngp` GPs on `net` (a ring of at least
 * wl_pphigs_frame_stations() stations).  Free with wl_pphigs_frame_free(). */
WlPphigsFrame *wl_pphigs_frame_new(SimEngine *eng, NetNet *net, guint ngp,
                                   const WlPphigsFrameSpec *spec);
void wl_pphigs_frame_free(WlPphigsFrame *f);

/* Runs one frame of `d` (ngp GPs) under view `vp` from the engine's
 * current time to its end.  FALSE with *err if the engine failed. */
gboolean wl_pphigs_frame_run(WlPphigsFrame *f, const WlPphigsDist *d,
                             Mat4 vp, WlPphigsFrameStats *out,
                             GError **err);

/* Appends every processor (gp0.., renderer0.., fb) with its busy times
 * over all frames run so far, the phases, frame times are the caller's. */
void wl_pphigs_frame_fill_result(const WlPphigsFrame *f, SimResult *r);
/* Utilisation over `elapsed`: mean of busy / elapsed over GPs and over
 * renderers. */
void wl_pphigs_frame_util(const WlPphigsFrame *f, SimTime elapsed,
                          double *gp_util, double *rend_util);

#endif
