/* model_param.h — a model's parameters: their types, their provenance
 * and typed getters on a checked model tree (model.h checks it).
 *
 * A parameter P is a map {value: V, source|calibrated|assumption: "text",
 * note: "text"}, or a bare scalar or list given as an override by a file
 * other than the model's (its provenance is then "override").
 */
#ifndef PGSIM_MACHINE_MODEL_PARAM_H
#define PGSIM_MACHINE_MODEL_PARAM_H

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
    MACH_T_COUNT_LIST, /* sequence of counts (mesh extents) */
    MACH_T_NUMBER      /* a bare decimal >= 0 (cycles per unit of work) */
} MachType;

/* What an error expects of a value of type t ("a time with its unit, e.g.
 * '350 us'"); static text. */
const char *mach_type_example(MachType t);

/* Where a parameter's value comes from. */
typedef enum {
    MACH_PROV_NONE,       /* no such parameter */
    MACH_PROV_SOURCE,     /* a published figure */
    MACH_PROV_CALIBRATED, /* fitted to named published cells */
    MACH_PROV_ASSUMPTION, /* an estimate, with its reasoning */
    MACH_PROV_OVERRIDE    /* set by a run config over the model's value */
} MachProvenance;

/* The keys that give a provenance, NULL-terminated, in MachProvenance
 * order from MACH_PROV_SOURCE: "source", "calibrated", "assumption". */
extern const char *const mach_provenance_keys[];

/* The provenance of (map, key) and its text (borrowed; NULL for an
 * override or when absent): the provenance given in the same file as the
 * value, so an override of `value` alone (the model's source merged in
 * from another file) is an override. */
MachProvenance mach_param_provenance(const CfgNode *map, const char *key,
                                     const char **text);
const char *mach_provenance_name(MachProvenance p);

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
/* A bare decimal >= 0 (MACH_T_NUMBER). */
gboolean mach_param_number(const CfgNode *map, const char *key,
                           gboolean required, double *out, GError **err);
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
