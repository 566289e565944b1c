/* mueller97_inst.c — the instancing trade-off of seed 000 §5 (issue 37
 * point 3): "Which of these methods is a better choice depends to a
 * large extent upon how much applications make use of structure
 * instancing ... [max-set] is the better choice for applications with
 * moderate or large amounts of instancing.  For applications that make
 * little or no use of structure instancing, the min-set method is the
 * obvious choice."
 *
 * setup.yaml's optional `instancing` map names a scene (a vehicle fleet
 * whose copies share vehicle trees as scene.instancing says: the picture
 * is the same at every level, only the sharing differs), the levels to
 * run, a structure database file (heavy instancing, rendered with the
 * scene's camera), P, chunk size and frames.  Each database runs with
 * min-set and max-set bookkeeping (push, fixed masters, static
 * regions); table "instancing" prints per database and bookkeeping the
 * copies held, messages, bytes, box transforms, the largest store and
 * the frame time, and claim C8 reads them (mueller97.h).
 *
 * C8: a database's instancing is its chunk instances per chunk (1: none;
 * 2 or more: moderate or large; our bounds).  The better method on a
 * database is max-set when its frame is more than RP_MU_GAIN (5 %, our
 * threshold) shorter than min-set's, else min-set (within that margin
 * the simpler bookkeeping, without instance pointers, wins).  The claim
 * holds when min-set is the better method on every database without
 * instancing and max-set on every database with moderate or large
 * instancing (NaN without one of each).  Cost: 2 runs per database.
 */
#include "sim/reproduce/mueller97.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/workload/metrics.h"
#include <math.h>
#include <string.h>

#define RP_MU_GAIN 1.05         /* our threshold: max-set's frame 5 % shorter */
#define RP_MU_NO_INSTANCING 1.5 /* below: "little or no" (per chunk) */
#define RP_MU_INSTANCED 2.0     /* from: "moderate or large" */

enum { MAX_LEVELS = 8 };

struct RpMuInst {
    CfgNode *scene; /* {scene: {...}} */
    char *levels[MAX_LEVELS];
    guint n_levels;
    char *database; /* NULL: none */
    guint procs, granularity, frames;
};

/* ---- setup --------------------------------------------------------------- */

static gboolean read_levels(RpMuInst *in, const CfgNode *map, GError **err)
{
    const CfgNode *seq = cfg_get(map, "levels");
    if (!seq || cfg_kind(seq) != CFG_SEQ || cfg_seq_len(seq) == 0 ||
        cfg_seq_len(seq) > MAX_LEVELS) {
        cfg_error(err, seq ? seq : map, seq ? "another value" : "nothing",
                  "a list of 1 to 8 scene.instancing values under 'levels'");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        const char *w = cfg_scalar(cfg_seq_at(seq, i));
        if (!w) {
            cfg_error(err, cfg_seq_at(seq, i), "a non-scalar",
                      "a scene.instancing value");
            return FALSE;
        }
        in->levels[in->n_levels++] = g_strdup(w);
    }
    return TRUE;
}

gboolean rp_mu_inst_load(const CfgNode *root, RpMuInst **out, GError **err)
{
    static const char *const keys[] = {"scene",      "levels",      "database",
                                       "processors", "granularity", "frames",
                                       NULL};
    const CfgNode *c = NULL;
    const char *scene = NULL, *db = NULL;
    uint64_t p = 16, g = 12, f = 10;
    *out = NULL;
    if (!cfg_get(root, "instancing"))
        return TRUE;
    RpMuInst *in = g_new0(RpMuInst, 1);
    gboolean ok = cfg_get_map(root, "instancing", TRUE,
                              "a map {scene, levels, database, processors, "
                              "granularity, frames}",
                              &c, err) &&
                  cfg_get_str(c, "scene", TRUE, &scene, err) &&
                  read_levels(in, c, err) &&
                  cfg_get_str(c, "database", FALSE, &db, err) &&
                  cfg_get_count(c, "processors", TRUE, 1, 64, &p, err) &&
                  cfg_get_count(c, "granularity", TRUE, 1, 65536, &g, err) &&
                  cfg_get_count(c, "frames", TRUE, 2, 1u << 20, &f, err) &&
                  cfg_check_unused_except(c, keys, err) &&
                  (in->scene = cfg_load_file(scene, err));
    in->database = g_strdup(db);
    in->procs = (guint)p;
    in->granularity = (guint)g;
    in->frames = (guint)f;
    if (!ok) {
        rp_mu_inst_free(in);
        return FALSE;
    }
    *out = in;
    return TRUE;
}

void rp_mu_inst_free(RpMuInst *in)
{
    if (!in)
        return;
    for (guint i = 0; i < in->n_levels; i++)
        g_free(in->levels[i]);
    g_free(in->database);
    cfg_free(in->scene);
    g_free(in);
}

/* ---- runs ---------------------------------------------------------------- */

/* One database (level, or the file when level is NULL) with one
 * bookkeeping into *pt. */
static gboolean run_one(const RpContext *ctx, const CfgNode *cell,
                        const RpMuInst *in, const char *level, WlShare *share,
                        RpMuInstPoint *pt, GError **err)
{
    char *set[] = {g_strdup_printf("workload.processors=%u", in->procs),
                   g_strdup_printf("workload.granularity=%u", in->granularity),
                   g_strdup_printf("workload.bookkeeping=%s",
                                   pt->minset ? "minset" : "maxset"),
                   g_strdup("workload.chunking=sorted"),
                   g_strdup_printf("run.frames=%u", in->frames),
                   level
                       ? g_strdup_printf("scene.instancing=%s", level)
                       : g_strdup_printf("workload.database=%s", in->database),
                   NULL};
    char *what = g_strdup_printf("instancing %s %s", pt->db,
                                 pt->minset ? "minset" : "maxset");
    rp_step(ctx, what);
    g_free(what);
    CfgNode *tree = cfg_copy(cell);
    cfg_merge(tree, in->scene);
    CfgRun *r = rp_run_build(ctx, tree, NULL, (const char *const *)set, err);
    for (guint i = 0; set[i]; i++)
        g_free(set[i]);
    SimResult *res = r ? rp_run_exec(ctx, r, share, err) : NULL;
    cfg_run_free(r);
    if (!res)
        return FALSE;
    double chunks = wl_metric(res, "chunks");
    pt->per_chunk =
        chunks > 0 ? wl_metric(res, "chunk_instances") / chunks : NAN;
    pt->copies = wl_metric(res, "copies");
    pt->messages = wl_metric(res, "messages_per_frame");
    pt->bytes = wl_metric(res, "migrated_bytes_per_frame");
    pt->transforms = wl_metric(res, "transforms_per_frame");
    pt->memory = wl_metric(res, "peak_memory");
    pt->frame_ms = wl_metric(res, "frame_ms");
    sim_result_free(res);
    return TRUE;
}

gboolean rp_mu_inst_run(const RpContext *ctx, const CfgNode *cell,
                        const RpMuInst *in, GArray *pts, GError **err)
{
    guint n = in->n_levels + (in->database != NULL);
    gboolean ok = TRUE;
    for (guint d = 0; ok && d < n; d++) {
        const char *level = d < in->n_levels ? in->levels[d] : NULL;
        WlShare *share = wl_share_new(); /* one database's two runs */
        for (int minset = 1; ok && minset >= 0; minset--) {
            RpMuInstPoint pt = {.minset = minset};
            g_strlcpy(pt.db, level ? level : "file", sizeof pt.db);
            ok = run_one(ctx, cell, in, level, share, &pt, err);
            if (ok)
                g_array_append_val(pts, pt);
        }
        wl_share_free(share);
    }
    return ok;
}

/* ---- rows ---------------------------------------------------------------- */

static void add(GPtrArray *rows, const char *row, const char *col, double v)
{
    g_ptr_array_add(rows, rp_row_new("instancing", row, col, v, NULL));
}

static void claim(GPtrArray *rows, const char *col, double v, const char *n)
{
    gboolean holds = strcmp(col, "holds") == 0;
    g_ptr_array_add(rows, rp_row_new("claims", "C8_instancing_tradeoff", col, v,
                                     holds ? n : NULL));
}

static const RpMuInstPoint *partner(const RpMuInstPoint *p, guint n,
                                    const RpMuInstPoint *mn)
{
    for (guint i = 0; i < n; i++)
        if (!p[i].minset && !strcmp(p[i].db, mn->db))
            return &p[i];
    return NULL;
}

void rp_mueller97_claims_instancing(const RpMuInstPoint *p, guint n,
                                    GPtrArray *rows)
{
    const char *text = "§5: min-set for little or no instancing, max-set "
                       "for moderate or large instancing";
    guint none = 0, inst = 0, none_ok = 0, inst_ok = 0;
    GString *why = g_string_new("");
    for (guint i = 0; i < n; i++) {
        char row[80];
        g_snprintf(row, sizeof row, "%s/%s", p[i].db,
                   p[i].minset ? "minset" : "maxset");
        add(rows, row, "instances_per_chunk", p[i].per_chunk);
        add(rows, row, "copies", p[i].copies);
        add(rows, row, "messages", p[i].messages);
        add(rows, row, "bytes", p[i].bytes);
        add(rows, row, "transforms", p[i].transforms);
        add(rows, row, "peak_memory", p[i].memory);
        add(rows, row, "frame_ms", p[i].frame_ms);
        const RpMuInstPoint *mx = p[i].minset ? partner(p, n, &p[i]) : NULL;
        if (!mx || !(mx->frame_ms > 0))
            continue;
        double gain = p[i].frame_ms / mx->frame_ms;
        gboolean maxset_better = gain > RP_MU_GAIN;
        g_snprintf(row, sizeof row, "%s", p[i].db);
        add(rows, row, "minset_over_maxset_frame", gain);
        if (p[i].per_chunk < RP_MU_NO_INSTANCING) {
            none++;
            none_ok += !maxset_better;
            if (maxset_better)
                g_string_append_printf(why,
                                       " on %s (%.2f instances a "
                                       "chunk) max-set's frame is %.2f "
                                       "times shorter;",
                                       p[i].db, p[i].per_chunk, gain);
        } else if (p[i].per_chunk >= RP_MU_INSTANCED) {
            inst++;
            inst_ok += maxset_better;
            if (!maxset_better)
                g_string_append_printf(why,
                                       " on %s (%.2f instances a "
                                       "chunk) min-set / max-set frame is "
                                       "only %.2f;",
                                       p[i].db, p[i].per_chunk, gain);
        }
    }
    double holds = none && inst ? none_ok == none && inst_ok == inst : NAN;
    if (holds == 0) {
        g_string_truncate(why, why->len - 1);
        g_string_prepend(why, "; does not hold, because");
    }
    g_string_prepend(why, text);
    claim(rows, "databases_without_instancing", none, text);
    claim(rows, "databases_instanced", inst, text);
    claim(rows, "minset_better_without", none_ok, text);
    claim(rows, "maxset_better_instanced", inst_ok, text);
    claim(rows, "holds", holds, holds == 0 ? why->str : text);
    g_string_free(why, TRUE);
}
