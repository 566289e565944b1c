/* igehy98_claims.c — the slides' "The API is scalable on a 24 processor
 * system" (seed 002, Argus "Conclusions"; the paper's abstract says
 * "achieves scalable performance on a 24 processor system") decided on
 * simulated runs (igehy98.h).  Table "claims", row scales_24:
 *
 *   <app>_hz_p<P>      the rate on P processors with C = P / contexts_per
 *                      contexts (setup.yaml: 6, 12, 24 with C = P / 3,
 *                      the slides' 8 contexts on 24);
 *   <app>_speedup      rate at the largest P over rate at the smallest;
 *   <app>_hz_c<C>      the rate against contexts on the largest P, with
 *                      <app>_peak_contexts and <app>_peak_hz;
 *   <app>_app_ms_c<C>, <app>_worker_ms_c<C>  at the most contexts: the
 *                      application time per context and the geometry
 *                      plus rasterisation time per worker (P - C) —
 *                      which side binds past the peak;
 *   <app>_shared_hz_c<C>  the same C with the workers time-sharing the
 *                      application threads' processors (`shared:`
 *                      overrides): whether the peak is the placement;
 *   holds              1 when every application's speedup is at least
 *                      efficiency x (largest P / smallest P) — our
 *                      threshold, in setup.yaml — with the reason as
 *                      the note.
 * Cost: (processors + contexts + 1) runs per application.
 */
#include "sim/reproduce/igehy98.h"
#include <math.h>

typedef struct {
    double hz, app, geo, ras;
} Fig;

static const char *const fig_names[] = {"frame_hz", "application_ms",
                                        "geometry_ms", "rasterisation_ms",
                                        NULL};

/* A list of counts (processors, contexts) from key k of c. */
static GArray *counts(const CfgNode *c, const char *k, GError **err)
{
    const CfgNode *s = cfg_get(c, k);
    if (!s || cfg_kind(s) != CFG_SEQ || cfg_seq_len(s) < 2) {
        cfg_error(err, s ? s : c, s ? "a short or non-list value" : "nothing",
                  "a list of at least two counts");
        return NULL;
    }
    GArray *a = g_array_new(FALSE, FALSE, sizeof(guint));
    for (guint i = 0; i < cfg_seq_len(s); i++) {
        const char *v = cfg_scalar(cfg_seq_at(s, i));
        guint64 n = 0;
        if (!v || !g_ascii_string_to_unsigned(v, 10, 1, 4096, &n, NULL)) {
            cfg_error(err, cfg_seq_at(s, i), v ? v : "a non-scalar",
                      "a count in [1, 4096]");
            g_array_free(a, TRUE);
            return NULL;
        }
        guint x = (guint)n;
        g_array_append_val(a, x);
    }
    return a;
}

/* The strings of list key k of c (NULL-terminated; g_strfreev). */
static char **strings(const CfgNode *c, const char *k)
{
    const CfgNode *s = cfg_get(c, k);
    guint n = s && cfg_kind(s) == CFG_SEQ ? cfg_seq_len(s) : 0;
    char **v = g_new0(char *, n + 1);
    for (guint i = 0; i < n; i++)
        v[i] = g_strdup(cfg_scalar(cfg_seq_at(s, i)));
    return v;
}

typedef struct {
    const RpContext *ctx;
    char *path;
    char **set, **shared;
    GPtrArray *rows;
    const char *app;
} Claim;

static gboolean run(Claim *c, guint P, guint C, gboolean shared, Fig *f,
                    GError **err)
{
    GPtrArray *v = g_ptr_array_new_with_free_func(g_free);
    for (guint i = 0; c->set[i]; i++)
        g_ptr_array_add(v, g_strdup(c->set[i]));
    for (guint i = 0; shared && c->shared[i]; i++)
        g_ptr_array_add(v, g_strdup(c->shared[i]));
    g_ptr_array_add(v, g_strdup_printf("workload.processors=%u", P));
    g_ptr_array_add(v, g_strdup_printf("workload.contexts=%u", C));
    g_ptr_array_add(v, NULL);
    double x[4];
    gboolean ok = rp_igehy98_metrics(c->ctx, c->path,
                                     (const char *const *)v->pdata,
                                     fig_names, x, err);
    g_ptr_array_free(v, TRUE);
    *f = (Fig){x[0], x[1], x[2], x[3]};
    return ok;
}

static void add(Claim *c, const char *col, guint n, double v)
{
    char name[64];
    if (n)
        g_snprintf(name, sizeof name, "%s_%s%u", c->app, col, n);
    else
        g_snprintf(name, sizeof name, "%s_%s", c->app, col);
    g_ptr_array_add(c->rows, rp_row_new("claims", "scales_24", name, v, NULL));
}

typedef struct {
    double speedup, need, peak_hz, app_ms, worker_ms, shared_hz;
    guint peak_c, last_c;
} Verdict;

/* One application's figures; *v gets what the note needs. */
static gboolean one_app(Claim *c, const GArray *procs, guint per,
                        const GArray *ctxs, double eff, Verdict *v,
                        GError **err)
{
    guint P0 = g_array_index(procs, guint, 0);
    guint P1 = g_array_index(procs, guint, procs->len - 1);
    double first = NAN, last = NAN;
    for (guint i = 0; i < procs->len; i++) {
        guint P = g_array_index(procs, guint, i);
        Fig f;
        if (!run(c, P, MAX(1, P / per), FALSE, &f, err))
            return FALSE;
        add(c, "hz_p", P, f.hz);
        first = i == 0 ? f.hz : first;
        last = f.hz;
    }
    v->speedup = last / first;
    v->need = eff * P1 / P0;
    add(c, "speedup", 0, v->speedup);
    v->peak_hz = -1;
    Fig f = {0};
    for (guint i = 0; i < ctxs->len; i++) {
        guint C = g_array_index(ctxs, guint, i);
        if (!run(c, P1, C, FALSE, &f, err))
            return FALSE;
        add(c, "hz_c", C, f.hz);
        if (f.hz > v->peak_hz) {
            v->peak_hz = f.hz;
            v->peak_c = C;
        }
        v->last_c = C;
    }
    add(c, "peak_contexts", 0, v->peak_c);
    add(c, "peak_hz", 0, v->peak_hz);
    v->app_ms = f.app / v->last_c;
    v->worker_ms = P1 > v->last_c ? (f.geo + f.ras) / (P1 - v->last_c) : NAN;
    add(c, "app_ms_c", v->last_c, v->app_ms);
    add(c, "worker_ms_c", v->last_c, v->worker_ms);
    Fig s;
    if (!run(c, P1, v->last_c, TRUE, &s, err))
        return FALSE;
    v->shared_hz = s.hz;
    add(c, "shared_hz_c", v->last_c, s.hz);
    return TRUE;
}

static void note_app(GString *n, const char *app, const Verdict *v,
                     guint P1)
{
    g_string_append_printf(
        n,
        "; %s: x%.2f (needed x%.2f), peak %.1f Hz at %u contexts on %u; at "
        "%u contexts the %u workers carry %.1f ms each against %.1f ms per "
        "application thread (%s binds), and with the workers sharing the "
        "application threads' processors %u contexts give %.1f Hz (%.0f%% "
        "of the peak: %s)",
        app, v->speedup, v->need, v->peak_hz, v->peak_c, P1, v->last_c,
        P1 - v->last_c, v->worker_ms, v->app_ms,
        v->worker_ms > v->app_ms ? "the workers' side" : "the application",
        v->last_c, v->shared_hz, 100 * v->shared_hz / v->peak_hz,
        v->shared_hz >= 0.9 * v->peak_hz
            ? "the fall past the peak is the model's placement of one "
              "processor per application thread, not the API"
            : "the placement does not explain the fall");
}

gboolean rp_igehy98_claims(const RpContext *ctx, const char *dir,
                           const CfgNode *claims, const CfgNode *apps,
                           GPtrArray *rows, GError **err)
{
    const CfgNode *k = NULL;
    uint64_t per = 3;
    double eff = 0.75;
    if (!cfg_get_map(claims, "scales_24", TRUE, "a map of the claim's runs",
                     &k, err) ||
        !cfg_get_count(k, "contexts_per", FALSE, 1, 4096, &per, err) ||
        !cfg_get_double(k, "efficiency", FALSE, 0, 1, &eff, err))
        return FALSE;
    GArray *procs = counts(k, "processors", err);
    GArray *ctxs = procs ? counts(k, "contexts", err) : NULL;
    if (!ctxs) {
        if (procs)
            g_array_free(procs, TRUE);
        return FALSE;
    }
    Claim c = {ctx, NULL, strings(k, "set"), strings(k, "shared"), rows, NULL};
    guint P1 = g_array_index(procs, guint, procs->len - 1);
    GString *note = g_string_new(NULL);
    gboolean ok = TRUE, all = TRUE;
    for (guint a = 0; ok && a < cfg_map_len(apps); a++) {
        c.app = cfg_map_key(apps, a);
        c.path = g_build_filename(dir, cfg_scalar(cfg_map_value(apps, a)),
                                  NULL);
        Verdict v = {0};
        ok = one_app(&c, procs, (guint)per, ctxs, eff, &v, err);
        g_free(c.path);
        if (ok) {
            all = all && v.speedup >= v.need;
            note_app(note, c.app, &v, P1);
        }
    }
    if (ok) {
        g_string_prepend(
            note, all ? "holds, because the rate grows with the processors "
                        "(contexts = processors / 3)"
                      : "does not hold, because the rate does not grow "
                        "enough with the processors (contexts = processors "
                        "/ 3)");
        g_ptr_array_add(rows, rp_row_new("claims", "scales_24", "holds",
                                         all ? 1.0 : 0.0, note->str));
    }
    g_string_free(note, TRUE);
    g_strfreev(c.set);
    g_strfreev(c.shared);
    g_array_free(procs, TRUE);
    g_array_free(ctxs, TRUE);
    return ok;
}
