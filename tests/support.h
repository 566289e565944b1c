/* support.h — set-up steps many test binaries share. */
#ifndef PGSIM_TESTS_SUPPORT_H
#define PGSIM_TESTS_SUPPORT_H

/* Makes a GLib warning or critical (an error set twice, a bad
 * argument) fail the test, as an error would. */
void support_warnings_fatal(void);
/* cmocka group set-up: models are looked up in tests/data/models. */
int support_test_models(void **state);

#endif
