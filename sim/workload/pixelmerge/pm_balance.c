/* pm_balance.c — strips, recursive adaptive subdivision (RS) and
 * heuristic bin packing (HBP) of the merge load (seed 003 §4.1, §4.2).
 *
 * RS works on the prefix array S[y] = counts[0] + ... + counts[y - 1]
 * (S has height + 1 entries), the result of the global sum and a local
 * prefix; a band [lo, hi) is cut at the s in [lo, hi] whose S[s] is
 * closest to (S[lo] + S[hi]) / 2, found by binary search.
 * Equal strips are RS on unit counts, so they halve like RS does.
 */
#include "sim/workload/pixelmerge/pm_balance.h"
#include <stdlib.h>
#include <string.h>

const char *const wl_pm_balance_names[] = {"strips", "rs", "hbp", NULL};

static gboolean is_pow2(guint n)
{
    return n > 0 && (n & (n - 1)) == 0;
}

static guint log2u(guint n)
{
    guint d = 0;
    while ((1u << d) < n)
        d++;
    return d;
}

/* Smallest s in [lo, hi] with 2 S[s] >= S[lo] + S[hi]; then the nearer of
 * s - 1 and s to the middle (the lower on a tie). */
static guint rs_cut(const uint64_t *S, guint lo, guint hi)
{
    uint64_t twice_mid = S[lo] + S[hi];
    guint a = lo, b = hi;
    while (a < b) {
        guint m = a + (b - a) / 2;
        if (2 * S[m] >= twice_mid)
            b = m;
        else
            a = m + 1;
    }
    if (a > lo) {
        uint64_t over = 2 * S[a] - twice_mid;
        uint64_t under = twice_mid - 2 * S[a - 1];
        if (under <= over)
            return a - 1;
    }
    return a;
}

static void rs_assign(const uint64_t *S, guint *owner, guint lo, guint hi,
                      guint level, guint dims, guint base)
{
    if (level == dims) {
        for (guint y = lo; y < hi; y++)
            owner[y] = base;
        return;
    }
    guint s = rs_cut(S, lo, hi);
    rs_assign(S, owner, lo, s, level + 1, dims, base);
    rs_assign(S, owner, s, hi, level + 1, dims, base | (1u << level));
}

static void partition_rs(WlPmPartition *p, const uint64_t *counts,
                         gboolean unit)
{
    uint64_t *S = g_new0(uint64_t, p->height + 1); /* S[0] = 0 */
    for (guint y = 0; y < p->height; y++)
        S[y + 1] = S[y] + (unit ? 1 : counts[y]);
    rs_assign(S, p->owner, 0, p->height, 0, log2u(p->n_procs), 0);
    p->banded = TRUE;
    g_free(S);
}

typedef struct {
    uint64_t count;
    guint y;
} RowCount;

static int row_count_cmp(const void *a, const void *b)
{
    const RowCount *x = a, *y = b;
    if (x->count != y->count)
        return x->count > y->count ? -1 : 1;
    return x->y < y->y ? -1 : (x->y > y->y);
}

static guint least_loaded(const uint64_t *load, guint n)
{
    guint best = 0;
    for (guint k = 1; k < n; k++)
        if (load[k] < load[best])
            best = k;
    return best;
}

static void partition_hbp(WlPmPartition *p, const uint64_t *counts)
{
    RowCount *rows = g_new(RowCount, p->height);
    for (guint y = 0; y < p->height; y++)
        rows[y] = (RowCount){counts[y], y};
    qsort(rows, p->height, sizeof *rows, row_count_cmp);
    uint64_t *load = g_new0(uint64_t, p->n_procs);
    for (guint i = 0; i < p->height; i++) {
        guint k = least_loaded(load, p->n_procs);
        p->owner[rows[i].y] = k;
        load[k] += rows[i].count;
    }
    p->banded = FALSE;
    g_free(load);
    g_free(rows);
}

WlPmPartition *wl_pm_partition_new(WlPmBalance how, guint n_procs,
                                   const uint64_t *counts, guint height)
{
    g_assert(is_pow2(n_procs) && height > 0);
    WlPmPartition *p = g_new0(WlPmPartition, 1);
    p->n_procs = n_procs;
    p->height = height;
    p->owner = g_new0(guint, height);
    switch (how) {
    case WL_PM_BAL_STRIPS:
        partition_rs(p, counts, TRUE);
        break;
    case WL_PM_BAL_RS:
        partition_rs(p, counts, FALSE);
        break;
    case WL_PM_BAL_HBP:
        partition_hbp(p, counts);
        break;
    default:
        g_assert_not_reached();
    }
    return p;
}

void wl_pm_partition_free(WlPmPartition *p)
{
    if (!p)
        return;
    g_free(p->owner);
    g_free(p);
}

void wl_pm_partition_loads(const WlPmPartition *p, const uint64_t *counts,
                           uint64_t *load)
{
    memset(load, 0, p->n_procs * sizeof *load);
    for (guint y = 0; y < p->height; y++)
        load[p->owner[y]] += counts[y];
}

double wl_pm_load_imbalance(const uint64_t *load, guint n)
{
    g_assert(n > 0);
    uint64_t mn = load[0], mx = load[0];
    double sum = 0;
    for (guint k = 0; k < n; k++) {
        mn = MIN(mn, load[k]);
        mx = MAX(mx, load[k]);
        sum += (double)load[k];
    }
    if (sum == 0)
        return 0.0;
    return (double)(mx - mn) / (sum / n);
}
