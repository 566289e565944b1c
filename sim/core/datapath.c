/* datapath.c — data-file search (see datapath.h for the order). */
#include "sim/core/datapath.h"
#include "sim/core/error.h"

static char *try_root(const char *root, const char *name)
{
    char *p = g_build_filename(root, name, NULL);
    if (g_file_test(p, G_FILE_TEST_EXISTS))
        return p;
    g_free(p);
    return NULL;
}

static char *try_env(const char *name)
{
    const char *env = g_getenv("PGSIM_DATA");
    if (!env || !*env)
        return NULL;
    char **roots = g_strsplit(env, ":", -1), *hit = NULL;
    for (char **r = roots; *r && !hit; r++)
        if (**r)
            hit = try_root(*r, name);
    g_strfreev(roots);
    return hit;
}

static char *try_exe(const char *name)
{
    char *exe = g_file_read_link("/proc/self/exe", NULL);
    if (!exe)
        return NULL;
    char *bindir = g_path_get_dirname(exe);
    char *up = g_build_filename(bindir, "..", NULL);
    char *share = g_build_filename(bindir, "..", "share", "pgsim", NULL);
    char *hit = try_root(up, name);
    if (!hit)
        hit = try_root(share, name);
    g_free(share);
    g_free(up);
    g_free(bindir);
    g_free(exe);
    return hit;
}

char *sim_data_path(const char *name)
{
    if (g_path_is_absolute(name) || g_file_test(name, G_FILE_TEST_EXISTS))
        return g_strdup(name);
    char *hit = try_env(name);
    if (!hit)
        hit = try_exe(name);
    return hit ? hit : g_strdup(name);
}

gboolean sim_file_read(const char *path, char **text, gsize *len,
                       GError **err)
{
    GError *e = NULL;
    if (g_file_get_contents(path, text, len, &e))
        return TRUE;
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s", e->message);
    g_error_free(e);
    return FALSE;
}
