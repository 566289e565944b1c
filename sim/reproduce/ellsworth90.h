/* ellsworth90.h — `pgsim reproduce ellsworth90`: seed 001's table for
 * the four generated databases at the setup's GP counts (4 and 16).
 *
 * Rows (table "1"): one per database; columns simple_eff_P,
 * complex_eff_P, util_P, speedup_P for each P (efficiency and
 * utilisation in percent, of the complex algorithm for util and
 * speedup); by_structure_eff_P, by_structure_util_P and
 * by_structure_speedup_P are pgsim's own (§2.1's rejected
 * distribute-by-structure; the paper prints no such cells).  Table "db": the generated databases' depth, structures,
 * polys_per_structure, poly_attr_ratio, offscreen_pct.
 */
#ifndef PGSIM_REPRODUCE_ELLSWORTH90_H
#define PGSIM_REPRODUCE_ELLSWORTH90_H

#include "sim/core/cfg.h"
#include "sim/reproduce/reproduce.h"

/* What every cell runs (all borrowed). */
typedef struct {
    const CfgNode *cell;     /* a pphigs run config (setup.yaml's `cell`) */
    const char *fidelity;    /* run.fidelity of every cell */
    const guint *gp_counts;  /* the table's GP columns */
    guint n_gp;
    const RpContext *ctx;    /* the user's overrides and model folders
                                (rp_run_build); NULL: none */
} RpEllRig;

/* Appends RpRow * for the n databases named (`workload.database` of the
 * cell, in row order) at each of the rig's GP counts: one run of the
 * cell per database, GP count and algorithm.  FALSE with *err if a
 * database or the machine is bad. */
gboolean rp_ellsworth90_table1(const RpEllRig *rig, const char *const *dbs,
                               guint n, GPtrArray *rows, GError **err);

/* Appends the cv rows of loo.yaml beside `setup` (ellsworth90_cv.c):
 * cv/<db>/loo_<column> per left-out cell and refit_min_/refit_max_ of
 * each predicted cell; none when there is no loo.yaml.  FALSE with a
 * located *err on a bad file. */
gboolean rp_ellsworth90_loo(const char *setup, GPtrArray *rows,
                            GError **err);

extern const RpPaperOps rp_ellsworth90;

#endif
