/* test_pphigs_deal.c — the three ways of dealing a display list over
 * the GPs on lists worked out by hand: which GP owns each primitive and
 * what each GP's load is.
 *   simple (§2.2) and complex (§2.3): attributes and ordinary executes
 *   on every GP, the least-loaded choice (this structure's load first,
 *   then the GP's whole load, then the lowest GP; loads a hair apart),
 *   the complex algorithm's clusters of at most c x maxw;
 *   by structure (§2.1): an executed structure dealt whole unless,
 *   instanced once, it weighs more than one GP's share (its subtree's
 *   weight included), then broken up; GP loads within 1e-12 tie and the
 *   lowest GP wins.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/workload/pphigs/pphigs_distrib.h"

/* Simple and complex: triangles weigh 1, polygons 1.5, everything else
 * 0; clusters of 2 x maxw. */
static const WlPphigsWeights W = {
    .w = {[SCENE_EL_TRIANGLE] = 1, [SCENE_EL_POLYGON] = 1.5},
    .w_vertex = 0,
    .cluster = 2,
};

/* By structure: triangles weigh 1, polygons 1 - 1e-12 (a load a hair
 * below a triangle's), executes 1, attributes 0. */
static const WlPphigsWeights WB = {
    .w = {[SCENE_EL_TRIANGLE] = 1,
          [SCENE_EL_POLYGON] = 1 - 1e-12,
          [SCENE_EL_EXECUTE] = 1},
    .w_vertex = 0,
    .cluster = 2,
};

static void add(SceneDb *db, guint sid, SceneElem e)
{
    assert_true(scene_db_append(db, sid, &e, NULL));
}

static void expect_owners(const WlPphigsDist *d, guint sid, const gint *want,
                          guint n)
{
    assert_int_equal(scene_db_len(wl_pphigs_dist_host(d), sid), n);
    for (guint i = 0; i < n; i++)
        if (wl_pphigs_dist_owner(d, sid, i) != want[i])
            fail_msg("element %u of structure %u: GP %d, expected %d", i, sid,
                     wl_pphigs_dist_owner(d, sid, i), want[i]);
}

static void prims(SceneDb *db, guint sid, SceneElemKind kind, guint n)
{
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (guint i = 0; i < n; i++)
        add(db, sid, scene_elem_prim(kind, v, 3));
}

/* root: colour, 2 triangles, execute s1; s1: 4 triangles; 3 GPs.
 * SIMPLE deals one primitive at a time to the least-loaded GP: the
 * root's to 0, 1; s1's structure loads start even, so the GP loads
 * decide: 2 (load 0), then 0, 1 (ties to the lowest), then 2. */
static SceneDb *two_level(void)
{
    SceneDb *db = scene_db_new();
    guint r = scene_db_add_struct(db, "r"), s1 = scene_db_add_struct(db, "s1");
    add(db, r, scene_elem_color(vec3(1, 0, 0)));
    prims(db, r, SCENE_EL_TRIANGLE, 2);
    add(db, r, scene_elem_execute(s1));
    prims(db, s1, SCENE_EL_TRIANGLE, 4);
    scene_db_post(db, r);
    return db;
}

static void test_simple(void **st)
{
    (void)st;
    SceneDb *db = two_level();
    WlPphigsDist *d = wl_pphigs_dist_new(db, 3, WL_PPHIGS_SIMPLE, &W);
    static const gint r[] = {-1, 0, 1, -1}, s1[] = {2, 0, 1, 2};
    expect_owners(d, 0, r, 4);
    expect_owners(d, 1, s1, 4);
    /* attributes and the execute on every GP: each GP's root holds the
     * colour, its triangles and the execute */
    static const guint len[] = {3, 3, 2};
    for (guint g = 0; g < 3; g++)
        assert_int_equal(scene_db_len(wl_pphigs_dist_gp(d, g), 0), len[g]);
    double loads[3];
    wl_pphigs_dist_loads(d, loads);
    assert_true(loads[0] == 2 && loads[1] == 2 && loads[2] == 2);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* COMPLEX: clusters of at most 2 x maxw = 2 weight stay on one GP: the
 * root's 2 triangles on 0; s1's 4 on 1, 1 (even structure loads: the
 * GP loads decide) then 2, 2. */
static void test_complex_clusters(void **st)
{
    (void)st;
    SceneDb *db = two_level();
    WlPphigsDist *d = wl_pphigs_dist_new(db, 3, WL_PPHIGS_COMPLEX, &W);
    static const gint r[] = {-1, 0, 0, -1}, s1[] = {1, 1, 2, 2};
    expect_owners(d, 0, r, 4);
    expect_owners(d, 1, s1, 4);
    wl_pphigs_dist_free(d);
    /* a polygon (1.5) makes maxw 1.5, clusters 3: triangles 1 + 1 + 1
     * fit, the fourth opens a new cluster */
    SceneDb *p = scene_db_new();
    guint s = scene_db_add_struct(p, "s");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    add(p, s, scene_elem_prim(SCENE_EL_POLYGON, v, 3));
    prims(p, s, SCENE_EL_TRIANGLE, 5);
    scene_db_post(p, s);
    d = wl_pphigs_dist_new(p, 2, WL_PPHIGS_COMPLEX, &W);
    /* 1.5 + 1 = 2.5 <= 3 on GP 0, + 1 = 3.5 > 3: GP 1 takes 1, 1, 1 (3),
     * the fifth triangle: back to the lighter GP 0 (2.5 < 3) */
    static const gint own[] = {0, 0, 1, 1, 1, 0};
    expect_owners(d, 0, own, 6);
    wl_pphigs_dist_free(d);
    scene_db_free(p);
    scene_db_free(db);
}

/* Loads a hair apart: a triangle (1) on GP 0, a polygon (1 - 1e-12) on
 * GP 1; GP 1 is lighter by less than the 1e-12 that counts, and by more
 * than the 1e-12 within which loads tie on the GPs' totals, so the next
 * triangle stays on GP 0, the lower GP. */
static void test_near_tie(void **st)
{
    (void)st;
    const WlPphigsWeights w = {
        .w = {[SCENE_EL_TRIANGLE] = 1, [SCENE_EL_POLYGON] = 1 - 1e-12},
        .cluster = 2};
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "s");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    prims(db, s, SCENE_EL_TRIANGLE, 1);
    add(db, s, scene_elem_prim(SCENE_EL_POLYGON, v, 3));
    prims(db, s, SCENE_EL_TRIANGLE, 1);
    scene_db_post(db, s);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_SIMPLE, &w);
    static const gint own[] = {0, 1, 0};
    expect_owners(d, 0, own, 3);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

static void expect_loads(const WlPphigsDist *d, const double *want)
{
    double got[8];
    wl_pphigs_dist_loads(d, got);
    for (guint g = 0; g < wl_pphigs_dist_ngp(d); g++)
        assert_true(fabs(got[g] - want[g]) < 1e-9);
}

/* Root r (posted): execute a, then 6 triangles; a: m triangles; 4 GPs.
 * Weights: subtree(a) = m, the execute 1 + m, the list 7 + m, so a
 * share is (7 + m) / 4. */
static WlPphigsDist *exec_list(guint m, guint a_uses)
{
    SceneDb *db = scene_db_new();
    guint r = scene_db_add_struct(db, "r"), a = scene_db_add_struct(db, "a");
    for (guint u = 0; u < a_uses; u++)
        add(db, r, scene_elem_execute(a));
    prims(db, r, SCENE_EL_TRIANGLE, 6);
    prims(db, a, SCENE_EL_TRIANGLE, m);
    scene_db_post(db, r);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 4, WL_PPHIGS_BY_STRUCTURE, &WB);
    scene_db_free(db);
    assert_int_equal(wl_pphigs_dist_algo(d), WL_PPHIGS_BY_STRUCTURE);
    return d;
}

/* m = 1: the execute weighs 2 = the share (8 / 4), not above it, so a
 * goes whole to GP 0; the triangles then fill GPs 1, 2, 3, 1, 2, 3 (ties
 * to the lowest GP).  Loads 2 each. */
static void test_whole_at_share(void **st)
{
    (void)st;
    WlPphigsDist *d = exec_list(1, 1);
    static const gint r_own[] = {-1, 1, 2, 3, 1, 2, 3}, a_own[] = {0};
    expect_owners(d, 0, r_own, 7);
    expect_owners(d, 1, a_own, 1);
    static const double loads[] = {2, 2, 2, 2};
    expect_loads(d, loads);
    wl_pphigs_dist_free(d);
}

/* m = 2: the execute weighs 3 > 9 / 4, so a (instanced once, not
 * posted) is broken up: its triangles dealt to GPs 0, 1, its execute to
 * those two only (the skeleton: GPs 2 and 3 hold nothing under it); the
 * root's triangles then to 2, 3, 0, 1, 2, 3.  GPs 0 and 1 traverse the
 * execute (weight 1) besides their two triangles. */
static void test_broken_above_share(void **st)
{
    (void)st;
    WlPphigsDist *d = exec_list(2, 1);
    static const gint r_own[] = {-1, 2, 3, 0, 1, 2, 3}, a_own[] = {0, 1};
    expect_owners(d, 0, r_own, 7);
    expect_owners(d, 1, a_own, 2);
    static const double loads[] = {3, 3, 2, 2};
    expect_loads(d, loads);
    wl_pphigs_dist_free(d);
}

/* a (m = 3) executed twice is not broken up although each execute
 * weighs 4 > 14 / 4: each instance goes whole to one GP (GPs 0 and 1),
 * the triangles to 2, 3, 2, 3, 2, 3. */
static void test_shared_structure_whole(void **st)
{
    (void)st;
    WlPphigsDist *d = exec_list(3, 2);
    static const gint r_own[] = {-1, -1, 2, 3, 2, 3, 2, 3};
    expect_owners(d, 0, r_own, 8);
    static const double loads[] = {4, 4, 3, 3};
    expect_loads(d, loads);
    wl_pphigs_dist_free(d);
}

/* Loads within 1e-12 tie and the lowest GP wins: a triangle (1) to GP 0,
 * a polygon (1 - 1e-12) to GP 1, then the next triangle to GP 0 again
 * (GP 1 is lighter by exactly 1e-12, not more), the last to GP 1. */
static void test_near_tie_lowest_gp(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint r = scene_db_add_struct(db, "r");
    prims(db, r, SCENE_EL_TRIANGLE, 1);
    prims(db, r, SCENE_EL_POLYGON, 1);
    prims(db, r, SCENE_EL_TRIANGLE, 2);
    scene_db_post(db, r);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_BY_STRUCTURE, &WB);
    scene_db_free(db);
    static const gint own[] = {0, 1, 0, 1};
    expect_owners(d, 0, own, 4);
    wl_pphigs_dist_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_simple),
        cmocka_unit_test(test_complex_clusters),
        cmocka_unit_test(test_near_tie),
        cmocka_unit_test(test_whole_at_share),
        cmocka_unit_test(test_broken_above_share),
        cmocka_unit_test(test_shared_structure_whole),
        cmocka_unit_test(test_near_tie_lowest_gp),
    };
    return cmocka_run_group_tests_name("pphigs_deal", tests, NULL, NULL);
}
