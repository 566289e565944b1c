/* atomic.h — whole-file writes that never leave a partial file.
 *
 * The data go to a temporary file in the target's directory
 * (".<name>.XXXXXX"), which is fsync'ed and renamed over the target;
 * the directory is then fsync'ed.  A reader sees either the old file or
 * the complete new one; a failure at any step removes the temporary file.
 */
#ifndef PGSIM_OUTPUT_ATOMIC_H
#define PGSIM_OUTPUT_ATOMIC_H

#include <glib.h>

/* Writes len bytes to path atomically; FALSE with *err (SIM_ERROR_IO,
 * "path: found <reason>, expected a writable file") on failure. */
gboolean rpt_write_atomic(const char *path, const void *data, size_t len,
                          GError **err);

#endif
