/* pphigs_rig.c — the tests' rig (pphigs_rig.h): a fresh distribution
 * of a generated database followed by one event-driven frame on a fresh
 * Pixel-Planes 5 machine; the metrics are the GPs' busy times.
 * Also one run of the flock config with overrides, through the runner.
 * Cost: per database and GP count, 2 distributions and 2 frames, O(n P)
 * each, plus one frame on one GP.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/workload/pphigs/pphigs_rig.h"
#include <string.h>

MachMachine *pphigs_rig_machine_new(SimEngine *eng, const char *model, guint ngp,
                                   const char *fidelity, GError **err)
{
    char *text =
        g_strdup_printf("model: %s\nnodes: {gp: {count: %u}}\n", model, ngp);
    CfgNode *sec = cfg_load_string(text, "<pphigs machine>", err);
    MachMachine *m = sec ? mach_new_from_cfg(eng, sec, fidelity, err) : NULL;
    cfg_free(sec);
    g_free(text);
    return m;
}

static WlPphigsDist *distribute(const ScenePphigsDb *db, guint ngp,
                                WlPphigsAlgo a, const WlPphigsCosts *c,
                                double cluster_scale, guint strip_split)
{
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(
        c, wl_pphigs_cluster_factor(cluster_scale, ngp), &w);
    w.strip_split = strip_split;
    return wl_pphigs_dist_new(db->db, ngp, a, &w);
}

/* Per-GP processor times (us) of one frame of `a` on ngp GPs. */
static gboolean frame_times(const ScenePphigsDb *db, guint ngp, WlPphigsAlgo a,
                            const PphigsRig *rig, double *us, GError **err)
{
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        pphigs_rig_machine_new(eng, rig->model, ngp, rig->fidelity, err);
    WlPphigsFrame *f =
        m ? wl_pphigs_frame_new(m, &rig->setup.frame, err) : NULL;
    gboolean ok = f != NULL;
    if (ok) {
        WlPphigsDist *d =
            distribute(db, ngp, a, wl_pphigs_frame_costs(f),
                       rig->setup.cluster_scale, rig->setup.strip_split);
        WlPphigsFrameStats st;
        ok = wl_pphigs_frame_run(f, d, scene_camera_view_proj(&db->camera),
                                 NULL, &st, err);
        if (ok)
            memcpy(us, st.gp_time_us, ngp * sizeof *us);
        wl_pphigs_dist_free(d);
    }
    wl_pphigs_frame_free(f);
    mach_free(m);
    sim_engine_free(eng);
    return ok;
}

static gboolean run_algo(const ScenePphigsDb *db, guint ngp, WlPphigsAlgo a,
                         const PphigsRig *rig, double t1,
                         WlPphigsMetrics *out, GError **err)
{
    double *us = g_new(double, ngp);
    gboolean ok = frame_times(db, ngp, a, rig, us, err);
    if (ok)
        wl_pphigs_metrics_from(t1, us, ngp, out);
    g_free(us);
    return ok;
}

gboolean pphigs_rig_run_db(const ScenePphigsDb *db, guint ngp,
                          const PphigsRig *rig, WlPphigsMetrics *simple,
                          WlPphigsMetrics *complex, GError **err)
{
    double t1 = 0;
    return frame_times(db, 1, WL_PPHIGS_SIMPLE, rig, &t1, err) &&
           run_algo(db, ngp, WL_PPHIGS_SIMPLE, rig, t1, simple, err) &&
           run_algo(db, ngp, WL_PPHIGS_COMPLEX, rig, t1, complex, err);
}

gboolean pphigs_rig_run_algo(const ScenePphigsDb *db, guint ngp,
                            WlPphigsAlgo a, const PphigsRig *rig,
                            WlPphigsMetrics *out, GError **err)
{
    double t1 = 0;
    return frame_times(db, 1, WL_PPHIGS_SIMPLE, rig, &t1, err) &&
           run_algo(db, ngp, a, rig, t1, out, err);
}

static void analytic_algo(const ScenePphigsDb *db, guint ngp, WlPphigsAlgo a,
                          const WlPphigsCosts *c, double cs, WlPphigsMetrics *m)
{
    WlPphigsDist *d = distribute(db, ngp, a, c, cs, 0);
    double *us = g_new(double, ngp);
    wl_pphigs_metrics(d, scene_camera_view_proj(&db->camera), c, us, m);
    g_free(us);
    wl_pphigs_dist_free(d);
}

void pphigs_rig_analytic(const ScenePphigsDb *db, guint ngp,
                               const WlPphigsCosts *c, double cluster_scale,
                               WlPphigsMetrics *simple,
                               WlPphigsMetrics *complex)
{
    analytic_algo(db, ngp, WL_PPHIGS_SIMPLE, c, cluster_scale, simple);
    analytic_algo(db, ngp, WL_PPHIGS_COMPLEX, c, cluster_scale, complex);
}

SimResult *pphigs_rig_run_flock(const char *const *sets, CfgRun **run)
{
    GError *err = NULL;
    *run = cfg_run_load("configs/pphigs-flock.yaml", sets, &err);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *r = *run ? cfg_run_exec(*run, &o, &err) : NULL;
    if (!r)
        fail_msg("%s", err->message);
    return r;
}
