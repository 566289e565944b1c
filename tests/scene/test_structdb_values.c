/* test_structdb_values.c — sim/scene/structdb.c field by field where
 * test_structdb.c checks behaviour: the element constructors' every
 * field, a copy's flags and deltas, duplicate names (the first wins), the
 * box cache invalidated by every kind of edit, boxes under a projective
 * matrix and under matrices inside a structure, chunk boxes, primitives
 * without area left out of a flattened mesh, every field of a traversed
 * primitive instance and of the max-set nodes, and the statistics of a
 * shared sub-structure. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/structdb.h"
#include "tests/support.h"

#define EQ(a, b) assert_true(fabs((a) - (b)) < 1e-12)

static void add(SceneDb *db, guint sid, SceneElem e)
{
    GError *err = NULL;
    if (!scene_db_append(db, sid, &e, &err))
        fail_msg("%s", err->message);
}

static void add_tri(SceneDb *db, guint sid, double x)
{
    Vec3 v[3] = {vec3(x, 0, 0), vec3(x + 1, 0, 0), vec3(x, 1, 0)};
    add(db, sid, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
}

static void test_constructors(void **st)
{
    (void)st;
    Vec3 v[2] = {vec3(1, 2, 3), vec3(4, 5, 6)};
    for (SceneElemKind k = 0; k <= SCENE_EL_SPHERE; k++) {
        SceneElem e = scene_elem_prim(k, v, 2);
        assert_int_equal(e.kind, k);
        assert_ptr_equal(e.verts, v);
        assert_int_equal(e.nverts, 2);
        assert_true(e.tag == 0 && e.child == 0);
        /* only an order-dependent primitive advances the priority */
        assert_true(e.delta == (k == SCENE_EL_POLYGON2D));
        assert_true(scene_elem_is_prim(k) && !scene_elem_is_attr(k));
    }
    SceneElem c = scene_elem_color(vec3(0.25, 0.5, 0.75));
    assert_int_equal(c.kind, SCENE_EL_COLOR);
    assert_true(c.color.x == 0.25 && c.color.y == 0.5 && c.color.z == 0.75);
    assert_true(c.delta == 0 && c.nverts == 0 && c.verts == NULL);
    Mat4 id = mat4_identity();
    assert_memory_equal(&c.matrix, &id, sizeof id);
    SceneElem m = scene_elem_matrix(mat4_translate(1, 2, 3), SCENE_MAT_CONCAT);
    assert_int_equal(m.kind, SCENE_EL_MATRIX);
    assert_int_equal(m.mode, SCENE_MAT_CONCAT);
    assert_true(m.matrix.m[0][3] == 1 && m.matrix.m[2][3] == 3 &&
                m.delta == 0);
    SceneElem x = scene_elem_execute(5);
    assert_int_equal(x.kind, SCENE_EL_EXECUTE);
    assert_int_equal(x.child, 5);
    assert_true(x.delta == 0 && x.nverts == 0);
    assert_true(scene_elem_is_attr(SCENE_EL_COLOR) &&
                scene_elem_is_attr(SCENE_EL_MATRIX));
    assert_false(scene_elem_is_attr(SCENE_EL_EXECUTE));
    assert_false(scene_elem_is_prim(SCENE_EL_COLOR) ||
                 scene_elem_is_prim(SCENE_EL_MATRIX) ||
                 scene_elem_is_prim(SCENE_EL_EXECUTE));
    const char *names[SCENE_EL_NKINDS] = {
        "triangle", "polygon", "tristrip", "polygon2d",  "line",
        "sphere",   "color",   "matrix",   "execute",    "line_color",
        "sphere_color"};
    /* a colour per primitive type (PHIGS; seed 001 §2.3.1) */
    assert_true(scene_elem_is_attr(SCENE_EL_LINE_COLOR) &&
                scene_elem_is_attr(SCENE_EL_SPHERE_COLOR));
    assert_int_equal(scene_elem_color_of(SCENE_EL_LINE), SCENE_EL_LINE_COLOR);
    assert_int_equal(scene_elem_color_of(SCENE_EL_SPHERE),
                     SCENE_EL_SPHERE_COLOR);
    assert_int_equal(scene_elem_color_of(SCENE_EL_TRISTRIP), SCENE_EL_COLOR);
    SceneElem lc = scene_elem_kind_color(SCENE_EL_LINE_COLOR, vec3(1, 0, 0));
    assert_true(lc.kind == SCENE_EL_LINE_COLOR && lc.color.x == 1);
    for (SceneElemKind k = 0; k < SCENE_EL_NKINDS; k++)
        assert_string_equal(scene_elem_kind_name(k), names[k]);
}

/* A copy keeps names, flags, deltas, elements (their own vertices) and
 * the posted list; duplicate names resolve to the first structure. */
static void test_copy_and_names(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint a = scene_db_add_struct(db, "a"), b = scene_db_add_struct(db, "b");
    guint a2 = scene_db_add_struct(db, "a");
    assert_int_equal(a2, 2);
    guint f = 99;
    assert_true(scene_db_find(db, "a", &f));
    assert_int_equal(f, a);
    assert_true(scene_db_find(db, "b", &f));
    assert_int_equal(f, b);
    assert_false(scene_db_find(db, "c", &f));
    assert_int_equal(f, b);
    add_tri(db, b, 3);
    add(db, a, scene_elem_execute(b));
    scene_db_set_primitive(db, b, TRUE);
    scene_db_set_end_delta(db, b, 4);
    scene_db_set_delta(db, b, 0, 2);
    scene_db_post(db, a2);
    scene_db_post(db, a);
    SceneDb *c = scene_db_copy(db);
    assert_int_equal(scene_db_struct_count(c), 3);
    assert_true(scene_db_is_primitive(c, b) && !scene_db_is_primitive(c, a));
    assert_true(scene_db_end_delta(c, b) == 4 && scene_db_end_delta(c, a) == 0);
    const SceneElem *e = scene_db_elem(c, b, 0);
    assert_true(e->delta == 2 && e->nverts == 3 && e->verts[1].x == 4);
    assert_ptr_not_equal(e->verts, scene_db_elem(db, b, 0)->verts);
    assert_null(scene_db_elem(c, a, 0)->verts);
    assert_int_equal(scene_db_posted_count(c), 2);
    assert_int_equal(scene_db_posted_at(c, 0), a2);
    assert_int_equal(scene_db_posted_at(c, 1), a);
    assert_string_equal(scene_db_struct_name(c, a2), "a");
    /* the copy's boxes are computed, not taken from its blank cache */
    SceneBox bo = scene_db_struct_bbox(db, a), bc = scene_db_struct_bbox(c, a);
    assert_memory_equal(&bo, &bc, sizeof bo);
    assert_true(bc.min.x == 3 && bc.max.x == 4 && bc.max.y == 1);
    scene_db_free(c);
    scene_db_free(db);
}

/* Every edit -- append, insert, modify, delete -- invalidates the cached
 * boxes of the structure and of those executing it. */
static void test_box_cache(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint top = scene_db_add_struct(db, "top"), leaf = scene_db_add_struct(db, "leaf");
    add(db, top, scene_elem_matrix(mat4_translate(0, 10, 0), SCENE_MAT_REPLACE));
    add(db, top, scene_elem_execute(leaf));
    add_tri(db, leaf, 0);
    EQ(scene_db_struct_bbox(db, top).max.x, 1);
    EQ(scene_db_struct_bbox(db, top).min.y, 10);
    add_tri(db, leaf, 5); /* append */
    EQ(scene_db_struct_bbox(db, top).max.x, 6);
    Vec3 v[3] = {vec3(-7, 0, 0), vec3(0, 0, 0), vec3(0, 1, 0)};
    SceneElem t = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    assert_true(scene_db_insert(db, leaf, 0, &t, NULL)); /* insert */
    EQ(scene_db_struct_bbox(db, top).min.x, -7);
    scene_db_delete(db, leaf, 0); /* delete */
    EQ(scene_db_struct_bbox(db, top).min.x, 0);
    v[0] = vec3(0, 0, -3);
    t = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    assert_true(scene_db_modify(db, leaf, 1, &t, NULL)); /* modify */
    SceneBox b = scene_db_struct_bbox(db, top);
    EQ(b.min.z, -3);
    EQ(b.max.x, 1);
    EQ(b.max.y, 11);
    scene_db_free(db);
}

/* Boxes of points under a projective matrix are divided by w; a matrix
 * inside a structure applies to the primitives after it (REPLACE drops
 * the earlier one, CONCAT composes). */
static void test_box_matrices(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "s");
    Mat4 half = mat4_identity();
    half.m[3][3] = 2; /* w = 2: every point halved */
    add(db, s, scene_elem_matrix(half, SCENE_MAT_REPLACE));
    add_tri(db, s, 4); /* x 4..5 -> 2..2.5, y 0..1 -> 0..0.5 */
    SceneBox b = scene_db_struct_bbox(db, s);
    EQ(b.min.x, 2);
    EQ(b.max.x, 2.5);
    EQ(b.max.y, 0.5);
    add(db, s, scene_elem_matrix(mat4_translate(0, 0, 3), SCENE_MAT_REPLACE));
    add(db, s, scene_elem_matrix(mat4_translate(1, 0, 0), SCENE_MAT_CONCAT));
    add_tri(db, s, 0); /* at x 1..2, z 3 */
    b = scene_db_struct_bbox(db, s);
    EQ(b.min.x, 1);
    EQ(b.max.x, 2.5);
    EQ(b.max.z, 3);
    EQ(b.min.z, 0);
    EQ(b.max.y, 1);
    /* a point sent to w = 0 (infinity) is taken as it is (w read as 1) */
    SceneDb *inf = scene_db_new();
    guint si = scene_db_add_struct(inf, "inf");
    Mat4 wx = mat4_identity();
    wx.m[3][3] = 0;
    wx.m[3][0] = 1; /* w = x */
    add(inf, si, scene_elem_matrix(wx, SCENE_MAT_REPLACE));
    Vec3 q[3] = {vec3(0, 5, 6), vec3(2, 4, 0), vec3(4, 0, 8)};
    add(inf, si, scene_elem_prim(SCENE_EL_TRIANGLE, q, 3));
    b = scene_db_struct_bbox(inf, si); /* (0 5 6); (1 2 0); (1 0 2) */
    assert_true(b.min.x == 0 && b.max.x == 1 && b.min.y == 0 &&
                b.max.y == 5 && b.min.z == 0 && b.max.z == 6);
    scene_db_free(inf);
    /* chunks of 1: each primitive under its own matrix */
    GArray *c = scene_db_chunk_bboxes(db, s, 1);
    assert_int_equal(c->len, 2);
    EQ(g_array_index(c, SceneBox, 0).max.x, 2.5);
    EQ(g_array_index(c, SceneBox, 1).min.x, 1);
    EQ(g_array_index(c, SceneBox, 1).min.z, 3);
    g_array_unref(c);
    /* one chunk of everything; exactly full chunks leave no empty tail */
    c = scene_db_chunk_bboxes(db, s, 2);
    assert_int_equal(c->len, 1);
    EQ(g_array_index(c, SceneBox, 0).min.x, 1);
    EQ(g_array_index(c, SceneBox, 0).max.x, 2.5);
    g_array_unref(c);
    c = scene_db_chunk_bboxes(db, s, 3);
    assert_int_equal(c->len, 1);
    g_array_unref(c);
    scene_db_free(db);
}

typedef struct {
    GArray *inst;
} Rec;

static void rec_fn(const ScenePrimInst *pi, void *ud)
{
    Rec *r = ud;
    g_array_append_val(r->inst, *pi);
}

/* root: [tri, exec mid, odp]; mid: [green, exec leaf, tri]; leaf: [odp,
 * strip of 2 vertices, polygon]; every field of every instance. */
static void test_instances(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    guint mid = scene_db_add_struct(db, "mid");
    guint leaf = scene_db_add_struct(db, "leaf");
    Vec3 v[4] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(0, 1, 0)};
    add(db, root, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    add(db, root, scene_elem_execute(mid));
    add(db, root, scene_elem_prim(SCENE_EL_POLYGON2D, v, 3));
    add(db, mid, scene_elem_color(vec3(0, 1, 0)));
    add(db, mid, scene_elem_matrix(mat4_translate(2, 0, 0), SCENE_MAT_CONCAT));
    add(db, mid, scene_elem_execute(leaf));
    add(db, mid, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    add(db, leaf, scene_elem_prim(SCENE_EL_POLYGON2D, v, 3));
    add(db, leaf, scene_elem_prim(SCENE_EL_TRISTRIP, v, 2));
    add(db, leaf, scene_elem_prim(SCENE_EL_POLYGON, v, 4));
    scene_db_set_end_delta(db, leaf, 10);
    scene_db_post(db, root);
    Rec r = {g_array_new(FALSE, FALSE, sizeof(ScenePrimInst))};
    scene_db_traverse(db, rec_fn, &r);
    assert_int_equal(r.inst->len, 6);
    const ScenePrimInst *p = (const ScenePrimInst *)r.inst->data;
    const guint sid[6] = {root, leaf, leaf, leaf, mid, root};
    const guint pos[6] = {0, 0, 1, 2, 3, 2};
    const guint depth[6] = {1, 3, 3, 3, 2, 1};
    const guint inst[6] = {0, 2, 2, 2, 1, 0};
    const int64_t prio[6] = {0, 1, 1, 1, 11, 12};
    const double x0[6] = {0, 2, 2, 2, 2, 0};
    const double green[6] = {1, 1, 1, 1, 1, 1}, red[6] = {1, 0, 0, 0, 0, 1};
    for (guint i = 0; i < 6; i++) {
        assert_int_equal(p[i].sid, sid[i]);
        assert_int_equal(p[i].pos, pos[i]);
        assert_ptr_equal(p[i].el, scene_db_elem(db, sid[i], pos[i]));
        assert_int_equal(p[i].depth, depth[i]);
        assert_int_equal(p[i].instance, inst[i]);
        assert_true(p[i].priority == prio[i]);
        Vec4 o = mat4_apply_point(p[i].matrix, vec3(0, 0, 0));
        EQ(o.x, x0[i]);
        EQ(p[i].color.y, green[i]);
        EQ(p[i].color.x, red[i]);
    }
    /* the flattened mesh: the 2-vertex strip has no area and is left out */
    SceneMesh *m = scene_db_flatten(db);
    assert_int_equal(scene_mesh_n_polys(m), 5);
    assert_int_equal(scene_mesh_n_vertices(m), 3 + 3 + 4 + 3 + 3);
    assert_int_equal(scene_mesh_poly_len(m, 2), 4);
    for (guint i = 0, base = 0; i < 5; i++) /* each on its own vertices */
        for (guint k = 0; k < scene_mesh_poly_len(m, i); k++, base++)
            assert_int_equal(scene_mesh_poly(m, i)[k], base);
    assert_int_equal(g_array_index(m->poly_tag, uint32_t, 2), leaf);
    Vec3 q = scene_mesh_vertex(m, scene_mesh_poly(m, 2)[2]);
    assert_true(q.x == 3 && q.y == 1 && q.z == 0);
    scene_mesh_free(m);
    /* from mid, under a matrix, a colour and a priority given */
    g_array_set_size(r.inst, 0);
    int64_t pr = 100;
    scene_db_traverse_from(db, mid, mat4_translate(0, 5, 0), vec3(0, 0, 1),
                           &pr, rec_fn, &r);
    assert_int_equal(r.inst->len, 4);
    p = (const ScenePrimInst *)r.inst->data;
    assert_int_equal(p[0].depth, 2);
    assert_int_equal(p[0].instance, 1);
    assert_true(p[0].priority == 101);
    assert_int_equal(p[3].depth, 1);
    assert_int_equal(p[3].instance, 0);
    assert_true(p[3].priority == 111);
    EQ(mat4_apply_point(p[3].matrix, vec3(0, 0, 0)).y, 5);
    EQ(p[3].color.y, 1);
    assert_true(pr == 111);
    g_array_unref(r.inst);
    /* statistics reaching the last structure created (leaf) */
    SceneDbStats ds;
    scene_db_stats(db, &ds);
    assert_true(ds.structures == 3 && ds.depth == 3 && ds.primitives == 6 &&
                ds.min_primitives == 6 && ds.attributes == 2 &&
                ds.executes == 2 && ds.instances == 3);
    /* max-set: root, mid, leaf with parents, depths and entry matrices */
    GArray *mx = scene_db_maxset(db);
    assert_int_equal(mx->len, 3);
    const SceneMaxNode *n = (const SceneMaxNode *)mx->data;
    assert_true(n[0].sid == root && n[0].parent == -1 && n[0].depth == 1);
    assert_true(n[1].sid == mid && n[1].parent == 0 && n[1].depth == 2);
    assert_true(n[2].sid == leaf && n[2].parent == 1 && n[2].depth == 3);
    EQ(mat4_apply_point(n[1].matrix, vec3(0, 0, 0)).x, 0);
    EQ(mat4_apply_point(n[2].matrix, vec3(0, 0, 0)).x, 2);
    g_array_unref(mx);
    scene_db_free(db);
}

/* The cycle check: a path found after a dead end names only the chain
 * (the dead end is dropped), and each structure is searched once, so a
 * 48-level lattice of doubled executes (2^48 paths) is checked at once. */
static void test_cycle_search(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint a = scene_db_add_struct(db, "a"), d = scene_db_add_struct(db, "d");
    guint b = scene_db_add_struct(db, "b"), c = scene_db_add_struct(db, "c");
    guint e = scene_db_add_struct(db, "e");
    add(db, a, scene_elem_execute(d));
    add(db, d, scene_elem_execute(e));
    add(db, a, scene_elem_execute(b));
    add(db, b, scene_elem_execute(c));
    SceneElem x = scene_elem_execute(a);
    GError *err = NULL;
    assert_false(scene_db_append(db, c, &x, &err));
    assert_string_equal(err->message,
                        "found execute of 'a' in 'c' closing the cycle "
                        "c -> a -> b -> c, expected an acyclic structure "
                        "network");
    g_clear_error(&err);
    guint top = scene_db_add_struct(db, "lattice");
    guint prev = top;
    for (int i = 0; i < 48; i++) {
        char name[16];
        g_snprintf(name, sizeof name, "l%d", i);
        guint next = scene_db_add_struct(db, name);
        add(db, prev, scene_elem_execute(next));
        add(db, prev, scene_elem_execute(next));
        prev = next;
    }
    guint root = scene_db_add_struct(db, "root");
    add(db, root, scene_elem_execute(top)); /* searches the whole lattice */
    x = scene_elem_execute(root);
    assert_false(scene_db_append(db, prev, &x, &err)); /* and back up */
    g_clear_error(&err);
    scene_db_free(db);
}

/* A sub-structure executed from two parents: counted once in the min-set
 * (structures, stored primitives), twice in the max-set. */
static void test_stats_shared(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint a = scene_db_add_struct(db, "a"), b = scene_db_add_struct(db, "b");
    guint c = scene_db_add_struct(db, "c");
    scene_db_add_struct(db, "unreached");
    add(db, a, scene_elem_execute(b));
    add(db, a, scene_elem_execute(c));
    add(db, b, scene_elem_execute(c));
    add(db, c, scene_elem_color(vec3(1, 0, 0)));
    add_tri(db, c, 0);
    add_tri(db, c, 1);
    add_tri(db, a, 0);
    scene_db_post(db, a);
    SceneDbStats s;
    scene_db_stats(db, &s);
    assert_int_equal(s.structures, 3);
    assert_int_equal(s.depth, 3);
    assert_true(s.primitives == 5 && s.min_primitives == 3);
    assert_true(s.attributes == 2 && s.executes == 3 && s.instances == 4);
    assert_int_equal(scene_db_height(db, a), 3);
    assert_int_equal(scene_db_height(db, c), 1);
    GArray *k = scene_db_children(db, a);
    assert_int_equal(k->len, 2);
    assert_int_equal(g_array_index(k, guint, 0), b);
    assert_int_equal(g_array_index(k, guint, 1), c);
    g_array_unref(k);
    assert_int_equal(scene_db_execute_count(db, a, c), 1);
    assert_int_equal(scene_db_execute_count(db, b, c), 1); /* its first */
    guint none = scene_db_add_struct(db, "none"); /* no elements at all */
    SceneDb *lone = scene_db_new();
    scene_db_post(lone, scene_db_add_struct(lone, "empty"));
    GArray *mx = scene_db_maxset(lone);
    assert_int_equal(mx->len, 1);
    g_array_unref(mx);
    scene_db_free(lone);
    k = scene_db_children(db, none);
    assert_int_equal(k->len, 0);
    g_array_unref(k);
    assert_int_equal(scene_db_height(db, none), 1);
    assert_int_equal(scene_db_execute_count(db, c, a), 0);
    /* posting a structure twice counts it once; nothing posted: zeros */
    scene_db_post(db, a);
    scene_db_stats(db, &s);
    assert_true(s.instances == 4);
    assert_true(scene_db_unpost(db, a));
    scene_db_stats(db, &s);
    assert_true(s.structures == 0 && s.depth == 0 && s.instances == 0);
    scene_db_free(db);
}

int main(void)
{
    /* a reader that goes on after its error sets a GError over another,
     * and GLib warns: that is a failure here */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_constructors),
        cmocka_unit_test(test_copy_and_names),
        cmocka_unit_test(test_box_cache),
        cmocka_unit_test(test_box_matrices),
        cmocka_unit_test(test_instances),
        cmocka_unit_test(test_cycle_search),
        cmocka_unit_test(test_stats_shared),
    };
    return cmocka_run_group_tests_name("structdb_values", tests, NULL, NULL);
}
