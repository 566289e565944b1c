/* plot.h — charts through gnuplot.
 *
 * A PlotSpec says which columns of a DataTable go on x and y, which one
 * splits the rows into series, log axes and labels.  plot_render() writes
 * <dir>/<name>.dat (one gnuplot data block per series: x, mean y, min y,
 * max y over the rows that share x) and <dir>/<name>.gp (a script that
 * draws <name>.png with pngcairo and <name>.svg), then runs gnuplot on it
 * in <dir>, so a user can edit the .gp file and rerun `gnuplot NAME.gp`.
 */
#ifndef PGSIM_OUTPUT_PLOT_H
#define PGSIM_OUTPUT_PLOT_H

#include "sim/output/table.h"
#include "sim/core/cfg.h"

typedef struct {
    char *name;   /* output file stem */
    char *x, *y;  /* column names */
    char *series; /* column name; NULL: one series */
    gboolean logx, logy;
    char *title, *xlabel, *ylabel; /* NULL: from the columns (plot_label) */
    char *style;       /* "linespoints" (default), "points", "lines" */
    gboolean diagonal; /* also draw y = x (simulated against published) */
} PlotSpec;

/* An axis label from a column name: underscores as spaces and a known
 * unit suffix as "(unit)": "mean_frame_s" -> "mean frame (s)",
 * "comm_bytes" -> "comm (B)" (g_free).  Default labels and titles come
 * from it. */
char *plot_label(const char *col);

/* Returns a new spec with x and y set; free with plot_spec_free(). */
PlotSpec *plot_spec_new(const char *name, const char *x, const char *y);
void plot_spec_free(gpointer spec);
/* Reads a `plots:` list of maps {name, x, y, series, logx, logy, title,
 * xlabel, ylabel, style} into specs (PlotSpec *); located errors. */
gboolean plot_specs_read(GPtrArray *specs, const CfgNode *seq, GError **err);
/* Checks that the spec's columns exist in t; error names the missing one
 * and lists the columns. */
gboolean plot_check_columns(const PlotSpec *p, const DataTable *t,
                            GError **err);
/* A new table of columns x, y, series (dt_free), the shape most charts
 * take, and one row of it (numbers written so they read back exactly). */
DataTable *plot_xy_table_new(void);
void plot_xy_add(DataTable *t, double x, double y, const char *series);
/* Writes NAME.dat and NAME.gp in dir and runs gnuplot there.  Rows whose
 * x or y is empty or not a number are skipped (a categorical x, one that
 * is not numeric, is placed at 0, 1, 2 ... in first-seen order). */
gboolean plot_render(const PlotSpec *p, const DataTable *t, const char *dir,
                     GError **err);

#endif
