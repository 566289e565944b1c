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

typedef enum {
    RP_LABEL_NONE,      /* the paper has no labels file */
    RP_LABEL_FITTED,    /* used in a fit, no leave-one-out value */
    RP_LABEL_CV,        /* used in a fit, leave-one-out value beside it */
    RP_LABEL_PREDICTED, /* withheld, or never used in any fit */
    RP_LABEL_CLAIM,     /* a claim computed on the simulated data */
    RP_LABEL_LOO        /* a leave-one-out value shown beside its cell */
} RpLabel;

typedef struct {
    char *table, *row, *column;
    double sim;       /* NAN when not produced */
    double published; /* NAN when withheld / unlisted */
    double rel_error; /* NAN unless both known and published != 0 */
    RpStatus status;
    char *unit; /* from the paper file; "" if none */
    char *note; /* row note, else cell note; NULL if none */
    /* rp_labels.h: what the cell is (RP_LABEL_NONE until labelled) */
    RpLabel label;
    char *fitted_by;      /* the constants fitted on it; NULL if none */
    double loo_sim;       /* its leave-one-out value; NAN if none */
    double loo_rel_error; /* (loo_sim - published) / published; or NAN */
    double lo, hi;        /* its interval for the published value; NAN */
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
    /* rp_labels_apply(): the headline.  Out of sample: predicted cells at
     * their error and cross-validated ones at their leave-one-out error;
     * in sample: fitted and cross-validated cells at the printed error.
     * Intervals: the range [loo_min, loo_max] of the cross-validated
     * cells' leave-one-out errors; a visible cell is inside its own
     * interval when its out-of-sample error lies in the range of the
     * other cells' leave-one-out errors. */
    gboolean labelled;
    guint oos_n, oos_cv, ins_n; /* cells in each mean */
    double oos_mean, oos_worst, ins_mean, ins_worst; /* NAN when none */
    int oos_worst_i, ins_worst_i;                    /* -1 when none */
    guint loo_n;                /* leave-one-out errors in the range */
    double loo_min, loo_max;    /* NAN when loo_n < 2 */
    guint inside, inside_of;    /* visible cells in their own interval */
    GPtrArray *overrides; /* char *: the user's --set items; NULL: none */
    SimInputs *inputs;    /* the files the paper's runs read; NULL: none */
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
/* "fitted", "cross-validated", "predicted", "claim", "leave-one-out";
 * "" for RP_LABEL_NONE. */
const char *rp_label_name(RpLabel l);
/* The cell's label as printed: "fitted (ipsc2 node costs)",
 * "cross-validated: left out 258.2 (-19.8%)", "predicted, in [a, b]";
 * new string (g_free). */
char *rp_label_text(const RpJoined *j);

/* The table's provenance: its setup file as the config, its SHA-256 and
 * tree, RP_SEED and its fidelity (pointers borrowed from t). */
SimProvenance rp_table_provenance(const RpTable *t);
void rp_table_text(const RpTable *t, GString *out);
/* The provenance comment lines, then (header) the column header line,
 * then the rows; rp_table_csv_rows() writes the rows alone. */
void rp_table_csv(const RpTable *t, gboolean header, GString *out);
void rp_table_csv_rows(const RpTable *t, GString *out);
/* The column header without its newline (labelled tables add label,
 * fitted_by, loo_sim, loo_rel_error, interval_lo, interval_hi). */
void rp_table_csv_head(const RpTable *t, GString *out);
/* JSON (json-glib): paper, citation, fidelity, wall_s, provenance,
 * cells, summary; rp_table_node() is the same tree (json_node_unref). */
void rp_table_json(const RpTable *t, GString *out);
JsonNode *rp_table_node(const RpTable *t);
/* "mean |rel_error| 4.2% over 12 cells, worst 9.9% (table 2, 2POT,
 * tpg_400)" — the summary line (no newline). */
void rp_table_summary(const RpTable *t, GString *out);

#endif
