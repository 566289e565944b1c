/* support.h — set-up steps many test binaries share. */
#ifndef PGSIM_TESTS_SUPPORT_H
#define PGSIM_TESTS_SUPPORT_H

#include "sim/core/cfg.h"
#include "sim/core/result.h"
#include "sim/core/engine.h"
#include "sim/scene/camera.h"

/* Makes a GLib warning or critical (an error set twice, a bad
 * argument) fail the test, as an error would. */
void support_warnings_fatal(void);
/* cmocka group set-up: models are looked up in tests/data/models. */
int support_test_models(void **state);
/* Every field of two cameras equal, bit for bit.  Not memcmp: the
 * padding after `proj` is indeterminate, and differs between an -O0 and
 * an -O2 build of the same test. */
int support_camera_equal(const SceneCamera *a, const SceneCamera *b);
/* Removes a file, or a folder and everything in it (test scratch). */
void support_rm_tree(const char *path);
/* How many entries a folder holds (0 when it cannot be read). */
int support_entries(const char *dir);

/* A test run through the runner (sim/run/run.h), as `pgsim run` makes
 * it.  Zero fields keep the config's own settings. */
typedef struct {
    const char *fidelity;         /* run.fidelity */
    int frames;                   /* run.frames */
    uint64_t seed;                /* run.seed */
    const char *out_dir;          /* pgsim run --out */
    gboolean all_frames;          /* --frames all */
    const char *const *overrides; /* --set, NULL-terminated; may be NULL */
    SimTrace *trace;  /* attached to the engine (borrowed); NULL: none */
    gboolean dry_run; /* pgsim validate: NULL with SIM_ERROR_DRY_RUN */
    SimTime *now;     /* when set: receives the engine's clock after
                         the run (also after a failed one) */
} SupportRun;
/* Loads, builds and runs a config (root is taken; schema_version: 1 is
 * added when missing): a new result, or NULL with *err set. */
SimResult *support_run_tree(CfgNode *root, const SupportRun *o, GError **err);
/* The same from YAML text (named "test.yaml" in errors). */
SimResult *support_run_text(const char *yaml, const SupportRun *o,
                            GError **err);
/* Metric `name` of r; fails the test when r has none. */
double support_metric(const SimResult *r, const char *name);

#endif
