/* test_pphigs_cfg.c — the pphigs workload through its YAML: the generated
 * databases' statistics match the published "db" rows of
 * configs/papers/ellsworth90.yaml (both files read through cfg); bad
 * inputs fail with a located error; the reproduction's event-driven
 * frames give the analytic traversal's metrics; the `pphigs` workload
 * runs configs/pphigs-flock.yaml deterministically and honours
 * overrides.  Run from the repository root (make test does).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pphigs/ellsworth90.h"
#include "sim/workload/workload.h"
#include <string.h>

static const char *const names[] = {"space_station", "building_lobby",
                                    "flock_old_well", "two_human_figures"};

/* Published value of a "db" cell, or FALSE when the paper has none. */
static gboolean published(const CfgNode *paper, const char *row,
                          const char *col, double *v)
{
    char *path = g_strdup_printf("tables.db.rows.%s", row);
    const CfgNode *r = cfg_path(paper, path);
    g_free(path);
    assert_non_null(r);
    if (!cfg_get(r, col))
        return FALSE;
    assert_true(cfg_get_double(r, col, TRUE, 0, 1e9, v, NULL));
    return TRUE;
}

/* Within the table's printed precision (3 significant digits). */
static void near(double sim, double pub, double tol)
{
    assert_true(fabs(sim - pub) <= tol * fabs(pub) + 1e-9);
}

static void test_db_stats_match_paper(void **st)
{
    (void)st;
    CfgNode *paper = cfg_load_file("configs/papers/ellsworth90.yaml", NULL);
    assert_non_null(paper);
    for (guint i = 0; i < G_N_ELEMENTS(names); i++) {
        ScenePphigsSpec s;
        ScenePphigsDb db;
        assert_true(wl_pphigs_spec_load("configs/pphigs/databases.yaml",
                                        names[i], &s, NULL));
        assert_true(scene_pphigs_generate(&s, &db, NULL));
        SceneDbStats x;
        scene_db_stats(db.db, &x);
        double v;
        assert_true(published(paper, names[i], "depth", &v));
        assert_int_equal(x.depth, (guint)v);
        assert_true(published(paper, names[i], "structures", &v));
        assert_int_equal(x.structures, (guint)v);
        assert_true(published(paper, names[i], "polys_per_structure", &v));
        near((double)x.primitives / x.structures, v, 0.005);
        assert_true(published(paper, names[i], "poly_attr_ratio", &v));
        near((double)x.primitives / x.attributes, v, 0.005);
        double off = 100 * scene_pphigs_offscreen_share(
                               db.db, scene_camera_view_proj(&db.camera));
        if (published(paper, names[i], "offscreen_pct", &v))
            assert_true(fabs(off - v) < 2.0);
        else
            assert_true(off < 1.0);
        scene_pphigs_db_clear(&db);
    }
    cfg_free(paper);
}

static void expect_error(const char *yaml, const char *what)
{
    GError *err = NULL;
    CfgNode *n = cfg_load_string(yaml, "bad.yaml", NULL);
    assert_non_null(n);
    ScenePphigsSpec s;
    assert_false(wl_pphigs_spec_from_cfg(n, &s, &err));
    assert_non_null(err);
    assert_non_null(strstr(err->message, "bad.yaml:"));
    assert_non_null(strstr(err->message, what));
    g_clear_error(&err);
    cfg_free(n);
}

static void test_bad_specs(void **st)
{
    (void)st;
    expect_error("{kind: teapot, seed: 1}", "teapot");
    expect_error("{kind: space_station, polygns: 10}", "polygns");
    expect_error("{kind: space_station, polygons: -3}", "-3");
    GError *err = NULL;
    ScenePphigsSpec s;
    assert_false(wl_pphigs_spec_load("configs/pphigs/databases.yaml",
                                     "teapots", &s, &err));
    assert_non_null(strstr(err->message, "teapots"));
    g_clear_error(&err);
}

static void test_frames_equal_analytic(void **st)
{
    (void)st;
    CfgNode *fr = cfg_load_file("configs/pphigs/frame.yaml", NULL);
    assert_non_null(fr);
    WlPphigsHw hw;
    assert_true(wl_pphigs_hw_load("models/pixel-planes-5.yaml", fr, &hw,
                                  NULL));
    hw.fidelity = NET_PACKET;
    ScenePphigsSpec s;
    assert_true(wl_pphigs_spec_load("configs/pphigs/databases.yaml",
                                    "flock_old_well", &s, NULL));
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    WlPphigsMetrics a[2], b[2];
    wl_pphigs_run_db(&db, 4, &hw.costs, hw.cluster_scale, &hw, &a[0],
                     &a[1]);
    wl_pphigs_run_db(&db, 4, &hw.costs, hw.cluster_scale, NULL, &b[0],
                     &b[1]);
    for (int k = 0; k < 2; k++) {
        near(a[k].t1, b[k].t1, 1e-9);
        near(a[k].efficiency, b[k].efficiency, 1e-9);
        near(a[k].utilisation, b[k].utilisation, 1e-9);
    }
    assert_true(a[1].efficiency > a[0].efficiency); /* complex wins */
    scene_pphigs_db_clear(&db);
    cfg_free(fr);
}

typedef struct {
    GArray *frames;
    double m[9];
    uint64_t bytes;
} Out;

static void run_flock(const char *const *sets, Out *o)
{
    CfgNode *root = cfg_load_file("configs/pphigs-flock.yaml", NULL);
    assert_non_null(root);
    assert_true(cfg_set_override(root, "workload.gps=4", NULL));
    for (; sets && *sets; sets++)
        assert_true(cfg_set_override(root, *sets, NULL));
    const WlOps *ops = wl_find("pphigs");
    assert_non_null(ops);
    GError *err = NULL;
    assert_non_null(cfg_get(cfg_get(root, "workload"), "type")); /* app's */
    void *p = ops->parse(cfg_get(root, "workload"), &err);
    assert_non_null(p);
    SimEngine *eng = sim_engine_new(3);
    WlContext ctx = {eng, root, 3, "packet", 3, NULL, TRUE};
    SimResult *r = sim_result_new("pphigs", "pixel-planes-5");
    assert_true(ops->run(&ctx, p, r, &err));
    assert_true(cfg_check_unused(cfg_get(root, "workload"), NULL));
    o->frames = g_array_new(FALSE, FALSE, sizeof(SimTime));
    g_array_append_vals(o->frames, r->frame_times->data,
                        r->frame_times->len);
    assert_int_equal(r->metrics->len, 9);
    for (guint i = 0; i < 9; i++)
        o->m[i] = ((SimMetric *)g_ptr_array_index(r->metrics, i))->value;
    o->bytes = r->comm_bytes;
    assert_int_equal(r->nodes->len, 4 + 16 + 1);
    sim_result_free(r);
    sim_engine_free(eng);
    ops->free_params(p);
    cfg_free(root);
}

static void test_workload_runs(void **st)
{
    (void)st;
    Out a, b, c;
    run_flock(NULL, &a);
    run_flock(NULL, &b);
    assert_int_equal(a.frames->len, 3);
    assert_memory_equal(a.frames->data, b.frames->data,
                        3 * sizeof(SimTime));
    assert_memory_equal(a.m, b.m, sizeof a.m);
    assert_int_equal(a.bytes, b.bytes);
    assert_true(a.m[7] == 12); /* 4 edits x 3 frames */
    const char *sets[] = {"workload.database=building_lobby",
                          "workload.algorithm=simple",
                          "workload.edits_per_frame=0", NULL};
    run_flock(sets, &c);
    assert_true(c.m[7] == 0);
    assert_true(c.m[4] != a.m[4]); /* other database: other commands */
    g_array_unref(a.frames);
    g_array_unref(b.frames);
    g_array_unref(c.frames);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_db_stats_match_paper),
        cmocka_unit_test(test_bad_specs),
        cmocka_unit_test(test_frames_equal_analytic),
        cmocka_unit_test(test_workload_runs),
    };
    return cmocka_run_group_tests_name("pphigs_cfg", tests, NULL, NULL);
}
