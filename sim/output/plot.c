/* plot.c — charts through gnuplot (pngcairo and svg terminals).
 *
 * Rows are grouped by series (first-seen order) and, within a series, by
 * x; each group becomes one data line "x mean min max label", sorted by x.
 * When any group holds more than one row (repetitions), the chart draws
 * min..max error bars around the mean.  O(rows log rows).
 */
#include "sim/output/plot.h"
#include "sim/core/datapath.h"
#include "sim/core/memlimit.h"
#include <errno.h>
#include <glib/gstdio.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    double x;
    char *label;
    double sum, min, max;
    int n;
} PlotGroup;

typedef struct {
    char *name;
    GArray *groups; /* PlotGroup */
} PlotSeries;

/* An input error about cell (r, c) of t (r G_MAXUINT: column c's header,
 * c -1: the header's first cell): at its place in the file t was read
 * from (dt_where), else under the chart's name with the data row. */
static void data_error(GError **err, const DataTable *t, guint r, int c,
                       const PlotSpec *p, const char *found,
                       const char *expected)
{
    char *where = dt_where(t, r, c < 0 ? 0 : c);
    if (where)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found %s, expected %s", where, found, expected);
    else if (r != G_MAXUINT)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "plot %s: found %s (data row %u), expected %s", p->name,
                    found, r + 1, expected);
    else
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "plot %s: found %s, expected %s", p->name, found,
                    expected);
    g_free(where);
}

static gboolean need_col(const PlotSpec *p, const char *what, const char *name,
                         const DataTable *t, GError **err)
{
    if (!name || dt_col(t, name) >= 0)
        return TRUE;
    char *cols = dt_col_names(t);
    char *found = g_strdup_printf("no column '%s' for %s", name, what);
    char *expected = g_strdup_printf("a column of: %s", cols);
    data_error(err, t, G_MAXUINT, -1, p, found, expected);
    g_free(expected);
    g_free(found);
    g_free(cols);
    return FALSE;
}

gboolean plot_check_columns(const PlotSpec *p, const DataTable *t, GError **err)
{
    return need_col(p, "x", p->x, t, err) && need_col(p, "y", p->y, t, err) &&
           need_col(p, "series", p->series, t, err);
}

/* ---- grouping -------------------------------------------------------- */

static gboolean number(const char *s, double *out)
{
    char *end = NULL;
    if (!s || !*s)
        return FALSE;
    *out = g_ascii_strtod(s, &end);
    return *end == '\0' && isfinite(*out);
}

static gboolean x_is_numeric(const DataTable *t, int xc)
{
    double v;
    for (guint r = 0; r < t->rows->len; r++) {
        const char *s = dt_cell(t, r, xc);
        if (*s && !number(s, &v))
            return FALSE;
    }
    return TRUE;
}

static void series_free(gpointer p)
{
    PlotSeries *s = p;
    for (guint i = 0; i < s->groups->len; i++)
        g_free(g_array_index(s->groups, PlotGroup, i).label);
    g_array_free(s->groups, TRUE);
    g_free(s->name);
    g_free(s);
}

/* Rows are grouped in O(rows log rows): series and categories through
 * hash tables, points sorted by x (stable: the first-seen label of an x
 * stays) and equal x merged. */
typedef struct {
    GPtrArray *all;    /* PlotSeries, first-seen order */
    GHashTable *index; /* series name (borrowed) -> position + 1 */
    GHashTable *cats;  /* category label (borrowed) -> position + 1 */
} Grouping;

static PlotSeries *series_for(Grouping *g, const char *name)
{
    guint at = GPOINTER_TO_UINT(g_hash_table_lookup(g->index, name));
    if (at)
        return g_ptr_array_index(g->all, at - 1);
    PlotSeries *s = g_new0(PlotSeries, 1);
    s->name = g_strdup(name);
    s->groups = g_array_new(FALSE, TRUE, sizeof(PlotGroup));
    g_ptr_array_add(g->all, s);
    g_hash_table_insert(g->index, s->name, GUINT_TO_POINTER(g->all->len));
    return s;
}

static double category(Grouping *g, const char *label)
{
    guint at = GPOINTER_TO_UINT(g_hash_table_lookup(g->cats, label));
    if (!at) {
        at = g_hash_table_size(g->cats) + 1;
        g_hash_table_insert(g->cats, (gpointer)label, GUINT_TO_POINTER(at));
    }
    return at - 1;
}

static gint by_x(gconstpointer a, gconstpointer b)
{
    double x = ((const PlotGroup *)a)->x, y = ((const PlotGroup *)b)->x;
    return x < y ? -1 : x > y;
}

/* Sorts a series' points by x and folds equal x into one group. */
static void merge_groups(GArray *gs)
{
    g_array_sort(gs, by_x);
    guint k = 0;
    for (guint i = 0; i < gs->len; i++) {
        PlotGroup *p = &g_array_index(gs, PlotGroup, i);
        PlotGroup *q = k ? &g_array_index(gs, PlotGroup, k - 1) : NULL;
        if (q && q->x == p->x) {
            q->sum += p->sum;
            q->min = MIN(q->min, p->min);
            q->max = MAX(q->max, p->max);
            q->n += p->n;
            g_free(p->label);
        } else {
            g_array_index(gs, PlotGroup, k++) = *p;
        }
    }
    g_array_set_size(gs, k);
}

typedef struct {
    const char *one, *many; /* "series", "categories" */
    int limit;
} PlotLimit;

static const PlotLimit series_limit = {"series", "series", PLOT_MAX_SERIES};
static const PlotLimit category_limit = {"category", "categories",
                                         PLOT_MAX_CATEGORIES};

/* TRUE with *err when cell (row, col) of t would be the (limit+1)-th
 * distinct value of `seen` (series names or categories). */
static gboolean over_limit(const PlotSpec *p, GHashTable *seen,
                           const PlotLimit *lim, const DataTable *t,
                           guint row, int col, GError **err)
{
    const char *value = dt_cell(t, row, col);
    if (g_hash_table_size(seen) < (guint)lim->limit ||
        g_hash_table_contains(seen, value))
        return FALSE;
    char *shown = plot_printable(value);
    char *found = g_strdup_printf("a %s number %d, '%s' in column '%s'",
                                  lim->one, lim->limit + 1, shown,
                                  (const char *)g_ptr_array_index(t->cols, col));
    char *expected = g_strdup_printf("at most %d %s in chart '%s'",
                                     lim->limit, lim->many, p->name);
    data_error(err, t, row, col, p, found, expected);
    g_free(expected);
    g_free(found);
    g_free(shown);
    return TRUE;
}

/* What a chart of t holds at once within the memory limit (memlimit.h):
 * per row a point, its label and its line of the .dat text (assumption:
 * 160 bytes and the label three times); per distinct series (at most
 * PLOT_MAX_SERIES) its name three times and two plot clauses.  O(rows). */
static gboolean chart_fits(const PlotSpec *p, const DataTable *t,
                           GError **err)
{
    int xc = dt_col(t, p->x), sc = p->series ? dt_col(t, p->series) : -1;
    double bytes = 0, series = 0;
    for (guint r = 0; r < t->rows->len; r++) {
        double s = sc >= 0 ? (double)strlen(dt_cell(t, r, sc)) : 0;
        bytes += 160.0 + 3.0 * (double)strlen(dt_cell(t, r, xc)) + 3.0 * s;
        series = MAX(series, s);
    }
    bytes += MIN(t->rows->len, PLOT_MAX_SERIES) * (3.0 * series + 400.0);
    char *what = g_strdup_printf("a chart of %u rows", t->rows->len);
    char *where = dt_where(t, G_MAXUINT, dt_col(t, p->y));
    char *named = where ? NULL : g_strdup_printf("plot %s", p->name);
    gboolean ok = sim_mem_check(bytes, where ? where : named, what, err);
    g_free(named);
    g_free(where);
    g_free(what);
    return ok;
}

static GPtrArray *group_rows(const PlotSpec *p, const DataTable *t,
                             gboolean *categorical, GError **err)
{
    int xc = dt_col(t, p->x), yc = dt_col(t, p->y);
    int sc = p->series ? dt_col(t, p->series) : -1;
    Grouping g = {g_ptr_array_new_with_free_func(series_free),
                  g_hash_table_new(g_str_hash, g_str_equal),
                  g_hash_table_new(g_str_hash, g_str_equal)};
    *categorical = !x_is_numeric(t, xc);
    for (guint r = 0; r < t->rows->len; r++) {
        double x, y;
        const char *xs = dt_cell(t, r, xc);
        const char *sn = sc >= 0 ? dt_cell(t, r, sc) : "";
        if (!number(dt_cell(t, r, yc), &y) || !*xs)
            continue;
        if ((sc >= 0 && over_limit(p, g.index, &series_limit, t, r, sc, err)) ||
            (*categorical &&
             over_limit(p, g.cats, &category_limit, t, r, xc, err))) {
            g_ptr_array_free(g.all, TRUE);
            g.all = NULL;
            break;
        }
        x = *categorical ? category(&g, xs) : g_ascii_strtod(xs, NULL);
        PlotGroup pt = {x, g_strdup(xs), y, y, y, 1};
        g_array_append_val(series_for(&g, sn)->groups, pt);
    }
    for (guint i = 0; g.all && i < g.all->len; i++)
        merge_groups(((PlotSeries *)g_ptr_array_index(g.all, i))->groups);
    g_hash_table_destroy(g.index);
    g_hash_table_destroy(g.cats);
    return g.all;
}

/* ---- writing --------------------------------------------------------- */

gboolean plot_name_ok(const char *name)
{
    gsize n = name ? strlen(name) : 0;
    if (n == 0 || n > PLOT_NAME_MAX ||
        !(g_ascii_isalnum(name[0]) || name[0] == '_'))
        return FALSE;
    for (gsize i = 0; i < n; i++)
        if (!g_ascii_isalnum(name[i]) && !strchr("._+-", name[i]))
            return FALSE;
    return TRUE;
}

char *plot_printable(const char *s)
{
    char *o = g_strdup(s);
    for (char *c = o; *c; c++)
        if ((guchar)*c < 0x20 || *c == 0x7f)
            *c = ' ';
    return o;
}

/* A gnuplot string expression of single-quoted pieces: gnuplot
 * substitutes backquotes (shell commands) inside double quotes and reads
 * backslash escapes there, but in single quotes nothing is special except
 * the quote itself (gnuplot 5.4 "help syntax", "help substitution").
 * gnuplot 5.4's scanner reads a doubled quote inside a string but not at
 * its start (three quotes and a letter are an empty string and a stray
 * token), so a quote is joined in as "'": 'it' . "'" . 's'.  A control
 * byte would end the command line (the next line a new command, such as
 * `!rm ...`), so it becomes a space. */
static void put_quoted(GString *o, const char *s)
{
    g_string_append_c(o, '\'');
    for (; *s; s++) {
        if (*s == '\'')
            g_string_append(o, "' . \"'\" . '");
        else
            g_string_append_c(o, (guchar)*s < 0x20 || *s == 0x7f ? ' ' : *s);
    }
    g_string_append_c(o, '\'');
}

/* A label field of the data file, in double quotes (gnuplot's data
 * reader has no escapes): quotes become single quotes, control bytes
 * (the tab separator, line ends) spaces. */
static void put_data_label(GString *o, const char *s)
{
    g_string_append_c(o, '"');
    for (; *s; s++)
        g_string_append_c(o, *s == '"' ? '\''
                             : (guchar)*s < 0x20 || *s == 0x7f ? ' '
                                                               : *s);
    g_string_append_c(o, '"');
}

/* A comment line of a data file or script (no line end inside). */
static void put_comment(GString *o, const char *fmt, ...) G_GNUC_PRINTF(2, 3);
static void put_comment(GString *o, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *text = g_strdup_vprintf(fmt, ap);
    va_end(ap);
    char *line = plot_printable(text);
    g_string_append_printf(o, "# %s\n", line);
    g_free(line);
    g_free(text);
}

static gboolean has_spread(const GPtrArray *all)
{
    for (guint i = 0; i < all->len; i++) {
        const PlotSeries *s = g_ptr_array_index(all, i);
        for (guint k = 0; k < s->groups->len; k++)
            if (g_array_index(s->groups, PlotGroup, k).n > 1)
                return TRUE;
    }
    return FALSE;
}

static GString *data_text(const PlotSpec *p, const GPtrArray *all)
{
    GString *o = g_string_new(NULL);
    put_comment(o, "%s: x=%s y=%s (mean, min, max over rows with the same "
                "x) label", p->name, p->x, p->y);
    for (guint i = 0; i < all->len; i++) {
        const PlotSeries *s = g_ptr_array_index(all, i);
        put_comment(o, "series %s", s->name);
        for (guint k = 0; k < s->groups->len; k++) {
            const PlotGroup *g = &g_array_index(s->groups, PlotGroup, k);
            g_string_append_printf(o, "%.17g\t%.17g\t%.17g\t%.17g\t", g->x,
                                   g->sum / g->n, g->min, g->max);
            put_data_label(o, g->label);
            g_string_append_c(o, '\n');
        }
        g_string_append(o, "\n\n");
    }
    return o;
}

/* Title: the spec's, else "<y> against <x>[, by <series>]" from the
 * labels (never the file stem). */
static char *chart_title(const PlotSpec *p, const char *xl, const char *yl)
{
    char *sl = p->series ? plot_label(p->series) : NULL;
    char *t = p->title ? g_strdup(p->title)
              : sl     ? g_strdup_printf("%s against %s, by %s", yl, xl, sl)
                       : g_strdup_printf("%s against %s", yl, xl);
    g_free(sl);
    if (!p->where)
        return t;
    char *w = g_strdup_printf("%s (rows where %s)", t, p->where);
    g_free(t);
    return w;
}

/* The data's extent: x over the points, y over the bars. */
static void extent(const GPtrArray *all, double x[2], double y[2])
{
    x[0] = y[0] = INFINITY;
    x[1] = y[1] = -INFINITY;
    for (guint i = 0; i < all->len; i++) {
        const PlotSeries *s = g_ptr_array_index(all, i);
        for (guint k = 0; k < s->groups->len; k++) {
            const PlotGroup *g = &g_array_index(s->groups, PlotGroup, k);
            if (g->x > 0)
                x[0] = MIN(x[0], g->x), x[1] = MAX(x[1], g->x);
            if (g->min > 0)
                y[0] = MIN(y[0], g->min);
            y[1] = MAX(y[1], g->max);
        }
    }
}

static void script_head(GString *o, const PlotSpec *p, const GPtrArray *all,
                        gboolean cat)
{
    char *xl = p->xlabel ? g_strdup(p->xlabel) : plot_label(p->x);
    char *yl = p->ylabel ? g_strdup(p->ylabel) : plot_label(p->y);
    char *title = chart_title(p, xl, yl);
    put_comment(o, "pgsim chart: edit and rerun 'gnuplot %s.gp'", p->name);
    g_string_append(o, "set title ");
    put_quoted(o, title);
    g_string_append(o, "\nset xlabel ");
    put_quoted(o, xl);
    g_string_append(o, "\nset ylabel ");
    put_quoted(o, yl);
    /* the key below the plot, where it covers no data */
    g_string_append(o, "\nset grid\nset key below left\n"
                       "set datafile separator \"\\t\"\n");
    double x[2], y[2];
    extent(all, x, y);
    if (p->logx && !cat) {
        g_string_append(o, "set logscale x\n");
        plot_log_axis(o, "x", x[0], x[1]);
    }
    if (p->logy) {
        g_string_append(o, "set logscale y\n");
        plot_log_axis(o, "y", y[0], y[1]);
    }
    if (cat)
        g_string_append(o, "set offsets 0.5, 0.5, 0, 0\n"
                           "set xtics rotate by -30 nomirror\n");
    g_free(title);
    g_free(xl);
    g_free(yl);
}

/* What min..max bars span: a sweep's repetitions (a chart of a sweep
 * averages nothing else, plot_unplotted), or any rows sharing x. */
static const char *bars_meaning(gboolean sweep)
{
    return sweep ? "bars: min to max over the repetitions (point: mean)"
                 : "bars: min to max over the rows with that x (point: mean)";
}

static void script_plot(GString *o, const PlotSpec *p, const GPtrArray *all,
                        gboolean cat, int bars)
{
    g_string_append(o, "plot");
    for (guint i = 0; i < all->len; i++) {
        const PlotSeries *s = g_ptr_array_index(all, i);
        g_string_append_printf(o, "%s '%s.dat' index %u using 1:2",
                               i ? ", \\\n    " : " ", p->name, i);
        if (bars)
            g_string_append(o, ":3:4");
        if (cat)
            g_string_append(o, ":xtic(5)");
        /* categories are not a continuum: points, never joining lines */
        gboolean pts = cat || strcmp(p->style, "points") == 0;
        const char *with = bars  ? pts ? "yerrorbars" : "yerrorlines"
                           : pts ? "points pointtype 7 pointsize 1.2"
                                 : p->style;
        g_string_append_printf(o, " with %s", with);
        g_string_append(o, " title ");
        char *t = p->series ? g_strdup_printf("%s=%s", p->series, s->name)
                            : plot_label(p->y);
        put_quoted(o, t);
        g_free(t);
    }
    if (p->diagonal)
        g_string_append(o, ", \\\n    x with lines dashtype 2 lc rgb "
                           "\"gray\" title \"y = x\"");
    if (bars) {
        g_string_append(o, ", \\\n    keyentry with yerrorbars lc rgb "
                           "\"black\" title ");
        put_quoted(o, bars_meaning(bars > 1));
    }
    g_string_append_c(o, '\n');
}

/* sweep: the rows are a sweep's (bars are its repetitions). */
static GString *script_text(const PlotSpec *p, const GPtrArray *all,
                            gboolean cat, gboolean sweep)
{
    GString *o = g_string_new(NULL);
    GString *plot = g_string_new(NULL);
    script_head(o, p, all, cat);
    script_plot(plot, p, all, cat, has_spread(all) ? 1 + sweep : 0);
    g_string_append_printf(o,
                           "set terminal pngcairo size 900,560 "
                           "noenhanced font \"sans,10\"\n"
                           "set output '%s.png'\n%s",
                           p->name, plot->str);
    g_string_append_printf(o,
                           "set terminal svg size 900,560 noenhanced "
                           "font \"sans,10\"\nset output '%s.svg'\n%s"
                           "set output\n",
                           p->name, plot->str);
    g_string_free(plot, TRUE);
    return o;
}

static gboolean save(const char *dir, const char *name, const char *ext,
                     const GString *s, GError **err)
{
    char *file = g_strconcat(name, ext, NULL);
    char *path = g_build_filename(dir, file, NULL);
    gboolean ok = sim_file_write(path, s->str, s->len, err);
    g_free(path);
    g_free(file);
    return ok;
}

static gboolean run_gnuplot(const char *dir, const char *name, GError **err)
{
    char *script = g_strconcat(name, ".gp", NULL);
    char *argv[] = {"gnuplot", script, NULL};
    char *errs = NULL;
    int status = 0;
    GError *e = NULL;
    gboolean ok = g_spawn_sync(dir, argv, NULL, G_SPAWN_SEARCH_PATH, NULL, NULL,
                               NULL, &errs, &status, &e) &&
                  g_spawn_check_wait_status(status, &e);
    if (!ok) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "gnuplot %s/%s: %s%s%s", dir,
                    script, e->message, errs && *errs ? ": " : "",
                    errs ? g_strstrip(errs) : "");
        g_error_free(e);
    }
    g_free(errs);
    g_free(script);
    return ok;
}

/* The chart's four files, drawn in a private folder beside them
 * (dir/.NAME-XXXXXX) and renamed into dir only when gnuplot made a PNG
 * and an SVG that are not empty: a failed chart leaves the earlier one,
 * or nothing, and no stray script, data or empty image. */
static const char *const chart_exts[] = {".dat", ".gp", ".svg", ".png"};

static gboolean chart_made(const char *stage, const char *name, GError **err)
{
    for (guint i = 2; i < G_N_ELEMENTS(chart_exts); i++) {
        char *file = g_strconcat(name, chart_exts[i], NULL);
        char *path = g_build_filename(stage, file, NULL);
        GStatBuf st;
        int rc = g_stat(path, &st), e = errno;
        gboolean ok = rc == 0 && st.st_size > 0;
        if (!ok)
            g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                        "gnuplot: found %s, expected a chart in %s",
                        rc == 0 ? "an empty file" : g_strerror(e), path);
        g_free(path);
        g_free(file);
        if (!ok)
            return FALSE;
    }
    return TRUE;
}

/* Renames the staged files into dir (keep) or removes them; then the
 * stage folder. */
static gboolean unstage(const char *stage, const char *dir, const char *name,
                        gboolean keep, GError **err)
{
    gboolean ok = TRUE;
    for (guint i = 0; i < G_N_ELEMENTS(chart_exts); i++) {
        char *file = g_strconcat(name, chart_exts[i], NULL);
        if (keep && ok)
            ok = sim_move_into(stage, dir, file, err);
        char *from = g_build_filename(stage, file, NULL);
        g_remove(from); /* not moved: dropped */
        g_free(from);
        g_free(file);
    }
    g_rmdir(stage);
    return ok;
}

static gboolean draw(const char *dir, const char *name, const GString *dat,
                     const GString *gp, GError **err)
{
    if (g_mkdir_with_parents(dir, 0777) != 0) {
        int e = errno;
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found %s, expected a folder for the chart", dir,
                    g_strerror(e));
        return FALSE;
    }
    char *tmpl = g_strdup_printf(".%s-XXXXXX", name);
    char *stage = g_build_filename(dir, tmpl, NULL);
    g_free(tmpl);
    if (!g_mkdtemp(stage)) {
        int e = errno;
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found %s, expected a writable folder", dir,
                    g_strerror(e));
        g_free(stage);
        return FALSE;
    }
    gboolean ok = save(stage, name, ".dat", dat, err) &&
                  save(stage, name, ".gp", gp, err) &&
                  run_gnuplot(stage, name, err) &&
                  chart_made(stage, name, err);
    ok = unstage(stage, dir, name, ok, ok ? err : NULL) && ok;
    g_free(stage);
    return ok;
}

/* Skips a comment to its line end; returns the last byte of it. */
static const char *comment_end(const char *c)
{
    while (c[1] && c[1] != '\n')
        c++;
    return c;
}

gboolean plot_script_safe(const char *gp)
{
    char quote = 0; /* the open string's quote, or 0 */
    gboolean line_start = TRUE, continued = FALSE;
    for (const char *c = gp; *c; c++) {
        if (line_start && !continued && !g_str_has_prefix(c, "# ") &&
            !g_str_has_prefix(c, "set ") && !g_str_has_prefix(c, "plot "))
            return FALSE;
        line_start = FALSE;
        if (quote == '"' && *c == '\\' && c[1] && c[1] != '\n')
            c++; /* an escape in a double-quoted constant of ours */
        else if (*c == '\n' && quote)
            return FALSE; /* a string would span lines */
        else if (*c == '\n')
            line_start = TRUE, continued = c > gp && c[-1] == '\\';
        else if (*c == '`' && quote != '\'')
            return FALSE;
        else if (*c == '#' && !quote)
            c = comment_end(c);
        else if ((*c == '\'' || *c == '"') && (!quote || quote == *c))
            quote = quote ? 0 : *c;
    }
    return !quote;
}

static gboolean chart_texts(const PlotSpec *p, const DataTable *t,
                            GString **dat, GString **gp, GError **err);

gboolean plot_texts(const PlotSpec *p, const DataTable *t, GString **dat,
                    GString **gp, GError **err)
{
    if (!plot_name_ok(p->name)) {
        char *shown = plot_printable(p->name ? p->name : "");
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "plot: found the chart name '%s', expected " PLOT_NAME_RULE,
                    shown);
        g_free(shown);
        return FALSE;
    }
    if (!plot_check_columns(p, t, err) || !chart_fits(p, t, err))
        return FALSE;
    PlotSpec q = *p; /* p, or with a series per value of the parameter */
    if (!plot_split_unplotted(&q, t, err))
        return FALSE;
    gboolean ok = chart_texts(&q, t, dat, gp, err);
    if (q.series != p->series)
        g_free(q.series);
    return ok;
}

static gboolean chart_texts(const PlotSpec *p, const DataTable *t,
                            GString **dat, GString **gp, GError **err)
{
    gboolean cat;
    GPtrArray *all = group_rows(p, t, &cat, err);
    if (!all)
        return FALSE;
    gboolean ok = all->len > 0;
    if (ok) {
        *dat = data_text(p, all);
        *gp = script_text(p, all, cat, dt_col(t, "repetition") >= 0);
        g_assert(plot_script_safe((*gp)->str)); /* put_quoted's promise */
    } else {
        char *found = g_strdup_printf("no row with a number in both '%s' "
                                      "and '%s'", p->x, p->y);
        data_error(err, t, G_MAXUINT, dt_col(t, p->y), p, found,
                   "at least one for the chart");
        g_free(found);
    }
    g_ptr_array_free(all, TRUE);
    return ok;
}

gboolean plot_render(const PlotSpec *p, const DataTable *t, const char *dir,
                     GError **err)
{
    GString *dat = NULL, *gp = NULL;
    if (!plot_texts(p, t, &dat, &gp, err))
        return FALSE;
    gboolean ok = draw(dir, p->name, dat, gp, err);
    g_string_free(dat, TRUE);
    g_string_free(gp, TRUE);
    return ok;
}
