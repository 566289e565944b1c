/* outdir.c — staging a run's output folder and moving it into place
 * (outdir.h).  O(files in the folder). */
#include "sim/app/run/outdir.h"
#include "sim/core/datapath.h"
#include "sim/core/error.h"

#include <errno.h>
#include <glib/gstdio.h>
#include <string.h>

char *out_stage_new(const char *dir, GError **err)
{
    char *parent = g_path_get_dirname(dir);
    char *base = g_path_get_basename(dir);
    char *tmpl = g_strdup_printf(".%s.new-XXXXXX", base);
    char *stage = g_build_filename(parent, tmpl, NULL);
    if (g_mkdir_with_parents(parent, 0777) != 0 || !g_mkdtemp(stage)) {
        int e = errno;
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found %s, expected a writable folder for --out %s",
                    parent, g_strerror(e), dir);
        g_clear_pointer(&stage, g_free);
    }
    g_free(tmpl);
    g_free(base);
    g_free(parent);
    return stage;
}

gboolean out_is_run_file(const char *name)
{
    static const char *const fixed[] = {"summary.txt", "result.json",
                                        "result.csv", "frame.png"};
    for (guint i = 0; i < G_N_ELEMENTS(fixed); i++)
        if (strcmp(name, fixed[i]) == 0)
            return TRUE;
    if (g_str_has_prefix(name, "frame-") && g_str_has_suffix(name, ".png")) {
        gsize n = strlen(name);
        for (gsize i = 6; i + 4 < n; i++)
            if (!g_ascii_isdigit(name[i]))
                return FALSE;
        return n > 10;
    }
    return g_str_has_suffix(name, "_frames.csv") ||
           g_str_has_suffix(name, "_frames_stages.csv");
}

/* The names of the regular files in dir (NULL-terminated, g_strfreev);
 * none when dir cannot be read. */
static char **names_in(const char *dir)
{
    GPtrArray *a = g_ptr_array_new();
    GDir *d = g_dir_open(dir, 0, NULL);
    for (const char *n; d && (n = g_dir_read_name(d));) {
        char *path = g_build_filename(dir, n, NULL);
        if (g_file_test(path, G_FILE_TEST_IS_REGULAR))
            g_ptr_array_add(a, g_strdup(n));
        g_free(path);
    }
    if (d)
        g_dir_close(d);
    g_ptr_array_add(a, NULL);
    return (char **)g_ptr_array_free(a, FALSE);
}

/* Removes dir's run files that the new run did not write. */
static void remove_stale(const char *dir, char *const *fresh)
{
    char **old = names_in(dir);
    for (char **n = old; *n; n++)
        if (out_is_run_file(*n) &&
            !g_strv_contains((const char *const *)fresh, *n)) {
            char *path = g_build_filename(dir, *n, NULL);
            g_remove(path);
            g_free(path);
        }
    g_strfreev(old);
}

gboolean out_stage_commit(const char *stage, const char *dir, GError **err)
{
    if (g_mkdir_with_parents(dir, 0777) != 0) {
        int e = errno;
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found %s, expected a directory that can be created",
                    dir, g_strerror(e));
        out_stage_discard(stage);
        return FALSE;
    }
    char **fresh = names_in(stage);
    gboolean ok = TRUE;
    for (char **n = fresh; ok && *n; n++)
        ok = sim_move_into(stage, dir, *n, err);
    if (ok)
        remove_stale(dir, fresh);
    g_strfreev(fresh);
    out_stage_discard(stage);
    return ok;
}

void out_stage_discard(const char *stage)
{
    if (!stage)
        return;
    char **left = names_in(stage);
    for (char **n = left; *n; n++) {
        char *path = g_build_filename(stage, *n, NULL);
        g_remove(path);
        g_free(path);
    }
    g_strfreev(left);
    g_rmdir(stage);
}
