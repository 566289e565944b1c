/* outdir.h — a run's output folder (`pgsim run --out DIR`), replaced as
 * a whole.
 *
 * Everything a run writes into DIR (the report's three files, frame
 * images, frame logs) is written into a private staging folder beside it
 * (DIR's parent, ".NAME.new-XXXXXX") and moved into DIR only when the
 * run has succeeded; a run that fails removes its staging folder, so DIR
 * keeps the earlier run's files untouched.  On success the earlier run's
 * files that the new run did not write (a frame-0007.png of a longer
 * run, a frame.png, a frame log) are removed, so DIR is wholly new; other
 * files in DIR are left alone.
 */
#ifndef PGSIM_APP_RUN_OUTDIR_H
#define PGSIM_APP_RUN_OUTDIR_H

#include <glib.h>

/* A new empty staging folder beside dir (its parent created if needed)
 * (g_free), or NULL and *err. */
char *out_stage_new(const char *dir, GError **err);
/* Moves the staged files into dir (created if needed), removing the
 * earlier run's files that are not among them, then the staging folder.
 * FALSE and *err when a file cannot be moved. */
gboolean out_stage_commit(const char *stage, const char *dir, GError **err);
/* Removes the staging folder and what it holds (a failed run); NULL is
 * a no-op. */
void out_stage_discard(const char *stage);
/* TRUE for a name a run writes into its folder: summary.txt,
 * result.json, result.csv, frame.png, frame-NNNN.png, *_frames.csv,
 * *_frames_stages.csv. */
gboolean out_is_run_file(const char *name);

#endif
