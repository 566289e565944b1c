/* run.h — the runner: a run config checked from top to bottom, built
 * once (engine, machine, scene) and run (docs/architecture.md, "the path
 * of one run").  Everything that runs a workload comes through here:
 * `pgsim run`, `validate`, sweep points, reproductions, replay's
 * recording and the benches.
 *
 *     schema_version: 1                 # required, must be 1
 *     machine: {model: ipsc2, ...}      # optional; sim/machine checks it
 *     workload: {type: tokenring, ...}  # required; the workload parses it
 *     scene: {...}                      # optional; sim/scene checks it
 *     run: {seed: 1, frames: 1, fidelity: faithful, until: 10 ms}
 *
 * Loading applies --set overrides first, then reads every section with
 * its consumer: the workload parses its own and says (WlOps.plan) which
 * of `machine:` and `scene:` it reads; the runner builds those (the
 * machine on the run's engine at run.fidelity, with the workload's
 * machine overrides), refuses a present section the workload does not
 * read, and finally rejects any key nobody read (cfg_check_unused on the
 * whole tree).  run.until becomes the engine's horizon.  Every problem is a located error with exit status 2
 * (docs/config.md).  Machine models are looked up by the machine layer,
 * with the config's repository models/ directory and the install prefix's
 * share/pgsim/models as extra folders (CfgRun.model_dirs).
 */
#ifndef PGSIM_RUN_RUN_H
#define PGSIM_RUN_RUN_H

#include "sim/core/cfg.h"
#include "sim/core/record.h"
#include "sim/core/result.h"
#include "sim/workload/workload.h"

typedef struct {
    CfgNode *root;           /* owned: the tree after overrides */
    SimEngine *eng;          /* owned: seeded with `seed`, horizon `until` */
    MachMachine *machine_built; /* owned: the workload's machine; NULL when
                                   it reads none (WlPlan) */
    Scene *scene_built;      /* owned: the workload's scene; NULL when it
                                reads none */
    gboolean executed;       /* cfg_run_exec() ran (it runs once) */
    const CfgNode *machine;  /* borrowed from root; NULL when absent */
    const CfgNode *scene;    /* borrowed from root; NULL when absent */
    const CfgNode *workload; /* borrowed: the workload section */
    const WlOps *wl;
    void *wl_params;      /* owned (wl->free_params) */
    uint64_t seed;        /* run.seed, default 1 */
    int frames;           /* run.frames, default 1 */
    const char *fidelity; /* run.fidelity, default "faithful": the machine
                             model's network.fidelity (static) */
    SimTime until;        /* run.until; SIM_TIME_MAX when absent */
    char *path;           /* the config file as named; NULL for a tree */
    GPtrArray *model_dirs; /* char *, NULL-terminated: the extra model
                              folders (the config's repository models/,
                              the install prefix's) */
    char *sha256;         /* of the file's bytes; NULL for a tree */
    GPtrArray *overrides; /* char *: the overrides applied, in order */
    SimInputs *inputs;    /* owned: the files the load and the run read
                             (sim/core/inputs.h), for the provenance */
    GPtrArray *notes;     /* char *: what the runner tells the result
                             (node kinds played by others: roles.h) */
} CfgRun;

/* Loads and checks a run config; `overrides` is a NULL-terminated list of
 * "key.path=value" (may be NULL).  Returns a new CfgRun (cfg_run_free) or
 * NULL with *err set. */
CfgRun *cfg_run_load(const char *path, const char *const *overrides,
                     GError **err);
/* The same from a tree already loaded (takes ownership of root, also on
 * failure); overrides are applied first.  For sweeps. */
CfgRun *cfg_run_from_tree(CfgNode *root, const char *const *overrides,
                          GError **err);
/* The same two with more model folders (`models`, NULL-terminated,
 * borrowed; NULL: none) searched before the usual extra folders:
 * `pgsim reproduce --models DIR`. */
CfgRun *cfg_run_load_in(const char *path, const char *const *overrides,
                        const char *const *models, GError **err);
CfgRun *cfg_run_from_tree_in(CfgNode *root, const char *const *overrides,
                             const char *const *models, GError **err);
void cfg_run_free(CfgRun *run);

/* Options for one execution of a loaded config. */
typedef struct {
    const char *out_dir; /* passed to the workload; NULL: none */
    gboolean quiet;      /* no progress display */
    gboolean progress;   /* show progress (when stderr is a terminal) */
    SimTrace *trace;     /* attached to the engine; NULL: none (borrowed) */
    gboolean dry_run;    /* stop before the first event (sim_engine_set_dry_run):
                            NULL with SIM_ERROR_DRY_RUN means "would run" */
    gboolean all_frames; /* with out_dir: an image of every frame */
    SimRecorder *recorder; /* --record (sim/core/record.h); NULL: none */
    WlShare *share; /* what this run may share with the caller's other
                       runs (sim/workload/share.h); NULL: nothing */
} CfgRunOpts;

/* Runs the config's workload on the engine, machine and scene the load
 * built (once: a CfgRun runs one time) and returns a new result
 * (sim_result_free) with the engine figures and wall-clock time filled,
 * or NULL with *err set. */
SimResult *cfg_run_exec(CfgRun *run, const CfgRunOpts *opts,
                        GError **err);

#endif
