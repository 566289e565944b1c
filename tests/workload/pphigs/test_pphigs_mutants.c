/* test_pphigs_mutants.c — claims of the PPHIGS workload that mutation
 * testing (make mutate, docs/testing.md) found unchecked: the
 * non-primitive cost sums every colour, matrix and execute element of
 * every instance in the max-set view, the posted root's included. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pphigs/pphigs_metrics.h"

static void add(SceneDb *db, guint sid, SceneElem e)
{
    assert_true(scene_db_append(db, sid, &e, NULL));
}

/* root: colour, replace matrix, triangle, execute child; child: concat
 * matrix, triangle.  Non-primitives: 1 colour, 1 matrix, 1 execute in
 * the root and 1 concat in the child. */
static void test_nonprim_cost(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    guint child = scene_db_add_struct(db, "child");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    add(db, root, scene_elem_color(vec3(1, 0, 0)));
    add(db, root, scene_elem_matrix(mat4_identity(), SCENE_MAT_REPLACE));
    add(db, root, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    add(db, root, scene_elem_execute(child));
    add(db, child, scene_elem_matrix(mat4_identity(), SCENE_MAT_CONCAT));
    add(db, child, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    scene_db_post(db, root);
    WlPphigsCosts c = {.poly = 1000, .vertex = 100, .reject_vertex = 10,
                       .color = 1, .matrix = 20, .concat = 300,
                       .execute = 4000};
    assert_int_equal(wl_pphigs_nonprim_cost(db, &c), 1 + 20 + 4000 + 300);
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nonprim_cost),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
