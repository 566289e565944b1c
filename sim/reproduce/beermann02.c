/* beermann02.c — seed 002's statements decided on simulated runs
 * (beermann02.h): the runs of setup.yaml's `runs:` through the runner,
 * each made once, their metrics as figures "RUN.METRIC", and each claim
 * of `claims:` decided from its tests (rp_beermann02_decide) or taken
 * from another paper's claim hook (`from:`).  The sentences, the runs
 * and every threshold are in the YAML; nothing here knows a statement.
 * O(runs + tests) work beside the runs themselves.
 */
#include "sim/reproduce/beermann02.h"
#include "sim/reproduce/igehy98.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/workload/metrics.h"
#include <math.h>
#include <string.h>

/* ---- deciding a claim from figures -------------------------------------- */

/* The figure named by key k of test t ("RUN.METRIC"); FALSE with a
 * located error when the table lacks it. */
static gboolean figure(const CfgNode *t, const char *k, GHashTable *figs,
                       double *v, GError **err)
{
    const char *ref = NULL;
    if (!cfg_get_str(t, k, TRUE, &ref, err))
        return FALSE;
    const double *x = g_hash_table_lookup(figs, ref);
    if (!x) {
        cfg_error(err, cfg_get(t, k), ref,
                  "RUN.METRIC with RUN one of runs: and METRIC a metric "
                  "its workload declares");
        return FALSE;
    }
    *v = *x;
    return TRUE;
}

/* One test: its value (of, of / over or of - minus) as a column; a
 * failed check is described in why. */
static gboolean one_test(const CfgNode *t, GHashTable *figs, const char *id,
                         GPtrArray *rows, GString *why, guint *checks,
                         GError **err)
{
    const char *name = NULL;
    double of = NAN, by = NAN, lo = -INFINITY, hi = INFINITY;
    gboolean over = cfg_has(t, "over"), minus = cfg_has(t, "minus");
    if (cfg_kind(t) != CFG_MAP) {
        cfg_error(err, t, "a non-map test", "{name, of, over|minus, min, max}");
        return FALSE;
    }
    if (over && minus) {
        cfg_error(err, t, "both over and minus", "one of them");
        return FALSE;
    }
    if (!cfg_get_str(t, "name", TRUE, &name, err) ||
        !figure(t, "of", figs, &of, err) ||
        (over && !figure(t, "over", figs, &by, err)) ||
        (minus && !figure(t, "minus", figs, &by, err)) ||
        !cfg_get_double(t, "min", FALSE, -1e300, 1e300, &lo, err) ||
        !cfg_get_double(t, "max", FALSE, -1e300, 1e300, &hi, err) ||
        !cfg_check_unused(t, err))
        return FALSE;
    double v = over ? of / by : minus ? of - by : of;
    g_ptr_array_add(rows, rp_row_new("claims", id, name, v, NULL));
    if (isinf(lo) && isinf(hi))
        return TRUE; /* a figure beside the checks */
    (*checks)++;
    if (v >= lo && v <= hi)
        return TRUE;
    g_string_append_printf(why, "%s%s is %.4g", why->len ? "; " : "", name, v);
    if (over || minus)
        g_string_append_printf(why, " (%.4g %s %.4g)", of, over ? "/" : "-",
                               by);
    if (isnan(v))
        g_string_append(why, ", not a number");
    else if (v < lo)
        g_string_append_printf(why, ", below %.4g", lo);
    else
        g_string_append_printf(why, ", above %.4g", hi);
    return TRUE;
}

/* The claim's quoted sentence: slide "S": "says". */
static char *sentence(const CfgNode *claim, GError **err)
{
    const char *slide = NULL, *says = NULL, *part = NULL, *reading = NULL;
    if (!cfg_get_str(claim, "part", TRUE, &part, err) ||
        !cfg_get_str(claim, "slide", TRUE, &slide, err) ||
        !cfg_get_str(claim, "says", TRUE, &says, err) ||
        !cfg_get_str(claim, "reading", TRUE, &reading, err))
        return NULL;
    return g_strdup_printf("%s, slide \"%s\": \"%s\"", part, slide, says);
}

static void verdict(GPtrArray *rows, const char *id, const char *s,
                    double holds, const char *why, const char *if_not)
{
    char *w = if_not ? g_strdup_printf("%s (%s)", why, if_not) : NULL;
    why = w ? w : why;
    char *note = isnan(holds) ? g_strdup_printf("%s: no check", s)
                 : holds > 0.5
                     ? g_strdup_printf("%s: holds", s)
                     : g_strdup_printf("%s: does not hold, because %s", s, why);
    g_ptr_array_add(rows, rp_row_new("claims", id, "holds", holds, note));
    g_free(note);
    g_free(w);
}

gboolean rp_beermann02_decide(const char *id, const CfgNode *claim,
                              GHashTable *figures, GPtrArray *rows,
                              GError **err)
{
    const char *if_not = NULL;
    char *s = sentence(claim, err);
    if (!s || !cfg_get_str(claim, "if_not", FALSE, &if_not, err)) {
        g_free(s);
        return FALSE;
    }
    const CfgNode *tests = cfg_get(claim, "tests");
    gboolean ok = tests && cfg_kind(tests) == CFG_SEQ && cfg_seq_len(tests);
    if (!ok)
        cfg_error(err, tests ? tests : claim,
                  tests ? "an empty or non-list tests" : "no tests",
                  "tests: [{name, of, over|minus, min, max}, ...]");
    GString *why = g_string_new(NULL);
    guint checks = 0;
    for (guint i = 0; ok && i < cfg_seq_len(tests); i++)
        ok = one_test(cfg_seq_at(tests, i), figures, id, rows, why, &checks,
                      err);
    if (ok && !checks) {
        cfg_error(err, tests, "tests that check nothing",
                  "at least one test with min or max");
        ok = FALSE;
    }
    if (ok)
        verdict(rows, id, s, why->len ? 0.0 : 1.0, why->str, if_not);
    g_string_free(why, TRUE);
    g_free(s);
    return ok;
}

/* ---- the runs ------------------------------------------------------------ */

typedef struct {
    const RpContext *ctx;
    char *dir;           /* of setup.yaml */
    const CfgNode *runs; /* setup.yaml runs: */
    GHashTable *want;    /* run name -> GPtrArray of CfgNode * (refs) */
    GHashTable *figs;    /* "RUN.METRIC" -> double * */
} B2;

/* Notes the reference of key k of test t (absent: nothing). */
static gboolean note_ref(B2 *b, const CfgNode *t, const char *k, GError **err)
{
    const CfgNode *n =
        cfg_kind(t) == CFG_MAP && cfg_has(t, k) ? cfg_get(t, k) : NULL;
    const char *ref = n ? cfg_scalar(n) : NULL;
    if (!n)
        return TRUE;
    const char *dot = ref ? strchr(ref, '.') : NULL;
    char *run = dot ? g_strndup(ref, (gsize)(dot - ref)) : NULL;
    if (!run || !cfg_has(b->runs, run) || !dot[1]) {
        cfg_error(err, n, ref ? ref : "a non-scalar",
                  "RUN.METRIC with RUN one of runs:");
        g_free(run);
        return FALSE;
    }
    GPtrArray *a = g_hash_table_lookup(b->want, run);
    if (!a) {
        a = g_ptr_array_new();
        g_hash_table_insert(b->want, g_strdup(run), a);
    }
    g_ptr_array_add(a, (gpointer)n);
    g_free(run);
    return TRUE;
}

static gboolean note_claim_refs(B2 *b, const CfgNode *claim, GError **err)
{
    const CfgNode *tests =
        cfg_has(claim, "tests") ? cfg_get(claim, "tests") : NULL;
    guint n = tests && cfg_kind(tests) == CFG_SEQ ? cfg_seq_len(tests) : 0;
    for (guint i = 0; i < n; i++) {
        const CfgNode *t = cfg_seq_at(tests, i);
        if (!note_ref(b, t, "of", err) || !note_ref(b, t, "over", err) ||
            !note_ref(b, t, "minus", err))
            return FALSE;
    }
    return TRUE;
}

/* Runs `name` once and records the metrics its tests read. */
static gboolean one_run(B2 *b, const char *name, GPtrArray *refs, GError **err)
{
    const CfgNode *run = cfg_get(b->runs, name);
    const char *rel = NULL;
    if (cfg_kind(run) != CFG_MAP) {
        cfg_error(err, run, "a non-map run", "{config: PATH, set: [...]}");
        return FALSE;
    }
    char **sets = NULL;
    if (!cfg_get_str(run, "config", TRUE, &rel, err) ||
        !(sets = rp_sets_of(run, err)) || !cfg_check_unused(run, err)) {
        g_strfreev(sets);
        return FALSE;
    }
    char *path = g_build_filename(b->dir, rel, NULL);
    char *what = g_strdup_printf("beermann02 %s", name);
    rp_step(b->ctx, what);
    g_free(what);
    CfgRun *r =
        rp_run_build(b->ctx, NULL, path, (const char *const *)sets, err);
    g_free(path);
    g_strfreev(sets);
    SimResult *res = r ? rp_run_exec(b->ctx, r, NULL, err) : NULL;
    cfg_run_free(r);
    if (!res)
        return FALSE;
    const WlOps *ops = res->workload ? wl_find(res->workload) : NULL;
    gboolean ok = TRUE;
    for (guint i = 0; ok && i < refs->len; i++) {
        const CfgNode *n = refs->pdata[i];
        const char *ref = cfg_scalar(n), *metric = strchr(ref, '.') + 1;
        if (!ops || !wl_metric_decl(ops, metric)) {
            cfg_error(err, n, ref, "a metric the run's workload declares");
            ok = FALSE;
            break;
        }
        double *v = g_new(double, 1);
        if (!wl_get_metric(res, metric, v))
            *v = NAN;
        g_hash_table_replace(b->figs, g_strdup(ref), v);
    }
    sim_result_free(res);
    return ok;
}

/* ---- a claim another paper decides --------------------------------------- */

static const char *const from_papers[] = {"igehy98", NULL};

/* Whether column c of the other paper's claim is taken: its verdict,
 * the speed-ups and the rates against processors. */
static gboolean taken(const char *c)
{
    return !strcmp(c, "holds") || g_str_has_suffix(c, "_speedup") ||
           strstr(c, "_hz_p") != NULL;
}

/* `from: {paper, claim, setup}`: the other paper's claim hook on its
 * own setup; its rows of that claim become this claim's. */
static gboolean from_claim(B2 *b, const char *id, const CfgNode *claim,
                           GPtrArray *rows, GError **err)
{
    const CfgNode *f = NULL;
    const char *name = NULL, *rel = NULL;
    int paper = 0;
    char *s = sentence(claim, err);
    if (!s ||
        !cfg_get_map(claim, "from", TRUE, "{paper, claim, setup}", &f, err) ||
        !cfg_get_enum(f, "paper", TRUE, from_papers, &paper, err) ||
        !cfg_get_str(f, "claim", TRUE, &name, err) ||
        !cfg_get_str(f, "setup", TRUE, &rel, err) ||
        !cfg_check_unused(claim, err)) {
        g_free(s);
        return FALSE;
    }
    char *path = g_build_filename(b->dir, rel, NULL);
    CfgNode *root = cfg_load_file(path, err);
    char *dir = g_path_get_dirname(path);
    g_free(path);
    const CfgNode *claims = NULL, *apps = NULL;
    GPtrArray *got = g_ptr_array_new_with_free_func(rp_row_free);
    gboolean ok =
        root &&
        cfg_get_map(root, "claims", TRUE, "the paper's claims", &claims, err) &&
        cfg_get_map(root, "applications", TRUE, "the paper's applications",
                    &apps, err);
    if (ok && !cfg_has(claims, name)) {
        cfg_error(err, cfg_get(f, "claim"), name,
                  "a claim of that paper's setup");
        ok = FALSE;
    }
    rp_step(b->ctx, "beermann02 igehy98 claim");
    ok = ok && rp_igehy98_claims(b->ctx, dir, claims, apps, got, err);
    double holds = NAN;
    const char *note = "";
    for (guint i = 0; ok && i < got->len; i++) {
        const RpRow *r = got->pdata[i];
        if (strcmp(r->table, "claims") || strcmp(r->row, name) ||
            !taken(r->column))
            continue;
        if (!strcmp(r->column, "holds")) {
            holds = r->sim;
            note = r->note ? r->note : "";
        } else
            g_ptr_array_add(rows,
                            rp_row_new("claims", id, r->column, r->sim, NULL));
    }
    if (ok) {
        char *why = g_strdup_printf("%s (pgsim reproduce %s, claims %s)", note,
                                    from_papers[paper], name);
        char *n = g_strdup_printf("%s: %s", s, why);
        g_ptr_array_add(rows, rp_row_new("claims", id, "holds", holds, n));
        g_free(n);
        g_free(why);
    }
    g_ptr_array_free(got, TRUE);
    cfg_free(root);
    g_free(dir);
    g_free(s);
    return ok;
}

/* ---- the paper ------------------------------------------------------------
 */

/* Whether claim i of claims is one `only` asks for (NULL: all). */
static gboolean wanted(const CfgNode *claims, guint i, const char *only)
{
    return !only || !strcmp(cfg_map_key(claims, i), only);
}

/* Runs every run the wanted claims read; b->figs gets their figures. */
static gboolean make_runs(B2 *b, const CfgNode *claims, const char *only,
                          GError **err)
{
    gboolean ok = TRUE;
    for (guint i = 0; ok && i < cfg_map_len(claims); i++)
        if (wanted(claims, i, only))
            ok = note_claim_refs(b, cfg_map_value(claims, i), err);
    /* in the file's order, so progress and errors are deterministic */
    for (guint i = 0; ok && i < cfg_map_len(b->runs); i++) {
        const char *name = cfg_map_key(b->runs, i);
        GPtrArray *refs = g_hash_table_lookup(b->want, name);
        if (refs)
            ok = one_run(b, name, refs, err);
        else if (!only) {
            cfg_error(err, cfg_map_value(b->runs, i), name,
                      "a run some claim's test reads");
            ok = FALSE;
        } else
            cfg_mark_read(cfg_map_value(b->runs, i));
    }
    return ok;
}

gboolean rp_beermann02_claims(const RpContext *ctx, const CfgNode *root,
                              const char *dir, const char *only,
                              GPtrArray *rows, GHashTable **figures,
                              GError **err)
{
    B2 b = {ctx, g_strdup(dir), NULL,
            g_hash_table_new_full(g_str_hash, g_str_equal, g_free,
                                  (GDestroyNotify)g_ptr_array_unref),
            g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free)};
    const CfgNode *claims = NULL;
    gboolean ok =
        cfg_get_map(root, "runs", TRUE, "a map of runs", &b.runs, err) &&
        cfg_get_map(root, "claims", TRUE, "a map of claims", &claims, err) &&
        make_runs(&b, claims, only, err);
    guint decided = 0;
    for (guint i = 0; ok && i < cfg_map_len(claims); i++) {
        const char *id = cfg_map_key(claims, i);
        const CfgNode *c = cfg_map_value(claims, i);
        if (!wanted(claims, i, only)) {
            cfg_mark_read(c);
            continue;
        }
        decided++;
        ok = cfg_has(c, "from")
                 ? from_claim(&b, id, c, rows, err)
                 : rp_beermann02_decide(id, c, b.figs, rows, err);
    }
    if (ok && !decided) {
        cfg_error(err, claims, only, "the id of a claim");
        ok = FALSE;
    }
    ok = ok && cfg_check_unused(root, err);
    g_hash_table_destroy(b.want);
    if (figures && ok)
        *figures = b.figs;
    else
        g_hash_table_destroy(b.figs);
    g_free(b.dir);
    return ok;
}

static gboolean beermann02_run(const RpContext *ctx, GPtrArray *rows,
                               GError **err)
{
    CfgNode *root = cfg_load_file(ctx->setup, err);
    if (!root)
        return FALSE;
    char *dir = g_path_get_dirname(ctx->setup);
    gboolean ok = rp_beermann02_claims(ctx, root, dir, NULL, rows, NULL, err);
    g_free(dir);
    cfg_free(root);
    return ok;
}

const RpPaperOps rp_beermann02 = {
    .name = "beermann02",
    .citation = "beermann02: seed 002's slides (Beermann, Interfaces and "
                "Software Systems: IRIS Performer, Argus, Curved PN "
                "triangles), each statement decided on simulated runs",
    .setup = "setup.yaml",
    .rows = beermann02_run,
    .cost_s = 4.5, /* measured: user time of `pgsim reproduce beermann02` */
};
