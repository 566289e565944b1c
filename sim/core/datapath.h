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

/* Reads a whole file into *text (g_free; NUL-terminated), its length into
 * *len if not NULL; FALSE with a SIM_ERROR_IO error naming the file. */
gboolean sim_file_read(const char *path, char **text, gsize *len,
                       GError **err);

#endif
