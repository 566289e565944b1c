/* ag_pipe.h — one frame of Argus on a simulated shared-memory machine:
 * application threads issue their contexts' command blocks, geometry
 * threads transform, shade and bucket them to tiles, rasterisation
 * threads draw each tile's primitives in an order that honours the
 * parallel API (seed 002, "Argus" slides and Figure 2 "The Argus
 * Pipeline"; implementation: graphics.stanford.edu/projects/flashg/argus).
 *
 *   application thread c (one per context): per block, the batch's
 *       application work when the block opens a batch (Nurbs: evaluate
 *       each distinct patch vertex; March: visit the cell's voxels and
 *       emit its triangles), the API issue cost of its vertices and
 *       batch, one lock to append the block to the shared geometry queue
 *       and the command bytes through shared memory.  With a bounded
 *       buffer (buffer_bytes) a thread whose context's blocks not yet
 *       through geometry fill it waits (issue_blocked); state commands,
 *       display lists and the glFinish baseline: ag_issue.c.
 *   geometry threads: pop blocks FIFO (one lock), transform and light
 *       each vertex, set up and bucket each triangle, write it to each
 *       overlapped tile's queue (bytes through shared memory).
 *   rasterisation threads: tile t belongs to rasteriser
 *       wl_ag_tile_owner() (interleaved along rows and columns).  A tile
 *       keeps, per context, the next block it must pass; a block whose
 *       geometry is done may be drawn at the tile when its waits are
 *       satisfied there — ordering "within the pixel processors", one of
 *       the two schemes of the Argus page.  Per-tile counters: a P
 *       consumes one V of the same cell signalled at this tile; a
 *       glpBarrier wait needs every party's arrival (the post of its
 *       last block before the barrier) drawn at this tile; a
 *       glpWaitContext(m) needs the tile past the blocks m had issued
 *       when the waiting block was issued.  Blocks with nothing for the
 *       tile and no synchronisation, clear or swap are skipped free (the
 *       reclaim pointer).  Drawing pays set-up per triangle, fill per
 *       fragment (z-tested or blended) and per cleared pixel (0 with
 *       fill_rate infinite: seed 002's footnote), one semaphore
 *       operation per synchronisation command.
 *   application barrier (Figure 2's appBarrier): an application thread
 *       reaching it parks until every context's thread has; the last
 *       one wakes the others.
 *
 * Threads map to processors in that order (app 0..C-1, geometry, then
 * raster), thread k on processor k mod P (FIFO: threads sharing a
 * processor take turns at work granularity).  A uniprocessor run puts
 * every thread on processor 0 and pays no lock, semaphore or memory
 * transfer (a serial library has no queues).
 * Events: O(blocks x (1 + tiles touched)) per frame.
 */
#ifndef PGSIM_WORKLOAD_ARGUS_AG_PIPE_H
#define PGSIM_WORKLOAD_ARGUS_AG_PIPE_H

#include "sim/machine/machine.h"
#include "sim/machine/shmem.h"
#include "sim/workload/argus/ag_stream.h"
#include "sim/workload/argus/ag_tile.h"

typedef enum { WL_AG_APP_NONE, WL_AG_APP_NURBS, WL_AG_APP_MARCH } AgApp;
extern const char *const wl_ag_app_names[]; /* "none" "nurbs" "march" */

/* Costs of the `cpu` node kind (wl_ag_cost_ops lists them), for pricing
 * the pipeline's counts by hand; the pipeline itself gives the machine
 * named counts (ag_pipe.c compute) and keeps no copy. */
typedef struct {
    SimTime nurbs_vertex, march_voxel, march_triangle;
    SimTime issue_vertex, issue_batch;
    SimTime geom_vertex, geom_triangle, geom_tile;
    SimTime rast_triangle, rast_pixel, rast_blend, rast_clear;
    SimTime lock, sema;
    SimTime issue_state, geom_state;
} AgCosts;
extern const char *const wl_ag_cost_ops[];
/* The same, declared for the machine (WlOps.needs; costs.h). */
extern const MachNeed wl_ag_needs[];

/* Where the parallel API's ordering is enforced (the Argus page's two
 * schemes, ag_order.c): PIXEL within the pixel processors (each tile
 * honours every command at that tile); GEOMETRY between the geometry
 * processors (a block is sequenced when its waits are met there, and
 * every tile draws blocks in that one sequence, the reclaim pointer
 * skipping slots with nothing for it). */
typedef enum { WL_AG_SCHEME_PIXEL, WL_AG_SCHEME_GEOMETRY } AgScheme;
extern const char *const wl_ag_scheme_names[]; /* "pixel" "geometry" */
/* How the program's ordering points are met (ag_issue.c): GLP by the
 * parallel API's commands in the streams; FINISH by the baseline the
 * paper compares with: the issuing thread glFinish()es (waits until
 * every tile has passed the commands issued so far, every context's, or
 * its own with finish_context) and then signals the other application
 * threads, which wait before issuing. */
typedef enum { WL_AG_SYNC_GLP, WL_AG_SYNC_FINISH } AgSyncMode;
extern const char *const wl_ag_sync_names[]; /* "glp" "finish" */

typedef struct {
    guint procs, contexts, geometry, rasterisers;
    gboolean uniprocessor;
    gboolean fill_infinite;
    gboolean pool; /* workers: pool (below) */
    AgApp app;
    uint64_t voxels_per_batch; /* March: cell voxels */
    guint vertex_bytes, triangle_bytes;
    double mem_bandwidth; /* bytes/s; 0: infinite */
    SimTime mem_latency;
    AgScheme scheme;
    AgSyncMode sync;
    gboolean finish_context; /* glFinish drains the caller's context only
                              * (else every context's commands issued
                              * before the call: the whole pipe) */
    gboolean retained;     /* display lists: compiled in the first frame,
                            * executed by reference after (ag_issue.c) */
    uint64_t buffer_bytes; /* per context command buffer; 0: unbounded */
    guint state_bytes;     /* one state command */
    guint call_bytes;      /* one glCallList */
} AgSetup;

typedef struct {
    SimTime start, end;
    uint64_t triangles, verts_issued, bucketed, pixels, syncs, blocks;
    SimTime app_busy, geom_busy, rast_busy; /* summed over threads */
    uint64_t shmem_bytes;
    SimTime issue_blocked; /* application threads on a full buffer */
    SimTime finish_wait;   /* on glFinish or another thread (sync: finish) */
    uint64_t states;        /* state commands issued */
    uint64_t command_bytes; /* written into the command buffers */
    uint64_t order_violations; /* ag_order.c: 0 when every tile's order
                                * honours every synchronisation command */
} AgFrameStats;

typedef struct AgPipe AgPipe;

/* Borrowed: machine, streams, frame, mesh, view (all outlive the pipe). */
AgPipe *wl_ag_pipe_new(MachMachine *m, const AgSetup *s, const AgStreams *st,
                       AgFrame *f, const SceneMesh *mesh, const RastView *view);
void wl_ag_pipe_free(AgPipe *p);
/* Runs one frame from now to the last tile's last block; FALSE with *err
 * on an engine error or a deadlock (blocks left undrawn). */
gboolean wl_ag_pipe_frame(AgPipe *p, SimTime until, AgFrameStats *out,
                          GError **err);
/* After a frame: the synchronisation commands of `st` (the pipe's
 * streams, or the same blocks with more commands) that some tile's
 * order of passing blocks broke (ag_order.c); 0 means command-
 * sequential consistency held at every tile. */
uint64_t wl_ag_pipe_order_check(const AgPipe *p, const AgStreams *st);
gboolean wl_ag_costs_from_machine(const MachMachine *m, AgCosts *c,
                                  GError **err);

#endif
