/* sweep_log.h — the sweep's results log: one JSON line per finished point.
 *
 * <dir>/results.jsonl grows by one complete line per finished point (one
 * write() of the whole line on an O_APPEND descriptor, then fsync), in
 * completion order.  Reopening with resume discards a trailing partial
 * line (a kill during a write) and remembers which points finished; a
 * point recorded with "status":"error" is run again and its newer line
 * wins.  <dir>/sweep.fingerprint ties the log to one expanded sweep.
 *
 * sweep_log_finish() rewrites results.jsonl ordered by point index (the
 * last line per point) and writes results.csv, both atomically, so the
 * final files do not depend on -j, ranks or interruptions.  A point's
 * line carries the files its run read under SWEEP_INPUTS_KEY (kind,
 * path, sha256, shipped); their union, in point order, is the inputs of
 * the sweep's provenance, not a column of results.csv.
 */
#ifndef PGSIM_APP_SWEEP_SWEEP_LOG_H
#define PGSIM_APP_SWEEP_SWEEP_LOG_H

#include "sim/app/sweep/sweep_spec.h"
#include "sim/output/table.h"

#define SWEEP_INPUTS_KEY "inputs"

typedef struct SweepLog SweepLog;

/* Opens (creating dir) the log for a sweep of n points.  Without resume an
 * existing non-empty log is an error; with resume a log from another sweep
 * (fingerprint differs) is an error.  Returns a new log (close with
 * sweep_log_close()) or NULL with *err set. */
SweepLog *sweep_log_open(const char *dir, const SweepSpec *spec,
                         gboolean resume, GError **err);
void sweep_log_close(SweepLog *log);
/* TRUE when point i finished successfully in an earlier run. */
gboolean sweep_log_done(const SweepLog *log, guint i);
guint sweep_log_n_done(const SweepLog *log);
/* Appends one complete line (ending in '\n') and syncs it to disk. */
gboolean sweep_log_append(SweepLog *log, const char *line, GError **err);

/* Reads the log, keeps the last line per point, and writes the ordered
 * results.jsonl and results.csv.  *table_out (if not NULL) receives the
 * CSV table (free with dt_free()). */
gboolean sweep_log_finish(const char *dir, const SweepSpec *spec,
                          DataTable **table_out, GError **err);

#endif
