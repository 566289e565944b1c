/* support.h — set-up steps many test binaries share. */
#ifndef PGSIM_TESTS_SUPPORT_H
#define PGSIM_TESTS_SUPPORT_H

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

#endif
