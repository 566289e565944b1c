/* proc.h — processors: serialised work with busy-time accounting.
 *
 * A MachProc runs one piece of work at a time.  mach_proc_compute() on a
 * busy processor queues the work behind everything already submitted
 * (FIFO): it starts when the processor frees and its `done` handler runs
 * at start + cost.  Busy time is charged to the given phase (phase ids
 * from sim_engine_phase()) when the work is submitted, and a trace span
 * [start, end) is emitted if a trace is attached.
 *
 * Model only what is touched: a processor is a few words in its
 * machine's array; its engine entity, name and per-phase array are made
 * the first time it computes.  The FIFO needs no queue: it is the
 * processor's `free_at` time, because completions are scheduled in
 * submission order at non-decreasing times and the engine breaks ties by
 * schedule order.  Cost: O(1) plus one engine event per request.
 */
#ifndef PGSIM_MACHINE_PROC_H
#define PGSIM_MACHINE_PROC_H

#include "sim/core/engine.h"
#include "sim/core/record.h"
#include "sim/core/stats.h"
#include "sim/machine/work.h"

typedef struct MachMachine MachMachine;
typedef struct MachProc MachProc;

/* What a node kind is: borrowed from the machine. */
typedef struct {
    const char *name; /* "gp", "renderer", "node" ... */
    guint first;      /* global id of its first processor */
    guint count;
    double clock_hz;      /* 0 when the model gives none */
    uint64_t memory;      /* bytes per node, 0 when not given */
    uint64_t lanes;       /* SIMD lanes per processor, 1 if not SIMD */
    uint64_t lane_memory; /* bytes per lane, 0 when not given */
    GHashTable *costs;    /* op name -> MachCost * (costs.h): its costs,
                             explicit ones and those derived so far */
    MachProcDesc desc;    /* its processor description (work.h) */
} MachKindInfo;

/* Submits `cost` of work in `phase`; done(eng, ctx, arg) runs when it
 * completes (done may be NULL: the work only occupies the processor).
 * Returns FALSE if the completion time overflows SimTime (the engine is
 * then stopped with SIM_ERROR_OVERFLOW). */
gboolean mach_proc_compute(MachProc *p, SimTime cost, unsigned phase,
                           SimHandler done, void *ctx, void *arg);

/* A named operation count, {name, count}: the name is a cost of the
 * processor's kind (`nodes.KIND.costs.NAME`). */
typedef SimOp MachOp;

/* The same work given as n_ops >= 1 counts: cost = sum of count x mach_cost()
 * of each name on the processor's kind (asserted to exist: check with
 * mach_costs_new() first), saturating.  Same time, busy time and
 * events as mach_proc_compute() of that cost; a recording (`--record`)
 * writes the names and counts (a `c` line, docs/traces.md) instead of
 * the time, so a replay prices them from its target's cost table. */
gboolean mach_proc_compute_ops(MachProc *p, const MachOp *ops, guint n_ops,
                               unsigned phase, SimHandler done, void *ctx,
                               void *arg);

/* Work of `cost` that the caller priced from n_ops >= 1 named counts of
 * constants outside the kind's cost table (a workload's own section of
 * the model: `dpscan.op`, docs/traces.md); the same as
 * mach_proc_compute() of cost, but a recording writes the names and
 * counts, not the time. */
gboolean mach_proc_compute_priced(MachProc *p, SimTime cost, const MachOp *ops,
                                  guint n_ops, unsigned phase, SimHandler done,
                                  void *ctx, void *arg);

/* Named counts gathered for one piece of work: mach_ops_add() adds to
 * the entry of that name (a static string) or appends one. */
#define MACH_OPS_MAX 16
typedef struct {
    MachOp op[MACH_OPS_MAX];
    guint n;
} MachOps;

void mach_ops_add(MachOps *o, const char *name, uint64_t count);
/* o's time on p's kind: what mach_proc_compute_ops() charges for it. */
SimTime mach_proc_ops_cost(const MachProc *p, const MachOps *o);
/* mach_proc_compute_ops() of o; an empty o is a time of 0. */
gboolean mach_proc_compute_list(MachProc *p, const MachOps *o, unsigned phase,
                                SimHandler done, void *ctx, void *arg);

/* For sim/machine/overlap.c: work of `cost` (the longest of its terms,
 * priced by the caller) that a recording writes as the worker's counts
 * w->ops (n_ops >= 1) and the further terms (a `c` line with `|`
 * terms). */
gboolean mach_proc_compute_terms(MachProc *p, SimTime cost, const SimWork *w,
                                 unsigned phase, SimHandler done, void *ctx,
                                 void *arg);

/* The time at which all work submitted so far completes (<= now: idle). */
SimTime mach_proc_free_at(const MachProc *p);
gboolean mach_proc_idle(const MachProc *p);

/* Busy time over all phases / in one phase, of work submitted so far. */
SimTime mach_proc_busy(const MachProc *p);
SimTime mach_proc_busy_phase(const MachProc *p, unsigned phase);
/* Requests submitted so far. */
uint64_t mach_proc_requests(const MachProc *p);

/* Global id (0 .. mach_proc_total()-1, in node-kind order), the index
 * within its kind, the kind name (borrowed) and the name ("gp3"). */
guint mach_proc_id(const MachProc *p);
guint mach_proc_index(const MachProc *p);
const char *mach_proc_kind(const MachProc *p);
const char *mach_proc_name(MachProc *p);
/* The engine entity of this processor (registered on first use). */
uint32_t mach_proc_entity(MachProc *p);
MachMachine *mach_proc_machine(const MachProc *p);

/* ---- for machine.c only ------------------------------------------------ */

struct MachProc {
    MachMachine *m;           /* opaque here: only handed back */
    SimEngine *eng;           /* the machine's engine */
    const MachKindInfo *info; /* its kind (the machine's, stable) */
    SimTime free_at;
    SimBusy busy; /* per_phase NULL until first used */
    uint64_t requests;
    char *name;      /* NULL until first asked for */
    uint32_t entity; /* UINT32_MAX until first asked for */
    guint id;
    guint16 kind;
};

void mach_proc_init(MachProc *p, MachMachine *m, SimEngine *eng,
                    const MachKindInfo *info, guint id, guint16 kind);
void mach_proc_clear(MachProc *p);

#endif
