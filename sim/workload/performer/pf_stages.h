/* pf_stages.h — what each Performer stage does to the town and what it
 * costs on the machine (the WlPfStageFns the pipeline calls).
 *
 * APP moves the cars (DCS) and places the camera on the ground height
 * the last finished ISECT found; CULL traverses the graph at the frame's
 * camera and the stress it is given into a display list kept in one of
 * WL_PF_NBUF buffers (multibuffering: frame n uses buffer n mod
 * WL_PF_NBUF; the pipeline never has more frames between CULL and DRAW);
 * DRAW replays that list; ISECT intersects a vertical segment under the
 * eye with the graph.
 *
 * Costs are counted operations times the model's per-operation costs
 * (models/sgi-onyx.yaml: cpu app_* cull_* draw_* isect_*, pipe triangle
 * and state, network bandwidth and startup).  DRAW counts three streams:
 * the CPU issuing (geosets, state changes, matrix operations, vertices),
 * the bus carrying 3 x vertex_bytes per triangle, and the pipe
 * (triangles, state changes).  With `piped` (the workload's run) draw()
 * returns the CPU's time and draw_work() hands the three to the graphics
 * pipe process (pf_gpipe.h), which runs them through its FIFO; without
 * it (the closed form, kept for callers of the stage functions alone)
 * DRAW's time is the slowest of the three, the CPU's counts with the
 * pipe's counts and the bus stream as overlapping terms
 * (sim/machine/overlap.h).  Each frame's counts are kept for the
 * per-frame log.
 *
 * Several pipes (wl_pf_stages_set_pipes): pipe i of N culls its own
 * channel, a 1/N slice of the horizontal field of view turned by a
 * heading offset (pfChannel view offsets, channels side by side), into
 * its own display lists, and draws them; a frame's counts add over the
 * pipes and its cpu, bus and pipe times are the slowest pipe's.
 * update() prices APP's update list of a frame (pfBuffer): one update per
 * moved car's DCS plus the camera, at the workload's `update` cost.
 * Strips (the slides' pfuBuilder meshing): with `strip` = L > 1
 * triangles per strip, a geoset of T triangles is ceil(T / L) strips
 * and sends T + 2 ceil(T / L) vertices instead of 3 T; DRAW's vertex
 * work, its bytes to the pipe and its arena reads count vertices (the
 * pipe's work stays per triangle).
 * Traversal callbacks (pf_cull.h) cost the workload's cull_callback and
 * draw_callback each; with either cost set, CULL's and DRAW's CPU work
 * is a time, not counts (a recording writes it so).
 * Each stage also counts its shared-arena bytes (arena_bytes(); the
 * per-operation sizes of `arena`, pf_arena.h).
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_STAGES_H
#define PGSIM_WORKLOAD_PERFORMER_PF_STAGES_H

#include "sim/machine/shmem.h"
#include "sim/workload/performer/pf_cull.h"
#include "sim/workload/performer/pf_pipeline.h"
#include "sim/workload/performer/pf_town.h"
#include "sim/workload/workload.h"

#define WL_PF_NBUF 4

typedef struct {
    SimTime app_frame, app_dcs;
    SimTime cull_node, cull_lod, cull_billboard, cull_item;
    SimTime draw_geoset, draw_state, draw_matrix, draw_vertex;
    SimTime isect_node, isect_triangle;
    SimTime pipe_triangle, pipe_state;
    uint64_t vertex_bytes;
    SimTime update; /* apply one update-list entry (the workload's) */
    guint strip;    /* triangles per strip (<= 1: independent) */
    SimTime cull_callback, draw_callback; /* one callback (the workload's) */
} WlPfCosts;

typedef struct {
    WlPfCullStats cull;
    WlPfDrawStats draw;
    WlPfIsectStats isect;
    guint dl_items;
    SimTime cpu, bus, pipe; /* DRAW's three times */
    uint64_t bytes;         /* DRAW's command bytes to the pipe */
    double ground;          /* the ground height APP used */
    guint updates;          /* APP's update-list entries */
} WlPfFrameStats;

typedef struct {
    WlPfTown *town;
    WlPfCosts c;
    MachShmem bus; /* the bus that feeds the pipe (sim/machine/shmem.h) */
    SimEngine *eng;
    MachProc *draw_cpu;  /* the process running DRAW (set by the caller) */
    gboolean cull, lazy; /* frustum culling; lazy pfGeoState */
    GArray *dl[WL_PF_MAX_PIPES * WL_PF_NBUF]; /* pipe i: from i NBUF */
    guint pipes, chan; /* pipes; the one the pipeline named last */
    WlPfDrawStats pdraw[WL_PF_MAX_PIPES]; /* each pipe's last DRAW */
    SimTime pcpu[WL_PF_MAX_PIPES], ppipe[WL_PF_MAX_PIPES];
    uint64_t pbytes[WL_PF_MAX_PIPES];
    WlPfArenaParams arena; /* bytes per operation (pf_arena.h) */
    uint64_t last_bytes;   /* the arena bytes of the last stage called */
    GArray *frames; /* WlPfFrameStats, one per frame */
    double ground;  /* the latest ISECT result */
    gboolean isect;
    gboolean app_timed; /* app_frame is the workload's app_work, not a
                           machine cost: APP's work is a time */
    MachOps last;       /* the named counts of the last stage called */
    MachOverlap over;   /* its overlapping terms (DRAW's pipe and bus) */
    gboolean piped;     /* a graphics pipe process (pf_gpipe.h) runs
                           DRAW's streams: draw() gives the CPU's time */
} WlPfStages;

/* Reads the costs from m (kinds cpu and pipe); FALSE with a located
 * error naming what is missing. */
/* The costs wl_pf_costs_read looks up, per kind (`pgsim help run`). */
extern const WlNeed wl_pf_town_needs[];

gboolean wl_pf_costs_read(MachMachine *m, uint64_t vertex_bytes, WlPfCosts *c,
                          GError **err);
/* A new stage context over town (borrowed) for `frames` frames; the bus
 * is m's shared memory (network bandwidth and startup, mach_shmem_init);
 * NULL with *err when m has none. */
WlPfStages *wl_pf_stages_new(MachMachine *m, WlPfTown *town, const WlPfCosts *c,
                             gboolean cull, gboolean lazy, gboolean isect,
                             guint frames, GError **err);
void wl_pf_stages_free(WlPfStages *s);
/* Culls and draws for `pipes` channels (1 <= pipes <= WL_PF_MAX_PIPES;
 * 1 by default). */
void wl_pf_stages_set_pipes(WlPfStages *s, guint pipes);
/* The stage functions (ctx: a WlPfStages). */
WlPfStageFns wl_pf_stage_fns(gboolean isect);
/* CPU time of DRAW's issuing work for the counts st (lazy or eager
 * state changes; st->vertices, or 3 per triangle when 0). */
SimTime wl_pf_draw_cpu(const WlPfCosts *c, const WlPfDrawStats *st,
                       gboolean lazy);
static inline WlPfFrameStats *wl_pf_frame_stats(WlPfStages *s, guint n)
{
    return &g_array_index(s->frames, WlPfFrameStats, n);
}

#endif
