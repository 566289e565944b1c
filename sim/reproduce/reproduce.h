/* reproduce.h — paper reproductions: one small table of hooks per paper.
 *
 * A paper lives in two places: sim/reproduce/<name>.c (its RpPaperOps:
 * name, citation, setup file, rows hook) and configs/papers/<name>/
 * (published.yaml: what the paper printed; setup.yaml: what to simulate).
 * Adding a paper is one file here, one line in rp_registry.c and one
 * folder of YAML.  The rows hook regenerates the paper's tables by
 * running the simulator and fills rows (table, row, column, sim).
 * Published values are never in C: the driver reads them from
 * published.yaml and joins them to the rows by (table, row, column); a
 * withheld cell has no published value and the prediction is printed all
 * the same.  The driver
 * (`pgsim reproduce NAME|all [--format text|csv|json] [--out DIR]
 * [--fidelity faithful|analytic|flow|packet|all]`) prints the table with the
 * relative error (sim - published) / published, writes charts, and
 * reports wall time per fidelity.
 *
 * CSV columns: paper,table,row,column,sim,published,rel_error
 */
#ifndef PGSIM_REPRODUCE_REPRODUCE_H
#define PGSIM_REPRODUCE_REPRODUCE_H

#include "sim/output/progress.h"
#include <glib.h>

/* The seed of every engine a reproduction starts (recorded in the
 * provenance of its outputs). */
#define RP_SEED 1

typedef struct {
    char *table;  /* "1", "2", "fig1", "text" ... */
    char *row;    /* "2POT", "P16/2POT" ... */
    char *column; /* "tpg_400", "pair_rs_merge_ms" ... */
    double sim;   /* NAN when the simulator could not produce it */
    char *note;   /* optional ("out of memory in the paper"); NULL */
} RpRow;

typedef struct {
    const char *setup;    /* the paper's setup file (path, borrowed) */
    const char *fidelity; /* network fidelity for this pass */
    const char *out_dir;  /* where charts may be written; NULL for none */
    gboolean quiet;       /* no progress output */
    RptProgress *progress; /* the caller's progress line; NULL: none */
    GString *fidelity_used; /* the driver's: see rp_note_fidelity() */
    const char *const *sets; /* the user's machine.KEY=VALUE overrides,
                                NULL-terminated, applied after a paper's
                                own to every run it makes (rp_run_build);
                                NULL: none */
    const char *const *models; /* more model folders, searched before the
                                  usual extra folders (run.h); NULL: none */
} RpContext;

/* A paper reports that it is about to simulate `what` ("2POT N=400
 * P=16"): the progress line (a terminal only) counts it and shows it. */
void rp_step(const RpContext *ctx, const char *what);
/* A paper reports the transport a machine of its runs used
 * (mach_fidelity(), "packet (faithful)"): the table's fidelity then
 * names it ("faithful: ipsc2 packet").  Once per (machine, word). */
void rp_note_fidelity(const RpContext *ctx, const char *machine,
                      const char *fidelity);

typedef struct {
    const char *name;     /* "kurc96": also its folder configs/papers/<name> */
    const char *citation; /* one line: authors, title, what is simulated */
    const char *setup;    /* setup file in that folder: "setup.yaml" */
    /* Runs the simulations described by ctx->setup; appends RpRow * (made
     * with rp_row_new) to rows.  FALSE with *err on failure. */
    gboolean (*rows)(const RpContext *ctx, GPtrArray *rows, GError **err);
    /* CPU seconds of one faithful pass on the 2-core development machine,
     * a hint only: `reproduce all -j` starts the costliest papers first
     * (0: cheap or unknown).  Never changes a result. */
    double cost_s;
} RpPaperOps;

/* Returns a new row (copies strings); the array's free func is
 * rp_row_free. */
RpRow *rp_row_new(const char *table, const char *row, const char *column,
                  double sim, const char *note);
void rp_row_free(gpointer row);

/* NULL-terminated list of every reproduction (sim/reproduce/rp_registry.c). */
extern const RpPaperOps *const rp_all[];
const RpPaperOps *rp_find(const char *name);

#endif
