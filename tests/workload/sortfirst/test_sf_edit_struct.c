/* test_sf_edit_struct.c — the structure, primitive, colour and execute
 * add/delete edits of sort-first (sf_edit.h, sf_edit_struct.c,
 * sf_db_edit.c) on a small vehicle (40 structures, 3,000 triangles, 3
 * instances, 64 x 64, 4 processors), under min-set and max-set:
 *   - each kind alone, frame by frame: the regions' image equals a
 *     serial render of the edited database flattened anew here, and
 *     (kinds that change what is drawn) differs from the unedited one;
 *     the chunks hold every primitive of the edited database exactly
 *     once, each at most N, each box exactly its primitives' box (so
 *     volumes grow and shrink), each chunk one instance per max-set node
 *     of its structure; the book's state is consistent (masters hold
 *     their chunks and, max-set, every pointer; a pointer's processor
 *     holds its chunk; a max-set slave copy is referenced by a pointer;
 *     the migration invariant);
 *   - execute_add makes more max-set nodes and polygons, execute_delete
 *     fewer, prim_create more chunks' polygons, prim_delete fewer;
 *   - every kind at once, 40 rounds, both bookkeepings (a fixed seed);
 *   - the same through the runner with image checks, and the chunk
 *     counts and edit metrics move.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/scene_cfg.h"
#include "tests/workload/sortfirst/sf_testutil.h"

static const char *const small = SF_TEST_SMALL;

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

static uint64_t image_digest(const RastZBuffer *zb)
{
    const guint8 *rgba = (const guint8 *)zb->rgba,
                 *prim = (const guint8 *)zb->prim;
    uint64_t h = 1469598103934665603u;
    for (int i = 0; i < 64 * 64 * 4; i++)
        h = (h ^ rgba[i]) * 1099511628211u;
    for (int i = 0; i < 64 * 64 * 4; i++)
        h = (h ^ prim[i]) * 1099511628211u;
    return h;
}

/* A digest of db flattened and drawn serially with frame f's camera. */
static uint64_t serial_digest(const Scene *scene, const SceneDb *db, int f)
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
    uint64_t h = image_digest(zb);
    scene_mesh_free(mesh);
    rast_zbuffer_free(zb);
    return h;
}

/* Every primitive of the edited database in exactly one chunk of its
 * structure, chunks of at most N with tight boxes and one instance per
 * max-set node of their structure. */
static void check_chunks(const WlSfDb *d, const SceneDb *db)
{
    guint ns = scene_db_struct_count(db);
    assert_int_equal(d->n_structs, ns);
    guint *nodes = g_new0(guint, ns);
    for (guint i = 0; i < d->nodes->len; i++)
        nodes[g_array_index(d->nodes, SceneMaxNode, i).sid]++;
    GHashTable *seen = g_hash_table_new(g_direct_hash, g_direct_equal);
    uint64_t prims = 0;
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        assert_true(ch->n_prims >= 1 && ch->n_prims <= d->granularity);
        assert_int_equal(ch->n_inst, nodes[ch->sid]);
        SceneBox b = scene_box_empty();
        for (guint k = 0; k < ch->n_prims; k++) {
            guint pos = g_array_index(d->prims, guint, ch->prim_first + k);
            const SceneElem *e = scene_db_elem(db, ch->sid, pos);
            assert_true(scene_elem_is_prim(e->kind) && e->nverts >= 3);
            gpointer key = GUINT_TO_POINTER(ch->sid * 100000 + pos + 1);
            assert_false(g_hash_table_contains(seen, key));
            g_hash_table_add(seen, key);
            for (guint v = 0; v < e->nverts; v++)
                b = scene_box_add_point(b, e->verts[v]);
        }
        assert_memory_equal(&b, &ch->box, sizeof b);
    }
    for (guint s = 0; s < ns; s++)
        for (guint i = 0; i < scene_db_len(db, s); i++) {
            const SceneElem *e = scene_db_elem(db, s, i);
            prims += scene_elem_is_prim(e->kind) && e->nverts >= 3;
        }
    assert_int_equal(g_hash_table_size(seen), prims);
    assert_int_equal(d->min_prims, prims);
    g_hash_table_unref(seen);
    g_free(nodes);
}

/* The book after a frame: masters hold their chunks (and, max-set,
 * every pointer of them); max-set, a pointer's holder holds the chunk
 * and a slave copy has a pointer; every overlap is held. */
static void check_book(const WlSfBook *b)
{
    const WlSfDb *d = b->db;
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        uint64_t m = wl_sf_bit(b->master[c]), refs = 0;
        assert_true(b->held_data[c] & m);
        for (guint i = ch->inst_first; b->bk == WL_SF_MAXSET &&
                                       i < ch->inst_first + ch->n_inst;
             i++) {
            assert_true(b->held_inst[i] & m);
            assert_true((b->held_inst[i] & ~b->held_data[c]) == 0);
            refs |= b->held_inst[i];
        }
        if (b->bk == WL_SF_MAXSET && ch->n_inst)
            assert_true((b->held_data[c] & ~refs) == 0);
    }
    guint inst, proc;
    assert_true(wl_sf_book_check(b, &inst, &proc));
}

static uint64_t max_polys(const Fixture *f)
{
    return scene_mesh_n_polys(f->db->flat);
}

/* `frames` frames of spec under bk with every check; returns the last
 * frame's max-set polygons, *changed: some frame's image differed from
 * the unedited database's. */
static uint64_t run_checked(WlSfBookkeeping bk, const WlSfEditSpec *spec,
                            int frames, gboolean *changed)
{
    Fixture f;
    fixture_init(&f, bk, spec);
    GError *e = NULL;
    *changed = FALSE;
    for (int frame = 0; frame < frames; frame++) {
        if (!wl_sf_run_frames(f.run, 1, SIM_TIME_MAX, &e))
            fail_msg("frame %d: %s", frame, e->message);
        const SceneDb *now = wl_sf_edit_db(f.edit);
        uint64_t got = image_digest(wl_sf_run_zbuffer(f.run));
        assert_true(got == serial_digest(f.scene, now, frame));
        *changed |= got != serial_digest(f.scene, f.scene->db, frame);
        check_chunks(f.db, now);
        check_book(wl_sf_run_book(f.run));
    }
    const uint64_t *ap = wl_sf_edit_applied(f.edit);
    for (int k = 0; k < WL_SF_ED_N; k++)
        if (spec->per_frame[k] && k != WL_SF_ED_DELETE)
            assert_true(ap[k] > 0);
    uint64_t polys = max_polys(&f);
    fixture_clear(&f);
    return polys;
}

static WlSfEditSpec only(int kind, uint64_t n)
{
    WlSfEditSpec s = {{0}, 10};
    s.per_frame[kind] = n;
    return s;
}

static const uint64_t vehicle_polys = 3 * 3000; /* max-set, unedited */

static void test_each_kind(void **state)
{
    (void)state;
    for (int bk = 0; bk <= 1; bk++) {
        gboolean changed;
        WlSfEditSpec s = only(WL_SF_ED_PRIM_CHANGE, 30);
        run_checked((WlSfBookkeeping)bk, &s, 5, &changed);
        assert_true(changed);
        s = only(WL_SF_ED_COLOR, 2);
        run_checked((WlSfBookkeeping)bk, &s, 5, &changed);
        assert_true(changed);
        s = only(WL_SF_ED_PRIM_CREATE, 4);
        assert_true(run_checked((WlSfBookkeeping)bk, &s, 5, &changed) >
                    vehicle_polys);
        assert_true(changed);
        s = only(WL_SF_ED_PRIM_DELETE, 20);
        assert_true(run_checked((WlSfBookkeeping)bk, &s, 5, &changed) <
                    vehicle_polys);
        assert_true(changed);
        s = only(WL_SF_ED_EXEC_ADD, 1);
        assert_true(run_checked((WlSfBookkeeping)bk, &s, 5, &changed) >
                    vehicle_polys);
        s = only(WL_SF_ED_EXEC_DELETE, 1);
        assert_true(run_checked((WlSfBookkeeping)bk, &s, 5, &changed) <
                    vehicle_polys);
        assert_true(changed);
    }
}

/* Create, add 3 primitives, close, then execute it somewhere (an
 * execute_add may pick it: run until one does) and delete structures
 * nothing executes. */
static void test_structures(void **state)
{
    (void)state;
    for (int bk = 0; bk <= 1; bk++) {
        WlSfEditSpec s = {{0}, 10};
        s.per_frame[WL_SF_ED_CREATE] = 1;
        s.per_frame[WL_SF_ED_ADD] = 3;
        s.per_frame[WL_SF_ED_CLOSE] = 1;
        s.per_frame[WL_SF_ED_EXEC_ADD] = 2;
        gboolean changed;
        run_checked((WlSfBookkeeping)bk, &s, 8, &changed);
        s = only(WL_SF_ED_DELETE, 1);
        s.per_frame[WL_SF_ED_EXEC_DELETE] = 2;
        run_checked((WlSfBookkeeping)bk, &s, 6, &changed);
        assert_true(changed);
    }
}

/* A posted root is never deleted; the vehicle's one posted root
 * (the world) unposted is, being neither posted nor executed. */
static void test_delete_root(void **state)
{
    (void)state;
    Fixture f;
    WlSfEditSpec s = only(WL_SF_ED_DELETE, 3);
    fixture_init(&f, WL_SF_MAXSET, &s);
    GError *e = NULL;
    assert_true(wl_sf_run_frames(f.run, 3, SIM_TIME_MAX, &e));
    assert_int_equal(wl_sf_edit_applied(f.edit)[WL_SF_ED_DELETE], 0);
    assert_int_equal(max_polys(&f), vehicle_polys);
    fixture_clear(&f);
    s.per_frame[WL_SF_ED_UNPOST] = 1;
    s.per_frame[WL_SF_ED_DELETE] = 1;
    fixture_init(&f, WL_SF_MAXSET, &s);
    guint world = scene_db_posted_at(f.scene->db, 0);
    assert_true(wl_sf_run_frames(f.run, 2, SIM_TIME_MAX, &e));
    const SceneDb *db = wl_sf_edit_db(f.edit);
    /* frame 1: the world unposted, then deleted (the only structure
     * neither posted nor executed); its tree and chunks are gone */
    assert_int_equal(wl_sf_edit_applied(f.edit)[WL_SF_ED_DELETE], 1);
    assert_int_equal(scene_db_len(db, world), 0);
    assert_int_equal(scene_db_posted_count(db), 0);
    assert_int_equal(max_polys(&f), 0);
    for (guint c = 0; c < wl_sf_n_chunks(f.db); c++)
        assert_int_not_equal(wl_sf_chunk(f.db, c)->sid, world);
    check_chunks(f.db, db);
    fixture_clear(&f);
}

static void test_random_rounds(void **state)
{
    (void)state;
    WlSfEditSpec s = {{1, 1, 1, 1, 1, 2, 1, 2, 2, 2, 1, 1, 1, 1}, 20};
    for (int bk = 0; bk <= 1; bk++) {
        gboolean changed;
        run_checked((WlSfBookkeeping)bk, &s, 40, &changed);
        assert_true(changed);
    }
}

/* Through the runner: every kind, image checked each frame; the chunks
 * are re-formed (their count moves) and the edit metrics count them. */
static void test_runner(void **state)
{
    (void)state;
    const char *all =
        "{create: 1, add: 2, close: 1, prim_create: 2, prim_change: 2, "
        "prim_delete: 2, color: 1, execute_add: 1, execute_delete: 1, "
        "delete: 1}";
    for (int bk = 0; bk <= 1; bk++) {
        const char *b = bk ? "maxset" : "minset";
        SimResult *r = sf_test_run_checked(small, 10, "workload.bookkeeping",
                                           b, "workload.edits", all);
        SimResult *base = sf_test_run_checked(small, 10,
                                              "workload.bookkeeping", b,
                                              "workload.edits", "{}");
        assert_true(sf_test_metric(r, "edits_per_frame") > 10);
        assert_true(sf_test_metric(r, "chunks") !=
                    sf_test_metric(base, "chunks"));
        sim_result_free(r);
        sim_result_free(base);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_kind),
        cmocka_unit_test(test_structures),
        cmocka_unit_test(test_delete_root),
        cmocka_unit_test(test_random_rounds),
        cmocka_unit_test(test_runner),
    };
    return cmocka_run_group_tests_name("sf_edit_struct", tests, NULL, NULL);
}
