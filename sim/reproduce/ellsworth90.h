/* ellsworth90.h — `pgsim reproduce ellsworth90`: seed 001's table for
 * the four generated databases at the setup's GP counts (4 and 16).
 *
 * Rows (table "1"): one per database; columns simple_eff_P,
 * complex_eff_P, util_P, speedup_P for each P (efficiency and
 * utilisation in percent, of the complex algorithm for util and
 * speedup); by_structure_eff_P, by_structure_util_P and
 * by_structure_speedup_P are pgsim's own (§2.1's rejected
 * distribute-by-structure; the paper prints no such cells).  Table "db": the generated databases' depth, structures,
 * polys_per_structure, poly_attr_ratio, offscreen_pct.  Table "claims"
 * (ellsworth90_claims.c): §2.2's cube, §5.2's mesh and the abstract's
 * one million polygons per second, each with the figures it is decided
 * on and `holds`.
 */
#ifndef PGSIM_REPRODUCE_ELLSWORTH90_H
#define PGSIM_REPRODUCE_ELLSWORTH90_H

#include "sim/core/cfg.h"
#include "sim/core/result.h"
#include "sim/reproduce/reproduce.h"
#include "sim/scene/structdb.h"

/* What every cell runs (all borrowed). */
typedef struct {
    const CfgNode *cell;     /* a pphigs run config (setup.yaml's `cell`) */
    const char *fidelity;    /* run.fidelity of every cell */
    const guint *gp_counts;  /* the table's GP columns */
    guint n_gp;
    const RpContext *ctx;    /* the user's overrides and model folders
                                (rp_run_build); NULL: none */
} RpEllRig;

/* Appends RpRow * for the n databases named (`workload.database` of the
 * cell, in row order) at each of the rig's GP counts: one run of the
 * cell per database, GP count and algorithm; then per database its db
 * rows and the million claims' rates (rp_ellsworth90_rate_rows).  FALSE with *err if a
 * database or the machine is bad. */
gboolean rp_ellsworth90_table1(const RpEllRig *rig, const char *const *dbs,
                               guint n, GPtrArray *rows, GError **err);

/* Appends the cv rows of loo.yaml beside `setup` (ellsworth90_cv.c):
 * cv/<db>/loo_<column> per left-out cell and refit_min_/refit_max_ of
 * each predicted cell; none when there is no loo.yaml.  FALSE with a
 * located *err on a bad file. */
gboolean rp_ellsworth90_loo(const char *setup, GPtrArray *rows,
                            GError **err);

/* One run of the rig's cell with workload.database `db`, `gps` GPs and
 * `algo`: a new result (sim_result_free), or NULL with *err. */
SimResult *rp_ellsworth90_run(const RpEllRig *rig, const char *db, guint gps,
                              const char *algo, GError **err);

/* The paper's figures the claims are decided against (setup.yaml's
 * `claims:`; borrowed strings). */
typedef struct {
    const char *cube;           /* §2.2's cube database file */
    guint cube_gps, cube_idle;  /* 8 GPs, 2 left with empty structures */
    const char *cube_algorithm; /* simple (by primitive, §2.2) */
    const char *mesh;           /* §5.2's 16x16 mesh database file */
    guint mesh_gps;             /* 16 */
    double polygons_per_s;      /* the abstract's goal, 10^6 */
} RpEllClaims;

/* Claims figure rows of one run at the table's largest GP count (the
 * million claims): gp_polygons_per_s and frame_polygons_per_s of row
 * "million <db> <gps> GPs". */
void rp_ellsworth90_rate_rows(const SimResult *r, const char *db, guint gps,
                              GPtrArray *rows);
/* Claims figure rows of the worked examples: a run of the cube, the
 * mesh's dealing.  FALSE with *err on a bad database or machine. */
gboolean rp_ellsworth90_example_rows(const RpEllRig *rig,
                                     const RpEllClaims *cl, GPtrArray *rows,
                                     GError **err);
/* GPs of `gps` that hold one strip of the quad mesh `db` dealt by
 * primitive (simple): quads all in one row or column, as many as the
 * mesh's side. */
guint rp_ellsworth90_strips(const SceneDb *db, guint gps);
/* Appends the holds rows of every claim from the figure rows in rows
 * (ellsworth90_claims.c). */
void rp_ellsworth90_claims(GPtrArray *rows, const RpEllClaims *cl);

extern const RpPaperOps rp_ellsworth90;

#endif
