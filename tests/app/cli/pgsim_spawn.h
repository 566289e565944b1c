/* pgsim_spawn.h — tests that run the built binary (build/pgsim, or
 * build-san/pgsim under PGSIM_SANITIZE) and look at what it printed. */
#ifndef PGSIM_TESTS_APP_CLI_PGSIM_SPAWN_H
#define PGSIM_TESTS_APP_CLI_PGSIM_SPAWN_H

/* Path of the binary under test. */
const char *test_pgsim_bin(void);
/* Runs pgsim with the NULL-terminated args; returns the exit status (-1
 * when it did not exit) and sets *out and *err to its output (g_free). */
int test_pgsim(const char *const *args, char **out, char **err);
/* Writes dir/ring.yaml (a 2-frame token ring) and dir/s.yaml, a sweep
 * named s over it with workload.nodes taking `values` (YAML list items,
 * "4, 8"); returns the sweep's path (g_free). */
char *test_ring_sweep(const char *dir, const char *values);

/* The text of file `path` between the lines `begin` and `end` (each
 * with its newline); fails the test when either is missing (g_free). */
char *test_doc_between(const char *path, const char *begin, const char *end);

#endif
