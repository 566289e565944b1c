/* model.h — machine model files: finding, loading and checking them.
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

/* The type of a parameter's value. */
typedef enum {
    MACH_T_WORD,      /* a bare word: "hypercube", "e-cube" */
    MACH_T_COUNT,     /* dimensionless count, optional K/M suffix */
    MACH_T_TIME,      /* SimTime */
    MACH_T_BANDWIDTH, /* bytes per second */
    MACH_T_FREQ,      /* Hz */
    MACH_T_SIZE,      /* bytes */
    MACH_T_BW_LIST,   /* sequence of bandwidths (per fat-tree level) */
    MACH_T_COUNT_LIST /* sequence of counts (mesh extents) */
} MachType;

/* The model search path, a union with the user's folders first: ./models,
 * each directory of $PGSIM_MODELS (colon-separated; the run-config
 * loader appends the config's project models/ and the install's), then
 * models/ under every data root (sim_data_roots: $PGSIM_DATA, the build
 * tree, share/pgsim).  A new array of strings (g_ptr_array_free(a, TRUE)).
 * A folder holding a user's own model hides none of the shipped ones. */
GPtrArray *mach_model_dirs(void);
/* Finds <name>.yaml in the first folder of mach_model_dirs() that has it.
 * Returns a newly allocated path (g_free) or NULL with *err set (the
 * error lists the folders that exist). */
char *mach_model_path(const char *name, GError **err);

/* Loads and checks a model by name.  Returns a new tree (cfg_free) or
 * NULL with *err set. */
CfgNode *mach_load_model(const char *name, GError **err);

/* Checks a model tree (after any merge): schema version, known keys,
 * units, provenance.  `model_file` is the file whose values must carry
 * provenance (NULL: every value must).  Marks every key it accepts as
 * read, so cfg_check_unused() afterwards finds nothing. */
gboolean mach_model_check(const CfgNode *root, const char *model_file,
                          GError **err);

/* Where a parameter's value comes from. */
typedef enum {
    MACH_PROV_NONE,       /* no such parameter */
    MACH_PROV_SOURCE,     /* a published figure */
    MACH_PROV_CALIBRATED, /* fitted to named published cells */
    MACH_PROV_ASSUMPTION, /* an estimate, with its reasoning */
    MACH_PROV_OVERRIDE    /* set by a run config over the model's value */
} MachProvenance;

/* The provenance of (map, key) and its text (borrowed; NULL for an
 * override or when absent): the provenance given in the same file as the
 * value, so an override of `value` alone (the model's source merged in
 * from another file) is an override. */
MachProvenance mach_param_provenance(const CfgNode *map, const char *key,
                                     const char **text);
const char *mach_provenance_name(MachProvenance p);

/* The expected type of a node-kind or network key; FALSE if unknown. */
gboolean mach_kind_key_type(const char *key, MachType *out);
gboolean mach_net_key_type(const char *key, MachType *out);

/* A parameter's value node: the `value` of a parameter map, or the bare
 * scalar/sequence of an override.  NULL if `map` has no such key. */
const CfgNode *mach_param_node(const CfgNode *map, const char *key);

/* Typed getters on a checked tree; FALSE with *err when absent (if
 * required) or malformed.  An absent optional key leaves *out alone. */
gboolean mach_param_time(const CfgNode *map, const char *key, gboolean required,
                         SimTime *out, GError **err);
gboolean mach_param_count(const CfgNode *map, const char *key,
                          gboolean required, uint64_t *out, GError **err);
gboolean mach_param_bandwidth(const CfgNode *map, const char *key,
                              gboolean required, double *out, GError **err);
gboolean mach_param_freq(const CfgNode *map, const char *key, gboolean required,
                         double *out, GError **err);
gboolean mach_param_size(const CfgNode *map, const char *key, gboolean required,
                         uint64_t *out, GError **err);
/* A list of bandwidths (bytes/s); *out is a new GArray of double
 * (g_array_unref) or untouched when the optional key is absent. */
gboolean mach_param_bw_list(const CfgNode *map, const char *key,
                            gboolean required, GArray **out, GError **err);
/* A list of counts; *out is a new GArray of uint64_t (g_array_unref) or
 * untouched when the optional key is absent. */
gboolean mach_param_count_list(const CfgNode *map, const char *key,
                               gboolean required, GArray **out, GError **err);
/* A word value (borrowed), or NULL when absent. */
const char *mach_param_word(const CfgNode *map, const char *key);

#endif
