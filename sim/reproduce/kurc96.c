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
 * Every run is one frame on a fresh engine and machine built at the
 * context's network fidelity; runs are cached by (scene, N, P, scheme,
 * balance): about 90.  Charts: kurc96_plot.c.
 */
#include "sim/reproduce/kurc96.h"
#include "sim/scene/scene_cfg.h"
#include "sim/workload/pixelmerge/pm_workload.h"
#include <math.h>


const char *const rp_kurc96_scenes[] = {"1POT",   "2POT",   "4POT_1", "4POT_2",
                                        "8POT_1", "8POT_2", NULL};
enum { N_SCENES = 6 };

typedef struct {
    const RpContext *ctx;
    CfgNode *setup;
    WlPmParams *base;
    Scene *scenes[N_SCENES];
    GHashTable *cache; /* key -> RpKurcRun * */
} Kurc;

static gboolean load_scenes(Kurc *k, GError **err)
{
    const CfgNode *sc = cfg_get(k->setup, "scenes");
    for (int i = 0; i < N_SCENES; i++) {
        const CfgNode *s = sc ? cfg_get(sc, rp_kurc96_scenes[i]) : NULL;
        if (!s) {
            cfg_error(err, sc ? sc : k->setup,
                      "no scene "
                      "'1POT' ... '8POT_2'",
                      "scenes: {1POT: ..., 2POT: "
                      "..., 4POT_1, 4POT_2, 8POT_1, 8POT_2}");
            return FALSE;
        }
        k->scenes[i] = scene_from_cfg(s, err);
        if (!k->scenes[i])
            return FALSE;
    }
    return TRUE;
}

static gboolean kurc_init(Kurc *k, const RpContext *ctx, GError **err)
{
    k->ctx = ctx;
    k->cache = g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free);
    k->setup = cfg_load_file(ctx->setup, err);
    if (!k->setup)
        return FALSE;
    const CfgNode *wl = cfg_get(k->setup, "workload");
    const char *type = NULL;
    if (!cfg_get_str(wl, "type", TRUE, &type, err))
        return FALSE;
    k->base = wl_pixelmerge_ops.parse(wl, err);
    if (!k->base || !load_scenes(k, err) ||
        !mach_check_section(cfg_get(k->setup, "machine"), err))
        return FALSE;
    cfg_mark_read(cfg_get(k->setup, "view")); /* used through anchors */
    return cfg_check_unused(k->setup, err);
}

static void kurc_clear(Kurc *k)
{
    for (int i = 0; i < N_SCENES; i++)
        if (k->scenes[i])
            scene_free(k->scenes[i]);
    if (k->base)
        wl_pixelmerge_ops.free_params(k->base);
    cfg_free(k->setup);
    g_hash_table_destroy(k->cache);
}

static double metric(const SimResult *r, const char *name)
{
    double v = NAN;
    sim_result_get_metric(r, name, &v);
    return v;
}

static void run_from_result(RpKurcRun *run, const SimResult *r,
                            const MachMachine *m)
{
    run->span_ms = metric(r, "span_ms");
    run->zbuf_ms = metric(r, "zbuf_ms");
    run->merge_ms = metric(r, "merge_ms");
    run->volume = metric(r, "concurrent_volume");
    run->imbalance = metric(r, "load_imbalance");
    run->speedup = metric(r, "speedup");
    run->polygons = metric(r, "polygons");
    run->tpg = metric(r, "tpg");
    run->tpf = metric(r, "tpf");
    run->memory = metric(r, "peak_memory");
    const MachKindInfo *node = mach_kind(m, "node");
    run->node_memory = node ? (double)node->memory : 0;
}

static gboolean simulate(Kurc *k, const WlPmParams *p, int scene,
                         RpKurcRun *run, GError **err)
{
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m = mach_new_from_cfg(eng, cfg_get(k->setup, "machine"),
                                       k->ctx->fidelity, err);
    SimResult *r = sim_result_new("pixelmerge", "ipsc2");
    WlPmCosts c;
    if (m)
        rp_note_fidelity(k->ctx, mach_name(m), mach_fidelity(m));
    gboolean ok = m && wl_pm_costs_from_machine(m, p->count_bytes, &c, err) &&
                  wl_pm_run_frames(m, k->scenes[scene], p, &c, 1, r, err);
    if (ok)
        run_from_result(run, r, m);
    sim_result_free(r);
    mach_free(m);
    sim_engine_free(eng);
    return ok;
}

/* The cached run of (scene, N, P, scheme, balance). */
static const RpKurcRun *get_run(Kurc *k, int scene, guint n, guint procs,
                                WlPmScheme scheme, WlPmBalance bal,
                                GError **err)
{
    char *key = g_strdup_printf("%d/%u/%u/%d/%d", scene, n, procs, scheme, bal);
    RpKurcRun *run = g_hash_table_lookup(k->cache, key);
    if (run) {
        g_free(key);
        return run;
    }
    WlPmParams p = *k->base;
    p.setup.scheme = scheme;
    p.setup.balance = bal;
    p.setup.procs = procs;
    p.setup.resolution = n;
    char *what = g_strdup_printf("%s N=%u P=%u %s-%s", rp_kurc96_scenes[scene],
                                 n, procs, wl_pm_scheme_names[scheme],
                                 wl_pm_balance_names[bal]);
    rp_step(k->ctx, what);
    g_free(what);
    run = g_new0(RpKurcRun, 1);
    if (!simulate(k, &p, scene, run, err)) {
        g_free(run);
        g_free(key);
        return NULL;
    }

    g_hash_table_insert(k->cache, key, run);
    return run;
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
        const RpKurcRun *a =
            get_run(k, i, 400, 16, WL_PM_AAPC, WL_PM_BAL_HBP, err);
        const RpKurcRun *b =
            a ? get_run(k, i, 640, 16, WL_PM_AAPC, WL_PM_BAL_HBP, err) : NULL;
        if (!b)
            return FALSE;
        add(rows, "1", s, "polygons", a->polygons, NULL);
        add(rows, "1", s, "tpg_400", a->tpg, NULL);
        add(rows, "1", s, "tpf_400", a->tpf, NULL);
        add(rows, "1", s, "tpg_640", b->tpg, NULL);
        add(rows, "1", s, "tpf_640", b->tpf, NULL);
    }
    return TRUE;
}

/* The note of a ZBUF-EXC cell at P=8: the paper marks with "*" the
 * ZBUF-EXC runs that ran out of local memory, all in the withheld P=8
 * rows; we say what our memory model predicts. */
static char *memory_note(const RpKurcRun *zx)
{
    return g_strdup_printf("paper: '*' (out of memory) on some P=8 "
                           "ZBUF-EXC runs; model: %.2f of %.2f MB, %s",
                           zx->memory / 1e6, zx->node_memory / 1e6,
                           zx->memory > zx->node_memory ? "OUT OF MEMORY"
                                                        : "fits");
}

static void table2_row(GPtrArray *rows, const char *row, const RpKurcRun *pr,
                       const RpKurcRun *zx, const char *zx_note)
{
    add(rows, "2", row, "pair_rs_span_ms", pr->span_ms, NULL);
    add(rows, "2", row, "pair_rs_zbuf_ms", pr->zbuf_ms, NULL);
    add(rows, "2", row, "pair_rs_merge_ms", pr->merge_ms, NULL);
    add(rows, "2", row, "zbuf_exc_span_ms", zx->span_ms, zx_note);
    add(rows, "2", row, "zbuf_exc_zbuf_ms", zx->zbuf_ms, zx_note);
    add(rows, "2", row, "zbuf_exc_merge_ms", zx->merge_ms, zx_note);
}

static gboolean table2(Kurc *k, GPtrArray *rows, GError **err)
{
    static const guint procs[] = {16, 8};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < N_SCENES; i++) {
            const RpKurcRun *pr =
                get_run(k, i, 400, procs[j], WL_PM_PAIR, WL_PM_BAL_RS, err);
            const RpKurcRun *zx =
                pr ? get_run(k, i, 400, procs[j], WL_PM_ZBUF_EXC,
                             WL_PM_BAL_STRIPS, err)
                   : NULL;
            if (!zx)
                return FALSE;
            char *row =
                g_strdup_printf("P%u/%s", procs[j], rp_kurc96_scenes[i]);
            char *note = procs[j] == 8 ? memory_note(zx) : NULL;
            table2_row(rows, row, pr, zx, note);
            g_free(note);
            g_free(row);
        }
    return TRUE;
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
        r[i] = get_run(k, scene, n, procs, i < 2 ? WL_PM_PAIR : WL_PM_AAPC,
                       i % 2 ? WL_PM_BAL_HBP : WL_PM_BAL_RS, err);
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
    const RpKurcRun *r = get_run(k, 1, 640, 16, WL_PM_AAPC, WL_PM_BAL_HBP, err);
    if (r)
        add(rows, "text", "P16/2POT/640", "aapc_hbp_speedup", r->speedup,
            "serial = the local phases of the whole scene on one node");
    return r != NULL;
}

static gboolean kurc96_run(const RpContext *ctx, GPtrArray *rows, GError **err)
{
    Kurc k = {0};
    RpKurcFigs figs = {0};
    gboolean ok = kurc_init(&k, ctx, err) && table1(&k, rows, err) &&
                  table2(&k, rows, err) && figures(&k, rows, &figs, err) &&
                  speedup(&k, rows, err);
    if (ok && ctx->out_dir)
        rp_kurc96_charts(&figs, ctx->out_dir, ctx->fidelity);
    rp_kurc96_figs_clear(&figs);
    kurc_clear(&k);
    return ok;
}

const RpPaperOps rp_kurc96 = {
    .name = "kurc96",
    .citation = "Kurç, Aykanat, Özgüç: active pixel merging on the iPSC/2 "
               "hypercube (seed 003): Tables 1-2, Figs. 1-2, speed-up",
    .setup = "setup.yaml",
    .rows = kurc96_run,
};
