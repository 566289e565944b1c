/* ortega93_cv.c — how far the one fitted CM-200 constant can be trusted:
 * the in-sample and the leave-one-out error of send_slice over the 18
 * visible time cells of Tables 1 and 2 (ortega93.h).
 *
 * A SIMD frame time is exactly linear in the machine's costs (dp_cost.h
 * WlDpCoef), so each cell is a_i + s * b_i with s = send_slice, b_i the
 * summed router-node loads of the cell and a_i the rest at the model's
 * values.  Fitting s by least squares on relative error, y_i published:
 *     s = sum w_i (1 - a_i / y_i) / sum w_i^2,   w_i = b_i / y_i,
 * clamped at 0.  In-sample: the cells at the model's send_slice (what the
 * tables print) and the fit on all 18 (which should be the model's value:
 * a check that models/cm200.yaml is at its optimum); leave-one-out: cell
 * i at the fit on the other 17.  The held costs (op, step, scan_slice)
 * are public figures or assumptions, not refitted here.  O(cells^2).
 */
#include "sim/reproduce/ortega93.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/reproduce/rp_papers.h"
#include <math.h>

static double fit_s(const RpOrCell *c, guint n, guint skip)
{
    double num = 0, den = 0;
    for (guint i = 0; i < n; i++) {
        if (i == skip)
            continue;
        double w = c[i].b / c[i].pub;
        num += w * (1.0 - c[i].a / c[i].pub);
        den += w * w;
    }
    return den > 0 && num > 0 ? num / den : 0.0;
}

static void add(GPtrArray *rows, const char *row, const char *col, double v,
                const char *note)
{
    g_ptr_array_add(rows, rp_row_new("cv", row, col, v, note));
}

/* Mean and worst |error| of a_i + s_i b_i against pub_i. */
static void errors(const RpOrCell *c, guint n, const double *s, double *mean,
                   double *worst)
{
    *mean = 0;
    *worst = 0;
    for (guint i = 0; i < n; i++) {
        double e = fabs((c[i].a + s[i] * c[i].b) / c[i].pub - 1.0);
        *mean += e / n;
        *worst = MAX(*worst, e);
    }
}

/* Joins the cells to their published times; FALSE with *err if one has
 * none (the CM-200 tables are visible). */
static gboolean join(GArray *cells, GError **err)
{
    char *path = rp_paper_path(RP_PAPERS_DIR, "ortega93");
    RpPaper *paper = rp_paper_load(path, err);
    g_free(path);
    if (!paper)
        return FALSE;
    gboolean ok = TRUE;
    for (guint i = 0; ok && i < cells->len; i++) {
        RpOrCell *c = &g_array_index(cells, RpOrCell, i);
        const RpCell *p = rp_paper_cell(paper, c->table, c->row, "time_s");
        ok = p && isfinite(p->value) && p->value > 0;
        if (ok)
            c->pub = p->value;
        else
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "ortega93: no published time_s for table %s row %s",
                        c->table, c->row);
    }
    rp_paper_free(paper);
    return ok;
}

gboolean rp_ortega93_cv(GArray *cells, GPtrArray *rows, GError **err)
{
    guint n = cells->len;
    if (n < 2)
        return TRUE;
    if (!join(cells, err))
        return FALSE;
    const RpOrCell *c = (const RpOrCell *)cells->data;
    double *model = g_new(double, n), *all = g_new(double, n),
           *loo = g_new(double, n);
    double s_all = fit_s(c, n, n);
    for (guint i = 0; i < n; i++) {
        model[i] = c[i].s;
        all[i] = s_all;
        loo[i] = fit_s(c, n, i);
        char *note = g_strdup_printf(
            "left out of the fit: %+.1f%% (in-sample %+.1f%%)",
            100 * ((c[i].a + loo[i] * c[i].b) / c[i].pub - 1),
            100 * ((c[i].a + c[i].s * c[i].b) / c[i].pub - 1));
        char *row = g_strdup_printf("table %s %s", c[i].table, c[i].row);
        add(rows, row, "loo_time_s", c[i].a + loo[i] * c[i].b, note);
        g_free(row);
        g_free(note);
    }
    double m[3], w[3];
    errors(c, n, model, &m[0], &w[0]);
    errors(c, n, all, &m[1], &w[1]);
    errors(c, n, loo, &m[2], &w[2]);
    const char *what = "% over the 18 CM-200 time cells (Tables 1, 2)";
    add(rows, "CM-200", "send_slice_model_us", c[0].s * 1e6, NULL);
    add(rows, "CM-200", "send_slice_fit_us", s_all * 1e6,
        "least squares on relative error, all 18 cells");
    add(rows, "CM-200", "in_sample_mean_abs_pct", 100 * m[0], what);
    add(rows, "CM-200", "in_sample_worst_abs_pct", 100 * w[0], what);
    add(rows, "CM-200", "refit_mean_abs_pct", 100 * m[1], what);
    add(rows, "CM-200", "loo_mean_abs_pct", 100 * m[2], what);
    add(rows, "CM-200", "loo_worst_abs_pct", 100 * w[2], what);
    g_free(model);
    g_free(all);
    g_free(loo);
    return TRUE;
}
