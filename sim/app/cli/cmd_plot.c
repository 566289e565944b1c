/* cmd_plot.c — `pgsim plot RESULTS.csv --x K --y K [--series K] [--logx]
 * [--logy] [--title T] [--where K=V ...] [-o FILE.png]`: an ad hoc chart
 * of two columns of a CSV file (a sweep's results.csv, a reproduction's
 * table ...).  Each --where keeps only the rows whose column K reads
 * exactly V (all of them must hold).
 *
 * Writes FILE.png, FILE.svg, FILE.gp and FILE.dat (default: <y>-vs-<x>
 * next to the CSV, other characters than plot_name_ok's as '_') through
 * plot_render(); an -o name outside plot_name_ok's set is refused.
 */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/output/plot.h"
#include <stdio.h>
#include <string.h>

typedef struct {
    char *x, *y, *series, *title, *out;
    char **where; /* "K=V" items */
    gboolean logx, logy;
} PlotOpts;

/* -o names a .png in a directory that exists (nothing is created). */
static gboolean check_out(const char *out)
{
    char *lower = g_ascii_strdown(out, -1);
    gboolean png = g_str_has_suffix(lower, ".png");
    g_free(lower);
    if (!png) {
        fprintf(stderr,
                "pgsim plot: -o: found '%s', expected a file name ending "
                "in .png\n",
                out);
        return FALSE;
    }
    char *base = g_path_get_basename(out);
    base[strlen(base) - 4] = '\0';
    gboolean named = plot_name_ok(base);
    if (!named) {
        char *shown = plot_printable(base);
        fprintf(stderr, "pgsim plot: -o: found the name '%s', expected %s\n",
                shown, PLOT_NAME_RULE);
        g_free(shown);
    }
    g_free(base);
    if (!named)
        return FALSE;
    char *dir = g_path_get_dirname(out);
    gboolean ok = g_file_test(dir, G_FILE_TEST_IS_DIR);
    if (!ok)
        fprintf(stderr,
                "pgsim plot: -o: found no directory '%s', expected an "
                "existing directory for %s\n",
                dir, out);
    g_free(dir);
    return ok;
}

/* FALSE when the caller should return *status (help, or a bad option). */
static gboolean parse_opts(PlotOpts *o, int *argc, char ***argv, int *status)
{
    GOptionEntry entries[] = {
        {"x", 0, 0, G_OPTION_ARG_STRING, &o->x, "x column", "K"},
        {"y", 0, 0, G_OPTION_ARG_STRING, &o->y, "y column", "K"},
        {"series", 0, 0, G_OPTION_ARG_STRING, &o->series,
         "column that splits rows into lines", "K"},
        {"logx", 0, 0, G_OPTION_ARG_NONE, &o->logx, "log x axis", NULL},
        {"logy", 0, 0, G_OPTION_ARG_NONE, &o->logy, "log y axis", NULL},
        {"title", 0, 0, G_OPTION_ARG_STRING, &o->title, "chart title", "T"},
        {"where", 0, 0, G_OPTION_ARG_STRING_ARRAY, &o->where,
         "keep the rows whose column K is V (repeatable)", "K=V"},
        {"output", 'o', 0, G_OPTION_ARG_FILENAME, &o->out,
         "PNG to write (an SVG, .gp and .dat go beside it)", "FILE.png"},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    if (!cli_parse("plot", "RESULTS.csv",
                   "Charts two columns of a CSV file with gnuplot; lines "
                   "starting with '#' (the provenance header) are skipped "
                   "(docs/sweeps.md).",
                   entries, argc, argv, status))
        return FALSE;
    *status = 2;
    if (!cli_want_args("plot", "RESULTS.csv", *argc, *argv, 1))
        return FALSE;
    if (!o->x || !o->y) {
        fprintf(stderr, "pgsim plot: found no --%s, expected --x K --y K\n",
                o->x ? "y" : "x");
        return FALSE;
    }
    return !o->out || check_out(o->out);
}

/* "<y>-vs-<x>" with every character outside PLOT_NAME_RULE as '_' (the
 * columns are data). */
static char *default_stem(const PlotOpts *o)
{
    char *stem = g_strdup_printf("%s-vs-%s", o->y, o->x);
    for (char *c = stem; *c; c++)
        if (!g_ascii_isalnum(*c) && (c == stem || !strchr("._+-", *c)))
            *c = '_';
    if (strlen(stem) > PLOT_NAME_MAX)
        stem[PLOT_NAME_MAX] = '\0';
    return stem;
}

/* Splits -o FILE.png (or the default) into a directory and a stem. */
static void out_names(const PlotOpts *o, const char *csv, char **dir,
                      char **stem)
{
    if (o->out) {
        *dir = g_path_get_dirname(o->out);
        char *base = g_path_get_basename(o->out);
        base[strlen(base) - 4] = '\0'; /* check_out: ends in .png */
        *stem = base;
    } else {
        *dir = g_path_get_dirname(csv);
        *stem = default_stem(o);
    }
}

/* Equal text, or equal numbers ("4" and "4.0"). */
static gboolean same_value(const char *cell, const char *want)
{
    char *e1 = NULL, *e2 = NULL;
    if (strcmp(cell, want) == 0)
        return TRUE;
    double a = g_ascii_strtod(cell, &e1), b = g_ascii_strtod(want, &e2);
    return *cell && *want && !*e1 && !*e2 && a == b;
}

/* An input error at the header of column c of t (its first cell when c
 * is -1): "file:line:col: found ..., expected ...". */
static void header_error(GError **err, const DataTable *t, int c,
                         const char *found, const char *expected)
{
    char *where = dt_where(t, G_MAXUINT, c < 0 ? 0 : c);
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "%s: found %s, expected %s",
                where ? where : "pgsim plot", found, expected);
    g_free(where);
}

gboolean cli_keep_where(DataTable **t, const char *item, GError **err)
{
    const char *eq = strchr(item, '=');
    char *key = eq ? g_strndup(item, (gsize)(eq - item)) : NULL;
    int c = key && *key ? dt_col(*t, key) : -1;
    if (c < 0) {
        char *cols = dt_col_names(*t);
        char *found = g_strdup_printf("%s '%s' (--where %s)",
                                      eq ? "no column" : "no '=' in",
                                      eq ? key : item, item);
        char *expected =
            g_strdup_printf("--where COLUMN=VALUE with a column of: %s", cols);
        header_error(err, *t, -1, found, expected);
        g_free(expected);
        g_free(found);
        g_free(cols);
        g_free(key);
        return FALSE;
    }
    DataTable *kept = dt_new_like(*t);
    for (guint r = 0; r < (*t)->rows->len; r++)
        if (same_value(dt_cell(*t, r, c), eq + 1))
            dt_copy_row(kept, *t, r);
    if (kept->rows->len == 0) {
        char *found = g_strdup_printf("no row with %s", item);
        header_error(err, *t, c, found, "at least one (--where)");
        g_free(found);
        dt_free(kept);
        kept = NULL;
    }
    dt_free(*t);
    *t = kept;
    g_free(key);
    return kept != NULL;
}

static DataTable *read_rows(const PlotOpts *o, const char *csv, GError **err)
{
    DataTable *t = dt_read_csv(csv, err);
    for (int i = 0; t && o->where && o->where[i]; i++)
        if (!cli_keep_where(&t, o->where[i], err))
            return NULL;
    return t;
}

static gboolean plot_csv(const PlotOpts *o, const char *csv, GError **err)
{
    DataTable *t = read_rows(o, csv, err);
    if (!t)
        return FALSE;
    char *dir, *stem;
    out_names(o, csv, &dir, &stem);
    PlotSpec *p = plot_spec_new(stem, o->x, o->y);
    p->series = g_strdup(o->series);
    p->title = g_strdup(o->title);
    p->where = o->where ? g_strjoinv(", ", o->where) : NULL;
    p->logx = o->logx;
    p->logy = o->logy;
    gboolean ok = plot_render(p, t, dir, err);
    if (ok)
        printf("%s/%s.png\n", dir, stem);
    plot_spec_free(p);
    dt_free(t);
    g_free(dir);
    g_free(stem);
    return ok;
}

int cmd_plot(int argc, char **argv)
{
    PlotOpts o = {0};
    GError *err = NULL;
    int st = 0;
    if (parse_opts(&o, &argc, &argv, &st)) {
        st = 0;
        if (!plot_csv(&o, argv[1], &err))
            st = cli_fail(err);
    }
    g_free(o.x);
    g_free(o.y);
    g_free(o.series);
    g_free(o.title);
    g_free(o.out);
    g_strfreev(o.where);
    return st;
}
