/* model.h — machine model files: loading and checking them; with
 * model_find.h (the search path) and model_param.h (types, provenance and
 * typed getters), which it includes.
 *
 * A model (models/<name>.yaml, docs/models.md) is a YAML tree:
 *
 *     schema_version: 1
 *     name: ipsc2
 *     description: ...            references: {key: text, ...}
 *     nodes:   {<kind>: {count: P, clock: P, ..., costs: {<op>: P}}}
 *     network: {topology: P, bandwidth: P, ...}
 *
 * where every parameter P is a map {value: V, source|calibrated|assumption:
 * "text", note: "text"}.  A time, bandwidth, frequency or size V must carry
 * its unit ("2.8 MB/s"), a count may not.  The checker rejects a missing
 * unit, a missing provenance or an unknown key with a located error.
 *
 * Other top-level sections belong to workloads (`pphigs:` in
 * pixel-planes-5.yaml): each entry needs a value and a provenance (a
 * string or a list of calibration cells); the workload parses it.
 *
 * Overrides: a run config may say `machine: {model: ipsc2, nodes: {node:
 * {count: 8}}}`.  The model is loaded, the section is deep-merged over it,
 * and a bare scalar that comes from a file other than the model file is
 * accepted as a user override (its provenance is "override").
 *
 * Cost: linear in the size of the tree.
 */
#ifndef PGSIM_MACHINE_MODEL_H
#define PGSIM_MACHINE_MODEL_H

#include "sim/core/cfg.h"
#include "sim/machine/model_find.h"
#include "sim/machine/model_param.h"

/* Loads and checks a model by name, found on the search path with the
 * `extra` folders (model_find.h; NULL for none).  Returns a new tree
 * (cfg_free) or NULL with *err set. */
CfgNode *mach_load_model_in(const char *name, const char *const *extra,
                            GError **err);
/* mach_load_model_in(name, NULL, err). */
CfgNode *mach_load_model(const char *name, GError **err);

/* Checks a model tree (after any merge): schema version, known keys,
 * units, provenance.  `model_file` is the file whose values must carry
 * provenance (NULL: every value must).  Marks every key it accepts as
 * read, so cfg_check_unused() afterwards finds nothing. */
gboolean mach_model_check(const CfgNode *root, const char *model_file,
                          GError **err);

/* The expected type of a node-kind or network key; FALSE if unknown. */
gboolean mach_kind_key_type(const char *key, MachType *out);
gboolean mach_net_key_type(const char *key, MachType *out);

#endif
