/* sorts.h — one scene, three sorts (issue 35, point 5): a comparison
 * file runs one scene on one machine under several workloads (sort-first,
 * sort-middle, sort-last) at several processor counts and collects, per
 * run, Molnar's overlap factor, the communication volume per frame, the
 * load balance and the frame time (docs/sorts.md).
 *
 *     three_sorts: 1
 *     name: three-sorts               # optional; default: the file's stem
 *     processors: [2, 4, 8, 16, 32]   # P, each run's worker processors
 *     machine: {model: cluster-ib}    # every run's machine section
 *     scene: {generator: ...}         # every run's scene
 *     run: {frames: 3, fidelity: analytic}
 *     sorts:
 *       - sort: sort-first            # the row's name in the table
 *         workload: {type: sortfirst, ...}
 *         scene: section              # section (default): the scene as
 *                                     # the run's scene:; database: its
 *                                     # structure database as a file,
 *                                     # the path in workload.database
 *         processors: {workload.processors: 1}  # key: share of P
 *         overlap: chunk_overlap      # the workload's metrics read
 *         bytes: migrated_bytes_per_frame
 *         frame: frame_ms             # default frame_ms
 *         balance: {node: 1}          # node kinds doing the work:
 *                                     # share of P of each
 *
 * A run's config is {schema_version: 1, machine, scene (section mode),
 * workload, run} with each `processors` key set to share x P (an
 * integer, else a located error).  balance: for each kind, the largest
 * per-processor busy time of that kind over the mean over share x P
 * processors (the workers; one that did nothing counts 0, the machine's
 * unused processors not at all); the sort's is the largest over its
 * kinds.  Every problem in the file is a located error (exit 2).
 */
#ifndef PGSIM_APP_SORTS_SORTS_H
#define PGSIM_APP_SORTS_SORTS_H

#include "sim/core/cfg.h"
#include "sim/core/result.h"
#include "sim/output/table.h"

typedef struct {
    char *sort;              /* the row's name */
    const CfgNode *workload; /* borrowed from the spec's tree */
    gboolean scene_as_db;    /* scene: database */
    GPtrArray *keys;         /* char *: keys set from P */
    GArray *shares;          /* double, one per key */
    char *overlap, *bytes, *frame; /* metric names */
    GPtrArray *balance;      /* char *: node kinds */
    GArray *bshares;         /* double, their shares of P */
} SortsSort;

typedef struct {
    CfgNode *root;    /* owned: the file */
    char *name;
    GArray *procs;    /* guint */
    const CfgNode *machine, *scene, *run; /* borrowed; NULL when absent */
    GPtrArray *sorts; /* SortsSort * */
} SortsSpec;

/* Reads and checks a comparison file after the overrides `sets`
 * ("key.path=value", NULL-terminated, may be NULL: `pgsim sorts --set`,
 * on the file's own keys: processors, machine.*, scene.*, run.*); NULL
 * with a located *err. */
SortsSpec *sorts_spec_load(const char *path, const char *const *sets,
                           GError **err);
void sorts_spec_free(SortsSpec *s);

/* The largest per-processor busy time of r's processors of `kind` over
 * the mean over n of them (processors that did nothing count 0); NAN when
 * none was busy or more than n were. */
double sorts_kind_balance(const SimResult *r, const char *kind, guint n);

/* Runs every sort at every P (sorts outer, P inner) and returns the
 * table sort, processors, overlap, bytes, balance, frame_ms (dt_free),
 * or NULL with *err.  Files the runs need (a scene's database) go to
 * out_dir, which must exist. */
DataTable *sorts_run(const SortsSpec *s, const char *out_dir, GError **err);

/* Writes the charts frame_ms and bytes against processors, one line a
 * sort, into out_dir (plot_render). */
gboolean sorts_charts(const SortsSpec *s, const DataTable *t,
                      const char *out_dir, GError **err);

#endif
