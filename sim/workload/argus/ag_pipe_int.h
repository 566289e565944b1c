/* ag_pipe_int.h — the Argus pipeline's shared state, private to
 * sim/workload/argus (ag_pipe.c: geometry, tiles, rasterisers, frames;
 * ag_issue.c: application threads; ag_order.c: the geometry-sequence
 * ordering scheme and the per-tile order check).  Not for other
 * workloads or tests: the public interface is ag_pipe.h.
 */
#ifndef PGSIM_WORKLOAD_ARGUS_AG_PIPE_INT_H
#define PGSIM_WORKLOAD_ARGUS_AG_PIPE_INT_H

#include "sim/workload/argus/ag_pipe.h"

typedef struct {
    gboolean done;
    guint wait_upto; /* glpWaitContext: the context's blocks issued then */
    guint n_tiles;
    guint *tile_ids;   /* sorted */
    guint *tile_start; /* n_tiles + 1 offsets into tris */
    uint32_t *tris;
    uint64_t cmd_bytes; /* in its context's command buffer until geometry */
} BlockState;

/* What an application thread is waiting for (ag_issue.c). */
typedef enum {
    AG_RUN,
    AG_PARK_BUFFER, /* a full command buffer */
    AG_PARK_WAIT,   /* sync: finish — another thread's signal */
    AG_PARK_FINISH  /* sync: finish — glFinish of its own commands */
} AgPark;

struct AgPipe {
    MachMachine *m;
    SimEngine *eng;
    AgSetup s;
    const AgStreams *st;
    AgFrame *f;
    const SceneMesh *mesh;
    const RastView *view;
    MachShmem mem;
    unsigned ph_app, ph_geom, ph_rast;
    guint *ctx_off, nblocks;
    BlockState *bs;
    guint *app_next;
    guint *app_bar;        /* per application barrier: threads arrived */
    gboolean *app_arrived; /* per context: at its barrier's head block */
    gboolean *app_parked;  /* per context: waiting there */
    GQueue gq;
    gboolean *g_busy;
    guint *g_block;
    guint ntiles, C;
    guint *tnext; /* ntiles x C */
    int32_t *sem; /* ntiles x (sems + barriers): semaphore counts, then
                   * glpBarrier arrivals */
    guint nsem;   /* sems + barriers */
    guint *t_rr;  /* per tile: context to try first */
    guint tiles_left;
    gboolean *r_busy;
    guint nw;          /* workers of the pool (workers: pool), else 0 */
    gboolean *t_busy;  /* pool: a worker is drawing the tile */
    guint pool_cursor; /* pool: the tile to try first */
    guint *r_cursor, *r_tile, *r_block;
    GArray **r_tiles; /* tiles of each rasteriser, in row-major order */
    AgFrameStats *out;
    /* ag_issue.c */
    gboolean compiled;  /* retained: the display lists exist */
    uint64_t *buf_used; /* per context: bytes in its command buffer */
    AgPark *park;       /* per context */
    SimTime *since;     /* per context: when it parked */
    guint *finish_upto; /* C x C: context c's glFinish waits until every
                         * tile has passed this many of m's blocks */
    int32_t *app_sem;   /* nsem: application-level counts (sync: finish) */
    gboolean *app_passed; /* per context: its next block is past the
                           * application barrier */
    /* ag_order.c */
    guint *seq_block; /* GEOMETRY: block of each sequence number */
    guint next_seq;
    guint *seq_ctx;   /* per context: its blocks sequenced */
    guint *tseq;      /* per tile: next sequence number to pass */
    int32_t *gsem;    /* nsem: counts at the geometry stage */
    GArray **log;     /* per tile: blocks in the order it passed them */
};

/* ag_pipe.c */
MachProc *wl_ag_thread_proc(AgPipe *p, guint thread);
const AgBlock *wl_ag_block_at(const AgPipe *p, guint b, guint *ctx);
void wl_ag_sync_ops(const AgPipe *p, MachOps *o, const char *op, uint64_t n);
void wl_ag_compute(MachProc *proc, const MachOps *o, unsigned phase,
                   SimHandler done, AgPipe *p, guint arg, SimTime *busy);
void wl_ag_enqueue(SimEngine *eng, void *ctx, void *arg);
guint *wl_ag_tnext(AgPipe *p, guint t, guint c);
void wl_ag_tile_advance(AgPipe *p, guint t);
gboolean wl_ag_tile_busy(const AgPipe *p, guint t);
/* Whether tiles honour the glp commands (scheme pixel, sync glp). */
static inline gboolean wl_ag_tile_syncs(const AgPipe *p)
{
    return p->s.scheme == WL_AG_SCHEME_PIXEL && p->s.sync == WL_AG_SYNC_GLP;
}

/* ag_issue.c */
void wl_ag_issue_alloc(AgPipe *p);
void wl_ag_issue_free(AgPipe *p);
void wl_ag_issue_reset(AgPipe *p);
void wl_ag_app_issue(SimEngine *eng, void *ctx, void *arg);
/* Block gb's geometry is done: its commands leave the buffer. */
void wl_ag_issue_freed(AgPipe *p, guint gb);
/* Wakes threads whose glFinish or application-level wait is over. */
void wl_ag_finish_poll(AgPipe *p);

/* ag_order.c */
void wl_ag_order_alloc(AgPipe *p);
void wl_ag_order_free(AgPipe *p);
void wl_ag_order_reset(AgPipe *p);
/* The next block for a geometry thread (removed from the queue), or
 * G_MAXUINT: FIFO, or under GEOMETRY the first queued block that is its
 * context's next and whose waits are met there (it is sequenced). */
guint wl_ag_geom_pop(AgPipe *p);
/* GEOMETRY: tile t's next block in the sequence if its geometry is
 * done, else G_MAXUINT. */
guint wl_ag_seq_pick(AgPipe *p, guint t);
/* Tile t passes block gb of context c (drawn or skipped). */
void wl_ag_tile_pass(AgPipe *p, guint t, guint c, guint gb);
/* Counter of a semaphore, or of a barrier's arrivals, in a table of
 * sems + barriers entries (the tiles', the geometry stage's, the
 * application threads'). */
int32_t *wl_ag_count_at(int32_t *tab, const AgStreams *st, const AgSync *s);
/* Violations of the streams' synchronisation in the tiles' logs. */
uint64_t wl_ag_order_violations(const AgPipe *p, const AgStreams *st);

#endif
