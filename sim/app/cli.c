/* cli.c — placeholder dispatch until the foundation CLI lands. */
#include "sim/app/cli.h"
#include <stdio.h>
#include <string.h>

int cli_main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--version") == 0) {
        printf("pgsim %s\n", PGSIM_VERSION);
        return 0;
    }
    fprintf(stderr, "usage: pgsim COMMAND ...\n");
    return 2;
}
