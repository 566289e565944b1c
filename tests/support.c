/* support.c — set-up steps many test binaries share (support.h). */
#include "tests/support.h"
#include "sim/run/run.h"

#include <glib.h>
#include <glib/gstdio.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

void support_warnings_fatal(void)
{
    g_log_set_always_fatal(G_LOG_FATAL_MASK | G_LOG_LEVEL_WARNING |
                           G_LOG_LEVEL_CRITICAL);
}

int support_test_models(void **state)
{
    (void)state;
    g_setenv("PGSIM_MODELS", "tests/data/models", TRUE);
    return 0;
}

static int vec3_same(Vec3 a, Vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

int support_camera_equal(const SceneCamera *a, const SceneCamera *b)
{
    return a->proj == b->proj && vec3_same(a->eye, b->eye) &&
           vec3_same(a->target, b->target) && vec3_same(a->up, b->up) &&
           a->fov_deg == b->fov_deg && a->height == b->height &&
           a->near == b->near && a->far == b->far && a->aspect == b->aspect;
}

int support_entries(const char *dir)
{
    GDir *d = g_dir_open(dir, 0, NULL);
    int n = 0;
    while (d && g_dir_read_name(d))
        n++;
    if (d)
        g_dir_close(d);
    return n;
}

void support_rm_tree(const char *path)
{
    GDir *d = g_dir_open(path, 0, NULL);
    if (d) {
        const char *e;
        while ((e = g_dir_read_name(d))) {
            char *p = g_build_filename(path, e, NULL);
            support_rm_tree(p);
            g_free(p);
        }
        g_dir_close(d);
    }
    g_remove(path);
}

/* The run settings of `o` as overrides, after the caller's own. */
static GPtrArray *run_overrides(const CfgNode *root, const SupportRun *o)
{
    GPtrArray *ov = g_ptr_array_new_with_free_func(g_free);
    if (!cfg_has(root, "schema_version"))
        g_ptr_array_add(ov, g_strdup("schema_version=1"));
    if (o && o->fidelity)
        g_ptr_array_add(ov, g_strdup_printf("run.fidelity=%s", o->fidelity));
    if (o && o->frames)
        g_ptr_array_add(ov, g_strdup_printf("run.frames=%d", o->frames));
    if (o && o->seed)
        g_ptr_array_add(ov, g_strdup_printf("run.seed=%" G_GUINT64_FORMAT,
                                            o->seed));
    for (guint i = 0; o && o->overrides && o->overrides[i]; i++)
        g_ptr_array_add(ov, g_strdup(o->overrides[i]));
    g_ptr_array_add(ov, NULL);
    return ov;
}

SimResult *support_run_tree(CfgNode *root, const SupportRun *o, GError **err)
{
    GPtrArray *ov = run_overrides(root, o);
    CfgRun *run =
        cfg_run_from_tree(root, (const char *const *)ov->pdata, err);
    g_ptr_array_free(ov, TRUE);
    if (!run)
        return NULL;
    CfgRunOpts opts = {.out_dir = o ? o->out_dir : NULL,
                       .quiet = TRUE,
                       .trace = o ? o->trace : NULL,
                       .dry_run = o && o->dry_run,
                       .all_frames = o && o->all_frames};
    SimResult *r = cfg_run_exec(run, &opts, err);
    if (o && o->now)
        *o->now = sim_now(run->eng);
    cfg_run_free(run);
    return r;
}

SimResult *support_run_text(const char *yaml, const SupportRun *o,
                            GError **err)
{
    CfgNode *root = cfg_load_string(yaml, "test.yaml", err);
    return root ? support_run_tree(root, o, err) : NULL;
}

double support_metric(const SimResult *r, const char *name)
{
    double v = -1;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}
