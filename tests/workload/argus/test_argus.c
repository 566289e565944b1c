/* test_argus.c — the argus workload (seed 002): the parallel API's
 * ordering reaches the frame buffer (a back-to-front blended scene equals
 * the serial render when the semaphores are honoured and differs when the
 * same loop is issued without them, with static tile owners and with
 * the worker pool, which also balances better), --out DIR gets
 * DIR/frame.png through the frame hook, the streams of Figure 3(c) carry
 * the waits and signals they should, more contexts go faster when the
 * application work dominates, and a machine without enough processors
 * is refused. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <string.h>

#include "sim/scene/march.h"
#include "sim/workload/argus/ag_tile.h"
#include "sim/workload/argus/ag_workload.h"
#include "tests/support.h"

static const char *workers = "split";

/* A small March: 16^3 lattice in 4^3-cube cells (64 cells), 240 x 200. */
static char *config(const char *order, int contexts, int voxels)
{
    return g_strdup_printf(
        "machine: {model: origin2000}\n"
        "workload: {type: argus, processors: 24, contexts: %d,\n"
        "  application: march, voxels_per_cell: %d, cells: 4,\n"
        "  order: %s, primitives: triangles, pixels: blend, alpha: 0.4,\n"
        "  tile: 32, block: 8, width: 240, height: 200, workers: %s,\n"
        "  fill_rate: finite}\n"
        "scene: {generator: march, grid: 16, cell: 4, iso: 1.67}\n"
        "run: {frames: 1}\n",
        contexts, voxels, order, workers);
}

static const char *out_dir; /* the frame hook's directory, or NULL */

static SimResult *run_text(const char *text, GError **err)
{
    CfgNode *root = cfg_load_string(text, "argus.yaml", err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = 1, .out_dir = out_dir};
    return support_run_tree(root, &o, err);
}

static double metric(const SimResult *r, const char *name)
{
    double v = -1;
    assert_true(sim_result_get_metric(r, name, &v));
    return v;
}

static double run_metric(const char *order, int contexts, int voxels,
                         const char *name)
{
    GError *e = NULL;
    char *text = config(order, contexts, voxels);
    SimResult *r = run_text(text, &e);
    g_free(text);
    if (!r)
        fail_msg("%s", e->message);
    double v = metric(r, name);
    sim_result_free(r);
    return v;
}

static void count_tile(guint tile, void *ctx)
{
    GArray *a = ctx;
    g_array_append_val(a, tile);
}

/* Bucketing: a triangle in one corner tile lands in that tile only, a
 * triangle whose box spans the screen in all 16 (64 x 64 pixels, 16-pixel
 * tiles, identity view: clip = world). */
static void test_bucket_corner_tiles(void **state)
{
    (void)state;
    AgFrame *f =
        wl_ag_frame_new(64, 64, 16, WL_AG_OPAQUE, 1, (RastColor){0, 0, 0});
    SceneMesh *m = scene_mesh_new();
    const double v[9][2] = {{-0.9, 0.9}, {-0.8, 0.9},  {-0.9, 0.8},
                            {0.8, -0.8}, {0.9, -0.8},  {0.9, -0.9},
                            {-0.9, 0.9}, {0.9, -0.9},  {0.9, 0.9}};
    for (int i = 0; i < 9; i++)
        scene_mesh_add_vertex(m, vec3(v[i][0], v[i][1], 0));
    for (uint32_t t = 0; t < 3; t++)
        scene_mesh_add_tri(m, 3 * t, 3 * t + 1, 3 * t + 2,
                           scene_color(1, 1, 1), 0);
    Mat4 id = mat4_identity();
    const guint want[3] = {0, 15, G_MAXUINT};
    for (guint t = 0; t < 3; t++) {
        GArray *a = g_array_new(FALSE, FALSE, sizeof(guint));
        guint n = wl_ag_bucket(f, &id, m, t, count_tile, a);
        assert_int_equal(n, a->len);
        if (want[t] == G_MAXUINT) {
            assert_int_equal(n, 16); /* its screen box covers every tile */
        } else {
            assert_int_equal(n, 1);
            assert_int_equal(g_array_index(a, guint, 0), want[t]);
        }
        g_array_free(a, TRUE);
    }
    scene_mesh_free(m);
    wl_ag_frame_free(f);
}

static void test_semaphores_order_the_blend(void **state)
{
    (void)state;
    assert_true(run_metric("cells", 4, 64, "image_matches_serial") == 1);
    assert_true(run_metric("none", 4, 64, "image_matches_serial") == 0);
    assert_true(run_metric("none", 4, 64, "pixels_differing") > 0);
    /* one context issues serially: no semaphores needed */
    assert_true(run_metric("none", 1, 64, "image_matches_serial") == 1);
}

/* The pool (workers: pool) keeps the order, and balances better than
 * tiles owned statically when the rasterisers bound the frame (no
 * application work): never slower, and no faster than all the work
 * spread over every worker allows. */
static void test_pool_orders_and_balances(void **state)
{
    (void)state;
    workers = "pool";
    double ok = run_metric("cells", 4, 64, "image_matches_serial");
    double bad = run_metric("none", 4, 64, "pixels_differing");
    double pool = run_metric("cells", 4, 0, "frame_ms");
    double busy = run_metric("cells", 4, 0, "geometry_ms") +
                  run_metric("cells", 4, 0, "rasterisation_ms");
    workers = "split";
    double split = run_metric("cells", 4, 0, "frame_ms");
    assert_true(ok == 1);
    assert_true(bad > 0);
    assert_true(pool < split);
    assert_true(pool >= busy / 20 * 0.999); /* 20 workers */
}

/* pgsim run --out DIR: the presented frame reaches DIR/frame.png through
 * the generic frame hook; no directory, no file. */
static void test_frame_hook_writes_png(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("argus-XXXXXX", NULL);
    assert_non_null(dir);
    char *png = g_build_filename(dir, "frame.png", NULL);
    run_metric("cells", 4, 64, "frame_hz");
    assert_false(g_file_test(png, G_FILE_TEST_EXISTS));
    out_dir = dir;
    run_metric("cells", 4, 64, "frame_hz");
    out_dir = NULL;
    RastImage *img = rast_image_read_png(png, NULL);
    assert_non_null(img);
    assert_int_equal(img->width, 240);
    rast_image_free(img);
    g_remove(png);
    g_rmdir(dir);
    g_free(png);
    g_free(dir);
}

static void test_streams_of_figure_3c(void **state)
{
    (void)state;
    SceneMarchParams mp = scene_march_defaults();
    mp.iso.grid = 16;
    mp.cell = 4;
    SceneMesh *m = scene_iso_mesh_cells(&mp.iso, mp.cell);
    GError *e = NULL;
    AgStreams *s = wl_ag_streams_new(m, 3, WL_AG_ORDER_CELLS,
                                     WL_AG_PRIM_TRIANGLES, 1u << 20, 4, &e);
    assert_non_null(s);
    assert_int_equal(s->batches->len, 64);
    /* each of the 3 * 4 * 4 * 3 = 144 neighbour pairs: one P, one V */
    assert_int_equal(wl_ag_count_syncs(s, WL_AG_SYNC_P), 144);
    assert_int_equal(wl_ag_count_syncs(s, WL_AG_SYNC_V), 144);
    guint seen = 0;
    for (guint c = 0; c < 3; c++) {
        GArray *b = wl_ag_ctx_blocks(s, c);
        for (guint i = 0; i < b->len; i++) {
            const AgBlock *k = &g_array_index(b, AgBlock, i);
            if (k->clear || k->swap)
                continue; /* Figure 2's frame loop (test_ag_pipe) */
            guint cell = g_array_index(s->batches, AgBatch, k->batch).tag;
            guint z = cell / 16, j = cell % 16;
            assert_int_equal(j % 3, (c + z) % 3); /* (myProc + i) % P */
            seen++;
        }
    }
    assert_int_equal(seen, 64);
    assert_int_equal(wl_ag_n_blocks(s), 66); /* and the clear and swap */
    AgStreams *none = wl_ag_streams_new(m, 3, WL_AG_ORDER_NONE,
                                        WL_AG_PRIM_TRIANGLES, 1u << 20, 4, &e);
    assert_int_equal(wl_ag_count_syncs(none, WL_AG_SYNC_P) +
                         wl_ag_count_syncs(none, WL_AG_SYNC_V),
                     0);
    wl_ag_streams_free(none);
    wl_ag_streams_free(s);
    scene_mesh_free(m);
}

static void test_contexts_speed_up_issue(void **state)
{
    (void)state;
    double one = run_metric("cells", 1, 20000, "frame_hz");
    double four = run_metric("cells", 4, 20000, "frame_hz");
    assert_true(four > 2.0 * one);
    assert_true(four <= 4.0 * one * 1.001); /* no speed-up above C */
}

static void test_too_many_processors(void **state)
{
    (void)state;
    GError *e = NULL;
    char *text;
    text = g_strdup(
        "machine: {model: origin2000}\n"
        "workload: {type: argus, processors: 25}\n"
        "scene: {generator: nurbs, patches_u: 1, patches_v: 1, tess: 2}\n");
    SimResult *r = run_text(text, &e);
    g_free(text);
    assert_null(r);
    assert_non_null(strstr(e->message, "25 processors"));
    g_error_free(e);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bucket_corner_tiles),
        cmocka_unit_test(test_semaphores_order_the_blend),
        cmocka_unit_test(test_pool_orders_and_balances),
        cmocka_unit_test(test_frame_hook_writes_png),
        cmocka_unit_test(test_streams_of_figure_3c),
        cmocka_unit_test(test_contexts_speed_up_issue),
        cmocka_unit_test(test_too_many_processors),
    };
    return cmocka_run_group_tests_name("argus", tests, NULL, NULL);
}
