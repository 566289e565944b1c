/* model_find.c — the model search path and finding a model file by name
 * (model_find.h).
 *
 * The path is built afresh on each lookup (the user's $PGSIM_MODELS may
 * change between runs of one process, as in the tests), with folders
 * compared by canonical name so that a folder named twice is searched
 * once.  A name is a plain file stem, so a lookup never leaves the
 * folders listed.  Cost: O(folders^2) name comparisons plus one stat per
 * folder until the model is found.
 */
#include "sim/machine/model_find.h"
#include "sim/core/datapath.h"
#include "sim/core/inputs.h"
#include "sim/core/error.h"
#include <string.h>

static gboolean name_ok(const char *name)
{
    if (!name || !*name || name[0] == '.')
        return FALSE;
    for (const char *c = name; *c; c++)
        if (!g_ascii_isalnum(*c) && *c != '-' && *c != '_' && *c != '.')
            return FALSE;
    return TRUE;
}

static char *try_dir(const char *dir, const char *name)
{
    char *file = g_strconcat(name, ".yaml", NULL);
    char *path = g_build_filename(dir, file, NULL);
    g_free(file);
    if (g_file_test(path, G_FILE_TEST_IS_REGULAR))
        return path;
    g_free(path);
    return NULL;
}

/* Adds dir (owned) unless the same folder is already listed. */
static void add_dir(GPtrArray *dirs, char *dir)
{
    char *c = g_canonicalize_filename(dir, NULL);
    gboolean dup = FALSE;
    for (guint i = 0; !dup && i < dirs->len; i++) {
        char *o = g_canonicalize_filename(dirs->pdata[i], NULL);
        dup = strcmp(o, c) == 0;
        g_free(o);
    }
    g_free(c);
    if (dup)
        g_free(dir);
    else
        g_ptr_array_add(dirs, dir);
}

GPtrArray *mach_model_dirs_in(const char *const *extra)
{
    GPtrArray *dirs = g_ptr_array_new_with_free_func(g_free);
    if (!sim_inputs_dir_shipped("models")) /* else with the shipped ones */
        add_dir(dirs, g_strdup("models"));
    char **list = sim_env_dirs("PGSIM_MODELS");
    for (char **d = list; *d; d++)
        add_dir(dirs, g_strdup(*d));
    g_strfreev(list);
    for (const char *const *d = extra; d && *d; d++)
        if (**d)
            add_dir(dirs, g_strdup(*d));
    GPtrArray *roots = sim_data_roots();
    for (guint i = 0; i < roots->len; i++)
        add_dir(dirs, g_build_filename(roots->pdata[i], "models", NULL));
    g_ptr_array_free(roots, TRUE);
    return dirs;
}

GPtrArray *mach_model_dirs(void)
{
    return mach_model_dirs_in(NULL);
}

static void no_model(GError **err, const char *name, const GPtrArray *dirs)
{
    GString *s = g_string_new(NULL);
    for (guint i = 0; i < dirs->len; i++)
        if (g_file_test(dirs->pdata[i], G_FILE_TEST_IS_DIR))
            g_string_append_printf(s, "%s%s", s->len ? ", " : "",
                                   (const char *)dirs->pdata[i]);
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "found no model '%s', expected models/%s.yaml (model folders "
                "searched: %s; more with $PGSIM_MODELS)",
                name, name, s->len ? s->str : "none exists");
    g_string_free(s, TRUE);
}

char *mach_model_path_in(const char *name, const char *const *extra,
                         GError **err)
{
    if (!name_ok(name)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "found model name '%s', expected a plain name such as "
                    "'ipsc2' (letters, digits, '-', '_')",
                    name ? name : "");
        return NULL;
    }
    GPtrArray *dirs = mach_model_dirs_in(extra);
    char *path = NULL;
    for (guint i = 0; !path && i < dirs->len; i++)
        path = try_dir(dirs->pdata[i], name);
    if (!path)
        no_model(err, name, dirs);
    g_ptr_array_free(dirs, TRUE);
    return path;
}


char *mach_model_path(const char *name, GError **err)
{
    return mach_model_path_in(name, NULL, err);
}
