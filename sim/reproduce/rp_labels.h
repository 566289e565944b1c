/* rp_labels.h — what each reproduced cell is: fitted, cross-validated,
 * predicted, a computed claim or a leave-one-out value.
 *
 * configs/papers/<paper>/labels.yaml says, as data, which cells each
 * fitted constant of the paper's models and setup used
 * (docs/reproduction-format.md, "Labels"):
 *
 *     claims: [{table: claims}]            # rows that are computed claims
 *     leave_one_out: [{table: cv}]         # rows holding leave-one-out values
 *     fits:
 *       - constant: ipsc2 node costs (models/ipsc2.yaml)
 *         cells: [{table: "2", row: "P16/..."}]  # column: any if omitted
 *         loo: {table: cv, row: "{row}", column: "{column}"}
 *
 * Patterns are GLib simple globs (* and ?).  A cell matched by a fit is
 * `fitted`, or `cross-validated` when the fit's `loo` template names a
 * produced row (its sim is the cell's value had the cell been left out
 * of the fit); every other cell is `predicted` (withheld, or never used
 * in any fit).  rp_labels_apply() labels a joined table and computes its
 * headline: the out-of-sample error (predicted cells at their error,
 * cross-validated cells at their leave-one-out error), the in-sample
 * error (fitted and cross-validated cells at the printed error) and the
 * leave-one-out intervals (rp_table.h).  O(cells x (patterns + cells)).
 */
#ifndef PGSIM_REPRODUCE_RP_LABELS_H
#define PGSIM_REPRODUCE_RP_LABELS_H

#include "sim/reproduce/rp_table.h"

#define RP_LABELS_FILE "labels.yaml"

typedef struct RpLabels RpLabels;

/* Reads a labels file; a new RpLabels (free with rp_labels_free()) or
 * NULL with a located *err. */
RpLabels *rp_labels_load(const char *path, GError **err);
void rp_labels_free(RpLabels *l);
/* Labels every cell of t and fills its headline (t->labelled TRUE). */
void rp_labels_apply(const RpLabels *l, RpTable *t);

#endif
