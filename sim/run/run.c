/* run.c — the runner: loading, building and running a run config (run.h).
 *
 * Order matters for good errors: overrides first (so --set can fix or
 * break anything), then the sections in a fixed order (schema_version,
 * run, workload, machine, scene), each read by its consumer, and last the
 * unknown-key check over the whole tree, which therefore sees exactly the
 * keys no consumer knew.  Every error is located (file:line:col).
 *
 * Model search path: the machine layer looks in ./models, the user's
 * $PGSIM_MODELS, the runner's extra folders and the shipped models/
 * under every data root (sim/machine/model_find.h).  The extra folders
 * are the models/ directory of the repository that holds the config
 * (nearest ancestor of the config's directory with a models/ folder) and
 * the install prefix's share/pgsim/models; they are passed as a
 * parameter (CfgRun.model_dirs), never through the environment.
 */
#include "sim/run/run.h"
#include "sim/output/provenance.h"
#include "sim/core/datapath.h"
#include "sim/core/memlimit.h"
#include "sim/output/progress.h"
#include "sim/machine/machine.h"
#include "sim/machine/model.h"
#include "sim/machine/roles.h"
#include "sim/scene/scene_cfg.h"
#include "sim/workload/metrics.h"
#include <string.h>

#ifndef PGSIM_PREFIX
#define PGSIM_PREFIX "/usr/local"
#endif

/* The first is the default: the machine model's own (machine.h). */
static const char *const fidelities[] = {"faithful", "analytic", "flow",
                                         "packet", NULL};

/* Nearest ancestor directory of `path` that has a models/ folder. */
static char *repo_models_dir(const char *path)
{
    char *dir = g_path_get_dirname(path);
    char *abs = g_canonicalize_filename(dir, NULL);
    g_free(dir);
    for (;;) {
        char *m = g_build_filename(abs, "models", NULL);
        if (g_file_test(m, G_FILE_TEST_IS_DIR)) {
            g_free(abs);
            return m;
        }
        g_free(m);
        char *up = g_path_get_dirname(abs);
        gboolean top = strcmp(up, abs) == 0;
        g_free(abs);
        abs = up;
        if (top)
            break;
    }
    g_free(abs);
    return NULL;
}

static void add_dir(GPtrArray *dirs, char *dir)
{
    if (dir && g_file_test(dir, G_FILE_TEST_IS_DIR))
        g_ptr_array_add(dirs, dir);
    else
        g_free(dir);
}

/* The extra model folders of a config at `path` (NULL: a tree with no
 * file), NULL-terminated. */
static GPtrArray *model_dirs(const char *path, const char *const *models)
{
    GPtrArray *dirs = g_ptr_array_new_with_free_func(g_free);
    for (int i = 0; models && models[i]; i++)
        g_ptr_array_add(dirs, g_strdup(models[i]));
    if (path)
        add_dir(dirs, repo_models_dir(path));
    add_dir(dirs, g_strdup(PGSIM_PREFIX "/share/pgsim/models"));
    g_ptr_array_add(dirs, NULL);
    return dirs;
}

static gboolean check_root(const CfgNode *root, GError **err)
{
    if (cfg_kind(root) == CFG_MAP)
        return TRUE;
    char *found = cfg_describe(root);
    cfg_error(err, root, found, "a map starting with schema_version: 1");
    g_free(found);
    return FALSE;
}

static gboolean check_schema(const CfgNode *root, GError **err)
{
    const CfgNode *v = cfg_get(root, "schema_version");
    if (!v) {
        cfg_error(err, root, "no key 'schema_version'",
                  "schema_version: 1 at the top");
        return FALSE;
    }
    if (g_strcmp0(cfg_scalar(v), "1") != 0) {
        char *found = cfg_describe(v);
        cfg_error(err, v, found, "1 (the only schema version)");
        g_free(found);
        return FALSE;
    }
    return TRUE;
}

static gboolean read_run(CfgRun *r, GError **err)
{
    const CfgNode *run = cfg_get(r->root, "run");
    int64_t seed = 1, frames = 1;
    int fid = 0;
    r->until = SIM_TIME_MAX;
    if (run && cfg_kind(run) != CFG_MAP) {
        char *found = cfg_describe(run);
        cfg_error(err, run, found, "a map (seed, frames, fidelity, until)");
        g_free(found);
        return FALSE;
    }
    if (!cfg_get_int(run, "seed", FALSE, 0, INT64_MAX, &seed, err) ||
        !cfg_get_int(run, "frames", FALSE, 1, 10000000, &frames, err) ||
        !cfg_get_enum(run, "fidelity", FALSE, fidelities, &fid, err) ||
        !cfg_get_time(run, "until", FALSE, &r->until, err))
        return FALSE;
    r->seed = (uint64_t)seed;
    r->frames = (int)frames;
    r->fidelity = fidelities[fid];
    return TRUE;
}

static char *workload_names(void)
{
    GString *s = g_string_new("one of: ");
    for (int i = 0; wl_all[i]; i++)
        g_string_append_printf(s, "%s%s", i ? ", " : "", wl_all[i]->name);
    if (!wl_all[0])
        g_string_append(s, "(no workload is registered)");
    return g_string_free(s, FALSE);
}

static gboolean read_workload(CfgRun *r, GError **err)
{
    const char *type = NULL;
    r->workload = cfg_get(r->root, "workload");
    if (!r->workload) {
        cfg_error(err, r->root, "no key 'workload'",
                  "workload: {type: <name>, ...}");
        return FALSE;
    }
    if (!cfg_get_str(r->workload, "type", TRUE, &type, err))
        return FALSE;
    r->wl = wl_find(type);
    if (!r->wl) {
        char *found = g_strdup_printf("workload '%s'", type);
        char *names = workload_names();
        cfg_error(err, cfg_get(r->workload, "type"), found, names);
        g_free(found);
        g_free(names);
        return FALSE;
    }
    r->wl_params = r->wl->parse(r->workload, err);
    return r->wl_params != NULL;
}

/* The workload's own memory estimate (WlOps.mem_bytes) against the limit,
 * located at the workload section. */
static gboolean check_workload_memory(const CfgRun *r, GError **err)
{
    if (!r->wl->mem_bytes)
        return TRUE;
    GString *what = g_string_new(NULL);
    g_string_printf(what, "workload %s's own state (", r->wl->name);
    double bytes = r->wl->mem_bytes(r->wl_params, what);
    g_string_append_c(what, ')');
    char *where = g_strdup_printf("%s:%d:%d", cfg_file(r->workload),
                                  cfg_line(r->workload), cfg_col(r->workload));
    gboolean ok = sim_mem_check(bytes, where, what->str, err);
    g_free(where);
    g_string_free(what, TRUE);
    return ok;
}

/* A section present in the config that the workload will not read: it
 * would be ignored, so it is refused where it stands. */
static gboolean refuse_unread(const CfgRun *r, const char *key,
                              GError **err)
{
    const CfgNode *sec = cfg_get(r->root, key);
    if (!sec)
        return TRUE;
    char *found = g_strdup_printf("a %s: section", key);
    char *exp = g_strdup_printf("none: workload %s does not read it with "
                                "these settings ('pgsim help run')",
                                r->wl->name);
    cfg_error(err, sec, found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

/* The machine section the workload runs on: the config's (or the
 * workload's default model), with the workload's own overrides applied
 * to a copy.  Returns a new tree or NULL with *err set. */
static CfgNode *machine_section(const CfgRun *r, const WlPlan *plan,
                                GError **err)
{
    CfgNode *sec;
    if (r->machine) {
        sec = cfg_copy(r->machine);
    } else if (plan->default_model) {
        char *text = g_strdup_printf("model: %s\n", plan->default_model);
        char *where = g_strdup_printf("<%s's default machine>", r->wl->name);
        sec = cfg_load_string(text, where, err);
        g_free(where);
        g_free(text);
    } else {
        char *exp = g_strdup_printf("machine: {model: NAME} (workload %s "
                                    "runs on a machine; docs/models.md)",
                                    r->wl->name);
        cfg_error(err, r->root, "no key 'machine'", exp);
        g_free(exp);
        return NULL;
    }
    for (guint i = 0; sec && i < plan->machine_set->len; i++) {
        if (!cfg_set_override(sec, plan->machine_set->pdata[i], err)) {
            cfg_free(sec);
            return NULL;
        }
    }
    return sec;
}

/* The workload's model-dependent overrides (WlOps.plan_machine), applied
 * to sec. */
static gboolean plan_machine(const CfgRun *r, CfgNode *sec, GError **err)
{
    if (!r->wl->plan_machine)
        return TRUE;
    const char *const *dirs = (const char *const *)r->model_dirs->pdata;
    char *model_file = NULL;
    CfgNode *tree = mach_section_tree_in(sec, dirs, &model_file, err);
    GPtrArray *set = g_ptr_array_new_with_free_func(g_free);
    gboolean ok = tree && mach_model_check(tree, model_file, err) &&
                  r->wl->plan_machine(r->wl_params, r->machine, tree, set,
                                      err);
    for (guint i = 0; ok && i < set->len; i++)
        ok = cfg_set_override(sec, set->pdata[i], err);
    g_ptr_array_free(set, TRUE);
    cfg_free(tree);
    g_free(model_file);
    return ok;
}

/* The node kinds the workload needs and the machine lacks, carved from
 * the kinds that play them (sim/machine/roles.h). */
static gboolean play_roles(CfgRun *r, CfgNode *sec, GError **err)
{
    GPtrArray *kinds = g_ptr_array_new();
    for (const WlNeed *n = r->wl->needs; n && n->kind; n++)
        g_ptr_array_add(kinds, (gpointer)n->kind);
    g_ptr_array_add(kinds, NULL);
    gboolean ok = mach_section_roles(
        sec, (const char *const *)r->model_dirs->pdata,
        (const char *const *)kinds->pdata, r->notes, err);
    g_ptr_array_free(kinds, TRUE);
    return ok;
}

static gboolean build_machine(CfgRun *r, const WlPlan *plan, GError **err)
{
    CfgNode *sec = machine_section(r, plan, err);
    if (!sec)
        return FALSE;
    if (!plan_machine(r, sec, err) || !play_roles(r, sec, err)) {
        cfg_free(sec);
        return FALSE;
    }
    r->machine_built =
        mach_new_from_cfg_in(r->eng, sec, r->fidelity,
                             (const char *const *)r->model_dirs->pdata, err);
    cfg_free(sec);
    if (r->machine_built && r->machine)
        cfg_mark_read(r->machine);
    return r->machine_built != NULL;
}

/* Builds what the workload's plan says it reads, once, on a new engine
 * whose horizon is run.until; refuses what it does not read. */
static gboolean build(CfgRun *r, GError **err)
{
    WlPlan plan = {.machine_set = g_ptr_array_new_with_free_func(g_free)};
    if (r->wl->plan)
        r->wl->plan(r->wl_params, &plan);
    r->machine = cfg_get(r->root, "machine");
    r->scene = cfg_get(r->root, "scene");
    r->eng = sim_engine_new(r->seed);
    sim_engine_set_horizon(r->eng, r->until);
    gboolean ok =
        ((plan.reads & WL_READS_MACHINE) ? build_machine(r, &plan, err)
                                         : refuse_unread(r, "machine", err)) &&
        ((plan.reads & WL_READS_SCENE)
             ? (r->scene_built = scene_from_cfg(r->scene, err)) != NULL
             : refuse_unread(r, "scene", err));
    g_ptr_array_free(plan.machine_set, TRUE);
    return ok;
}

/* A machine that --set made from nothing must name a model (or be a
 * whole inline machine with a name): otherwise the machine layer would
 * report a missing 'name' that the user never meant to write. */
static gboolean check_made_machine(const CfgNode *root, GError **err)
{
    if (!cfg_has(root, "machine"))
        return TRUE;
    const CfgNode *m = cfg_get(root, "machine");
    if (cfg_kind(m) != CFG_MAP || cfg_has(m, "model") || cfg_has(m, "name"))
        return TRUE;
    cfg_error(err, m,
              "a machine made by --set alone, with no model (the config has "
              "no machine: section)",
              "--set machine.model=NAME too (a model in models/, "
              "docs/models.md), or a machine: section in the config");
    return FALSE;
}

static gboolean apply_overrides(CfgNode *root, const char *const *ov,
                                GError **err)
{
    gboolean had_machine = cfg_has(root, "machine");
    for (int i = 0; ov && ov[i]; i++)
        if (!cfg_set_override(root, ov[i], err))
            return FALSE;
    return had_machine || check_made_machine(root, err);
}

/* Loads a tree (taken) read from `path` (NULL: none). */
static CfgRun *run_new(CfgNode *root, const char *const *overrides,
                       const char *path, const char *const *models,
                       GError **err)
{
    CfgRun *r = g_new0(CfgRun, 1);
    r->notes = g_ptr_array_new_with_free_func(g_free);
    r->root = root;
    r->path = g_strdup(path);
    r->model_dirs = model_dirs(path, models);
    r->inputs = sim_inputs_new();
    sim_inputs_push(r->inputs);
    r->overrides = g_ptr_array_new_with_free_func(g_free);
    for (int i = 0; overrides && overrides[i]; i++)
        g_ptr_array_add(r->overrides, g_strdup(overrides[i]));
    gboolean ok =
        check_root(root, err) && apply_overrides(root, overrides, err) &&
        check_schema(root, err) && read_run(r, err) &&
        read_workload(r, err) && check_workload_memory(r, err) &&
        build(r, err) && cfg_check_unused(root, err);
    sim_inputs_pop(r->inputs);
    if (!ok) {
        cfg_run_free(r);
        return NULL;
    }
    return r;
}

CfgRun *cfg_run_from_tree_in(CfgNode *root, const char *const *overrides,
                             const char *const *models, GError **err)
{
    return run_new(root, overrides, NULL, models, err);
}

CfgRun *cfg_run_from_tree(CfgNode *root, const char *const *overrides,
                          GError **err)
{
    return run_new(root, overrides, NULL, NULL, err);
}

CfgRun *cfg_run_load_in(const char *path, const char *const *overrides,
                        const char *const *models, GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    CfgRun *r = root ? run_new(root, overrides, path, models, err) : NULL;
    if (r)
        r->sha256 = prov_file_sha256(path);
    return r;
}

CfgRun *cfg_run_load(const char *path, const char *const *overrides,
                     GError **err)
{
    return cfg_run_load_in(path, overrides, NULL, err);
}

void cfg_run_free(CfgRun *r)
{
    if (!r)
        return;
    if (r->wl && r->wl_params)
        r->wl->free_params(r->wl_params);
    mach_free(r->machine_built); /* before its engine */
    scene_free(r->scene_built);
    sim_engine_free(r->eng);
    cfg_free(r->root);
    if (r->model_dirs)
        g_ptr_array_free(r->model_dirs, TRUE);
    g_free(r->path);
    g_free(r->sha256);
    sim_inputs_free(r->inputs);
    if (r->overrides)
        g_ptr_array_free(r->overrides, TRUE);
    g_ptr_array_free(r->notes, TRUE);
    g_free(r);
}

static char *machine_name(const CfgRun *r)
{
    const char *model = cfg_scalar(cfg_get(r->machine, "model"));
    return g_strdup(model ? model : r->machine ? "inline" : "none");
}

static void fill_provenance(SimResult *res, const CfgRun *r)
{
    res->config_path = g_strdup(r->path);
    res->config_sha256 = g_strdup(r->sha256);
    res->config_effective = prov_cfg_json(r->root);
    for (guint i = 0; r->overrides && i < r->overrides->len; i++)
        g_ptr_array_add(res->overrides, g_strdup(r->overrides->pdata[i]));
    res->inputs = sim_inputs_new();
    sim_inputs_merge(res->inputs, r->inputs);
}

/* The feasibility figures (result.h): the workload's per-node peak and
 * the smallest node memory over the kinds of the processors it used.
 * O(used processors x kinds). */
static void fill_memory(SimResult *res, const MachMachine *m)
{
    res->mem_peak = sim_result_metric(res, SIM_PEAK_MEMORY_METRIC);
    for (guint i = 0; m && i < res->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(res->nodes, i);
        const MachKindInfo *k = mach_kind(m, n->kind);
        if (k && k->memory && (!res->mem_node || k->memory < res->mem_node)) {
            res->mem_node = k->memory;
            g_free(res->mem_kind);
            res->mem_kind = g_strdup(k->name);
        }
    }
}

/* A speed-up above the processors metric that the workload did not
 * explain: say that the serial reference is not the parallel run on one
 * processor, so the figure is not read as more than linear scaling. */
static void note_speedup(SimResult *res)
{
    double sp = sim_result_metric(res, "speedup");
    double p = sim_result_metric(res, "processors");
    if (res->notes->len || !(sp > p))
        return;
    char *t = g_strdup_printf("speed-up %.1f is above P = %.0f: the "
                              "workload's serial reference is not its "
                              "parallel run on one processor "
                              "(docs/workloads.md says how it is made)",
                              sp, p);
    sim_result_add_note(res, t);
    g_free(t);
}

SimResult *cfg_run_exec(CfgRun *r, const CfgRunOpts *opts, GError **err)
{
    g_assert(!r->executed); /* the built objects carry one run's state */
    r->executed = TRUE;
    SimEngine *eng = r->eng;
    sim_engine_set_trace(eng, opts ? opts->trace : NULL);
    sim_engine_set_recorder(eng, opts ? opts->recorder : NULL);
    sim_engine_set_dry_run(eng, opts && opts->dry_run);
    char *mname = machine_name(r);
    SimResult *res = sim_result_new(r->wl->name, mname);
    g_free(mname);
    g_free(res->fidelity);
    res->fidelity = g_strdup(r->fidelity);
    res->seed = r->seed;
    fill_provenance(res, r);
    WlContext ctx = {.eng = eng,
                     .root = r->root,
                     .machine = r->machine_built,
                     .scene = r->scene_built,
                     .until = r->until,
                     .seed = r->seed,
                     .fidelity = r->fidelity,
                     .frames = r->frames,
                     .out_dir = opts ? opts->out_dir : NULL,
                     .quiet = opts ? opts->quiet : TRUE,
                     .all_frames = opts && opts->all_frames,
                     .share = opts ? opts->share : NULL};
    RptProgress *p = opts && opts->progress && !opts->quiet
                         ? rpt_progress_new(0, r->wl->name)
                         : NULL;
    rpt_progress_attach(p, eng);
    gint64 t0 = g_get_monotonic_time();
    sim_inputs_push(r->inputs);
    gboolean ok = r->wl->run(&ctx, r->wl_params, res, err) &&
                  wl_check_metrics(r->wl, res, err);
    sim_inputs_pop(r->inputs);
    sim_inputs_merge(res->inputs, r->inputs);
    res->wall_s = (double)(g_get_monotonic_time() - t0) * 1e-6;
    rpt_progress_finish(p);
    res->events = sim_engine_events(eng);
    if (!res->elapsed)
        res->elapsed = sim_now(eng);
    if (!ok) {
        sim_result_free(res);
        return NULL;
    }
    fill_memory(res, r->machine_built);
    note_speedup(res);
    for (guint i = 0; i < r->notes->len; i++)
        sim_result_add_note(res, g_ptr_array_index(r->notes, i));
    for (guint k = 0; r->machine_built &&
                      k < mach_kind_count(r->machine_built);
         k++)
        mach_costs_note_derived(mach_kind_at(r->machine_built, k), res);
    return res;
}
