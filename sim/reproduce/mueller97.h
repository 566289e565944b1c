/* mueller97.h — `pgsim reproduce mueller97`: seed 000's Charts 1-5
 * (Mueller, "Hierarchical graphics databases in sort-first", §4) from
 * the sortfirst workload on the vehicle database, and the claims of
 * §4.2 as computed rows.
 *
 * Tables (rows "P<p>/g<n>" unless said; every figure a mean over the
 * frames after the first of the run, as the paper averaged "across the
 * frames in the animation"):
 *   "1"  Chart 1, chunking strategies at one P and bookkeeping: rows
 *        "<strategy>/g<n>", columns box_region_ratio, chunk_overlap;
 *   "2"  Chart 2, communication: bytes_minset, bytes_maxset per frame;
 *   "3"  Chart 3, chunk overlap: chunk_overlap, box_region_ratio;
 *   "4"  Chart 4, min-set transformations: transforms, master_boxes,
 *        slave_boxes, new_boxes, polygons;
 *   "5"  Chart 5, the same for max-set;
 *   "instancing"  rows "<database>/<bookkeeping>": the instancing
 *        trade-off of §5 on databases with no, moderate and heavy
 *        instancing (mueller97_inst.c; setup.yaml's `instancing`);
 *   "claims"  one row per claim of §4.2, §3.3.2.2 and §5
 *        (mueller97_claims.c, C8 mueller97_inst.c; the pull cases,
 *        min-set at setup.yaml's `pull`, feed only C7).
 * The paper's charts carry no numbers in the seed's text, so
 * configs/papers/mueller97/published.yaml lists captions only and every
 * row is printed as a prediction.  With an output directory the hook
 * draws the five charts (mueller97-chart<k>.{png,svg,gp,dat}).
 */
#ifndef PGSIM_REPRODUCE_MUELLER97_H
#define PGSIM_REPRODUCE_MUELLER97_H

#include "sim/core/cfg.h"
#include "sim/reproduce/reproduce.h"

/* Chunking strategies (§4.1), named as the workload's `chunking` key. */
typedef enum { RP_MU_SORTED, RP_MU_UNSORTED, RP_MU_PARTIAL } RpMuChunking;
/* "sorted", "unsorted", "partially_sorted", NULL */
extern const char *const rp_mu_chunking_names[];

/* One simulated case, the figures the charts and claims read. */
typedef struct {
    guint procs, granularity;
    gboolean minset; /* bookkeeping: min-set (else max-set) */
    RpMuChunking chunking;
    guint instances; /* max-set instances of the database's root */
    double bytes, overlap, ratio; /* per frame; overlap; box / region */
    double master, slave, fresh, polys, transforms; /* per frame */
    gboolean pull;        /* migration: pull (§3.3.2.2; min-set) */
    double messages;      /* per frame */
    double requests;      /* pull: chunks requested per frame, else 0 */
    double memory;        /* peak_memory: the largest processor store */
    double frame_ms;
    double interrupt_ms;  /* pull: masters' request interrupts a frame */
} RpMuellerPoint;

/* The instancing trade-off (mueller97_inst.c): one database and
 * bookkeeping. */
typedef struct {
    char db[32];      /* the scene.instancing level, or "file" */
    gboolean minset;
    double per_chunk; /* chunk instances per chunk */
    double copies, messages, bytes, transforms, memory, frame_ms;
} RpMuInstPoint;
typedef struct RpMuInst RpMuInst;

extern const RpPaperOps rp_mueller97;

/* setup.yaml's optional `instancing` map into *out (NULL when absent);
 * FALSE with *err on a bad map.  Free with rp_mu_inst_free(). */
gboolean rp_mu_inst_load(const CfgNode *root, RpMuInst **out, GError **err);
void rp_mu_inst_free(RpMuInst *in);
/* Runs every database of `in` with min-set and max-set on `cell` (a
 * sortfirst config without scene), appending RpMuInstPoint to pts. */
gboolean rp_mu_inst_run(const RpContext *ctx, const CfgNode *cell,
                        const RpMuInst *in, GArray *pts, GError **err);
/* Table "instancing" and claim C8 (min-set without instancing, max-set
 * with it) from the points. */
void rp_mueller97_claims_instancing(const RpMuInstPoint *p, guint n,
                                    GPtrArray *rows);

/* Appends the claim rows (table "claims") computed from the points
 * (push cases only). */
void rp_mueller97_claims(const RpMuellerPoint *pts, guint n, GPtrArray *rows);
/* Appends the row of "push beats pull" (§3.3.2.2): each pull case
 * against the push case of its P and chunk size in pts. */
void rp_mueller97_claims_pull(const RpMuellerPoint *pts, guint n,
                              const RpMuellerPoint *pull, guint n_pull,
                              GPtrArray *rows);
/* Spearman's rank correlation of x and y (ties averaged); NaN when
 * either is constant. */
double rp_mueller97_spearman(const double *x, const double *y, guint n);
/* Draws Charts 1-5 from the points into dir (errors are reported on
 * stderr and leave the chart out). */
void rp_mueller97_charts(const RpMuellerPoint *pts, guint n,
                         guint chart1_procs, const char *dir);

#endif
