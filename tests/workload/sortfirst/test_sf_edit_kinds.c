/* test_sf_edit_kinds.c — each sort-first edit kind (sf_edit.h) on a
 * three-structure database small enough to work out by hand:
 *   root (posted): matrix, execute a;  a: triangle;  b: triangle.
 * A matrix edit turns the root's matrix (the first structure's: found
 * in structure 0) by the angle about y and moves no max-set node; an
 * execute edit can only point root's execute at b (the one other
 * structure of a's height), creating one node and collecting one; an
 * unpost then a post of the root rebuild its tree (both nodes created
 * and collected); the per-kind counts add up.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <string.h>

#include "sim/core/rng.h"
#include "sim/workload/sortfirst/sf_edit.h"

typedef struct {
    SceneDb *src;
    WlSfDb *sf;
    WlSfBook *book;
    WlSfEdit *edit;
    SimRng rng;
    Vec3 v[3];
} Fix;

/* fix_init posts b as well (a second posting). */
static gboolean post_b;
/* fix_init gives root a triangle of its own, after its matrix. */
static gboolean root_prim;

static void add(SceneDb *db, guint sid, SceneElem e)
{
    assert_true(scene_db_append(db, sid, &e, NULL));
}

static void fix_init(Fix *f, const WlSfEditSpec *spec)
{
    f->v[0] = vec3(0, 0, 0), f->v[1] = vec3(1, 0, 0), f->v[2] = vec3(0, 1, 0);
    f->src = scene_db_new();
    guint root = scene_db_add_struct(f->src, "root");
    guint a = scene_db_add_struct(f->src, "a");
    guint b = scene_db_add_struct(f->src, "b");
    add(f->src, root, scene_elem_matrix(mat4_translate(1, 2, 3),
                                        SCENE_MAT_REPLACE));
    if (root_prim)
        add(f->src, root, scene_elem_prim(SCENE_EL_TRIANGLE, f->v, 3));
    add(f->src, root, scene_elem_execute(a));
    add(f->src, a, scene_elem_prim(SCENE_EL_TRIANGLE, f->v, 3));
    add(f->src, b, scene_elem_prim(SCENE_EL_TRIANGLE, f->v, 3));
    scene_db_post(f->src, root);
    if (post_b)
        scene_db_post(f->src, b);
    GError *e = NULL;
    f->sf = wl_sf_db_new(f->src, 2, 1, WL_SF_CHUNK_SORTED, &e);
    assert_non_null(f->sf);
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16);
    WlSfSizes z = {64, 40, 36, 8, 4, 8, 16, 96};
    f->book = wl_sf_book_new(f->sf, &r, WL_SF_MAXSET, &z);
    sim_rng_init(&f->rng, 3, 0);
    f->edit = wl_sf_edit_new(f->src, f->sf, spec, &f->rng);
}

static void fix_clear(Fix *f)
{
    wl_sf_edit_free(f->edit);
    wl_sf_book_free(f->book);
    wl_sf_db_free(f->sf);
    scene_db_free(f->src);
}

/* One editing frame; its counts must be (commands, created, collected). */
static gint64 *edit_frame(Fix *f, uint64_t commands, uint64_t created,
                          uint64_t collected)
{
    WlSfEditFrame ef;
    WlSfRemapWork w[2];
    memset(w, 0, sizeof w);
    gint64 *map = wl_sf_edit_frame(f->edit, f->book, &ef, w);
    assert_int_equal(ef.commands, commands);
    assert_int_equal(ef.nodes_created, created);
    assert_int_equal(ef.nodes_collected, collected);
    return map;
}

static void test_matrix_edit(void **st)
{
    (void)st;
    const WlSfEditSpec spec = {{1, 0, 0, 0}, 90};
    Fix f;
    fix_init(&f, &spec);
    gint64 *map = edit_frame(&f, 1, 0, 0);
    assert_non_null(map); /* one instance, the same one */
    assert_int_equal(wl_sf_n_insts(f.sf), 1);
    assert_int_equal(map[0], 0);
    g_free(map);
    const SceneElem *m = scene_db_elem(wl_sf_edit_db(f.edit), 0, 0);
    Mat4 want = mat4_mul(mat4_translate(1, 2, 3),
                         mat4_rotate(vec3(0, 1, 0), G_PI / 2));
    assert_memory_equal(&m->matrix, &want, sizeof want);
    assert_int_equal(wl_sf_edit_applied(f.edit)[WL_SF_ED_MATRIX], 1);
    /* the source database is not touched */
    Mat4 src = scene_db_elem(f.src, 0, 0)->matrix;
    Mat4 t = mat4_translate(1, 2, 3);
    assert_memory_equal(&src, &t, sizeof t);
    fix_clear(&f);
}

static void test_execute_edit(void **st)
{
    (void)st;
    const WlSfEditSpec spec = {{0, 1, 0, 0}, 10};
    Fix f;
    fix_init(&f, &spec);
    gint64 *map = edit_frame(&f, 1, 1, 1);
    assert_int_equal(scene_db_elem(wl_sf_edit_db(f.edit), 0, 1)->child, 2);
    assert_int_equal(wl_sf_n_insts(f.sf), 1);
    assert_int_equal(map[0], -1); /* b's instance is new */
    g_free(map);
    assert_int_equal(wl_sf_edit_applied(f.edit)[WL_SF_ED_EXECUTE], 1);
    /* and back: a again */
    map = edit_frame(&f, 1, 1, 1);
    assert_int_equal(scene_db_elem(wl_sf_edit_db(f.edit), 0, 1)->child, 1);
    g_free(map);
    assert_int_equal(wl_sf_edit_applied(f.edit)[WL_SF_ED_EXECUTE], 2);
    fix_clear(&f);
}

/* Unpost the root, post it again: a new posting, a new tree. */
static void test_unpost_post(void **st)
{
    (void)st;
    const WlSfEditSpec spec = {{0, 0, 1, 1}, 10};
    Fix f;
    fix_init(&f, &spec);
    gint64 *map = edit_frame(&f, 2, 2, 2);
    assert_int_equal(map[0], -1);
    g_free(map);
    assert_true(scene_db_is_posted(wl_sf_edit_db(f.edit), 0));
    assert_int_equal(scene_db_posted_count(wl_sf_edit_db(f.edit)), 1);
    const uint64_t *ap = wl_sf_edit_applied(f.edit);
    assert_int_equal(ap[WL_SF_ED_UNPOST], 1);
    assert_int_equal(ap[WL_SF_ED_POST], 1);
    assert_int_equal(ap[WL_SF_ED_MATRIX] + ap[WL_SF_ED_EXECUTE], 0);
    fix_clear(&f);
}

/* No edit asked: no command, no map. */
static void test_nothing(void **st)
{
    (void)st;
    const WlSfEditSpec spec = {{0, 0, 0, 0}, 10};
    assert_false(wl_sf_edit_any(&spec));
    const WlSfEditSpec one = {{0, 0, 0, 1}, 10};
    assert_true(wl_sf_edit_any(&one));
    Fix f;
    fix_init(&f, &spec);
    assert_null(edit_frame(&f, 0, 0, 0));
    fix_clear(&f);
}

/* A matrix edit with fix_init's flags set as given: the db has `nodes`
 * max-set nodes and two instances, and both continue (map 0, 1). */
static void matrix_keeps_both(gboolean two, gboolean own, guint nodes)
{
    const WlSfEditSpec spec = {{1, 0, 0, 0}, 30};
    Fix f;
    post_b = two;
    root_prim = own;
    fix_init(&f, &spec);
    post_b = root_prim = FALSE;
    assert_int_equal(f.sf->nodes->len, nodes);
    assert_int_equal(wl_sf_n_insts(f.sf), 2);
    gint64 *map = edit_frame(&f, 1, 0, 0);
    assert_int_equal(map[0], 0);
    assert_int_equal(map[1], 1);
    g_free(map);
    fix_clear(&f);
}

/* Two postings: root (node 0, its execute of a node 1) and b (node 2,
 * a root too).  A matrix edit keeps both trees: every node and instance
 * continues (b's root is matched to the old root of its own posting,
 * not to a child of node 0). */
static void test_two_postings(void **st)
{
    (void)st;
    matrix_keeps_both(TRUE, FALSE, 3);
}

/* The root's own triangle: its chunk (chunk 0, structure 0) has one
 * instance, of max-set node 0 (instance 0); a's, of node 1, is
 * instance 1.  A matrix edit keeps both: node 0 continues old node 0,
 * so its instance is old instance 0, not a new one. */
static void test_root_node_kept(void **st)
{
    (void)st;
    matrix_keeps_both(FALSE, TRUE, 2);
}

/* Structure 0 a leaf ("b" first): an execute edit can point the root's
 * execute of "a" at it, structure 0 being of a's height. */
static void test_execute_to_first(void **st)
{
    (void)st;
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    SceneDb *src = scene_db_new();
    guint b = scene_db_add_struct(src, "b");
    guint root = scene_db_add_struct(src, "root");
    guint a = scene_db_add_struct(src, "a");
    add(src, b, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    add(src, root, scene_elem_execute(a));
    add(src, a, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    scene_db_post(src, root);
    WlSfDb *sf = wl_sf_db_new(src, 2, 1, WL_SF_CHUNK_SORTED, NULL);
    assert_non_null(sf);
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16);
    WlSfSizes z = {64, 40, 36, 8, 4, 8, 16, 96};
    WlSfBook *book = wl_sf_book_new(sf, &r, WL_SF_MAXSET, &z);
    SimRng rng;
    sim_rng_init(&rng, 3, 0);
    const WlSfEditSpec spec = {{0, 1, 0, 0}, 10};
    WlSfEdit *ed = wl_sf_edit_new(src, sf, &spec, &rng);
    WlSfEditFrame ef;
    WlSfRemapWork w[2] = {{0}};
    gint64 *map = wl_sf_edit_frame(ed, book, &ef, w);
    assert_int_equal(ef.commands, 1);
    assert_int_equal(scene_db_elem(wl_sf_edit_db(ed), root, 0)->child, b);
    g_free(map);
    wl_sf_edit_free(ed);
    wl_sf_book_free(book);
    wl_sf_db_free(sf);
    scene_db_free(src);
}

/* Unposting the only posted structure leaves no instance: the edit
 * still hands back a map (empty, but not NULL: numbers changed, so the
 * run remaps its prediction too); both nodes are collected.  A second
 * frame finds nothing to unpost: no command, no map. */
static void test_unpost_last(void **st)
{
    (void)st;
    const WlSfEditSpec spec = {{0, 0, 1, 0}, 10};
    Fix f;
    fix_init(&f, &spec);
    gint64 *map = edit_frame(&f, 1, 0, 2);
    assert_non_null(map);
    assert_int_equal(wl_sf_n_insts(f.sf), 0);
    assert_int_equal(f.sf->nodes->len, 0);
    g_free(map);
    assert_null(edit_frame(&f, 0, 0, 0));
    assert_int_equal(wl_sf_edit_applied(f.edit)[WL_SF_ED_UNPOST], 1);
    fix_clear(&f);
}

/* ---- the execute edit's 16 tries (MAX_EXEC_TRIES) --------------------- */

/* One leaf L; a and b execute L (the same height); the posted root
 * executes a once, then L 98 times.  Of the 101 executes only root's
 * first can be retargeted (at b): every other points at L, the one
 * structure of its height.  Each try draws an execute (1 in 101) and a
 * starting structure (sf_edit.c edit_execute, retarget). */
static SceneDb *tries_db(void)
{
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    SceneDb *db = scene_db_new();
    guint l = scene_db_add_struct(db, "L");
    guint a = scene_db_add_struct(db, "a");
    guint b = scene_db_add_struct(db, "b");
    guint root = scene_db_add_struct(db, "root");
    add(db, l, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    add(db, a, scene_elem_execute(l));
    add(db, b, scene_elem_execute(l));
    add(db, root, scene_elem_execute(a));
    for (int k = 0; k < 98; k++)
        add(db, root, scene_elem_execute(l));
    scene_db_post(db, root);
    return db;
}

/* The try (0-based) on which seed `seed` first draws root's execute of
 * a (execute 2 of the 101: a's, b's, then root's), replaying the two
 * draws of each try; G_MAXUINT if not within 40. */
static guint first_hit(uint64_t seed)
{
    SimRng g;
    sim_rng_init(&g, seed, 0);
    for (guint t = 0; t < 40; t++) {
        gboolean hit = sim_rng_below(&g, 101) == 2;
        sim_rng_below(&g, 4);
        if (hit)
            return t;
    }
    return G_MAXUINT;
}

/* Whether one execute edit with `seed` applies. */
static gboolean execute_applies(SceneDb *src, uint64_t seed)
{
    WlSfDb *sf = wl_sf_db_new(src, 2, 1, WL_SF_CHUNK_SORTED, NULL);
    assert_non_null(sf);
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16);
    WlSfSizes z = {64, 40, 36, 8, 4, 8, 16, 96};
    WlSfBook *book = wl_sf_book_new(sf, &r, WL_SF_MAXSET, &z);
    SimRng rng;
    sim_rng_init(&rng, seed, 0);
    const WlSfEditSpec spec = {{0, 1, 0, 0}, 10};
    WlSfEdit *ed = wl_sf_edit_new(src, sf, &spec, &rng);
    WlSfEditFrame ef;
    WlSfRemapWork w[2] = {{0}};
    g_free(wl_sf_edit_frame(ed, book, &ef, w));
    gboolean applied = ef.commands == 1;
    if (applied) /* root's execute of a now points at b */
        assert_int_equal(scene_db_elem(wl_sf_edit_db(ed), 3, 0)->child, 2);
    wl_sf_edit_free(ed);
    wl_sf_book_free(book);
    wl_sf_db_free(sf);
    return applied;
}

/* An execute edit gives up after exactly 16 tries: a seed whose first
 * draw of the one retargetable execute is the 16th try applies, one
 * whose first is the 17th does not (nor one of the 2nd, as a check). */
static void test_execute_tries(void **st)
{
    (void)st;
    SceneDb *src = tries_db();
    const guint want[3] = {1, 15, 16};
    for (guint k = 0; k < 3; k++) {
        uint64_t seed = 1;
        while (first_hit(seed) != want[k])
            seed++;
        assert_true(execute_applies(src, seed) == (want[k] < 16));
    }
    scene_db_free(src);
}

/* A post with no structure unposted by an edit picks one never posted:
 * the first not posted from a random structure on (sf_edit.c
 * edit_post).  With a seed whose draw starts at the root (posted) that
 * is a (structure 1), then b; with all three posted no edit applies. */
static void test_post_random(void **st)
{
    (void)st;
    uint64_t seed = 1;
    for (;; seed++) {
        SimRng g;
        sim_rng_init(&g, seed, 0);
        if (sim_rng_below(&g, 3) == 0)
            break;
    }
    const WlSfEditSpec spec = {{0, 0, 0, 1}, 10};
    Fix f;
    fix_init(&f, &spec);
    sim_rng_init(&f.rng, seed, 0); /* the editor's (borrowed) */
    g_free(edit_frame(&f, 1, 1, 0)); /* a: one new root node */
    const SceneDb *db = wl_sf_edit_db(f.edit);
    assert_true(scene_db_is_posted(db, 1));
    assert_false(scene_db_is_posted(db, 2));
    g_free(edit_frame(&f, 1, 1, 0)); /* then b, the one left */
    assert_true(scene_db_is_posted(db, 2));
    assert_int_equal(scene_db_posted_count(db), 3);
    assert_null(edit_frame(&f, 0, 0, 0));
    assert_int_equal(wl_sf_edit_applied(f.edit)[WL_SF_ED_POST], 2);
    fix_clear(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_matrix_edit),
        cmocka_unit_test(test_execute_edit),
        cmocka_unit_test(test_unpost_post),
        cmocka_unit_test(test_nothing),
        cmocka_unit_test(test_two_postings),
        cmocka_unit_test(test_root_node_kept),
        cmocka_unit_test(test_execute_to_first),
        cmocka_unit_test(test_unpost_last),
        cmocka_unit_test(test_execute_tries),
        cmocka_unit_test(test_post_random),
    };
    return cmocka_run_group_tests_name("sf_edit_kinds", tests, NULL, NULL);
}
