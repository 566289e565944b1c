/* cli.h — subcommand dispatch and the option parsing they share.
 *
 * cli_main() dispatches `pgsim COMMAND ...` through the table in
 * commands.c; `pgsim help [CMD]`, `pgsim --help` and `pgsim --version` are
 * handled here.  cli_parse() wraps GOptionContext so that every
 * subcommand gets the same --help and the same located-style errors
 * ("pgsim run: found unknown option '--x', expected one of: ...").
 */
#ifndef PGSIM_APP_CLI_CLI_H
#define PGSIM_APP_CLI_CLI_H

#include <glib.h>
#include <stdio.h>

#define PGSIM_VERSION "0.1.0"

/* Parses argv and runs a subcommand; returns the process exit status
 * (0 success, 2 bad input, 1 internal failure). */
int cli_main(int argc, char **argv);

/* Parses options for subcommand `cmd` (argv[0]); `params` is the usage
 * tail ("CONFIG"), `summary` one paragraph for --help.  Adds -h/--help.
 * Returns TRUE to go on (argv keeps argv[0] and the positional
 * arguments); FALSE when the caller should return *status: 0 after
 * printing help on stdout, 2 after printing an error on stderr. */
/* The options every command takes (--mem-limit BYTES: memlimit.h);
 * cli_parse() adds them itself, other parsers list the entry. */
gboolean cli_set_mem_limit(const gchar *name, const gchar *value,
                           gpointer data, GError **err);
#define CLI_MEM_LIMIT_ENTRY                                                    \
    {"mem-limit", 0, 0, G_OPTION_ARG_CALLBACK, (gpointer)cli_set_mem_limit,    \
     "memory a run may ask for (default: physical memory)", "BYTES"}
void cli_add_common(GOptionContext *ctx);
gboolean cli_parse(const char *cmd, const char *params, const char *summary,
                   const GOptionEntry *entries, int *argc, char ***argv,
                   int *status);

/* Prints "pgsim: <message>" on stderr, frees err, returns its exit
 * status (sim_error_exit_status). */
int cli_fail(GError *err);

/* Checks the positional argument count (argc includes argv[0]); prints a
 * located-style error and returns FALSE when it is not n. */
gboolean cli_want_args(const char *cmd, const char *params, int argc,
                       char **argv, int n);

/* Prints the top-level usage and the command list to f. */
void cli_usage(FILE *f);

#endif
