/* reproduce.h — paper reproductions: the contract between workloads and
 * the reproduction driver.
 *
 * A reproduction regenerates a paper's tables by running the simulator
 * and fills rows (paper, table, row, column, sim).  Published values are
 * never in C: the driver reads them from configs/papers/<name>.yaml and
 * joins them to the rows by (table, row, column); a withheld cell has no
 * published value and the prediction is printed all the same.  The driver
 * (`pgsim reproduce NAME|all [--format text|csv|json] [--out DIR]
 * [--fidelity analytic|flow|packet|all]`) prints the table with the
 * relative error (sim - published) / published, writes charts, and
 * reports wall time per fidelity.
 *
 * CSV columns: paper,table,row,column,sim,published,rel_error
 */
#ifndef PGSIM_APP_REPRODUCE_H
#define PGSIM_APP_REPRODUCE_H

#include <glib.h>

typedef struct {
    char *table;  /* "1", "2", "fig1", "text" ... */
    char *row;    /* "2POT", "P16/2POT" ... */
    char *column; /* "tpg_400", "pair_rs_merge_ms" ... */
    double sim;   /* NAN when the simulator could not produce it */
    char *note;   /* optional ("out of memory in the paper"); NULL */
} RpRow;

typedef struct {
    const char *fidelity; /* network fidelity for this pass */
    const char *out_dir;  /* where charts may be written; NULL for none */
    gboolean quiet;       /* no progress output */
} RpContext;

typedef struct {
    const char *name; /* "kurc96", "ellsworth90" */
    const char *summary;
    /* Runs the simulations; appends RpRow * (made with rp_row_new) to
     * rows.  FALSE with *err on failure. */
    gboolean (*run)(const RpContext *ctx, GPtrArray *rows, GError **err);
} RpReproduction;

/* Returns a new row (copies strings); the array's free func is
 * rp_row_free. */
RpRow *rp_row_new(const char *table, const char *row, const char *column,
                  double sim, const char *note);
void rp_row_free(gpointer row);

/* NULL-terminated list of every reproduction (sim/app/reproductions.c). */
extern const RpReproduction *const rp_all[];
const RpReproduction *rp_find(const char *name);

#endif
