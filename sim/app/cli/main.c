/* main.c — pgsim command-line entry point (subcommand dispatch).
 *
 * The user's locale is taken for the character set (so GOption decodes
 * arguments such as '350 µs' from the terminal's encoding), but numbers
 * are always read and written in the C locale: a decimal comma in a
 * result file would break CSV and determinism across machines. */
#include "sim/app/cli/cli.h"
#include <locale.h>

int main(int argc, char **argv)
{
    setlocale(LC_ALL, "");
    setlocale(LC_NUMERIC, "C");
    return cli_main(argc, argv);
}
