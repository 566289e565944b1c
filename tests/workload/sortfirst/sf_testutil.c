/* sf_testutil.c — see sf_testutil.h. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/scene_cfg.h"
#include "tests/support.h"
#include "tests/workload/sortfirst/sf_testutil.h"

SimResult *sf_test_run(const char *text, const char *const *overrides,
                       int frames, const char *out_dir, gboolean all,
                       GError **err)
{
    CfgNode *root = cfg_load_string(text, "sf.yaml", err);
    assert_non_null(root);
    for (guint k = 0; overrides && overrides[k]; k++)
        assert_true(cfg_set_override(root, overrides[k], err));
    SupportRun o = {.fidelity = "analytic",
                    .frames = frames,
                    .seed = 1,
                    .out_dir = out_dir,
                    .all_frames = all};
    return support_run_tree(root, &o, err);
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

WlSfDb *sf_test_tiny_db(SceneDb **src, guint procs)
{
    Vec3 t[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    *src = scene_db_new();
    guint r = scene_db_add_struct(*src, "r");
    for (int i = 0; i < 3; i++) {
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, t, 3);
        assert_true(scene_db_append(*src, r, &e, NULL));
    }
    scene_db_post(*src, r);
    WlSfDb *db = wl_sf_db_new(*src, procs, 2, WL_SF_CHUNK_SORTED, NULL);
    assert_non_null(db);
    assert_int_equal(wl_sf_n_chunks(db), 2);
    assert_int_equal(wl_sf_chunk(db, 0)->polys, 2);
    assert_int_equal(wl_sf_chunk(db, 1)->polys, 1);
    return db;
}

/* A right triangle over [x0, x1] x [y0, y1] at z = 0. */
static void tri(SceneDb *db, guint sid, double x0, double y0, double x1,
                double y1)
{
    Vec3 v[3] = {vec3(x0, y0, 0), vec3(x1, y0, 0), vec3(x0, y1, 0)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    assert_true(scene_db_append(db, sid, &e, NULL));
}

SceneDb *sf_test_hand_db(void)
{
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    tri(db, root, -0.75, 0.25, -0.25, 0.75); /* tile 0 */
    tri(db, root, 0.25, 0.25, 0.75, 0.75);   /* tile 1 */
    tri(db, root, -0.25, -0.25, 0.25, 0.25); /* all four */
    tri(db, root, 3, 0, 3.5, 0.5);           /* off */
    tri(db, root, 3, -1, 3.5, -0.5);         /* off */
    scene_db_post(db, root);
    return db;
}

void sf_test_edit_init(SfEditFixture *f, WlSfBookkeeping bk,
                       const WlSfEditSpec *spec)
{
    GError *e = NULL;
    f->root = cfg_load_string(SF_TEST_SMALL, "sf.yaml", &e);
    assert_non_null(f->root);
    f->scene = scene_from_cfg(cfg_get(f->root, "scene"), &e);
    assert_non_null(f->scene);
    f->eng = sim_engine_new(1);
    f->m = mach_new_from_model(f->eng, "cluster-ib", "analytic", &e);
    assert_non_null(f->m);
    assert_true(wl_sf_costs_from_machine(f->m, &f->c, &e));
    f->db = wl_sf_db_new(f->scene->db, 4, 5, WL_SF_CHUNK_SORTED, &e);
    assert_non_null(f->db);
    WlSfSetup s = {.procs = 4,
                   .resolution = 64,
                   .bk = bk,
                   .sizes = {64, 40, 36, 8, 4, 8, 16, 96},
                   .cull_back = TRUE,
                   .check_image = TRUE,
                   .edits = TRUE};
    f->run = wl_sf_run_new(f->m, f->scene, f->db, &s, &f->c);
    f->edit = wl_sf_edit_new(f->scene->db, f->db, spec,
                             sim_entity_rng(f->eng,
                                            sim_entity_add(f->eng, "editor")));
    wl_sf_run_set_edit(f->run, f->edit);
}

void sf_test_edit_clear(SfEditFixture *f)
{
    wl_sf_run_free(f->run);
    wl_sf_edit_free(f->edit);
    wl_sf_db_free(f->db);
    mach_free(f->m);
    sim_engine_free(f->eng);
    scene_free(f->scene);
    cfg_free(f->root);
}
