/* sf_testutil.h — running the `sortfirst` workload from a config text in
 * the sort-first tests (shared by test_sortfirst.c, test_sf_trav.c and
 * test_sf_edit.c). */
#ifndef PGSIM_TESTS_SF_TESTUTIL_H
#define PGSIM_TESTS_SF_TESTUTIL_H

#include "sim/workload/sortfirst/sf_workload.h"

/* A small vehicle (40 structures, 3,000 triangles, 3 instances) on 4
 * processors, chunks of 5, 64 x 64, max-set. */
#define SF_TEST_SMALL                                                      \
    "machine: {model: cluster-ib}\n"                                       \
    "workload: {type: sortfirst, processors: 4, granularity: 5,\n"         \
    "           resolution: 64, bookkeeping: maxset}\n"                    \
    "scene: {generator: vehicle, structures: 40, triangles: 3000,\n"       \
    "        instances: 3, circle_radius: 6, camera_radius: 15,\n"         \
    "        camera_height: 5, fov: 30, degrees_per_frame: 12}\n"

/* A run of SF_TEST_SMALL's scene on cluster-ib (analytic), checking
 * every frame's image, with an editor of `spec` set. */
typedef struct {
    CfgNode *root;
    Scene *scene;
    SimEngine *eng;
    MachMachine *m;
    WlSfDb *db;
    WlSfRun *run;
    WlSfEdit *edit;
    WlSfCosts c;
} SfEditFixture;

void sf_test_edit_init(SfEditFixture *f, WlSfBookkeeping bk,
                       const WlSfEditSpec *spec);
void sf_test_edit_clear(SfEditFixture *f);

/* Runs `text` with the NULL-terminated overrides (may be NULL) for
 * `frames` frames, seed 1, analytic; frames to out_dir (NULL: none),
 * every frame when `all`.  A new result, or NULL with *err set.  Fails
 * the test on an unreadable config or override.  Through the runner
 * (tests/support.h). */
SimResult *sf_test_run(const char *text, const char *const *overrides,
                       int frames, const char *out_dir, gboolean all,
                       GError **err);
/* `text` for `frames` frames with the overrides key_a=val_a and
 * key_b=val_b (printf'd); fails the test on an error or an image that
 * differs from the serial render. */
SimResult *sf_test_run_checked(const char *text, int frames,
                               const char *key_a, const char *val_a,
                               const char *key_b, const char *val_b);
/* Metric `name` of r; fails the test when absent. */
double sf_test_metric(const SimResult *r, const char *name);

/* One posted structure of 3 triangles in chunks of at most 2, dealt over
 * `procs`: chunk 0 (2 triangles) mastered by 0, chunk 1 (1) by 1 % procs,
 * one instance each.  *src gets the structure database (free both). */
WlSfDb *sf_test_tiny_db(SceneDb **src, guint procs);

/* Five right triangles at z = 0 posted by one structure, in the order
 * (world boxes) [-0.75, -0.25] x [0.25, 0.75], [0.25, 0.75] x [0.25,
 * 0.75], [-0.25, 0.25]^2, [3, 3.5] x [0, 0.5], [3, 3.5] x [-1, -0.5]:
 * under an orthographic camera of height 2 on a 16 x 16 screen, one in
 * each top tile of a 2 x 2 split, one across all four, two off. */
SceneDb *sf_test_hand_db(void);
#endif
