/* pphigs_metrics.h — GP traversal/transform time of a distributed display list
 * and the metrics of seed 001 §6.
 *
 * A GP's processor time is the sum, over every element instance its
 * traversal visits, of the element's actual cost: an on-screen polygon
 * costs poly + vertex * nverts (a line line + 2 vertex, a sphere sphere
 * + 2 vertex: its centre and a surface point); a trivially rejected (off-screen) one
 * reject_vertex * nverts — an invalidated weight (§5.2); colour, replace
 * and concatenate matrices and executes have their own costs.  The costs
 * are the GP cost table of the machine (models/pixel-planes-5.yaml,
 * nodes.gp.costs, read by wl_pphigs_costs_from_machine()), exact
 * picoseconds, so a frame's busy time (pphigs_frame.h) equals these sums.
 *
 *   distribution efficiency = T1 / sum_g T_g
 *   processor utilisation   = sum_g T_g / (P max_g T_g)
 *   overall speed-up        = P * efficiency * utilisation = T1 / max T_g
 * where T1 is the time of a single processor traversing the host list.
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_PPHIGS_METRICS_H
#define PGSIM_WORKLOAD_PPHIGS_PPHIGS_METRICS_H

#include "sim/core/time.h"
#include "sim/machine/proc.h"
#include "sim/workload/pphigs/pphigs_distrib.h"

typedef struct {
    SimTime poly, vertex;  /* on-screen polygon, plus per vertex */
    SimTime reject_vertex; /* per vertex of a trivially rejected polygon */
    SimTime color, matrix, concat, execute; /* per element (color: any of
                                               the three colour kinds) */
    SimTime line, sphere; /* on-screen line, sphere apart from vertices */
} WlPphigsCosts;

typedef struct {
    double t1;                               /* single processor (us) */
    double sum, max;                         /* over the GPs (us) */
    double efficiency, utilisation, speedup; /* fractions, factor */
} WlPphigsMetrics;

/* The operations wl_pphigs_elem_cost() / wl_pphigs_prim_cost() /
 * wl_pphigs_nonprim_cost() price, as named counts of the GP's costs
 * (polygon, vertex, reject_vertex, color, matrix_replace, matrix_concat,
 * execute) added to o: the same time on a machine whose GP costs are c. */
void wl_pphigs_elem_ops(const SceneElem *e, MachOps *o);
void wl_pphigs_prim_ops(const SceneElem *e, gboolean offscreen, MachOps *o);
void wl_pphigs_nonprim_ops(const SceneDb *db, MachOps *o);

/* Nominal (on-screen) cost of one element: poly + vertex * nverts for a
 * primitive, else the attribute's or execute's cost. */
SimTime wl_pphigs_elem_cost(const WlPphigsCosts *c, const SceneElem *e);
/* Actual cost of a primitive: nominal, or reject_vertex * nverts when
 * `offscreen` (trivially rejected). */
SimTime wl_pphigs_prim_cost(const WlPphigsCosts *c, const SceneElem *e,
                            gboolean offscreen);
/* Attributes and executes of every structure instance of `db` (max-set):
 * the non-primitive part of a traversal. */
SimTime wl_pphigs_nonprim_cost(const SceneDb *db, const WlPphigsCosts *c);
/* Time of one traversal of `db`'s posted structures under view `vp`. */
SimTime wl_pphigs_traversal_cost(const SceneDb *db, Mat4 vp,
                                 const WlPphigsCosts *c);
/* Metrics from T1 and the ngp per-GP times (us). */
void wl_pphigs_metrics_from(double t1, const double *gp_us, guint ngp,
                            WlPphigsMetrics *m);
/* Per-GP times (out[g], ngp entries, us) and the metrics, analytically:
 * the same sums a frame's busy times give (tests compare the two). */
void wl_pphigs_metrics(const WlPphigsDist *d, Mat4 vp, const WlPphigsCosts *c,
                       double *gp_us, WlPphigsMetrics *m);
/* Nominal weights from the costs (§2.3.4: the usual on-screen time, in
 * microseconds), with clustering factor `cluster`. */
void wl_pphigs_weights_from_costs(const WlPphigsCosts *c, double cluster,
                                  WlPphigsWeights *w);

#endif
