/* cmd_sorts.c — `pgsim sorts FILE.yaml [--set K=V ...] [--out DIR]
 * [--no-charts]`: one
 * scene on one machine as sort-first, sort-middle and sort-last over a
 * range of processor counts (sim/app/sorts/sorts.h, docs/sorts.md).
 * Prints the table (sort, processors, overlap, bytes, balance,
 * frame_ms), writes it as DIR/<name>.csv and charts frame time and bytes
 * against processors (DIR/<name>-frame.png, -bytes.png); DIR defaults
 * to out/<name>.  --set overrides the file's own keys (processors,
 * machine.*, scene.*, run.*). */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/app/sorts/sorts.h"
#include "sim/core/error.h"
#include <errno.h>
#include <stdio.h>
#include <string.h>

/* The table as aligned text on stdout. */
static void print_table(const DataTable *t)
{
    guint nc = t->cols->len;
    guint w[16] = {0};
    for (guint c = 0; c < nc && c < 16; c++) {
        w[c] = (guint)strlen(t->cols->pdata[c]);
        for (guint r = 0; r < t->rows->len; r++)
            w[c] = MAX(w[c], (guint)strlen(dt_cell(t, r, (int)c)));
    }
    for (guint c = 0; c < nc && c < 16; c++)
        printf("%s%-*s", c ? "  " : "", (int)w[c], (char *)t->cols->pdata[c]);
    printf("\n");
    for (guint r = 0; r < t->rows->len; r++) {
        for (guint c = 0; c < nc && c < 16; c++)
            printf(c ? "  %*s" : "%-*s", (int)w[c], dt_cell(t, r, (int)c));
        printf("\n");
    }
}

static gboolean write_csv(const DataTable *t, const char *dir,
                          const char *name, GError **err)
{
    GString *o = g_string_new(NULL);
    dt_write_csv(t, o);
    char *file = g_strdup_printf("%s.csv", name);
    char *path = g_build_filename(dir, file, NULL);
    gboolean ok = g_file_set_contents(path, o->str, (gssize)o->len, NULL);
    if (!ok)
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found a file that cannot be written, expected a "
                    "writable output folder",
                    path);
    else
        fprintf(stderr, "wrote %s\n", path);
    g_free(path);
    g_free(file);
    g_string_free(o, TRUE);
    return ok;
}

int cmd_sorts(int argc, char **argv)
{
    char *out = NULL;
    char **sets = NULL;
    gboolean no_charts = FALSE;
    int status = 0;
    GOptionEntry entries[] = {
        {"out", 0, 0, G_OPTION_ARG_FILENAME, &out,
         "output folder (default out/<name>)", "DIR"},
        {"set", 0, 0, G_OPTION_ARG_STRING_ARRAY, &sets,
         "override a key of FILE (processors, machine.*, scene.*, run.*)",
         "K=V"},
        {"no-charts", 0, 0, G_OPTION_ARG_NONE, &no_charts,
         "write the table only, no gnuplot charts", NULL},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    if (!cli_parse("sorts", "FILE.yaml",
                   "Runs one scene on one machine as sort-first, "
                   "sort-middle and sort-last at each processor count of "
                   "FILE (configs/three-sorts.yaml) and prints Molnar's "
                   "overlap factor, bytes per frame, load balance and frame "
                   "time side by side (docs/sorts.md).",
                   entries, &argc, &argv, &status))
        return status;
    if (!cli_want_args("sorts", "FILE.yaml", argc, argv, 1))
        return 2;
    GError *err = NULL;
    SortsSpec *s = sorts_spec_load(argv[1], (const char *const *)sets, &err);
    g_strfreev(sets);
    if (!s) {
        g_free(out);
        return cli_fail(err);
    }
    char *dir = out ? g_strdup(out) : g_build_filename("out", s->name, NULL);
    DataTable *t = NULL;
    if (g_mkdir_with_parents(dir, 0755) != 0)
        g_set_error(&err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found a folder that cannot be made (%s), expected "
                    "a writable --out",
                    dir, g_strerror(errno));
    else
        t = sorts_run(s, dir, &err);
    gboolean ok = t && write_csv(t, dir, s->name, &err) &&
                  (no_charts || sorts_charts(s, t, dir, &err));
    if (t)
        print_table(t);
    int rc = ok ? 0 : cli_fail(err);
    if (t)
        dt_free(t);
    g_free(dir);
    g_free(out);
    sorts_spec_free(s);
    return rc;
}
