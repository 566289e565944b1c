/* pf_pipeline.h — Performer's multiprocessed frame pipeline on a video
 * clock (Rohlf and Helman, SIGGRAPH '94; seed 002, slides "libpf":
 * Multiprocessing, Process Synchronization, Frame Control, Data
 * Synchronization, Achieving Real-Time).
 *
 * Stages APP, CULL and DRAW of frame n run in that order, each as work
 * on a processor (MachProc).  The multiprocessing mode (pfMultiprocess)
 * combines or splits them at every stage boundary: APPCULLDRAW (one
 * process), APPCULL_DRAW, APP_CULLDRAW, APP_CULL_DRAW.  Each of `pipes`
 * graphics pipes (pfPipe) has its own CULL and DRAW: a process the mode
 * gives it, or, where the mode combines CULL (and DRAW) with APP, the
 * APP process serving every pipe in turn (APP, CULL 0, [DRAW 0,] CULL 1,
 * ...).  ISECT, when given, is an asynchronous process started with
 * each APP frame if idle (PFMP_FORK_ISECT), or, with `isect_in_app`,
 * runs after APP in the APP process every frame.
 *
 * Clocks: video retraces every V; frame boundaries every T = k V (the
 * fixed frame rate).  pfSync: the process that runs APP starts frame
 * n + 1 at the first frame boundary after it finished its part of frame
 * n (APP, or APP+CULL, or APP+CULL+DRAW when they share it) and after
 * the boundary frame n started on.  Hand-off to a CULL process: without
 * `update_list`, APP hands frame n to CULL when CULL takes it (pfFrame
 * blocks until then) and pfSyncs after; with it (pfBuffer: APP's changes
 * are kept in an update list applied downstream at the frame boundary),
 * APP pfSyncs first, frame n reaches the CULLs at that boundary, APP
 * n + 1 starts when every CULL took it, and each CULL process first
 * applies the update list (the `update` stage function's time).  So a
 * process boundary costs a frame boundary: one frame of latency per
 * pipeline stage.  Multibuffering: CULL of frame n waits until its
 * pipe's DRAW finished frame n - 2 (two display lists).  DRAW of frame n
 * starts after its CULL and after frame n - 1 was swapped in
 * (double-buffered frame buffer); a DRAW process in phase *locked*
 * starts only on a frame boundary, *floating* at once (a DRAW sharing
 * its process with CULL follows it at once).  The swap is at the next
 * video retrace after DRAW ends (locked: the next frame boundary); a
 * frame is swapped when every pipe swapped it.  Latency of frame n: its
 * swap minus its APP start; throughput: frames swapped per second.
 *
 * Stress feedback (pfChanStressFilter), per pipe: after each DRAW, load
 * = DRAW time / T; when load leaves [low, high], stress += gain (load -
 * (low + high) / 2), clamped to [1, max].  CULL reads its pipe's stress
 * at its start: the latest finished DRAW's, so the response is at least
 * one frame late.
 *
 * One engine event per stage start and end; O(frames x pipes) records.
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_PIPELINE_H
#define PGSIM_WORKLOAD_PERFORMER_PF_PIPELINE_H

#include "sim/machine/overlap.h"
#include "sim/workload/performer/pf_gpipe.h"

#define WL_PF_MAX_PIPES 8

typedef enum {
    WL_PF_MP_APPCULLDRAW,   /* one process */
    WL_PF_MP_APPCULL_DRAW,  /* APP+CULL, DRAW */
    WL_PF_MP_APP_CULL_DRAW, /* three processes */
    WL_PF_MP_APP_CULLDRAW,  /* APP, CULL+DRAW */
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
    /* Several pipes: called before cull(), draw() and draw_work() with
     * the pipe they are for (NULL: one pipe). */
    void (*channel)(void *ctx, guint pipe);
    /* With update_list: a CULL process's time to apply APP's update list
     * of `frame` (NULL: none); priced as a time, in phase "update". */
    SimTime (*update)(void *ctx, guint frame);
    /* With an arena: the shared-arena bytes of the stage just called
     * (pf_arena.h; NULL: none). */
    uint64_t (*arena_bytes)(void *ctx);
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
    guint pipes;            /* graphics pipes (0 or 1: one) */
    WlPfGpipe *const *gpipes; /* pipes > 1 with a pipe process: one per
                                 pipe (gpipe is then unused) */
    gboolean update_list;   /* pfBuffer hand-off at the frame boundary */
    gboolean isect_in_app;  /* ISECT after APP in the APP process */
    WlPfArena *arena;       /* NULL: stages move no arena bytes; else
                               each stage's work runs in pieces, each
                               after its share of arena_bytes() */
} WlPfPipeParams;

typedef struct {
    SimTime app_start, app_end, cull_start, cull_end;
    SimTime draw_start, draw_end, swap;
    SimTime isect; /* ISECT time started with this frame (0: none) */
    SimTime cull_ms, draw_ms; /* CULL's and DRAW's start to end, the mean
                                 over the pipes (one pipe: end - start) */
    double stress; /* stress CULL used */
} WlPfFrameRec;

/* The stage names and mode names, for configs and reports. */
extern const char *const wl_pf_mp_mode_names[];

/* Runs p->frames frames on procs (procs[0] the APP process, then the
 * others as wl_pf_mp_proc() places them, then ISECT's if f->isect and
 * not isect_in_app): fills recs (WlPfFrameRec, p->frames entries; cull
 * and draw: the first start and the last end over the pipes).  FALSE
 * with *err if the engine stops on an error. */
gboolean wl_pf_pipe_run(SimEngine *eng, MachProc *const *procs,
                        const WlPfPipeParams *p, const WlPfStageFns *f,
                        void *ctx, GArray *recs, SimTime until, GError **err);
/* Processes the mode needs with `pipes` pipes (0: one), without ISECT:
 * 1; 1 + pipes (APPCULL_DRAW, APP_CULLDRAW); 1 + 2 pipes (APP_CULL_DRAW). */
guint wl_pf_mp_procs(WlPfMpMode mode, guint pipes);
/* The index in procs of pipe i's CULL (draw FALSE) or DRAW process. */
guint wl_pf_mp_proc(WlPfMpMode mode, guint i, gboolean draw);

/* Summaries of a run: mean seconds between swaps (1 / throughput), mean
 * latency (swap - APP start), both over frames [skip, frames). */
double wl_pf_mean_interval_s(const GArray *recs, guint skip);
double wl_pf_mean_latency_s(const GArray *recs, guint skip);

#endif
