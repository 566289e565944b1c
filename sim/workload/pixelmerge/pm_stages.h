/* pm_stages.h — the stage plans of the sort-last compositing schemes:
 * which blocks of processes combine at each stage (pm_composite.h runs
 * a plan on real pixels).
 *
 * A block is a run of consecutive ranks (visibility order) whose active
 * processes hold, between them, the whole image composited over the
 * block's ranks, each its own piece.  At first every rank is a block of
 * one.  A stage cuts the list of blocks into groups of consecutive
 * blocks; each group of k > 1 blocks becomes one block (pm_composite.h
 * re-splits the image among the group's active processes).
 *
 *   binary swap   (Ma, Painter, Hansen, Krogh 1994) groups of 2, log2 P
 *                 stages.  P not a power of two: the extra processes are
 *                 folded in first — with P = 2^d + e, a fold stage pairs
 *                 ranks (0,1), (2,3) ... (2e-2, 2e-1): the odd rank of a
 *                 pair sends its whole image to the even one and leaves
 *                 (the pairs are adjacent in visibility order, so the
 *                 over operator stays ordered); then binary swap runs on
 *                 the 2^d remaining blocks;
 *   direct send   (Hsu 1993; Neumann 1993) one stage, one group of P;
 *   radix-k       (Peterka, Goodell, Ross, Shen, Thakur 2009) stage i
 *                 groups k_i blocks; the radices' product must be P (so
 *                 binary swap is k = 2, 2, ... and direct send k = P);
 *                 without radices, P's prime factors in increasing order,
 *                 neighbours multiplied while the product stays <= 8
 *                 (IceT's default target k);
 *   2-3 swap      (Yu, Wang, Ma 2008) any P: each stage cuts the m
 *                 blocks into groups of 2, with one group of 3 (the last)
 *                 when m is odd, until one block is left.
 * Cost: O(P log P).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_STAGES_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_STAGES_H

#include "sim/workload/pixelmerge/pm_merge.h"

typedef struct {
    guint n_groups;
    guint *size;  /* blocks in each group, in rank order */
    gboolean fold; /* a group's image goes whole to its first process */
} WlPmStage;

typedef struct {
    guint n_stages;
    WlPmStage *stage;
} WlPmPlan;

/* The most radices a plan takes (2^32 has 32 factors). */
#define WL_PM_MAX_RADICES 32

/* Returns a new plan of `scheme` (a compositing scheme) for n_procs >= 1;
 * radices[n_radices] for radix-k (n_radices 0: the default
 * factorisation; else their product must be n_procs, asserted: see
 * wl_pm_radices_ok).  Free with wl_pm_plan_free(). */
WlPmPlan *wl_pm_plan_new(WlPmScheme scheme, guint n_procs,
                         const guint *radices, guint n_radices);
void wl_pm_plan_free(WlPmPlan *plan);

/* TRUE when every radix is >= 2 and their product is n_procs. */
gboolean wl_pm_radices_ok(const guint *radices, guint n_radices,
                          guint n_procs);

/* The default radices of n_procs into out[WL_PM_MAX_RADICES]; returns
 * how many (0 for n_procs 1). */
guint wl_pm_radices_default(guint n_procs, guint *out);

#endif
