/* ag_stream.h — the command streams of the Argus workload: what each
 * graphics context issues, in order, with the parallel API's
 * synchronisation commands (seed 002; Igehy, Stoll and Hanrahan,
 * "The Design of a Parallel Graphics Interface", SIGGRAPH 1998).
 *
 * A scene's triangles come in batches: maximal runs of consecutive
 * polygons with one tag (a Nurbs patch, a March cell).  A context issues
 * its batches in order; each batch is cut into blocks of at most
 * `block_tris` triangles (Argus closes a command block "at fixed
 * intervals", graphics.stanford.edu/projects/flashg/argus/implementation).
 * Synchronisation commands sit at block boundaries: a block carries the
 * waits issued before its first command (glpPSema, glpWaitContext, the
 * wait half of glpBarrier, the application's own barrier) and the
 * signals issued after its last one (glpVSema, the arrival half of
 * glpBarrier).
 *
 * Every order issues a frame as the interactive loop of seed 002's
 * Figure 2 (Igehy, Stoll and Hanrahan 1998, section 3): the master
 * (context 0) issues glClear (a block that clears every tile), meets
 * the slaves at an application barrier (appBarrier: application
 * threads wait, not graphics streams), and draws; each slave, after
 * the application barrier, issues glpWaitContext(master) — its later
 * commands are ordered after every command the master had issued at
 * that moment, the clear included — and draws; every context ends its
 * drawing with glpBarrier(0) — no context's commands after the barrier
 * are executed before every context's commands before it — and the
 * master then issues glXSwapBuffers (a block that presents every tile).
 * With one context: clear, drawing, swap, and no synchronisation.
 *
 * Orders (AgOrder):
 *   FRAME   batches dealt to contexts cyclically, no ordering inside a
 *           frame, one glpBarrier of all contexts at its end (Nurbs:
 *           "synchronization done only on frame boundaries");
 *   CELLS   the ordered marching-cubes loop of seed 002 Figure 3(c) in
 *           three dimensions: batches are the cells of an n x n x n grid
 *           (tag = x + n (y + n z)); context p takes, for every z, the
 *           (y, x) cells whose index j = x + n y has j = p + z mod C; it
 *           waits (P) on the cell behind it along each axis and signals
 *           (V) once for each neighbour in front;
 *   NONE    the same loop without semaphores (Figure 3(b)).
 * With one context every order issues the batches serially, without
 * synchronisation commands (Figure 3(a)).  O(triangles) to build.
 */
#ifndef PGSIM_WORKLOAD_ARGUS_AG_STREAM_H
#define PGSIM_WORKLOAD_ARGUS_AG_STREAM_H

#include "sim/scene/mesh.h"

typedef enum { WL_AG_ORDER_FRAME, WL_AG_ORDER_CELLS, WL_AG_ORDER_NONE } AgOrder;
extern const char *const wl_ag_order_names[]; /* "frame" "cells" "none" */

typedef enum { WL_AG_PRIM_STRIPS, WL_AG_PRIM_TRIANGLES } AgPrim;
extern const char *const wl_ag_prim_names[]; /* "strips" "triangles" */

/* Pre (before the block): P, BARRIER_WAIT, WAIT_CONTEXT, APP_BARRIER;
 * post (after it): V, BARRIER (arrival). */
typedef enum {
    WL_AG_SYNC_P,            /* glpPSema(id) */
    WL_AG_SYNC_V,            /* glpVSema(id) */
    WL_AG_SYNC_BARRIER,      /* glpBarrier(id): this context has arrived */
    WL_AG_SYNC_BARRIER_WAIT, /* glpBarrier(id): wait for every party */
    WL_AG_SYNC_WAIT_CONTEXT, /* glpWaitContext(context id) */
    WL_AG_SYNC_APP_BARRIER,  /* the application threads' barrier id */
    WL_AG_SYNC_KINDS
} AgSyncKind;

typedef struct {
    AgSyncKind kind;
    guint id; /* semaphore (a cell), barrier number or context */
} AgSync;

#define WL_AG_MAX_SYNC 6

typedef struct {
    guint ctx;      /* the issuing context (a block's place in its
                     * stream is its index there) */
    guint batch;    /* index into the stream's batches */
    guint first, n; /* triangles [first, first + n) of the mesh */
    gboolean opens; /* first block of its batch (pays the app work) */
    gboolean clear, swap; /* glClear / glXSwapBuffers (no triangles) */
    guint n_pre, n_post;
    AgSync pre[WL_AG_MAX_SYNC], post[WL_AG_MAX_SYNC];
    uint64_t verts; /* vertices issued for the block's triangles */
    guint n_state;  /* state commands issued before its first primitive
                     * (wl_ag_streams_set_state; 0 with state: none) */
} AgBlock;

typedef struct {
    guint first, n; /* triangles of the batch */
    guint tag;
    uint64_t verts;    /* vertices issued (strips share two) */
    uint64_t distinct; /* distinct mesh vertices (patch evaluations) */
} AgBatch;

/* Graphics state in the streams (seed 002, "Three Issues of a Parallel
 * API #1"): NONE issues no state command (its cost is the per-batch
 * issue_batch, as calibrated); STATEFUL gives each context its own
 * state (matrix, material, enables, colour): the context's first block
 * sets all four (a context inherits nothing from another) and a block
 * opening a batch whose colour differs from the context's current one
 * sets the colour; STATELESS makes every primitive carry all four
 * ("every command must include all information to execute"). */
typedef enum {
    WL_AG_STATE_NONE,
    WL_AG_STATE_STATEFUL,
    WL_AG_STATE_STATELESS
} AgStateMode;
extern const char *const wl_ag_state_names[]; /* "none" "stateful" "stateless" */
#define WL_AG_STATE_ITEMS 4 /* matrix, material, enables, colour */

typedef struct {
    GArray *batches; /* AgBatch, in mesh order */
    GPtrArray *ctx;  /* per context: GArray of AgBlock, in issue order */
    guint contexts;
    guint sems;     /* semaphore ids are < sems */
    guint barriers; /* glpBarrier ids are < barriers */
    guint barrier_parties;
    uint64_t syncs; /* synchronisation commands in all streams */
    uint64_t states; /* state commands in all streams */
} AgStreams;

/* Builds the streams of `m` (triangles only) for `contexts` contexts.
 * CELLS and NONE need batch tags that increase through the cell indices
 * of an n x n x n grid (cells = n; 0: the least n that holds the last
 * tag); cells without triangles become empty batches.  FALSE with *err
 * otherwise.  Free with wl_ag_streams_free(). */
AgStreams *wl_ag_streams_new(const SceneMesh *m, guint contexts, AgOrder ord,
                             AgPrim prim, guint block_tris, guint cells,
                             GError **err);
void wl_ag_streams_free(AgStreams *s);
/* Sets every block's n_state for `mode` (AgStateMode above; the batch
 * colour is its first polygon's) and s->states.  O(blocks). */
void wl_ag_streams_set_state(AgStreams *s, const SceneMesh *m,
                             AgStateMode mode);
static inline GArray *wl_ag_ctx_blocks(const AgStreams *s, guint c)
{
    return g_ptr_array_index(s->ctx, c);
}
/* Blocks over all contexts. */
guint wl_ag_n_blocks(const AgStreams *s);
/* Synchronisation commands of kind k in all streams. */
guint64 wl_ag_count_syncs(const AgStreams *s, AgSyncKind k);
/* Removes every command of kind k (the same program issued without it:
 * what the ordering tests compare against). */
void wl_ag_streams_drop(AgStreams *s, AgSyncKind k);

#endif
