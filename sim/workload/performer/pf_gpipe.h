/* pf_gpipe.h — the graphics pipe as a process fed through a bounded
 * command FIFO on the bus (issue 36, point 1; seed 002's "three
 * bottlenecks": the host CPU, the bus, the graphics pipe).
 *
 * DRAW's CPU issues a frame's commands in chunks of `chunk` bytes: it
 * computes a chunk (busy), then writes it into the FIFO; the write
 * crosses the bus (a transfer booked on the machine's shared memory,
 * sim/machine/shmem.h) and lands in the pipe's queue.  The FIFO holds
 * `depth` bytes counted from the write until the pipe has consumed the
 * chunk; a write that does not fit blocks DRAW's CPU until the pipe frees
 * enough (back-pressure).  The pipe is a process: it takes chunks in
 * order and computes each at its own costs; it starts a frame's commands
 * only after the previous frame was swapped in (double-buffered frame
 * buffer) and swaps a frame at the first multiple of `swap_step` after
 * its last command.  So DRAW of frame n can issue while the pipe still
 * renders frame n - 1, and a frame's time is set by whichever of CPU,
 * bus and pipe is slowest, plus filling and draining the FIFO.
 *
 * Assumption: the commands of one frame are uniform, so every chunk
 * carries the same share (to the picosecond and byte, summing exactly)
 * of the frame's CPU time, bytes and pipe time.
 *
 * Accounting: the CPU's busy time is its chunks' work only; its blocked
 * time is the time it waits on a full FIFO; the pipe's busy time is its
 * work, its blocked time the wait for a swap, its idle time the rest.
 * Trace: busy spans in phases "draw" and "pipe", blocked spans in phases
 * "fifo_full" (DRAW's CPU) and "swap_wait" (the pipe), a flow per chunk.
 * A recording (`--record`) gets each chunk's counts and the joins: a
 * write after a full FIFO waits for the chunk's computation too, and a
 * chunk's computation on the pipe for its arrival and the pipe's
 * previous action.  O(1) per chunk, about four engine events per chunk.
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_GPIPE_H
#define PGSIM_WORKLOAD_PERFORMER_PF_GPIPE_H

#include "sim/workload/performer/pf_arena.h"

typedef struct WlPfGpipe WlPfGpipe;

/* The FIFO's defaults (the workload's `fifo`): assumptions, no source at
 * hand gives the RealityEngine2's command FIFO. */
#define WL_PF_FIFO_DEPTH (64 * 1024)
#define WL_PF_FIFO_CHUNK (8 * 1024)

/* One frame's work through the pipe: as named counts priced on each
 * processor's kind (cpu_ops, pipe_ops: each chunk gets its share of
 * every count, and a recording writes them), or, where a list is empty,
 * as the time beside it. */
typedef struct {
    SimTime cpu;    /* DRAW CPU's issuing time */
    uint64_t bytes; /* command bytes over the bus */
    SimTime pipe;   /* the pipe's time */
    MachOps cpu_ops, pipe_ops;
    uint64_t arena_bytes; /* DRAW's reads of the shared arena */
} WlPfDrawWork;

/* Where the FIFO's and the stages' time went, totals over the run. */
typedef struct {
    SimTime cpu_busy, cpu_blocked;
    SimTime pipe_busy, pipe_blocked;
    uint64_t chunks, max_used; /* chunks written; peak FIFO fill, bytes */
} WlPfGpipeStats;

/* Called when DRAW's CPU wrote frame n's last command (cpu_done) and at
 * frame n's swap (swapped, at the swap time). */
typedef void (*WlPfGpipeFn)(void *ctx, guint n);

/* A pipe fed by cpu through bus (borrowed), FIFO `depth` bytes, chunks of
 * `chunk` bytes (1 <= chunk <= depth). */
WlPfGpipe *wl_pf_gpipe_new(SimEngine *eng, MachProc *cpu, MachProc *pipe,
                           MachShmem *bus, uint64_t depth, uint64_t chunk);
void wl_pf_gpipe_free(WlPfGpipe *g);
/* Swaps fall on multiples of step (a retrace, or a frame boundary);
 * call before the first frame (wl_pf_pipe_run does). */
void wl_pf_gpipe_set_swap(WlPfGpipe *g, SimTime step, WlPfGpipeFn cpu_done,
                          WlPfGpipeFn swapped, void *ctx);
/* DRAW's CPU reads each chunk's share of the frame's arena_bytes over
 * a's memory bus before computing it (NULL: no arena). */
void wl_pf_gpipe_set_arena(WlPfGpipe *g, WlPfArena *a);
/* DRAW's CPU starts issuing frame n (frames in order, one at a time:
 * after the previous cpu_done). */
void wl_pf_gpipe_frame(WlPfGpipe *g, guint n, const WlPfDrawWork *w);
/* The pipe's end of frame n's last command (0 before it). */
SimTime wl_pf_gpipe_frame_end(const WlPfGpipe *g, guint n);
const WlPfGpipeStats *wl_pf_gpipe_stats(const WlPfGpipe *g);

#endif
