/* rp_table.h — a reproduction's rows joined to the published values.
 *
 * rp_table_join() matches the rows a reproduction produced (RpRow) to the
 * cells of its paper (RpPaper) by (table, row, column) and computes
 * rel_error = (sim - published) / published.  Rows come first in the order
 * the reproduction made them; published cells it did not produce follow,
 * marked "not simulated".  The summary covers the compared cells: those
 * with a finite sim and a non-withheld, non-zero published value.
 *
 * Writers append to a GString: text for people, CSV
 * (paper,table,row,column,sim,published,rel_error; published and
 * rel_error empty where withheld or unknown) and JSON for programs.
 * Each carries the table's provenance (provenance.h): a line under the
 * text's title, "# " comment lines before the CSV rows, an object in
 * the JSON.
 */
#ifndef PGSIM_REPRODUCE_RP_TABLE_H
#define PGSIM_REPRODUCE_RP_TABLE_H

#include "sim/reproduce/rp_papers.h"
#include "sim/reproduce/reproduce.h"
#include "sim/core/error.h"
#include "sim/output/json.h"
#include "sim/output/provenance.h"

typedef enum {
    RP_COMPARED, /* sim and published both known */
    RP_WITHHELD, /* the paper's value is withheld: prediction only */
    RP_UNLISTED, /* the paper file has no such cell */
    RP_MISSING   /* published, but the reproduction did not produce it */
} RpStatus;

typedef struct {
    char *table, *row, *column;
    double sim;       /* NAN when not produced */
    double published; /* NAN when withheld / unlisted */
    double rel_error; /* NAN unless both known and published != 0 */
    RpStatus status;
    char *unit; /* from the paper file; "" if none */
    char *note; /* row note, else cell note; NULL if none */
} RpJoined;

typedef struct {
    char *paper;
    char *citation;
    char *fidelity;
    double wall_s;    /* wall time of the reproduction run; 0 if unknown */
    GPtrArray *cells; /* RpJoined * */
    guint compared;   /* cells with a finite rel_error */
    double mean_abs;  /* mean |rel_error| over them; NAN when none */
    double worst_abs; /* max |rel_error|; NAN when none */
    int worst;        /* index into cells of the worst; -1 when none */
    /* provenance (rp_driver.c): the setup file, its SHA-256 and its tree
     * as JSON text; NULL when the table was joined without a setup */
    char *setup, *setup_sha256, *setup_json;
} RpTable;

/* Joins rows (RpRow *, borrowed) to the paper; returns a new table (free
 * with rp_table_free()). */
RpTable *rp_table_join(const RpPaper *paper, const GPtrArray *rows,
                       const char *fidelity, double wall_s);
void rp_table_free(RpTable *t);
/* The cell for a key; NULL if none.  Borrowed. O(cells). */
const RpJoined *rp_table_find(const RpTable *t, const char *table,
                              const char *row, const char *column);
const char *rp_status_name(RpStatus s);

/* The table's provenance: its setup file as the config, its SHA-256 and
 * tree, RP_SEED and its fidelity (pointers borrowed from t). */
SimProvenance rp_table_provenance(const RpTable *t);
void rp_table_text(const RpTable *t, GString *out);
/* The provenance comment lines, then (header) the column header line,
 * then the rows; rp_table_csv_rows() writes the rows alone. */
void rp_table_csv(const RpTable *t, gboolean header, GString *out);
void rp_table_csv_rows(const RpTable *t, GString *out);
/* JSON (json-glib): paper, citation, fidelity, wall_s, provenance,
 * cells, summary; rp_table_node() is the same tree (json_node_unref). */
void rp_table_json(const RpTable *t, GString *out);
JsonNode *rp_table_node(const RpTable *t);
/* "mean |rel_error| 4.2% over 12 cells, worst 9.9% (table 2, 2POT,
 * tpg_400)" — the summary line (no newline). */
void rp_table_summary(const RpTable *t, GString *out);

#endif
