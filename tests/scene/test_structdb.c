/* test_structdb.c — the hierarchical structure database: inherited state,
 * edits, cycles, posting, min-set and max-set views, boxes, priorities.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/structdb.h"
#include <string.h>

#define NEAR(a, b) assert_true(fabs((a) - (b)) < 1e-9)

typedef struct {
    GArray *inst; /* ScenePrimInst copies */
} Rec;

static void rec_fn(const ScenePrimInst *pi, void *ud)
{
    Rec *r = ud;
    g_array_append_val(r->inst, *pi);
}

static GArray *collect(const SceneDb *db)
{
    Rec r = {g_array_new(FALSE, FALSE, sizeof(ScenePrimInst))};
    scene_db_traverse(db, rec_fn, &r);
    return r.inst;
}

static void add_tri(SceneDb *db, guint sid, double x, uint64_t tag)
{
    Vec3 v[3] = {vec3(x, 0, 0), vec3(x + 1, 0, 0), vec3(x, 1, 0)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    e.tag = tag;
    assert_true(scene_db_append(db, sid, &e, NULL));
}

static void add(SceneDb *db, guint sid, SceneElem e)
{
    GError *err = NULL;
    assert_true(scene_db_append(db, sid, &e, &err));
    assert_null(err);
}

static Vec3 xf(Mat4 m, Vec3 p)
{
    Vec4 q = mat4_apply_point(m, p);
    return vec3(q.x, q.y, q.z);
}

/* root: red, T(10), tri#1, exec child, tri#4; child: concat S(2), tri#2,
 * blue, tri#3.  tri#4 must see red and T(10) again. */
static SceneDb *sample(guint *root, guint *child)
{
    SceneDb *db = scene_db_new();
    *root = scene_db_add_struct(db, "root");
    *child = scene_db_add_struct(db, "child");
    add(db, *root, scene_elem_color(vec3(1, 0, 0)));
    add(db, *root,
        scene_elem_matrix(mat4_translate(10, 0, 0), SCENE_MAT_REPLACE));
    add_tri(db, *root, 0, 1);
    add(db, *root, scene_elem_execute(*child));
    add_tri(db, *root, 0, 4);
    add(db, *child, scene_elem_matrix(mat4_scale(2, 2, 2), SCENE_MAT_CONCAT));
    add_tri(db, *child, 0, 2);
    add(db, *child, scene_elem_color(vec3(0, 0, 1)));
    add_tri(db, *child, 0, 3);
    scene_db_post(db, *root);
    return db;
}

static void test_inherited_state(void **st)
{
    (void)st;
    guint root, child;
    SceneDb *db = sample(&root, &child);
    GArray *a = collect(db);
    assert_int_equal(a->len, 4);
    const ScenePrimInst *p = (const ScenePrimInst *)a->data;
    uint64_t tags[4] = {1, 2, 3, 4};
    for (int i = 0; i < 4; i++)
        assert_int_equal(p[i].el->tag, tags[i]);
    NEAR(p[0].color.x, 1);
    NEAR(xf(p[0].matrix, vec3(1, 0, 0)).x, 11);
    /* child: inherited T(10), local S(2): x -> 10 + 2x */
    NEAR(xf(p[1].matrix, vec3(1, 0, 0)).x, 12);
    NEAR(p[1].color.x, 1);
    NEAR(p[2].color.z, 1);
    assert_int_equal(p[1].depth, 2);
    /* back in root: the child's colour and matrix are gone */
    NEAR(p[3].color.x, 1);
    NEAR(p[3].color.z, 0);
    NEAR(xf(p[3].matrix, vec3(1, 0, 0)).x, 11);
    g_array_unref(a);
    scene_db_free(db);
    scene_db_free(NULL);
}

static void test_replace_vs_concat(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "s");
    add(db, s, scene_elem_matrix(mat4_translate(1, 0, 0), SCENE_MAT_REPLACE));
    add(db, s, scene_elem_matrix(mat4_translate(2, 0, 0), SCENE_MAT_CONCAT));
    add_tri(db, s, 0, 1);
    add(db, s, scene_elem_matrix(mat4_translate(5, 0, 0), SCENE_MAT_REPLACE));
    add_tri(db, s, 0, 2);
    scene_db_post(db, s);
    GArray *a = collect(db);
    const ScenePrimInst *p = (const ScenePrimInst *)a->data;
    NEAR(xf(p[0].matrix, vec3(0, 0, 0)).x, 3);
    NEAR(xf(p[1].matrix, vec3(0, 0, 0)).x, 5);
    g_array_unref(a);
    scene_db_free(db);
}

static void test_edits(void **st)
{
    (void)st;
    guint root, child;
    SceneDb *db = sample(&root, &child);
    /* insert a green colour before tri#1 */
    SceneElem g = scene_elem_color(vec3(0, 1, 0));
    assert_true(scene_db_insert(db, root, 2, &g, NULL));
    GArray *a = collect(db);
    NEAR(g_array_index(a, ScenePrimInst, 0).color.y, 1);
    NEAR(g_array_index(a, ScenePrimInst, 3).color.y, 1);
    g_array_unref(a);
    /* modify the translation; a kind change is refused */
    SceneElem m =
        scene_elem_matrix(mat4_translate(20, 0, 0), SCENE_MAT_REPLACE);
    assert_true(scene_db_modify(db, root, 1, &m, NULL));
    GError *err = NULL;
    assert_false(scene_db_modify(db, root, 1, &g, &err));
    assert_non_null(strstr(err->message, "found modify of a matrix"));
    g_clear_error(&err);
    /* delete tri#2 in the child */
    assert_int_equal(scene_db_elem(db, child, 1)->tag, 2);
    scene_db_delete(db, child, 1);
    a = collect(db);
    assert_int_equal(a->len, 3);
    assert_int_equal(g_array_index(a, ScenePrimInst, 1).el->tag, 3);
    NEAR(xf(g_array_index(a, ScenePrimInst, 0).matrix, vec3(0, 0, 0)).x, 20);
    g_array_unref(a);
    scene_db_free(db);
}

static void test_cycles(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint a = scene_db_add_struct(db, "a");
    guint b = scene_db_add_struct(db, "b");
    guint c = scene_db_add_struct(db, "c");
    add(db, a, scene_elem_execute(b));
    add(db, b, scene_elem_execute(c));
    GError *err = NULL;
    SceneElem e = scene_elem_execute(a);
    assert_false(scene_db_append(db, c, &e, &err));
    assert_int_equal(err->code, SIM_ERROR_INPUT);
    assert_non_null(strstr(err->message, "c -> a -> b -> c"));
    assert_non_null(strstr(err->message, "expected an acyclic"));
    g_clear_error(&err);
    e = scene_elem_execute(c);
    assert_false(scene_db_insert(db, c, 0, &e, &err));
    assert_non_null(strstr(err->message, "c -> c"));
    g_clear_error(&err);
    /* modify an execute into a cycle */
    e = scene_elem_execute(a);
    assert_false(scene_db_modify(db, b, 0, &e, &err));
    g_clear_error(&err);
    e = scene_elem_execute(scene_db_struct_count(db)); /* one past the end */
    assert_false(scene_db_append(db, a, &e, &err));
    assert_non_null(strstr(err->message, "unknown structure"));
    g_clear_error(&err);
    e = scene_elem_execute(99);
    assert_false(scene_db_append(db, a, &e, &err));
    assert_non_null(strstr(err->message, "unknown structure"));
    g_clear_error(&err);
    /* a DAG with a shared child is fine */
    e = scene_elem_execute(c);
    assert_true(scene_db_append(db, a, &e, NULL));
    assert_int_equal(scene_db_len(db, c), 0);
    scene_db_free(db);
}

static void test_posting(void **st)
{
    (void)st;
    guint root, child;
    SceneDb *db = sample(&root, &child);
    scene_db_post(db, root);
    assert_int_equal(scene_db_posted_count(db), 1);
    scene_db_post(db, child);
    GArray *a = collect(db);
    assert_int_equal(a->len, 6);
    /* the child posted alone inherits nothing */
    NEAR(g_array_index(a, ScenePrimInst, 4).color.x, 1);
    NEAR(xf(g_array_index(a, ScenePrimInst, 4).matrix, vec3(1, 0, 0)).x, 2);
    g_array_unref(a);
    assert_true(scene_db_unpost(db, root));
    assert_false(scene_db_unpost(db, root));
    assert_false(scene_db_is_posted(db, root));
    a = collect(db);
    assert_int_equal(a->len, 2);
    g_array_unref(a);
    scene_db_free(db);
}

static void test_views(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint top = scene_db_add_struct(db, "top");
    guint arm = scene_db_add_struct(db, "arm");
    guint hand = scene_db_add_struct(db, "hand");
    for (int i = 0; i < 3; i++) {
        add(db, top,
            scene_elem_matrix(mat4_translate(i, 0, 0), SCENE_MAT_REPLACE));
        add(db, top, scene_elem_execute(arm));
    }
    add(db, arm, scene_elem_execute(hand));
    add(db, arm, scene_elem_execute(hand));
    add_tri(db, hand, 0, 7);
    scene_db_post(db, top);
    GArray *kids = scene_db_children(db, top);
    assert_int_equal(kids->len, 1);
    assert_int_equal(scene_db_execute_count(db, top, arm), 3);
    g_array_unref(kids);
    assert_int_equal(scene_db_height(db, top), 3);
    GArray *mx = scene_db_maxset(db);
    assert_int_equal(mx->len, 1 + 3 + 6);
    SceneMaxNode *n = (SceneMaxNode *)mx->data;
    assert_int_equal(n[0].parent, -1);
    assert_int_equal(n[1].sid, arm);
    assert_int_equal(n[2].parent, 1);
    assert_int_equal(n[2].depth, 3);
    NEAR(xf(n[4].matrix, vec3(0, 0, 0)).x, 1);
    /* traversal instance numbers match the max-set nodes */
    GArray *a = collect(db);
    assert_int_equal(a->len, 6);
    for (guint i = 0; i < a->len; i++) {
        const ScenePrimInst *p = &g_array_index(a, ScenePrimInst, i);
        assert_int_equal(n[p->instance].sid, hand);
    }
    g_array_unref(a);
    /* from one root: numbered from 0 like scene_db_maxset() of that root */
    Rec rf = {g_array_new(FALSE, FALSE, sizeof(ScenePrimInst))};
    int64_t pr = 0;
    scene_db_traverse_from(db, arm, mat4_identity(), vec3(1, 1, 1), &pr,
                           rec_fn, &rf);
    assert_int_equal(rf.inst->len, 2);
    assert_int_equal(g_array_index(rf.inst, ScenePrimInst, 0).instance, 1);
    assert_int_equal(g_array_index(rf.inst, ScenePrimInst, 1).instance, 2);
    g_array_unref(rf.inst);
    SceneDbStats s;
    scene_db_stats(db, &s);
    assert_int_equal(s.structures, 3);
    assert_int_equal(s.depth, 3);
    assert_int_equal(s.primitives, 6);
    assert_int_equal(s.min_primitives, 1);
    assert_int_equal(s.attributes, 3);
    assert_int_equal(s.executes, 9);
    assert_int_equal(s.instances, 10);
    g_array_unref(mx);
    scene_db_free(db);
}

static void test_bboxes(void **st)
{
    (void)st;
    guint root, child;
    SceneDb *db = sample(&root, &child);
    SceneBox b = scene_db_struct_bbox(db, child);
    NEAR(b.max.x, 2);
    b = scene_db_struct_bbox(db, root);
    NEAR(b.min.x, 10);
    NEAR(b.max.x, 12);
    SceneElem m =
        scene_elem_matrix(mat4_translate(-5, 0, 0), SCENE_MAT_REPLACE);
    assert_true(scene_db_modify(db, root, 1, &m, NULL));
    b = scene_db_struct_bbox(db, root); /* the cache follows the edit */
    NEAR(b.min.x, -5);
    for (int i = 0; i < 5; i++)
        add_tri(db, child, 10 * i, 100 + i);
    GArray *c = scene_db_chunk_bboxes(db, child, 3);
    assert_int_equal(c->len, 3); /* 7 primitives in chunks of 3 */
    NEAR(g_array_index(c, SceneBox, 0).min.x, 0);
    NEAR(g_array_index(c, SceneBox, 2).max.x, 2 * 41);
    g_array_unref(c);
    scene_db_free(db);
}

static void add_odp(SceneDb *db, guint sid, uint64_t tag)
{
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON2D, v, 3);
    e.tag = tag;
    assert_true(scene_db_append(db, sid, &e, NULL));
}

static void test_priorities(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint a = scene_db_add_struct(db, "a");
    guint b = scene_db_add_struct(db, "b");
    add_odp(db, a, 1);
    add(db, a, scene_elem_execute(b));
    add_odp(db, a, 4);
    add(db, a, scene_elem_execute(b));
    add_odp(db, b, 2);
    add_odp(db, b, 3);
    scene_db_post(db, a);
    GArray *r = collect(db);
    assert_int_equal(r->len, 6);
    for (guint i = 0; i < r->len; i++)
        assert_int_equal(g_array_index(r, ScenePrimInst, i).priority, i + 1);
    g_array_unref(r);
    /* a portion holding only the 2nd ODP of b, with deltas: b = {odp
     * with delta 2, end 0}; a = {exec b, exec b}, each execute with delta
     * 1 (the missing ODPs #1 and #4) */
    SceneDb *p = scene_db_copy(db);
    scene_db_delete(p, a, 2);
    scene_db_delete(p, a, 0);
    scene_db_delete(p, b, 0);
    scene_db_set_delta(p, b, 0, 2);
    scene_db_set_delta(p, a, 0, 1);
    scene_db_set_delta(p, a, 1, 1);
    r = collect(p);
    assert_int_equal(r->len, 2);
    assert_int_equal(g_array_index(r, ScenePrimInst, 0).priority, 3);
    assert_int_equal(g_array_index(r, ScenePrimInst, 1).priority, 6);
    g_array_unref(r);
    int64_t pr = 0;
    scene_db_set_end_delta(p, b, 5);
    assert_true(scene_db_end_delta(p, b) == 5 && scene_db_end_delta(p, a) == 0);
    assert_string_equal(scene_elem_kind_name(SCENE_EL_POLYGON2D), "polygon2d");
    assert_string_equal(scene_elem_kind_name(SCENE_EL_EXECUTE), "execute");
    scene_db_traverse_from(p, b, mat4_identity(), vec3(1, 1, 1), &pr, NULL,
                           NULL);
    assert_int_equal(pr, 7);
    scene_db_free(p);
    scene_db_free(db);
}

/* scene_db_flatten: one polygon per primitive instance, world positions,
 * inherited colours, structure ids as tags, strips as n - 2 triangles
 * of one winding. */
static void test_flatten(void **st)
{
    (void)st;
    guint root, child;
    SceneDb *db = sample(&root, &child);
    Vec3 strip[5] = {vec3(0, 0, 0), vec3(0, 1, 0), vec3(1, 0, 0), vec3(1, 1, 0),
                     vec3(2, 0, 0)};
    add(db, child, scene_elem_prim(SCENE_EL_TRISTRIP, strip, 5));
    SceneMesh *m = scene_db_flatten(db);
    /* tri#1, (child: tri#2, tri#3, strip = 3 triangles), tri#4 */
    assert_int_equal(scene_mesh_n_polys(m), 7);
    Vec3 p0 = scene_mesh_vertex(m, scene_mesh_poly(m, 0)[1]);
    NEAR(p0.x, 11); /* T(10) applied to (1, 0, 0) */
    Vec3 p1 = scene_mesh_vertex(m, scene_mesh_poly(m, 1)[1]);
    NEAR(p1.x, 12); /* T(10) S(2) */
    assert_int_equal(g_array_index(m->poly_tag, uint32_t, 1), child);
    SceneColor c2 = g_array_index(m->poly_color, SceneColor, 2);
    assert_true(c2.b == 1.0f && c2.r == 0.0f);
    SceneColor c6 = g_array_index(m->poly_color, SceneColor, 6);
    assert_true(c6.r == 1.0f && c6.b == 0.0f); /* red again after */
    /* the strip's triangles all face one way (-z: (0,0) (0,1) (1,0) is
     * clockwise seen from +z) */
    for (guint i = 3; i < 6; i++)
        assert_true(scene_mesh_poly_normal(m, i).z < -0.99);
    /* strip triangle k takes strip vertices k, k + 1, k + 2, the first
     * two swapped when k is odd */
    uint32_t b0 = scene_mesh_poly(m, 3)[0];
    const uint32_t want[3][3] = {{0, 1, 2}, {2, 1, 3}, {2, 3, 4}};
    for (guint k = 0; k < 3; k++)
        for (guint j = 0; j < 3; j++)
            assert_int_equal(scene_mesh_poly(m, 3 + k)[j], b0 + want[k][j]);
    scene_mesh_free(m);
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_inherited_state),
        cmocka_unit_test(test_replace_vs_concat),
        cmocka_unit_test(test_edits),
        cmocka_unit_test(test_cycles),
        cmocka_unit_test(test_posting),
        cmocka_unit_test(test_views),
        cmocka_unit_test(test_bboxes),
        cmocka_unit_test(test_priorities),
        cmocka_unit_test(test_flatten),
    };
    return cmocka_run_group_tests_name("structdb", tests, NULL, NULL);
}
