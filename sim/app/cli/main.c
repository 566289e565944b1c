/* main.c — pgsim command-line entry point (subcommand dispatch). */
#include "sim/app/cli/cli.h"

int main(int argc, char **argv)
{
    return cli_main(argc, argv);
}
