/* model_find.h — where machine models are found: the model search path.
 *
 * A model is named (`machine: {model: ipsc2}`) and found as <name>.yaml
 * in the first folder of the search path that has it.  The path is a
 * union, the user's folders first (docs/models.md):
 *
 *     1. ./models, unless it is a shipped folder of step 4 (pgsim run
 *        from its own checkout), which is searched there
 *     2. each directory of $PGSIM_MODELS (colon-separated; a user setting)
 *     3. the caller's extra folders, in order (e.g. the models/ of the
 *        repository that holds a run config, the install's models)
 *     4. models/ under every data root (sim_data_roots: $PGSIM_DATA, the
 *        build tree, share/pgsim)
 *
 * A folder holding a user's own model hides none of the shipped ones; a
 * folder listed twice (even spelt differently) is searched once.  Extra
 * folders are parameters, never environment variables: `extra` is a
 * NULL-terminated array of paths (borrowed), or NULL for none.
 */
#ifndef PGSIM_MACHINE_MODEL_FIND_H
#define PGSIM_MACHINE_MODEL_FIND_H

#include <glib.h>

/* The search path above.  A new array of strings
 * (g_ptr_array_free(a, TRUE)). */
GPtrArray *mach_model_dirs_in(const char *const *extra);
/* mach_model_dirs_in(NULL). */
GPtrArray *mach_model_dirs(void);

/* Finds <name>.yaml in the first folder of the search path that has it.
 * Returns a newly allocated path (g_free) or NULL with *err set (a name
 * that is not plain, or no such model: the error lists the folders that
 * exist). */
char *mach_model_path_in(const char *name, const char *const *extra,
                         GError **err);
/* mach_model_path_in(name, NULL, err). */
char *mach_model_path(const char *name, GError **err);

#endif
