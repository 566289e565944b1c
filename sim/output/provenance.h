/* provenance.h — where an output came from, in the same words for every
 * output: `run` (result.json, result.csv rows), sweeps (provenance.json,
 * results.csv comment lines) and reproductions (<paper>.json; comment
 * lines in <paper>.csv; a line in <paper>.txt and in the Markdown
 * report).
 *
 * The fields: pgsim_version (git describe at build time), config (the
 * input file's path), config_sha256 (of its bytes), overrides (the --set
 * items, in order), seed, fidelity, effective_config (the input tree
 * after the overrides, every scalar a string as written), inputs (each
 * model, scene, mesh, database and trace file read: kind, path, SHA-256
 * of its bytes; sim/core/inputs.h).  A model from outside the shipped
 * models/ folders is also named in a note line at the top of text
 * reports (prov_text_notes).
 */
#ifndef PGSIM_OUTPUT_PROVENANCE_H
#define PGSIM_OUTPUT_PROVENANCE_H

#include "sim/core/cfg.h"
#include "sim/core/inputs.h"
#include "sim/output/json.h"

typedef struct {
    const char *config;        /* path; NULL for a tree built in memory */
    const char *config_sha256; /* NULL when config is NULL */
    const GPtrArray *overrides; /* char *; NULL: none */
    guint64 seed;
    const char *fidelity;
    const char *effective_config; /* JSON text (prov_cfg_json) or NULL */
    const SimInputs *inputs; /* the files read; NULL: none */
} SimProvenance;

/* The pgsim build: git describe at build time; "unknown" outside git. */
const char *prov_version(void);
/* SHA-256 of a file's bytes as hex (g_free); NULL when unreadable. */
char *prov_file_sha256(const char *path);
/* A config tree as one-line JSON text (g_free): maps, sequences, every
 * scalar a string. */
char *prov_cfg_json(const CfgNode *n);
/* Adds the inputs as an array value [{kind, path, sha256, shipped}]. */
void prov_inputs_json(JsonBuilder *b, const SimInputs *inputs);
/* Adds member "provenance": {...} to the object being built. */
void prov_json(JsonBuilder *b, const SimProvenance *p);
/* The same as CSV rows "<section>,<name>,,<field>,<value>," for
 * report-style CSV (section "provenance"); fields quoted as needed. */
void prov_csv_rows(GString *out, const SimProvenance *p);
/* The same as comment lines "# <field>: <value>", one per field and one
 * "# override: ..." per --set item, for tabular CSV whose columns are
 * not name/value (sweep results, reproduction tables): readers skip
 * lines starting with '#' (dt_parse_csv, pgsim plot, pandas with
 * comment='#', R's read.csv with comment.char='#').  A line break inside
 * a value is written as "\n", so each field stays one line. */
void prov_comment_lines(GString *out, const SimProvenance *p);
/* The same as one line for text reports (no newline):
 * "provenance: pgsim V; config PATH (sha256 H); overrides A, B; seed N;
 * fidelity F; inputs KIND PATH (sha256 H), ..." (no effective config:
 * the JSON outputs hold it). */
void prov_text_line(GString *out, const SimProvenance *p);
/* For the first lines of a text report: one line per model read from
 * outside the shipped models/ folders, "note: machine model PATH is not
 * a shipped model (sha256 H)\n"; nothing when every model is shipped. */
void prov_text_notes(GString *out, const SimProvenance *p);
#endif
