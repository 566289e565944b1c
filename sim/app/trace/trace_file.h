/* trace_file.h — trace files of a run: Chrome Trace Event JSON (opens in
 * Perfetto and chrome://tracing) or Paje (opens in ViTE).
 *
 * trc_open() picks the format from the extension (.json or .paje) and
 * returns a SimTrace to attach with sim_engine_set_trace(); the model
 * layers then report per-node phase spans, messages and marks through the
 * sim_trace_* hooks (sim/core/trace.h).  A cap on the number of events
 * keeps files bounded: when it is reached, recording stops, the file gets
 * a note saying so, and one line goes to stderr.  The file is written to
 * a temporary name and renamed into place by trc_close().  docs/traces.md
 * describes both formats.
 */
#ifndef PGSIM_APP_TRACE_TRACE_FILE_H
#define PGSIM_APP_TRACE_TRACE_FILE_H

#include "sim/core/error.h"
#include "sim/core/trace.h"

#define TRC_DEFAULT_CAP 1000000

/* Returns a new trace writing to path (free with trc_close()), or NULL
 * with *err (unknown extension, unwritable file).  max_events: the cap
 * (0: TRC_DEFAULT_CAP). */
SimTrace *trc_open(const char *path, uint64_t max_events, GError **err);
/* Finishes and closes the file; FALSE with *err on a write error.  NULL is
 * a no-op. */
gboolean trc_close(SimTrace *tr, GError **err);
/* Closes the file and removes it (a failed run leaves no trace file, as
 * it leaves no --out files).  NULL is a no-op. */
void trc_discard(SimTrace *tr);
/* Events recorded so far, and whether the cap was hit. */
uint64_t trc_events(const SimTrace *tr);
gboolean trc_truncated(const SimTrace *tr);

#endif
