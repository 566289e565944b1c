/* plot_params.c — a chart never averages over a parameter it does not
 * plot (issue 33, point 5).
 *
 * A sweep's results table (sim/app/sweep) has its parameters as the
 * columns between `seed` and `status`.  Rows that share a chart's x and
 * series are averaged into one point, with min..max bars: that is honest
 * only when they differ in the repetition alone.  plot_unplotted() finds
 * the parameters that differ within such a group; plot_texts() draws one
 * series per value of the one such parameter of a chart without series,
 * and refuses any other case with a message naming the parameter.
 * Tables that are not a sweep's (no seed..status columns) are taken as
 * they are.  O(rows x parameters).  Also the ticks of a log axis
 * (plot_log_axis): one labelled tick per decade at least.
 */
#include "sim/output/plot.h"
#include "sim/core/error.h"
#include <math.h>
#include <string.h>

/* TRUE when rows of t that share x and series hold two values of column
 * c; their x and the two values go to *x, *a, *b (borrowed). */
static gboolean varies(const PlotSpec *p, const DataTable *t, int c,
                       const char **x, const char **a, const char **b)
{
    int xc = dt_col(t, p->x), yc = dt_col(t, p->y);
    int sc = p->series ? dt_col(t, p->series) : -1;
    GHashTable *first =
        g_hash_table_new_full(g_str_hash, g_str_equal, g_free, NULL);
    gboolean found = FALSE;
    for (guint r = 0; !found && r < t->rows->len; r++) {
        const char *xs = dt_cell(t, r, xc), *v = dt_cell(t, r, c);
        if (!*xs || !*dt_cell(t, r, yc))
            continue;
        char *key = g_strdup_printf("%s\x1f%s", sc >= 0 ? dt_cell(t, r, sc)
                                                        : "", xs);
        const char *seen = g_hash_table_lookup(first, key);
        if (!seen) {
            g_hash_table_insert(first, key, (gpointer)v);
            continue;
        }
        g_free(key);
        if (strcmp(seen, v) != 0) {
            *x = xs, *a = seen, *b = v;
            found = TRUE;
        }
    }
    g_hash_table_destroy(first);
    return found;
}

guint plot_unplotted(const PlotSpec *p, const DataTable *t, char **first,
                     GString *why)
{
    int lo = dt_col(t, "seed"), hi = dt_col(t, "status");
    int xc = dt_col(t, p->x), sc = p->series ? dt_col(t, p->series) : -1;
    guint n = 0;
    for (int c = lo + 1; lo >= 0 && c < hi; c++) {
        const char *x, *a, *b, *name = g_ptr_array_index(t->cols, c);
        if (c == xc || c == sc || !varies(p, t, c, &x, &a, &b))
            continue;
        char *shown = plot_printable(name), *sx = plot_printable(x),
             *sa = plot_printable(a), *sb = plot_printable(b);
        g_string_append_printf(why,
                               "%s'%s' ('%s' and '%s' where %s = %s)",
                               n ? ", " : "", shown, sa, sb, p->x, sx);
        g_free(shown), g_free(sx), g_free(sa), g_free(sb);
        if (!n++)
            *first = g_strdup(name);
    }
    return n;
}

/* A chart of a sweep without series that would average over one swept
 * parameter gets a series per value of it; more such parameters, or one
 * beside a series, are refused, named. */
gboolean plot_split_unplotted(PlotSpec *q, const DataTable *t, GError **err)
{
    char *first = NULL;
    GString *why = g_string_new(NULL);
    guint n = plot_unplotted(q, t, &first, why);
    if (n == 1 && !q->series)
        q->series = first;
    else if (n)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "plot %s: found rows with the same x%s that differ in "
                    "the swept %s %s, expected a chart that averages over "
                    "repetitions only: give it as the series, or keep one "
                    "value (pgsim plot --where KEY=VALUE)",
                    q->name, q->series ? " and series" : "",
                    n > 1 ? "parameters" : "parameter", why->str);
    if (n != 1 || q->series != first)
        g_free(first);
    g_string_free(why, TRUE);
    return n == 0 || q->series == first;
}

/* The 1-2-5 value at or below (down) or at or above x > 0. */
static double step125(double x, gboolean down)
{
    static const double m[] = {1, 2, 5, 10};
    double d = pow(10, floor(log10(x)));
    if (down) {
        double v = d;
        for (int i = 0; i < 3 && m[i] * d <= x * (1 + 1e-12); i++)
            v = m[i] * d;
        return v;
    }
    for (int i = 0; i < 4; i++)
        if (m[i] * d >= x * (1 - 1e-12))
            return m[i] * d;
    return 10 * d;
}

/* A log axis: its range the 1-2-5 values around the data, a labelled
 * tick at every decade inside and, when the range spans at most two
 * decades, at 2 and 5 times them too (so never one lone label). */
void plot_log_axis(GString *o, const char *axis, double lo, double hi)
{
    if (!(lo > 0) || !(hi >= lo) || !isfinite(hi))
        return; /* nothing positive to scale: gnuplot's own */
    double r0 = step125(lo, TRUE), r1 = step125(hi, FALSE);
    if (r1 <= r0)
        r1 = step125(r0 * 1.5, FALSE);
    char a_s[G_ASCII_DTOSTR_BUF_SIZE], b_s[G_ASCII_DTOSTR_BUF_SIZE];
    g_string_append_printf(o, "set %srange [%s:%s]\nset format %s '%%g'\n"
                              "set m%stics 10\nset %stics (",
                           axis, g_ascii_formatd(a_s, sizeof a_s, "%g", r0),
                           g_ascii_formatd(b_s, sizeof b_s, "%g", r1), axis,
                           axis, axis);
    static const int steps[] = {1, 2, 5};
    int a = (int)floor(log10(r0)), b = (int)ceil(log10(r1));
    int per = b - a <= 2 ? 3 : 1;
    gboolean any = FALSE;
    for (int k = a; k <= b && k - a < 400; k++)
        for (int m = 0; m < per; m++) {
            double v = steps[m] * pow(10, k);
            if (v < r0 * (1 - 1e-12) || v > r1 * (1 + 1e-12))
                continue;
            char t[G_ASCII_DTOSTR_BUF_SIZE];
            g_string_append_printf(o, "%s%s", any ? ", " : "",
                                   g_ascii_formatd(t, sizeof t, "%g", v));
            any = TRUE;
        }
    g_string_append(o, ")\n");
}
