/* cmd_run.c — `pgsim run CONFIG [--set k=v]... [--fidelity F] [--seed N] [--out DIR]
 * [--format text|json|csv] [--timing] [--trace FILE] [--record FILE] [--quiet]
 * [--strict]`.
 *
 * Loads and checks the config (config.h), runs it, prints the report on
 * stdout in the chosen format and, with --out, writes summary.txt,
 * result.json and result.csv into DIR atomically.  Wall-clock figures
 * appear in the text on stdout, and in files only with --timing, so the
 * files are byte-identical across runs with the same config and seed.
 * A run whose per-node memory footprint exceeds the model's node memory
 * is warned about on stderr; with --strict it is an error (exit 2).
 */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/run/run.h"
#include "sim/app/replay/rpl_record.h"
#include "sim/app/run/outdir.h"
#include "sim/app/run/report.h"
#include "sim/app/trace/trace_file.h"
#include "sim/core/error.h"
#include <string.h>

typedef struct {
    char **sets;
    char *seed, *out, *format, *trace, *fidelity, *frames, *record;
    int trace_cap;
    gboolean quiet, timing, strict;
} RunOpts;

#define TRACE_CAP_UNSET G_MININT /* --trace-cap not given */

static const char summary[] =
    "Runs a simulation described by a YAML config (docs/config.md) and "
    "prints its report (docs/output.md).";

/* One line per kind: "KIND: op, op, ...", indented by `pad`. */
static void append_needs(GString *s, const WlNeed *needs, int pad)
{
    for (const WlNeed *n = needs; n && n->kind; n++) {
        g_string_append_printf(s, "\n%*s%s:", pad, "", n->kind);
        for (guint k = 0; n->ops[k]; k++)
            g_string_append_printf(s, "%s %s", k ? "," : "", n->ops[k]);
    }
}

/* The metrics a workload declares, one a line: "name [unit]  meaning". */
static void append_metrics(GString *s, const WlMetric *metrics)
{
    g_string_append(s, "\n      metrics:");
    for (const WlMetric *m = metrics; m && m->name; m++) {
        char *head = g_strdup_printf("%s%s%s%s", m->name, *m->unit ? " [" : "",
                                     m->unit, *m->unit ? "]" : "");
        g_string_append_printf(s, "\n        %-34s %s", head, m->meaning);
        g_free(head);
    }
}

/* The summary, then each workload (workload.type) with the costs it asks
 * a machine model for (nodes.KIND.costs.OP), those of its other modes,
 * and the metrics it reports. */
static char *help_text(void)
{
    GString *s = g_string_new(summary);
    g_string_append(s, "\n\nWorkloads (workload.type) and the costs each "
                       "needs from a machine model (nodes.KIND.costs), then the "
                       "metrics it reports (name [unit], meaning):");
    for (guint i = 0; wl_all[i]; i++) {
        const WlOps *w = wl_all[i];
        g_string_append_printf(s, "\n  %-11s %s", w->name, w->summary);
        if (!w->needs && !w->needs_alt)
            g_string_append(s, "\n      (declares none; docs/workloads.md)");
        append_needs(s, w->needs, 6);
        for (const WlNeedAlt *a = w->needs_alt; a && a->when; a++) {
            g_string_append_printf(s, "\n      %s:", a->when);
            append_needs(s, a->needs, 8);
        }
        append_metrics(s, w->metrics);
    }
    g_string_append(s, "\nKeys of each workload: docs/workloads.md.");
    return g_string_free(s, FALSE);
}

/* Checks --seed and --format; prints the error and returns FALSE. */
static gboolean check_flags(const RunOpts *o, guint64 *seed, RptFormat *fmt)
{
    GError *e = NULL;
    if (o->seed &&
        !g_ascii_string_to_unsigned(o->seed, 10, 0, G_MAXINT64, seed, NULL)) {
        fprintf(stderr,
                "pgsim run: --seed: found '%s', expected a "
                "non-negative integer\n",
                o->seed);
        return FALSE;
    }
    if (o->trace_cap != TRACE_CAP_UNSET && o->trace_cap < 1) {
        fprintf(stderr,
                "pgsim run: --trace-cap: found %d, expected a positive "
                "number of events (default %d)\n",
                o->trace_cap, TRC_DEFAULT_CAP);
        return FALSE;
    }
    if (o->format && !rpt_format_parse(o->format, fmt)) {
        fprintf(stderr,
                "pgsim run: --format: found '%s', expected one of: "
                "text, json, csv\n",
                o->format);
        return FALSE;
    }
    if (o->frames && strcmp(o->frames, "all") && strcmp(o->frames, "last")) {
        fprintf(stderr,
                "pgsim run: --frames: found '%s', expected last or all\n",
                o->frames);
        return FALSE;
    }
    g_clear_error(&e);
    return TRUE;
}

/* Names the frame images the workload wrote into dir, or says that it
 * wrote none (tokenring and performer model no pixels; others may not
 * draw in a given run) (g_free). */
static char *frame_note(const char *dir, const char *workload)
{
    char *last = g_build_filename(dir, "frame.png", NULL);
    char *first = g_build_filename(dir, "frame-0000.png", NULL);
    char *note = g_file_test(last, G_FILE_TEST_EXISTS) ? g_strdup(" and frame.png")
                 : g_file_test(first, G_FILE_TEST_EXISTS)
                     ? g_strdup(" and frame-NNNN.png")
                     : g_strdup_printf("; no frame image (this %s run "
                                       "drew no pixels)",
                                       workload);
    g_free(last);
    g_free(first);
    return note;
}

/* Prints the report; with --out, writes its files into the staging
 * folder beside the run's images and moves them all into place. */
static int report(const SimResult *res, const RunOpts *o, RptFormat fmt,
                  const char *stage)
{
    char *text = rpt_render(res, fmt, o->timing || fmt == RPT_TEXT);
    fputs(text, stdout);
    fflush(stdout);
    g_free(text);
    GError *e = NULL;
    if (stage && !rpt_write_dir(res, stage, o->timing, &e)) {
        out_stage_discard(stage);
        return cli_fail(e);
    }
    if (stage && !out_stage_commit(stage, o->out, &e))
        return cli_fail(e);
    if (o->out && !o->quiet) {
        char *note = frame_note(o->out, res->workload);
        fprintf(stderr,
                "pgsim run: wrote %s/{summary.txt,result.json,"
                "result.csv}%s\n",
                o->out, note);
        g_free(note);
    }
    return 0;
}

/* A per-node footprint above the node memory: a warning on stderr (even
 * with --quiet), or with --strict an error (FALSE: exit 2, no report). */
static gboolean feasible(const char *path, const SimResult *res,
                         gboolean strict)
{
    char *note = sim_result_mem_note(res);
    if (note)
        fprintf(stderr, "pgsim run: %s: %s: %s\n",
                strict ? "error" : "warning", path, note);
    if (note && !strict)
        fprintf(stderr, "pgsim run: (--strict makes this an error)\n");
    g_free(note);
    return !note || !strict;
}

static int run(const char *path, const RunOpts *o)
{
    guint64 seed = 0;
    RptFormat fmt = RPT_TEXT;
    if (!check_flags(o, &seed, &fmt))
        return 2;
    GError *e = NULL;
    GPtrArray *sets = g_ptr_array_new_with_free_func(g_free);
    for (char **k = o->sets; k && *k; k++)
        g_ptr_array_add(sets, g_strdup(*k));
    if (o->fidelity) /* --fidelity F is --set run.fidelity=F */
        g_ptr_array_add(sets, g_strconcat("run.fidelity=", o->fidelity, NULL));
    g_ptr_array_add(sets, NULL);
    CfgRun *r = cfg_run_load(path, (const char *const *)sets->pdata, &e);
    g_ptr_array_free(sets, TRUE);
    if (!r)
        return cli_fail(e);
    if (o->seed)
        r->seed = seed;
    SimTrace *tr = o->trace
                       ? trc_open(o->trace,
                                  o->trace_cap == TRACE_CAP_UNSET
                                      ? 0
                                      : (uint64_t)o->trace_cap,
                                  &e)
                       : NULL;
    if (o->trace && !tr) {
        cfg_run_free(r);
        return cli_fail(e);
    }
    /* everything the run writes goes to a staging folder first, so a
     * failure leaves an earlier run's --out folder as it was (outdir.h) */
    char *stage = o->out ? out_stage_new(o->out, &e) : NULL;
    if (o->out && !stage) {
        trc_discard(tr);
        cfg_run_free(r);
        return cli_fail(e);
    }
    CfgRunOpts ro = {.out_dir = stage,
                     .quiet = o->quiet,
                     .progress = TRUE,
                     .trace = tr,
                     .all_frames = o->frames && !strcmp(o->frames, "all")};
    RplRecorder *rec = o->record ? rpl_recorder_new() : NULL;
    ro.recorder = rec ? rpl_recorder_hook(rec) : NULL;
    SimResult *res = cfg_run_exec(r, &ro, &e);
    if (res && rec && !rpl_record_finish(rec, o->record, r, res, o->quiet, &e))
        g_clear_pointer(&res, sim_result_free);
    rpl_recorder_free(rec);
    cfg_run_free(r);
    if (!res || !trc_close(tr, &e)) {
        if (!res)
            trc_discard(tr); /* a failed run leaves no trace file */
        out_stage_discard(stage);
        g_free(stage);
        if (res)
            sim_result_free(res);
        return cli_fail(e);
    }
    if (!feasible(path, res, o->strict)) {
        out_stage_discard(stage);
        g_free(stage);
        sim_result_free(res);
        return 2;
    }
    int status = report(res, o, fmt, stage);
    sim_result_free(res);
    g_free(stage);
    return status;
}

int cmd_run(int argc, char **argv)
{
    RunOpts o = {.trace_cap = TRACE_CAP_UNSET};
    const GOptionEntry entries[] = {
        {"set", 0, 0, G_OPTION_ARG_STRING_ARRAY, &o.sets,
         "override a config key (repeatable)", "KEY.PATH=VALUE"},
        {"fidelity", 0, 0, G_OPTION_ARG_STRING, &o.fidelity,
         "network model: faithful (default: the machine model's own), "
         "analytic, flow or packet (overrides run.fidelity)",
         "F"},
        {"seed", 0, 0, G_OPTION_ARG_STRING, &o.seed,
         "random seed (overrides run.seed)", "N"},
        {"out", 0, 0, G_OPTION_ARG_FILENAME, &o.out,
         "write summary.txt, result.json, result.csv and the final frame "
         "(frame.png, for workloads that render one) into DIR",
         "DIR"},
        {"format", 0, 0, G_OPTION_ARG_STRING, &o.format,
         "report on stdout: text (default), json or csv", "FMT"},
        {"frames", 0, 0, G_OPTION_ARG_STRING, &o.frames,
         "with --out: images of the last frame (default) or all frames",
         "last|all"},
        {"timing", 0, 0, G_OPTION_ARG_NONE, &o.timing,
         "include wall-clock figures in JSON/CSV", NULL},
        {"trace", 0, 0, G_OPTION_ARG_FILENAME, &o.trace,
         "write a trace: FILE.json (Perfetto) or FILE.paje (ViTE)", "FILE"},
        {"trace-cap", 0, 0, G_OPTION_ARG_INT, &o.trace_cap,
         "stop tracing after N events (default 1000000)", "N"},
        {"record", 0, 0, G_OPTION_ARG_FILENAME, &o.record,
         "record a time-independent trace for `pgsim replay` "
         "(docs/traces.md; gzip if FILE ends in .gz)",
         "FILE"},
        {"quiet", 'q', 0, G_OPTION_ARG_NONE, &o.quiet,
         "no progress display or notes on stderr", NULL},
        {"strict", 0, 0, G_OPTION_ARG_NONE, &o.strict,
         "a configuration that does not fit the machine (per-node memory "
         "above the model's) is an error (exit 2), not a warning",
         NULL},
        G_OPTION_ENTRY_NULL,
    };
    int status;
    char *help = help_text();
    gboolean go = cli_parse("run", "CONFIG", help, entries, &argc, &argv,
                            &status);
    g_free(help);
    if (go)
        status = cli_want_args("run", "CONFIG", argc, argv, 1)
                     ? run(argv[1], &o)
                     : 2;
    g_strfreev(o.sets);
    g_free(o.fidelity);
    g_free(o.seed);
    g_free(o.out);
    g_free(o.format);
    g_free(o.trace);
    g_free(o.frames);
    g_free(o.record);
    return status;
}
