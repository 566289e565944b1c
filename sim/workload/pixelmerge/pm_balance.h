/* pm_balance.h — load balancing of the pixel merging phase (seed 003 §4):
 * which processor owns (gathers and z-buffers) each scanline.
 *
 * Input is the global count of local foremost pixels per scanline, summed
 * over all processors (the element-by-element global sum of §4.1), which
 * is exactly the number of pixels the owner of that scanline will merge.
 *
 *   strips  equal horizontal bands of N/P scanlines (the baseline);
 *   RS      recursive adaptive subdivision (§4.1): the band is cut into
 *           two bands of consecutive scanlines with pixel counts as equal
 *           as the scanline granularity allows; the top band goes to the
 *           subcube whose address bit `level` is 0, the bottom one to the
 *           subcube where it is 1; recurse d = log2 P levels;
 *   HBP     heuristic bin packing (§4.2): scanlines in decreasing count
 *           order, each to the currently least loaded processor.
 *
 * Address bit `level` choosing the half at recursion level `level` makes
 * the RS and strips partitions the recursive halving that the pairwise
 * exchange (§3.1) performs on channel `level` at stage `level`.
 * Ties: the lower split point, the lower scanline, the lower processor.
 * Cost: strips O(N), RS O(N + P log N), HBP O(N log N + N P).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_BALANCE_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_BALANCE_H

#include <glib.h>
#include <stdint.h>

typedef enum { WL_PM_BAL_STRIPS, WL_PM_BAL_RS, WL_PM_BAL_HBP } WlPmBalance;

/* NULL-terminated names, indexed by WlPmBalance: "strips", "rs", "hbp". */
extern const char *const wl_pm_balance_names[];

typedef struct {
    guint n_procs;   /* a power of two */
    guint height;    /* scanlines */
    guint *owner;    /* per scanline, < n_procs */
    gboolean banded; /* every processor owns consecutive scanlines */
} WlPmPartition;

/* Returns a new partition of `height` scanlines over n_procs (a power of
 * two) by `how`, from the global per-scanline counts; free with
 * wl_pm_partition_free(). */
WlPmPartition *wl_pm_partition_new(WlPmBalance how, guint n_procs,
                                   const uint64_t *counts, guint height);
void wl_pm_partition_free(WlPmPartition *p);

/* Per processor: the sum of counts of its scanlines, into load[n_procs]. */
void wl_pm_partition_loads(const WlPmPartition *p, const uint64_t *counts,
                           uint64_t *load);

/* Load imbalance of Fig. 2: (max - min) / mean of load[n]; 0 if the mean
 * is 0. */
double wl_pm_load_imbalance(const uint64_t *load, guint n);

#endif
