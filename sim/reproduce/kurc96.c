/* kurc96.c — `pgsim reproduce kurc96`: Kurç, Aykanat, Özgüç, "Active
 * pixel merging on hypercube multicomputers" (seed 003) on the simulated
 * iPSC/2 (models/ipsc2.yaml, through the `pixelmerge` workload).
 *
 * The setup (machine, message formats, memory model, the six teapot
 * scenes and the one view rule they share) is ctx->setup
 * (configs/papers/kurc96/setup.yaml unless a test names another);
 * published values are joined by the driver from
 * configs/papers/kurc96/published.yaml, never read here.  Rows:
 *   table 1   <scene> x polygons, tpg_400, tpf_400, tpg_640, tpf_640
 *   table 2   P16/<scene>, P8/<scene> x {pair_rs, zbuf_exc}_{span, zbuf,
 *             merge}_ms (N=400); P8 ZBUF-EXC cells carry the memory note
 *   fig1      a/P<p> (2POT, N=400, P = 2..16) and b/<scene>/<N> (P=16)
 *             x {pair, aapc}_{rs, hbp}_bytes: total volume of concurrent
 *             communication (§5)
 *   fig2      the same rows x {rs, hbp}_imbalance: (max - min) / mean
 *             merge operations of AAPC (§5)
 *   text      P16/2POT/640 x aapc_hbp_speedup
 * Every run is one frame of the `pixelmerge` workload through the runner
 * (sim/run/run.h): a run tree of the setup's machine, workload and the
 * row's scene, with the run's scheme, balance, processors and resolution
 * and run.seed / frames / fidelity as overrides, built on a fresh engine
 * and machine at the context's network fidelity; results are the
 * workload's metrics.  Runs are cached by (scene, N, P, scheme,
 * balance): about 90.  The cross-validation's cost changes are overrides
 * of the model's node costs (machine.nodes.node.costs.OP.value), so they
 * reach the machine that prices the work.  Charts: kurc96_plot.c.
 */
#include "sim/reproduce/kurc96.h"
#include "sim/machine/machine.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/workload/metrics.h"
#include <math.h>

const char *const rp_kurc96_scenes[] = {"1POT",   "2POT",   "4POT_1", "4POT_2",
                                        "8POT_1", "8POT_2", NULL};
enum { N_SCENES = 6 };

/* The node costs of each fitted group (RP_KURC_GROUPS, in its order):
 * scatter and gather are one group. */
static const char *const group_ops[RP_KURC_GROUPS][2] = {
    {"polygon", NULL},    {"span", NULL},      {"insert_step", NULL},
    {"pixel", NULL},      {"zbuf_init", NULL}, {"compare", NULL},
    {"scatter", "gather"}};

typedef struct {
    const RpContext *ctx;
    CfgNode *setup;
    SimTime cost[RP_KURC_GROUPS][2]; /* the model's node costs of the groups */
    gboolean have_costs;             /* cost[] read from a built machine */
    GHashTable *cache;               /* key -> RpKurcRun * */
} Kurc;

/* Every scene of the paper is there, and nothing else. */
static gboolean check_scenes(const Kurc *k, GError **err)
{
    const CfgNode *sc;
    if (!cfg_get_map(k->setup, "scenes", TRUE,
                     "scenes: {1POT: ..., 2POT: ..., 4POT_1, 4POT_2, "
                     "8POT_1, 8POT_2}",
                     &sc, err))
        return FALSE;
    for (int i = 0; i < N_SCENES; i++)
        if (!cfg_get(sc, rp_kurc96_scenes[i])) {
            cfg_error(err, sc, "no scene '1POT' ... '8POT_2'",
                      "scenes: {1POT: ..., 2POT: ..., 4POT_1, 4POT_2, "
                      "8POT_1, 8POT_2}");
            return FALSE;
        }
    for (guint i = 0; i < cfg_map_len(sc); i++) {
        const char *key = cfg_map_key(sc, i);
        if (!g_strv_contains((const char *const *)rp_kurc96_scenes, key)) {
            char *found = g_strdup_printf("scene '%s'", key);
            cfg_error(err, cfg_map_value(sc, i), found,
                      "one of 1POT, 2POT, 4POT_1, 4POT_2, 8POT_1, 8POT_2");
            g_free(found);
            return FALSE;
        }
    }
    return TRUE;
}

/* Loads the setup and checks its top level; the runner checks each
 * section when it builds a run from it. */
static gboolean kurc_init(Kurc *k, const RpContext *ctx, GError **err)
{
    static const char *const runner_reads[] = {"machine", "workload", "scenes",
                                               NULL};
    k->ctx = ctx;
    k->cache = g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free);
    k->setup = cfg_load_file(ctx->setup, err);
    const CfgNode *sec;
    if (!k->setup ||
        !cfg_get_map(k->setup, "machine", TRUE, "machine: {model: ipsc2}", &sec,
                     err) ||
        !cfg_get_map(k->setup, "workload", TRUE,
                     "workload: {type: pixelmerge, ...}", &sec, err) ||
        !check_scenes(k, err))
        return FALSE;
    cfg_mark_read(cfg_get(k->setup, "view")); /* used through anchors */
    return cfg_check_unused_except(k->setup, runner_reads, err);
}

static void kurc_clear(Kurc *k)
{
    cfg_free(k->setup);
    g_hash_table_destroy(k->cache);
}

/* The run tree of scene `scene`: the setup's machine and workload
 * sections and the scene, copied with their places in the setup file. */
static CfgNode *run_tree(const Kurc *k, const char *scene, GError **err)
{
    CfgNode *root = cfg_load_string("schema_version: 1\n", k->ctx->setup, err);
    if (!root)
        return NULL;
    cfg_map_put(root, "machine", cfg_copy(cfg_get(k->setup, "machine")));
    cfg_map_put(root, "workload", cfg_copy(cfg_get(k->setup, "workload")));
    cfg_map_put(root, "scene",
                cfg_copy(cfg_get(cfg_get(k->setup, "scenes"), scene)));
    return root;
}

/* The overrides of one run, NULL-terminated (g_ptr_array_unref); scale
 * (NULL: none) multiplies the node costs of the fitted groups. */
static GPtrArray *run_overrides(const Kurc *k, const RpKurcSpec *sp,
                                const double *scale)
{
    GPtrArray *o = g_ptr_array_new_with_free_func(g_free);
    g_ptr_array_add(o, g_strdup_printf("workload.scheme=%s", sp->scheme));
    g_ptr_array_add(o, g_strdup_printf("workload.balance=%s", sp->balance));
    g_ptr_array_add(o, g_strdup_printf("workload.processors=%u", sp->procs));
    g_ptr_array_add(o,
                    g_strdup_printf("workload.resolution=%u", sp->resolution));
    g_ptr_array_add(o, g_strdup("run.frames=1"));
    for (int g = 0; scale && g < RP_KURC_GROUPS; g++)
        for (int j = 0; j < 2 && group_ops[g][j] && scale[g] != 1; j++) {
            SimTime t = (SimTime)llround((double)k->cost[g][j] * scale[g]);
            g_ptr_array_add(o, g_strdup_printf("machine.nodes.node.costs.%s."
                                               "value=%" G_GUINT64_FORMAT " ps",
                                               group_ops[g][j], t));
        }
    g_ptr_array_add(o, NULL);
    return o;
}

/* Reads the groups' node costs from machine m, once. */
static gboolean read_costs(Kurc *k, const MachMachine *m, GError **err)
{
    for (int g = 0; !k->have_costs && g < RP_KURC_GROUPS; g++)
        for (int j = 0; j < 2 && group_ops[g][j]; j++)
            if (!mach_cost_lookup(m, "node", group_ops[g][j], &k->cost[g][j],
                                  err))
                return FALSE;
    k->have_costs = TRUE;
    return TRUE;
}

static CfgRun *build(Kurc *k, const RpKurcSpec *sp, const double *scale,
                     GError **err)
{
    CfgNode *root = run_tree(k, sp->scene, err);
    if (!root)
        return NULL;
    GPtrArray *ov = run_overrides(k, sp, scale);
    CfgRun *r =
        rp_run_build(k->ctx, root, NULL, (const char *const *)ov->pdata, err);
    g_ptr_array_unref(ov);
    return r;
}

static void run_from_result(RpKurcRun *run, const SimResult *r,
                            const MachMachine *m)
{
    run->span_ms = wl_metric(r, "span_ms");
    run->zbuf_ms = wl_metric(r, "zbuf_ms");
    run->merge_ms = wl_metric(r, "merge_ms");
    run->volume = wl_metric(r, "concurrent_volume");
    run->imbalance = wl_metric(r, "load_imbalance");
    run->speedup = wl_metric(r, "speedup");
    run->polygons = wl_metric(r, "polygons");
    run->tpg = wl_metric(r, "tpg");
    run->tpf = wl_metric(r, "tpf");
    run->memory = wl_metric(r, "peak_memory");
    static const char *const part[5] = {"memory_base", "memory_polygons",
                                        "memory_spans", "memory_zbuffer",
                                        "memory_buffers"};
    for (int i = 0; i < 5; i++)
        run->mem_part[i] = wl_metric(r, part[i]);
    const MachKindInfo *node = mach_kind(m, "node");
    run->node_memory = node ? (double)node->memory : 0;
}

/* One run; scale (NULL: none) multiplies the fitted cost groups. */
static gboolean simulate(Kurc *k, const RpKurcSpec *sp, const double *scale,
                         RpKurcRun *run, GError **err)
{
    if (scale && !k->have_costs) { /* the model's costs, from a build */
        CfgRun *b = build(k, sp, NULL, err);
        gboolean ok = b && read_costs(k, b->machine_built, err);
        cfg_run_free(b);
        if (!ok)
            return FALSE;
    }
    CfgRun *r = build(k, sp, scale, err);
    SimResult *res = r ? rp_run_exec(k->ctx, r, NULL, err) : NULL;
    gboolean ok = res && (scale || read_costs(k, r->machine_built, err));
    if (ok)
        run_from_result(run, res, r->machine_built);
    sim_result_free(res);
    cfg_run_free(r);
    return ok;
}

/* The cached run of sp. */
static const RpKurcRun *get_run(Kurc *k, const RpKurcSpec *sp, GError **err)
{
    char *key = g_strdup_printf("%s/%u/%u/%s/%s", sp->scene, sp->resolution,
                                sp->procs, sp->scheme, sp->balance);
    RpKurcRun *run = g_hash_table_lookup(k->cache, key);
    if (run) {
        g_free(key);
        return run;
    }
    char *what =
        g_strdup_printf("%s N=%u P=%u %s-%s", sp->scene, sp->resolution,
                        sp->procs, sp->scheme, sp->balance);
    rp_step(k->ctx, what);
    g_free(what);
    run = g_new0(RpKurcRun, 1);
    if (!simulate(k, sp, NULL, run, err)) {
        g_free(run);
        g_free(key);
        return NULL;
    }
    g_hash_table_insert(k->cache, key, run);
    return run;
}

/* The run of scene i (rp_kurc96_scenes) with these settings. */
static const RpKurcRun *run_of(Kurc *k, int i, guint n, guint procs,
                               const char *scheme, const char *balance,
                               GError **err)
{
    RpKurcSpec sp = {rp_kurc96_scenes[i], n, procs, scheme, balance};
    return get_run(k, &sp, err);
}

gboolean rp_kurc96_simulate(const RpContext *ctx, const RpKurcSpec *sp,
                            const double *scale, RpKurcRun *run, GError **err)
{
    Kurc k = {0};
    gboolean ok = kurc_init(&k, ctx, err) && simulate(&k, sp, scale, run, err);
    kurc_clear(&k);
    return ok;
}

static void add(GPtrArray *rows, const char *table, const char *row,
                const char *col, double v, const char *note)
{
    g_ptr_array_add(rows, rp_row_new(table, row, col, v, note));
}

static gboolean table1(Kurc *k, GPtrArray *rows, GError **err)
{
    for (int i = 0; i < N_SCENES; i++) {
        const char *s = rp_kurc96_scenes[i];
        const RpKurcRun *a = run_of(k, i, 400, 16, "aapc", "hbp", err);
        const RpKurcRun *b =
            a ? run_of(k, i, 640, 16, "aapc", "hbp", err) : NULL;
        if (!b)
            return FALSE;
        add(rows, "1", s, "polygons", a->polygons, NULL);
        add(rows, "1", s, "tpg_400", a->tpg, NULL);
        add(rows, "1", s, "tpf_400", a->tpf, NULL);
        add(rows, "1", s, "tpg_640", b->tpg, NULL);
        add(rows, "1", s, "tpf_640", b->tpf, NULL);
        /* Both end points: about a pixel more per span, and a span has
         * fewer pixels at N=400 than at 640 (issue 11). */
        add(rows, "1", s, "tpg_640_over_400", b->tpg / a->tpg,
            "screen area ratio 640^2 / 400^2 = 2.56");
    }
    return TRUE;
}

/* The memory verdict of a run: "* out of memory: ..." when the node's
 * peak (the workload's memory model) exceeds the machine's node memory,
 * else "fits: ...".  The paper marks with "*" the ZBUF-EXC runs that did
 * not fit (all in the withheld P=8 rows: every P=16 run has times). */
char *rp_kurc96_memory_note(const RpKurcRun *r)
{
    const double mb = 1048576.0; /* MiB */
    return g_strdup_printf(
        "%s %.2f of %.2f MiB (base %.2f, polygons %.2f, spans %.2f, "
        "z-buffer/WPA %.2f, message buffers %.2f)",
        r->memory > r->node_memory ? "* out of memory:" : "fits:",
        r->memory / mb, r->node_memory / mb, r->mem_part[0] / mb,
        r->mem_part[1] / mb, r->mem_part[2] / mb, r->mem_part[3] / mb,
        r->mem_part[4] / mb);
}

static void table2_row(GPtrArray *rows, const char *row, const RpKurcRun *pr,
                       const RpKurcRun *zx)
{
    char *zx_note = rp_kurc96_memory_note(zx);
    char *pr_note =
        pr->memory > pr->node_memory ? rp_kurc96_memory_note(pr) : NULL;
    add(rows, "2", row, "pair_rs_span_ms", pr->span_ms, pr_note);
    add(rows, "2", row, "pair_rs_zbuf_ms", pr->zbuf_ms, pr_note);
    add(rows, "2", row, "pair_rs_merge_ms", pr->merge_ms, pr_note);
    add(rows, "2", row, "zbuf_exc_span_ms", zx->span_ms, zx_note);
    add(rows, "2", row, "zbuf_exc_zbuf_ms", zx->zbuf_ms, zx_note);
    add(rows, "2", row, "zbuf_exc_merge_ms", zx->merge_ms, zx_note);
    g_free(zx_note);
    g_free(pr_note);
}

static gboolean table2(Kurc *k, GPtrArray *rows, GError **err)
{
    static const guint procs[] = {16, 8};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < N_SCENES; i++) {
            const RpKurcRun *pr =
                run_of(k, i, 400, procs[j], "pair", "rs", err);
            const RpKurcRun *zx =
                pr ? run_of(k, i, 400, procs[j], "zbuf_exc", "strips", err)
                   : NULL;
            if (!zx)
                return FALSE;
            char *row =
                g_strdup_printf("P%u/%s", procs[j], rp_kurc96_scenes[i]);
            table2_row(rows, row, pr, zx);
            g_free(row);
        }
    return TRUE;
}

/* ---- leave-one-scene-out (kurc96_cv.c) --------------------------------- */

#define CV_STEP 0.1 /* relative cost change of the finite differences */

static double phase_ms(const RpKurcRun *r, int ph)
{
    return ph == 0 ? r->span_ms : ph == 1 ? r->zbuf_ms : r->merge_ms;
}

static const char *const cv_cols[6] = {"pair_rs_span_ms",  "pair_rs_zbuf_ms",
                                       "pair_rs_merge_ms", "zbuf_exc_span_ms",
                                       "zbuf_exc_zbuf_ms", "zbuf_exc_merge_ms"};

typedef struct {
    int scene[N_SCENES * 6];
    double pub[N_SCENES * 6], sim[N_SCENES * 6];
    double jac[N_SCENES * 6 * RP_KURC_GROUPS];
} CvCells;

/* The six cells of scene s (PAIR-RS, ZBUF-EXC; P=16, N=400): values and
 * the response to each cost group, by re-running with it CV_STEP up. */
static gboolean cv_scene(Kurc *k, int s, const RpPaper *paper, CvCells *c,
                         GError **err)
{
    char *row = g_strdup_printf("P16/%s", rp_kurc96_scenes[s]);
    gboolean ok = TRUE;
    for (int m = 0; ok && m < 2; m++) {
        RpKurcSpec sp = {rp_kurc96_scenes[s], 400, 16, m ? "zbuf_exc" : "pair",
                         m ? "strips" : "rs"};
        const RpKurcRun *b = get_run(k, &sp, err);
        ok = b != NULL;
        for (int g = 0; ok && g < RP_KURC_GROUPS; g++) {
            double scale[RP_KURC_GROUPS];
            for (int j = 0; j < RP_KURC_GROUPS; j++)
                scale[j] = j == g ? 1 + CV_STEP : 1;
            RpKurcRun r;
            rp_step(k->ctx, "leave-one-scene-out responses");
            ok = simulate(k, &sp, scale, &r, err);
            for (int ph = 0; ok && ph < 3; ph++) {
                int i = (s * 2 + m) * 3 + ph;
                c->jac[i * RP_KURC_GROUPS + g] =
                    (phase_ms(&r, ph) - phase_ms(b, ph)) / CV_STEP;
            }
        }
        for (int ph = 0; ok && ph < 3; ph++) {
            int i = (s * 2 + m) * 3 + ph;
            const RpCell *cell = rp_paper_cell(paper, "2", row, cv_cols[i % 6]);
            c->scene[i] = s;
            c->sim[i] = phase_ms(b, ph);
            c->pub[i] = cell ? cell->value : NAN;
            if (!cell || !isfinite(cell->value)) {
                g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                            "kurc96: no published Table 2 %s %s", row,
                            cv_cols[i % 6]);
                ok = FALSE;
            }
        }
    }
    g_free(row);
    return ok;
}

static void cv_rows(GPtrArray *rows, const CvCells *c, const double *loso,
                    const RpKurcCv *cv)
{
    for (int i = 0; i < cv->n; i++) {
        char *row = g_strdup_printf("P16/%s", rp_kurc96_scenes[c->scene[i]]);
        char *note = g_strdup_printf(
            "scene left out of the fit: %+.1f%% (in-sample %+.1f%%)",
            100 * (loso[i] / c->pub[i] - 1), 100 * (c->sim[i] / c->pub[i] - 1));
        add(rows, "cv", row, cv_cols[i % 6], loso[i], note);
        g_free(note);
        g_free(row);
    }
    double m[2], w[2];
    rp_kurc96_cv_errors(cv, c->sim, &m[0], &w[0]);
    rp_kurc96_cv_errors(cv, loso, &m[1], &w[1]);
    const char *what = "% over the 36 P=16 cells of Table 2";
    add(rows, "cv", "P16", "in_sample_mean_abs_pct", 100 * m[0], what);
    add(rows, "cv", "P16", "in_sample_worst_abs_pct", 100 * w[0], what);
    add(rows, "cv", "P16", "loso_mean_abs_pct", 100 * m[1], what);
    add(rows, "cv", "P16", "loso_worst_abs_pct", 100 * w[1], what);
}

/* In-sample and leave-one-scene-out errors of the node-cost fit. */
static gboolean cross_validate(Kurc *k, GPtrArray *rows, GError **err)
{
    char *path = rp_paper_path(RP_PAPERS_DIR, rp_kurc96.name);
    RpPaper *paper = rp_paper_load(path, err);
    g_free(path);
    if (!paper)
        return FALSE;
    CvCells *c = g_new0(CvCells, 1);
    gboolean ok = TRUE;
    for (int s = 0; ok && s < N_SCENES; s++)
        ok = cv_scene(k, s, paper, c, err);
    if (ok) {
        RpKurcCv cv = {N_SCENES * 6, RP_KURC_GROUPS, N_SCENES, c->scene,
                       c->pub,       c->sim,         c->jac};
        double loso[N_SCENES * 6];
        rp_kurc96_cv_run(&cv, loso);
        cv_rows(rows, c, loso, &cv);
    }
    g_free(c);
    rp_paper_free(paper);
    return ok;
}

/* Fig. 1 and 2 values of one (scene, N, P) point: four volumes (PAIR and
 * AAPC with RS and HBP) and the RS and HBP imbalances of AAPC. */
static gboolean fig_point(Kurc *k, GPtrArray *rows, int scene, guint n,
                          guint procs, const char *row, RpKurcPoint *pt,
                          GError **err)
{
    static const char *const col[4] = {"pair_rs_bytes", "pair_hbp_bytes",
                                       "aapc_rs_bytes", "aapc_hbp_bytes"};
    const RpKurcRun *r[4];
    for (int i = 0; i < 4; i++) {
        r[i] = run_of(k, scene, n, procs, i < 2 ? "pair" : "aapc",
                      i % 2 ? "hbp" : "rs", err);
        if (!r[i])
            return FALSE;
        add(rows, "fig1", row, col[i], r[i]->volume, NULL);
        pt->volume[i] = r[i]->volume;
    }
    add(rows, "fig2", row, "rs_imbalance", r[2]->imbalance, NULL);
    add(rows, "fig2", row, "hbp_imbalance", r[3]->imbalance, NULL);
    pt->imbalance[0] = r[2]->imbalance;
    pt->imbalance[1] = r[3]->imbalance;
    pt->label = g_strdup(row);
    pt->procs = procs;
    return TRUE;
}

static gboolean figures(Kurc *k, GPtrArray *rows, RpKurcFigs *f, GError **err)
{
    gboolean ok = TRUE;
    for (guint p = 2; ok && p <= 16; p *= 2) {
        char *row = g_strdup_printf("a/P%u", p);
        ok = fig_point(k, rows, 1, 400, p, row, &f->a[f->n_a++], err);
        g_free(row);
    }
    for (int i = 0; ok && i < N_SCENES * 2; i++) {
        guint n = i % 2 ? 640 : 400;
        char *row = g_strdup_printf("b/%s/%u", rp_kurc96_scenes[i / 2], n);
        ok = fig_point(k, rows, i / 2, n, 16, row, &f->b[f->n_b++], err);
        g_free(row);
    }
    return ok;
}

static gboolean speedup(Kurc *k, GPtrArray *rows, GError **err)
{
    const RpKurcRun *r = run_of(k, 1, 640, 16, "aapc", "hbp", err);
    if (r)
        add(rows, "text", "P16/2POT/640", "aapc_hbp_speedup", r->speedup,
            "P=16; serial = the modified scanline z-buffer over all "
            "polygons on one node, no merge (§5)");
    return r != NULL;
}

static gboolean kurc96_run(const RpContext *ctx, GPtrArray *rows, GError **err)
{
    Kurc k = {0};
    RpKurcFigs figs = {0};
    gboolean ok = kurc_init(&k, ctx, err) && table1(&k, rows, err) &&
                  table2(&k, rows, err) && cross_validate(&k, rows, err) &&
                  figures(&k, rows, &figs, err) && speedup(&k, rows, err);
    if (ok)
        rp_kurc96_claims(&figs, rows);
    if (ok && ctx->out_dir)
        rp_kurc96_charts(&figs, ctx->out_dir, ctx->fidelity);
    rp_kurc96_figs_clear(&figs);
    kurc_clear(&k);
    return ok;
}

const RpPaperOps rp_kurc96 = {
    .name = "kurc96",
    .citation = "Kurç, Aykanat, Özgüç: active pixel merging on the iPSC/2 "
                "hypercube (kurc96): Tables 1-2, Figs. 1-2, speed-up",
    .setup = "setup.yaml",
    .rows = kurc96_run,
    .cost_s = 12, /* measured: user time of `pgsim reproduce kurc96` */
};
