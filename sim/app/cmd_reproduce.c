/* cmd_reproduce.c — `pgsim reproduce NAME|all [--format text|csv|json]
 * [--out DIR] [--fidelity analytic|flow|packet|all] [--papers DIR]
 * [--quiet]`.
 *
 * Runs paper reproductions (sim/app/reproduce.h), joins them to the
 * published values in configs/papers/<name>.yaml and prints the tables in
 * the chosen format on stdout.  With --out DIR each reproduction's table
 * is also written, atomically, as DIR/<name>.{txt,csv,json}.
 */
#include "sim/app/commands.h"
#include "sim/app/rp_driver.h"
#include "sim/app/rp_speed.h"
#include <stdio.h>
#include <string.h>

typedef enum { FMT_TEXT, FMT_CSV, FMT_JSON } RpFormat;

typedef struct {
    char *format;
    char *out_dir;
    char *fidelity;
    char *papers;
    gboolean quiet;
    RpFormat fmt;
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
                "--format: found '%s', expected text, csv or json",
                o->format);
    return FALSE;
}

static gboolean parse_opts(RpOpts *o, int *argc, char ***argv, GError **err)
{
    GOptionEntry entries[] = {
        {"format", 0, 0, G_OPTION_ARG_STRING, &o->format,
         "text (default), csv or json", "FMT"},
        {"out", 0, 0, G_OPTION_ARG_FILENAME, &o->out_dir,
         "also write <name>.{txt,csv,json} and charts here", "DIR"},
        {"fidelity", 0, 0, G_OPTION_ARG_STRING, &o->fidelity,
         "analytic, flow (default), packet or all", "F"},
        {"papers", 0, 0, G_OPTION_ARG_FILENAME, &o->papers,
         "published values (default configs/papers)", "DIR"},
        {"quiet", 'q', 0, G_OPTION_ARG_NONE, &o->quiet, "no progress", NULL},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    GOptionContext *ctx = g_option_context_new("NAME|all");
    g_option_context_set_summary(ctx, "Reruns a paper's tables and compares "
                                      "them with the published values.");
    g_option_context_add_main_entries(ctx, entries, NULL);
    gboolean ok = g_option_context_parse(ctx, argc, argv, err);
    g_option_context_free(ctx);
    if (!ok) {
        (*err)->domain = SIM_ERROR;
        (*err)->code = SIM_ERROR_INPUT;
        return FALSE;
    }
    if (!o->format)
        o->format = g_strdup("text");
    if (!o->fidelity)
        o->fidelity = g_strdup(RP_DEFAULT_FIDELITY);
    if (!rp_fidelity_valid(o->fidelity) && strcmp(o->fidelity, "all")) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "--fidelity: found '%s', expected analytic, flow, "
                    "packet or all", o->fidelity);
        return FALSE;
    }
    return parse_format(o, err);
}

/* passes: one RpTable, or one per fidelity for --fidelity all. */
static void format_passes(const GPtrArray *passes, RpFormat f,
                          gboolean first, GString *out)
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

static gboolean write_file(const char *dir, const char *name,
                           const char *ext, const GString *s, GError **err)
{
    char *file = g_strconcat(name, ".", ext, NULL);
    char *path = g_build_filename(dir, file, NULL);
    gboolean ok = g_file_set_contents(path, s->str, (gssize)s->len, err);
    if (!ok) {
        (*err)->domain = SIM_ERROR;
        (*err)->code = SIM_ERROR_IO;
    }
    g_free(path);
    g_free(file);
    return ok;
}

static gboolean write_outputs(const GPtrArray *passes, const char *dir,
                              GError **err)
{
    static const char *const ext[] = {"txt", "csv", "json"};
    const RpTable *t = g_ptr_array_index(passes, 0);
    if (g_mkdir_with_parents(dir, 0755) != 0) {
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

static GPtrArray *run_passes(const RpReproduction *rp, const RpOpts *o,
                             GError **err)
{
    RpContext ctx = {o->fidelity, o->out_dir, o->quiet};
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

static gboolean run_one(const RpReproduction *rp, const RpOpts *o,
                        gboolean first, GError **err)
{
    if (!o->quiet)
        fprintf(stderr, "reproduce: %s (fidelity %s)\n", rp->name,
                o->fidelity);
    GPtrArray *passes = run_passes(rp, o, err);
    if (!passes)
        return FALSE;
    GString *s = g_string_new(NULL);
    format_passes(passes, o->fmt, first, s);
    fputs(s->str, stdout);
    fflush(stdout);
    g_string_free(s, TRUE);
    gboolean ok = !o->out_dir || write_outputs(passes, o->out_dir, err);
    g_ptr_array_free(passes, TRUE);
    return ok;
}

static gboolean run_named(const char *name, const RpOpts *o, GError **err)
{
    if (strcmp(name, "all") == 0) {
        for (int i = 0; rp_all[i]; i++)
            if (!run_one(rp_all[i], o, i == 0, err))
                return FALSE;
        return TRUE;
    }
    const RpReproduction *rp = rp_find(name);
    if (!rp) {
        GString *known = g_string_new("all");
        for (int i = 0; rp_all[i]; i++)
            g_string_append_printf(known, ", %s", rp_all[i]->name);
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "reproduce: found '%s', expected one of: %s", name,
                    known->str);
        g_string_free(known, TRUE);
        return FALSE;
    }
    return run_one(rp, o, TRUE, err);
}

int cmd_reproduce(int argc, char **argv)
{
    RpOpts o = {0};
    GError *err = NULL;
    gboolean ok = parse_opts(&o, &argc, &argv, &err);
    if (ok && argc != 2) {
        g_set_error(&err, SIM_ERROR, SIM_ERROR_INPUT,
                    "reproduce: found %d names, expected one (NAME or all)",
                    argc - 1);
        ok = FALSE;
    }
    if (ok)
        ok = run_named(argv[1], &o, &err);
    int status = 0;
    if (!ok) {
        fprintf(stderr, "pgsim reproduce: %s\n", err->message);
        status = sim_error_exit_status(err);
        g_error_free(err);
    }
    g_free(o.format);
    g_free(o.out_dir);
    g_free(o.fidelity);
    g_free(o.papers);
    return status;
}
