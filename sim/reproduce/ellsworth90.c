/* ellsworth90.c — `pgsim reproduce ellsworth90`: seed 001's table (§6)
 * for the four generated databases, each cell one run of the pphigs
 * workload through the runner (sim/run/run.h): setup.yaml's `cell` with
 * the cell's database, GP count and algorithm set, one event-driven
 * frame on a Pixel-Planes 5 machine built by the machine layer.  The
 * cells are the workload's declared metrics (seed 001 §6's efficiency,
 * utilisation and speed-up of the frame, T1 the host list's traversal;
 * the database's counts).  Everything it simulates is named by
 * configs/papers/ellsworth90/setup.yaml; the published values are joined
 * by the driver, never read here.
 * Cost: per database and GP count, 3 runs (simple, complex, by
 * structure), each a distribution and a frame, O(n P).
 */
#include "sim/reproduce/ellsworth90.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/workload/metrics.h"

enum { MAX_ROWS = 16, MAX_GPS = 16 };

/* ---- one cell ---------------------------------------------------------- */

SimResult *rp_ellsworth90_run(const RpEllRig *rig, const char *db, guint gps,
                              const char *algo, GError **err)
{
    char *set[] = {g_strdup_printf("workload.database=%s", db),
                   g_strdup_printf("workload.gps=%u", gps),
                   g_strdup_printf("workload.algorithm=%s", algo), NULL};
    RpContext c = {.fidelity = rig->fidelity, /* the label names none */
                   .sets = rig->ctx ? rig->ctx->sets : NULL,
                   .models = rig->ctx ? rig->ctx->models : NULL};
    CfgRun *r = rp_run_build(&c, cfg_copy(rig->cell), NULL,
                             (const char *const *)set, err);
    SimResult *res = r ? rp_run_exec(&c, r, NULL, err) : NULL;
    cfg_run_free(r);
    for (guint i = 0; set[i]; i++)
        g_free(set[i]);
    return res;
}

/* ---- rows ------------------------------------------------------------- */

static void add(GPtrArray *rows, const char *table, const char *row,
                const char *col, double v)
{
    g_ptr_array_add(rows, rp_row_new(table, row, col, v, NULL));
}

/* The database table, from any run of the database. */
static void db_rows(const SimResult *r, const char *row, GPtrArray *rows)
{
    double prims = wl_metric(r, "db_primitives");
    add(rows, "db", row, "depth", wl_metric(r, "db_depth"));
    add(rows, "db", row, "structures", wl_metric(r, "db_structures"));
    add(rows, "db", row, "polys_per_structure",
        prims / wl_metric(r, "db_structures"));
    add(rows, "db", row, "poly_attr_ratio",
        prims / MAX(wl_metric(r, "db_attributes"), 1));
    add(rows, "db", row, "offscreen_pct", wl_metric(r, "db_offscreen_pct"));
}

/* pgsim's own columns: §2.1's distribute-by-structure, which the paper
 * describes and rejects but does not measure (no published cells). */
static void by_structure_rows(const SimResult *m, const char *row, guint p,
                              GPtrArray *rows)
{
    static const char *const what[] = {"eff", "util", "speedup"};
    double v[] = {wl_metric(m, "distribution_efficiency_pct"),
                  wl_metric(m, "processor_utilisation_pct"),
                  wl_metric(m, "speedup")};
    for (int i = 0; i < 3; i++) {
        char col[40];
        g_snprintf(col, sizeof col, "by_structure_%s_%u", what[i], p);
        g_ptr_array_add(rows, rp_row_new("1", row, col, v[i],
                                         "pgsim's own: §2.1, not measured "
                                         "in the paper"));
    }
}

static void paper_rows(const SimResult *s, const SimResult *x,
                       const char *row, guint p, GPtrArray *rows)
{
    char col[32];
    g_snprintf(col, sizeof col, "simple_eff_%u", p);
    add(rows, "1", row, col, wl_metric(s, "distribution_efficiency_pct"));
    g_snprintf(col, sizeof col, "complex_eff_%u", p);
    add(rows, "1", row, col, wl_metric(x, "distribution_efficiency_pct"));
    g_snprintf(col, sizeof col, "util_%u", p);
    add(rows, "1", row, col, wl_metric(x, "processor_utilisation_pct"));
    g_snprintf(col, sizeof col, "speedup_%u", p);
    add(rows, "1", row, col, wl_metric(x, "speedup"));
}

/* One database's rows: at each GP count the three algorithms, then the
 * database table from the last run. */
static gboolean db_cells(const RpEllRig *rig, const char *db, GPtrArray *rows,
                         GError **err)
{
    static const char *const algos[] = {"simple", "complex", "by_structure"};
    SimResult *m[3] = {NULL, NULL, NULL};
    gboolean ok = TRUE;
    for (guint k = 0; ok && k < rig->n_gp; k++) {
        for (int a = 0; a < 3; a++)
            sim_result_free(m[a]), m[a] = NULL;
        for (int a = 0; ok && a < 3; a++)
            ok = (m[a] = rp_ellsworth90_run(rig, db, rig->gp_counts[k],
                                            algos[a], err)) != NULL;
        if (ok) {
            paper_rows(m[0], m[1], db, rig->gp_counts[k], rows);
            by_structure_rows(m[2], db, rig->gp_counts[k], rows);
        }
    }
    if (ok) {
        db_rows(m[1], db, rows);
        rp_ellsworth90_rate_rows(m[1], db, rig->gp_counts[rig->n_gp - 1],
                                 rows);
    }
    for (int a = 0; a < 3; a++)
        sim_result_free(m[a]);
    return ok;
}

gboolean rp_ellsworth90_table1(const RpEllRig *rig, const char *const *dbs,
                               guint n, GPtrArray *rows, GError **err)
{
    for (guint i = 0; i < n; i++)
        if (!db_cells(rig, dbs[i], rows, err))
            return FALSE;
    return TRUE;
}

/* ---- setup ------------------------------------------------------------ */

typedef struct {
    CfgNode *root;
    const CfgNode *cell;
    const char *dbs[MAX_ROWS];
    guint n_dbs, gp_counts[MAX_GPS], n_gp;
    RpEllClaims claims;
} EllSetup;

static gboolean seq_of(const CfgNode *root, const char *key, guint max,
                       const CfgNode **seq, GError **err)
{
    *seq = cfg_get(root, key);
    if (*seq && cfg_kind(*seq) == CFG_SEQ && cfg_seq_len(*seq) > 0 &&
        cfg_seq_len(*seq) <= max)
        return TRUE;
    char *want = g_strdup_printf("a list of 1 to %u entries under '%s'", max,
                                 key);
    cfg_error(err, *seq ? *seq : root, *seq ? "another value" : "nothing",
              want);
    g_free(want);
    return FALSE;
}

static gboolean read_rows(EllSetup *s, GError **err)
{
    const CfgNode *rows;
    if (!seq_of(s->root, "rows", MAX_ROWS, &rows, err))
        return FALSE;
    for (guint i = 0; i < cfg_seq_len(rows); i++) {
        const CfgNode *r = cfg_seq_at(rows, i);
        if (cfg_kind(r) != CFG_SCALAR) {
            cfg_error(err, r, "another value", "a database name");
            return FALSE;
        }
        s->dbs[s->n_dbs++] = cfg_scalar(r);
    }
    return TRUE;
}

static gboolean read_gp_counts(EllSetup *s, GError **err)
{
    const CfgNode *gps;
    if (!seq_of(s->root, "gp_counts", MAX_GPS, &gps, err))
        return FALSE;
    for (guint i = 0; i < cfg_seq_len(gps); i++) {
        uint64_t n;
        const CfgNode *g = cfg_seq_at(gps, i);
        if (!cfg_parse_count(cfg_scalar(g), "gp_counts", &n, err))
            return FALSE;
        s->gp_counts[s->n_gp++] = (guint)n;
    }
    return TRUE;
}

static gboolean count_of(const CfgNode *map, const char *key, guint max,
                         guint *out, GError **err)
{
    uint64_t n = 0;
    gboolean ok = cfg_get_count(map, key, TRUE, 1, max, &n, err);
    *out = (guint)n;
    return ok;
}

/* claims: {cube: {database, gps, algorithm, idle_gps}, mesh: {database,
 * gps}, polygons_per_s}: the paper's figures (ellsworth90_claims.c). */
static gboolean read_claims(EllSetup *s, GError **err)
{
    const CfgNode *c, *cube, *mesh;
    RpEllClaims *cl = &s->claims;
    return cfg_get_map(s->root, "claims", TRUE, "a map {cube, mesh, "
                       "polygons_per_s}", &c, err) &&
           cfg_get_map(c, "cube", TRUE, "a map {database, gps, algorithm, "
                       "idle_gps}", &cube, err) &&
           cfg_get_map(c, "mesh", TRUE, "a map {database, gps}", &mesh,
                       err) &&
           cfg_get_str(cube, "database", TRUE, &cl->cube, err) &&
           count_of(cube, "gps", 64, &cl->cube_gps, err) &&
           cfg_get_str(cube, "algorithm", TRUE, &cl->cube_algorithm, err) &&
           count_of(cube, "idle_gps", 64, &cl->cube_idle, err) &&
           cfg_check_unused(cube, err) &&
           cfg_get_str(mesh, "database", TRUE, &cl->mesh, err) &&
           count_of(mesh, "gps", 64, &cl->mesh_gps, err) &&
           cfg_check_unused(mesh, err) &&
           cfg_get_double(c, "polygons_per_s", TRUE, 1, 1e12,
                          &cl->polygons_per_s, err) &&
           cfg_check_unused(c, err);
}

/* setup.yaml; the cell's keys are the runner's to check (every run). */
static gboolean setup_load(EllSetup *s, const char *path, GError **err)
{
    static const char *const runner_reads[] = {"cell", NULL};
    s->root = cfg_load_file(path, err);
    return s->root &&
           cfg_get_map(s->root, "cell", TRUE, "a pphigs run config",
                       &s->cell, err) &&
           read_rows(s, err) && read_gp_counts(s, err) &&
           read_claims(s, err) && cfg_check_unused_except(s->root, runner_reads, err);
}

static gboolean ellsworth90_rows(const RpContext *ctx, GPtrArray *rows,
                                 GError **err)
{
    EllSetup s = {0};
    gboolean ok = setup_load(&s, ctx->setup, err);
    if (ok) {
        RpEllRig rig = {s.cell, ctx->fidelity ? ctx->fidelity : "analytic",
                        s.gp_counts, s.n_gp, ctx};
        ok = rp_ellsworth90_table1(&rig, s.dbs, s.n_dbs, rows, err) &&
             rp_ellsworth90_loo(ctx->setup, rows, err) &&
             rp_ellsworth90_example_rows(&rig, &s.claims, rows, err);
        if (ok)
            rp_ellsworth90_claims(rows, &s.claims);
    }
    cfg_free(s.root);
    return ok;
}

const RpPaperOps rp_ellsworth90 = {
    .name = "ellsworth90",
    .citation = "Ellsworth, Good, Tebbs 1990: distributing display lists "
                "(PPHIGS on Pixel-Planes 5), 4 and 16 GPs",
    .setup = "setup.yaml",
    .rows = ellsworth90_rows,
    .cost_s = 1.1, /* measured: user time of `pgsim reproduce ellsworth90` */
};
