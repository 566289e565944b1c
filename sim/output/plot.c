/* plot.c — charts through gnuplot (pngcairo and svg terminals).
 *
 * Rows are grouped by series (first-seen order) and, within a series, by
 * x; each group becomes one data line "x mean min max label", sorted by x.
 * When any group holds more than one row (repetitions), the chart draws
 * min..max error bars around the mean.  O(rows * groups per series).
 */
#include "sim/output/plot.h"
#include "sim/core/datapath.h"
#include <math.h>
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

PlotSpec *plot_spec_new(const char *name, const char *x, const char *y)
{
    PlotSpec *p = g_new0(PlotSpec, 1);
    p->name = g_strdup(name);
    p->x = g_strdup(x);
    p->y = g_strdup(y);
    p->style = g_strdup("linespoints");
    return p;
}

void plot_spec_free(gpointer spec)
{
    PlotSpec *p = spec;
    if (!p)
        return;
    g_free(p->name);
    g_free(p->x);
    g_free(p->y);
    g_free(p->series);
    g_free(p->title);
    g_free(p->xlabel);
    g_free(p->ylabel);
    g_free(p->style);
    g_free(p);
}

/* ---- reading specs --------------------------------------------------- */

static gboolean opt_str(const CfgNode *m, const char *key, char **out,
                        GError **err)
{
    const char *s = NULL;
    if (!cfg_get_str(m, key, FALSE, &s, err))
        return FALSE;
    if (s) {
        g_free(*out);
        *out = g_strdup(s);
    }
    return TRUE;
}

static PlotSpec *read_spec(const CfgNode *m, guint i, GError **err)
{
    static const char *const styles[] = {"linespoints", "points", "lines",
                                         NULL};
    const char *x = NULL, *y = NULL;
    int style = 0;
    if (!cfg_get_str(m, "x", TRUE, &x, err) ||
        !cfg_get_str(m, "y", TRUE, &y, err) ||
        !cfg_get_enum(m, "style", FALSE, styles, &style, err))
        return NULL;
    char *name = g_strdup_printf("plot%u", i + 1);
    PlotSpec *p = plot_spec_new(name, x, y);
    g_free(name);
    g_free(p->style);
    p->style = g_strdup(styles[style]);
    if (opt_str(m, "name", &p->name, err) &&
        opt_str(m, "series", &p->series, err) &&
        opt_str(m, "title", &p->title, err) &&
        opt_str(m, "xlabel", &p->xlabel, err) &&
        opt_str(m, "ylabel", &p->ylabel, err) &&
        cfg_get_bool(m, "logx", FALSE, &p->logx, err) &&
        cfg_get_bool(m, "logy", FALSE, &p->logy, err) &&
        cfg_check_unused(m, err))
        return p;
    plot_spec_free(p);
    return NULL;
}

gboolean plot_specs_read(GPtrArray *specs, const CfgNode *seq, GError **err)
{
    if (cfg_kind(seq) != CFG_SEQ) {
        cfg_error(err, seq, "a non-list 'plots'", "a list of {x, y, ...}");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        const CfgNode *m = cfg_seq_at(seq, i);
        if (cfg_kind(m) != CFG_MAP) {
            cfg_error(err, m, "a plot that is not a map",
                      "{x, y, series, logx, logy, title, ...}");
            return FALSE;
        }
        PlotSpec *p = read_spec(m, i, err);
        if (!p)
            return FALSE;
        g_ptr_array_add(specs, p);
    }
    return TRUE;
}

static gboolean need_col(const char *what, const char *name, const DataTable *t,
                         GError **err)
{
    if (!name || dt_col(t, name) >= 0)
        return TRUE;
    char *cols = dt_col_names(t);
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "plot %s: found column '%s', expected one of: %s", what, name,
                cols);
    g_free(cols);
    return FALSE;
}

gboolean plot_check_columns(const PlotSpec *p, const DataTable *t, GError **err)
{
    return need_col("x", p->x, t, err) && need_col("y", p->y, t, err) &&
           need_col("series", p->series, t, err);
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

static PlotSeries *series_for(GPtrArray *all, const char *name)
{
    for (guint i = 0; i < all->len; i++) {
        PlotSeries *s = g_ptr_array_index(all, i);
        if (strcmp(s->name, name) == 0)
            return s;
    }
    PlotSeries *s = g_new0(PlotSeries, 1);
    s->name = g_strdup(name);
    s->groups = g_array_new(FALSE, TRUE, sizeof(PlotGroup));
    g_ptr_array_add(all, s);
    return s;
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

static void add_point(PlotSeries *s, double x, const char *label, double y)
{
    PlotGroup *g = NULL;
    for (guint i = 0; i < s->groups->len && !g; i++)
        if (g_array_index(s->groups, PlotGroup, i).x == x)
            g = &g_array_index(s->groups, PlotGroup, i);
    if (!g) {
        PlotGroup ng = {x, g_strdup(label), 0.0, y, y, 0};
        g_array_append_val(s->groups, ng);
        g = &g_array_index(s->groups, PlotGroup, s->groups->len - 1);
    }
    g->sum += y;
    g->min = MIN(g->min, y);
    g->max = MAX(g->max, y);
    g->n++;
}

static double category(GPtrArray *cats, const char *label)
{
    for (guint i = 0; i < cats->len; i++)
        if (strcmp(g_ptr_array_index(cats, i), label) == 0)
            return i;
    g_ptr_array_add(cats, g_strdup(label));
    return cats->len - 1;
}

static gint by_x(gconstpointer a, gconstpointer b)
{
    double x = ((const PlotGroup *)a)->x, y = ((const PlotGroup *)b)->x;
    return x < y ? -1 : x > y;
}

static GPtrArray *group_rows(const PlotSpec *p, const DataTable *t,
                             gboolean *categorical)
{
    int xc = dt_col(t, p->x), yc = dt_col(t, p->y);
    int sc = p->series ? dt_col(t, p->series) : -1;
    GPtrArray *all = g_ptr_array_new_with_free_func(series_free);
    GPtrArray *cats = g_ptr_array_new_with_free_func(g_free);
    *categorical = !x_is_numeric(t, xc);
    for (guint r = 0; r < t->rows->len; r++) {
        double x, y;
        const char *xs = dt_cell(t, r, xc);
        if (!number(dt_cell(t, r, yc), &y) || !*xs)
            continue;
        x = *categorical ? category(cats, xs) : g_ascii_strtod(xs, NULL);
        add_point(series_for(all, sc >= 0 ? dt_cell(t, r, sc) : ""), x, xs, y);
    }
    for (guint i = 0; i < all->len; i++)
        g_array_sort(((PlotSeries *)g_ptr_array_index(all, i))->groups, by_x);
    g_ptr_array_free(cats, TRUE);
    return all;
}

/* ---- writing --------------------------------------------------------- */

static void put_quoted(GString *o, const char *s)
{
    g_string_append_c(o, '"');
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            g_string_append_c(o, '\\');
        g_string_append_c(o, *s == '\n' ? ' ' : *s);
    }
    g_string_append_c(o, '"');
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
    g_string_append_printf(o,
                           "# %s: x=%s y=%s (mean, min, max over rows "
                           "with the same x) label\n",
                           p->name, p->x, p->y);
    for (guint i = 0; i < all->len; i++) {
        const PlotSeries *s = g_ptr_array_index(all, i);
        g_string_append_printf(o, "# series %s\n", s->name);
        for (guint k = 0; k < s->groups->len; k++) {
            const PlotGroup *g = &g_array_index(s->groups, PlotGroup, k);
            g_string_append_printf(o, "%.17g\t%.17g\t%.17g\t%.17g\t", g->x,
                                   g->sum / g->n, g->min, g->max);
            put_quoted(o, g->label);
            g_string_append_c(o, '\n');
        }
        g_string_append(o, "\n\n");
    }
    return o;
}

/* Unit suffixes of pgsim's column names ("mean_frame_s", "comm_bytes"). */
static const struct {
    const char *suffix, *unit;
} col_units[] = {/* longer suffixes first: "_per_s" before "_s" */
                 {"_per_s", "1/s"}, {"_bytes", "B"}, {"_fps", "frames/s"},
                 {"_pct", "%"},     {"_ms", "ms"},   {"_us", "us"},
                 {"_ns", "ns"},     {"_kb", "kB"},   {"_mb", "MB"},
                 {"_hz", "Hz"},     {"_s", "s"}};

char *plot_label(const char *col)
{
    for (guint i = 0; i < G_N_ELEMENTS(col_units); i++) {
        const char *suf = col_units[i].suffix;
        gsize n = strlen(col), k = strlen(suf);
        if (n <= k || strcmp(col + n - k, suf) != 0)
            continue;
        char *stem = g_strndup(col, n - (suf[0] == '_' ? k : 0));
        g_strdelimit(stem, "_", ' ');
        char *label = g_strdup_printf("%s (%s)", stem, col_units[i].unit);
        g_free(stem);
        return label;
    }
    char *label = g_strdup(col);
    g_strdelimit(label, "_", ' ');
    return label;
}

/* Title: the spec's, else "<y> against <x>[, by <series>]" from the
 * labels (never the file stem). */
static char *chart_title(const PlotSpec *p, const char *xl, const char *yl)
{
    if (p->title)
        return g_strdup(p->title);
    if (!p->series)
        return g_strdup_printf("%s against %s", yl, xl);
    char *sl = plot_label(p->series);
    char *t = g_strdup_printf("%s against %s, by %s", yl, xl, sl);
    g_free(sl);
    return t;
}

static void script_head(GString *o, const PlotSpec *p, gboolean cat)
{
    char *xl = p->xlabel ? g_strdup(p->xlabel) : plot_label(p->x);
    char *yl = p->ylabel ? g_strdup(p->ylabel) : plot_label(p->y);
    char *title = chart_title(p, xl, yl);
    g_string_append(o, "# pgsim chart: edit and rerun `gnuplot ");
    g_string_append_printf(o, "%s.gp`\nset title ", p->name);
    put_quoted(o, title);
    g_string_append(o, "\nset xlabel ");
    put_quoted(o, xl);
    g_string_append(o, "\nset ylabel ");
    put_quoted(o, yl);
    g_string_append(o, "\nset grid\nset key top left\n"
                       "set datafile separator \"\\t\"\n");
    /* log axes end at the data, not at the enclosing decades */
    if (p->logx && !cat)
        g_string_append(o, "set logscale x\nset autoscale xfix\n"
                           "set offsets graph 0.02, graph 0.02, 0, 0\n");
    if (p->logy)
        g_string_append(o, "set logscale y\nset autoscale yfix\n");
    if (cat)
        g_string_append(o, "set offsets 0.5, 0.5, 0, 0\n"
                           "set xtics rotate by -30 nomirror\n");
    g_free(title);
    g_free(xl);
    g_free(yl);
}

static void script_plot(GString *o, const PlotSpec *p, const GPtrArray *all,
                        gboolean cat, gboolean bars)
{
    g_string_append(o, "plot");
    for (guint i = 0; i < all->len; i++) {
        const PlotSeries *s = g_ptr_array_index(all, i);
        g_string_append_printf(o, "%s \"%s.dat\" index %u using 1:2",
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
    g_string_append_c(o, '\n');
}

static GString *script_text(const PlotSpec *p, const GPtrArray *all,
                            gboolean cat)
{
    GString *o = g_string_new(NULL);
    GString *plot = g_string_new(NULL);
    script_head(o, p, cat);
    script_plot(plot, p, all, cat, has_spread(all));
    g_string_append_printf(o,
                           "set terminal pngcairo size 900,560 "
                           "noenhanced font \"sans,10\"\n"
                           "set output \"%s.png\"\n%s",
                           p->name, plot->str);
    g_string_append_printf(o,
                           "set terminal svg size 900,560 noenhanced "
                           "font \"sans,10\"\nset output \"%s.svg\"\n%s"
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

DataTable *plot_xy_table_new(void)
{
    GPtrArray *cols = g_ptr_array_new();
    g_ptr_array_add(cols, "x");
    g_ptr_array_add(cols, "y");
    g_ptr_array_add(cols, "series");
    DataTable *t = dt_new(cols);
    g_ptr_array_free(cols, TRUE);
    return t;
}

void plot_xy_add(DataTable *t, double x, double y, const char *series)
{
    char xs[40], ys[40];
    g_snprintf(xs, sizeof xs, "%.17g", x);
    g_snprintf(ys, sizeof ys, "%.17g", y);
    char *row[] = {xs, ys, (char *)series};
    dt_add_row(t, row);
}

gboolean plot_render(const PlotSpec *p, const DataTable *t, const char *dir,
                     GError **err)
{
    if (!plot_check_columns(p, t, err))
        return FALSE;
    gboolean cat;
    GPtrArray *all = group_rows(p, t, &cat);
    if (all->len == 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "plot %s: no row has a number in both '%s' and '%s'",
                    p->name, p->x, p->y);
        g_ptr_array_free(all, TRUE);
        return FALSE;
    }
    GString *dat = data_text(p, all), *gp = script_text(p, all, cat);
    gboolean ok = g_mkdir_with_parents(dir, 0777) == 0 &&
                  save(dir, p->name, ".dat", dat, err) &&
                  save(dir, p->name, ".gp", gp, err) &&
                  run_gnuplot(dir, p->name, err);
    if (!ok && err && !*err)
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot create", dir);
    g_string_free(dat, TRUE);
    g_string_free(gp, TRUE);
    g_ptr_array_free(all, TRUE);
    return ok;
}
