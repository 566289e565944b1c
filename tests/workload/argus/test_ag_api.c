/* test_ag_api.c — the rest of the parallel API on Argus (issue 36 point
 * 5; sim/workload/argus/ag_issue.c, ag_order.c, ag_stream.c state):
 * per-context state commands and their cost, stateless against
 * stateful; display lists compiled once and executed by reference;
 * the glFinish baseline against glpBarrier/glpPSema (slower when the
 * program orders much, not when it orders only the frame); a bounded
 * command buffer blocking the issuing thread; both ordering schemes
 * keeping command-sequential consistency at every tile, and the check
 * seeing it broken when the pipe runs without the semaphores.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/scene_cfg.h"
#include "sim/workload/argus/ag_workload.h"
#include "tests/support.h"

/* A small March (16^3 lattice, 4^3 cells), 4 contexts (unless `extra`
 * says), blended back to front on 24 processors; `extra` adds workload
 * keys. */
static char *config(const char *order, const char *extra)
{
    return g_strdup_printf(
        "machine: {model: origin2000}\n"
        "workload: {type: argus, processors: 24, %s\n"
        "  application: march, voxels_per_cell: 64, cells: 4,\n"
        "  order: %s, primitives: triangles, pixels: blend, alpha: 0.4,\n"
        "  tile: 32, block: 8, width: 240, height: 200, workers: pool,\n"
        "  fill_rate: finite%s%s}\n"
        "scene: {generator: march, grid: 16, cell: 4, iso: 1.67}\n",
        strstr(extra, "contexts:") ? "" : "contexts: 4,", order,
        extra[0] ? ", " : "", extra);
}

static SimResult *run(const char *order, const char *extra, int frames)
{
    char *text = config(order, extra);
    GError *e = NULL;
    CfgNode *root = cfg_load_string(text, "api.yaml", &e);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = frames};
    SimResult *r = support_run_tree(root, &o, &e);
    if (!r)
        fail_msg("%s", e->message);
    g_free(text);
    return r;
}

static double metric(const SimResult *r, const char *name)
{
    double v = -1;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}

static double one(const char *order, const char *extra, const char *name)
{
    SimResult *r = run(order, extra, 1);
    double v = metric(r, name);
    sim_result_free(r);
    return v;
}

/* ---- state ------------------------------------------------------------- */

typedef struct {
    CfgNode *root;
    Scene *scene;
    SceneMesh *mesh;
} Mesh;

static Mesh march_mesh(void)
{
    Mesh m;
    GError *e = NULL;
    m.root = cfg_load_string(
        "scene: {generator: march, grid: 16, cell: 4, iso: 1.67}\n", "s.yaml",
        &e);
    m.scene = scene_from_cfg(cfg_get(m.root, "scene"), &e);
    assert_non_null(m.scene);
    m.mesh = scene_flatten(m.scene);
    return m;
}

static void mesh_free(Mesh *m)
{
    scene_mesh_free(m->mesh);
    scene_free(m->scene);
    cfg_free(m->root);
}

/* Colour changes along context c's own batches (the first batch sets it
 * with the rest of the state). */
static uint64_t own_changes(const AgStreams *st, const SceneMesh *m, guint c)
{
    GArray *b = wl_ag_ctx_blocks(st, c);
    uint64_t n = 0;
    gboolean have = FALSE;
    SceneColor cur = {0, 0, 0};
    for (guint i = 0; i < b->len; i++) {
        const AgBlock *k = &g_array_index(b, AgBlock, i);
        if (!k->opens || k->n == 0)
            continue;
        SceneColor x = g_array_index(m->poly_color, SceneColor, k->first);
        if (have && i > 0 && (x.r != cur.r || x.g != cur.g || x.b != cur.b))
            n++;
        have = TRUE;
        cur = x;
    }
    return n;
}

/* Stateful: each context sets its whole state in its first block (it
 * inherits nothing from another context) and then only its own colour
 * changes; more contexts, more state commands.  Stateless: four per
 * primitive. */
static void test_state_per_context(void **state)
{
    (void)state;
    Mesh m = march_mesh();
    uint64_t total[2] = {0, 0};
    const guint ctxs[2] = {1, 4};
    for (int k = 0; k < 2; k++) {
        GError *e = NULL;
        AgStreams *st = wl_ag_streams_new(m.mesh, ctxs[k], WL_AG_ORDER_CELLS,
                                          WL_AG_PRIM_TRIANGLES, 8, 4, &e);
        assert_non_null(st);
        wl_ag_streams_set_state(st, m.mesh, WL_AG_STATE_STATEFUL);
        uint64_t want = 0;
        for (guint c = 0; c < ctxs[k]; c++) {
            const AgBlock *first =
                &g_array_index(wl_ag_ctx_blocks(st, c), AgBlock, 0);
            if (first->n_state != WL_AG_STATE_ITEMS)
                fail_msg("context %u of %u: first block %u state commands "
                         "(n %u, opens %d, clear %d)", c, ctxs[k],
                         first->n_state, first->n, first->opens, first->clear);
            want += WL_AG_STATE_ITEMS + own_changes(st, m.mesh, c);
        }
        assert_int_equal(st->states, want);
        total[k] = st->states;
        wl_ag_streams_set_state(st, m.mesh, WL_AG_STATE_STATELESS);
        assert_int_equal(st->states,
                         WL_AG_STATE_ITEMS * scene_mesh_n_polys(m.mesh));
        wl_ag_streams_set_state(st, m.mesh, WL_AG_STATE_NONE);
        assert_int_equal(st->states, 0);
        wl_ag_streams_free(st);
    }
    assert_true(total[1] >= total[0] + 3 * WL_AG_STATE_ITEMS);
    mesh_free(&m);
}

/* The state commands' cost: the application time grows by issue_state
 * per command, the command bytes by `state` bytes per command, and the
 * stateless interface is dearer than the stateful one. */
static void test_state_costs(void **state)
{
    (void)state;
    SimResult *none = run("cells", "state: none", 1);
    SimResult *full = run("cells", "state: stateful", 1);
    SimResult *less = run("cells", "state: stateless", 1);
    assert_true(metric(none, "state_commands") == 0);
    double nf = metric(full, "state_commands");
    double nl = metric(less, "state_commands");
    assert_true(nf >= 4 * WL_AG_STATE_ITEMS && nl > 10 * nf);
    /* origin2000: issue_state 0.2 us, bytes.state 32 B by default */
    double d_ms = metric(less, "application_ms") - metric(none, "application_ms");
    assert_true(fabs(d_ms - nl * 0.2e-3) < 1e-9 * nl);
    double d_b = metric(less, "command_bytes") - metric(none, "command_bytes");
    assert_true(d_b == nl * 32);
    assert_true(metric(less, "frame_ms") > metric(full, "frame_ms"));
    assert_true(metric(less, "image_matches_serial") == 1);
    sim_result_free(none);
    sim_result_free(full);
    sim_result_free(less);
}

/* ---- immediate and retained modes --------------------------------------- */

/* Retained: the first frame compiles (issues as immediate mode), the
 * second calls the lists: one small command per batch, no application
 * work, a shorter frame, the same picture. */
static void test_retained_mode(void **state)
{
    (void)state;
    SimResult *im = run("cells", "", 2);
    SimResult *re = run("cells", "mode: retained", 2);
    assert_true(metric(im, "command_bytes_last") == metric(im, "command_bytes"));
    assert_true(metric(re, "command_bytes") == metric(im, "command_bytes"));
    /* 64 cells, one 8-byte glCallList each */
    assert_true(metric(re, "command_bytes_last") == 64 * 8);
    assert_true(metric(re, "application_ms_last") <
                0.1 * metric(im, "application_ms_last"));
    assert_true(metric(re, "frame_ms_last") < metric(im, "frame_ms_last"));
    assert_true(metric(re, "image_matches_serial") == 1);
    assert_true(metric(re, "order_violations") == 0);
    sim_result_free(im);
    sim_result_free(re);
}

/* ---- glFinish against glpBarrier / glpPSema ----------------------------- */

/* The ordered March (a semaphore per cell face): glFinish at every
 * signal drains the pipe, the parallel API does not (here x2); with
 * only the frame's barrier (order: frame) the one drain before the
 * swap costs this 2.7 ms frame about 5 % (the full Nurbs frame 0.01 %,
 * docs/workloads.md), and with one context (no synchronisation) the
 * two are the same run. */
static void test_finish_baseline(void **state)
{
    (void)state;
    double glp = one("cells", "sync: glp", "frame_hz");
    SimResult *fin = run("cells", "sync: finish", 1);
    double metric_hz_finish = metric(fin, "frame_hz");
    assert_true(glp > 1.3 * metric_hz_finish);
    assert_true(metric(fin, "finish_wait_ms") > 0);
    assert_true(metric(fin, "image_matches_serial") == 1);
    assert_true(metric(fin, "order_violations") == 0);
    sim_result_free(fin);
    assert_true(one("cells", "sync: glp", "finish_wait_ms") == 0);
    double g1 = one("frame", "sync: glp", "frame_hz");
    double f1 = one("frame", "sync: finish", "frame_hz");
    assert_true(f1 <= g1 && g1 - f1 < 0.1 * g1);
    assert_true(g1 / f1 - 1 < 0.25 * (glp / metric_hz_finish - 1));
    /* glFinish drains the whole pipe by default: a context that reaches
     * the frame's barrier first also waits for the others' commands, so
     * the threads wait longer than with finish: context */
    double wp = one("frame", "sync: finish, finish: pipe", "finish_wait_ms");
    double wc = one("frame", "sync: finish, finish: context",
                    "finish_wait_ms");
    assert_true(wp > wc && wc > 0);
    SimResult *a = run("cells", "sync: glp, contexts: 1", 1);
    SimResult *b = run("cells", "sync: finish, contexts: 1", 1);
    assert_true(metric(a, "frame_ms") == metric(b, "frame_ms"));
    sim_result_free(a);
    sim_result_free(b);
}

/* ---- bounded command buffers -------------------------------------------- */

/* A buffer smaller than two blocks (8 triangles x 3 vertices x 32 B =
 * 768 B a block) blocks the issuing threads and slows the frame; an
 * unbounded or large one never blocks. */
static void test_bounded_buffer(void **state)
{
    (void)state;
    SimResult *free_ = run("cells", "buffer: 0", 1);
    SimResult *big = run("cells", "buffer: 1 MiB", 1);
    SimResult *small = run("cells", "buffer: 1000 B", 1);
    assert_true(metric(free_, "issue_blocked_ms") == 0);
    assert_true(metric(big, "issue_blocked_ms") == 0);
    assert_true(metric(big, "frame_ms") == metric(free_, "frame_ms"));
    assert_true(metric(small, "issue_blocked_ms") > 0);
    assert_true(metric(small, "frame_ms") > metric(free_, "frame_ms"));
    assert_true(metric(small, "image_matches_serial") == 1);
    sim_result_free(free_);
    sim_result_free(big);
    sim_result_free(small);
}

/* ---- ordering schemes ---------------------------------------------------- */

/* Both schemes (and the glFinish baseline under each) keep every
 * tile's order consistent with every glpPSema, glpBarrier and
 * glpWaitContext: no violation, the serial picture. */
static void test_schemes_consistent(void **state)
{
    (void)state;
    const char *const v[] = {"ordering: pixel", "ordering: geometry",
                             "ordering: pixel, sync: finish",
                             "ordering: geometry, sync: finish",
                             "ordering: geometry, buffer: 1000 B"};
    for (guint i = 0; i < G_N_ELEMENTS(v); i++) {
        SimResult *r = run("cells", v[i], 1);
        if (metric(r, "order_violations") != 0 ||
            metric(r, "image_matches_serial") != 1)
            fail_msg("%s: %g violations, image %g", v[i],
                     metric(r, "order_violations"),
                     metric(r, "image_matches_serial"));
        sim_result_free(r);
    }
}

/* The check can fail: the pipe runs the streams without glpPSema (so
 * neither scheme orders the cells) and the tiles' logs, replayed
 * against the streams with them, break some; with them, none. */
static void test_check_sees_broken_order(void **state)
{
    (void)state;
    Mesh m = march_mesh();
    GError *e = NULL;
    for (int scheme = 0; scheme < 2; scheme++)
        for (int drop = 0; drop < 2; drop++) {
            SimEngine *eng = sim_engine_new(1);
            CfgNode *root =
                cfg_load_string("machine: {model: origin2000}\n", "m", &e);
            MachMachine *mach = mach_new_from_cfg(
                eng, cfg_get(root, "machine"), "analytic", &e);
            assert_non_null(mach);
            AgStreams *want = wl_ag_streams_new(
                m.mesh, 4, WL_AG_ORDER_CELLS, WL_AG_PRIM_TRIANGLES, 8, 4, &e);
            AgStreams *ran = wl_ag_streams_new(
                m.mesh, 4, WL_AG_ORDER_CELLS, WL_AG_PRIM_TRIANGLES, 8, 4, &e);
            if (drop)
                wl_ag_streams_drop(ran, WL_AG_SYNC_P);
            AgFrame *f = wl_ag_frame_new(240, 200, 32, WL_AG_BLEND, 0.4f,
                                         (RastColor){0, 0, 0});
            RastView view = rast_view_for_camera(&m.scene->camera, 240, 200);
            view.cull_back = FALSE;
            AgSetup s = {.procs = 24, .contexts = 4, .geometry = 10,
                         .rasterisers = 10, .app = WL_AG_APP_MARCH,
                         .voxels_per_batch = 64, .vertex_bytes = 32,
                         .triangle_bytes = 64,
                         .scheme = scheme ? WL_AG_SCHEME_GEOMETRY
                                          : WL_AG_SCHEME_PIXEL};
            AgPipe *p = wl_ag_pipe_new(mach, &s, ran, f, m.mesh, &view);
            AgFrameStats fs;
            assert_true(wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e));
            uint64_t bad = wl_ag_pipe_order_check(p, want);
            if (drop ? bad == 0 : bad != 0)
                fail_msg("scheme %d, P dropped %d: %" G_GUINT64_FORMAT
                         " violations", scheme, drop, bad);
            assert_int_equal(fs.order_violations, 0); /* against `ran` */
            wl_ag_pipe_free(p);
            wl_ag_frame_free(f);
            wl_ag_streams_free(want);
            wl_ag_streams_free(ran);
            mach_free(mach);
            cfg_free(root);
            sim_engine_free(eng);
        }
    mesh_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_state_per_context),
        cmocka_unit_test(test_state_costs),
        cmocka_unit_test(test_retained_mode),
        cmocka_unit_test(test_finish_baseline),
        cmocka_unit_test(test_bounded_buffer),
        cmocka_unit_test(test_schemes_consistent),
        cmocka_unit_test(test_check_sees_broken_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
