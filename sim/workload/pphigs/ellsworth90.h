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
 *
 * Every processor time is a GP's busy time (phases traverse + transform)
 * in one event-driven frame on a Pixel-Planes 5 machine built by the
 * machine layer with P GPs (frame.h); T1 is the same on a one-GP machine.
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_ELLSWORTH90_H
#define PGSIM_WORKLOAD_PPHIGS_ELLSWORTH90_H

#include "sim/app/reproduce.h"
#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/metrics.h"
#include "sim/workload/pphigs/pphigs_cfg.h"

/* What a reproduction cell runs on (all borrowed). */
typedef struct {
    const char *model;    /* machine model name: "pixel-planes-5" */
    const char *fidelity; /* ring transport: analytic, flow or packet */
    WlPphigsSetup setup;  /* frame sizes, clustering scale */
} WlPphigsRig;

/* A new machine of model `model` with `ngp` GPs (a `nodes.gp.count`
 * override), on eng; NULL with *err. */
MachMachine *wl_pphigs_machine_new(SimEngine *eng, const char *model, guint ngp,
                                   const char *fidelity, GError **err);

/* One database at one GP count with both algorithms, from frames on
 * fresh machines (see above).  FALSE with *err (bad model ...). */
gboolean wl_pphigs_run_db(const ScenePphigsDb *db, guint ngp,
                          const WlPphigsRig *rig, WlPphigsMetrics *simple,
                          WlPphigsMetrics *complex, GError **err);
/* The same computed analytically (metrics.h) from a cost table: the
 * cross-check that frames add up to the traversal cost model. */
void wl_pphigs_run_db_analytic(const ScenePphigsDb *db, guint ngp,
                               const WlPphigsCosts *c, double cluster_scale,
                               WlPphigsMetrics *simple,
                               WlPphigsMetrics *complex);

/* Appends RpRow * (sim/app/reproduce.h) for the given databases (specs
 * in seed 001's row order; n of them).  FALSE with *err if a spec or the
 * machine is bad. */
gboolean wl_pphigs_table1(const ScenePphigsSpec *specs, guint n,
                          const WlPphigsRig *rig, GPtrArray *rows,
                          GError **err);

/* The reproduction (sim/app/reproductions.c): reads
 * configs/pphigs/databases.yaml and configs/pphigs/frame.yaml from the
 * working directory and the model pixel-planes-5 by name. */
extern const RpReproduction wl_pphigs_ellsworth90;

#endif
