/* cli.h — subcommand dispatch: run, validate, bench, help, ... */
#ifndef PGSIM_APP_CLI_H
#define PGSIM_APP_CLI_H

#define PGSIM_VERSION "0.1.0"

/* Parses argv and runs a subcommand; returns the process exit status
 * (0 success, 2 bad input, 1 internal failure). */
int cli_main(int argc, char **argv);

#endif
