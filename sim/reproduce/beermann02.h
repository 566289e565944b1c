/* beermann02.h — `pgsim reproduce beermann02`: the statements of seed 002
 * (Dale Beermann's slides "Interfaces and Software Systems": IRIS
 * Performer, the Argus parallel graphics interface, Curved PN triangles)
 * each decided on simulated runs.
 *
 * Everything a statement is decided on is data in
 * configs/papers/beermann02/setup.yaml:
 *
 *   runs:    NAME: {config: PATH (relative to setup.yaml), set: [k=v ...]}
 *   claims:  ID: {part, slide, says, reading, if_not, tests: [TEST ...]}
 *            or ID: {part, slide, says, reading,
 *                    from: {paper: igehy98, claim: scales_24}}
 *   TEST:    {name, of: RUN.METRIC, over: RUN.METRIC | minus: RUN.METRIC,
 *             min: X, max: Y}
 *
 * `says` is the slides' sentence, quoted; `reading` how we test it (and
 * which threshold is ours).  A test's value is `of`, `of / over` or
 * `of - minus`; a test with `min` or `max` is checked (min <= value <=
 * max), one with neither is a figure shown beside the checks.  Table
 * "claims", row ID: a column per test and `holds` (1 yes, 0 no) whose
 * note is "<slide>: \"<says>\": holds" or "... does not hold, because
 * <the failing checks with their values> (<if_not>)", if_not being
 * the claim's optional sentence on why a figure may miss.  A `from:` claim runs
 * another paper's claim hook on that paper's own setup (igehy98.h) and takes
 * its verdict and figures: the same computation, not a copy.  Each run is made
 * once (rp_run_build / rp_run_exec), whatever number of tests read it.  Cost:
 * one run per entry of `runs:` (about 30 short runs) plus the igehy98
 * claim's 18.
 */
#ifndef PGSIM_REPRODUCE_BEERMANN02_H
#define PGSIM_REPRODUCE_BEERMANN02_H

#include "sim/core/cfg.h"
#include "sim/reproduce/reproduce.h"

extern const RpPaperOps rp_beermann02;

/* Runs what the claims of setup tree `root` read (config paths relative
 * to dir) and appends their rows; only: one claim's id (only its runs
 * are made), NULL for all.  With figures, *figures gets the table of
 * figures read ("RUN.METRIC" -> double *; g_hash_table_destroy).  FALSE
 * with a located *err. */
gboolean rp_beermann02_claims(const RpContext *ctx, const CfgNode *root,
                              const char *dir, const char *only,
                              GPtrArray *rows, GHashTable **figures,
                              GError **err);

/* Decides claim `id` (its setup.yaml node) from figures: a table of
 * "RUN.METRIC" -> double * (NaN: the run did not set it).  Appends the
 * claim's rows (table "claims") to rows.  A claim with `from:` is not
 * decided here (FALSE with *err).  FALSE with a located *err when a
 * test is malformed or names a figure the table lacks. */
gboolean rp_beermann02_decide(const char *id, const CfgNode *claim,
                              GHashTable *figures, GPtrArray *rows,
                              GError **err);

#endif
