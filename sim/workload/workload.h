/* workload.h — the workload plug-in contract.
 *
 * A workload is a small ops table.  The runner (sim/run/run.h) loads the
 * config, finds the workload named by `workload.type`, lets it parse its
 * own section, asks it which other sections it reads (plan()), builds
 * the engine, the machine and the scene once, refuses every section the
 * workload does not read, and calls run() with the built objects in a
 * WlContext.  A workload states its work on the machine's processors
 * and network; the engine's clock is the only clock, and the runner's
 * stop time (run.until) is the engine's horizon, so a workload honours
 * it by ending its frame loop when sim_engine_cut() says so.
 */
#ifndef PGSIM_WORKLOAD_WORKLOAD_H
#define PGSIM_WORKLOAD_WORKLOAD_H

#include "sim/core/cfg.h"
#include "sim/core/engine.h"
#include "sim/core/result.h"
#include "sim/machine/costs.h"
#include "sim/machine/machine.h"
#include "sim/raster/image.h"
#include "sim/scene/scene.h"
#include "sim/workload/share.h"

typedef struct {
    SimEngine *eng;      /* fresh engine seeded with `seed`; borrowed */
    const CfgNode *root; /* whole config (machine, scene ...); borrowed */
    MachMachine *machine; /* built by the runner (WL_READS_MACHINE), on
                             eng at `fidelity`; else NULL; borrowed */
    Scene *scene;         /* built from `scene:` (WL_READS_SCENE); else
                             NULL; borrowed: the workload may edit it (a
                             run uses it once) */
    SimTime until;        /* run.until (also eng's horizon); SIM_TIME_MAX:
                             none */
    uint64_t seed;
    const char *fidelity; /* "analytic", "flow" or "packet" */
    int frames;           /* frames to simulate (>= 1) */
    const char *out_dir;  /* where images etc. may go; NULL: none */
    gboolean quiet;       /* no progress output */
    gboolean all_frames;  /* with out_dir: an image of every frame */
    WlShare *share;       /* what consecutive runs may share (share.h);
                             NULL: nothing; borrowed */
} WlContext;

/* Frame images (pgsim run --out DIR): a workload that renders a picture
 * asks wl_wants_frame() after each frame and, if TRUE, hands the image
 * to wl_emit_frame(), which writes DIR/frame.png for the last frame, or
 * DIR/frame-NNNN.png for every frame with --frames all.  No output
 * directory: wl_wants_frame() is FALSE and nothing is built. */
gboolean wl_wants_frame(const WlContext *ctx, int frame);
gboolean wl_emit_frame(const WlContext *ctx, int frame, const RastImage *img,
                       GError **err);
/* Frame boundaries in the trace (docs/traces.md): an instant "frame N"
 * at the simulated time frame N ended.  No trace: nothing. */
void wl_mark_frame(SimEngine *eng, guint frame, SimTime end);

/* Costs a workload asks a machine model for: operation names under
 * nodes.<kind>.costs, declared once; the machine fills them, with their
 * provenance, through mach_costs_new() (sim/machine/costs.h). */
typedef MachNeed WlNeed;

/* The costs of one mode of a workload ("with pn:, on Pixel-Planes 5"). */
typedef struct {
    const char *when;
    const WlNeed *needs; /* ended by a NULL kind */
} WlNeedAlt;

/* A metric a workload puts in its SimResult: the name, the unit exactly
 * as passed to sim_result_set_metric ("" when dimensionless) and what it
 * means, in one line.  Tables end with a NULL name (sim/workload/metrics.h
 * checks results and reads metrics against them). */
typedef struct {
    const char *name;
    const char *unit;
    const char *meaning;
} WlMetric;

/* The sections of a run config a workload reads besides its own. */
enum {
    WL_READS_MACHINE = 1u << 0, /* the runner builds ctx->machine */
    WL_READS_SCENE = 1u << 1,   /* the runner builds ctx->scene */
};

/* What the runner builds for one parsed workload (WlOps.plan). */
typedef struct {
    unsigned reads;            /* WL_READS_* */
    const char *default_model; /* the model when the config has no
                                  machine: section; NULL: one is needed */
    /* "key.path=value" overrides of the machine section that workload
     * keys stand for (pphigs `gps: 16` is nodes.gp.count=16), applied
     * after the config's own; the runner owns and frees them. */
    GPtrArray *machine_set;
} WlPlan;

typedef struct {
    const char *name;
    const char *summary;
    /* Parses the `workload` section (type already read); returns params or
     * NULL with *err set. */
    void *(*parse)(const CfgNode *section, GError **err);
    void (*free_params)(void *params);
    /* Fills `plan` (zeroed, machine_set an empty array) for parsed params:
     * which sections the runner builds, and refuses when present and
     * unread.  NULL: the workload reads no section but its own. */
    void (*plan)(const void *params, WlPlan *plan);
    /* Optional, with WL_READS_MACHINE: once the model is known, the
     * machine overrides that depend on it (dpscan's `processors` are a
     * SIMD array's lanes or an SPMD machine's nodes).  `given` is the
     * config's machine: section (NULL: the plan's default model), `model`
     * that section merged over its model and checked (model.h); both
     * borrowed.
     * Appends "key.path=value" strings (g_free) to machine_set, or
     * returns FALSE with a located *err (a machine it cannot run on). */
    gboolean (*plan_machine)(const void *params, const CfgNode *given,
                             const CfgNode *model, GPtrArray *machine_set,
                             GError **err);
    /* Runs the workload and fills `out`; FALSE with *err on failure.
     * The runner (cfg_run_exec) fills seed, fidelity, events, wall time
     * and, if left 0, elapsed: workloads need not. */
    gboolean (*run)(const WlContext *ctx, void *params, SimResult *out,
                    GError **err);
    /* The machine costs run() looks up, per node kind, ended by a NULL
     * kind; NULL when it needs no machine.  `pgsim help run` lists them,
     * so a new model can be written against them (test_workload checks
     * a shipped config's model has them). */
    const WlNeed *needs;
    /* Optional: the costs of its other modes, or model keys it reads
     * outside nodes.KIND.costs, each set under a heading (`when`); ended
     * by when == NULL.  `pgsim help run` lists them after `needs`. */
    const WlNeedAlt *needs_alt;
    /* Optional: the bytes run() will allocate for the workload's own state
     * (frame buffers, per-processor tables, geometry it generates),
     * estimated from the parsed params alone; appends to `what` the sizes
     * it used ("64 processors, 4096 x 4096 pixels").  The config loader
     * (cfg_run_from_tree: validate, run and every sweep point) refuses a
     * config whose estimate exceeds sim_mem_limit() before run()
     * allocates anything.  NULL: nothing beyond the scene, image and
     * event pool, which their owners check. */
    double (*mem_bytes)(const void *params, GString *what);
    /* Every metric run() may set, in the order it sets them, ended by a
     * NULL name.  The runner refuses a result holding any other
     * (wl_check_metrics), papers read metrics through it (wl_metric) and
     * `pgsim help run` lists it. */
    const WlMetric *metrics;
} WlOps;

/* The per-frame log's path: `path` (a workload's frame_log key) when
 * set, else <out_dir>/<name> under `pgsim run --out DIR`, else NULL (no
 * log).  A new string (g_free). */
char *wl_frame_log_path(const WlContext *ctx, const char *path,
                        const char *name);
/* Writes `text` to path; FALSE with "<workload>: found an unwritable
 * frame_log ..." in *err. */
gboolean wl_frame_log_write(const char *path, const GString *text,
                            const char *workload, GError **err);

/* WlOps.plan of a workload that always reads the machine and the scene
 * (pixelmerge, sortfirst, argus). */
void wl_plan_machine_scene(const void *params, WlPlan *plan);

/* Looks a workload up by name; NULL if unknown. */
const WlOps *wl_find(const char *name);
/* NULL-terminated list of every workload, for help and errors. */
extern const WlOps *const wl_all[];

#endif
