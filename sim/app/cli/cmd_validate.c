/* cmd_validate.c — `pgsim validate FILE... [--set k=v]...`: loads and
 * checks run configs exactly as `pgsim run` does and runs the workload up
 * to its first simulated event (the engine's dry run), so "ok" means the
 * config will run: the machine is built, the workload has its costs and
 * the scene fits the memory limit.  A sweep file (docs/sweeps.md: no
 * schema_version, a `parameters:` map) is checked as `pgsim sweep` would
 * run it: the file, then every point's config the same way.  Prints
 * "FILE: ok" for each good one and stops at the first error (exit status
 * 2, located message); writes nothing. */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/run/run.h"
#include "sim/app/sweep/sweep_spec.h"

static const char summary[] =
    "Checks run configs (docs/config.md) and sweep files (docs/sweeps.md) "
    "without running them: every check `pgsim run` makes up to the first "
    "simulated event (schema, types, units, ranges, unknown keys, the "
    "machine built from its model, the costs the workload needs, the scene "
    "and the memory it will take); for a sweep, every point's config.";

/* Runs a loaded config's workload in a dry run (everything up to the
 * first simulated event, nothing written); frees r. */
static gboolean dry_run(CfgRun *r, GError **err)
{
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

static gboolean check_one(const char *path, char **sets, GError **err)
{
    CfgRun *r = cfg_run_load(path, (const char *const *)sets, err);
    return r && dry_run(r, err);
}

/* A sweep file: a map without schema_version that has parameters. */
static gboolean is_sweep(const char *path)
{
    CfgNode *root = cfg_load_file(path, NULL);
    gboolean yes = root && cfg_kind(root) == CFG_MAP &&
                   !cfg_get(root, "schema_version") &&
                   cfg_get(root, "parameters");
    cfg_free(root);
    return yes;
}

/* Every point of a sweep, loaded and dry-run like a config. */
static gboolean check_sweep(const char *path, char **sets, guint *points,
                            GError **err)
{
    SweepSpec *s = sweep_spec_load(path, err);
    if (!s)
        return FALSE;
    gboolean ok = TRUE;
    *points = sweep_spec_points(s);
    for (guint i = 0; ok && i < *points; i++) {
        SweepPoint pt = sweep_spec_point(s, i);
        CfgNode *cfg = sweep_spec_config(s, &pt, err);
        CfgRun *r =
            cfg ? cfg_run_from_tree(cfg, (const char *const *)sets, err) : NULL;
        ok = r && dry_run(r, err);
        if (!ok)
            g_prefix_error(err, "%s: point %u: ", path, i);
    }
    sweep_spec_free(s);
    return ok;
}

static int validate(int argc, char **argv, char **sets)
{
    for (int i = 1; i < argc; i++) {
        GError *e = NULL;
        guint points = 0;
        if (is_sweep(argv[i])) {
            if (!check_sweep(argv[i], sets, &points, &e))
                return cli_fail(e);
            printf("%s: ok (sweep, %u points)\n", argv[i], points);
            continue;
        }
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
