/* rp_driver.c — running reproductions and collecting their tables.
 *
 * A pass: run the paper's rows hook on its setup file (wall time
 * measured around the hook only), then load the published values and
 * join.  The paper file is read once per
 * pass, which is negligible next to the simulation.  O(rows + cells).
 */
#include "sim/reproduce/rp_driver.h"
#include "sim/reproduce/rp_labels.h"
#include "sim/output/provenance.h"
#include <string.h>

const char *const rp_fidelities[] = {"analytic", "flow", "packet", NULL};

gboolean rp_fidelity_valid(const char *f)
{
    if (strcmp(f, RP_DEFAULT_FIDELITY) == 0)
        return TRUE;
    for (int i = 0; rp_fidelities[i]; i++)
        if (strcmp(f, rp_fidelities[i]) == 0)
            return TRUE;
    return FALSE;
}

static RpPaper *load_paper(const RpPaperOps *rp, const char *dir,
                           GError **err)
{
    char *path = rp_paper_path(dir ? dir : RP_PAPERS_DIR, rp->name);
    RpPaper *p = rp_paper_load(path, err);
    if (p && strcmp(p->name, rp->name) != 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found paper.name '%s', expected '%s'", path, p->name,
                    rp->name);
        rp_paper_free(p);
        p = NULL;
    }
    g_free(path);
    return p;
}

/* The setup file's SHA-256 and tree into t's provenance, under `name`:
 * the path as the user gave it, or the paper's own setup named relative
 * to the data root it was found in ("configs/papers/kurc96/setup.yaml",
 * not "/.../build/../configs/..."), so the line is the same wherever the
 * checkout or the binary lies. */
static void note_setup(RpTable *t, const char *setup, const char *name)
{
    t->setup = g_strdup(name);
    t->setup_sha256 = prov_file_sha256(setup);
    CfgNode *root = cfg_load_file(setup, NULL);
    t->setup_json = root ? prov_cfg_json(root) : NULL;
    cfg_free(root);
}

/* Labels t from <dir>/<name>/labels.yaml when the paper has one. */
static gboolean apply_labels(RpTable *t, const char *dir, const char *name,
                      GError **err)
{
    char *path = rp_paper_file(dir, name, RP_LABELS_FILE);
    gboolean ok = TRUE;
    if (g_file_test(path, G_FILE_TEST_EXISTS)) {
        RpLabels *l = rp_labels_load(path, err);
        ok = l != NULL;
        if (l)
            rp_labels_apply(l, t);
        rp_labels_free(l);
    }
    g_free(path);
    return ok;
}

RpTable *rp_drive(const RpPaperOps *rp, const char *papers_dir,
                  const RpContext *ctx, GError **err)
{
    g_assert(ctx->fidelity);
    RpPaper *paper = load_paper(rp, papers_dir, err);
    if (!paper)
        return NULL;
    RpContext c = *ctx;
    const char *dir = papers_dir ? papers_dir : RP_PAPERS_DIR;
    char *setup = rp_paper_file(dir, rp->name, rp->setup);
    char *setup_name = g_build_filename(dir, rp->name, rp->setup, NULL);
    if (!c.setup)
        c.setup = setup;
    GString *used = g_string_new(NULL);
    c.fidelity_used = used;
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    SimInputs *inputs = sim_inputs_new();
    sim_inputs_push(inputs);
    gint64 t0 = g_get_monotonic_time();
    gboolean ok = rp->rows(&c, rows, err);
    double wall = (double)(g_get_monotonic_time() - t0) * 1e-6;
    sim_inputs_pop(inputs);
    gboolean faithful = strcmp(ctx->fidelity, RP_DEFAULT_FIDELITY) == 0;
    char *label = faithful && used->len ? g_strdup_printf("%s: %s", ctx->fidelity,
                                              used->str)
                            : g_strdup(ctx->fidelity);
    RpTable *t = ok ? rp_table_join(paper, rows, label, wall) : NULL;
    if (t) {
        note_setup(t, c.setup, ctx->setup ? ctx->setup : setup_name);
        t->inputs = inputs;
        inputs = NULL;
        t->overrides = g_ptr_array_new_with_free_func(g_free);
        for (int i = 0; ctx && ctx->sets && ctx->sets[i]; i++)
            g_ptr_array_add(t->overrides, g_strdup(ctx->sets[i]));
    }
    sim_inputs_free(inputs);
    if (t && !apply_labels(t, dir, rp->name, err)) {
        rp_table_free(t);
        t = NULL;
        ok = TRUE; /* the error is the labels file's, unprefixed */
    }
    g_free(label);
    g_string_free(used, TRUE);
    if (!ok)
        g_prefix_error(err, "%s (fidelity %s): ", rp->name, ctx->fidelity);
    g_ptr_array_free(rows, TRUE);
    rp_paper_free(paper);
    g_free(setup);
    g_free(setup_name);
    return t;
}

GPtrArray *rp_drive_fidelities(const RpPaperOps *rp, const char *papers_dir,
                               const RpContext *ctx, GError **err)
{
    GPtrArray *out =
        g_ptr_array_new_with_free_func((GDestroyNotify)rp_table_free);
    for (int i = 0; rp_fidelities[i]; i++) {
        RpContext c = *ctx;
        c.fidelity = rp_fidelities[i];
        RpTable *t = rp_drive(rp, papers_dir, &c, err);
        if (!t) {
            g_ptr_array_free(out, TRUE);
            return NULL;
        }
        g_ptr_array_add(out, t);
    }
    return out;
}

/* The run of tree or path with ov (char *, taken) and then the user's
 * ctx->sets, on ctx->models. */
static CfgRun *build_with_user(const RpContext *ctx, CfgNode *tree,
                               const char *path, GPtrArray *ov, GError **err)
{
    for (int i = 0; ctx->sets && ctx->sets[i]; i++)
        g_ptr_array_add(ov, g_strdup(ctx->sets[i]));
    g_ptr_array_add(ov, NULL);
    const char *const *all = (const char *const *)ov->pdata;
    CfgRun *r = tree ? cfg_run_from_tree_in(tree, all, ctx->models, err)
                     : cfg_run_load_in(path, all, ctx->models, err);
    g_ptr_array_free(ov, TRUE);
    return r;
}

static GPtrArray *copy_sets(const char *const *sets)
{
    GPtrArray *ov = g_ptr_array_new_with_free_func(g_free);
    for (guint i = 0; sets && sets[i]; i++)
        g_ptr_array_add(ov, g_strdup(sets[i]));
    return ov;
}

char **rp_sets_of(const CfgNode *m, GError **err)
{
    const CfgNode *set = cfg_get(m, "set");
    if (set && cfg_kind(set) != CFG_SEQ) {
        cfg_error(err, set, "a non-list set", "set: [key=value, ...]");
        return NULL;
    }
    guint n = set ? cfg_seq_len(set) : 0;
    char **v = g_new0(char *, n + 1);
    for (guint i = 0; i < n; i++) {
        const char *s = cfg_scalar(cfg_seq_at(set, i));
        if (!s) {
            cfg_error(err, cfg_seq_at(set, i), "a non-scalar override",
                      "key=value");
            g_strfreev(v);
            return NULL;
        }
        v[i] = g_strdup(s);
    }
    return v;
}

CfgRun *rp_run_build(const RpContext *ctx, CfgNode *tree, const char *path,
                     const char *const *sets, GError **err)
{
    GPtrArray *ov = copy_sets(sets);
    g_ptr_array_add(ov, g_strdup_printf("run.fidelity=%s",
                                        ctx->fidelity ? ctx->fidelity
                                                      : "analytic"));
    g_ptr_array_add(ov, g_strdup_printf("run.seed=%d", (int)RP_SEED));
    return build_with_user(ctx, tree, path, ov, err);
}

CfgRun *rp_run_build_as_is(const RpContext *ctx, CfgNode *tree,
                           const char *const *sets, GError **err)
{
    return build_with_user(ctx, tree, NULL, copy_sets(sets), err);
}

SimResult *rp_run_exec(const RpContext *ctx, CfgRun *r, WlShare *share,
                       GError **err)
{
    CfgRunOpts o = {.quiet = TRUE, .share = share};
    SimResult *res = cfg_run_exec(r, &o, err);
    if (res) {
        const char *model = cfg_scalar(cfg_path(r->root, "machine.model"));
        rp_note_fidelity(ctx, model ? model : mach_name(r->machine_built),
                         mach_fidelity(r->machine_built));
    }
    return res;
}

void rp_step(const RpContext *ctx, const char *what)
{
    if (!ctx || !ctx->progress)
        return;
    RptProgress *p = ctx->progress;
    rpt_progress_note(p, what);
    rpt_progress_update(p, rpt_progress_done(p) + 1);
}

void rp_note_fidelity(const RpContext *ctx, const char *machine,
                      const char *fidelity)
{
    if (!ctx || !ctx->fidelity_used)
        return;
    char *word = g_strndup(fidelity, strcspn(fidelity, " "));
    char *item = g_strdup_printf("%s %s", machine, word);
    if (!strstr(ctx->fidelity_used->str, item))
        g_string_append_printf(ctx->fidelity_used, "%s%s",
                               ctx->fidelity_used->len ? ", " : "", item);
    g_free(item);
    g_free(word);
}
