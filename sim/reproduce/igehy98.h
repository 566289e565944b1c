/* igehy98.h — `pgsim reproduce igehy98`: seed 002's "Performance of
 * Argus" table (Igehy, Stoll, Hanrahan, SIGGRAPH 98) from the argus
 * workload on models/origin2000.yaml.
 *
 * Table "1": rows uniprocessor, serial_api, parallel_4, parallel_8 and
 * issue_bound_x2 (the 8-context footnote's own quantity); columns
 * nurbs_hz and march_hz.  What each row runs: configs/papers/igehy98/
 * setup.yaml.  With an output directory the hook also draws
 * igehy98-rates.png (simulated rate per row and application).
 */
#ifndef PGSIM_REPRODUCE_IGEHY98_H
#define PGSIM_REPRODUCE_IGEHY98_H

#include "sim/core/cfg.h"
#include "sim/reproduce/reproduce.h"

extern const RpPaperOps rp_igehy98;

/* The frame rate of one run through the runner: config file `path` with
 * the overrides (NULL-terminated `--set` assignments), at the pass's
 * network fidelity (ctx->fidelity, noted in the table's header).  FALSE
 * with *err on failure. */
gboolean rp_igehy98_rate(const RpContext *ctx, const char *path,
                         const char *const *sets, double *hz, GError **err);

/* The same run's metrics `names` (NULL-terminated; declared by the
 * argus workload) into vals. */
gboolean rp_igehy98_metrics(const RpContext *ctx, const char *path,
                            const char *const *sets,
                            const char *const *names, double *vals,
                            GError **err);

/* Table "claims" (igehy98_claims.c): the slides' "The API is scalable
 * on a 24 processor system", decided on runs that setup.yaml's
 * `claims:` describes (paths of `apps` relative to dir). */
gboolean rp_igehy98_claims(const RpContext *ctx, const char *dir,
                           const CfgNode *claims, const CfgNode *apps,
                           GPtrArray *rows, GError **err);

#endif
