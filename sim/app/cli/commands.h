/* commands.h — the subcommand table.
 *
 * Each subcommand lives in sim/app/cmd_<name>.c as
 *     int cmd_<name>(int argc, char **argv);
 * where argv[0] is the subcommand name; it returns the exit status
 * (0 success, 2 bad input, 1 internal failure).  To add one: declare it
 * here and add one row to the table in commands.c.
 */
#ifndef PGSIM_APP_CLI_COMMANDS_H
#define PGSIM_APP_CLI_COMMANDS_H

#include "sim/output/table.h"

typedef struct {
    const char *name;
    int (*fn)(int argc, char **argv);
    const char *summary; /* one line for `pgsim help` */
} CliCommand;

int cmd_bench(int argc, char **argv);
int cmd_help(int argc, char **argv);
int cmd_run(int argc, char **argv);
int cmd_validate(int argc, char **argv);
int cmd_render(int argc, char **argv);

/* NULL-terminated table, in the order `pgsim help` lists them. */
extern const CliCommand cli_commands[];
/* The row for a command name, or NULL (sim/app/cli/cli.c). */
const CliCommand *cli_find_command(const char *name);

int cmd_reproduce(int argc, char **argv);
int cmd_sweep(int argc, char **argv);
int cmd_plot(int argc, char **argv);
int cmd_replay(int argc, char **argv);
int cmd_models(int argc, char **argv);
int cmd_sorts(int argc, char **argv);

/* Keeps the rows of *t whose column K reads V, for one "K=V" (pgsim plot
 * --where, a sweep chart's where:); FALSE with *err when the item or
 * the column is bad (*t kept) or no row is left (*t freed, NULL)
 * (cmd_plot.c). */
gboolean cli_keep_where(DataTable **t, const char *item, GError **err);

#endif
