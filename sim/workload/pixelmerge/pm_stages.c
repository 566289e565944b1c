/* pm_stages.c — stage plans of binary swap, direct send, radix-k and
 * 2-3 swap (see pm_stages.h for the schemes and their sources).
 *
 * Invariant of a plan: at each stage the group sizes add up to the
 * number of blocks left by the previous stage; the last stage leaves
 * one block (no stage at all for one process).
 */
#include "sim/workload/pixelmerge/pm_stages.h"

/* Appends a stage of `n` groups with sizes size[n] (copied). */
static void add_stage(GArray *stages, const guint *size, guint n,
                      gboolean fold)
{
    WlPmStage st = {n, g_memdup2(size, n * sizeof *size), fold};
    g_array_append_val(stages, st);
}

/* Stages of groups of k blocks, for each radix k, over m blocks. */
static void radix_stages(GArray *stages, guint m, const guint *radix, guint nr)
{
    for (guint i = 0; i < nr; i++) {
        g_assert(m % radix[i] == 0);
        guint g = m / radix[i];
        guint *size = g_new(guint, g);
        for (guint j = 0; j < g; j++)
            size[j] = radix[i];
        add_stage(stages, size, g, FALSE);
        g_free(size);
        m = g;
    }
}

/* Binary swap: a fold stage when n is not a power of two, then halving. */
static void binary_swap(GArray *stages, guint n)
{
    guint pow = 1, d = 0;
    while (pow * 2 <= n) {
        pow *= 2;
        d++;
    }
    guint e = n - pow;
    if (e) {
        guint *size = g_new(guint, pow);
        for (guint j = 0; j < pow; j++)
            size[j] = j < e ? 2 : 1;
        add_stage(stages, size, pow, TRUE);
        g_free(size);
    }
    guint two[WL_PM_MAX_RADICES];
    for (guint i = 0; i < d; i++)
        two[i] = 2;
    radix_stages(stages, pow, two, d);
}

/* 2-3 swap: pairs, the last group a triple when the count is odd. */
static void two_three(GArray *stages, guint m)
{
    while (m > 1) {
        guint g = m / 2;
        guint *size = g_new(guint, g);
        for (guint j = 0; j < g; j++)
            size[j] = 2;
        size[g - 1] += m % 2;
        add_stage(stages, size, g, FALSE);
        g_free(size);
        m = g;
    }
}

guint wl_pm_radices_default(guint n, guint *out)
{
    guint k = 0;
    for (guint f = 2; n > 1;) {
        if (n % f) {
            f = f * f > n ? n : f + 1;
            continue;
        }
        n /= f;
        if (k > 0 && out[k - 1] * f <= 8)
            out[k - 1] *= f;
        else
            out[k++] = f;
    }
    return k;
}

gboolean wl_pm_radices_ok(const guint *radices, guint n_radices, guint n)
{
    uint64_t prod = 1;
    for (guint i = 0; i < n_radices; i++) {
        if (radices[i] < 2)
            return FALSE;
        prod *= radices[i];
        if (prod > n)
            return FALSE;
    }
    return prod == n;
}

WlPmPlan *wl_pm_plan_new(WlPmScheme scheme, guint n, const guint *radices,
                         guint n_radices)
{
    g_assert(n >= 1 && wl_pm_scheme_composites(scheme));
    GArray *stages = g_array_new(FALSE, FALSE, sizeof(WlPmStage));
    guint def[WL_PM_MAX_RADICES];
    switch (scheme) {
    case WL_PM_BINARY_SWAP:
        binary_swap(stages, n);
        break;
    case WL_PM_DIRECT_SEND:
        radix_stages(stages, n, &n, n > 1);
        break;
    case WL_PM_RADIX_K:
        if (n_radices == 0) {
            n_radices = wl_pm_radices_default(n, def);
            radices = def;
        }
        g_assert(wl_pm_radices_ok(radices, n_radices, n));
        radix_stages(stages, n, radices, n_radices);
        break;
    default:
        two_three(stages, n);
        break;
    }
    WlPmPlan *plan = g_new0(WlPmPlan, 1);
    plan->n_stages = stages->len;
    plan->stage = (WlPmStage *)(void *)g_array_free(stages, FALSE);
    return plan;
}

void wl_pm_plan_free(WlPmPlan *plan)
{
    if (!plan)
        return;
    for (guint i = 0; i < plan->n_stages; i++)
        g_free(plan->stage[i].size);
    g_free(plan->stage);
    g_free(plan);
}
