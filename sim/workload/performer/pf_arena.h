/* pf_arena.h — the stages' traffic to Performer's shared arena as
 * contention for the memory bus (issue 36, point 2; seed 002, "libpf":
 * Data Synchronization, the pfBuffers and the scene graph live in one
 * shared arena that every process reads and writes).
 *
 * A stage's work is `pieces` pieces: each reads or writes its share of
 * the stage's arena bytes (a transfer booked on the machine's memory bus,
 * sim/machine/shmem.h, so the stages' transfers queue behind each other)
 * and then computes its share of the stage's work.  So APP, CULL, DRAW
 * and ISECT running at once on different processors slow each other by
 * the time their transfers wait for the bus; one process alone pays only
 * bytes / bandwidth + latency a piece.  The processor is stalled while
 * its piece's transfer runs: busy in phase "arena" for the transfer's
 * time, its wait for the bus included, so a recording (`--record`)
 * writes the stall as that time and a replay on the same machine gives
 * the run back (on another machine the stall is not repriced).
 *
 * Bytes per operation (the workload's `arena` map, assumptions): `node`
 * per node CULL visits or ISECT tests, `item` per display-list item CULL
 * writes and DRAW reads, `entry` per update-list entry (APP writes it,
 * a CULL process reads it and writes its pfBuffer copy: twice), 3 x
 * vertex_bytes per triangle DRAW reads from the geosets, 36 B per
 * triangle ISECT tests.  O(pieces) events per stage.
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_ARENA_H
#define PGSIM_WORKLOAD_PERFORMER_PF_ARENA_H

#include "sim/machine/overlap.h"
#include "sim/machine/shmem.h"

typedef struct {
    uint64_t node, item, entry; /* bytes per operation */
    guint pieces;               /* a stage's pieces (>= 1) */
} WlPfArenaParams;

typedef struct {
    MachShmem bus;      /* the memory bus (network aggregate_bandwidth) */
    WlPfArenaParams p;
    SimTime queued;     /* total time transfers waited for the bus */
    SimEngine *eng;
    GPtrArray *jobs;    /* stage runs under way (freed by _clear) */
    unsigned phase;     /* "arena": the processors' stalls */
} WlPfArena;

/* Splits `total` into n shares summing to it exactly: share i. */
uint64_t wl_pf_share(uint64_t total, guint i, guint n);
/* Share i of n of every count of o. */
void wl_pf_share_ops(MachOps *out, const MachOps *o, guint i, guint n);

/* An arena over m's memory bus: the network's aggregate_bandwidth and
 * startup; FALSE with *err naming the machine when it has none. */
gboolean wl_pf_arena_init(WlPfArena *a, SimEngine *eng, MachMachine *m,
                          const WlPfArenaParams *p, GError **err);
/* Frees the stage runs a cut run left under way. */
void wl_pf_arena_clear(WlPfArena *a);
/* Books `bytes` for processor p now on the bus; p stalls until their end,
 * then done(eng, ctx, arg); adds the wait for the bus to a->queued. */
void wl_pf_arena_move(WlPfArena *a, MachProc *p, uint64_t bytes,
                      SimHandler done, void *ctx, void *arg);
/* Runs work `c` (or the counts ops, when it has any: they price to c)
 * on p in phase `phase` in a->p.pieces pieces, each after its share of
 * `bytes`, then done(eng, ctx, arg). */
void wl_pf_arena_run(WlPfArena *a, MachProc *p, unsigned phase, SimTime c,
                     const MachOps *ops, uint64_t bytes, SimHandler done,
                     void *ctx, void *arg);

#endif
