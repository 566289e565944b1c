/* commands.c — the subcommand table (one row per subcommand). */
#include "sim/app/cli/commands.h"
#include <stddef.h>

const CliCommand cli_commands[] = {
    {"run", cmd_run, "run a simulation config and print its report"},
    {"validate", cmd_validate, "check configs without running them"},
    {"bench", cmd_bench, "run a benchmark and print its figures"},
    {"render", cmd_render, "render one frame of a scene to a PNG"},
    {"reproduce", cmd_reproduce,
     "rerun a paper's tables and compare with the published values"},
    {"sweep", cmd_sweep,
     "run a parameter sweep (locally or under mpirun) with charts"},
    {"replay", cmd_replay,
     "replay a recorded trace on any machine model (docs/traces.md)"},
    {"sorts", cmd_sorts,
     "one scene on one machine as sort-first, -middle and -last"},
    {"plot", cmd_plot, "chart two columns of a results CSV with gnuplot"},
    {"models", cmd_models,
     "list the machine models, or print docs/models.md's tables"},
    {"help", cmd_help, "list the commands, or show one's options"},
    {NULL, NULL, NULL},
};
