/* kurc96_cv.c — how far the node-cost fit of kurc96 can be trusted: the
 * in-sample error and the leave-one-scene-out error (issue 11, point 2).
 *
 * The node costs of models/ipsc2.yaml were fitted by scripts/kurc96/fit.py
 * on all 36 P=16, N=400 cells of Table 2 (6 scenes x 6 columns).  Around
 * those costs every cell is, to first order, sim_i + sum_j J_ij x_j, with
 * x_j the relative change of cost group j and J_ij the simulator's own
 * response to a small change (finite differences, kurc96.c).  Leaving
 * scene s out: the x minimising the squared relative errors of the 30
 * cells of the other five scenes (costs kept non-negative: x_j >= -1,
 * by pinning and re-solving), then the six cells of scene s predicted at
 * that x.  Linearised, so it needs 1 + groups runs per cell, not a refit
 * per scene; exact where phases are linear in the costs (span and local
 * z-buffer), first order in the merge (network waits).
 * Cost: O(scenes x groups^2 x cells).
 */
#include "sim/reproduce/kurc96.h"
#include <math.h>
#include <string.h>

/* Normal equations of min ||A x - b|| over the free columns, by Gaussian
 * elimination with partial pivoting and a tiny ridge; x of pinned
 * columns is left as it is. */
static void lsq(const double *A, const double *b, int rows, int cols,
                const gboolean *pinned, double *x)
{
    double M[RP_KURC_GROUPS][RP_KURC_GROUPS + 1];
    int idx[RP_KURC_GROUPS], n = 0;
    for (int j = 0; j < cols; j++)
        if (!pinned[j])
            idx[n++] = j;
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < n; k++) {
            double s = i == k ? 1e-12 : 0;
            for (int r = 0; r < rows; r++)
                s += A[r * cols + idx[i]] * A[r * cols + idx[k]];
            M[i][k] = s;
        }
        double v = 0;
        for (int r = 0; r < rows; r++) {
            double rhs = b[r];
            for (int j = 0; j < cols; j++)
                if (pinned[j])
                    rhs -= A[r * cols + j] * x[j];
            v += A[r * cols + idx[i]] * rhs;
        }
        M[i][n] = v;
    }
    for (int i = 0; i < n; i++) {
        int p = i;
        for (int k = i + 1; k < n; k++)
            if (fabs(M[k][i]) > fabs(M[p][i]))
                p = k;
        for (int c = 0; c <= n; c++) {
            double t = M[i][c];
            M[i][c] = M[p][c];
            M[p][c] = t;
        }
        for (int k = i + 1; k < n; k++) {
            double f = M[k][i] / M[i][i];
            for (int c = i; c <= n; c++)
                M[k][c] -= f * M[i][c];
        }
    }
    for (int i = n - 1; i >= 0; i--) {
        double s = M[i][n];
        for (int c = i + 1; c < n; c++)
            s -= M[i][c] * x[idx[c]];
        x[idx[i]] = s / M[i][i];
    }
}

/* x minimising the relative errors of the cells not of scene `out`
 * (out < 0: all cells), with x_j >= -1. */
static void fit_without(const RpKurcCv *cv, int out, double *x)
{
    int rows = 0, g = cv->groups;
    double *A = g_new(double, (gsize)cv->n * g), *b = g_new(double, cv->n);
    for (int i = 0; i < cv->n; i++) {
        if (cv->scene[i] == out)
            continue;
        for (int j = 0; j < g; j++)
            A[rows * g + j] = cv->jac[i * g + j] / cv->pub[i];
        b[rows++] = 1.0 - cv->sim[i] / cv->pub[i];
    }
    gboolean pinned[RP_KURC_GROUPS] = {FALSE};
    memset(x, 0, sizeof(double) * (gsize)g);
    for (int round = 0; round <= g; round++) {
        lsq(A, b, rows, g, pinned, x);
        gboolean again = FALSE;
        for (int j = 0; j < g; j++)
            if (!pinned[j] && x[j] < -1) {
                pinned[j] = again = TRUE;
                x[j] = -1;
            }
        if (!again)
            break;
    }
    g_free(A);
    g_free(b);
}

double rp_kurc96_cv_predict(const RpKurcCv *cv, int i, const double *x)
{
    double v = cv->sim[i];
    for (int j = 0; j < cv->groups; j++)
        v += cv->jac[i * cv->groups + j] * x[j];
    return v;
}

void rp_kurc96_cv_run(const RpKurcCv *cv, double *loso)
{
    g_assert(cv->groups <= RP_KURC_GROUPS);
    double x[RP_KURC_GROUPS];
    for (int s = 0; s < cv->scenes; s++) {
        fit_without(cv, s, x);
        for (int i = 0; i < cv->n; i++)
            if (cv->scene[i] == s)
                loso[i] = rp_kurc96_cv_predict(cv, i, x);
    }
}

void rp_kurc96_cv_errors(const RpKurcCv *cv, const double *v, double *mean,
                         double *worst)
{
    *mean = *worst = 0;
    for (int i = 0; i < cv->n; i++) {
        double e = fabs(v[i] / cv->pub[i] - 1);
        *mean += e / cv->n;
        *worst = MAX(*worst, e);
    }
}
