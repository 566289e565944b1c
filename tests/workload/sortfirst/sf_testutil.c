/* sf_testutil.c — see sf_testutil.h. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "tests/workload/sortfirst/sf_testutil.h"

SimResult *sf_test_run(const char *text, const char *const *overrides,
                       int frames, const char *out_dir, gboolean all,
                       GError **err)
{
    CfgNode *root = cfg_load_string(text, "sf.yaml", err);
    assert_non_null(root);
    for (guint k = 0; overrides && overrides[k]; k++)
        assert_true(cfg_set_override(root, overrides[k], err));
    void *p = wl_sortfirst_ops.parse(cfg_get(root, "workload"), err);
    SimResult *r = NULL;
    if (p) {
        SimEngine *eng = sim_engine_new(1);
        WlContext ctx = {.eng = eng,
                         .root = root,
                         .seed = 1,
                         .fidelity = "analytic",
                         .frames = frames,
                         .out_dir = out_dir,
                         .quiet = TRUE,
                         .all_frames = all};
        r = sim_result_new("sortfirst", "");
        if (!wl_sortfirst_ops.run(&ctx, p, r, err)) {
            sim_result_free(r);
            r = NULL;
        }
        sim_engine_free(eng);
        wl_sortfirst_ops.free_params(p);
    }
    cfg_free(root);
    return r;
}

SimResult *sf_test_run_checked(const char *text, int frames,
                               const char *key_a, const char *val_a,
                               const char *key_b, const char *val_b)
{
    char *a = g_strdup_printf("%s=%s", key_a, val_a);
    char *b = g_strdup_printf("%s=%s", key_b, val_b);
    const char *const o[] = {a, b, NULL};
    GError *e = NULL;
    SimResult *r = sf_test_run(text, o, frames, NULL, FALSE, &e);
    if (!r)
        fail_msg("%s", e->message);
    assert_true(sf_test_metric(r, "image_matches_serial") == 1);
    g_free(a);
    g_free(b);
    return r;
}

double sf_test_metric(const SimResult *r, const char *name)
{
    double v = NAN;
    assert_true(sim_result_get_metric(r, name, &v));
    return v;
}
