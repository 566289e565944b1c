/* mueller97_plot.c — the charts of `pgsim reproduce mueller97` (seed
 * 000 Charts 1-5) from the simulated points, as gnuplot PNG/SVG through
 * plot_render() (sim/output/plot.h): Chart 1 chunk overlap against
 * chunk size per chunking strategy (at Chart 1's P), Chart 2 bytes a
 * frame against chunk size per P (max-set), Chart 3 chunk overlap
 * against the box / region ratio per P, Charts 4 and 5 transformations
 * against chunk size per P for min-set and max-set (chunk size 1 left
 * out, as the paper did).  O(points).
 */
#include "sim/output/plot.h"
#include "sim/reproduce/mueller97.h"

typedef enum { C1, C2, C3, C4, C5 } Chart;

/* Whether point p belongs to chart c; its x, y and series into the row. */
static gboolean point_of(Chart c, const RpMuellerPoint *p, guint c1_procs,
                         gboolean c1_minset, double *x, double *y,
                         char *series, gsize len)
{
    g_snprintf(series, len, "P = %u", p->procs);
    *x = p->granularity;
    switch (c) {
    case C1:
        g_snprintf(series, len, "%s", rp_mu_chunking_names[p->chunking]);
        *y = p->overlap;
        return p->procs == c1_procs && p->minset == c1_minset;
    case C2:
        *y = p->bytes;
        return p->chunking == RP_MU_SORTED && !p->minset;
    case C3:
        *x = p->ratio;
        *y = p->overlap;
        return p->chunking == RP_MU_SORTED && !p->minset;
    case C4:
    case C5:
        *y = p->transforms;
        return p->chunking == RP_MU_SORTED && p->minset == (c == C4) &&
               p->granularity > 1;
    }
    return FALSE;
}

static const char *const names[] = {"mueller97-chart1", "mueller97-chart2",
                                    "mueller97-chart3", "mueller97-chart4",
                                    "mueller97-chart5"};
static const char *const titles[] = {
    "Chart 1: chunking strategies (simulated)",
    "Chart 2: communication (max-set, sorted, simulated)",
    "Chart 3: chunk overlap (max-set, sorted, simulated)",
    "Chart 4: transformations, min-set (simulated)",
    "Chart 5: transformations, max-set (simulated)"};
static const char *const ylabels[] = {
    "chunk overlap (regions per chunk)", "bytes sent per frame",
    "chunk overlap (regions per chunk)", "transformations per frame",
    "transformations per frame"};

static void chart(Chart c, const RpMuellerPoint *pts, guint n,
                  guint c1_procs, const char *dir)
{
    DataTable *t = plot_xy_table_new();
    gboolean c1_minset = FALSE; /* Chart 1's bookkeeping: the other
                                   strategies' (max-set when none ran) */
    for (guint i = 0; i < n; i++)
        if (pts[i].chunking != RP_MU_SORTED)
            c1_minset = pts[i].minset;
    for (guint i = 0; i < n; i++) {
        double x, y;
        char series[32];
        if (point_of(c, &pts[i], c1_procs, c1_minset, &x, &y, series,
                     sizeof series))
            plot_xy_add(t, x, y, series);
    }
    PlotSpec *p = plot_spec_new(names[c], "x", "y");
    p->series = g_strdup("series");
    p->title = g_strdup(titles[c]);
    p->xlabel = g_strdup(c == C3 ? "chunk box size / region size"
                                 : "primitives per chunk");
    p->ylabel = g_strdup(ylabels[c]);
    if (c == C3)
        p->style = g_strdup("points");
    GError *err = NULL;
    if (!plot_render(p, t, dir, &err)) {
        g_printerr("mueller97: chart %s not drawn: %s\n", names[c],
                   err->message);
        g_clear_error(&err);
    }
    plot_spec_free(p);
    dt_free(t);
}

void rp_mueller97_charts(const RpMuellerPoint *pts, guint n,
                         guint chart1_procs, const char *dir)
{
    if (g_mkdir_with_parents(dir, 0777) != 0) {
        g_printerr("mueller97: cannot create %s; no charts\n", dir);
        return;
    }
    for (Chart c = C1; c <= C5; c++)
        chart(c, pts, n, chart1_procs, dir);
}
