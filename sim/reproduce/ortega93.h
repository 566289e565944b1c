/* ortega93.h — `pgsim reproduce ortega93`: seed 004's Tables 1-4.
 *
 * Ortega, Hansen and Ahrens, "Fast data parallel polygon rendering"
 * (LA-UR 93-3173; Supercomputing '93): times and polygons per second of
 * a small-polygon and a large-polygon data set on CM-200 partitions of
 * 16K-64K processors (Tables 1, 2: visible) and CM-5 partitions of
 * 32-512 nodes (Tables 3, 4: withheld, predicted from the CM-5 model).
 *
 * The sweep is declared in configs/papers/ortega93/setup.yaml (ctx->setup) (scenes,
 * resolutions, partitions, machine per table); machine constants come
 * from the `dpscan:` sections of models/<machine>.yaml.  Rows are
 * "<partition>/<width>x<height>" (e.g. "16K/1280x1024", "512/640x480");
 * columns `time_s` (frame time, seconds) and `polygons_per_s` (polygons
 * in the data set / frame time), as the paper's two halves of a table.
 * Each table at each resolution is one run of workload dpscan through
 * the runner (sim/run/run.h) on its machine model, the one render costed
 * on every partition of the table (workload.partitions; metrics
 * time_s@P, polygons); a CM-200 table is run again with
 * machine.dpscan.send_slice=0 us for table "cv".  Table "text" holds the two
 * sentences of §6 (the fastest small-polygon rate of the 64K CM-200 and
 * of the 512-node CM-5); table "claims" decides §6's other sentences
 * from the simulated cells; table "cv" gives the CM-200 fit's in-sample
 * and leave-one-out errors.  With --out, Figures 3 and 4 as charts.
 *
 * Setting PGSIM_DP_COEF=<file> also writes the linear coefficients of
 * every SIMD cell (dp_cost.h) as CSV, for scripts/fit-ortega93.py.
 */
#ifndef PGSIM_REPRODUCE_ORTEGA93_H
#define PGSIM_REPRODUCE_ORTEGA93_H

#include "sim/reproduce/reproduce.h"

extern const RpPaperOps rp_ortega93;

/* Figures 3 and 4 (speed-up charts) from the rows into dir
 * (ortega93_plot.c); a chart that cannot be drawn is reported on
 * stderr, not an error. */
void rp_ortega93_charts(GPtrArray *rows, const char *dir);

/* The three other sentences of §6 as computed rows of table "claims"
 * (ortega93_claims.c: over 600,000 on the 64K CM-200; large polygons an
 * order of magnitude slower; the large set's worse speed-up), appended
 * to rows from the simulated cells already in it. */
void rp_ortega93_claims(GPtrArray *rows);

/* One CM-200 time cell as a line in send_slice s (ortega93_cv.c): the
 * simulated time is a + s * b exactly, a the cell's time in a run with
 * send_slice overridden to 0; pub its published time (filled by
 * rp_ortega93_cv). */
typedef struct {
    char table[8], row[48];
    double a, b, s, pub;
} RpOrCell;

/* Table "cv": the in-sample and leave-one-out error of the CM-200's
 * fitted send_slice over the cells (published times joined from
 * configs/papers/ortega93/published.yaml); FALSE with *err if a cell
 * has no published time. */
gboolean rp_ortega93_cv(GArray *cells, GPtrArray *rows, GError **err);

#endif
