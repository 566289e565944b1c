/* metrics.h — a workload's declared outputs (WlOps.metrics, workload.h).
 *
 * Each workload declares every metric its run() may set: name, unit and
 * one-line meaning.  The runner checks each finished result against the
 * declaration (wl_check_metrics: a metric set but not declared, or set
 * with another unit, is a bug and fails the run), and code that reads a
 * metric back by name reads it through the declaration (wl_metric), so a
 * misspelt name stops the program instead of reading a silent NaN.
 * Complexity: O(declared) per name looked up.
 */
#ifndef PGSIM_WORKLOAD_METRICS_H
#define PGSIM_WORKLOAD_METRICS_H

#include "sim/core/result.h"
#include "sim/workload/workload.h"

/* ops' declaration of `name`; NULL when ops does not declare it.  A
 * declared name ending in "@P" declares a family: NAME@16384, NAME@32
 * (one per processor count the run was asked for, dpscan's partitions). */
const WlMetric *wl_metric_decl(const WlOps *ops, const char *name);

/* TRUE when every metric of r is declared by ops with the unit it was
 * set with; else FALSE with an internal error (exit status 1) naming the
 * first that is not. */
gboolean wl_check_metrics(const WlOps *ops, const SimResult *r,
                          GError **err);

/* The value of metric `name` of r, NAN when the run did not set it.
 * `name` must be declared by r's workload (wl_find(r->workload)): an
 * undeclared name is a programming error and aborts (g_error). */
double wl_metric(const SimResult *r, const char *name);
/* The same as a lookup: FALSE when the run did not set it. */
gboolean wl_get_metric(const SimResult *r, const char *name, double *value);

#endif
