/* test_pphigs_examples.c — seed 001's worked examples as shipped
 * databases (configs/pphigs/cube100.yaml, mesh16.yaml).  §2.2: a cube
 * instanced 100 times on 8 GPs, distributed by primitive (simple), puts
 * one face on each of 6 GPs and leaves 2 with no primitive to transform;
 * marking the cube a primitive structure (§2.3.3) or distributing by
 * structure (§2.1) leaves none idle.  §5.2: a 16x16 quad mesh dealt over
 * 16 GPs gives each GP one strip (a column of 16 quads: spatially
 * coherent, so a view of part of the mesh invalidates whole GPs'
 * weights, which §5.2's rebalancing is for).  Run from the repository
 * root (make test does).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <string.h>

#include "sim/run/run.h"
#include "tests/workload/pphigs/pphigs_rig.h"
#include "sim/scene/structdb_file.h"
#include "sim/workload/pphigs/pphigs_distrib.h"
#include "sim/workload/pphigs/pphigs_metrics.h"

/* GPs that transformed no primitive in a one-frame run of the cube. */
static guint cube_idle_gps(const char *db, const char *algo)
{
    char *d = g_strdup_printf("workload.database=%s", db);
    char *a = g_strdup_printf("workload.algorithm=%s", algo);
    const char *sets[] = {d, a, "workload.gps=8", "run.frames=1",
                          "workload.edits_per_frame=0",
                          "workload.rebalance.enabled=false", NULL};
    CfgRun *run = NULL;
    SimResult *r = pphigs_rig_run_flock(sets, &run);
    unsigned ph = G_MAXUINT;
    for (guint i = 0; i < r->phases->len; i++)
        if (!strcmp(g_ptr_array_index(r->phases, i), "transform"))
            ph = i;
    assert_true(ph != G_MAXUINT);
    guint idle = 0, gps = 0;
    for (guint i = 0; i < r->nodes->len; i++) {
        SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        if (strcmp(n->kind, "gp") != 0)
            continue;
        gps++;
        idle += sim_busy_phase(&n->busy, ph) == 0;
    }
    assert_int_equal(gps, 8); /* every GP executes the 100 instances */
    double img = 0;
    assert_true(sim_result_get_metric(r, "image_matches_serial", &img));
    assert_true(img == 1);
    sim_result_free(r);
    cfg_run_free(run);
    g_free(d);
    g_free(a);
    return idle;
}

static void test_cube_leaves_two_idle(void **st)
{
    (void)st;
    const char *cube = "configs/pphigs/cube100.yaml";
    assert_int_equal(cube_idle_gps(cube, "simple"), 2);
    assert_int_equal(cube_idle_gps(cube, "by_structure"), 0);
    /* the same cube as a primitive structure (§2.3.3) */
    CfgNode *root = cfg_load_file(cube, NULL);
    assert_non_null(root);
    SceneDb *db = scene_db_from_cfg(root, NULL);
    assert_non_null(db);
    guint sid = 0;
    assert_true(scene_db_find(db, "cube", &sid));
    scene_db_set_primitive(db, sid, TRUE);
    char *path = g_build_filename(g_get_tmp_dir(), "pgsim-cube100p.yaml",
                                  NULL);
    assert_true(scene_db_save(db, path, NULL));
    assert_int_equal(cube_idle_gps(path, "complex"), 0);
    g_unlink(path);
    g_free(path);
    scene_db_free(db);
    cfg_free(root);
}

typedef struct {
    double x[256];
    guint n;
} Quads;

static void quad_x(const ScenePrimInst *pi, void *ud)
{
    Quads *q = ud;
    q->x[q->n++] = pi->el->verts[0].x;
}

/* Every GP holds 16 quads of one column (x equal): a strip each. */
static void test_mesh_strips(void **st)
{
    (void)st;
    SceneDb *db = scene_db_load("configs/pphigs/mesh16.yaml", NULL);
    assert_non_null(db);
    /* any costs: equal quads weigh the same */
    static const WlPphigsCosts c = {.poly = SIM_US, .vertex = SIM_US};
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(&c, 4, &w);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 16, WL_PPHIGS_SIMPLE, &w);
    double seen[16];
    for (guint g = 0; g < 16; g++) {
        Quads q = {.n = 0};
        scene_db_traverse(wl_pphigs_dist_gp(d, g), quad_x, &q);
        assert_int_equal(q.n, 16);
        for (guint i = 1; i < q.n; i++)
            assert_true(q.x[i] == q.x[0]);
        seen[g] = q.x[0];
        for (guint h = 0; h < g; h++)
            assert_true(seen[h] != seen[g]); /* 16 different columns */
    }
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube_leaves_two_idle),
        cmocka_unit_test(test_mesh_strips),
    };
    return cmocka_run_group_tests_name("pphigs_examples", tests, NULL, NULL);
}
