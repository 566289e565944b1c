/* datapath.h — finding the project's data files (models/, configs/, data/)
 * wherever pgsim is run from.
 *
 * A data file is named relative to the project root, e.g.
 * "configs/papers/kurc96/published.yaml".  sim_data_path() returns the first of:
 *   1. the name itself, if it exists relative to the current directory;
 *   2. <root>/<name> for each root in $PGSIM_DATA (colon-separated);
 *   3. <exe>/../<name>, where <exe> is the directory of the running binary
 *      (a build tree: build/pgsim sits one level below the root);
 *   4. <exe>/../share/pgsim/<name> (an installed pgsim).
 * If none exists it returns the name unchanged, so that the error a caller
 * reports names what was asked for.  O(number of roots) file tests.
 */
#ifndef PGSIM_CORE_DATAPATH_H
#define PGSIM_CORE_DATAPATH_H

#include <glib.h>

/* Returns a newly allocated path (g_free). */
char *sim_data_path(const char *name);
/* The roots of steps 2-4 in order (a new array of strings; free with
 * g_ptr_array_free(roots, TRUE)), for searches that want every hit. */
GPtrArray *sim_data_roots(void);
/* The non-empty entries of the colon-separated folder list in
 * environment variable var, in order (g_strfreev; empty when unset). */
char **sim_env_dirs(const char *var);

/* Reads a whole input file in one pass into *text (g_free;
 * NUL-terminated), its length into *len if not NULL.  The file must be a
 * regular file (not a device, FIFO or directory) of at most
 * sim_file_limit() bytes, checked before anything is allocated; FALSE
 * with a SIM_ERROR_IO error "path:0:0: found ..., expected ..." naming
 * the file otherwise. */
gboolean sim_file_read(const char *path, char **text, gsize *len,
                       GError **err);

/* Writes len bytes to path as one whole file: GLib's
 * g_file_set_contents_full() (temporary file beside it, fsync, rename), so
 * a reader sees the old file or the complete new one.  The new file's
 * mode is 0666 less the umask, like any file a program creates.  FALSE
 * with *err (SIM_ERROR_IO, "path: found <reason>, expected a writable
 * file") on failure; the target is then untouched. */
gboolean sim_file_write(const char *path, const void *data, gsize len,
                        GError **err);

/* The size limit of input files in bytes: SIM_FILE_LIMIT_DEFAULT (1 GiB)
 * unless $PGSIM_MAX_INPUT (bytes, with an optional k/M/G suffix) or
 * sim_file_set_limit() (0 restores the default) says otherwise. */
#define SIM_FILE_LIMIT_DEFAULT ((guint64)1 << 30)
guint64 sim_file_limit(void);
void sim_file_set_limit(guint64 bytes);

/* Moves stage/name to dir/name (a rename: the same file system); FALSE
 * with "DIR/NAME: found <reason>, expected a writable file" in *err. */
gboolean sim_move_into(const char *stage, const char *dir, const char *name,
                       GError **err);

#endif
