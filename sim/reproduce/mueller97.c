/* mueller97.c — `pgsim reproduce mueller97` (mueller97.h): seed 000's
 * test runs (§4.1: chunk sizes 1, 5, 12, 26; 4 to 20 processors; min-set
 * and max-set; the chunking strategies) on the vehicle database, each a
 * run of the sortfirst workload through the runner (sim/run/run.h):
 * setup.yaml's `cell` with the case's processors, chunk size,
 * bookkeeping and chunking set, read through the workload's declared
 * metrics.  What runs is configs/papers/mueller97/setup.yaml; nothing
 * here is a published value.  The cases hand the runner one share
 * (sim/workload/share.h): the workload rasterises each frame of the
 * scene once for all of them and keeps the chunk database of consecutive
 * cases of one chunking and chunk size.  Cost: per case O(frames x (P x
 * chunk instances + polygons rendered + their spans)) plus building the
 * scene.
 */
#include "sim/reproduce/mueller97.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/workload/metrics.h"
#include <math.h>
#include <string.h>

enum { MAX_LIST = 16, MAX_COUNT = 65536, MINSET = 0, MAXSET = 1 };

const char *const rp_mu_chunking_names[] = {"sorted", "unsorted",
                                            "partially_sorted", NULL};
static const char *const bk_names[] = {"minset", "maxset", NULL};

typedef struct {
    CfgNode *root;
    const CfgNode *cell;       /* a sortfirst run config but its scene */
    CfgNode *scene;            /* the scene file: {scene: {...}} */
    guint gran[MAX_LIST], n_gran, procs[MAX_LIST], n_procs;
    gboolean bk[2];            /* bookkeeping run: [minset, maxset] */
    guint c1_procs;            /* Chart 1's processor count */
    int c1_bk;                 /* Chart 1's bookkeeping */
    gboolean chunking[3];      /* Chart 1's strategies, by RpMuChunking */
    guint pull_procs;          /* the pull cases' P (sorted, min-set) */
    guint pull_gran[MAX_LIST], n_pull_gran; /* and chunk sizes */
    RpMuInst *inst;            /* the instancing trade-off, or NULL */
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
        if (v < 1 || v > MAX_COUNT) {
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

static gboolean read_chart1(MuSetup *s, GError **err)
{
    const CfgNode *c;
    uint64_t p = 16;
    if (!cfg_get_map(s->root, "chart1", TRUE,
                     "a map {processors, bookkeeping, chunking}", &c, err) ||
        !cfg_get_count(c, "processors", TRUE, 1, MAX_COUNT, &p, err) ||
        !cfg_get_enum(c, "bookkeeping", TRUE, bk_names, &s->c1_bk, err) ||
        !words(c, "chunking", rp_mu_chunking_names, s->chunking, err))
        return FALSE;
    s->c1_procs = (guint)p;
    return TRUE;
}

/* `pull`: the min-set pull cases of "push beats pull" (§3.3.2.2). */
static gboolean read_pull(MuSetup *s, GError **err)
{
    static const char *const keys[] = {"processors", "granularities", NULL};
    const CfgNode *c;
    uint64_t p = 16;
    if (!cfg_get_map(s->root, "pull", TRUE,
                     "a map {processors, granularities}", &c, err) ||
        !cfg_get_count(c, "processors", TRUE, 1, MAX_COUNT, &p, err) ||
        !counts(c, "granularities", s->pull_gran, &s->n_pull_gran, err) ||
        !cfg_check_unused_except(c, keys, err))
        return FALSE;
    s->pull_procs = (guint)p;
    return TRUE;
}

/* The scene file named by `scene`: a map holding only `scene:`, which
 * becomes every case's scene section (the cell has none of its own). */
static gboolean read_scene(MuSetup *s, GError **err)
{
    static const char *const scene_only[] = {"scene", NULL};
    const char *path = NULL;
    const CfgNode *sec = NULL;
    if (cfg_has(s->cell, "scene")) {
        cfg_error(err, cfg_get(s->cell, "scene"), "a scene in cell",
                  "the scene of the top-level `scene:` file only");
        return FALSE;
    }
    if (!cfg_get_str(s->root, "scene", TRUE, &path, err) ||
        !(s->scene = cfg_load_file(path, err)))
        return FALSE;
    if (cfg_kind(s->scene) != CFG_MAP) {
        cfg_error(err, s->scene, "a non-map", "a scene file {scene: {...}}");
        return FALSE;
    }
    return cfg_get_map(s->scene, "scene", TRUE, "a scene map", &sec, err) &&
           cfg_check_unused_except(s->scene, scene_only, err);
}

/* setup.yaml; the cell's keys are the runner's to check (every run). */
static gboolean setup_load(MuSetup *s, const char *path, GError **err)
{
    static const char *const runner_reads[] = {"cell", NULL};
    s->root = cfg_load_file(path, err);
    return s->root &&
           cfg_get_map(s->root, "cell", TRUE, "a sortfirst run config",
                       &s->cell, err) &&
           read_scene(s, err) &&
           counts(s->root, "granularities", s->gran, &s->n_gran, err) &&
           counts(s->root, "processors", s->procs, &s->n_procs, err) &&
           words(s->root, "bookkeeping", bk_names, s->bk, err) &&
           read_chart1(s, err) && read_pull(s, err) &&
           rp_mu_inst_load(s->root, &s->inst, err) &&
           cfg_check_unused_except(s->root, runner_reads, err);
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
    pt->messages = wl_metric(r, "messages_per_frame");
    pt->requests = pt->pull ? wl_metric(r, "requests_per_frame") : 0;
    pt->interrupt_ms = pt->pull ? wl_metric(r, "interrupt_ms") : 0;
    pt->memory = wl_metric(r, "peak_memory");
    pt->frame_ms = wl_metric(r, "frame_ms");
    /* max-set instances of the root: chunk instances per chunk, rounded */
    guint chunks = (guint)wl_metric(r, "chunks");
    guint insts = (guint)wl_metric(r, "chunk_instances");
    pt->instances = (insts + chunks / 2) / MAX(chunks, 1);
}

/* The run of the cell for one case: a new result, or NULL with *err;
 * notes the machine's fidelity. */
static SimResult *run_cell(const RpContext *ctx, const MuSetup *s,
                           WlShare *share, const RpMuellerPoint *pt,
                           GError **err)
{
    char *set[] = {
        g_strdup_printf("workload.processors=%u", pt->procs),
        g_strdup_printf("workload.granularity=%u", pt->granularity),
        g_strdup_printf("workload.bookkeeping=%s",
                        bk_names[pt->minset ? MINSET : MAXSET]),
        g_strdup_printf("workload.chunking=%s",
                        rp_mu_chunking_names[pt->chunking]),
        g_strdup_printf("workload.migration=%s", pt->pull ? "pull" : "push"),
        NULL};
    CfgNode *tree = cfg_copy(s->cell);
    cfg_merge(tree, s->scene); /* adds its scene: section */
    CfgRun *r = rp_run_build(ctx, tree, NULL, (const char *const *)set, err);
    for (guint i = 0; set[i]; i++)
        g_free(set[i]);
    SimResult *res = r ? rp_run_exec(ctx, r, share, err) : NULL;
    cfg_run_free(r);
    return res;
}

static gboolean run_case(const RpContext *ctx, const MuSetup *s,
                         WlShare *share, RpMuellerPoint *pt, GError **err)
{
    char *what = g_strdup_printf("%s %s%s g=%u P=%u",
                                 rp_mu_chunking_names[pt->chunking],
                                 pt->minset ? "minset" : "maxset",
                                 pt->pull ? " pull" : "", pt->granularity,
                                 pt->procs);
    rp_step(ctx, what);
    g_free(what);
    SimResult *res = run_cell(ctx, s, share, pt, err);
    if (res)
        point_from(pt, res);
    sim_result_free(res);
    return res != NULL;
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
                                         .minset = bk == MINSET,
                                         .chunking = (RpMuChunking)ch};
                    gboolean sorted = ch == RP_MU_SORTED;
                    gboolean grid = sorted && s->bk[bk];
                    gboolean c1 = !sorted && s->chunking[ch] &&
                                  pt.procs == s->c1_procs && bk == s->c1_bk;
                    if (grid || c1)
                        g_array_append_val(pts, pt);
                }
    return pts;
}

/* The pull cases: sorted, min-set, at `pull`'s P and chunk sizes. */
static GArray *pull_cases(const MuSetup *s)
{
    GArray *pts = g_array_new(FALSE, TRUE, sizeof(RpMuellerPoint));
    for (guint g = 0; g < s->n_pull_gran; g++) {
        RpMuellerPoint pt = {.procs = s->pull_procs,
                             .granularity = s->pull_gran[g],
                             .minset = TRUE,
                             .chunking = RP_MU_SORTED,
                             .pull = TRUE};
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
                   rp_mu_chunking_names[pt->chunking], pt->granularity);
        add(rows, "1", r1, "box_region_ratio", pt->ratio);
        add(rows, "1", r1, "chunk_overlap", pt->overlap);
    }
    if (pt->chunking != RP_MU_SORTED)
        return;
    add(rows, "2", row, pt->minset ? "bytes_minset" : "bytes_maxset",
        pt->bytes);
    if (!pt->minset || !s->bk[MAXSET]) {
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
    GArray *pts = cases(&s), *pull = pull_cases(&s);
    WlShare *share = wl_share_new();
    for (guint i = 0; ok && i < pts->len; i++)
        ok = run_case(ctx, &s, share, &g_array_index(pts, RpMuellerPoint, i),
                      err);
    for (guint i = 0; ok && i < pull->len; i++)
        ok = run_case(ctx, &s, share,
                      &g_array_index(pull, RpMuellerPoint, i), err);
    wl_share_free(share);
    GArray *ip = g_array_new(FALSE, TRUE, sizeof(RpMuInstPoint));
    if (ok && s.inst)
        ok = rp_mu_inst_run(ctx, s.cell, s.inst, ip, err);
    const RpMuellerPoint *p = (const RpMuellerPoint *)(void *)pts->data;
    for (guint i = 0; ok && i < pts->len; i++)
        chart_rows(&p[i], &s, rows);
    if (ok)
        rp_mueller97_claims(p, pts->len, rows);
    if (ok)
        rp_mueller97_claims_pull(
            p, pts->len, (const RpMuellerPoint *)(void *)pull->data,
            pull->len, rows);
    if (ok && ip->len)
        rp_mueller97_claims_instancing(
            (const RpMuInstPoint *)(void *)ip->data, ip->len, rows);
    if (ok && ctx->out_dir)
        rp_mueller97_charts(p, pts->len, s.c1_procs, ctx->out_dir);
    g_array_unref(ip);
    rp_mu_inst_free(s.inst);
    g_array_unref(pts);
    g_array_unref(pull);
    cfg_free(s.scene);
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
    .cost_s = 32, /* measured: user time of `pgsim reproduce mueller97` */
};
