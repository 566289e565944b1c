/* test_pphigs_bystruct.c — distribute-by-structure (§2.1) on small lists
 * worked out by hand: which GP owns each primitive, when an executed
 * structure is dealt whole and when it is broken up (its weight, its
 * subtree's included, against one GP's share), and how near-ties between
 * GP loads are settled (loads within 1e-12 tie; the lowest GP wins).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pphigs/pphigs_distrib.h"
#include <math.h>

/* Triangles weigh 1, polygons 1 - 1e-12 (a load a hair below a
 * triangle's), executes 1, attributes 0; no per-vertex weight. */
static const WlPphigsWeights W = {
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

static void add_prims(SceneDb *db, guint sid, SceneElemKind kind, guint n)
{
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (guint i = 0; i < n; i++)
        add(db, sid, scene_elem_prim(kind, v, 3));
}

static void expect_owners(const WlPphigsDist *d, guint sid, const gint *want,
                          guint n)
{
    assert_int_equal(scene_db_len(wl_pphigs_dist_host(d), sid), n);
    for (guint i = 0; i < n; i++)
        assert_int_equal(wl_pphigs_dist_owner(d, sid, i), want[i]);
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
    add_prims(db, r, SCENE_EL_TRIANGLE, 6);
    add_prims(db, a, SCENE_EL_TRIANGLE, m);
    scene_db_post(db, r);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 4, WL_PPHIGS_BY_STRUCTURE, &W);
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
 * posted) is broken up: its execute to every GP, its triangles dealt to
 * GPs 0, 1; the root's triangles then to 2, 3, 0, 1, 2, 3.  Every GP
 * traverses the execute (weight 1) besides its two triangles. */
static void test_broken_above_share(void **st)
{
    (void)st;
    WlPphigsDist *d = exec_list(2, 1);
    static const gint r_own[] = {-1, 2, 3, 0, 1, 2, 3}, a_own[] = {0, 1};
    expect_owners(d, 0, r_own, 7);
    expect_owners(d, 1, a_own, 2);
    static const double loads[] = {3, 3, 3, 3};
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
    add_prims(db, r, SCENE_EL_TRIANGLE, 1);
    add_prims(db, r, SCENE_EL_POLYGON, 1);
    add_prims(db, r, SCENE_EL_TRIANGLE, 2);
    scene_db_post(db, r);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_BY_STRUCTURE, &W);
    scene_db_free(db);
    static const gint own[] = {0, 1, 0, 1};
    expect_owners(d, 0, own, 4);
    wl_pphigs_dist_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_whole_at_share),
        cmocka_unit_test(test_broken_above_share),
        cmocka_unit_test(test_shared_structure_whole),
        cmocka_unit_test(test_near_tie_lowest_gp),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
