/* overlap.h — one piece of work whose parts run on overlapping
 * resources: it lasts as long as its longest part.
 *
 * A processor that feeds another through a FIFO (Performer's DRAW: the
 * CPU issues the display list while the bus carries it and the graphics
 * pipe renders it, seed 002) waits for the slowest of the three; its work
 * is not a sum of counts but a maximum of terms.  A MachOverlap holds the
 * worker's own named counts and up to MACH_TERMS_MAX further terms:
 * counts priced on another processor's kind (the pipe's triangles), or
 * bytes streamed through a shared memory (sim/machine/shmem.h), priced
 * as that transfer on an idle memory.  The other resources' own work
 * (the pipe's counts, the bus transfer) is submitted separately by the
 * caller; the terms only say how long the worker is held.
 *
 * A recording (`--record`) writes the work as a `c` line with `|` terms
 * (docs/traces.md), so a replay prices each term on its target and takes
 * the longest.  O(terms x counts) per piece of work.
 */
#ifndef PGSIM_MACHINE_OVERLAP_H
#define PGSIM_MACHINE_OVERLAP_H

#include "sim/machine/proc.h"

typedef struct MachShmem MachShmem;

#define MACH_TERMS_MAX 3

typedef struct {
    const MachProc *on;   /* counts: priced on its kind; bus: the receiver */
    MachOps ops;          /* counts (none for a bus term) */
    const MachShmem *bus; /* NULL: a count term */
    uint64_t bytes;       /* bus: bytes streamed to `on` */
} MachTerm;

typedef struct {
    MachOps own; /* the worker's counts, priced on its own kind */
    MachTerm term[MACH_TERMS_MAX];
    guint n; /* further terms */
} MachOverlap;

/* Empties o (no counts, no terms). */
void mach_overlap_reset(MachOverlap *o);
/* Adds a term: counts ops priced on processor on's kind. */
void mach_overlap_ops(MachOverlap *o, const MachProc *on, const MachOps *ops);
/* Adds a term: `bytes` streamed to processor `to` through bus. */
void mach_overlap_bus(MachOverlap *o, const MachShmem *bus, const MachProc *to,
                      uint64_t bytes);
/* The time worker p is held: the longest of its own counts' cost on its
 * kind and each term's (saturating). */
SimTime mach_overlap_cost(const MachProc *p, const MachOverlap *o);
/* Submits that time as work of p in `phase` (as mach_proc_compute());
 * o->own must hold at least one count.  Without further terms this is
 * mach_proc_compute_list() of o->own. */
gboolean mach_proc_compute_overlap(MachProc *p, const MachOverlap *o,
                                   unsigned phase, SimHandler done, void *ctx,
                                   void *arg);

#endif
