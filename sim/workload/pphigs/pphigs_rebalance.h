/* pphigs_rebalance.h — display-list rebalancing (seed 001 §5).
 *
 * After each frame the caller hands in the GPs' measured traversal times
 * (the real traversal: off-screen primitives cost a fraction of their
 * nominal weight).  Imbalance is (max - mean) / max of those times: the
 * share of the frame's transformation time lost to the slowest GP.
 *
 * Detection (§5): when the imbalance exceeds `threshold` for `frames`
 * consecutive frames, the cause is classified by the nominal loads
 * (wl_pphigs_dist_loads, §5.1): if they are themselves imbalanced past
 * the threshold it is an imperfect distribution, otherwise invalidated
 * weights (§5.2).
 * Correction, at most `fraction` of the measured excess (max - mean) and
 * at most `max_moves` element moves per frame:
 *   imperfect    dealt elements picked at random (seeded stream) move
 *                from the most to the least loaded GP (by nominal load),
 *                each lighter than the gap between the two;
 *   invalidated  an on-screen primitive of the most loaded GP (measured)
 *                is exchanged with an off-screen one of the same nominal
 *                weight on the least loaded GP.
 * Moves use wl_pphigs_dist_move (the editing machinery of §3), so every
 * GP keeps the attributes it needs.
 *
 * Limits: primitives inside primitive structures are moved only as whole
 * instances (their execute), and only by the imperfect-distribution
 * path; invalidated weights are measured on directly dealt primitives.
 * Cost per correcting frame: O(host max-set + moves * host size).
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_PPHIGS_REBALANCE_H
#define PGSIM_WORKLOAD_PPHIGS_PPHIGS_REBALANCE_H

#include "sim/workload/pphigs/pphigs_metrics.h"

typedef struct {
    double threshold; /* imbalance that counts (0.10 in §5) */
    guint frames;     /* consecutive frames over it before acting */
    double fraction;  /* share of the excess corrected per frame */
    guint max_moves;  /* element moves per frame, at most */
    uint64_t seed;    /* random picks of §5.1 */
} WlPphigsRebalParams;

typedef enum {
    WL_PPHIGS_REBAL_NONE,
    WL_PPHIGS_REBAL_IMPERFECT,  /* §5.1 */
    WL_PPHIGS_REBAL_INVALIDATED /* §5.2 */
} WlPphigsRebalCause;

typedef struct {
    double imbalance;         /* measured this frame */
    double nominal_imbalance; /* of the nominal loads */
    guint over;               /* consecutive frames over the threshold */
    WlPphigsRebalCause cause; /* of this frame's correction */
    guint moves;              /* elements moved this frame */
    uint64_t total_moves;     /* since wl_pphigs_rebal_new */
} WlPphigsRebalStep;

typedef struct WlPphigsRebal WlPphigsRebal;

/* Returns a new rebalancer; free with wl_pphigs_rebal_free(). */
WlPphigsRebal *wl_pphigs_rebal_new(const WlPphigsRebalParams *p);
void wl_pphigs_rebal_free(WlPphigsRebal *rb);

/* (max - mean) / max of n values; 0 when all are 0. */
double wl_pphigs_imbalance(const double *v, guint n);

/* One frame: `gp_us` holds the ngp measured times of the frame just
 * drawn under `vp`; may move elements of `d` (effective next frame). */
void wl_pphigs_rebal_frame(WlPphigsRebal *rb, WlPphigsDist *d, Mat4 vp,
                           const WlPphigsCosts *c, const double *gp_us,
                           WlPphigsRebalStep *out);

const char *wl_pphigs_rebal_cause_name(WlPphigsRebalCause c);

#endif
