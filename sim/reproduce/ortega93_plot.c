/* ortega93_plot.c — Figures 3 and 4 of seed 004 from the simulated rows
 * of `pgsim reproduce ortega93 --out DIR`: speed-up of each data set and
 * resolution relative to the smallest partition of the machine (Fig. 3:
 * CM-5, Tables 3-4; Fig. 4: CM-200, Tables 1-2), with the linear
 * speed-up for reference, as gnuplot PNG/SVG (sim/output/plot.h).  The
 * seed's figures are not printed in its text, so these are predictions
 * (CM-5) and the visible tables' ratios (CM-200).  O(rows^2), rows < 100.
 */
#include "sim/output/plot.h"
#include "sim/reproduce/ortega93.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Processors of a row key "16K/1280x1024" or "32/640x480". */
static double row_procs(const char *row)
{
    char *end = NULL;
    double p = g_ascii_strtod(row, &end);
    return end && *end == 'K' ? p * 1024 : p;
}

static const char *row_res(const char *row)
{
    const char *s = strchr(row, '/');
    return s ? s + 1 : row;
}

/* time_s of `table` at the smallest partition of resolution res. */
static double base_time(GPtrArray *rows, const char *table, const char *res,
                        double *procs)
{
    double t = NAN;
    *procs = INFINITY;
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        if (g_strcmp0(r->table, table) || g_strcmp0(r->column, "time_s") ||
            g_strcmp0(row_res(r->row), res) || row_procs(r->row) >= *procs)
            continue;
        *procs = row_procs(r->row);
        t = r->sim;
    }
    return t;
}

static void add_point(DataTable *t, double x, double y, const char *series)
{
    char xs[40], ys[40];
    g_snprintf(xs, sizeof xs, "%.17g", x);
    g_snprintf(ys, sizeof ys, "%.17g", y);
    char *row[] = {xs, ys, (char *)series};
    dt_add_row(t, row);
}

/* Speed-up points of one table (`set` names the data set). */
static void table_points(GPtrArray *rows, const char *table, const char *set,
                         DataTable *t)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        if (g_strcmp0(r->table, table) || g_strcmp0(r->column, "time_s"))
            continue;
        double p0, t0 = base_time(rows, table, row_res(r->row), &p0);
        char *series = g_strdup_printf("%s %s", set, row_res(r->row));
        add_point(t, row_procs(r->row), t0 / r->sim, series);
        if (g_str_has_prefix(set, "small") &&
            g_str_has_prefix(row_res(r->row), "1280"))
            add_point(t, row_procs(r->row), row_procs(r->row) / p0, "linear");
        g_free(series);
    }
}

/* A log-x speed-up chart spec, one series per data set and resolution. */
static PlotSpec *speedup_spec(const char *name, const char *title)
{
    PlotSpec *p = plot_spec_new(name, "processors", "speedup");
    *p = (PlotSpec){.name = p->name,
                    .x = p->x,
                    .y = p->y,
                    .series = g_strdup("series"),
                    .logx = TRUE,
                    .title = g_strdup(title),
                    .xlabel = g_strdup("partition (processors)"),
                    .ylabel = g_strdup("speed-up over the smallest partition"),
                    .style = p->style};
    return p;
}

static void figure(GPtrArray *rows, const char *small, const char *large,
                   const char *name, const char *title, const char *dir)
{
    const char *names[] = {"processors", "speedup", "series"};
    GPtrArray *cols = g_ptr_array_new();
    for (int k = 0; k < 3; k++)
        g_ptr_array_add(cols, (gpointer)names[k]);
    DataTable *t = dt_new(cols);
    g_ptr_array_free(cols, TRUE);
    table_points(rows, small, "small", t);
    table_points(rows, large, "large", t);
    PlotSpec *p = speedup_spec(name, title);
    GError *err = NULL;
    gboolean ok = plot_render(p, t, dir, &err);
    plot_spec_free(p);
    dt_free(t);
    if (!ok)
        g_printerr("ortega93: chart %s not drawn: %s\n", name, err->message);
    g_clear_error(&err);
}

void rp_ortega93_charts(GPtrArray *rows, const char *dir)
{
    if (g_mkdir_with_parents(dir, 0755) != 0) {
        g_printerr("ortega93: cannot create %s; no charts\n", dir);
        return;
    }
    figure(rows, "3", "4", "ortega93-fig3",
           "Fig. 3: speed-up on the CM-5 (simulated, predicted)", dir);
    figure(rows, "1", "2", "ortega93-fig4",
           "Fig. 4: speed-up on the CM-200 (simulated)", dir);
}
