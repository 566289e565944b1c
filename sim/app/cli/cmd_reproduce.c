/* cmd_reproduce.c — `pgsim reproduce NAME|all [--format text|csv|json]
 * [--out DIR] [--fidelity faithful|analytic|flow|packet|all] [--papers DIR]
 * [--quiet] [--set machine.KEY=VALUE]... [--models DIR]...`.
 *
 * --set changes the machine of every run a paper makes (after the
 * paper's own overrides: a what-if on the paper's machine); only
 * machine.* keys, since the workloads and scenes are the paper's.
 * --models DIR adds a model folder, searched before the shipped models
 * (after ./models and $PGSIM_MODELS; sim/machine/model_find.h).  Both are
 * in every table's provenance with each model and scene file read, by
 * path and SHA-256; a model from outside the shipped folder is named in
 * the first lines of the text table.
 *
 * Runs paper reproductions (sim/reproduce/reproduce.h), joins them to the
 * published values in configs/papers/<name>/published.yaml and prints the
 * tables in the chosen format on stdout.  With --out DIR each reproduction's
 * table is also written, atomically, as DIR/<name>.{txt,csv,json} (and, with
 * --fidelity all, the chart DIR/<name>-speed.png).  `all` also writes the
 * Markdown report when asked where: --doc FILE, or DIR/reproduction.md
 * under --out DIR, with charts in <its directory>/reproduction/; never
 * into the current directory unasked.  Progress (which simulation a
 * paper is on, how long it has run) is one line on a terminal only.
 *
 * `all -j N` (default: the number of cores) runs up to N papers at once
 * (costliest first by RpPaperOps.cost_s; NAME,NAME... runs a list like
 * `all`),
 * each in a worker process of the pool that sweeps use too
 * (sim/app/pool/pool.h), without progress lines: the worker sends its
 * stdout text and its report section back on its pipe, and the parent,
 * once every worker has ended, prints and joins them in the registry's
 * order, so the output is the one of -j 1 (wall-time figures aside).  A
 * worker that fails, or dies, fails the command with the first such
 * paper's error in registry order.
 */
#include "sim/core/datapath.h"
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/app/pool/pool.h"
#include "sim/reproduce/rp_doc.h"
#include "sim/reproduce/rp_driver.h"
#include "sim/reproduce/rp_speed.h"
#include <stdio.h>
#include <string.h>

typedef enum { FMT_TEXT, FMT_CSV, FMT_JSON } RpFormat;

typedef struct {
    char *format;
    char *out_dir;
    char *fidelity;
    char *papers;
    char *doc;
    gboolean quiet;
    int jobs;
    char **sets;   /* --set machine.KEY=VALUE, NULL-terminated */
    char **models; /* --models DIR, NULL-terminated */
    RpFormat fmt;
    const RpPaperOps **list; /* `all` or NAME,NAME...: the papers, in order */
    int n_list;
} RpOpts;

static gboolean parse_format(RpOpts *o, GError **err)
{
    static const char *const names[] = {"text", "csv", "json"};
    for (int i = 0; i < 3; i++)
        if (strcmp(o->format, names[i]) == 0) {
            o->fmt = (RpFormat)i;
            return TRUE;
        }
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "--format: found '%s', expected text, csv or json", o->format);
    return FALSE;
}

/* FALSE when the caller should return *status (help, or a bad option). */
static gboolean parse_opts(RpOpts *o, int *argc, char ***argv, int *status)
{
    GOptionEntry entries[] = {
        {"format", 0, 0, G_OPTION_ARG_STRING, &o->format,
         "text (default), csv or json", "FMT"},
        {"out", 0, 0, G_OPTION_ARG_FILENAME, &o->out_dir,
         "also write <name>.{txt,csv,json} and charts here", "DIR"},
        {"fidelity", 0, 0, G_OPTION_ARG_STRING, &o->fidelity,
         "faithful (default: each machine model's own transport), "
         "analytic, flow, packet or all",
         "F"},
        {"papers", 0, 0, G_OPTION_ARG_FILENAME, &o->papers,
         "published values (default configs/papers)", "DIR"},
        {"doc", 0, 0, G_OPTION_ARG_FILENAME, &o->doc,
         "with 'all': write the Markdown report to FILE (default with "
         "--out: DIR/reproduction.md; else none)",
         "FILE"},
        {"quiet", 'q', 0, G_OPTION_ARG_NONE, &o->quiet, "no progress", NULL},
        {"set", 0, 0, G_OPTION_ARG_STRING_ARRAY, &o->sets,
         "change the machine of every run (repeatable)",
         "machine.KEY=VALUE"},
        {"models", 0, 0, G_OPTION_ARG_FILENAME_ARRAY, &o->models,
         "also look for machine models in DIR (repeatable)", "DIR"},
        {"jobs", 'j', 0, G_OPTION_ARG_INT, &o->jobs,
         "with 'all' or a list: papers run at once (default: the cores)", "N"},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    if (!cli_parse("reproduce", "NAME|all|NAME,NAME...",
                   "Reruns a paper's tables and compares them with the "
                   "published values (docs/reproduction-format.md).",
                   entries, argc, argv, status))
        return FALSE;
    *status = 2;
    return cli_want_args("reproduce", "NAME|all|NAME,NAME...", *argc, *argv, 1);
}

/* --set takes machine keys only, --models existing folders. */
static gboolean check_sets(const RpOpts *o, GError **err)
{
    for (int i = 0; o->sets && o->sets[i]; i++)
        if (!g_str_has_prefix(o->sets[i], "machine.") ||
            !strchr(o->sets[i], '=')) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "--set: found '%s', expected machine.KEY=VALUE (a "
                        "reproduction's workloads and scenes are the "
                        "paper's)",
                        o->sets[i]);
            return FALSE;
        }
    for (int i = 0; o->models && o->models[i]; i++)
        if (!g_file_test(o->models[i], G_FILE_TEST_IS_DIR)) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "--models: found '%s', expected a folder of machine "
                        "models",
                        o->models[i]);
            return FALSE;
        }
    return TRUE;
}

static gboolean check_opts(RpOpts *o, GError **err)
{
    if (!o->format)
        o->format = g_strdup("text");
    if (!o->fidelity)
        o->fidelity = g_strdup(RP_DEFAULT_FIDELITY);
    if (o->jobs < 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "--jobs: found %d, expected a count >= 1", o->jobs);
        return FALSE;
    }
    if (o->jobs == 0)
        o->jobs = (int)g_get_num_processors();
    if (!rp_fidelity_valid(o->fidelity) && strcmp(o->fidelity, "all")) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "--fidelity: found '%s', expected faithful, analytic, "
                    "flow, packet or all",
                    o->fidelity);
        return FALSE;
    }
    return check_sets(o, err) && parse_format(o, err);
}

/* passes: one RpTable, or one per fidelity for --fidelity all. */
static void format_passes(const GPtrArray *passes, RpFormat f, gboolean first,
                          GString *out)
{
    gboolean speed = passes->len > 1;
    const RpTable *t = g_ptr_array_index(passes, 0);
    if (f == FMT_TEXT) {
        if (!first)
            g_string_append_c(out, '\n');
        if (speed)
            rp_speed_text(passes, out);
        else
            rp_table_text(t, out);
    } else if (f == FMT_CSV) {
        if (speed)
            rp_speed_csv(passes, first, out);
        else
            rp_table_csv(t, first, out);
    } else {
        if (speed)
            rp_speed_json(passes, out);
        else
            rp_table_json(t, out);
        g_string_append_c(out, '\n');
    }
}

static gboolean write_file(const char *dir, const char *name, const char *ext,
                           const GString *s, GError **err)
{
    char *file = g_strconcat(name, ".", ext, NULL);
    char *path = g_build_filename(dir, file, NULL);
    gboolean ok = sim_file_write(path, s->str, s->len, err);
    g_free(path);
    g_free(file);
    return ok;
}

static gboolean write_outputs(const GPtrArray *passes, const char *dir,
                              GError **err)
{
    static const char *const ext[] = {"txt", "csv", "json"};
    const RpTable *t = g_ptr_array_index(passes, 0);
    if (g_mkdir_with_parents(dir, 0777) != 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot create", dir);
        return FALSE;
    }
    for (int f = 0; f < 3; f++) {
        GString *s = g_string_new(NULL);
        format_passes(passes, (RpFormat)f, TRUE, s);
        gboolean ok = write_file(dir, t->paper, ext[f], s, err);
        g_string_free(s, TRUE);
        if (!ok)
            return FALSE;
    }
    return passes->len < 2 || rp_speed_chart(passes, dir, err);
}

static GPtrArray *run_passes(const RpPaperOps *rp, const RpOpts *o,
                             RptProgress *bar, GError **err)
{
    RpContext ctx = {.fidelity = o->fidelity,
                     .out_dir = o->out_dir,
                     .quiet = o->quiet || !bar,
                     .progress = bar,
                     .sets = (const char *const *)o->sets,
                     .models = (const char *const *)o->models};
    if (strcmp(o->fidelity, "all") == 0)
        return rp_drive_fidelities(rp, o->papers, &ctx, err);
    RpTable *t = rp_drive(rp, o->papers, &ctx, err);
    if (!t)
        return NULL;
    GPtrArray *passes =
        g_ptr_array_new_with_free_func((GDestroyNotify)rp_table_free);
    g_ptr_array_add(passes, t);
    return passes;
}

/* Runs one reproduction, formats it into text and writes --out files;
 * returns its passes (the caller frees them) or NULL with *err. */
static GPtrArray *run_one_into(const RpPaperOps *rp, const RpOpts *o,
                               gboolean first, GString *text, GError **err)
{
    char *label = g_strdup_printf("reproduce %s (fidelity %s), runs", rp->name,
                                  o->fidelity);
    RptProgress *bar = o->quiet ? NULL : rpt_progress_new(0, label);
    g_free(label);
    GPtrArray *passes = run_passes(rp, o, bar, err);
    rpt_progress_finish(bar);
    if (!passes)
        return NULL;
    format_passes(passes, o->fmt, first, text);
    if (o->out_dir && !write_outputs(passes, o->out_dir, err)) {
        g_ptr_array_free(passes, TRUE);
        return NULL;
    }
    return passes;
}

/* The same, printed on stdout. */
static GPtrArray *run_one(const RpPaperOps *rp, const RpOpts *o, gboolean first,
                          GError **err)
{
    GString *s = g_string_new(NULL);
    GPtrArray *passes = run_one_into(rp, o, first, s, err);
    fputs(s->str, stdout);
    fflush(stdout);
    g_string_free(s, TRUE);
    return passes;
}

static GHashTable *captions_of(const RpPaperOps *rp, const RpOpts *o)
{
    char *path = rp_paper_path(o->papers ? o->papers : RP_PAPERS_DIR, rp->name);
    RpPaper *p = rp_paper_load(path, NULL);
    g_free(path);
    if (!p)
        return NULL;
    GHashTable *c = g_hash_table_ref(p->captions);
    rp_paper_free(p);
    return c;
}

/* Adds one paper's section (and its charts) to the report. */
static gboolean doc_paper(GString *md, const RpPaperOps *rp,
                          const GPtrArray *passes, const RpOpts *o,
                          const char *chart_dir, GError **err)
{
    const RpTable *fin = g_ptr_array_index(passes, passes->len - 1);
    if (g_mkdir_with_parents(chart_dir, 0777) != 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot create",
                    chart_dir);
        return FALSE;
    }
    if (!rp_doc_chart(fin, chart_dir, err) ||
        (passes->len > 1 && !rp_speed_chart(passes, chart_dir, err)))
        return FALSE;
    GHashTable *caps = captions_of(rp, o);
    rp_doc_paper(md, passes, caps, chart_dir, "reproduction");
    if (caps)
        g_hash_table_unref(caps);
    return TRUE;
}

/* Where `all` writes its report: --doc, else DIR/reproduction.md under
 * --out, else nowhere (NULL). */
static char *doc_path(const RpOpts *o)
{
    if (o->doc)
        return g_strdup(o->doc);
    return o->out_dir ? g_build_filename(o->out_dir, "reproduction.md", NULL)
                      : NULL;
}

/* Paper i of `all`: its stdout text into text and, when md is given, its
 * section (charts written on the way). */
static gboolean paper_all(int i, const RpOpts *o, const char *charts,
                          GString *text, GString *md, GError **err)
{
    const RpPaperOps *rp = o->list[i];
    GPtrArray *passes = run_one_into(rp, o, i == 0, text, err);
    gboolean ok = passes && (!md || doc_paper(md, rp, passes, o, charts, err));
    if (passes)
        g_ptr_array_free(passes, TRUE);
    return ok;
}

/* ---- -j: one worker process per paper (sim/app/pool) ---------------- */

typedef struct {
    const RpOpts *o;
    const char *charts;
    gboolean want_md;
} RpWork;

/* In the child: "O<text length>\n<text><md>" or "E<code>\n<msg>". */
static char *paper_work(void *ctx, guint i, gsize *len)
{
    const RpWork *w = ctx;
    RpOpts quiet = *w->o;
    quiet.quiet = TRUE; /* progress lines of parallel papers would mix */
    GString *text = g_string_new(NULL), *md = g_string_new(NULL);
    GString *out = g_string_new(NULL);
    GError *e = NULL;
    if (paper_all((int)i, &quiet, w->charts, text, w->want_md ? md : NULL, &e))
        g_string_printf(out, "O%zu\n%s%s", text->len, text->str, md->str);
    else
        g_string_printf(out, "E%d\n%s", e->code, e->message);
    *len = out->len;
    return g_string_free(out, FALSE);
}

/* Prints paper i's text and appends its section, from its worker's
 * output. */
static gboolean join_paper(const PoolResult *r, const char *name, GString *md,
                           GError **err)
{
    const char *buf = r->out->str, *rest;
    char *end = NULL;
    gsize len = r->out->len;
    gboolean read = !r->fail && len > 1;
    guint64 n = read ? g_ascii_strtoull(buf + 1, &end, 10) : 0;
    rest = end ? end + 1 : NULL;
    gboolean ok = read && buf[0] == 'O' && end && *end == '\n' &&
                  n <= len - (gsize)(rest - buf);
    if (ok) {
        fwrite(rest, 1, n, stdout);
        if (md)
            g_string_append_len(md, rest + n, (gssize)(len - (rest - buf) - n));
    } else if (read && buf[0] == 'E') {
        int code = (int)g_ascii_strtoll(buf + 1, &end, 10);
        g_set_error(err, SIM_ERROR, code, "%s", *end ? end + 1 : end);
    } else {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                    "reproduce %s: the worker ended without a result (%s)",
                    name, r->fail ? r->fail : "no output");
    }
    return ok;
}

/* The order in which -j starts the papers: costliest first (by their
 * cost_s hint; ties in list order), so that a long paper does not start
 * last and run alone (longest processing time first, Graham 1969). */
static guint *spawn_order(const RpOpts *o)
{
    guint *ord = g_new(guint, o->n_list);
    for (int i = 0; i < o->n_list; i++) {
        int j = i;
        for (; j > 0 && o->list[ord[j - 1]]->cost_s < o->list[i]->cost_s; j--)
            ord[j] = ord[j - 1];
        ord[j] = (guint)i;
    }
    return ord;
}

/* Runs every paper, up to o->jobs at once, then joins them in order. */
static gboolean papers_forked(const RpOpts *o, GString *md, const char *charts,
                              GError **err)
{
    guint n = (guint)o->n_list;
    if (!o->quiet)
        fprintf(stderr, "reproduce: %u papers, %d at once\n", n, o->jobs);
    RpWork w = {o, charts, md != NULL};
    guint *ord = spawn_order(o);
    PoolResult *r = pool_map(n, ord, paper_work, &w, o->jobs, err);
    gboolean ok = r != NULL;
    for (guint i = 0; ok && i < n; i++)
        ok = join_paper(&r[i], o->list[i]->name, md, err);
    fflush(stdout);
    pool_results_free(r, n);
    g_free(ord);
    return ok;
}

/* Runs every paper; adds each to md under chart_dir when md is given. */
static gboolean run_papers(const RpOpts *o, GString *md, const char *charts,
                           GError **err)
{
    if (o->jobs > 1 && o->n_list > 1)
        return papers_forked(o, md, charts, err);
    gboolean ok = TRUE;
    for (int i = 0; ok && i < o->n_list; i++) {
        const RpPaperOps *rp = o->list[i];
        GPtrArray *passes = run_one(rp, o, i == 0, err);
        ok = passes && (!md || doc_paper(md, rp, passes, o, charts, err));
        if (passes)
            g_ptr_array_free(passes, TRUE);
    }
    return ok;
}

static gboolean write_report(const RpOpts *o, const char *doc, GError **err)
{
    char *dir = g_path_get_dirname(doc);
    char *charts = g_build_filename(dir, "reproduction", NULL);
    GString *md = g_string_new(NULL);
    rp_doc_head(md, o->fidelity);
    gboolean ok = run_papers(o, md, charts, err);
    if (o->n_list == 0)
        g_string_append(md, "No reproduction is registered yet.\n");
    if (ok && g_mkdir_with_parents(dir, 0777) != 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: cannot create", dir);
        ok = FALSE;
    }
    ok = ok && sim_file_write(doc, md->str, md->len, err);
    if (ok && !o->quiet)
        fprintf(stderr, "reproduce: wrote %s\n", doc);
    g_string_free(md, TRUE);
    g_free(charts);
    g_free(dir);
    return ok;
}

static gboolean run_all(const RpOpts *o, GError **err)
{
    char *doc = doc_path(o);
    gboolean ok =
        doc ? write_report(o, doc, err) : run_papers(o, NULL, NULL, err);
    if (ok && !doc && !o->quiet)
        fprintf(stderr, "reproduce: no report written (--doc FILE or --out "
                        "DIR writes the Markdown report)\n");
    g_free(doc);
    return ok;
}

static void unknown_paper(const char *name, GError **err)
{
    GString *known = g_string_new("all");
    for (int i = 0; rp_all[i]; i++)
        g_string_append_printf(known, ", %s", rp_all[i]->name);
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "reproduce: found '%s', expected one of: %s (or several "
                "names joined by commas)",
                name, known->str);
    g_string_free(known, TRUE);
}

/* `all`, or NAME[,NAME...] (each once): the papers a run covers. */
static gboolean pick_papers(const char *arg, RpOpts *o, GError **err)
{
    int n = 0;
    while (rp_all[n])
        n++;
    o->list = g_new0(const RpPaperOps *, n + 1);
    if (strcmp(arg, "all") == 0) {
        memcpy(o->list, rp_all, (size_t)n * sizeof *o->list);
        o->n_list = n;
        return TRUE;
    }
    char **names = g_strsplit(arg, ",", -1);
    gboolean ok = TRUE;
    for (int i = 0; ok && names[i]; i++) {
        const RpPaperOps *rp = rp_find(names[i]);
        gboolean twice = FALSE;
        for (int j = 0; rp && j < o->n_list; j++)
            twice = twice || o->list[j] == rp;
        ok = rp && !twice;
        if (ok)
            o->list[o->n_list++] = rp;
        else if (twice)
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "reproduce: found '%s' twice, expected each paper "
                        "once",
                        names[i]);
        else
            unknown_paper(names[i], err);
    }
    g_strfreev(names);
    return ok;
}

/* One name runs that paper alone; `all` or a list of names runs them as
 * `all` does (report, -j). */
static gboolean run_named(const char *arg, RpOpts *o, GError **err)
{
    if (!pick_papers(arg, o, err))
        return FALSE;
    if (strcmp(arg, "all") == 0 || strchr(arg, ','))
        return run_all(o, err);
    GPtrArray *passes = run_one(o->list[0], o, TRUE, err);
    if (passes)
        g_ptr_array_free(passes, TRUE);
    return passes != NULL;
}

int cmd_reproduce(int argc, char **argv)
{
    RpOpts o = {0};
    GError *err = NULL;
    int status = 0;
    if (parse_opts(&o, &argc, &argv, &status)) {
        status = 0;
        if (!check_opts(&o, &err) || !run_named(argv[1], &o, &err))
            status = cli_fail(err);
    }
    g_free(o.format);
    g_free(o.out_dir);
    g_free(o.fidelity);
    g_free(o.papers);
    g_free(o.doc);
    g_strfreev(o.sets);
    g_strfreev(o.models);
    g_free(o.list);
    return status;
}
