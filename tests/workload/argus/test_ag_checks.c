/* test_ag_checks.c — the argus workload's parameters and metrics checked
 * against values the test computes itself (issue 21: a line a test runs
 * must have its result checked): the thread defaults of ag_workload.c's
 * opening comment (G = (P - C) / 2, R = P - C - G, at least 1 each), the
 * `pixels` metric against a serial draw of the same scene, check_image
 * off leaving no image metrics, and each located input error. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/machine/machine.h"
#include "sim/scene/scene_cfg.h"
#include "sim/workload/argus/ag_stream.h"
#include "sim/workload/argus/ag_tile.h"
#include "sim/workload/argus/ag_workload.h"
#include "tests/support.h"

static WlAgParams *parse(const char *workload, GError **err)
{
    char *text = g_strdup_printf("workload: {type: argus, %s}\n", workload);
    CfgNode *root = cfg_load_string(text, "t.yaml", err);
    g_free(text);
    assert_non_null(root);
    WlAgParams *p = wl_argus_ops.parse(cfg_get(root, "workload"), err);
    cfg_free(root);
    return p;
}

static void threads_are(const char *w, guint P, guint C, guint G, guint R)
{
    GError *err = NULL;
    WlAgParams *p = parse(w, &err);
    if (!p)
        fail_msg("%s: %s", w, err->message);
    if (p->setup.procs != P || p->setup.contexts != C ||
        p->setup.geometry != G || p->setup.rasterisers != R)
        fail_msg("%s: got P %u C %u G %u R %u, expected %u %u %u %u", w,
                 p->setup.procs, p->setup.contexts, p->setup.geometry,
                 p->setup.rasterisers, P, C, G, R);
    wl_argus_ops.free_params(p);
}

/* The located message: "t.yaml:1:COL: found ..., expected ..." */
static void rejected(const char *w, const char *message)
{
    GError *err = NULL;
    WlAgParams *p = parse(w, &err);
    assert_null(p);
    assert_non_null(err);
    if (strcmp(err->message, message))
        fail_msg("%s: message '%s', expected '%s'", w, err->message, message);
    g_error_free(err);
}

static void test_thread_defaults(void **state)
{
    (void)state;
    threads_are("processors: 24", 24, 1, 11, 12);
    threads_are("processors: 24, contexts: 4", 24, 4, 10, 10);
    threads_are("processors: 7, contexts: 2", 7, 2, 2, 3);
    threads_are("processors: 24, contexts: 4, geometry: 15", 24, 4, 15, 5);
    threads_are("processors: 24, contexts: 4, geometry: 20", 24, 4, 20, 1);
    threads_are("processors: 2, contexts: 2", 2, 2, 1, 1);
    threads_are("processors: 1", 1, 1, 1, 1);
    threads_are("processors: 3, geometry: 1, rasterisers: 1", 3, 1, 1, 1);
    threads_are("processors: 9, contexts: 3, uniprocessor: true", 1, 1, 1, 1);
    rejected("rasterisers: 0",
             "t.yaml:1:38: found '0', expected a count in [1, 1024]");
    rejected("geometry: 0",
             "t.yaml:1:35: found '0', expected a count in [1, 1024]");
    rejected("contexts: 0",
             "t.yaml:1:35: found '0', expected a count in [1, 1024]");
    rejected("processors: 0",
             "t.yaml:1:37: found '0', expected a count in [1, 4096]");
}

static void test_sizes_and_words(void **state)
{
    (void)state;
    GError *err = NULL;
    WlAgParams *p = parse("bytes: {vertex: 100 B, triangle: 7 B}, tile: 8, "
                          "block: 1, alpha: 1, width: 16, height: 17, "
                          "voxels_per_cell: 0, cells: 3, workers: pool, "
                          "fill_rate: finite, check_image: false",
                          &err);
    assert_non_null(p);
    assert_int_equal(p->setup.vertex_bytes, 100);
    assert_int_equal(p->setup.triangle_bytes, 7);
    assert_int_equal(p->tile, 8);
    assert_int_equal(p->block_tris, 1);
    assert_true(p->alpha == 1.0);
    assert_int_equal(p->width, 16);
    assert_int_equal(p->height, 17);
    assert_int_equal(p->setup.voxels_per_batch, 0);
    assert_int_equal(p->cells, 3);
    assert_true(p->setup.pool);
    assert_false(p->setup.fill_infinite);
    assert_false(p->check_image);
    wl_argus_ops.free_params(p);
    p = parse("processors: 4", &err);
    assert_int_equal(p->setup.vertex_bytes, 32);
    assert_int_equal(p->setup.triangle_bytes, 64);
    assert_true(p->setup.fill_infinite);
    assert_false(p->setup.pool);
    assert_true(p->check_image);
    assert_true(p->alpha == 0.35);
    assert_int_equal(p->tile, 128);
    assert_int_equal(p->block_tris, 64);
    assert_int_equal(p->setup.voxels_per_batch, 4096);
    /* no size (the scene's), cells from the last tag, no uniprocessor */
    assert_int_equal(p->width, 0);
    assert_int_equal(p->height, 0);
    assert_int_equal(p->cells, 0);
    assert_false(p->setup.uniprocessor);
    assert_int_equal(p->setup.app, WL_AG_APP_NONE);
    assert_int_equal(p->order, WL_AG_ORDER_FRAME);
    wl_argus_ops.free_params(p);
    /* sizes are capped at 1 MiB; the words map to their enums */
    p = parse("bytes: {vertex: 3 MiB, triangle: 1025 KiB}, application: "
              "nurbs, order: cells, primitives: triangles, pixels: blend",
              &err);
    assert_non_null(p);
    assert_int_equal(p->setup.vertex_bytes, 1 << 20);
    assert_int_equal(p->setup.triangle_bytes, 1 << 20);
    assert_int_equal(p->setup.app, WL_AG_APP_NURBS);
    assert_int_equal(p->order, WL_AG_ORDER_CELLS);
    assert_int_equal(p->prim, WL_AG_PRIM_TRIANGLES);
    assert_int_equal(p->pixels, WL_AG_BLEND);
    wl_argus_ops.free_params(p);
    p = parse("bytes: {vertex: 1 MiB, triangle: 1048575 B}, cells: 0", &err);
    assert_non_null(p);
    assert_int_equal(p->cells, 0); /* 0: from the last batch tag */
    assert_int_equal(p->setup.vertex_bytes, 1 << 20);
    assert_int_equal(p->setup.triangle_bytes, (1 << 20) - 1);
    assert_int_equal(p->setup.app, WL_AG_APP_NONE);
    assert_int_equal(p->order, WL_AG_ORDER_FRAME);
    assert_int_equal(p->prim, WL_AG_PRIM_STRIPS);
    assert_int_equal(p->pixels, WL_AG_OPAQUE);
    wl_argus_ops.free_params(p);
    rejected("bytes: 3",
             "t.yaml:1:32: found '3', expected a map {vertex, triangle} of sizes");
    rejected("bytes: {triangle: lots}",
             "t.yaml:1:43: found 'lots', expected a non-negative size with a unit (B, kB, KB, MB, GB, TB, KiB, MiB, GiB, TiB)");
    rejected("bytes: {vertex: lots}",
             "t.yaml:1:41: found 'lots', expected a non-negative size with a unit (B, kB, KB, MB, GB, TB, KiB, MiB, GiB, TiB)");
    rejected("voxels_per_cell: 1073741825",
             "t.yaml:1:42: found '1073741825', expected a count in [0, 1073741824]");
    rejected("tile: 7",
             "t.yaml:1:31: found '7', expected a count in [8, 4096]");
    rejected("block: 0",
             "t.yaml:1:32: found '0', expected a count in [1, 1048576]");
    rejected("width: 15",
             "t.yaml:1:32: found '15', expected a count in [16, 16384]");
    rejected("height: 15",
             "t.yaml:1:33: found '15', expected a count in [16, 16384]");
    rejected("alpha: 1.5",
             "t.yaml:1:32: found '1.5', expected a number in [0, 1]");
    rejected("workers: both",
             "t.yaml:1:34: found 'both', expected one of: split, pool");
    rejected("fill_rate: slow",
             "t.yaml:1:36: found 'slow', expected one of: infinite, finite");
}

/* ---- running ------------------------------------------------------------ */

static const char *machine = "machine: {model: origin2000}\n";

static int frames = 1; /* run()'s frame count */

static SimResult *run(const char *text, GError **err)
{
    CfgNode *root = cfg_load_string(text, "r.yaml", err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = frames};
    return support_run_tree(root, &o, err);
}

/* run() of a config that must run: its error fails the test. */
static SimResult *must_run(const char *text)
{
    GError *err = NULL;
    SimResult *r = run(text, &err);
    if (!r)
        fail_msg("%s", err->message);
    return r;
}

static double metric(const SimResult *r, const char *name)
{
    double v = -1;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}

static const char *nurbs_scene = "scene: {generator: nurbs, patches_u: 2, patches_v: 1, tess: 4}\n";

/* Pixels touched by the whole scene drawn serially into one frame. */
static double serial_pixels(const char *scene_yaml, int w, int h)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(scene_yaml, "s.yaml", &err);
    Scene *s = scene_from_cfg(cfg_get(root, "scene"), &err);
    assert_non_null(s);
    SceneMesh *m = scene_flatten(s);
    RastView v = rast_view_for_camera(&s->camera, w, h);
    v.cull_back = FALSE;
    RastColor bg = {0, 0, 0};
    AgFrame *f = wl_ag_frame_new(w, h, 32, WL_AG_OPAQUE, 1, bg);
    guint n = scene_mesh_n_polys(m);
    uint32_t *all = g_new(uint32_t, n);
    for (guint i = 0; i < n; i++)
        all[i] = i;
    double px = (double)wl_ag_draw(f, G_MAXUINT, &v, m, all, n);
    g_free(all);
    wl_ag_frame_free(f);
    scene_mesh_free(m);
    scene_free(s);
    cfg_free(root);
    return px;
}

static void test_pixels_equal_serial_draw(void **state)
{
    (void)state;
    char *text = g_strdup_printf(
        "%sworkload: {type: argus, processors: 6, contexts: 2, "
        "application: nurbs, tile: 32, block: 16, width: 96, height: 80, "
        "check_image: false}\n%s",
        machine, nurbs_scene);
    SimResult *r = must_run(text);
    double want = serial_pixels(nurbs_scene, 96, 80);
    assert_true(want > 100);
    assert_true(metric(r, "pixels") == want);
    assert_true(metric(r, "tiles") == 3 * 3);
    assert_true(metric(r, "processors") == 6);
    assert_true(metric(r, "geometry_threads") == 2);
    assert_true(metric(r, "rasterisers") == 2);
    double v = 0;
    assert_false(sim_result_get_metric(r, "image_matches_serial", &v));
    assert_false(sim_result_get_metric(r, "pixels_differing", &v));
    sim_result_free(r);
    g_free(text);
}

/* The march scene of the pricing tests on origin2000; head is the
 * workload's processor keys. */
static char *march_text(const char *head)
{
    return g_strdup_printf(
        "machine: {model: origin2000}\n"
        "workload: {type: argus, %s,\n"
        "  application: march, voxels_per_cell: 100, primitives: triangles,\n"
        "  tile: 32, block: 8, width: 64, height: 48, check_image: false,\n"
        "  fill_rate: finite}\n"
        "scene: {generator: march, grid: 8, cell: 4, iso: 1.67}\n",
        head);
}

/* A run and the machine its costs come from, for pricing its counts. */
typedef struct {
    SimResult *r;
    CfgNode *root;
    SimEngine *eng;
    MachMachine *m;
} Priced;

static Priced priced_run(const char *head)
{
    char *text = march_text(head);
    GError *err = NULL;
    Priced x = {run(text, &err), NULL, NULL, NULL};
    if (!x.r)
        fail_msg("%s", err->message);
    x.root = cfg_load_string(text, "m.yaml", &err);
    x.eng = sim_engine_new(1);
    x.m = mach_new_from_cfg(x.eng, cfg_get(x.root, "machine"), "analytic",
                            &err);
    assert_non_null(x.m);
    g_free(text);
    return x;
}

static void priced_free(Priced *x)
{
    mach_free(x->m);
    sim_engine_free(x->eng);
    cfg_free(x->root);
    sim_result_free(x->r);
}

static double cpu_cost(const Priced *x, const char *op)
{
    return mach_cost(x->m, "cpu", op);
}

/* Metric name (ms) equals ps picoseconds to 1e-9 relative. */
static void expect_ms(const Priced *x, const char *name, double ps,
                      const char *what)
{
    double ms = metric(x->r, name);
    if (fabs(ms - ps * 1e-9) > 1e-9 * ms)
        fail_msg("%s %.9f ms, expected %.9f%s", name, ms, ps * 1e-9, what);
}

/* The application threads' time is app_work + issue cost a block
 * (ag_pipe.c app_issue): march voxels and triangles of every batch, a
 * vertex cost a vertex issued, a batch cost a batch and a lock a block. */
static void test_application_time_from_costs(void **state)
{
    (void)state;
    Priced x = priced_run("processors: 5, contexts: 2");
    const SimResult *r = x.r;
    double batches = metric(r, "batches"), tris = metric(r, "triangles");
    double verts = metric(r, "vertices_issued"), blocks = metric(r, "blocks");
    assert_true(batches > 1 && tris > batches && blocks >= batches);
    assert_true(verts == 3 * tris);
    expect_ms(&x, "application_ms",
              batches * 100.0 * cpu_cost(&x, "march_voxel") +
                  tris * cpu_cost(&x, "march_triangle") +
                  verts * cpu_cost(&x, "issue_vertex") +
                  batches * cpu_cost(&x, "issue_batch") +
                  blocks * cpu_cost(&x, "lock"),
              "");
    /* geometry: a lock, the vertices and triangles of every block, and a
     * tile cost for every (tile, triangle) pair bucketed */
    double bucketed = metric(r, "bucketed_triangles");
    expect_ms(&x, "geometry_ms",
              blocks * cpu_cost(&x, "lock") +
                  verts * cpu_cost(&x, "geom_vertex") +
                  tris * cpu_cost(&x, "geom_triangle") +
                  bucketed * cpu_cost(&x, "geom_tile"),
              "");
    /* rasterisation (finite fill, opaque): every bucketed triangle, every
     * pixel drawn, every pixel cleared, a semaphore operation a sync */
    expect_ms(&x, "rasterisation_ms",
              bucketed * cpu_cost(&x, "rast_triangle") +
                  metric(r, "pixels") * cpu_cost(&x, "rast_pixel") +
                  64 * 48 * cpu_cost(&x, "rast_clear") +
                  metric(r, "tile_syncs") * cpu_cost(&x, "sema"),
              "");
    /* one frame from time 0: it ends when its last tile is drawn, the
     * last thing the run does */
    assert_true(fabs(metric(r, "frame_ms") - r->elapsed * 1e-9) < 1e-12);
    /* one frame: frame_hz is the inverse of frame_ms */
    assert_true(fabs(metric(r, "frame_hz") * metric(r, "frame_ms") - 1000) <
                1e-9);
    assert_true(metric(r, "geometry_ms") > 0);
    assert_true(metric(r, "rasterisation_ms") > 0);
    priced_free(&x);
}

/* Nurbs: the application evaluates each distinct patch vertex of a
 * batch once (nurbs_vertex), then issues as March does; strips issue a
 * batch's vertices as the streams count them. */
static void test_nurbs_application_time(void **state)
{
    (void)state;
    char *text = g_strdup_printf(
        "machine: {model: origin2000}\n"
        "workload: {type: argus, processors: 1, uniprocessor: true,\n"
        "  application: nurbs, primitives: strips, tile: 32, block: 16,\n"
        "  width: 64, height: 48, check_image: false}\n%s",
        nurbs_scene);
    SimResult *r = must_run(text);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "m.yaml", &err);
    Scene *sc = scene_from_cfg(cfg_get(root, "scene"), &err);
    SceneMesh *m = scene_flatten(sc);
    AgStreams *st = wl_ag_streams_new(m, 1, WL_AG_ORDER_FRAME,
                                      WL_AG_PRIM_STRIPS, 16, 0, &err);
    assert_non_null(st);
    uint64_t distinct = 0, verts = 0;
    for (guint b = 0; b < st->batches->len; b++) {
        const AgBatch *x = &g_array_index(st->batches, AgBatch, b);
        distinct += x->distinct;
        verts += x->verts;
    }
    assert_true(distinct > 0 && distinct < verts);
    assert_true(metric(r, "vertices_issued") == verts);
    assert_true(verts < 3 * metric(r, "triangles")); /* strips share */
    SimEngine *eng = sim_engine_new(1);
    MachMachine *mach =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    double want = distinct * mach_cost(mach, "cpu", "nurbs_vertex") +
                  verts * mach_cost(mach, "cpu", "issue_vertex") +
                  st->batches->len * mach_cost(mach, "cpu", "issue_batch");
    double ms = metric(r, "application_ms");
    if (fabs(ms - want * 1e-9) > 1e-9 * ms)
        fail_msg("application %.9f ms, expected %.9f", ms, want * 1e-9);
    mach_free(mach);
    sim_engine_free(eng);
    wl_ag_streams_free(st);
    scene_mesh_free(m);
    scene_free(sc);
    cfg_free(root);
    sim_result_free(r);
    g_free(text);
}

/* Blended pixels cost rast_blend (not rast_pixel); with an infinite
 * fill rate no pixel, blended or cleared, costs anything (seed 002's
 * footnote): rasterisation is triangles and semaphores. */
static void test_rasterisation_by_pixel_mode(void **state)
{
    (void)state;
    Priced x = priced_run("processors: 5, contexts: 2, pixels: blend");
    double bucketed = metric(x.r, "bucketed_triangles");
    double syncs = metric(x.r, "tile_syncs"), px = metric(x.r, "pixels");
    assert_true(px > 0 && syncs > 0);
    assert_true(cpu_cost(&x, "rast_blend") != cpu_cost(&x, "rast_pixel"));
    expect_ms(&x, "rasterisation_ms",
              bucketed * cpu_cost(&x, "rast_triangle") +
                  px * cpu_cost(&x, "rast_blend") +
                  64 * 48 * cpu_cost(&x, "rast_clear") +
                  syncs * cpu_cost(&x, "sema"),
              " (blend)");
    priced_free(&x);
    char *finite = march_text("processors: 5, contexts: 2");
    gchar **parts = g_strsplit(finite, "fill_rate: finite", 2);
    assert_non_null(parts[1]);
    char *text = g_strjoinv("fill_rate: infinite", parts);
    g_strfreev(parts);
    g_free(finite);
    SimResult *r = must_run(text);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "m.yaml", &err);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m = mach_new_from_cfg(eng, cfg_get(root, "machine"),
                                       "analytic", &err);
    double want = metric(r, "bucketed_triangles") *
                      mach_cost(m, "cpu", "rast_triangle") +
                  metric(r, "tile_syncs") * mach_cost(m, "cpu", "sema");
    double ms = metric(r, "rasterisation_ms");
    assert_true(fabs(ms - want * 1e-9) <= 1e-9 * ms);
    mach_free(m);
    sim_engine_free(eng);
    cfg_free(root);
    sim_result_free(r);
    g_free(text);
}

/* A uniprocessor pays no lock and no semaphore (ag_pipe.h): its
 * application time is the work alone, and the geometry and rasteriser
 * times carry no synchronisation; the multiprocessor run of the same
 * scene pays them (so this test fails if the uniprocessor is charged). */
static void test_uniprocessor_pays_no_sync(void **state)
{
    (void)state;
    Priced x = priced_run("processors: 1, uniprocessor: true");
    assert_true(cpu_cost(&x, "lock") > 0);
    double batches = metric(x.r, "batches"), tris = metric(x.r, "triangles");
    double verts = metric(x.r, "vertices_issued");
    expect_ms(&x, "application_ms",
              batches * 100.0 * cpu_cost(&x, "march_voxel") +
                  tris * cpu_cost(&x, "march_triangle") +
                  verts * cpu_cost(&x, "issue_vertex") +
                  batches * cpu_cost(&x, "issue_batch"),
              " (no lock)");
    expect_ms(&x, "geometry_ms",
              verts * cpu_cost(&x, "geom_vertex") +
                  tris * cpu_cost(&x, "geom_triangle") +
                  metric(x.r, "bucketed_triangles") *
                      cpu_cost(&x, "geom_tile"),
              " (no lock)");
    priced_free(&x);
}

/* Batches and their vertex counts on a hand-made mesh: a strip issues 3
 * vertices for its first triangle and 1 for each that shares exactly two
 * vertices with the one before; distinct counts mesh vertices. */
static void test_batch_vertices(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    for (guint i = 0; i < 12; i++)
        scene_mesh_add_vertex(m, vec3(i, i % 2, 0));
    const uint32_t tris[][4] = {
        /* tag 0: a strip of three, then one sharing a single vertex,
         * then one sharing two with it */
        {0, 1, 2, 0}, {1, 2, 3, 0}, {2, 3, 4, 0}, {4, 5, 6, 0}, {5, 6, 7, 0},
        /* tag 1: the same triangle twice (three shared), then a new one */
        {8, 9, 10, 1}, {8, 9, 10, 1}, {9, 10, 11, 1},
        /* tag 2: one triangle */
        {0, 5, 11, 2}};
    for (guint i = 0; i < G_N_ELEMENTS(tris); i++)
        scene_mesh_add_poly(m, tris[i], 3, scene_color(1, 1, 1), tris[i][3]);
    GError *err = NULL;
    AgStreams *s = wl_ag_streams_new(m, 2, WL_AG_ORDER_FRAME,
                                     WL_AG_PRIM_STRIPS, 2, 0, &err);
    assert_non_null(s);
    assert_int_equal(s->batches->len, 3);
    const guint first[] = {0, 5, 8}, n[] = {5, 3, 1}, tag[] = {0, 1, 2};
    const uint64_t verts[] = {3 + 1 + 1 + 3 + 1, 3 + 3 + 1, 3};
    const uint64_t distinct[] = {8, 4, 3};
    uint64_t issued = 0;
    for (guint b = 0; b < 3; b++) {
        const AgBatch *x = &g_array_index(s->batches, AgBatch, b);
        assert_int_equal(x->first, first[b]);
        assert_int_equal(x->n, n[b]);
        assert_int_equal(x->tag, tag[b]);
        assert_int_equal(x->verts, verts[b]);
        assert_int_equal(x->distinct, distinct[b]);
    }
    /* the blocks (2 triangles each) restart their strip: tag 0 as
     * {0, 1} {2, 3} {4}: 4 + 6 + 3; tag 1 as {5, 6} {7}: 6 + 3; tag 2: 3 */
    for (guint c = 0; c < 2; c++) {
        GArray *bl = wl_ag_ctx_blocks(s, c);
        for (guint k = 0; k < bl->len; k++)
            issued += g_array_index(bl, AgBlock, k).verts;
    }
    assert_int_equal(issued, 13 + 9 + 3);
    wl_ag_streams_free(s);
    s = wl_ag_streams_new(m, 1, WL_AG_ORDER_FRAME, WL_AG_PRIM_TRIANGLES, 4, 0,
                          &err);
    assert_int_equal(g_array_index(s->batches, AgBatch, 0).verts, 15);
    wl_ag_streams_free(s);
    /* more contexts than batches: the idle context still takes part in
     * the frame's barrier, through an empty block */
    s = wl_ag_streams_new(m, 4, WL_AG_ORDER_FRAME, WL_AG_PRIM_TRIANGLES, 8, 0,
                          &err);
    guint empty = 0;
    for (guint c = 0; c < 4; c++) {
        GArray *bl = wl_ag_ctx_blocks(s, c);
        assert_true(bl->len > 0);
        guint barrier = 0, arrive = 0;
        for (guint k = 0; k < bl->len; k++) {
            const AgBlock *b = &g_array_index(bl, AgBlock, k);
            for (guint i = 0; i < b->n_pre; i++)
                barrier += b->pre[i].kind == WL_AG_SYNC_APP_BARRIER;
            for (guint i = 0; i < b->n_post; i++)
                arrive += b->post[i].kind == WL_AG_SYNC_BARRIER;
            empty += b->batch == G_MAXUINT && b->n == 0 && !b->clear &&
                     !b->swap;
        }
        assert_int_equal(barrier, 1);
        assert_int_equal(arrive, 1);
    }
    assert_true(empty >= 1);
    wl_ag_streams_free(s);
    scene_mesh_free(m);
}

/* cells: 0 takes the grid from the last batch tag: n = ceil(cbrt(last
 * + 1)), so tags 0..7 make a 2^3 grid and tags 0..8 a 3^3 one (one
 * semaphore a cell); a mesh without triangles is one empty cell. */
static guint auto_cells(guint tags)
{
    SceneMesh *m = scene_mesh_new();
    for (guint i = 0; i < tags; i++) {
        uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(i, 0, 0)),
                         scene_mesh_add_vertex(m, vec3(i + 1, 0, 0)),
                         scene_mesh_add_vertex(m, vec3(i, 1, 0))};
        scene_mesh_add_poly(m, v, 3, scene_color(1, 1, 1), i);
    }
    GError *err = NULL;
    AgStreams *s = wl_ag_streams_new(m, 2, WL_AG_ORDER_CELLS,
                                     WL_AG_PRIM_TRIANGLES, 4, 0, &err);
    if (!s)
        fail_msg("%u tags: %s", tags, err->message);
    guint sems = s->sems;
    wl_ag_streams_free(s);
    scene_mesh_free(m);
    return sems;
}

static void test_cells_from_last_tag(void **state)
{
    (void)state;
    assert_int_equal(auto_cells(0), 1); /* no batch: one empty cell */
    assert_int_equal(auto_cells(1), 1);
    assert_int_equal(auto_cells(2), 8);
    assert_int_equal(auto_cells(8), 8);
    assert_int_equal(auto_cells(9), 27);
    assert_int_equal(auto_cells(27), 27);
    assert_int_equal(auto_cells(28), 64);
}

/* glClear and glXSwapBuffers of one tile touch that tile's pixels only
 * (64 x 48 in tiles of 32: the last row of tiles is 16 high). */
static void test_tile_clear_and_present(void **state)
{
    (void)state;
    RastColor bg = {0.25f, 0.5f, 0.75f};
    AgFrame *f = wl_ag_frame_new(64, 48, 32, WL_AG_OPAQUE, 1, bg);
    assert_int_equal(wl_ag_n_tiles(f), 4);
    for (guint t = 0; t < 4; t++) {
        for (gsize i = 0; i < 64 * 48; i++) {
            f->depth[i] = 0.5;
            f->prim[i] = 7;
            for (int k = 0; k < 3; k++)
                f->rgb[3 * i + k] = f->front[3 * i + k] = 1;
        }
        int x0 = (int)(t % 2) * 32, y0 = (int)(t / 2) * 32;
        int h = t < 2 ? 32 : 16;
        assert_int_equal(wl_ag_frame_clear_tile(f, t), 32 * h);
        for (int y = 0; y < 48; y++)
            for (int x = 0; x < 64; x++) {
                gsize i = (gsize)y * 64 + x;
                gboolean in = x >= x0 && x < x0 + 32 && y >= y0 && y < y0 + h;
                assert_true(f->rgb[3 * i] == (in ? 0.25f : 1));
                assert_true(f->rgb[3 * i + 2] == (in ? 0.75f : 1));
                assert_true(in ? f->depth[i] > 1e300 : f->depth[i] == 0.5);
                assert_true(f->prim[i] == (in ? RAST_NO_PRIM : 7));
            }
        wl_ag_frame_present_tile(f, t);
        for (int y = 0; y < 48; y++)
            for (int x = 0; x < 64; x++) {
                gsize i = (gsize)y * 64 + x;
                gboolean in = x >= x0 && x < x0 + 32 && y >= y0 && y < y0 + h;
                assert_true(f->front[3 * i + 1] == (in ? 0.5f : 1));
            }
    }
    /* the picture: (0, 0) kept the white front, (63, 47) was presented */
    RastImage *img = wl_ag_frame_front_image(f);
    assert_int_equal(rast_image_get(img, 0, 0), 0xffffffffu);
    assert_int_equal(rast_image_get(img, 63, 47),
                     rast_channel(0.25f) | rast_channel(0.5f) << 8 |
                         rast_channel(0.75f) << 16 | 0xff000000u);
    rast_image_free(img);
    assert_int_equal(wl_ag_frame_clear_tile(f, G_MAXUINT), 64 * 48);
    wl_ag_frame_free(f);
}

/* application: none leaves only the issue costs on the application
 * threads. */
static void test_application_none(void **state)
{
    (void)state;
    char *text = g_strdup_printf(
        "%sworkload: {type: argus, processors: 4, contexts: 1,\n"
        "  application: none, primitives: triangles, tile: 32, block: 1024,\n"
        "  width: 48, height: 48, check_image: false}\n%s",
        machine, nurbs_scene);
    SimResult *r = must_run(text);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "m.yaml", &err);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    double ps = metric(r, "vertices_issued") * mach_cost(m, "cpu", "issue_vertex") +
                metric(r, "batches") * mach_cost(m, "cpu", "issue_batch") +
                metric(r, "blocks") * mach_cost(m, "cpu", "lock");
    double ms = metric(r, "application_ms");
    if (fabs(ms - ps * 1e-9) > 1e-12 * ms)
        fail_msg("application %.12f ms, expected %.12f", ms, ps * 1e-9);
    mach_free(m);
    sim_engine_free(eng);
    cfg_free(root);
    sim_result_free(r);
    g_free(text);
}

static void run_fails(const char *text, const char *needle)
{
    GError *err = NULL;
    SimResult *r = run(text, &err);
    assert_null(r);
    assert_non_null(err);
    if (!strstr(err->message, needle))
        fail_msg("message '%s' lacks '%s'", err->message, needle);
    g_error_free(err);
}

static void test_run_errors(void **state)
{
    (void)state;
    const char *w = "workload: {type: argus, processors: 2, width: 32, "
                    "height: 32, tile: 16%s}\n";
    char *plain = g_strdup_printf(w, "");
    char *t = g_strconcat(machine, plain,
                          "scene: {generator: large_polygons, count: 1, "
                          "max_sides: 16, seed: 1}\n", NULL);
    /* the scene's only polygon (polygon 0) has 12 sides */
    run_fails(t, "argus: found a polygon of 12 vertices (polygon 0), "
                 "expected triangles (generators nurbs, march)");
    g_free(t);
    t = g_strconcat(machine, plain, "scene: {generator: nowhere}\n", NULL);
    run_fails(t, "nowhere");
    g_free(t);
    t = g_strconcat("machine: {model: no_such_machine}\n", plain, nurbs_scene,
                    NULL);
    run_fails(t, "no_such_machine");
    g_free(t);
    /* processors: the machine's 'cpu' count at most (origin2000: 24; a
     * machine without the kind has 0), located at the key */
    t = g_strconcat("machine: {model: pixel-planes-5}\n", plain, nurbs_scene,
                    NULL);
    /* its GPs play cpu (roles), but a ring is no shared memory */
    run_fails(t, "found machine 'pixel-planes-5' with a ring network and no "
                 "shared memory");
    g_free(t);
    t = g_strconcat(machine, "workload: {type: argus, processors: 25, "
                    "width: 32, height: 32, tile: 16}\n", nurbs_scene, NULL);
    run_fails(t, "r.yaml:2:37: found 25 processors, expected at most the 24 "
                 "'cpu' processors of machine 'origin2000'");
    g_free(t);
    t = g_strconcat(machine, "workload: {type: argus, processors: 24, "
                    "width: 32, height: 32, tile: 16}\n", nurbs_scene, NULL);
    sim_result_free(must_run(t));
    g_free(t);
    /* a shared-memory machine with cpus but neither Argus's costs nor a
     * processor description to derive them from (sgi-onyx has one) */
    t = g_strconcat("machine: {name: bare, provenance: assumption, nodes: "
                    "{cpu: {count: 4}}, network: {topology: bus, bandwidth: "
                    "1 GB/s, startup: 1 us}}\n",
                    plain, nurbs_scene, NULL);
    run_fails(t, "found no cost for 'nurbs_vertex' on 'cpu'");
    g_free(t);
    char *cells = g_strdup_printf(w, ", order: cells, cells: 1");
    t = g_strconcat(machine, cells, nurbs_scene, NULL);
    run_fails(t, "not increasing cell indices below 1^3");
    g_free(t);
    g_free(cells);
    g_free(plain);
}

/* Own memory: w x h pixels at 24 B (48 with check_image) + 3 B, and per
 * tile (ceil(w / tile) x ceil(h / tile)) 4 B x (contexts + 2). */
static void test_mem_bytes(void **state)
{
    (void)state;
    GError *err = NULL;
    WlAgParams *p = parse("width: 100, height: 64, tile: 32, contexts: 2, "
                          "processors: 8, check_image: false", &err);
    assert_non_null(p);
    GString *what = g_string_new("");
    /* tiles: 4 x 2 (a height of exactly 2 tiles) */
    assert_true(wl_argus_ops.mem_bytes(p, what) ==
                100.0 * 64 * 27 + 8 * 4.0 * 4);
    assert_string_equal(what->str, "100 x 64 pixels, 2 contexts");
    wl_argus_ops.free_params(p);
    p = parse("width: 64, height: 33, tile: 16, contexts: 3, processors: 8",
              &err);
    assert_non_null(p);
    g_string_truncate(what, 0);
    /* tiles: 4 x 3; check_image on by default */
    assert_true(wl_argus_ops.mem_bytes(p, what) ==
                64.0 * 33 * 51 + 12 * 4.0 * 5);
    wl_argus_ops.free_params(p);
    p = parse("width: 65, height: 16, tile: 16, processors: 8", &err);
    assert_non_null(p);
    /* tiles: 5 x 1 (a pixel past 4 tiles) */
    assert_true(wl_argus_ops.mem_bytes(p, what) ==
                65.0 * 16 * 51 + 5 * 1 * 4.0 * 3);
    wl_argus_ops.free_params(p);
    p = parse("tile: 32, processors: 8", &err);
    assert_non_null(p);
    /* no size: 1200 x 1200, 38 x 38 tiles, one context */
    assert_true(wl_argus_ops.mem_bytes(p, what) ==
                1200.0 * 1200 * 51 + 38 * 38 * 4.0 * 3);
    wl_argus_ops.free_params(p);
    g_string_free(what, TRUE);
}

/* Shared memory carries each block's issued vertices (bytes.vertex
 * each) and each bucketed triangle (bytes.triangle each); Figure 2's loop
 * around two contexts in frame order is 6 synchronisation commands (an
 * appBarrier and a glpBarrier each, glpWaitContext in context 1, the
 * swap's barrier wait). */
static void test_memory_bytes_and_syncs(void **state)
{
    (void)state;
    char *text = g_strdup_printf(
        "%sworkload: {type: argus, processors: 6, contexts: 2, "
        "application: nurbs, tile: 32, block: 16, width: 96, height: 80, "
        "bytes: {vertex: 24 B, triangle: 100 B}}\n%s",
        machine, nurbs_scene);
    SimResult *r = must_run(text);
    double v = metric(r, "vertices_issued"), b = metric(r, "bucketed_triangles");
    assert_true(v > 0 && b > 0);
    assert_true(metric(r, "shared_memory_bytes") == 24 * v + 100 * b);
    assert_true(metric(r, "sync_commands") == 6);
    assert_true(metric(r, "contexts") == 2);
    sim_result_free(r);
    g_free(text);
}

/* A uniprocessor moves nothing through shared memory (ag_pipe.h), so it
 * runs on a machine whose network is no shared bus; the multiprocessor
 * is refused there. */
static void test_uniprocessor_needs_no_memory(void **state)
{
    (void)state;
    const char *ring = "machine: {model: origin2000, network: "
                       "{topology: {value: ring, source: t}}}\n";
    const char *w = "workload: {type: argus, processors: %s, width: 32, "
                    "height: 32, tile: 16}\n";
    char *uni = g_strdup_printf(w, "1, uniprocessor: true");
    char *t = g_strconcat(ring, uni, nurbs_scene, NULL);
    GError *err = NULL;
    SimResult *r = run(t, &err);
    if (!r)
        fail_msg("%s", err->message);
    assert_true(metric(r, "pixels") > 0);
    sim_result_free(r);
    g_free(t);
    char *multi = g_strdup_printf(w, "2");
    t = g_strconcat(ring, multi, nurbs_scene, NULL);
    run_fails(t, "and no shared memory");
    g_free(t);
    g_free(multi);
    g_free(uni);
}

/* Every frame starts from a clean pipeline (ag_pipe.c reset): three
 * frames of the ordered, blended March on 4 contexts (semaphores,
 * barriers, glpWaitContext, round robins all in use) take exactly the
 * same time each, the shared memory carries the same bytes each, and
 * the last frame's picture is still the serial one. */
static void test_frames_alike(void **state)
{
    (void)state;
    const char *text =
        "machine: {model: origin2000}\n"
        "workload: {type: argus, processors: 12, contexts: 4,\n"
        "  application: march, voxels_per_cell: 50, cells: 2, order: cells,\n"
        "  primitives: triangles, pixels: blend, tile: 16, block: 4,\n"
        "  width: 48, height: 32, fill_rate: finite}\n"
        "scene: {generator: march, grid: 8, cell: 4, iso: 1.67}\n";
    SimResult *one = must_run(text);
    frames = 3;
    SimResult *r = must_run(text);
    frames = 1;
    assert_int_equal(r->frame_times->len, 3);
    SimTime t0 = g_array_index(one->frame_times, SimTime, 0);
    for (guint f = 0; f < 3; f++)
        assert_int_equal(g_array_index(r->frame_times, SimTime, f), t0);
    assert_true(metric(r, "image_matches_serial") == 1);
    assert_true(metric(r, "shared_memory_bytes") ==
                metric(one, "shared_memory_bytes"));
    assert_true(metric(r, "tile_syncs") > 0);
    sim_result_free(r);
    sim_result_free(one);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_thread_defaults),
        cmocka_unit_test(test_sizes_and_words),
        cmocka_unit_test(test_pixels_equal_serial_draw),
        cmocka_unit_test(test_run_errors),
        cmocka_unit_test(test_application_time_from_costs),
        cmocka_unit_test(test_uniprocessor_pays_no_sync),
        cmocka_unit_test(test_batch_vertices),
        cmocka_unit_test(test_cells_from_last_tag),
        cmocka_unit_test(test_tile_clear_and_present),
        cmocka_unit_test(test_application_none),
        cmocka_unit_test(test_mem_bytes),
        cmocka_unit_test(test_rasterisation_by_pixel_mode),
        cmocka_unit_test(test_nurbs_application_time),
        cmocka_unit_test(test_memory_bytes_and_syncs),
        cmocka_unit_test(test_uniprocessor_needs_no_memory),
        cmocka_unit_test(test_frames_alike),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
