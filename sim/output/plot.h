/* plot.h — charts through gnuplot.
 *
 * A PlotSpec says which columns of a DataTable go on x and y, which one
 * splits the rows into series, log axes and labels.  plot_render() writes
 * <dir>/<name>.dat (one gnuplot data block per series: x, mean y, min y,
 * max y over the rows that share x) and <dir>/<name>.gp (a script that
 * draws <name>.png with pngcairo and <name>.svg), then runs gnuplot on it
 * in <dir>, so a user can edit the .gp file and rerun `gnuplot NAME.gp`.
 * (plot.c draws; plot_spec.c reads specs; plot_label.c makes labels.)
 *
 * Data never becomes gnuplot code: values reach gnuplot only through the
 * .dat file, every text put into the script (titles, labels, series
 * names) is a single-quoted string, where gnuplot substitutes nothing
 * (no backquote commands, no macros), and the chart name, which names the
 * files, is limited to PLOT_NAME_RULE, so it never leaves <dir>.
 */
#ifndef PGSIM_OUTPUT_PLOT_H
#define PGSIM_OUTPUT_PLOT_H

#include "sim/output/table.h"
#include "sim/core/cfg.h"

/* A chart name: letters, digits and . _ + -, starting with a letter, a
 * digit or _ (so no path, no hidden file, no option), at most PLOT_NAME_MAX
 * bytes. */
#define PLOT_NAME_MAX 120
#define PLOT_NAME_RULE                                                        \
    "a name of letters, digits and . _ + - that starts with a letter, a "   \
    "digit or _ (at most 120 characters)"
/* More lines than this make no readable chart (and gnuplot rereads the
 * data file once per line): plot_render() refuses them. */
#define PLOT_MAX_SERIES 500
/* Nor more labels on a categorical (non-numeric) x axis: gnuplot takes
 * minutes over 200,000 of them. */
#define PLOT_MAX_CATEGORIES 1000

typedef struct {
    char *name;   /* output file stem (plot_name_ok) */
    char *x, *y;  /* column names */
    char *series; /* column name; NULL: one series */
    gboolean logx, logy;
    char *title, *xlabel, *ylabel; /* NULL: from the columns (plot_label) */
    char *style;       /* "linespoints" (default), "points", "lines" */
    gboolean diagonal; /* also draw y = x (simulated against published) */
    char *where;       /* the rows kept ("K=V, K=V"), shown in the title;
                          NULL: every row */
} PlotSpec;

/* An axis label from a column name: underscores as spaces and a known
 * unit suffix as "(unit)": "mean_frame_s" -> "mean frame (s)",
 * "comm_bytes" -> "comm (B)" (g_free).  Default labels and titles come
 * from it. */
char *plot_label(const char *col);

/* TRUE when name follows PLOT_NAME_RULE. */
gboolean plot_name_ok(const char *name);
/* TRUE when name follows PLOT_NAME_RULE, else a located error at `at`:
 * "found the <what> name '...', expected <PLOT_NAME_RULE>". */
gboolean plot_cfg_name_ok(const CfgNode *at, const char *what,
                          const char *name, GError **err);
/* A copy of s with control bytes as spaces, for messages (g_free). */
char *plot_printable(const char *s);

/* The swept parameters (a sweep table's columns between seed and
 * status) other than x and series whose values differ among rows that
 * share x and series, so a chart would average over them: how many, the
 * first one's name in *first (g_free) and "'K' ('a' and 'b' where X = x),
 * ..." appended to why (plot_params.c). */
guint plot_unplotted(const PlotSpec *p, const DataTable *t, char **first,
                     GString *why);

/* A chart of a sweep without series that would average over one swept
 * parameter gets q->series = that parameter (g_free it when it is not
 * the caller's); more such parameters, or one beside a series, are an
 * input error that names them (plot_params.c). */
gboolean plot_split_unplotted(PlotSpec *q, const DataTable *t, GError **err);
/* Appends gnuplot commands for a log axis ("x" or "y") over data in
 * [lo, hi]: its range the decades around them and a labelled tick at each
 * decade (also at 2 and 5 times them when they span one). */
void plot_log_axis(GString *o, const char *axis, double lo, double hi);

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
/* The same with x as given (a category, or a number already written). */
void plot_xy_add_label(DataTable *t, const char *x, double y,
                       const char *series);
/* Writes NAME.dat and NAME.gp and runs gnuplot on them in a private
 * folder inside dir, then renames the four files into dir: a failure
 * leaves dir as it was.  Rows whose x or y is empty or not a number are
 * skipped (a categorical x, one that is not numeric, is placed at 0, 1,
 * 2 ... in first-seen order).  A bad name, more than PLOT_MAX_SERIES
 * series or more than PLOT_MAX_CATEGORIES categories is an input error.
 * O(rows log rows). */
gboolean plot_render(const PlotSpec *p, const DataTable *t, const char *dir,
                     GError **err);
/* TRUE when a script keeps data out of gnuplot's code: every line starts
 * with "# ", "set " or "plot " or continues a line ending in a backslash, no
 * string spans lines and every backquote is inside single quotes.
 * plot_texts() asserts it of each script it makes. */
gboolean plot_script_safe(const char *gp);
/* What plot_render() writes, without writing it: new NAME.dat and NAME.gp
 * texts (g_string_free) in *dat and *gp, or FALSE and *err. */
gboolean plot_texts(const PlotSpec *p, const DataTable *t, GString **dat,
                    GString **gp, GError **err);

#endif
