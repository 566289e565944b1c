/* pairings.h — every shipped workload config on every model (issue 34,
 * point 2): `pgsim models --pairings LIST`.
 *
 * LIST (configs/pairings/pairings.yaml) gives each config's small-size
 * overrides (`small: {CONFIG: [key=value, ...]}`) and the pairings that
 * are physically meaningless (`meaningless:` rules of configs, models
 * (`"*"`: all, less `except`), the text the located error must hold, and
 * the reason).  Each workload config of configs/ (a file with a
 * `workload:` section and no `sweep:`) runs on each model of the models
 * folder (by name, with --set machine.model=NAME and its small
 * overrides): a listed pairing must fail with a located error holding
 * its text, every other one must run.  `pending:` rules, in the same
 * shape, list pairings that fail for a reason still to fix (a model
 * without a processor description yet); the table says so, and one
 * that runs after all is a run (remove the rule when none fails).  The table (Markdown, in
 * docs/models.md between marker lines, scripts/gen-models-doc.sh) gives
 * each run's mean frame time and marks each work class of a derived cost
 * and each kind played by another (roles).
 */
#ifndef PGSIM_APP_CLI_PAIRINGS_H
#define PGSIM_APP_CLI_PAIRINGS_H

#include <glib.h>

/* The .yaml files of dir in name order (g_ptr_array_unref), or NULL
 * with *err set (`pgsim models` lists models with it too). */
GPtrArray *cli_yaml_files(const char *dir, GError **err);

/* Runs every pairing; appends the Markdown table to md.  FALSE with one
 * *err listing every pairing whose behaviour and LIST disagree (or a
 * located error in LIST). */
gboolean pairings_table(const char *list, const char *configs_dir,
                        const char *models_dir, GString *md, GError **err);

#endif
