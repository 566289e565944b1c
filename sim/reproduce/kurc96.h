/* kurc96.h — `pgsim reproduce kurc96` (seed 003, kurc96.c) and its
 * charts (kurc96_plot.c): Figs. 1 and 2 drawn from the simulated
 * points through sim/output/plot.h.
 */
#ifndef PGSIM_REPRODUCE_KURC96_H
#define PGSIM_REPRODUCE_KURC96_H

#include "sim/reproduce/reproduce.h"

extern const RpPaperOps rp_kurc96;

/* Scene row keys in the paper's order, NULL-terminated. */
extern const char *const rp_kurc96_scenes[];

/* What one simulated run contributes to the tables. */
typedef struct {
    double span_ms, zbuf_ms, merge_ms, volume, imbalance, speedup;
    double polygons, tpg, tpf;
    double memory, node_memory; /* bytes per node: estimate, machine's */
    double mem_part[5]; /* base, polygons, spans, z-buffer/WPA, buffers */
} RpKurcRun;

/* Node-cost groups fitted on Table 2 (scripts/kurc96/fit.py): polygon,
 * span, insert_step, pixel, zbuf_init, compare, scatter = gather. */
#define RP_KURC_GROUPS 7

/* One run of the paper: scene row key (rp_kurc96_scenes), N, P and the
 * workload's scheme ("pair", "aapc", "zbuf_exc") and balance ("strips",
 * "rs", "hbp"). */
typedef struct {
    const char *scene;
    guint resolution, procs;
    const char *scheme, *balance;
} RpKurcSpec;

/* Runs sp once on the setup ctx->setup at ctx->fidelity, through the
 * runner, into *run; scale (NULL: none) multiplies the model's node costs
 * of the fitted groups (RP_KURC_GROUPS factors), given to the machine as
 * overrides of machine.nodes.node.costs.  FALSE with *err on failure. */
gboolean rp_kurc96_simulate(const RpContext *ctx, const RpKurcSpec *sp,
                            const double *scale, RpKurcRun *run, GError **err);
/* The memory verdict of a run, "* out of memory: 4.21 of 4.00 MiB (base
 * ..., z-buffer/WPA ..., message buffers ...)" or "fits: ...";
 * g_free(). */
char *rp_kurc96_memory_note(const RpKurcRun *r);

/* The linearised cells of the fit (kurc96_cv.c): cell i of scene
 * scene[i] has published value pub[i], simulated sim[i] at the model's
 * costs and jac[i * groups + j] = d sim / d (relative change of group j). */
typedef struct {
    int n, groups, scenes;
    const int *scene;
    const double *pub, *sim, *jac;
} RpKurcCv;

/* Leave-one-scene-out predictions of every cell into loso[n]. */
void rp_kurc96_cv_run(const RpKurcCv *cv, double *loso);
/* Cell i at relative cost changes x[groups]. */
double rp_kurc96_cv_predict(const RpKurcCv *cv, int i, const double *x);
/* Mean and largest |v / pub - 1| over the cells. */
void rp_kurc96_cv_errors(const RpKurcCv *cv, const double *v, double *mean,
                         double *worst);

/* One point of Figs. 1-2: volumes of PAIR-RS, PAIR-HBP, AAPC-RS,
 * AAPC-HBP (bytes) and the RS, HBP imbalances of AAPC. */
typedef struct {
    char *label; /* the row key, "a/P4" or "b/2POT/640" */
    guint procs;
    double volume[4];
    double imbalance[2];
} RpKurcPoint;

typedef struct {
    RpKurcPoint a[4];  /* 2POT, N=400, P = 2, 4, 8, 16 */
    RpKurcPoint b[12]; /* every scene at N=400 and 640, P=16 */
    guint n_a, n_b;
} RpKurcFigs;

void rp_kurc96_figs_clear(RpKurcFigs *f);
/* The paper's statements about Table 2, Figs. 1-2 and the recommended
 * scheme, computed from f and the Table 2 rows, appended to rows as
 * table "claims" (kurc96_claims.c). */
void rp_kurc96_claims(const RpKurcFigs *f, GPtrArray *rows);

/* Writes kurc96-fig1a/1b/2a/2b.{dat,gp,png,svg} into dir through gnuplot;
 * a chart that cannot be drawn prints a warning and is skipped (the
 * rows are the result, charts a convenience). */
void rp_kurc96_charts(const RpKurcFigs *f, const char *dir,
                      const char *fidelity);

#endif
