/* rp_ellsworth90.c — `pgsim reproduce ellsworth90`: seed 001's table
 * (§6) for the four generated databases at 4 and 16 GPs, from
 * event-driven Pixel-Planes 5 frames (ellsworth90.h).  Reads the
 * generator parameters, the cost model and the frame sizes through cfg;
 * the published values are joined by the driver, never read here.
 */
#include "sim/workload/pphigs/ellsworth90.h"

#define DB_FILE "configs/pphigs/databases.yaml"
#define MODEL_FILE "models/pixel-planes-5.yaml"
#define FRAME_FILE "configs/pphigs/frame.yaml"

static const char *const db_names[] = {"space_station", "building_lobby",
                                       "flock_old_well",
                                       "two_human_figures"};

static gboolean load_hw(const RpContext *ctx, WlPphigsHw *hw, GError **err)
{
    CfgNode *fr = cfg_load_file(FRAME_FILE, err);
    if (!fr)
        return FALSE;
    gboolean ok = wl_pphigs_hw_load(MODEL_FILE, fr, hw, err) &&
                  cfg_check_unused(fr, err);
    cfg_free(fr);
    hw->fidelity = NET_ANALYTIC;
    if (ok && ctx->fidelity &&
        !net_fidelity_parse(ctx->fidelity, &hw->fidelity)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "--fidelity: found '%s', expected analytic, flow or "
                    "packet", ctx->fidelity);
        ok = FALSE;
    }
    return ok;
}

static gboolean rp_run(const RpContext *ctx, GPtrArray *rows, GError **err)
{
    WlPphigsHw hw;
    if (!load_hw(ctx, &hw, err))
        return FALSE;
    ScenePphigsSpec specs[G_N_ELEMENTS(db_names)];
    for (guint i = 0; i < G_N_ELEMENTS(db_names); i++)
        if (!wl_pphigs_spec_load(DB_FILE, db_names[i], &specs[i], err))
            return FALSE;
    return wl_pphigs_table1(specs, G_N_ELEMENTS(db_names), &hw.costs,
                            hw.cluster_scale, &hw, rows, err);
}

const RpReproduction wl_pphigs_ellsworth90 = {
    .name = "ellsworth90",
    .summary = "Ellsworth, Good, Tebbs 1990: distributing display lists "
               "(PPHIGS on Pixel-Planes 5), 4 and 16 GPs",
    .run = rp_run,
};
