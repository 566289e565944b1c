/* pf_pipeline.h — Performer's multiprocessed frame pipeline on a video
 * clock (Rohlf and Helman, SIGGRAPH '94; seed 002, slides "libpf":
 * Multiprocessing, Process Synchronization, Frame Control, Data
 * Synchronization, Achieving Real-Time).
 *
 * Stages APP, CULL and DRAW of frame n run in that order, each as work
 * on a processor (MachProc); the multiprocessing mode maps them onto
 * one, two (APP+CULL, DRAW) or three processes.  ISECT, when given, is a
 * fourth, asynchronous process started with each APP frame if idle.
 *
 * Clocks: video retraces every V; frame boundaries every T = k V (the
 * fixed frame rate).  pfSync: the process that runs APP starts frame
 * n + 1 at the first frame boundary after it finished its part of frame
 * n (APP, or APP+CULL, or APP+CULL+DRAW when they share it) and after
 * the boundary frame n started on.  Multibuffering: APP hands frame n to
 * CULL when CULL takes it (pfFrame blocks until then); CULL of frame n
 * waits until DRAW finished frame n - 2 (two display lists).  DRAW of
 * frame n starts after its CULL and after frame n - 1 was swapped in
 * (double-buffered frame buffer); phase *locked*: only on a frame
 * boundary; *floating*: at once.  The swap is at the next video retrace
 * after DRAW ends (locked: the next frame boundary).  Latency of frame n:
 * its swap minus its APP start; throughput: frames swapped per second.
 *
 * Stress feedback (pfChanStressFilter): after each DRAW, load = DRAW
 * time / T; when load leaves [low, high], stress += gain (load - (low +
 * high) / 2), clamped to [1, max].  CULL reads the stress at its start:
 * the latest finished DRAW's, so the response is at least one frame late.
 *
 * One engine event per stage start and end; O(frames) records.
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_PIPELINE_H
#define PGSIM_WORKLOAD_PERFORMER_PF_PIPELINE_H

#include "sim/machine/overlap.h"
#include "sim/workload/performer/pf_gpipe.h"

typedef enum {
    WL_PF_MP_APPCULLDRAW,   /* one process */
    WL_PF_MP_APPCULL_DRAW,  /* APP+CULL, DRAW */
    WL_PF_MP_APP_CULL_DRAW, /* three processes */
    WL_PF_MP_NMODES
} WlPfMpMode;

/* Stage costs, called when the stage starts (frame data is produced
 * then; the callee multibuffers it by frame number). */
typedef struct {
    SimTime (*app)(void *ctx, guint frame);
    SimTime (*cull)(void *ctx, guint frame, double stress);
    SimTime (*draw)(void *ctx, guint frame);
    SimTime (*isect)(void *ctx, guint frame); /* NULL: no ISECT process */
    /* The named counts the stage just called priced (the same time: its
     * own counts, or the longest of overlapping terms), or NULL / none:
     * its work is a time.  NULL: stages give times. */
    const MachOverlap *(*ops)(void *ctx);
    /* With a graphics pipe (WlPfPipeParams.gpipe): the work of the frame
     * the last draw() call counted, for the pipe to run. */
    void (*draw_work)(void *ctx, guint frame, WlPfDrawWork *w);
} WlPfStageFns;

typedef struct {
    WlPfMpMode mode;
    SimTime video;    /* V: one retrace period */
    guint per_frame;  /* k: retraces per frame boundary (>= 1) */
    gboolean locked;  /* DRAW phase */
    gboolean stress;  /* stress-feedback LOD on */
    double low, high; /* load band */
    double gain, max_stress;
    guint frames;
    /* NULL: DRAW is one piece of work on its processor and the frame
     * swaps at the refresh after it; else DRAW's CPU feeds this pipe
     * (pf_gpipe.h, on DRAW's processor) and the pipe swaps the frame:
     * DRAW of frame n waits for its CULL (and, locked, a boundary) but
     * not for the swap of n - 1, which the pipe does in order. */
    WlPfGpipe *gpipe;
} WlPfPipeParams;

typedef struct {
    SimTime app_start, app_end, cull_start, cull_end;
    SimTime draw_start, draw_end, swap;
    SimTime isect; /* ISECT time started with this frame (0: none) */
    double stress; /* stress CULL used */
} WlPfFrameRec;

/* The stage names and mode names, for configs and reports. */
extern const char *const wl_pf_mp_mode_names[];

/* Runs p->frames frames on procs (procs[0] the first process, then the
 * next ones as the mode needs, then ISECT's if f->isect): fills recs
 * (WlPfFrameRec, p->frames entries).  FALSE with *err if the engine
 * stops on an error. */
gboolean wl_pf_pipe_run(SimEngine *eng, MachProc *const *procs,
                        const WlPfPipeParams *p, const WlPfStageFns *f,
                        void *ctx, GArray *recs, SimTime until, GError **err);
/* Processes the mode needs (1, 2 or 3), without ISECT. */
guint wl_pf_mp_procs(WlPfMpMode mode);

/* Summaries of a run: mean seconds between swaps (1 / throughput), mean
 * latency (swap - APP start), both over frames [skip, frames). */
double wl_pf_mean_interval_s(const GArray *recs, guint skip);
double wl_pf_mean_latency_s(const GArray *recs, guint skip);

#endif
