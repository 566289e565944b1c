/* test_pf_database.c — Performer's database side where it changes cost
 * (issue 36, point 3, part), on configs/performer-procs.yaml (the town
 * without stress feedback: the same triangles whatever the DRAW time):
 *   - strips (strip_length L): each geoset of T triangles sends T + 2
 *     ceil(T / L) vertices, not 3 T; DRAW's CPU time falls by the
 *     vertices saved x draw_vertex and its bytes by them x vertex_bytes,
 *     the pipe's time and the triangles do not move;
 *   - a deep town (the blocks under a quadtree of groups) draws the same
 *     triangles as the flat one; CULL visits fewer nodes in it when most
 *     of the town is outside the view, more when most is inside:
 *     efficiency depends on the graph's depth;
 *   - traversal callbacks cost their time per node that runs them;
 *   - a pfSequence draws only the child of the frame;
 *   - a pfPartition over the blocks: ISECT finds the same heights
 *     testing fewer nodes and triangles, and takes less time.
 * Runs of 12 frames, means over frames 4..11.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/core/cfg.h"
#include "sim/machine/machine.h"
#include "sim/workload/performer/pf_cull.h"
#include "sim/workload/performer/pf_town.h"
#include "tests/support.h"

static double metric(const SimResult *r, const char *name)
{
    double v = NAN;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}

/* configs/performer-procs.yaml (the town without stress, one pipe) with
 * the overrides (NULL-terminated, at most 4). */
static SimResult *run(const char *const *set)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_file("configs/performer-procs.yaml", &err);
    if (!root)
        fail_msg("%s", err->message);
    const char *sets[6] = {"workload.phase=floating"};
    for (guint i = 0; set[i]; i++)
        sets[i + 1] = set[i];
    SupportRun o = {.fidelity = "analytic", .frames = 12, .overrides = sets};
    SimResult *r = support_run_tree(root, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    return r;
}

static double onyx_cost(const char *kind, const char *op)
{
    SimEngine *eng = sim_engine_new(1);
    GError *err = NULL;
    MachMachine *m = mach_new_from_model(eng, "sgi-onyx", "analytic", &err);
    double v = mach_cost(m, kind, op) * 1e-9; /* ps -> ms */
    mach_free(m);
    sim_engine_free(eng);
    return v;
}

static void test_strips_save_vertices(void **st)
{
    (void)st;
    const char *none[] = {NULL}, *strips[] = {"workload.strip_length=4", NULL};
    SimResult *a = run(none), *b = run(strips);
    double tris = metric(a, "tris_per_frame");
    assert_true(metric(b, "tris_per_frame") == tris);
    assert_true(fabs(metric(a, "vertices_per_frame") - 3 * tris) < 1e-6);
    assert_true(fabs(metric(a, "vertices_saved_per_frame")) < 1e-6);
    double saved = metric(b, "vertices_saved_per_frame");
    /* at most 4 - 2 = 2 of every 3 vertices: T + 2 T / 4 = 1.5 T */
    assert_true(saved > 0 && saved <= 1.5 * tris + 1e-6);
    double dv = onyx_cost("cpu", "draw_vertex");
    double dcpu = metric(a, "draw_cpu_ms") - metric(b, "draw_cpu_ms");
    if (fabs(dcpu - saved * dv) > 1e-6)
        fail_msg("DRAW's CPU %.6f ms less, saved %.0f vertices x %.6f", dcpu,
                 saved, dv);
    assert_true(metric(a, "draw_pipe_ms") == metric(b, "draw_pipe_ms"));
    assert_true(b->comm_bytes < a->comm_bytes);
    sim_result_free(a);
    sim_result_free(b);
}

/* Flat against deep at a camera speed: the triangles are the same; the
 * deep town's CULL visits fewer nodes (and takes less time) exactly
 * when `fewer`. */
static void deep_against_flat(const char *speed, gboolean fewer)
{
    const char *flat[] = {speed, NULL}, *deep[] = {
        speed, "workload.town.hierarchy=quadtree", NULL};
    SimResult *a = run(flat), *b = run(deep);
    assert_true(metric(a, "tris_per_frame") == metric(b, "tris_per_frame"));
    double na = metric(a, "cull_nodes_per_frame");
    double nb = metric(b, "cull_nodes_per_frame");
    double ta = metric(a, "cull_ms"), tb = metric(b, "cull_ms");
    if ((nb < na) != fewer || (tb < ta) != fewer)
        fail_msg("%s: flat %.1f nodes %.3f ms, deep %.1f nodes %.3f ms", speed,
                 na, ta, nb, tb);
    sim_result_free(a);
    sim_result_free(b);
}

/* The slides' "efficiency depends on the depth and balance of the scene
 * graph", both ways: at the town's west edge (1 m a frame) the view
 * holds most of the 12 x 12 blocks and the quadtree's groups are extra
 * visits; driving 40 m a frame, frames 4..11 are past the middle, most
 * quadrants are behind the eye and one sphere test rejects each. */
static void test_deep_town_depends_on_the_view(void **st)
{
    (void)st;
    deep_against_flat("workload.town.speed=1", FALSE);
    deep_against_flat("workload.town.speed=40", TRUE);
}

/* Traversal callbacks on every house (pre and post, 5 us each): CULL
 * pays its callbacks and the display list's CALLBACK items (cull_item
 * each), DRAW's CPU its callbacks; the triangles do not move.  A count
 * of zero cost changes nothing but the display list. */
static void test_callbacks_cost_per_node(void **st)
{
    (void)st;
    /* no arena bytes in CULL: its time is its work */
    const char *none[] = {"workload.arena={node: 0 B, item: 0 B, entry: 0 B}",
                          NULL};
    const char *cbs[] = {none[0], "workload.callbacks={cull: 5 us, draw: 5 us}",
                         NULL};
    SimResult *a = run(none), *b = run(cbs);
    assert_true(metric(a, "tris_per_frame") == metric(b, "tris_per_frame"));
    assert_true(metric(a, "callbacks_per_frame") == 0);
    double n = metric(b, "callbacks_per_frame"); /* cull + draw, 2 each */
    assert_true(n > 0);
    /* every house CULL keeps runs 2 CULL and 2 DRAW callbacks */
    double dcpu = metric(b, "draw_cpu_ms") - metric(a, "draw_cpu_ms");
    if (fabs(dcpu - n / 2 * 5e-3) > 1e-6)
        fail_msg("DRAW's CPU %.6f ms more for %.0f callbacks", dcpu, n);
    double item = onyx_cost("cpu", "cull_item");
    double dcull = metric(b, "cull_ms") - metric(a, "cull_ms");
    if (fabs(dcull - n / 2 * (5e-3 + item)) > 1e-6)
        fail_msg("CULL %.6f ms more for %.0f callbacks", dcull, n);
    sim_result_free(a);
    sim_result_free(b);
}

/* pfSequence (slides "libpf": precomputed animations, each child shown
 * for a period): a sequence of children of 1, 2 and 3 triangles, each
 * shown 2 frames, draws 1, 1, 2, 2, 3, 3, 1 triangles in frames 0..6:
 * CULL visits and DRAW pays for the active child only. */
static void test_sequence_draws_one_child(void **st)
{
    (void)st;
    WlPfGraph *g = wl_pf_graph_new();
    guint gs = wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    guint seq = wl_pf_add_node(g, g->root, WL_PF_SEQUENCE);
    wl_pf_node(g, seq)->seq_frames = 2;
    Vec3 v[9];
    for (guint i = 0; i < 9; i++)
        v[i] = vec3(i % 3, (i + 1) % 3 == 0, i / 3);
    for (guint c = 1; c <= 3; c++)
        wl_pf_add_geoset(g, wl_pf_add_node(g, seq, WL_PF_GEODE), v, c, gs);
    wl_pf_update_bounds(g, g->root);
    WlPfView view = {.stress = 1, .cull = FALSE};
    const guint want[7] = {1, 1, 2, 2, 3, 3, 1};
    for (guint f = 0; f < 7; f++) {
        GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
        WlPfCullStats cs = {0};
        WlPfDrawStats ds = {0};
        view.frame = f;
        wl_pf_cull(g, &view, dl, &cs);
        wl_pf_draw(g, dl, &ds);
        assert_int_equal(ds.tris, want[f]);
        assert_int_equal(cs.nodes_visited, 3); /* root, sequence, child */
        g_array_free(dl, TRUE);
    }
    wl_pf_graph_free(g);
}

/* pfPartition: at 97 points over the town (flat and deep), ISECT with
 * the blocks in a 4 x 4 grid finds exactly the heights it finds
 * without; in the flat town it tests fewer nodes at every point (the
 * segment's cell holds the blocks whose spheres reach it, not all 64;
 * the deep town's quadtree already prunes, so there it need not); in a
 * run, fewer tests, less time. */
static void test_partition_isect(void **st)
{
    (void)st;
    for (int deep = 0; deep < 2; deep++) {
        WlPfTownParams p = wl_pf_town_defaults();
        p.deep = deep;
        WlPfTown *a = wl_pf_town_new(&p);
        p.partition = 4;
        WlPfTown *b = wl_pf_town_new(&p);
        double len = p.blocks * p.block;
        for (guint k = 0; k < 97; k++) {
            double x = fmod(k * 37.3, len), z = fmod(k * 53.9 + 7, len);
            WlPfIsectStats sa = {0}, sb = {0};
            wl_pf_isect(a->g, x, z, -100, 100, &sa);
            wl_pf_isect(b->g, x, z, -100, 100, &sb);
            if (!(sa.hit && sb.hit == sa.hit))
                fail_msg("(%.1f, %.1f) deep %d: hit %d with, %d without", x, z,
                         deep, sb.hit, sa.hit);
            assert_true(sb.height == sa.height);
            if (!deep && !(sb.nodes_tested < sa.nodes_tested &&
                           sb.tris_tested <= sa.tris_tested))
                fail_msg("(%.1f, %.1f): %lu nodes with, %lu without", x, z,
                         (unsigned long)sb.nodes_tested,
                         (unsigned long)sa.nodes_tested);
        }
        wl_pf_town_free(a);
        wl_pf_town_free(b);
    }
    const char *none[] = {NULL}, *part[] = {
        "workload.town.partition={cells: 4}", NULL};
    SimResult *a = run(none), *b = run(part);
    assert_true(metric(a, "tris_per_frame") == metric(b, "tris_per_frame"));
    double ta = metric(a, "isect_tests_per_frame");
    double tb = metric(b, "isect_tests_per_frame");
    if (!(tb < ta && metric(b, "isect_ms") < metric(a, "isect_ms")))
        fail_msg("ISECT tests %.1f with, %.1f without", tb, ta);
    sim_result_free(a);
    sim_result_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_strips_save_vertices),
        cmocka_unit_test(test_deep_town_depends_on_the_view),
        cmocka_unit_test(test_callbacks_cost_per_node),
        cmocka_unit_test(test_sequence_draws_one_child),
        cmocka_unit_test(test_partition_isect),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
