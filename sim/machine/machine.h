/* machine.h — a machine assembled from a model: node kinds, processors,
 * cost tables and the network parameters.
 *
 * Built from the `machine` section of a run config: `model: <name>` loads
 * models/<name>.yaml (model.h) and the rest of the section is deep-merged
 * over it as overrides; without `model:` the section itself is the model.
 * Processors are numbered in node-kind order (host 0, gp 1..16, ...);
 * those are also the network endpoint numbers.
 *
 * Costs are SimTime per named operation of a node kind, each with its
 * provenance: costs.h, the one home for pricing (a workload declares its
 * costs in a table and reads them from the set mach_costs_new() fills).
 *
 * The network: the machine builds a NetNet (sim/net/net.h) from the
 * model's `network` section at the requested fidelity (mnet.h); links get
 * state only when a message uses them.  Topologies the machine layer
 * cannot build yet leave mach_net() NULL and mach_require_net() explains.
 * The checked section and typed getters stay available for workloads.
 *
 * Memory: one hash table of costs per node kind; MachProcs are made 64
 * at a time when one of them is first asked for, so a machine whose
 * processors are never touched holds one pointer per 64 processors;
 * nothing per link until messages flow.
 */
#ifndef PGSIM_MACHINE_MACHINE_H
#define PGSIM_MACHINE_MACHINE_H

#include "sim/core/cfg.h"
#include "sim/core/result.h"
#include "sim/machine/costs.h"
#include "sim/machine/proc.h"
#include "sim/net/net.h"


/* Builds a machine from a config's `machine` section (borrowed; copied).
 * `fidelity` is "analytic", "flow", "packet" or MACH_FIDELITY_FAITHFUL:
 * the model's own `network.fidelity` (the transport that models its
 * hardware, e.g. circuit switching on the iPSC/2 = "packet"), reported
 * by mach_fidelity() as "<word> (faithful)".  A `model:` name is found on
 * the model search path with the extra folders `model_dirs` (a
 * NULL-terminated array, borrowed, or NULL: model_find.h), searched after
 * ./models and $PGSIM_MODELS and before the shipped models.  Returns a
 * new machine (mach_free) or NULL with *err set (unknown model, bad
 * override ...). */
MachMachine *mach_new_from_cfg_in(SimEngine *eng, const CfgNode *section,
                                  const char *fidelity,
                                  const char *const *model_dirs, GError **err);
/* mach_new_from_cfg_in() without extra folders. */
MachMachine *mach_new_from_cfg(SimEngine *eng, const CfgNode *section,
                               const char *fidelity, GError **err);
/* Checks a config's `machine` section early (load, merge, check) and
 * marks all of its keys read, so that cfg_check_unused() on the whole
 * config accepts them.  The app calls it before cfg_check_unused().
 * `model_dirs` as for mach_new_from_cfg_in(). */
gboolean mach_check_section_in(const CfgNode *section,
                               const char *const *model_dirs, GError **err);
gboolean mach_check_section(const CfgNode *section, GError **err);
/* The model tree of a section, unchecked: the model named by `model:`
 * (found as above) with the section deep-merged over it, or a copy of
 * the section itself.  Returns a new tree (cfg_free) and in *model_file
 * (g_free) the file whose values need provenance; NULL with *err if the
 * model is missing. */
CfgNode *mach_section_tree_in(const CfgNode *section,
                              const char *const *model_dirs, char **model_file,
                              GError **err);
CfgNode *mach_section_tree(const CfgNode *section, char **model_file,
                           GError **err);
/* mach_new_from_cfg() from a model name alone (no overrides). */
MachMachine *mach_new_from_model(SimEngine *eng, const char *name,
                                 const char *fidelity, GError **err);
void mach_free(MachMachine *m);

const char *mach_name(const MachMachine *m);
const char *mach_fidelity(const MachMachine *m);
/* The fidelity word that asks for the model's own (see above). */
#define MACH_FIDELITY_FAITHFUL "faithful"
SimEngine *mach_engine(const MachMachine *m);
/* The merged, checked model tree (borrowed). */
const CfgNode *mach_model_cfg(const MachMachine *m);

/* Node kinds, in model order. */
guint mach_kind_count(const MachMachine *m);
const MachKindInfo *mach_kind_at(const MachMachine *m, guint i);
/* NULL when the machine has no such kind. */
const MachKindInfo *mach_kind(const MachMachine *m, const char *kind);

/* Processors. */
guint mach_proc_total(const MachMachine *m);
MachProc *mach_proc_at(MachMachine *m, guint id);
/* The i-th processor of a kind (asserts the kind exists, i < count). */
MachProc *mach_proc(MachMachine *m, const char *kind, guint i);

/* Costs: mach_cost(), mach_cost_lookup(), mach_costs_new() ... in
 * costs.h. */

/* The machine's network (borrowed), or NULL if its topology is not yet
 * built by the machine layer; mach_require_net() then says so in *err. */
NetNet *mach_net(const MachMachine *m);
gboolean mach_require_net(const MachMachine *m, GError **err);

/* The checked network section (borrowed) and its typed parameters.
 * Getters return FALSE when the key is absent (no error) and leave *out. */
const CfgNode *mach_network_cfg(const MachMachine *m);
const char *mach_net_word(const MachMachine *m, const char *key);
gboolean mach_net_time(const MachMachine *m, const char *key, SimTime *out);
gboolean mach_net_bandwidth(const MachMachine *m, const char *key, double *out);
gboolean mach_net_size(const MachMachine *m, const char *key, uint64_t *out);
gboolean mach_net_count(const MachMachine *m, const char *key, uint64_t *out);
/* Per-level bandwidths (bytes/s) in a new GArray of double, or NULL. */
GArray *mach_net_bw_list(const MachMachine *m, const char *key);

/* Copies machine name, fidelity, phase names, every processor's busy
 * time (overall and per phase, in processor-id order) and the network's
 * communication statistics into r. */
void mach_fill_result(const MachMachine *m, SimResult *r);

#endif
