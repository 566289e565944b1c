/* pphigs_rig.h — the tests' rig: one generated database on a P-GP
 * Pixel-Planes 5, each distribution algorithm, from frames run by hand
 * (not through the runner), with T1 the busy time of a frame on a
 * one-GP machine; and the same computed analytically.  The tests hold
 * the workload's own metrics (sim/run, what `pgsim reproduce ellsworth90`
 * reads) against these.  The clustering factor is set from the number
 * of GPs: c = max(1, cluster_scale / P) (§2.3.2).
 *
 * Every processor time is a GP's busy time (phases traverse + transform)
 * in one event-driven frame on a Pixel-Planes 5 machine built by the
 * machine layer with P GPs (pphigs_frame.h).
 */
#ifndef PGSIM_TESTS_PPHIGS_RIG_H
#define PGSIM_TESTS_PPHIGS_RIG_H

#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/pphigs_metrics.h"
#include "sim/workload/pphigs/pphigs_cfg.h"
#include "sim/run/run.h"

/* What a reproduction cell runs on (all borrowed). */
typedef struct {
    const char *model;    /* machine model name: "pixel-planes-5" */
    const char *fidelity; /* ring transport: analytic, flow or packet */
    WlPphigsSetup setup;  /* frame sizes, clustering scale */
} PphigsRig;

/* A new machine of model `model` with `ngp` GPs (a `nodes.gp.count`
 * override), on eng; NULL with *err. */
MachMachine *pphigs_rig_machine_new(SimEngine *eng, const char *model, guint ngp,
                                   const char *fidelity, GError **err);

/* One database at one GP count with both algorithms, from frames on
 * fresh machines (see above).  FALSE with *err (bad model ...). */
gboolean pphigs_rig_run_db(const ScenePphigsDb *db, guint ngp,
                          const PphigsRig *rig, WlPphigsMetrics *simple,
                          WlPphigsMetrics *complex, GError **err);
/* One algorithm (any of the three) at one GP count, the same way. */
gboolean pphigs_rig_run_algo(const ScenePphigsDb *db, guint ngp,
                            WlPphigsAlgo a, const PphigsRig *rig,
                            WlPphigsMetrics *out, GError **err);
/* The same computed analytically (metrics.h) from a cost table: the
 * cross-check that frames add up to the traversal cost model. */
void pphigs_rig_analytic(const ScenePphigsDb *db, guint ngp,
                               const WlPphigsCosts *c, double cluster_scale,
                               WlPphigsMetrics *simple,
                               WlPphigsMetrics *complex);

/* One run of configs/pphigs-flock.yaml with the overrides `sets`
 * (NULL-terminated), quiet; fails the test on an error.  Free with
 * sim_result_free(); *run (cfg_run_free) holds what it borrows. */
SimResult *pphigs_rig_run_flock(const char *const *sets, CfgRun **run);

#endif
