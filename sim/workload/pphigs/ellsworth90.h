/* ellsworth90.h — the computation behind `pgsim reproduce ellsworth90`:
 * seed 001's table for the four databases at 4 and 16 GPs.
 *
 * Rows (table "1"): space_station, building_lobby, flock_old_well,
 * two_human_figures; columns simple_eff_P, complex_eff_P, util_P,
 * speedup_P for P = 4, 16 (efficiency and utilisation in percent, of the
 * complex algorithm for util and speedup).  Table "db": the generated
 * databases' depth, structures, polys_per_structure, poly_attr_ratio,
 * offscreen_pct.  The clustering factor is set from the number of GPs:
 * c = max(1, cluster_scale / P) (§2.3.2).
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_ELLSWORTH90_H
#define PGSIM_WORKLOAD_PPHIGS_ELLSWORTH90_H

#include "sim/app/reproduce.h"
#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/metrics.h"
#include "sim/workload/pphigs/pphigs_cfg.h"

double wl_pphigs_cluster_factor(double cluster_scale, guint ngp);

/* Runs one database at one GP count with both algorithms.  With hw the
 * processor times are the GPs' traverse busy times of one event-driven
 * frame each (frame.h; T1 from a one-GP frame); with hw NULL the
 * analytic traversal cost (metrics.h).  Both give the same numbers up to
 * picosecond rounding (tested). */
void wl_pphigs_run_db(const ScenePphigsDb *db, guint ngp,
                      const WlPphigsCosts *c, double cluster_scale,
                      const WlPphigsHw *hw, WlPphigsMetrics *simple,
                      WlPphigsMetrics *complex);

/* Appends RpRow * (sim/app/reproduce.h) for the given databases (specs
 * in seed 001's row order; n of them).  FALSE with *err if a spec is
 * bad. */
gboolean wl_pphigs_table1(const ScenePphigsSpec *specs, guint n,
                          const WlPphigsCosts *c, double cluster_scale,
                          const WlPphigsHw *hw, GPtrArray *rows,
                          GError **err);

/* The reproduction (sim/app/reproductions.c): reads
 * configs/pphigs/databases.yaml, models/pixel-planes-5.yaml and
 * configs/pphigs/frame.yaml from the working directory. */
extern const RpReproduction wl_pphigs_ellsworth90;

#endif
