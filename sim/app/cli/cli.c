/* cli.c — `pgsim COMMAND ...`: dispatch and shared option parsing.
 *
 * Every subcommand parses with cli_parse(), so --help, -h and the error
 * format are the same everywhere; `pgsim help CMD` simply runs
 * `CMD --help`.  Error messages follow the house format
 * "<where>: found <what>, expected <what>" and exit with status 2.
 */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include <string.h>

void cli_usage(FILE *f)
{
    fprintf(f, "usage: pgsim COMMAND [options]   (pgsim help COMMAND for "
               "its options)\n\ncommands:\n");
    for (int i = 0; cli_commands[i].name; i++)
        fprintf(f, "  %-10s %s\n", cli_commands[i].name,
                cli_commands[i].summary);
    fprintf(f, "\n  pgsim --version   print the version\n");
}

int cli_fail(GError *err)
{
    int status = sim_error_exit_status(err);
    fprintf(stderr, "pgsim: %s\n", err->message);
    g_error_free(err);
    return status;
}

static gboolean entry_matches(const GOptionEntry *e, const char *arg)
{
    size_t n = strcspn(arg, "=");
    if (arg[1] == '-')
        return strlen(e->long_name) == n - 2 &&
               strncmp(arg + 2, e->long_name, n - 2) == 0;
    return e->short_name && arg[1] == e->short_name;
}

/* The first argument that looks like an option and matches no entry. */
static const char *unknown_option(const GOptionEntry *entries, int argc,
                                  char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--") == 0)
            return NULL;
        if (argv[i][0] != '-' || !argv[i][1])
            continue;
        const GOptionEntry *e = entries;
        while (e->long_name && !entry_matches(e, argv[i]))
            e++;
        if (!e->long_name && strcmp(argv[i], "--help") != 0 &&
            strcmp(argv[i], "-h") != 0)
            return argv[i];
    }
    return NULL;
}

static char *option_list(const GOptionEntry *entries)
{
    GString *s = g_string_new("one of: ");
    for (const GOptionEntry *e = entries; e->long_name; e++)
        g_string_append_printf(s, "--%s, ", e->long_name);
    g_string_append(s, "--help");
    return g_string_free(s, FALSE);
}

static void parse_error(const char *cmd, const GOptionEntry *entries, int argc,
                        char **argv, const GError *e)
{
    const char *bad = unknown_option(entries, argc, argv);
    if (e->code == G_OPTION_ERROR_UNKNOWN_OPTION && bad) {
        char *list = option_list(entries);
        fprintf(stderr, "pgsim %s: found unknown option '%s', expected %s\n",
                cmd, bad, list);
        g_free(list);
    } else {
        fprintf(stderr,
                "pgsim %s: found a bad option (%s), expected the "
                "options of `pgsim help %s`\n",
                cmd, e->message, cmd);
    }
}

/* --mem-limit BYTES[k|M|G|T], accepted by every command (memlimit.h). */
gboolean cli_set_mem_limit(const gchar *name, const gchar *value,
                           gpointer data, GError **err)
{
    (void)name;
    (void)data;
    guint64 bytes = 0;
    if (sim_mem_parse(value, &bytes)) {
        sim_mem_set_limit(bytes);
        return TRUE;
    }
    g_set_error(err, G_OPTION_ERROR, G_OPTION_ERROR_BAD_VALUE,
                "--mem-limit: found '%s', expected a positive size in bytes "
                "with an optional k, M, G or T suffix",
                value);
    return FALSE;
}

void cli_add_common(GOptionContext *ctx)
{
    static const GOptionEntry common[] = {CLI_MEM_LIMIT_ENTRY,
                                          G_OPTION_ENTRY_NULL};
    g_option_context_add_main_entries(ctx, common, NULL);
}

static GOptionContext *make_context(const char *cmd, const char *params,
                                    const char *summary,
                                    const GOptionEntry *entries, gboolean *help)
{
    const GOptionEntry help_entry[] = {
        {"help", 'h', 0, G_OPTION_ARG_NONE, help, "Show this help", NULL},
        G_OPTION_ENTRY_NULL,
    };
    char *prg = g_strdup_printf("pgsim %s", cmd); /* "Usage: pgsim run" */
    g_set_prgname(prg);
    g_free(prg);
    GOptionContext *ctx = g_option_context_new(params);
    g_option_context_set_help_enabled(ctx, FALSE);
    g_option_context_set_summary(ctx, summary);
    g_option_context_add_main_entries(ctx, entries, NULL);
    g_option_context_add_main_entries(ctx, help_entry, NULL);
    cli_add_common(ctx);
    return ctx;
}

gboolean cli_parse(const char *cmd, const char *params, const char *summary,
                   const GOptionEntry *entries, int *argc, char ***argv,
                   int *status)
{
    gboolean help = FALSE;
    GOptionContext *ctx = make_context(cmd, params, summary, entries, &help);
    int argc0 = *argc;
    char **argv0 = g_memdup2(*argv, sizeof(char *) * (argc0 + 1));
    GError *e = NULL;
    gboolean ok = g_option_context_parse(ctx, argc, argv, &e);
    *status = 0;
    if (!ok) {
        parse_error(cmd, entries, argc0, argv0, e);
        g_error_free(e);
        *status = 2;
    } else if (help) {
        char *text = g_option_context_get_help(ctx, TRUE, NULL);
        /* GLib names the program by g_get_prgname(); say "pgsim" */
        fputs(text, stdout);
        g_free(text);
        ok = FALSE;
    }
    g_free(argv0);
    g_option_context_free(ctx);
    g_set_prgname("pgsim");
    return ok;
}

gboolean cli_want_args(const char *cmd, const char *params, int argc,
                       char **argv, int n)
{
    if (argc - 1 == n)
        return TRUE;
    if (argc - 1 < n)
        fprintf(stderr, "pgsim %s: found no %s, expected pgsim %s %s\n", cmd,
                params, cmd, params);
    else
        fprintf(stderr,
                "pgsim %s: found extra argument '%s', expected pgsim "
                "%s %s\n",
                cmd, argv[n + 1], cmd, params);
    return FALSE;
}

const CliCommand *cli_find_command(const char *name)
{
    for (int i = 0; cli_commands[i].name; i++)
        if (strcmp(cli_commands[i].name, name) == 0)
            return &cli_commands[i];
    return NULL;
}

int cli_main(int argc, char **argv)
{
    g_set_prgname("pgsim");
    if (argc < 2) {
        cli_usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "-V") == 0) {
        printf("pgsim %s\n", PGSIM_VERSION);
        return 0;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        cli_usage(stdout);
        return 0;
    }
    const CliCommand *c = cli_find_command(argv[1]);
    if (!c) {
        fprintf(stderr,
                "pgsim: found unknown command '%s', expected one of "
                "the commands below\n",
                argv[1]);
        cli_usage(stderr);
        return 2;
    }
    return c->fn(argc - 1, argv + 1);
}
