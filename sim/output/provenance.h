/* provenance.h — where an output came from, in the same words for every
 * output: `run` (result.json, result.csv), sweeps (sweep.json) and
 * reproductions (<paper>.json, <paper>.csv).
 *
 * The fields: pgsim_version (git describe at build time), config (the
 * input file's path), config_sha256 (of its bytes), overrides (the --set
 * items, in order), seed, fidelity, effective_config (the input tree
 * after the overrides, every scalar a string as written).
 */
#ifndef PGSIM_OUTPUT_PROVENANCE_H
#define PGSIM_OUTPUT_PROVENANCE_H

#include "sim/core/cfg.h"
#include "sim/output/json.h"

typedef struct {
    const char *config;        /* path; NULL for a tree built in memory */
    const char *config_sha256; /* NULL when config is NULL */
    const GPtrArray *overrides; /* char *; NULL: none */
    guint64 seed;
    const char *fidelity;
    const char *effective_config; /* JSON text (prov_cfg_json) or NULL */
} SimProvenance;

/* The pgsim build: git describe at build time; "unknown" outside git. */
const char *prov_version(void);
/* SHA-256 of a file's bytes as hex (g_free); NULL when unreadable. */
char *prov_file_sha256(const char *path);
/* A config tree as one-line JSON text (g_free): maps, sequences, every
 * scalar a string. */
char *prov_cfg_json(const CfgNode *n);
/* Adds member "provenance": {...} to the object being built. */
void prov_json(JsonBuilder *b, const SimProvenance *p);
/* The same as CSV rows "<section>,<name>,,<field>,<value>," for
 * report-style CSV (section "provenance"); fields quoted as needed. */
void prov_csv_rows(GString *out, const SimProvenance *p);
#endif
