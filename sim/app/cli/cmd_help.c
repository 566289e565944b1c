/* cmd_help.c — `pgsim help [CMD]`: the command list, or CMD --help. */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include <string.h>

int cmd_help(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 ||
        strcmp(argv[1], "-h") == 0) {
        cli_usage(stdout);
        return 0;
    }
    if (strcmp(argv[1], "help") == 0) {
        printf("Usage: pgsim help [COMMAND]\n\nPrints the list of commands, "
               "or COMMAND's options (the same as pgsim COMMAND --help).\n");
        return 0;
    }
    const CliCommand *c = cli_find_command(argv[1]);
    if (!c) {
        fprintf(stderr, "pgsim help: found '%s', expected a command\n",
                argv[1]);
        cli_usage(stderr);
        return 2;
    }
    char *args[] = {(char *)c->name, (char *)"--help", NULL};
    return c->fn(2, args);
}
