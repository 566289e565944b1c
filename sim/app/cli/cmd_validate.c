/* cmd_validate.c — `pgsim validate FILE... [--set k=v]...`: loads and
 * checks run configs exactly as `pgsim run` does and runs the workload up
 * to its first simulated event (the engine's dry run), so "ok" means the
 * config will run: the machine is built, the workload has its costs and
 * the scene fits the memory limit.  Prints "FILE: ok" for each good one
 * and stops at the first error (exit status 2, located message); writes
 * nothing. */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/app/run/config.h"

static const char summary[] =
    "Checks run configs (docs/config.md) without running them: every check "
    "`pgsim run` makes up to the first simulated event (schema, types, "
    "units, ranges, unknown keys, the machine built from its model, the "
    "costs the workload needs, the scene and the memory it will take).";

/* Loads the config and runs its workload in a dry run: everything up to
 * the first simulated event, nothing written. */
static gboolean check_one(const char *path, char **sets, GError **err)
{
    CfgRun *r = cfg_run_load(path, (const char *const *)sets, err);
    if (!r)
        return FALSE;
    CfgRunOpts opts = {.quiet = TRUE, .dry_run = TRUE};
    GError *e = NULL;
    SimResult *res = cfg_run_exec(r, &opts, &e);
    sim_result_free(res);
    cfg_run_free(r);
    if (!e || g_error_matches(e, SIM_ERROR, SIM_ERROR_DRY_RUN)) {
        g_clear_error(&e);
        return TRUE;
    }
    g_propagate_error(err, e);
    return FALSE;
}

static int validate(int argc, char **argv, char **sets)
{
    for (int i = 1; i < argc; i++) {
        GError *e = NULL;
        if (!check_one(argv[i], sets, &e))
            return cli_fail(e);
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
