/* cmd_validate.c — `pgsim validate FILE... [--set k=v]...`: loads and
 * checks run configs exactly as `pgsim run` does, without running them;
 * prints "FILE: ok" for each good one and stops at the first error
 * (exit status 2, located message). */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/app/run/config.h"

static const char summary[] =
    "Checks run configs (docs/config.md) without running them: schema, "
    "types, units, ranges, unknown keys, machine models and scenes.";

static int validate(int argc, char **argv, char **sets)
{
    for (int i = 1; i < argc; i++) {
        GError *e = NULL;
        CfgRun *r = cfg_run_load(argv[i], (const char *const *)sets, &e);
        if (!r)
            return cli_fail(e);
        cfg_run_free(r);
        printf("%s: ok\n", argv[i]);
    }
    return 0;
}

int cmd_validate(int argc, char **argv)
{
    char **sets = NULL;
    const GOptionEntry entries[] = {
        {"set", 0, 0, G_OPTION_ARG_STRING_ARRAY, &sets,
         "override a config key (repeatable)", "KEY.PATH=VALUE"},
        G_OPTION_ENTRY_NULL,
    };
    int status;
    if (cli_parse("validate", "FILE...", summary, entries, &argc, &argv,
                  &status)) {
        if (argc < 2)
            status = cli_want_args("validate", "FILE", argc, argv, 1) ? 0 : 2;
        else
            status = validate(argc, argv, sets);
    }
    g_strfreev(sets);
    return status;
}
