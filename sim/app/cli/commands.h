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

#endif
