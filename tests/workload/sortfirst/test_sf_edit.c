/* test_sf_edit.c — editing under sort-first (sf_edit.h, sf_book.h) on a
 * small vehicle (40 structures, 3,000 triangles, 3 instances, 64 x 64,
 * 4 processors):
 *   - after frames of matrix, execute, unpost and post edits the
 *     regions' image equals a serial render of the edited database,
 *     flattened anew here, and differs from the unedited scene's (so
 *     the comparison can fail), under min-set and max-set;
 *   - each kind does its work: a matrix edit moves no max-set node, an
 *     execute replaces subtrees (nodes created and collected, pointers
 *     collected, chunks of structures left unreachable collected), an
 *     unpost + post rebuilds a tree; edit time is charged (min-set:
 *     exactly one node_visit per command) and lengthens the frame;
 *   - min-set slaves delete a copy a frame after its last use: every
 *     held slave copy was needed this frame or the last, and some are
 *     held though not needed now;
 *   - runs with edits repeat exactly; bad edit keys are located. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/scene_cfg.h"
#include "tests/workload/sortfirst/sf_testutil.h"

static const char *const small = SF_TEST_SMALL;

static const WlSfEditSpec all_kinds = {{2, 2, 1, 1}, 25};

typedef SfEditFixture Fixture;

static void fixture_init(Fixture *f, WlSfBookkeeping bk,
                         const WlSfEditSpec *spec)
{
    sf_test_edit_init(f, bk, spec);
}

static void fixture_clear(Fixture *f)
{
    sf_test_edit_clear(f);
}

/* db flattened and drawn serially with frame f's camera. */
static RastZBuffer *serial_of(const Scene *scene, const SceneDb *db, int f)
{
    SceneCamera cam = scene_camera_at(scene, f);
    RastView v = rast_view_for_camera(&cam, 64, 64);
    v.cull_back = TRUE;
    SceneMesh *mesh = scene_db_flatten(db);
    RastZBuffer *zb = rast_zbuffer_new(64, 64);
    RastCounters c = {0};
    rast_zbuffer_clear(zb);
    rast_draw_mesh(&v, mesh, mat4_identity(), (SceneColor){1, 1, 1}, 0, NULL,
                   rast_zbuffer_sink(zb), &c);
    scene_mesh_free(mesh);
    return zb;
}

static gboolean same_image(const RastZBuffer *a, const RastZBuffer *b)
{
    size_t n = (size_t)a->width * (size_t)a->height;
    return memcmp(a->rgba, b->rgba, n * 4) == 0 &&
           memcmp(a->prim, b->prim, n * 4) == 0;
}

static void test_image_after_edits(void **state)
{
    (void)state;
    for (int bk = 0; bk <= 1; bk++) {
        Fixture f;
        fixture_init(&f, (WlSfBookkeeping)bk, &all_kinds);
        GError *e = NULL;
        for (int frame = 0; frame < 6; frame++) {
            if (!wl_sf_run_frames(f.run, 1, SIM_TIME_MAX, &e))
                fail_msg("%s", e->message);
            RastZBuffer *want =
                serial_of(f.scene, wl_sf_edit_db(f.edit), frame);
            RastZBuffer *before = serial_of(f.scene, f.scene->db, frame);
            assert_true(same_image(wl_sf_run_zbuffer(f.run), want));
            if (frame >= 2) /* the edits show */
                assert_false(same_image(want, before));
            rast_zbuffer_free(want);
            rast_zbuffer_free(before);
        }
        const uint64_t *n = wl_sf_edit_applied(f.edit);
        for (int k = 0; k < WL_SF_ED_N; k++)
            assert_true(n[k] == 5 * all_kinds.per_frame[k]);
        fixture_clear(&f);
    }
}

/* The min-set's copies are deleted a frame after their last use. */
static void test_deletion_next_frame(void **state)
{
    (void)state;
    const WlSfEditSpec none = {{0, 0, 0, 0}, 0};
    Fixture f;
    fixture_init(&f, WL_SF_MINSET, &none);
    GError *e = NULL;
    uint64_t lazy = 0;
    for (int frame = 0; frame < 6; frame++) {
        assert_true(wl_sf_run_frames(f.run, 1, SIM_TIME_MAX, &e));
        const WlSfBook *b = wl_sf_run_book(f.run);
        for (guint c = 0; c < wl_sf_n_chunks(f.db); c++) {
            uint64_t slaves = b->held_data[c] & ~wl_sf_bit(b->master[c]);
            assert_true((slaves & ~(b->used[c] | b->used_prev[c])) == 0);
            lazy += (uint64_t)__builtin_popcountll(slaves & ~b->used[c]);
        }
    }
    assert_true(lazy > 0);
    fixture_clear(&f);
}

static SimResult *run_edits(const char *bk, const char *edits)
{
    return sf_test_run_checked(small, 6, "workload.bookkeeping", bk,
                               "workload.edits", edits);
}

static void test_edit_work(void **state)
{
    (void)state;
    WlSfCosts c;
    Fixture f;
    fixture_init(&f, WL_SF_MAXSET, &all_kinds);
    c = f.c;
    fixture_clear(&f);
    /* a matrix edit: one command, the tree unchanged */
    SimResult *m = run_edits("minset", "{matrix: 1}");
    assert_true(sf_test_metric(m, "edits_per_frame") == 1);
    assert_true(sf_test_metric(m, "maxset_nodes_created_per_frame") == 0);
    assert_true(fabs(sf_test_metric(m, "edit_ms") * 1e9 -
                     (double)c.node_visit) < 1e-6);
    /* the command goes from processor 0 to the 3 others: a 64 B header
     * and 96 B a command each, one message more each; min-set sends no
     * pointers for new instances */
    assert_true(sf_test_metric(m, "edit_bytes_per_frame") == 3 * (64 + 96));
    assert_true(sf_test_metric(m, "messages_per_frame") == 4 * 3 + 3);
    sim_result_free(m);
    /* an execute: subtrees replaced, pointers and chunks collected */
    SimResult *x = run_edits("maxset", "{execute: 1}");
    SimResult *base = run_edits("maxset", "{}");
    double created = sf_test_metric(x, "maxset_nodes_created_per_frame");
    double gone = sf_test_metric(x, "maxset_nodes_collected_per_frame");
    assert_true(created > 0 && gone > 0);
    assert_true(sf_test_metric(x, "pointers_collected_per_frame") > 0);
    assert_true(sf_test_metric(x, "chunks_collected_per_frame") > 0);
    assert_true(sf_test_metric(x, "edit_ms") * 1e9 >
                (1 + created + gone) * (double)c.node_visit);
    assert_true(sf_test_metric(x, "frame_ms") >
                sf_test_metric(base, "frame_ms"));
    assert_true(sf_test_metric(x, "chunks") == sf_test_metric(base, "chunks"));
    sim_result_free(x);
    /* unpost + post: the same structure, a new tree; bytes beyond the
     * commands (the new instances' pointers) */
    SimResult *p = run_edits("maxset", "{unpost: 1, post: 1}");
    double nodes = sf_test_metric(p, "maxset_nodes_created_per_frame");
    assert_true(nodes > 0);
    assert_true(nodes == sf_test_metric(p, "maxset_nodes_collected_per_frame"));
    assert_true(sf_test_metric(p, "edit_bytes_per_frame") > 3 * (64 + 2 * 96));
    assert_true(sf_test_metric(p, "max_set_polygons") ==
                sf_test_metric(base, "max_set_polygons"));
    sim_result_free(p);
    sim_result_free(base);
}

/* Adaptive regions with the predicted estimate follow the renumbered
 * instances (their motion history remapped). */
static void test_adaptive_predicted(void **state)
{
    (void)state;
    SimResult *r = sf_test_run_checked(
        small, 6, "workload.regions", "adaptive", "workload.edits",
        "{matrix: 1, execute: 1, unpost: 1, post: 1}");
    assert_true(sf_test_metric(r, "edits_per_frame") == 4);
    sim_result_free(r);
}

static void test_repeatable(void **state)
{
    (void)state;
    const char *ed = "{matrix: 1, execute: 1, unpost: 1, post: 1}";
    SimResult *a = run_edits("maxset", ed), *b = run_edits("maxset", ed);
    const char *names[] = {"frame_ms", "edit_bytes_per_frame",
                           "migrated_bytes_per_frame",
                           "pointers_collected_per_frame"};
    for (guint k = 0; k < G_N_ELEMENTS(names); k++)
        assert_true(sf_test_metric(a, names[k]) == sf_test_metric(b, names[k]));
    sim_result_free(a);
    sim_result_free(b);
}

static void expect_error(const char *a, const char *b, const char *what)
{
    GError *e = NULL;
    const char *const o[] = {a, b, NULL};
    assert_null(sf_test_run(small, o, 1, NULL, FALSE, &e));
    assert_non_null(e);
    if (!strstr(e->message, what))
        fail_msg("'%s' not in '%s'", what, e->message);
    g_clear_error(&e);
}

static void test_errors(void **state)
{
    (void)state;
    expect_error("workload.edits={destroy: 1}", NULL, "destroy");
    expect_error("workload.edits=3", NULL, "{matrix, execute, unpost, post,");
    expect_error("workload.edits={matrix: -1}", NULL, "matrix");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_image_after_edits),
        cmocka_unit_test(test_deletion_next_frame),
        cmocka_unit_test(test_edit_work),
        cmocka_unit_test(test_adaptive_predicted),
        cmocka_unit_test(test_repeatable),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests_name("sf_edit", tests, NULL, NULL);
}
