/* sweep_run.c — running sweep points: one line per point, the master's
 * bookkeeping, and points in forked workers.
 *
 * Workers are the process pool's (sim/app/pool/pool.h: at most `jobs`
 * children, one per point); a worker's output becomes the point's line,
 * and a non-zero exit, a signal or anything but one complete line
 * becomes the point's error line.  Output order is the log's business
 * (sweep_log_finish sorts).  O(points).
 */
#include "sim/app/sweep/sweep_run.h"
#include "sim/app/pool/pool.h"
#include "sim/output/json.h"
#include <math.h>
#include "sim/output/provenance.h"
#include <string.h>

/* ---- lines ----------------------------------------------------------- */

/* A parameter value: a JSON number when its text is one, else a string. */
static void add_value(JsonBuilder *b, const char *text)
{
    JsonNode *v = js_parse(text, -1, NULL, NULL);
    if (js_is_num(v))
        json_builder_add_value(b, json_node_copy(v));
    else
        js_add_str(b, text);
    if (v)
        json_node_unref(v);
}

/* Opens the point's object: point, repetition, seed, parameter values. */
static JsonBuilder *line_head(const SweepSpec *s, guint i)
{
    SweepPoint pt = sweep_spec_point(s, i);
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_int(b, "point", pt.index);
    js_set_int(b, "repetition", pt.rep);
    js_set_int(b, "seed", (gint64)pt.seed);
    for (guint p = 0; p < s->params->len; p++) {
        const SweepParam *sp = g_ptr_array_index(s->params, p);
        json_builder_set_member_name(b, sp->key);
        add_value(b, sweep_spec_value(s, &pt, p));
    }
    return b;
}

/* Closes the object and returns it as one line ending in '\n'. */
static char *line_finish(JsonBuilder *b)
{
    json_builder_end_object(b);
    char *one = js_finish(b, FALSE);
    char *line = g_strconcat(one, "\n", NULL);
    g_free(one);
    return line;
}

char *sweep_point_error_line(const SweepSpec *s, guint i, const char *msg)
{
    JsonBuilder *b = line_head(s, i);
    js_set_str(b, "status", "error");
    js_set_str(b, "error", msg);
    return line_finish(b);
}

/* node_memory (B) and memory_fits (1 or 0): null where the model gives
 * no node memory or the workload reports no per-node footprint. */
static void put_memory(JsonBuilder *b, const SimResult *r)
{
    if (r->mem_node)
        js_set_num(b, "node_memory", (double)r->mem_node);
    else
        js_set_str(b, "node_memory", NULL);
    if (r->mem_node && isfinite(r->mem_peak))
        js_set_num(b, "memory_fits", sim_result_mem_exceeds(r) ? 0 : 1);
    else
        js_set_str(b, "memory_fits", NULL);
}

static void put_result(JsonBuilder *b, const SimResult *r)
{
    SimUtilUsed u = sim_result_util_used(r); /* idle ones apart */
    js_set_num(b, "frames", r->frame_times->len);
    js_set_num(b, "mean_frame_s", sim_result_mean_frame_s(r));
    js_set_num(b, "elapsed_s", sim_time_to_s(r->elapsed));
    js_set_num(b, "events", (double)r->events);
    js_set_num(b, "comm_bytes", (double)r->comm_bytes);
    js_set_num(b, "comm_messages", (double)r->comm_messages);
    js_set_num(b, "util_mean", u.mean);
    js_set_num(b, "util_max", u.max);
    js_set_num(b, "nodes_used", (double)u.used);
    js_set_num(b, "nodes_idle", (double)u.idle);
    put_memory(b, r);
    for (guint m = 0; m < r->metrics->len; m++) {
        const SimMetric *sm = g_ptr_array_index(r->metrics, m);
        js_set_num(b, sm->name, sm->value);
    }
    json_builder_set_member_name(b, SWEEP_INPUTS_KEY); /* not a column */
    prov_inputs_json(b, r->inputs);
}

char *sweep_point_line(const SweepSpec *s, guint i, SweepRunFn fn)
{
    SweepPoint pt = sweep_spec_point(s, i);
    GError *err = NULL;
    SimResult *r = NULL;
    CfgNode *cfg = sweep_spec_config(s, &pt, &err);
    gboolean ok = cfg && fn(cfg, pt.seed, &r, &err);
    cfg_free(cfg);
    if (!ok) {
        char *line =
            sweep_point_error_line(s, i, err ? err->message : "run failed");
        g_clear_error(&err);
        sim_result_free(r);
        return line;
    }
    JsonBuilder *b = line_head(s, i);
    js_set_str(b, "status", "ok");
    js_set_str(b, "error", NULL);
    put_result(b, r);
    sim_result_free(r);
    return line_finish(b);
}

/* ---- in worker processes (sim/app/pool) ------------------------------ */

typedef struct {
    const SweepSpec *spec;
    SweepRunFn fn;
    SweepJob *job;  /* sweep_run_local's points */
    int one;        /* sweep_point_isolated's point, or -1 once handed out */
    char *one_line; /* and its line */
} SweepPool;

static char *pool_work(void *ctx, guint i, gsize *len)
{
    const SweepPool *sp = ctx;
    char *line = sweep_point_line(sp->spec, i, sp->fn);
    *len = strlen(line);
    return line;
}

/* The point's line from what its worker wrote: an error line when the
 * worker failed or did not write exactly one complete line. */
static char *worker_line(const SweepSpec *s, guint i, const GString *out,
                         const char *fail)
{
    if (fail)
        return sweep_point_error_line(s, i, fail);
    if (out->len == 0 || out->str[out->len - 1] != '\n' ||
        memchr(out->str, '\n', out->len - 1))
        return sweep_point_error_line(s, i, "worker wrote no complete line");
    return g_strdup(out->str);
}

static gboolean one_next(void *ctx, guint *i)
{
    SweepPool *sp = ctx;
    if (sp->one < 0)
        return FALSE;
    *i = (guint)sp->one;
    sp->one = -1;
    return TRUE;
}

static gboolean one_done(void *ctx, guint i, const GString *out,
                         const char *fail, GError **err)
{
    (void)err;
    SweepPool *sp = ctx;
    sp->one_line = worker_line(sp->spec, i, out, fail);
    return TRUE;
}

char *sweep_point_isolated(const SweepSpec *s, guint i, SweepRunFn fn)
{
    static const PoolOps ops = {one_next, pool_work, one_done};
    SweepPool sp = {s, fn, NULL, (int)i, NULL};
    GError *err = NULL;
    if (!pool_run(&ops, &sp, 1, &err)) {
        g_clear_error(&err);
        return sweep_point_error_line(s, i, "cannot fork a worker");
    }
    return sp.one_line;
}

/* ---- the master's bookkeeping ---------------------------------------- */

void sweep_job_init(SweepJob *j, const SweepSpec *s, SweepLog *log,
                    SweepRunFn fn, gboolean progress)
{
    *j = (SweepJob){.spec = s, .log = log, .fn = fn};
    j->todo = g_array_new(FALSE, FALSE, sizeof(guint));
    for (guint i = 0; i < sweep_spec_points(s); i++)
        if (!log || !sweep_log_done(log, i))
            g_array_append_val(j->todo, i);
    if (progress && j->todo->len) {
        char *label = g_strdup_printf("sweep %s: points", s->name);
        j->bar = rpt_progress_new(j->todo->len, label);
        g_free(label);
        rpt_progress_note(j->bar, "0 failed");
    }
}

void sweep_job_clear(SweepJob *j)
{
    g_array_free(j->todo, TRUE);
    j->todo = NULL;
}

gboolean sweep_job_next(SweepJob *j, guint *i)
{
    if (j->next >= j->todo->len)
        return FALSE;
    *i = g_array_index(j->todo, guint, j->next++);
    return TRUE;
}

static gboolean line_failed(const char *line)
{
    JsonNode *v = js_parse(line, -1, NULL, NULL);
    const char *status = js_str(js_get(v, "status"));
    gboolean failed = status && strcmp(status, "error") == 0;
    if (v)
        json_node_unref(v);
    return failed;
}

gboolean sweep_job_finish(SweepJob *j, const char *line, GError **err)
{
    j->finished++;
    if (line_failed(line)) {
        j->failed++;
        char note[32];
        g_snprintf(note, sizeof note, "%u failed", j->failed);
        rpt_progress_note(j->bar, note);
    }
    rpt_progress_update(j->bar, j->finished);
    return !j->log || sweep_log_append(j->log, line, err);
}

void sweep_job_done(SweepJob *j)
{
    rpt_progress_finish(j->bar);
    j->bar = NULL;
}

/* ---- the local pool -------------------------------------------------- */

static gboolean pool_next(void *ctx, guint *i)
{
    return sweep_job_next(((SweepPool *)ctx)->job, i);
}

static gboolean pool_done(void *ctx, guint i, const GString *out,
                          const char *fail, GError **err)
{
    SweepPool *sp = ctx;
    char *line = worker_line(sp->spec, i, out, fail);
    gboolean ok = sweep_job_finish(sp->job, line, err);
    g_free(line);
    return ok;
}

gboolean sweep_run_local(SweepJob *j, int jobs, GError **err)
{
    static const PoolOps ops = {pool_next, pool_work, pool_done};
    SweepPool sp = {j->spec, j->fn, j, -1, NULL};
    gboolean ok = pool_run(&ops, &sp, jobs, err);
    sweep_job_done(j);
    return ok;
}
