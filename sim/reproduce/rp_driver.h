/* rp_driver.h — running reproductions and collecting their tables.
 *
 * rp_drive() runs one RpPaperOps at one fidelity on its setup
 * (<papers_dir>/<name>/setup.yaml unless ctx->setup names another),
 * times it, reads the paper's published values from
 * <papers_dir>/<name>/published.yaml and returns the joined table.  rp_drive_fidelities() does it once per network fidelity
 * (analytic, flow, packet) for `--fidelity all`.  At "faithful" the
 * table's fidelity reads "faithful: <what the paper noted>" (e.g.
 * "faithful: ipsc2 packet"), from rp_note_fidelity().
 */
#ifndef PGSIM_REPRODUCE_RP_DRIVER_H
#define PGSIM_REPRODUCE_RP_DRIVER_H

#include "sim/reproduce/rp_table.h"
#include "sim/run/run.h"

#define RP_PAPERS_DIR "configs/papers"
/* Each machine at the transport its model names (machine.h). */
#define RP_DEFAULT_FIDELITY "faithful"

/* The fidelities in order, coarse to fine; NULL-terminated (the passes
 * of --fidelity all). */
extern const char *const rp_fidelities[];
/* One of rp_fidelities or "faithful". */
gboolean rp_fidelity_valid(const char *f);

/* Runs rp with ctx (ctx->fidelity set) and joins; returns a new table
 * (free with rp_table_free()) or NULL with *err set. */
RpTable *rp_drive(const RpPaperOps *rp, const char *papers_dir,
                  const RpContext *ctx, GError **err);

/* Runs rp at every fidelity; returns a new array of RpTable * (one per
 * entry of rp_fidelities, array frees them) or NULL with *err set. */
GPtrArray *rp_drive_fidelities(const RpPaperOps *rp, const char *papers_dir,
                               const RpContext *ctx, GError **err);

/* A paper's run through the runner: tree (taken) or, when it is NULL,
 * the config file `path`, with the paper's overrides `sets`
 * (NULL-terminated; may be NULL) and then run.fidelity (ctx->fidelity;
 * "analytic" when it has none) and run.seed=RP_SEED, and last the user's
 * what-if ctx->sets (`reproduce --set`), with ctx->models as extra model
 * folders (cfg_run_from_tree_in).  A new run (cfg_run_free), or NULL
 * with *err. */
CfgRun *rp_run_build(const RpContext *ctx, CfgNode *tree, const char *path,
                     const char *const *sets, GError **err);
/* The same for a tree whose run: section the paper sets itself: no
 * run.fidelity or run.seed added. */
CfgRun *rp_run_build_as_is(const RpContext *ctx, CfgNode *tree,
                           const char *const *sets, GError **err);
/* The `set: [key=value, ...]` list of map `m` (absent: none) as a
 * NULL-terminated vector for rp_run_build (g_strfreev), or NULL with a
 * located *err (a non-list, a non-scalar entry). */
char **rp_sets_of(const CfgNode *m, GError **err);
/* Executes r quietly with share (may be NULL) and notes the transport of
 * its machine (rp_note_fidelity: the config's machine.model, else the
 * model's name).  A new result, or NULL with *err. */
SimResult *rp_run_exec(const RpContext *ctx, CfgRun *r, WlShare *share,
                       GError **err);

#endif
