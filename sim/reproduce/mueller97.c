/* mueller97.c — `pgsim reproduce mueller97` (mueller97.h): seed 000's
 * test runs (§4.1: chunk sizes 1, 5, 12, 26; 4 to 20 processors; min-set
 * and max-set; the chunking strategies) on the vehicle database, each a
 * run of the sortfirst workload (sim/workload/sortfirst/sf_frame.h) on
 * the setup's machine model.  What runs is configs/papers/mueller97/
 * setup.yaml; nothing here is a published value.  The scene is built
 * once, and each frame of it rasterised once (sim/raster/prerender.h:
 * every case renders the same frames at the same resolution, and counts
 * its regions' spans and pixels from that render); consecutive cases of
 * one chunking and chunk size share a chunk database, each case builds
 * its machine.  Cost: per case O(frames x (P x chunk
 * instances + polygons rendered + their spans)).
 */
#include "sim/reproduce/mueller97.h"
#include "sim/scene/scene_cfg.h"
#include "sim/workload/metrics.h"
#include "sim/workload/sortfirst/sf_workload.h"
#include <math.h>

enum { MAX_LIST = 16 };

typedef struct {
    CfgNode *root;
    const char *model, *scene;
    uint64_t frames, resolution;
    guint gran[MAX_LIST], n_gran, procs[MAX_LIST], n_procs;
    gboolean bk[2];            /* bookkeeping run: [minset, maxset] */
    guint c1_procs;            /* Chart 1's processor count */
    int c1_bk;                 /* Chart 1's bookkeeping */
    gboolean chunking[3];      /* Chart 1's strategies, by WlSfChunking */
    WlSfSizes sizes;
} MuSetup;

/* ---- setup ---------------------------------------------------------------
 */

static gboolean counts(const CfgNode *root, const char *key, guint *out,
                       guint *n, GError **err)
{
    const CfgNode *seq = cfg_get(root, key);
    if (!seq || cfg_kind(seq) != CFG_SEQ || cfg_seq_len(seq) == 0 ||
        cfg_seq_len(seq) > MAX_LIST) {
        char *want = g_strdup_printf("a list of 1 to %d counts under '%s'",
                                     MAX_LIST, key);
        cfg_error(err, seq ? seq : root, seq ? "another value" : "nothing",
                  want);
        g_free(want);
        return FALSE;
    }
    for (*n = 0; *n < cfg_seq_len(seq); (*n)++) {
        uint64_t v;
        const CfgNode *e = cfg_seq_at(seq, *n);
        if (!cfg_parse_count(cfg_scalar(e), key, &v, err))
            return FALSE;
        if (v < 1 || v > WL_SF_MAX_PROCS * 1024) {
            cfg_error(err, e, cfg_scalar(e), "a count of 1 .. 65536");
            return FALSE;
        }
        out[*n] = (guint)v;
    }
    return TRUE;
}

/* A list of words from `names` into flags[index]. */
static gboolean words(const CfgNode *map, const char *key,
                      const char *const *names, gboolean *flags, GError **err)
{
    const CfgNode *seq = cfg_get(map, key);
    if (!seq || cfg_kind(seq) != CFG_SEQ || cfg_seq_len(seq) == 0) {
        cfg_error(err, seq ? seq : map, seq ? "another value" : "nothing",
                  "a non-empty list of words");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        const CfgNode *e = cfg_seq_at(seq, i);
        const char *w = cfg_scalar(e);
        int k = 0;
        while (names[k] && (!w || strcmp(names[k], w) != 0))
            k++;
        if (!names[k]) {
            char *want = g_strjoinv(" | ", (char **)names);
            cfg_error(err, e, w ? w : "a non-word", want);
            g_free(want);
            return FALSE;
        }
        flags[k] = TRUE;
    }
    return TRUE;
}

static gboolean read_bytes(MuSetup *s, GError **err)
{
    const CfgNode *b;
    return cfg_get_map(s->root, "bytes", TRUE,
                       "a map {message, chunk, triangle, instance} of sizes",
                       &b, err) &&
           cfg_get_size(b, "message", TRUE, &s->sizes.message, err) &&
           cfg_get_size(b, "chunk", TRUE, &s->sizes.chunk, err) &&
           cfg_get_size(b, "triangle", TRUE, &s->sizes.triangle, err) &&
           cfg_get_size(b, "instance", TRUE, &s->sizes.instance, err);
}

static gboolean read_chart1(MuSetup *s, GError **err)
{
    const CfgNode *c;
    uint64_t p = 16;
    if (!cfg_get_map(s->root, "chart1", TRUE,
                     "a map {processors, bookkeeping, chunking}", &c, err) ||
        !cfg_get_count(c, "processors", TRUE, 1, WL_SF_MAX_PROCS, &p, err) ||
        !cfg_get_enum(c, "bookkeeping", TRUE, wl_sf_bookkeeping_names,
                      &s->c1_bk, err) ||
        !words(c, "chunking", wl_sf_chunking_names, s->chunking, err))
        return FALSE;
    s->c1_procs = (guint)p;
    return TRUE;
}

static gboolean setup_load(MuSetup *s, const char *path, GError **err)
{
    s->root = cfg_load_file(path, err);
    s->frames = 12;
    s->resolution = 256;
    return s->root && cfg_get_str(s->root, "model", TRUE, &s->model, err) &&
           cfg_get_str(s->root, "scene", TRUE, &s->scene, err) &&
           cfg_get_count(s->root, "frames", TRUE, 1, 1000, &s->frames, err) &&
           cfg_get_count(s->root, "resolution", TRUE, 16, 4096,
                         &s->resolution, err) &&
           counts(s->root, "granularities", s->gran, &s->n_gran, err) &&
           counts(s->root, "processors", s->procs, &s->n_procs, err) &&
           words(s->root, "bookkeeping", wl_sf_bookkeeping_names, s->bk,
                 err) &&
           read_chart1(s, err) && read_bytes(s, err) &&
           cfg_check_unused(s->root, err);
}

/* ---- one case ------------------------------------------------------------
 */

static void point_from(RpMuellerPoint *pt, const SimResult *r)
{
    pt->bytes = wl_metric(r, "migrated_bytes_per_frame");
    pt->overlap = wl_metric(r, "chunk_overlap");
    pt->ratio = wl_metric(r, "box_region_ratio");
    pt->master = wl_metric(r, "master_boxes_per_frame");
    pt->slave = wl_metric(r, "slave_boxes_per_frame");
    pt->fresh = wl_metric(r, "new_boxes_per_frame");
    pt->polys = wl_metric(r, "polygons_rendered_per_frame");
    pt->transforms = wl_metric(r, "transforms_per_frame");
}

/* What the cases share: each frame rasterised once, and the last chunk
 * database with its instances' screen rectangles per frame (cases come
 * grouped by chunking and chunk size, and P changes a database only
 * through its masters: wl_sf_db_set_procs()). */
typedef struct {
    RastPrerenderSet *pre;
    WlSfDb *db;
    WlSfScreenSet *screens;
} MuShared;

static WlSfDb *shared_db(MuShared *sh, const Scene *sc,
                         const RpMuellerPoint *pt, GError **err)
{
    WlSfDb *d = sh->db;
    if (d && d->granularity == pt->granularity &&
        d->chunking == pt->chunking) {
        wl_sf_db_set_procs(d, pt->procs);
        return d;
    }
    wl_sf_db_free(d);
    wl_sf_screen_set_clear(sh->screens);
    sh->db = wl_sf_db_new(sc->db, pt->procs, pt->granularity, pt->chunking,
                          err);
    return sh->db;
}

static gboolean run_on(MachMachine *m, const Scene *sc, const MuSetup *s,
                       MuShared *sh, RpMuellerPoint *pt, GError **err)
{
    WlSfCosts c;
    if (!wl_sf_costs_from_machine(m, &c, err))
        return FALSE;
    const WlSfDb *db = shared_db(sh, sc, pt, err);
    if (!db)
        return FALSE;
    WlSfSetup st = {.procs = pt->procs,
                    .resolution = (int)s->resolution,
                    .bk = pt->minset ? WL_SF_MINSET : WL_SF_MAXSET,
                    .sizes = s->sizes,
                    .cull_back = TRUE,
                    .pre = sh->pre,
                    .screens = sh->screens};
    WlSfRun *r = wl_sf_run_new(m, sc, db, &st, &c);
    gboolean ok = wl_sf_run_frames(r, (int)s->frames, SIM_TIME_MAX, err);
    if (ok) {
        SimResult *res = sim_result_new("sortfirst", s->model);
        wl_sf_fill_metrics(res, wl_sf_run_stats(r), db, &st);
        point_from(pt, res);
        sim_result_free(res);
        pt->instances = (wl_sf_n_insts(db) + wl_sf_n_chunks(db) / 2) /
                        MAX(wl_sf_n_chunks(db), 1);
    }
    wl_sf_run_free(r);
    return ok;
}

static gboolean run_case(const RpContext *ctx, const Scene *sc,
                         const MuSetup *s, MuShared *sh, RpMuellerPoint *pt,
                         GError **err)
{
    char *what = g_strdup_printf("%s %s g=%u P=%u",
                                 wl_sf_chunking_names[pt->chunking],
                                 pt->minset ? "minset" : "maxset",
                                 pt->granularity, pt->procs);
    rp_step(ctx, what);
    g_free(what);
    SimEngine *eng = sim_engine_new(RP_SEED);
    const char *fid = ctx->fidelity ? ctx->fidelity : "analytic";
    MachMachine *m = mach_new_from_model(eng, s->model, fid, err);
    gboolean ok = m != NULL;
    if (ok) {
        rp_note_fidelity(ctx, s->model, mach_fidelity(m));
        ok = run_on(m, sc, s, sh, pt, err);
    }
    mach_free(m);
    sim_engine_free(eng);
    return ok;
}

/* Every case: sorted chunking over the grid of processors, chunk sizes
 * and bookkeeping; the other strategies at Chart 1's P and bookkeeping. */
static GArray *cases(const MuSetup *s)
{
    GArray *pts = g_array_new(FALSE, TRUE, sizeof(RpMuellerPoint));
    for (int ch = 0; ch < 3; ch++)
        for (guint g = 0; g < s->n_gran; g++)
            for (guint p = 0; p < s->n_procs; p++)
                for (int bk = 0; bk < 2; bk++) {
                    RpMuellerPoint pt = {.procs = s->procs[p],
                                         .granularity = s->gran[g],
                                         .minset = bk == WL_SF_MINSET,
                                         .chunking = (WlSfChunking)ch};
                    gboolean sorted = ch == WL_SF_CHUNK_SORTED;
                    gboolean grid = sorted && s->bk[bk];
                    gboolean c1 = !sorted && s->chunking[ch] &&
                                  pt.procs == s->c1_procs && bk == s->c1_bk;
                    if (grid || c1)
                        g_array_append_val(pts, pt);
                }
    return pts;
}

/* ---- rows ----------------------------------------------------------------
 */

static void add(GPtrArray *rows, const char *table, const char *row,
                const char *col, double v)
{
    g_ptr_array_add(rows, rp_row_new(table, row, col, v, NULL));
}

static void chart_rows(const RpMuellerPoint *pt, const MuSetup *s,
                       GPtrArray *rows)
{
    char row[64];
    g_snprintf(row, sizeof row, "P%u/g%u", pt->procs, pt->granularity);
    if (pt->procs == s->c1_procs && (int)!pt->minset == s->c1_bk) {
        char r1[64];
        g_snprintf(r1, sizeof r1, "%s/g%u",
                   wl_sf_chunking_names[pt->chunking], pt->granularity);
        add(rows, "1", r1, "box_region_ratio", pt->ratio);
        add(rows, "1", r1, "chunk_overlap", pt->overlap);
    }
    if (pt->chunking != WL_SF_CHUNK_SORTED)
        return;
    add(rows, "2", row, pt->minset ? "bytes_minset" : "bytes_maxset",
        pt->bytes);
    if (!pt->minset || !s->bk[WL_SF_MAXSET]) {
        add(rows, "3", row, "chunk_overlap", pt->overlap);
        add(rows, "3", row, "box_region_ratio", pt->ratio);
    }
    const char *t = pt->minset ? "4" : "5";
    add(rows, t, row, "transforms", pt->transforms);
    add(rows, t, row, "master_boxes", pt->master);
    add(rows, t, row, "slave_boxes", pt->slave);
    add(rows, t, row, "new_boxes", pt->fresh);
    add(rows, t, row, "polygons", pt->polys);
}

static gboolean mueller97_rows(const RpContext *ctx, GPtrArray *rows,
                               GError **err)
{
    MuSetup s = {0};
    gboolean ok = setup_load(&s, ctx->setup, err);
    Scene *sc = ok ? scene_load(s.scene, err) : NULL;
    if (ok && sc && !sc->db) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found a scene without a structure database, "
                    "expected a hierarchical scene (generator: vehicle)",
                    s.scene);
        ok = FALSE;
    }
    ok = ok && sc;
    GArray *pts = cases(&s);
    MuShared sh = {rast_prerender_set_new(), NULL, wl_sf_screen_set_new()};
    for (guint i = 0; ok && i < pts->len; i++)
        ok = run_case(ctx, sc, &s, &sh,
                      &g_array_index(pts, RpMuellerPoint, i), err);
    rast_prerender_set_free(sh.pre);
    wl_sf_db_free(sh.db);
    wl_sf_screen_set_free(sh.screens);
    const RpMuellerPoint *p = (const RpMuellerPoint *)(void *)pts->data;
    for (guint i = 0; ok && i < pts->len; i++)
        chart_rows(&p[i], &s, rows);
    if (ok)
        rp_mueller97_claims(p, pts->len, rows);
    if (ok && ctx->out_dir)
        rp_mueller97_charts(p, pts->len, s.c1_procs, ctx->out_dir);
    g_array_unref(pts);
    scene_free(sc);
    cfg_free(s.root);
    return ok;
}

const RpPaperOps rp_mueller97 = {
    .name = "mueller97",
    .citation = "Mueller: hierarchical graphics databases in sort-first "
                "(Charts 1-5 and the claims of §4.2), the vehicle database "
                "instanced three times",
    .setup = "setup.yaml",
    .rows = mueller97_rows,
    .cost_s = 8, /* measured: user time of `pgsim reproduce mueller97` */
};
