/* rp_ellsworth90.c — `pgsim reproduce ellsworth90`: seed 001's table
 * (§6) for the four generated databases at 4 and 16 GPs, from
 * event-driven frames on Pixel-Planes 5 machines built by the machine
 * layer (ellsworth90.h).  Reads the generator parameters and the frame
 * sizes through cfg and the model by name (models/pixel-planes-5.yaml);
 * the published values are joined by the driver, never read here.
 */
#include "sim/workload/pphigs/ellsworth90.h"

#define DB_FILE "configs/pphigs/databases.yaml"
#define SETUP_FILE "configs/pphigs/frame.yaml"
#define MODEL "pixel-planes-5"

static const char *const db_names[] = {"space_station", "building_lobby",
                                       "flock_old_well", "two_human_figures"};

static gboolean rp_run(const RpContext *ctx, GPtrArray *rows, GError **err)
{
    WlPphigsRig rig = {
        MODEL, ctx->fidelity ? ctx->fidelity : "analytic", {{0}, 0}};
    if (!wl_pphigs_setup_load(SETUP_FILE, &rig.setup, err))
        return FALSE;
    ScenePphigsSpec specs[G_N_ELEMENTS(db_names)];
    for (guint i = 0; i < G_N_ELEMENTS(db_names); i++)
        if (!wl_pphigs_spec_load(DB_FILE, db_names[i], NULL, &specs[i], err))
            return FALSE;
    return wl_pphigs_table1(specs, G_N_ELEMENTS(db_names), &rig, rows, err);
}

const RpReproduction wl_pphigs_ellsworth90 = {
    .name = "ellsworth90",
    .summary = "Ellsworth, Good, Tebbs 1990: distributing display lists "
               "(PPHIGS on Pixel-Planes 5), 4 and 16 GPs",
    .run = rp_run,
};
