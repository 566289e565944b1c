/* metrics.h — GP traversal/transform time of a distributed display list
 * and the metrics of seed 001 §6.
 *
 * A GP's time is the sum, over every element instance its traversal
 * visits, of the element's actual cost: a polygon costs poly + vertex *
 * nverts when on-screen and `offscreen` times that when trivially
 * rejected (an invalidated weight, §5.2); colour, replace and
 * concatenate matrices, executes have their own costs.  The costs are
 * the GP cost table (models/pixel-planes-5.yaml, section pphigs), in
 * microseconds per element.
 *
 *   distribution efficiency = T1 / sum_g T_g
 *   processor utilisation   = sum_g T_g / (P max_g T_g)
 *   overall speed-up        = P * efficiency * utilisation = T1 / max T_g
 * where T1 is the time of a single processor traversing the host list.
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_METRICS_H
#define PGSIM_WORKLOAD_PPHIGS_METRICS_H

#include "sim/workload/pphigs/distrib.h"

typedef struct {
    double poly, vertex;  /* per polygon, per vertex (us) */
    double offscreen;     /* share of a polygon's cost when off-screen */
    double color, matrix, concat, execute; /* per element (us) */
} WlPphigsCosts;

typedef struct {
    double t1;         /* single processor (us) */
    double sum, max;   /* over the GPs (us) */
    double efficiency, utilisation, speedup; /* fractions, factor */
} WlPphigsMetrics;

/* On-screen cost of one element (us): poly + vertex * nverts for a
 * primitive, else the attribute's or execute's cost. */
double wl_pphigs_elem_us(const WlPphigsCosts *c, const SceneElem *e);
/* Time of one traversal of `db`'s posted structures under view `vp`. */
double wl_pphigs_traversal_us(const SceneDb *db, Mat4 vp,
                              const WlPphigsCosts *c);
/* Per-GP times (out[g], ngp entries) and the metrics. */
void wl_pphigs_metrics(const WlPphigsDist *d, Mat4 vp,
                       const WlPphigsCosts *c, double *gp_us,
                       WlPphigsMetrics *m);
/* Nominal weights from the costs (§2.3.4: the usual on-screen time). */
void wl_pphigs_weights_from_costs(const WlPphigsCosts *c, double cluster,
                                  WlPphigsWeights *w);

#endif
