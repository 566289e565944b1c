/* plot_label.c — what charts are labelled with and drawn from: axis
 * labels made from column names (plot_label: units from their suffixes)
 * and the small x, y, series tables papers and benchmarks chart
 * (plot_xy_*).  Split from plot.c, which draws.  O(length) each.
 */
#include "sim/output/plot.h"
#include <string.h>

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

DataTable *plot_xy_table_new(void)
{
    static const char *const cols[] = {"x", "y", "series", NULL};
    return dt_new_named(cols);
}

void plot_xy_add_label(DataTable *t, const char *x, double y,
                       const char *series)
{
    char ys[40];
    g_snprintf(ys, sizeof ys, "%.17g", y);
    char *row[] = {(char *)x, ys, (char *)series};
    dt_add_row(t, row);
}

void plot_xy_add(DataTable *t, double x, double y, const char *series)
{
    char xs[40];
    g_snprintf(xs, sizeof xs, "%.17g", x);
    plot_xy_add_label(t, xs, y, series);
}
