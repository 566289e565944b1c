/* test_pphigs_exact.c — the PPHIGS distribution (seed 001 §2-§5) on
 * lists of a handful of elements, every result worked out by hand: which
 * GP holds which host element after dealing (simple, complex clusters,
 * by structure), after edits, moves and strip splitting; the exact
 * traffic and nominal loads; the attribute-state cache's checkpoints
 * (where the backward scan stops, how far the cache walks); the
 * rebalancer's exact move counts (the gap test, the move cap, the
 * budget).  The other pphigs suites check properties on large random
 * lists (same render as the host, bounds); these pin the values.
 *
 * Lists are spelled one character per element: C colour, M replace
 * matrix, m concatenate matrix, t on-screen triangle, o off-screen
 * triangle (x = 5), p order-dependent polygon, 1-9 execute of that
 * structure.  A GP's list is printed as the host positions it holds,
 * 'a' for 0.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "sim/workload/pphigs/pphigs_rebalance.h"
#include "tests/workload/pphigs/pphigs_rig.h"
#include "sim/scene/pphigs_db.h"

/* Unit weights: a triangle 1 (w_vertex 0), attributes small. */
static const WlPphigsWeights W = {
    .w = {[SCENE_EL_TRIANGLE] = 1,
          [SCENE_EL_POLYGON] = 1,
          [SCENE_EL_TRISTRIP] = 2,
          [SCENE_EL_POLYGON2D] = 1,
          [SCENE_EL_COLOR] = 0.125,
          [SCENE_EL_MATRIX] = 0.25,
          [SCENE_EL_EXECUTE] = 0.5},
    .w_vertex = 0,
    .cluster = 1,
};

static SceneElem spell_elem(char ch, Vec3 *v)
{
    double x = ch == 'o' ? 5 : 0;
    v[0] = vec3(x, 0, 0), v[1] = vec3(x + 0.5, 0, 0), v[2] = vec3(x, 0.5, 0);
    switch (ch) {
    case 'C':
        return scene_elem_color(vec3(1, 0, 0));
    case 'M':
        return scene_elem_matrix(mat4_identity(), SCENE_MAT_REPLACE);
    case 'm':
        return scene_elem_matrix(mat4_identity(), SCENE_MAT_CONCAT);
    case 'p':
        return scene_elem_prim(SCENE_EL_POLYGON2D, v, 3);
    case 't':
    case 'o':
        return scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    default:
        g_assert(ch >= '1' && ch <= '9');
        return scene_elem_execute((guint)(ch - '0'));
    }
}

/* Structures spelled by the NULL-terminated list; 0 posted. */
static SceneDb *spell_db(const char *const *lists)
{
    SceneDb *db = scene_db_new();
    guint n = 0;
    while (lists[n])
        n++;
    for (guint s = 0; s < n; s++)
        scene_db_add_struct(db, (char[]){(char)('a' + s), 0});
    for (guint s = 0; s < n; s++)
        for (const char *c = lists[s]; *c; c++) {
            Vec3 v[3];
            SceneElem e = spell_elem(*c, v);
            assert_true(scene_db_append(db, s, &e, NULL));
        }
    scene_db_post(db, 0);
    return db;
}

/* The host positions GP g holds of structure sid, 'a' for 0. */
static void assert_gp(const WlPphigsDist *d, guint g, guint sid,
                      const char *want)
{
    const SceneDb *h = wl_pphigs_dist_host(d), *p = wl_pphigs_dist_gp(d, g);
    char got[64] = {0};
    for (guint i = 0; i < scene_db_len(p, sid) && i < 63; i++) {
        got[i] = '?';
        for (guint k = 0; k < scene_db_len(h, sid); k++)
            if (scene_db_elem(h, sid, k)->tag == scene_db_elem(p, sid, i)->tag)
                got[i] = (char)('a' + k);
    }
    assert_string_equal(got, want);
}

static WlPphigsDist *dist1(const char *list, guint ngp, WlPphigsAlgo a,
                           const WlPphigsWeights *w)
{
    const char *const lists[] = {list, NULL};
    SceneDb *db = spell_db(lists);
    WlPphigsDist *d = wl_pphigs_dist_new(db, ngp, a, w);
    scene_db_free(db);
    return d;
}

static void assert_loads(const WlPphigsDist *d, const double *want)
{
    double got[8];
    wl_pphigs_dist_loads(d, got);
    for (guint g = 0; g < wl_pphigs_dist_ngp(d); g++)
        assert_true(fabs(got[g] - want[g]) < 1e-12);
}

/* ---- dealing (§2.2-2.3) ---------------------------------------------- */

/* Simple: every attribute to every GP, each triangle to the least-loaded
 * GP, ties to the lowest: GP 0 b d, GP 1 c e, GP 2 f. */
static void test_simple_deal(void **st)
{
    (void)st;
    WlPphigsDist *d = dist1("Cttttt", 3, WL_PPHIGS_SIMPLE, &W);
    assert_int_equal(wl_pphigs_dist_algo(d), WL_PPHIGS_SIMPLE);
    assert_int_equal(wl_pphigs_dist_ngp(d), 3);
    assert_gp(d, 0, 0, "abe");
    assert_gp(d, 1, 0, "acf");
    assert_gp(d, 2, 0, "ad");
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(d);
    assert_int_equal(t->elements_sent, 8);
    assert_int_equal(t->sent_to[0], 3);
    assert_int_equal(t->sent_to[1], 3);
    assert_int_equal(t->sent_to[2], 2);
    assert_int_equal(t->sent_to[3], 0);
    assert_int_equal(t->elements_removed, 0);
    assert_int_equal(t->total_scan, 0); /* simple: no backward scan */
    static const double load[] = {2.125, 2.125, 1.125};
    assert_loads(d, load);
    static const gint own[] = {-1, 0, 1, 2, 0, 1};
    for (guint i = 0; i < 6; i++)
        assert_int_equal(wl_pphigs_dist_owner(d, 0, i), own[i]);
    wl_pphigs_dist_free(d);
}

/* Complex, c = 2 (clusters of two unit triangles): b c on GP 0, d e on
 * GP 1, f on GP 0 again (loads 2, 2: the tie goes to GP 0); the colour
 * only where a triangle after it is dealt. */
static void test_complex_clusters(void **st)
{
    (void)st;
    WlPphigsWeights w = W;
    w.cluster = 2;
    WlPphigsDist *d = dist1("Cttttt", 2, WL_PPHIGS_COMPLEX, &w);
    assert_gp(d, 0, 0, "abcf");
    assert_gp(d, 1, 0, "ade");
    static const double load[] = {3.125, 2.125};
    assert_loads(d, load);
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(d);
    assert_int_equal(t->elements_sent, 7);
    /* the initial step 2 scans nothing back from position 0 */
    assert_int_equal(t->total_scan, 0);
    wl_pphigs_dist_free(d);
    /* c = 1.5: a second triangle would exceed the cluster: one each */
    w.cluster = 1.5;
    d = dist1("Cttttt", 2, WL_PPHIGS_COMPLEX, &w);
    assert_gp(d, 0, 0, "abdf");
    assert_gp(d, 1, 0, "ace");
    wl_pphigs_dist_free(d);
}

/* A concatenate-mode matrix goes at once, with the replace matrix
 * before it, to every GP (a GP drawing after it needs both): GP 1 gets
 * a and c, GP 0 c; a replace matrix alone goes only with a triangle. */
static void test_concat_to_every_gp(void **st)
{
    (void)st;
    WlPphigsDist *d = dist1("Mtmt", 3, WL_PPHIGS_COMPLEX, &W);
    assert_gp(d, 0, 0, "abc");
    assert_gp(d, 1, 0, "acd");
    assert_gp(d, 2, 0, "ac");
    assert_int_equal(wl_pphigs_dist_traffic(d)->elements_sent, 8);
    wl_pphigs_dist_free(d);
    d = dist1("Mtmmt", 2, WL_PPHIGS_COMPLEX, &W);
    assert_gp(d, 0, 0, "abcd");
    assert_gp(d, 1, 0, "acde");
    wl_pphigs_dist_free(d);
    d = dist1("tMtt", 2, WL_PPHIGS_COMPLEX, &W); /* replace: only with t */
    assert_gp(d, 0, 0, "abd");
    assert_gp(d, 1, 0, "bc");
    wl_pphigs_dist_free(d);
}

/* Weights: a triangle w + 3 w_vertex; an execute of an ordinary
 * structure its own weight; of a primitive structure (complex) the
 * weight of the structure's elements as well. */
static void test_weights(void **st)
{
    (void)st;
    const char *const lists[] = {"12t", "Ctt", "tt", NULL};
    SceneDb *db = spell_db(lists);
    scene_db_set_primitive(db, 1, TRUE);
    WlPphigsWeights w = W;
    w.w_vertex = 0.5;
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
    const SceneDb *h = wl_pphigs_dist_host(d);
    assert_true(wl_pphigs_dist_weight(d, scene_db_elem(h, 0, 2)) == 2.5);
    /* 0.5 + 0.125 + 2 * 2.5 */
    assert_true(wl_pphigs_dist_weight(d, scene_db_elem(h, 0, 0)) == 5.625);
    assert_true(wl_pphigs_dist_weight(d, scene_db_elem(h, 0, 1)) == 0.5);
    assert_true(wl_pphigs_dist_weight(d, scene_db_elem(h, 1, 0)) == 0.125);
    /* the primitive-structure execute is dealt (to GP 0, the heavier),
     * its contents go to every GP; the ordinary execute to every GP */
    assert_int_equal(wl_pphigs_dist_owner(d, 0, 0), 0);
    assert_int_equal(wl_pphigs_dist_owner(d, 0, 1), -1);
    assert_int_equal(wl_pphigs_dist_owner(d, 0, 2), 1);
    assert_int_equal(wl_pphigs_dist_owner(d, 1, 1), -1);
    assert_gp(d, 0, 0, "ab");
    assert_gp(d, 1, 0, "bc");
    for (guint g = 0; g < 2; g++)
        assert_int_equal(scene_db_len(wl_pphigs_dist_gp(d, g), 1), 3);
    /* structure c dealt on its own: its loads tie, so its first
     * triangle goes to GP 1, the lighter overall (5.625 against 2.5),
     * the second to GP 0, lighter in c */
    assert_gp(d, 0, 2, "b");
    assert_gp(d, 1, 2, "a");
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* ---- §2.1 by structure ------------------------------------------------ */

/* a = C 1 2 t; b = t t t (weight 3.5 with its execute, over the share
 * (0.125 + 3.5 + 1.5 + 1) / 2 = 3.0625: broken up, its triangles dealt
 * in turn: GP 0, 1, 0); c = t (1.5: whole, to GP 1, the lighter); the
 * last t to GP 0 (loads 2, 2.5).  Ties go to the lower GP. */
static void test_by_structure_exact(void **st)
{
    (void)st;
    const char *const lists[] = {"C12t", "ttt", "t", NULL};
    SceneDb *db = spell_db(lists);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_BY_STRUCTURE, &W);
    assert_int_equal(wl_pphigs_dist_algo(d), WL_PPHIGS_BY_STRUCTURE);
    assert_gp(d, 0, 0, "abd");
    assert_gp(d, 1, 0, "abc");
    assert_gp(d, 0, 1, "ac");
    assert_gp(d, 1, 1, "b");
    assert_gp(d, 0, 2, "");
    assert_gp(d, 1, 2, "a");
    /* flat, over each GP's max-set: C 1 t + b's t t, and C 1 2 + t + t */
    static const double load[] = {3.625, 3.125};
    assert_loads(d, load);
    wl_pphigs_dist_free(d);
    /* with c instanced twice nothing changes for b; c goes whole (1.5
     * each) to the lighter GP both times */
    const char *const twice[] = {"C122", "ttt", "t", NULL};
    db = (scene_db_free(db), spell_db(twice));
    d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_BY_STRUCTURE, &W);
    assert_gp(d, 0, 0, "abd");
    assert_gp(d, 1, 0, "abc");
    assert_gp(d, 0, 2, "a");
    assert_gp(d, 1, 2, "a");
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* The bounds of §2.1's choices: an instance weighing exactly one GP's
 * share (2.5 of (0.5 + 2) * 2 / 2) stays whole; global loads within
 * 1e-12 of each other tie (to the lower GP). */
static void test_by_structure_bounds(void **st)
{
    (void)st;
    const char *const lists[] = {"12", "tt", "tt", NULL};
    SceneDb *db = spell_db(lists);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_BY_STRUCTURE, &W);
    assert_gp(d, 0, 0, "a");
    assert_gp(d, 1, 0, "b");
    assert_gp(d, 0, 1, "ab");
    assert_gp(d, 1, 1, "");
    assert_gp(d, 0, 2, "");
    assert_gp(d, 1, 2, "ab");
    wl_pphigs_dist_free(d);
    scene_db_free(db);
    const char *const tie[] = {"pt", NULL};
    db = spell_db(tie);
    WlPphigsWeights w = W;
    w.w[SCENE_EL_POLYGON2D] = 1e-12;
    d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_BY_STRUCTURE, &w);
    assert_gp(d, 0, 0, "ab");
    wl_pphigs_dist_free(d);
    w.w[SCENE_EL_POLYGON2D] = 2e-12; /* over the tolerance */
    d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_BY_STRUCTURE, &w);
    assert_gp(d, 0, 0, "a");
    assert_gp(d, 1, 0, "b");
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* ---- editing (§3) ------------------------------------------------------ */

/* Insert and delete in two steps; modify sends the new data to each
 * holder; traffic counted exactly. */
static void test_edits_exact(void **st)
{
    (void)st;
    WlPphigsDist *d = dist1("Cttt", 2, WL_PPHIGS_COMPLEX, &W);
    assert_gp(d, 0, 0, "abd");
    assert_gp(d, 1, 0, "ac");
    Vec3 v[3];
    SceneElem e = spell_elem('t', v);
    /* a triangle at 2: to the least-loaded GP 1 (loads 2, 1) at once */
    assert_true(wl_pphigs_dist_insert(d, 0, 2, &e, NULL));
    assert_int_equal(wl_pphigs_dist_owner(d, 0, 2), 1);
    wl_pphigs_dist_finish(d);
    assert_gp(d, 0, 0, "abe");
    assert_gp(d, 1, 0, "acd");
    assert_int_equal(wl_pphigs_dist_traffic(d)->elements_sent, 6);
    /* the backward scan from 2: b (GP 0), a colour: 2 examined, then the
     * start of the structure */
    assert_int_equal(wl_pphigs_dist_traffic(d)->last_scan, 2);
    static const double l1[] = {2.125, 2.125};
    assert_loads(d, l1);
    /* delete b: GP 0 loses it (and nothing else) */
    wl_pphigs_dist_delete(d, 0, 1);
    assert_int_equal(wl_pphigs_dist_traffic(d)->elements_removed, 1);
    wl_pphigs_dist_finish(d);
    assert_gp(d, 0, 0, "ad");
    assert_gp(d, 1, 0, "abc");
    static const double l2[] = {1.125, 2.125};
    assert_loads(d, l2);
    /* modify the colour: both holders get it */
    SceneElem c = spell_elem('C', v);
    c.color = vec3(0, 1, 0);
    assert_true(wl_pphigs_dist_modify(d, 0, 0, &c, NULL));
    assert_int_equal(wl_pphigs_dist_traffic(d)->elements_sent, 8);
    assert_int_equal(wl_pphigs_dist_traffic(d)->sent_to[0], 4);
    assert_int_equal(wl_pphigs_dist_traffic(d)->sent_to[1], 4);
    assert_true(scene_db_elem(wl_pphigs_dist_gp(d, 0), 0, 0)->color.y == 1);
    /* refused edits change nothing: a colour modified into a triangle,
     * an execute of the structure itself (a cycle) inserted or appended */
    GError *err = NULL;
    assert_false(wl_pphigs_dist_modify(d, 0, 0, &e, &err));
    assert_non_null(strstr(err->message, "expected an element of the same"));
    g_clear_error(&err);
    SceneElem x = scene_elem_execute(0);
    assert_false(wl_pphigs_dist_insert(d, 0, 1, &x, &err));
    assert_non_null(strstr(err->message, "expected an acyclic"));
    g_clear_error(&err);
    assert_false(wl_pphigs_dist_append(d, 0, &x, &err));
    g_clear_error(&err);
    assert_int_equal(scene_db_len(wl_pphigs_dist_host(d), 0), 4);
    assert_int_equal(wl_pphigs_dist_traffic(d)->elements_sent, 8);
    assert_gp(d, 0, 0, "ad");
    assert_gp(d, 1, 0, "abc");
    /* append: to GP 0 (loads 1, 2) */
    assert_true(wl_pphigs_dist_append(d, 0, &e, NULL));
    assert_gp(d, 0, 0, "ade");
    static const double l3[] = {2.125, 2.125};
    assert_loads(d, l3);
    wl_pphigs_dist_free(d);
}

/* An inserted colour goes to the host alone in step 1; step 2 walks on
 * past it until every GP has been checked, sending it to the GP of each
 * triangle after it (d on GP 1, e on GP 0); deleted, it leaves every
 * GP, and the triangles keep the colour before it. */
static void test_colour_insert_delete(void **st)
{
    (void)st;
    WlPphigsDist *d = dist1("Cttt", 2, WL_PPHIGS_COMPLEX, &W);
    Vec3 v[3];
    SceneElem c = spell_elem('C', v);
    assert_true(wl_pphigs_dist_insert(d, 0, 2, &c, NULL));
    assert_gp(d, 0, 0, "abe"); /* step 1: the host only */
    assert_gp(d, 1, 0, "ad");
    assert_int_equal(wl_pphigs_dist_owner(d, 0, 2), -1);
    wl_pphigs_dist_finish(d);
    assert_gp(d, 0, 0, "abce");
    assert_gp(d, 1, 0, "acd");
    assert_int_equal(wl_pphigs_dist_traffic(d)->last_scan, 2);
    assert_int_equal(wl_pphigs_dist_traffic(d)->elements_sent, 5 + 2);
    wl_pphigs_dist_delete(d, 0, 2);
    assert_int_equal(wl_pphigs_dist_traffic(d)->elements_removed, 2);
    wl_pphigs_dist_finish(d);
    assert_gp(d, 0, 0, "abd");
    assert_gp(d, 1, 0, "ac");
    assert_int_equal(wl_pphigs_dist_traffic(d)->elements_sent, 7);
    wl_pphigs_dist_free(d);
}

/* §4: ODP deltas worked out for a = p 1 p, b = p p on 2 GPs (a's p to
 * GP 0 and 1, the execute to both, b's p to GP 0 and 1): serial
 * priorities a.a 1, b.a 2, b.b 3, a.c 4; each GP's deltas add up to the
 * serial priority of each ODP it holds. */
static void test_odp_deltas(void **st)
{
    (void)st;
    const char *const lists[] = {"p1p", "pp", NULL};
    SceneDb *db = spell_db(lists);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &W);
    assert_gp(d, 0, 0, "ab");
    assert_gp(d, 1, 0, "bc");
    assert_gp(d, 0, 1, "a");
    assert_gp(d, 1, 1, "b");
    static const struct {
        guint g, s;
        int64_t delta[2], end;
    } want[] = {{0, 0, {1, 0}, 1}, {1, 0, {1, 1}, 0},
                {0, 1, {1, 0}, 1}, {1, 1, {2, 0}, 0}};
    for (guint k = 0; k < G_N_ELEMENTS(want); k++) {
        const SceneDb *p = wl_pphigs_dist_gp(d, want[k].g);
        for (guint i = 0; i < scene_db_len(p, want[k].s); i++)
            assert_int_equal(scene_db_elem(p, want[k].s, i)->delta,
                             want[k].delta[i]);
        assert_int_equal(scene_db_end_delta(p, want[k].s), want[k].end);
    }
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* A move takes the element off its GP, adds it to the other with the
 * attributes it needs there, and moves the load. */
static void test_move_exact(void **st)
{
    (void)st;
    WlPphigsDist *d = dist1("tCtt", 2, WL_PPHIGS_COMPLEX, &W);
    assert_gp(d, 0, 0, "abd");
    assert_gp(d, 1, 0, "bc");
    assert_false(wl_pphigs_dist_move(d, 0, 1, 0)); /* a colour */
    assert_false(wl_pphigs_dist_move(d, 0, 2, 1)); /* already there */
    assert_true(wl_pphigs_dist_move(d, 0, 3, 1));
    assert_gp(d, 0, 0, "ab"); /* the colour stays */
    assert_gp(d, 1, 0, "bcd");
    static const double load[] = {1.125, 2.125};
    assert_loads(d, load);
    assert_true(wl_pphigs_dist_move(d, 0, 2, 0));
    assert_gp(d, 0, 0, "abc"); /* the colour comes along */
    assert_gp(d, 1, 0, "bd");
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(d);
    assert_int_equal(t->elements_removed, 2);
    assert_int_equal(t->elements_sent, 5 + 2);
    wl_pphigs_dist_free(d);
    /* a GP lacking the colour gets it with the triangle: t t C t deals
     * a and d (with c) to GP 0, b to GP 1; d moved to GP 1 takes c */
    d = dist1("ttCt", 2, WL_PPHIGS_COMPLEX, &W);
    assert_gp(d, 0, 0, "acd");
    assert_gp(d, 1, 0, "b");
    assert_true(wl_pphigs_dist_move(d, 0, 3, 1));
    assert_gp(d, 0, 0, "ac");
    assert_gp(d, 1, 0, "bcd");
    assert_int_equal(wl_pphigs_dist_traffic(d)->last_scan, 3);
    wl_pphigs_dist_free(d);
}

/* ---- §2.3.2 strip splitting ------------------------------------------ */

/* Two strips of 10 vertices (8 triangles) in a row and one of 6, split
 * at 4 triangles: 2 + 2 + 1 pieces, none of more than 6 vertices. */
static void test_strip_pieces(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "strips");
    Vec3 v[10];
    for (int i = 0; i < 10; i++)
        v[i] = vec3(i / 2, i % 2, 0);
    static const guint nv[] = {10, 10, 6, 7};
    for (guint k = 0; k < 4; k++) {
        SceneElem e = scene_elem_prim(SCENE_EL_TRISTRIP, v, nv[k]);
        assert_true(scene_db_append(db, s, &e, NULL));
    }
    scene_db_post(db, s);
    WlPphigsWeights w = W;
    static const guint split[] = {4, 3}; /* 3 rounds up to 4 */
    for (guint t = 0; t < 2; t++) {
        w.strip_split = split[t];
        WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
        const SceneDb *h = wl_pphigs_dist_host(d);
        static const guint want[] = {6, 6, 6, 6, 6, 6, 3};
        assert_int_equal(scene_db_len(h, s), 7);
        for (guint i = 0; i < 7; i++)
            assert_int_equal(scene_db_elem(h, s, i)->nverts, want[i]);
        /* the pieces overlap by two vertices: the second starts at v[4] */
        assert_true(scene_db_elem(h, s, 1)->verts[0].x == 2);
        assert_true(scene_db_elem(h, s, 6)->verts[0].x == 2);
        wl_pphigs_dist_free(d);
    }
    scene_db_free(db);
}

/* ---- §3.4 the attribute-state cache ---------------------------------- */

/* Colour before every 3 triangles: C t t t C t t t ... (n elements). */
static SceneDb *ctt_db(guint n)
{
    char *list = g_malloc(n + 1);
    for (guint i = 0; i < n; i++)
        list[i] = i % 4 ? 't' : 'C';
    list[n] = 0;
    const char *const lists[] = {list, NULL};
    SceneDb *db = spell_db(lists);
    g_free(list);
    return db;
}

/* With a checkpoint after every 2nd triangle (C t t | t C t | t | C t
 * t | ..., checkpoints before 3, 6, 8, 11, 14, 16 ...) a scan back from
 * an insert stops at the nearest one behind it; without the cache it
 * runs back until each of the 8 GPs is known current. */
static void test_cache_checkpoints(void **st)
{
    (void)st;
    SceneDb *db = ctt_db(64);
    WlPphigsWeights w = W;
    w.attr_cache = 2;
    /* insert at: 40, 41, 42, 43, 44, 45, 46, 47; checkpoint at or
     * behind: 40, 40, 40, 43, 43, 43, 46, 46 */
    static const guint scan[] = {0, 1, 2, 0, 1, 2, 0, 1};
    for (guint k = 0; k < 8; k++) {
        WlPphigsDist *d = wl_pphigs_dist_new(db, 8, WL_PPHIGS_COMPLEX, &w);
        assert_int_equal(wl_pphigs_dist_traffic(d)->cache_walk, 64);
        Vec3 v[3];
        SceneElem e = spell_elem('t', v);
        assert_true(wl_pphigs_dist_insert(d, 0, 40 + k, &e, NULL));
        wl_pphigs_dist_finish(d);
        assert_int_equal(wl_pphigs_dist_traffic(d)->last_scan, scan[k]);
        assert_int_equal(wl_pphigs_dist_traffic(d)->cache_walk, 64);
        wl_pphigs_dist_free(d);
    }
    w.attr_cache = 0;
    WlPphigsDist *d = wl_pphigs_dist_new(db, 8, WL_PPHIGS_COMPLEX, &w);
    assert_int_equal(wl_pphigs_dist_traffic(d)->cache_walk, 0);
    Vec3 v[3];
    SceneElem e = spell_elem('t', v);
    assert_true(wl_pphigs_dist_insert(d, 0, 43, &e, NULL));
    wl_pphigs_dist_finish(d);
    /* 42 .. 33: 8 triangles dealt in turn to the 8 GPs (c = 1), and
     * the colours at 40 and 36 */
    assert_int_equal(wl_pphigs_dist_traffic(d)->last_scan, 10);
    assert_int_equal(wl_pphigs_dist_traffic(d)->max_scan, 10);
    assert_int_equal(wl_pphigs_dist_traffic(d)->total_scan, 10);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* The GPs holding a copy of host element (sid, pos). */
static guint holders(const WlPphigsDist *d, guint sid, guint pos)
{
    uint64_t tag = scene_db_elem(wl_pphigs_dist_host(d), sid, pos)->tag;
    guint n = 0;
    for (guint g = 0; g < wl_pphigs_dist_ngp(d); g++) {
        const SceneDb *p = wl_pphigs_dist_gp(d, g);
        for (guint i = 0; i < scene_db_len(p, sid); i++)
            n += scene_db_elem(p, sid, i)->tag == tag;
    }
    return n;
}

/* A triangle inserted at 40, before the colour there: the checkpoints
 * after it move on by one and so does the colour their state names
 * (now at 41).  A triangle inserted at 45 then scans back to the moved
 * checkpoint (44) and takes the colour at 41 to its GP, not the
 * triangle at 40, which stays on its one GP. */
static void test_cache_shift(void **st)
{
    (void)st;
    SceneDb *db = ctt_db(64);
    WlPphigsWeights w = W;
    w.attr_cache = 2;
    WlPphigsDist *d = wl_pphigs_dist_new(db, 8, WL_PPHIGS_COMPLEX, &w);
    Vec3 v[3];
    SceneElem e = spell_elem('t', v);
    assert_true(wl_pphigs_dist_insert(d, 0, 40, &e, NULL));
    wl_pphigs_dist_finish(d);
    assert_true(wl_pphigs_dist_insert(d, 0, 45, &e, NULL));
    wl_pphigs_dist_finish(d);
    assert_int_equal(wl_pphigs_dist_traffic(d)->last_scan, 1);
    assert_int_equal(holders(d, 0, 40), 1);
    assert_int_equal(holders(d, 0, 45), 1);
    gint g = wl_pphigs_dist_owner(d, 0, 45);
    assert_true(g >= 0);
    const SceneDb *p = wl_pphigs_dist_gp(d, (guint)g);
    uint64_t colour = scene_db_elem(wl_pphigs_dist_host(d), 0, 41)->tag;
    gboolean has = FALSE;
    for (guint i = 0; i < scene_db_len(p, 0); i++)
        has = has || scene_db_elem(p, 0, i)->tag == colour;
    assert_true(has);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* Deleting the colour at 40, where a checkpoint sits (the state before
 * 40 does not change), keeps that checkpoint: the scan back from 40
 * stops there at once and the cache walks nothing more; the
 * checkpoints after 40 are dropped, so an insert at 49 makes the cache
 * walk on from 40 to 49 (t t t C t t t C t, the old 41 .. 49) placing
 * checkpoints at 42, 45 and 47, where the scan back from 49 stops
 * after 48 and 47. */
static void test_cache_truncate(void **st)
{
    (void)st;
    SceneDb *db = ctt_db(64);
    WlPphigsWeights w = W;
    w.attr_cache = 2;
    WlPphigsDist *d = wl_pphigs_dist_new(db, 8, WL_PPHIGS_COMPLEX, &w);
    wl_pphigs_dist_delete(d, 0, 40);
    wl_pphigs_dist_finish(d);
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(d);
    assert_int_equal(t->last_scan, 0);
    assert_int_equal(t->cache_walk, 64);
    Vec3 v[3];
    SceneElem e = spell_elem('t', v);
    assert_true(wl_pphigs_dist_insert(d, 0, 49, &e, NULL));
    wl_pphigs_dist_finish(d);
    assert_int_equal(t->cache_walk, 64 + 9);
    assert_int_equal(t->last_scan, 2);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* ---- §5 rebalancing ---------------------------------------------------- */

static const WlPphigsCosts RC = {.poly = 600 * SIM_NS,
                                 .vertex = 100 * SIM_NS,
                                 .reject_vertex = 75 * SIM_NS,
                                 .color = 100 * SIM_NS,
                                 .matrix = 300 * SIM_NS,
                                 .concat = SIM_US,
                                 .execute = 500 * SIM_NS};

/* The analytic table rows deal the list as it is: one 40-triangle
 * strip stays whole on one of 4 GPs (strips are split only where the
 * frame setup asks), so each algorithm's utilisation is exactly 1/4. */
static void test_analytic_unsplit(void **st)
{
    (void)st;
    ScenePphigsDb db = {scene_db_new(), {0}};
    guint s = scene_db_add_struct(db.db, "strip");
    Vec3 v[42];
    for (int i = 0; i < 42; i++)
        v[i] = vec3(i / 2, i % 2, 0);
    SceneElem e = scene_elem_prim(SCENE_EL_TRISTRIP, v, 42);
    assert_true(scene_db_append(db.db, s, &e, NULL));
    scene_db_post(db.db, s);
    db.camera = scene_pphigs_fit_view(db.db);
    WlPphigsMetrics simple, complex;
    pphigs_rig_analytic(&db, 4, &RC, 8, &simple, &complex);
    assert_true(simple.utilisation == 0.25 && complex.utilisation == 0.25);
    assert_true(simple.efficiency == 1 && complex.efficiency == 1);
    scene_db_free(db.db);
}

/* One acting frame (frames = 1) with the given made-up GP times. */
static WlPphigsRebalStep rebal_once(WlPphigsDist *d, double fraction,
                                    guint max_moves, const double *us)
{
    WlPphigsRebalParams p = {.threshold = 0.1,
                             .frames = 1,
                             .fraction = fraction,
                             .max_moves = max_moves,
                             .seed = 3};
    WlPphigsRebal *rb = wl_pphigs_rebal_new(&p);
    WlPphigsRebalStep st;
    wl_pphigs_rebal_frame(rb, d, mat4_identity(), &RC, us, &st);
    wl_pphigs_rebal_free(rb);
    return st;
}

/* The list, all on GP 0 of 2 (a cluster large enough for all);
 * weights w, or (NULL) RC's: a triangle 0.9 us on screen, 0.225 off. */
static WlPphigsDist *piled(const char *list, const WlPphigsWeights *w0)
{
    WlPphigsWeights w;
    if (w0)
        w = *w0;
    else
        wl_pphigs_weights_from_costs(&RC, 1, &w);
    w.cluster = 100;
    WlPphigsDist *d = dist1(list, 2, WL_PPHIGS_COMPLEX, &w);
    assert_int_equal(scene_db_len(wl_pphigs_dist_gp(d, 1), 0), 0);
    return d;
}

/* §5.1: nine unit triangles on GP 0: a triangle moves while it is
 * lighter than the gap (9-0, 8-1, 7-2, 6-3; at 5-4 the gap is 1, no
 * longer lighter): 4 moves with an ample budget; the budget (fraction
 * of max - mean of the measured times) stops it after it is spent; the
 * cap stops it at max_moves. */
static void test_imperfect_exact(void **st)
{
    (void)st;
    static const double us[] = {9, 0};
    static const struct {
        double fraction;
        guint cap, moves;
    } c[] = {{4, 100, 4}, {1, 100, 4}, {0.5, 100, 3}, {0.25, 100, 2},
             {1e-9, 100, 1}, {4, 3, 3}, {4, 1, 1}};
    for (guint k = 0; k < G_N_ELEMENTS(c); k++) {
        WlPphigsDist *d = piled("ttttttttt", &W);
        WlPphigsRebalStep s = rebal_once(d, c[k].fraction, c[k].cap, us);
        assert_int_equal(s.cause, WL_PPHIGS_REBAL_IMPERFECT);
        assert_true(s.imbalance == 0.5); /* (9 - 4.5) / 9 */
        assert_true(s.nominal_imbalance == 0.5);
        assert_int_equal(s.over, 1);
        assert_int_equal(s.moves, c[k].moves);
        assert_int_equal(s.total_moves, c[k].moves);
        assert_int_equal(scene_db_len(wl_pphigs_dist_gp(d, 1), 0), c[k].moves);
        double load[2];
        wl_pphigs_dist_loads(d, load);
        assert_true(load[0] == 9 - c[k].moves && load[1] == c[k].moves);
        wl_pphigs_dist_free(d);
    }
}

/* §5.1 on 3 GPs: the move goes from the first of tied most-loaded GPs
 * to the first of tied least-loaded ones; a budget of exactly 2 moves
 * (fraction 0.5 of max - mean = 4) stops after 2. */
static void test_imperfect_ties(void **st)
{
    (void)st;
    WlPphigsWeights w = W;
    w.cluster = 100;
    static const double us3[] = {5, 5, 0}, us0[] = {9, 0, 0}, us8[] = {8, 0};
    for (int k = 0; k < 2; k++) { /* GP 0 holds 10, GP 1 5 of them */
        WlPphigsDist *d = dist1("tttttttttt", 3, WL_PPHIGS_COMPLEX, &w);
        for (guint i = 0; i < (k ? 0u : 5u); i++)
            assert_true(wl_pphigs_dist_move(d, 0, i, 1));
        WlPphigsRebalStep s = rebal_once(d, 1, 1, k ? us0 : us3);
        assert_int_equal(s.moves, 1);
        double load[3];
        wl_pphigs_dist_loads(d, load);
        assert_true(load[0] == (k ? 9 : 4) && load[1] == (k ? 1 : 5) &&
                    load[2] == (k ? 0 : 1));
        wl_pphigs_dist_free(d);
    }
    WlPphigsDist *d = piled("ttttttttt", &W);
    WlPphigsRebalStep s = rebal_once(d, 0.5, 100, us8);
    assert_int_equal(s.moves, 2);
    wl_pphigs_dist_free(d);
}

/* §5.2: four on-screen triangles on GP 0, four off-screen ones on GP 1
 * (nominal loads even): each exchange swaps one of each (2 moves); the
 * cap counts moves, so 3 allows one exchange, 4 two; with an ample
 * budget and cap all four pairs go (8 moves) and then none is left. */
static void test_invalidated_exact(void **st)
{
    (void)st;
    static const double us[] = {10, 0};
    static const struct {
        double fraction;
        guint cap, moves;
    } c[] = {{1, 100, 8}, {1, 3, 2}, {1, 4, 4}, {1, 2, 2},
             {1, 1, 0}, {1e-9, 100, 2}, {0.1, 100, 2}, {0.15, 100, 4}};
    for (guint k = 0; k < G_N_ELEMENTS(c); k++) {
        WlPphigsDist *d = piled("ttttoooo", NULL);
        for (guint i = 4; i < 8; i++)
            assert_true(wl_pphigs_dist_move(d, 0, i, 1));
        WlPphigsRebalStep s = rebal_once(d, c[k].fraction, c[k].cap, us);
        assert_int_equal(s.cause, WL_PPHIGS_REBAL_INVALIDATED);
        assert_true(s.nominal_imbalance == 0);
        assert_int_equal(s.moves, c[k].moves);
        guint on0 = 0; /* on-screen triangles left on GP 0 */
        for (guint i = 0; i < 4; i++)
            on0 += wl_pphigs_dist_owner(d, 0, i) == 0;
        assert_int_equal(on0, 4 - c[k].moves / 2);
        wl_pphigs_dist_free(d);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_simple_deal),
        cmocka_unit_test(test_complex_clusters),
        cmocka_unit_test(test_concat_to_every_gp),
        cmocka_unit_test(test_weights),
        cmocka_unit_test(test_by_structure_exact),
        cmocka_unit_test(test_by_structure_bounds),
        cmocka_unit_test(test_edits_exact),
        cmocka_unit_test(test_move_exact),
        cmocka_unit_test(test_colour_insert_delete),
        cmocka_unit_test(test_odp_deltas),
        cmocka_unit_test(test_strip_pieces),
        cmocka_unit_test(test_analytic_unsplit),
        cmocka_unit_test(test_cache_checkpoints),
        cmocka_unit_test(test_cache_truncate),
        cmocka_unit_test(test_cache_shift),
        cmocka_unit_test(test_imperfect_exact),
        cmocka_unit_test(test_imperfect_ties),
        cmocka_unit_test(test_invalidated_exact),
    };
    return cmocka_run_group_tests_name("pphigs_exact", tests, NULL, NULL);
}
