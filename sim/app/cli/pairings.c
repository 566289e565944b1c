/* pairings.c — every workload config on every model, checked against
 * the list of meaningless pairings, as a Markdown table (pairings.h).
 *
 * Invariants: configs and models are taken in file-name order, so the
 * table is deterministic; a pairing matches the first rule naming it.
 * Cost: one small run per pairing.
 */
#include "sim/app/cli/pairings.h"
#include "sim/core/error.h"
#include "sim/machine/machine.h"
#include "sim/run/run.h"
#include <string.h>

typedef struct {
    const CfgNode *configs, *models, *except;
    const char *error, *reason;
    gboolean pending; /* `pending:`: to do, not meaningless */
} Rule;

static gint by_name(gconstpointer a, gconstpointer b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

GPtrArray *cli_yaml_files(const char *dir, GError **err)
{
    GDir *d = g_dir_open(dir, 0, err);
    if (!d)
        return NULL;
    GPtrArray *files = g_ptr_array_new_with_free_func(g_free);
    for (const char *f; (f = g_dir_read_name(d));)
        if (g_str_has_suffix(f, ".yaml"))
            g_ptr_array_add(files, g_build_filename(dir, f, NULL));
    g_dir_close(d);
    g_ptr_array_sort(files, by_name);
    return files;
}

/* A config's or a model's name: its file name without ".yaml". */
static char *stem(const char *path)
{
    char *b = g_path_get_basename(path);
    b[strlen(b) - 5] = '\0';
    return b;
}

/* Whether a sequence of names holds `name` (or "*"). */
static gboolean names(const CfgNode *seq, const char *name)
{
    for (guint i = 0; seq && i < cfg_seq_len(seq); i++) {
        const char *s = cfg_scalar(cfg_seq_at(seq, i));
        if (s && (!strcmp(s, name) || !strcmp(s, "*")))
            return TRUE;
    }
    return FALSE;
}

static gboolean read_rule(const CfgNode *n, Rule *r, GError **err)
{
    r->configs = cfg_get(n, "configs");
    r->models = cfg_get(n, "models");
    r->except = cfg_get(n, "except");
    if (cfg_kind(r->configs) == CFG_SEQ && cfg_kind(r->models) == CFG_SEQ &&
        (!r->except || cfg_kind(r->except) == CFG_SEQ))
        return cfg_get_str(n, "error", TRUE, &r->error, err) &&
               cfg_get_str(n, "reason", TRUE, &r->reason, err);
    cfg_error(err, n, "a rule without lists configs: and models:",
              "{configs: [NAME|\"*\"], models: [NAME|\"*\"], except: [...], "
              "error: TEXT, reason: TEXT}");
    return FALSE;
}

/* The index of the first rule naming (config, model), or -1. */
static int rule_of(const GArray *rules, const char *config, const char *model)
{
    for (guint i = 0; i < rules->len; i++) {
        const Rule *r = &g_array_index(rules, Rule, i);
        if (names(r->configs, config) && names(r->models, model) &&
            !(r->except && names(r->except, model)))
            return (int)i;
    }
    return -1;
}

/* Whether path is a workload run config (not a sweep). */
static gboolean is_run_config(const char *path)
{
    CfgNode *t = cfg_load_file(path, NULL);
    gboolean ok = t && cfg_get(t, "workload") && !cfg_get(t, "sweep");
    cfg_free(t);
    return ok;
}

/* "109.6 us" */
static void append_time(GString *s, double sec)
{
    if (sec < 1e-3)
        g_string_append_printf(s, "%.4g us", sec * 1e6);
    else if (sec < 1)
        g_string_append_printf(s, "%.4g ms", sec * 1e3);
    else
        g_string_append_printf(s, "%.4g s", sec);
}

/* The letters of the work classes of the machine's derived costs. */
static void append_derived(GString *s, const MachMachine *m)
{
    static const char letters[MACH_W_N + 1] = "VSPZFIMB";
    gboolean used[MACH_W_N] = {FALSE};
    gboolean any = FALSE;
    for (guint k = 0; m && k < mach_kind_count(m); k++) {
        GHashTableIter it;
        gpointer v;
        g_hash_table_iter_init(&it, mach_kind_at(m, k)->costs);
        while (g_hash_table_iter_next(&it, NULL, &v)) {
            const MachCost *c = v;
            for (guint w = 0; c->from == MACH_COST_DERIVED && w < MACH_W_N;
                 w++)
                any = used[w] = used[w] || c->work[w] > 0;
        }
    }
    if (!any)
        return;
    g_string_append(s, " d:");
    for (guint w = 0; w < MACH_W_N; w++)
        if (used[w])
            g_string_append_c(s, letters[w]);
}

/* Runs config on model; the cell, or NULL with *err. */
static char *run_one(const char *config, const CfgNode *small,
                     const char *model, GError **err)
{
    GPtrArray *ov = g_ptr_array_new_with_free_func(g_free);
    for (guint i = 0; small && i < cfg_seq_len(small); i++)
        g_ptr_array_add(ov, g_strdup(cfg_scalar(cfg_seq_at(small, i))));
    g_ptr_array_add(ov, g_strdup_printf("machine.model=%s", model));
    g_ptr_array_add(ov, NULL);
    CfgRun *r = cfg_run_load(config, (const char *const *)ov->pdata, err);
    SimResult *res = r ? cfg_run_exec(r, NULL, err) : NULL;
    char *cell = NULL;
    if (res) {
        GString *s = g_string_new(NULL);
        append_time(s, sim_result_mean_frame_s(res));
        append_derived(s, r->machine_built);
        for (guint i = 0; i < res->notes->len; i++)
            if (strstr(g_ptr_array_index(res->notes, i), "played by"))
                g_string_append(s, " r");
        cell = g_string_free(s, FALSE);
    }
    sim_result_free(res);
    cfg_run_free(r);
    g_ptr_array_free(ov, TRUE);
    return cell;
}

/* An error message that starts "FILE:LINE:COL: " (the file may be
 * "--set KEY=VALUE", an override's place). */
static gboolean located(const char *msg)
{
    GRegex *re = g_regex_new("^[^\n]+?:[0-9]+:[0-9]+: ", 0, 0, NULL);
    gboolean ok = g_regex_match(re, msg, 0, NULL);
    g_regex_unref(re);
    return ok;
}

/* One pairing: its cell into md, a disagreement into bad. */
static void pairing(const char *path, const char *config, const char *model,
                    const CfgNode *small, const GArray *rules, GString *md,
                    GString *bad)
{
    GError *e = NULL;
    int k = rule_of(rules, config, model);
    char *cell = run_one(path, small, model, &e);
    if (cell && k >= 0 && g_array_index(rules, Rule, k).pending)
        k = -1; /* a pending pairing that runs now is simply run */
    if (cell && k >= 0)
        g_string_append_printf(bad, "\n  %s on %s runs (%s) but is listed "
                                    "as meaningless (rule %d)",
                               config, model, cell, k + 1);
    if (!cell && k < 0)
        g_string_append_printf(bad, "\n  %s on %s fails and is not listed: "
                                    "%s",
                               config, model, e->message);
    if (!cell && k >= 0) {
        const Rule *r = &g_array_index(rules, Rule, k);
        if (!located(e->message) || !strstr(e->message, r->error))
            g_string_append_printf(bad, "\n  %s on %s: found '%s', "
                                        "expected a located error with '%s'",
                                   config, model, e->message, r->error);
    }
    if (cell)
        g_string_append_printf(md, " %s |", cell);
    else
        g_string_append_printf(md, " - (%d) |", k + 1);
    g_free(cell);
    g_clear_error(&e);
}

static GPtrArray *model_names(const char *dir, GError **err)
{
    GPtrArray *files = cli_yaml_files(dir, err);
    if (!files)
        return NULL;
    GPtrArray *n = g_ptr_array_new_with_free_func(g_free);
    for (guint i = 0; i < files->len; i++)
        g_ptr_array_add(n, stem(files->pdata[i]));
    g_ptr_array_unref(files);
    return n;
}

/* The `meaningless:` rules, then the `pending:` ones. */
static GArray *read_rules(const CfgNode *list, GError **err)
{
    static const char *const keys[] = {"meaningless", "pending"};
    GArray *rules = g_array_new(FALSE, TRUE, sizeof(Rule));
    for (guint k = 0; k < G_N_ELEMENTS(keys); k++) {
        const CfgNode *seq = cfg_get(list, keys[k]);
        for (guint i = 0; seq && i < cfg_seq_len(seq); i++) {
            Rule r = {.pending = k == 1};
            if (!read_rule(cfg_seq_at(seq, i), &r, err)) {
                g_array_free(rules, TRUE);
                return NULL;
            }
            g_array_append_val(rules, r);
        }
    }
    return rules;
}

static void legend(GString *md, const GArray *rules)
{
    g_string_append(md, "\nd: the run used costs derived from a processor "
                        "description, with work of the classes V vertex, "
                        "S setup, P pixel, Z zcmp, F flop, I instr, M miss, "
                        "B membyte; r: a node kind the workload names was "
                        "played by another (roles).  Meaningless "
                        "pairings, refused with a located error:\n\n");
    for (guint i = 0; i < rules->len; i++) {
        const Rule *r = &g_array_index(rules, Rule, i);
        g_string_append_printf(md, "%u. %s%s\n", i + 1,
                               r->pending ? "*Not yet runnable, to do (not "
                                            "meaningless):* "
                                          : "",
                               r->reason);
    }
}

gboolean pairings_table(const char *list_path, const char *configs_dir,
                        const char *models_dir, GString *md, GError **err)
{
    CfgNode *list = cfg_load_file(list_path, err);
    GArray *rules = list ? read_rules(list, err) : NULL;
    GPtrArray *configs = rules ? cli_yaml_files(configs_dir, err) : NULL;
    GPtrArray *models = configs ? model_names(models_dir, err) : NULL;
    GString *bad = g_string_new(NULL);
    if (models) {
        g_string_append(md, "| config |");
        for (guint j = 0; j < models->len; j++)
            g_string_append_printf(md, " %s |", (char *)models->pdata[j]);
        g_string_append(md, "\n|---|");
        for (guint j = 0; j < models->len; j++)
            g_string_append(md, "---|");
        g_string_append_c(md, '\n');
    }
    for (guint i = 0; models && i < configs->len; i++) {
        const char *path = configs->pdata[i];
        if (!is_run_config(path))
            continue;
        char *c = stem(path);
        const CfgNode *small = cfg_path(list, "small");
        small = small ? cfg_get(small, c) : NULL;
        g_string_append_printf(md, "| `%s` |", c);
        for (guint j = 0; j < models->len; j++)
            pairing(path, c, models->pdata[j], small, rules, md, bad);
        g_string_append_c(md, '\n');
        g_free(c);
    }
    if (models)
        legend(md, rules);
    gboolean ok = models && !bad->len;
    if (models && bad->len)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: the pairings and the list disagree (docs/models.md, "
                    "Pairings):%s",
                    list_path, bad->str);
    g_string_free(bad, TRUE);
    if (models)
        g_ptr_array_unref(models);
    if (configs)
        g_ptr_array_unref(configs);
    if (rules)
        g_array_free(rules, TRUE);
    cfg_free(list);
    return ok;
}
