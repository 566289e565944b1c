/* costs.h — the one home for pricing: a machine's costs per node kind,
 * each with where it comes from, and the cost sets workloads declare.
 *
 * A cost is the time of one named operation on one node kind
 * (`nodes.KIND.costs.OP` of a model, docs/models.md).  The machine reads
 * each kind's table once when it is built (mach_cost_table_new) into
 * MachCost values that carry their provenance: today every cost is
 * `model` (an explicit value in a model file, or a run config's override
 * of it: the file, line and column of the value, the model key and the
 * source / calibration / assumption text the model gives); issue 34's
 * costs derived from a processor description will be `derived`.
 *
 * A workload declares the costs it reads once, in a MachNeed table (the
 * WlNeed table of its WlOps: kind + NULL-terminated op names, ended by a
 * NULL kind), and asks the machine for them with mach_costs_new(): every
 * missing cost of the table is listed in one located error, not one at a
 * time.  The set then answers prices (mach_costs_get, mach_costs_times)
 * and provenance (mach_costs_find, mach_costs_nth).  "count x cost" is
 * sim_time_mul_sat() (sim/core/time.h) everywhere, here included.
 *
 * Ownership: a set borrows the machine's tables (the machine must outlive
 * it).  Cost: O(declared costs) to build, one hash lookup per kind; a
 * lookup by name is O(declared costs) (sets are a few dozen entries:
 * workloads read them once, at setup, or price named counts through
 * mach_proc_compute_ops(), which uses the same tables).
 */
#ifndef PGSIM_MACHINE_COSTS_H
#define PGSIM_MACHINE_COSTS_H

#include "sim/core/cfg.h"
#include "sim/core/time.h"
#include "sim/core/result.h"
#include "sim/machine/model.h"
#include "sim/machine/proc.h"
#include "sim/machine/work.h"

typedef struct MachMachine MachMachine;

/* Where a cost's value comes from. */
typedef enum {
    MACH_COST_MODEL,  /* explicit: a model file's value (or an override) */
    MACH_COST_DERIVED /* computed from the op's work (work.h) on the
                         kind's processor description (issue 34) */
} MachCostFrom;

/* One cost and its provenance.  Strings are borrowed from the machine's
 * model tree. */
typedef struct {
    SimTime value;       /* first member: the time of one operation */
    MachCostFrom from;
    MachProvenance prov; /* source, calibrated, assumption or override */
    const char *kind, *op;
    const char *file; /* the file the value was read from: the model, or
                         the run config / --set of an override */
    int line, col;
    const char *text; /* the model's source / calibration / assumption
                         text; NULL for an override or a list of cells;
                         derived: the work and what priced it */
    double work[MACH_W_N]; /* derived: the op's work per class; else 0 */
} MachCost;

/* A workload's declared costs on one node kind: ops is NULL-terminated;
 * a table of them ends with a NULL kind.  (WlNeed in workload.h.)
 * work (may be NULL) states each op's work in machine-independent
 * classes (work.h): a cost the model lacks is derived from it when the
 * kind has a processor description that prices those classes. */
typedef struct {
    const char *kind;
    const char *const *ops;
    const MachWork *work;
} MachNeed;

/* ---- the machine's tables ------------------------------------------------ */

/* Reads a kind's `costs` map (may be NULL: no costs) of a checked model
 * tree into a new table op name -> MachCost * (g_hash_table_destroy);
 * names borrowed from the tree.  NULL with *err on a malformed time. */
GHashTable *mach_cost_table_new(const char *kind, const CfgNode *costs,
                                GError **err);

/* The cost of `op` on `kind` with its provenance (borrowed), or NULL when
 * the machine has no such kind or the kind no such cost. */
const MachCost *mach_cost_info(const MachMachine *m, const char *kind,
                               const char *op);
/* Cost of one `op` on `kind`.  mach_cost() asserts that it exists;
 * mach_cost_lookup() reports a missing one as a located input error. */
SimTime mach_cost(const MachMachine *m, const char *kind, const char *op);
gboolean mach_cost_lookup(const MachMachine *m, const char *kind,
                          const char *op, SimTime *out, GError **err);
/* Checks that `kind` exists and has every op of the NULL-terminated list;
 * all missing ones in one error (mach_costs_check). */
gboolean mach_require_costs(const MachMachine *m, const char *kind,
                            const char *const *ops, GError **err);

/* ---- a workload's cost set ----------------------------------------------- */

typedef struct MachCosts MachCosts;

/* The costs `needs` declares, from machine m: each explicit cost, else
 * one derived from its declared work on the kind's processor description
 * (added to the machine's table, provenance `derived`, so the processors
 * price named counts with it).  Returns a new set (mach_costs_free), or
 * NULL with one located error listing every missing kind and cost
 * ("FILE:L:C: found no cost for 'op' on 'kind', expected ...; N
 * missing:" then one "FILE:L:C: nodes.KIND.costs.OP" line each, with the
 * class to describe where the op has work). */
MachCosts *mach_costs_new(const MachMachine *m, const MachNeed *needs,
                          GError **err);
void mach_costs_free(MachCosts *c);
/* mach_costs_new() and free: TRUE when every declared cost is there. */
gboolean mach_costs_check(const MachMachine *m, const MachNeed *needs,
                          GError **err);

/* The declared cost (borrowed), or NULL when `needs` did not declare it. */
const MachCost *mach_costs_find(const MachCosts *c, const char *kind,
                                const char *op);
/* Its value (asserted declared); n of them, saturating. */
SimTime mach_costs_get(const MachCosts *c, const char *kind, const char *op);
SimTime mach_costs_times(const MachCosts *c, const char *kind, const char *op,
                         uint64_t n);
/* dst[i] = value of ops[i] on kind, for each op of the NULL-terminated
 * list (each asserted declared). */
void mach_costs_fill(const MachCosts *c, const char *kind,
                     const char *const *ops, SimTime *const *dst);
/* The set's costs in declaration order, for reports. */
guint mach_costs_len(const MachCosts *c);
const MachCost *mach_costs_nth(const MachCosts *c, guint i);

/* Adds to r one note listing the costs of kind k derived so far (op,
 * time, work), in op order; nothing when none is derived. */
void mach_costs_note_derived(const MachKindInfo *k, SimResult *r);

/* "model" or "derived". */
const char *mach_cost_from_name(MachCostFrom f);
/* One line for a report: "nodes.node.costs.polygon = 955.7 us (model,
 * calibrated, models/ipsc2.yaml:52:9)".  A new string (g_free). */
char *mach_cost_describe(const MachCost *c);

#endif
