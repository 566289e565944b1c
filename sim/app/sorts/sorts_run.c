/* sorts_run.c — runs a comparison (sorts.h): each sort's run config
 * built from the shared sections at each P, run through the runner, and
 * its row (overlap, bytes, balance, frame time) read from the result;
 * then the two charts against processors. */
#include "sim/app/sorts/sorts.h"
#include "sim/core/error.h"
#include "sim/output/plot.h"
#include "sim/run/run.h"
#include "sim/scene/scene.h"
#include "sim/scene/scene_cfg.h"
#include "sim/scene/structdb_file.h"
#include <math.h>
#include <string.h>

double sorts_kind_balance(const SimResult *r, const char *kind, guint n)
{
    double sum = 0, max = 0;
    guint busy = 0;
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *nr = g_ptr_array_index(r->nodes, i);
        if (strcmp(nr->kind, kind) != 0)
            continue;
        double b = (double)nr->busy.total;
        sum += b;
        max = MAX(max, b);
        busy++;
    }
    if (n == 0 || busy > n || sum <= 0)
        return NAN;
    return max / (sum / (double)n);
}

/* The scene's structure database written to out_dir/<name>-db.yaml (for
 * the sorts that read the scene as a database file); its path, or NULL
 * with *err. */
static char *write_db(const SortsSpec *s, const char *out_dir, GError **err)
{
    Scene *sc = scene_from_cfg(s->scene, err);
    if (!sc)
        return NULL;
    char *path = NULL;
    if (!sc->db) {
        cfg_error(err, s->scene, "a scene without a structure database",
                  "a hierarchical scene (e.g. generator: flock_old_well) for "
                  "a sort with scene: database");
    } else {
        char *file = g_strdup_printf("%s-db.yaml", s->name);
        path = g_build_filename(out_dir, file, NULL);
        g_free(file);
        if (!scene_db_save(sc->db, path, err)) {
            g_free(path);
            path = NULL;
        }
    }
    scene_free(sc);
    return path;
}

/* "key=value" set on the run tree, the value a YAML scalar. */
static gboolean set_key(CfgNode *root, const char *key, const char *value,
                        GError **err)
{
    char *a = g_strdup_printf("%s=%s", key, value);
    gboolean ok = cfg_set_override(root, a, err);
    g_free(a);
    return ok;
}

/* share x procs as a whole number of processors (at least 1) in *out,
 * else an input error naming the sort and `what`. */
static gboolean share_of(const SortsSort *o, const char *what, double share,
                         guint procs, guint *out, GError **err)
{
    double v = procs * share;
    if (v >= 1 && v == floor(v)) {
        *out = (guint)v;
        return TRUE;
    }
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "sort '%s': found %s = %g x %u = %g, expected a whole "
                "number of processors, at least 1",
                o->sort, what, share, procs, v);
    return FALSE;
}

/* The run config of sort o at P processors (cfg_free), or NULL. */
static CfgNode *run_tree(const SortsSpec *s, const SortsSort *o, guint procs,
                         const char *db_path, GError **err)
{
    CfgNode *root = cfg_load_string("schema_version: 1\n", "three-sorts", err);
    if (!root)
        return NULL;
    if (s->machine)
        cfg_map_put(root, "machine", cfg_copy(s->machine));
    if (s->scene && !o->scene_as_db)
        cfg_map_put(root, "scene", cfg_copy(s->scene));
    if (s->run)
        cfg_map_put(root, "run", cfg_copy(s->run));
    cfg_map_put(root, "workload", cfg_copy(o->workload));
    gboolean ok = !o->scene_as_db || set_key(root, "workload.database",
                                             db_path, err);
    for (guint k = 0; ok && k < o->keys->len; k++) {
        guint v;
        ok = share_of(o, o->keys->pdata[k], g_array_index(o->shares, double, k),
                      procs, &v, err);
        char *val = g_strdup_printf("%u", v);
        ok = ok && set_key(root, o->keys->pdata[k], val, err);
        g_free(val);
    }
    if (!ok) {
        cfg_free(root);
        return NULL;
    }
    return root;
}

/* A metric the sort names, from result r; an input error naming it when
 * the run did not set it. */
static gboolean read_metric(const SortsSort *o, const SimResult *r,
                            const char *name, double *out, GError **err)
{
    if (sim_result_get_metric(r, name, out))
        return TRUE;
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "sort '%s': found no metric '%s' in the %s run, expected "
                "a metric the workload sets (pgsim help run lists them)",
                o->sort, name, r->workload);
    return FALSE;
}

static char *num(double v)
{
    char buf[G_ASCII_DTOSTR_BUF_SIZE];
    if (isnan(v))
        return g_strdup("");
    return g_strdup(g_ascii_formatd(buf, sizeof buf, "%.6g", v));
}

/* One row of the table from the run of o at procs. */
static gboolean add_row(DataTable *t, const SortsSort *o, guint procs,
                        const SimResult *r, GError **err)
{
    double overlap, bytes, frame, balance = NAN;
    guint n;
    if (!read_metric(o, r, o->overlap, &overlap, err) ||
        !read_metric(o, r, o->bytes, &bytes, err) ||
        !read_metric(o, r, o->frame, &frame, err))
        return FALSE;
    for (guint k = 0; k < o->balance->len; k++) {
        const char *kind = o->balance->pdata[k];
        if (!share_of(o, kind, g_array_index(o->bshares, double, k), procs,
                      &n, err))
            return FALSE;
        double b = sorts_kind_balance(r, kind, n);
        if (isnan(b)) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "sort '%s': found no busy processor of kind '%s', or "
                        "more than %u, in the %s run, expected the %u "
                        "processors of the kind that do its work",
                        o->sort, kind, n, r->workload, n);
            return FALSE;
        }
        balance = isnan(balance) ? b : MAX(balance, b);
    }
    char *cells[6] = {g_strdup(o->sort), g_strdup_printf("%u", procs),
                      num(overlap), num(bytes), num(balance), num(frame)};
    dt_add_row(t, cells);
    for (guint i = 0; i < 6; i++)
        g_free(cells[i]);
    return TRUE;
}

static gboolean run_one(const SortsSpec *s, const SortsSort *o, guint procs,
                        const char *db_path, DataTable *t, GError **err)
{
    CfgNode *tree = run_tree(s, o, procs, db_path, err);
    if (!tree)
        return FALSE;
    CfgRun *run = cfg_run_from_tree(tree, NULL, err);
    if (!run)
        return FALSE;
    CfgRunOpts opts = {.quiet = TRUE};
    SimResult *r = cfg_run_exec(run, &opts, err);
    gboolean ok = r && add_row(t, o, procs, r, err);
    if (r)
        sim_result_free(r);
    cfg_run_free(run);
    return ok;
}

DataTable *sorts_run(const SortsSpec *s, const char *out_dir, GError **err)
{
    static const char *const cols[] = {"sort",    "processors", "overlap",
                                       "bytes",   "balance",    "frame_ms",
                                       NULL};
    char *db_path = NULL;
    for (guint i = 0; i < s->sorts->len && !db_path; i++)
        if (((SortsSort *)s->sorts->pdata[i])->scene_as_db &&
            !(db_path = write_db(s, out_dir, err)))
            return NULL;
    DataTable *t = dt_new_named(cols);
    gboolean ok = TRUE;
    for (guint i = 0; ok && i < s->sorts->len; i++)
        for (guint j = 0; ok && j < s->procs->len; j++)
            ok = run_one(s, s->sorts->pdata[i],
                         g_array_index(s->procs, guint, j), db_path, t, err);
    g_free(db_path);
    if (!ok) {
        dt_free(t);
        return NULL;
    }
    return t;
}

static gboolean chart(const DataTable *t, const char *dir, const char *name,
                      const char *y, const char *ylabel, const char *title,
                      GError **err)
{
    PlotSpec *p = plot_spec_new(name, "processors", y);
    p->series = g_strdup("sort");
    p->logx = TRUE;
    p->logy = TRUE;
    p->xlabel = g_strdup("processors");
    p->ylabel = g_strdup(ylabel);
    p->title = g_strdup(title);
    gboolean ok = plot_render(p, t, dir, err);
    plot_spec_free(p);
    return ok;
}

gboolean sorts_charts(const SortsSpec *s, const DataTable *t,
                      const char *out_dir, GError **err)
{
    char *fn = g_strdup_printf("%s-frame", s->name);
    char *bn = g_strdup_printf("%s-bytes", s->name);
    gboolean ok =
        chart(t, out_dir, fn, "frame_ms", "frame time (ms)",
              "One scene, three sorts: frame time against processors", err) &&
        chart(t, out_dir, bn, "bytes", "communication per frame (B)",
              "One scene, three sorts: bytes per frame against processors",
              err);
    g_free(fn);
    g_free(bn);
    return ok;
}
