/* bench.h — `pgsim bench <name>`: benchmarks that print figures.
 *
 * Each sub-benchmark is `int bench_<name>_main(int argc, char **argv)`
 * (argv[0] is its name) listed in the table in cmd_bench.c; it prints
 * human-readable lines and, last, one `<figure>: <number>` line.
 */
#ifndef PGSIM_APP_BENCH_BENCH_H
#define PGSIM_APP_BENCH_BENCH_H

#include <glib.h>

int bench_phold_main(int argc, char **argv);
int bench_net_main(int argc, char **argv);    /* bench_net.c */
int bench_raster_main(int argc, char **argv); /* bench_raster.c */
int bench_composite_main(int argc, char **argv); /* bench_composite.c */

/* Parses GOption entries for a sub-benchmark (--help included). */
gboolean bench_parse_options(const char *name, const char *summary,
                             GOptionEntry *entries, int *argc, char ***argv,
                             GError **err);
/* Prints the error to stderr, frees it, returns its exit status. */
int bench_fail(GError *err);

#endif
