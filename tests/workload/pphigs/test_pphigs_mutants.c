/* test_pphigs_mutants.c — claims of the PPHIGS workload that mutation
 * testing (make mutate, docs/testing.md) found unchecked: the
 * non-primitive cost sums every colour, matrix and execute element of
 * every instance in the max-set view, the posted root's included; the
 * first element of a distributed list draws on the far plane (its id is
 * at least 1); a polygon's depth plane and shade come from its fan
 * triangle (0, i, i+1) of largest screen area; modify reaches every
 * holder up to the 64th GP; a cut at the near plane lies on its edge,
 * in x, y and z; the pixel box starts from vertex 0; a polygon that
 * clipping takes past the command's edges draws nothing; a modify that
 * changes a matrix's mode is an insert and a delete, one whose insert
 * fails changes nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pphigs/pphigs_distrib.h"
#include "sim/workload/pphigs/pphigs_metrics.h"
#include "sim/workload/pphigs/pphigs_pixels.h"
#include <math.h>

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

/* pphigs_pixels.h: "the inherited colour, flat, times 0.3 + 0.7 |n_z| of
 * the polygon's normal in normalised device coordinates". */
static WlPphigsCmd command(const Vec3 *v)
{
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 3);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 0.5, 0.25), .depth = 1};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 100, 80, out), 1);
    WlPphigsCmd c = g_array_index(out, WlPphigsCmd, 0);
    g_array_free(out, TRUE);
    /* e borrows v (scene_elem_prim does not copy) */
    return c;
}

static uint32_t shaded(const Vec3 *v)
{
    return command(v).rgba;
}

static uint32_t rgba_of(double s)
{
    return 0xff000000u | (uint32_t)lrint(255 * s) |
           (uint32_t)lrint(255 * 0.5 * s) << 8 |
           (uint32_t)lrint(255 * 0.25 * s) << 16;
}

static void test_shading(void **state)
{
    (void)state;
    Vec3 flat[3] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0, 0.5, 0)};
    assert_int_equal(shaded(flat), rgba_of(1)); /* facing the eye: n_z = 1 */
    /* u = (1, 0, 0), v = (0.5, 1, 0.5): n = (0, -0.5, 1), n_z = 1/sqrt 1.25 */
    Vec3 tilt[3] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0, 0.5, 0.5)};
    assert_int_equal(shaded(tilt), rgba_of(0.3 + 0.7 / sqrt(1.25)));
    /* u = (1, 0, 0.5), v = (0.5, 1, 0): n = (-0.5, 0.25, 1) */
    Vec3 tilt2[3] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0.5), vec3(0, 0.5, 0)};
    assert_int_equal(shaded(tilt2), rgba_of(0.3 + 0.7 / sqrt(1.3125)));
}

/* A polygon over the whole screen (and past it) draws from pixel (0, 0)
 * to (width - 1, height - 1): its box is clamped to the screen, not
 * inside it. */
static void test_box_clamped_to_screen(void **state)
{
    (void)state;
    Vec3 big[3] = {vec3(-3, -3, 0), vec3(3, -3, 0), vec3(0, 3, 0)};
    WlPphigsCmd c = command(big);
    assert_int_equal(c.x0, 0);
    assert_int_equal(c.y0, 0);
    assert_int_equal(c.x1, 99);
    assert_int_equal(c.y1, 79);
}

/* A primitive on the far plane (NDC z = 1, inside [-1, 1]) has depth 0,
 * so its pixel key is its tag alone (pphigs_pixels.c pixel_key) and it
 * wins over the cleared key 0 only with a tag of at least 1: the ids the
 * distribution gives (pphigs_distrib.c retag) start at 1, so the host
 * list's very first element draws too. */
static void test_far_plane_first_element_draws(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    Vec3 v[3] = {vec3(-1, -1, 1), vec3(1, -1, 1), vec3(0, 1, 1)};
    add(db, root, scene_elem_prim(SCENE_EL_POLYGON, v, 3));
    scene_db_post(db, root);
    WlPphigsWeights w;
    WlPphigsCosts c = {.poly = 1000, .vertex = 100};
    wl_pphigs_weights_from_costs(&c, 1, &w);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 1, WL_PPHIGS_COMPLEX, &w);
    const SceneElem *e = scene_db_elem(wl_pphigs_dist_gp(d, 0), root, 0);
    ScenePrimInst pi = {.el = e, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1), .depth = 1};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 8, 8, out), 1);
    /* as many pixels as the same triangle at z = 0 (tag 0, depth > 0) */
    Vec3 near[3] = {vec3(-1, -1, 0), vec3(1, -1, 0), vec3(0, 1, 0)};
    SceneElem ne = scene_elem_prim(SCENE_EL_POLYGON, near, 3);
    pi.el = &ne;
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 8, 8, out), 1);
    uint64_t won[2];
    for (guint k = 0; k < 2; k++) {
        WlPphigsRegion *r = wl_pphigs_region_new(0, 0, 8, 8, 0);
        won[k] = wl_pphigs_region_draw(r, &g_array_index(out, WlPphigsCmd, k));
        wl_pphigs_region_free(r);
    }
    assert_true(won[1] > 0);
    assert_int_equal(won[0], won[1]);
    g_array_free(out, TRUE);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* A quad that is not planar, (-0.5, -0.5, 0) (0.5, -0.5, 0) (0.5, 0.2, 0)
 * (0, 0.9, 0.5): its fan triangles (0, 1, 2) and (0, 2, 3) have NDC
 * areas 0.35 and 0.525 (and (1, 2, 3), not a fan triangle, 0.175), so
 * (0, 2, 3) sets the plane and the shade: u = (1, 0.7, 0),
 * v = (0.5, 1.4, 0.5), n = (0.35, -0.5, 1.05); the plane has z = 0.5 at
 * vertex 3 (screen (50, 4) on 100 x 80), where (0, 1, 2)'s has z = 0. */
/* ... of largest area, the first of equal ones. */
static void test_largest_fan_triangle(void **state)
{
    (void)state;
    Vec3 v[4] = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0.5, 0.2, 0),
                 vec3(0, 0.9, 0.5)};
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 4);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 0.5, 0.25), .depth = 1};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 100, 80, out), 1);
    WlPphigsCmd c = g_array_index(out, WlPphigsCmd, 0);
    assert_int_equal(c.nedges, 4);
    assert_int_equal(c.rgba, rgba_of(0.3 + 0.7 * 1.05 / sqrt(1.475)));
    assert_true(fabs(c.z.a * 50 + c.z.b * 4 + c.z.c - 0.5) < 1e-12);
    assert_true(fabs(c.z.a * 25 + c.z.b * 60 + c.z.c) < 1e-12); /* vertex 0 */
    /* a square with vertex 3 lifted: both fan triangles have screen area
     * 1000 exactly, and the tie keeps the first, (0, 1, 2), flat at z = 0 */
    v[2] = vec3(0.5, 0.5, 0), v[3] = vec3(-0.5, 0.5, 0.5);
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 100, 80, out), 1);
    c = g_array_index(out, WlPphigsCmd, 1);
    assert_int_equal(c.rgba, rgba_of(1));
    assert_true(c.z.a == 0 && c.z.b == 0 && c.z.c == 0);
    g_array_free(out, TRUE);
}

/* On 64 GPs (the most a distribution takes) a modified colour, held by
 * every GP (simple algorithm), is sent to each of the 64 once and every
 * copy changes; deleted, it goes from all 64. */
static void test_modify_64_gps(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    add(db, root, scene_elem_color(vec3(1, 0, 0)));
    add(db, root, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    scene_db_post(db, root);
    WlPphigsWeights w = {.w = {[SCENE_EL_TRIANGLE] = 1}, .cluster = 1};
    WlPphigsDist *d = wl_pphigs_dist_new(db, 64, WL_PPHIGS_SIMPLE, &w);
    uint64_t sent = wl_pphigs_dist_traffic(d)->elements_sent;
    assert_int_equal(sent, 64 + 1);
    SceneElem c = scene_elem_color(vec3(0, 0, 1));
    assert_true(wl_pphigs_dist_modify(d, root, 0, &c, NULL));
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(d);
    assert_int_equal(t->elements_sent, sent + 64);
    for (guint g = 0; g < 64; g++) {
        assert_int_equal(t->sent_to[g], g == 0 ? 3 : 2);
        const SceneElem *e = scene_db_elem(wl_pphigs_dist_gp(d, g), root, 0);
        assert_true(e->kind == SCENE_EL_COLOR && e->color.z == 1 &&
                    e->color.x == 0);
    }
    /* deleted: removed from each of the 64 */
    wl_pphigs_dist_delete(d, root, 0);
    wl_pphigs_dist_finish(d);
    assert_int_equal(t->elements_removed, 64);
    for (guint g = 0; g < 64; g++)
        assert_int_equal(scene_db_len(wl_pphigs_dist_gp(d, g), root),
                         g == 0 ? 1 : 0);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* A view that takes w from z, keeps x and y and sets z' = w / 2 (NDC
 * z = 0.5 everywhere), and a triangle A (0, 0.25, 1), B (0.375, 0, 1),
 * C (0.25, 0.5, -1) with C behind the eye.  The clipped outline is A, B,
 * the cut of BC, the cut of CA (w = 1e-6, far off the 8 x 8 screen);
 * each cut is a point of its edge, so the outline's edges 1 (B to the
 * cut of BC) and 3 (the cut of CA to A) lie on the projected lines BC
 * and CA, which pass through C's projection (x/w, y/w) = (-0.25, -0.5),
 * screen (3, 6).  The cuts keep z' = w / 2, so the depth plane is flat
 * at 0.5 and every drawn pixel has the key of depth (1 - 0.5) / 2. */
static void test_near_cut_on_edge(void **state)
{
    (void)state;
    Mat4 wz = mat4_identity();
    wz.m[2][2] = 0.5;
    wz.m[3][2] = 1;
    wz.m[3][3] = 0;
    Vec3 v[3] = {vec3(0, 0.25, 1), vec3(0.375, 0, 1), vec3(0.25, 0.5, -1)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    e.tag = 9;
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1)};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, wz, 8, 8, out), 1);
    const WlPphigsCmd *c = &g_array_index(out, WlPphigsCmd, 0);
    assert_int_equal(c->nedges, 4);
    for (guint k = 1; k < 4; k += 2) {
        const WlPphigsLin *l = &c->edge[k];
        double at = l->a * 3 + l->b * 6 + l->c;
        assert_true(fabs(at) <= 1e-9 * (fabs(l->a) * 3 + fabs(l->b) * 6 +
                                          fabs(l->c)));
    }
    assert_true(c->z.a == 0 && c->z.b == 0 && c->z.c == 0.5);
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, 8, 8, 0);
    assert_true(wl_pphigs_region_draw(r, c) > 0);
    uint64_t key = (uint64_t)llrint(0.25 * (double)UINT32_MAX) << 31 | 9;
    for (guint i = 0; i < 64; i++)
        assert_true(r->key[i] == 0 || r->key[i] == key);
    wl_pphigs_region_free(r);
    g_array_free(out, TRUE);
}

/* The pixel box spans every vertex, the first one too: a triangle whose
 * vertex 0, NDC (0.5, 0.5), is its rightmost and topmost point (screen
 * (6, 2) on 8 x 8; the others (2, 3) and (4, 6)) covers centres x 2..5
 * (ceil(2 - 0.5) .. floor(6 - 0.5)) and y 2..5. */
static void test_box_from_vertex_0(void **state)
{
    (void)state;
    Vec3 v[3] = {vec3(0.5, 0.5, 0), vec3(-0.5, 0.25, 0), vec3(0, -0.5, 0)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1)};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, mat4_identity(), 8, 8, out), 1);
    const WlPphigsCmd *c = &g_array_index(out, WlPphigsCmd, 0);
    assert_true(c->x0 == 2 && c->x1 == 5 && c->y0 == 2 && c->y1 == 5);
    g_array_free(out, TRUE);
}

/* A 24-gon (the most edges a command has) with one vertex behind the
 * eye: near clipping replaces that vertex by two cuts, 25 vertices, one
 * more than a command holds: no command (like a 25-gon).  With every
 * vertex in front it draws. */
static void test_clipped_past_max_edges(void **state)
{
    (void)state;
    Mat4 wz = mat4_identity(); /* w = z, z' = 0 */
    wz.m[2][2] = 0;
    wz.m[3][2] = 1;
    wz.m[3][3] = 0;
    Vec3 ring[WL_PPHIGS_MAX_EDGES];
    for (int i = 0; i < WL_PPHIGS_MAX_EDGES; i++)
        ring[i] = vec3(0.5 * cos(i * 2 * G_PI / WL_PPHIGS_MAX_EDGES),
                       0.5 * sin(i * 2 * G_PI / WL_PPHIGS_MAX_EDGES), 1);
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, ring, WL_PPHIGS_MAX_EDGES);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1)};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, wz, 8, 8, out), 1);
    ring[5].z = -1;
    assert_int_equal(wl_pphigs_cmds(&pi, wz, 8, 8, out), 0);
    assert_int_equal(out->len, 1);
    g_array_free(out, TRUE);
}

/* pphigs_edit.c: a modify that changes a matrix's mode goes as an
 * insert and a delete, so its traffic and GP lists equal those of that
 * insert, delete and finish done by hand on a twin; a modify whose
 * insert fails (an execute that would close a cycle, also a change of
 * kind between executes of an ordinary and of a primitive structure)
 * changes nothing and returns FALSE. */
static void test_modify_as_insert_delete(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    guint prim = scene_db_add_struct(db, "prim");
    guint mid = scene_db_add_struct(db, "mid");
    scene_db_set_primitive(db, prim, TRUE);
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    add(db, prim, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    add(db, root, scene_elem_matrix(mat4_scale(2, 2, 2), SCENE_MAT_REPLACE));
    for (guint i = 0; i < 3; i++)
        add(db, root, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    add(db, root, scene_elem_execute(prim));
    add(db, root, scene_elem_execute(mid));
    add(db, mid, scene_elem_prim(SCENE_EL_TRIANGLE, v, 3));
    scene_db_post(db, root);
    WlPphigsWeights w = {.w = {[SCENE_EL_TRIANGLE] = 1}, .cluster = 1};
    WlPphigsDist *a = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
    WlPphigsDist *b = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
    SceneElem cat = scene_elem_matrix(mat4_scale(3, 3, 3), SCENE_MAT_CONCAT);
    assert_true(wl_pphigs_dist_modify(a, root, 0, &cat, NULL));
    assert_true(wl_pphigs_dist_insert(b, root, 0, &cat, NULL));
    wl_pphigs_dist_delete(b, root, 1);
    wl_pphigs_dist_finish(b);
    const WlPphigsTraffic *ta = wl_pphigs_dist_traffic(a),
                          *tb = wl_pphigs_dist_traffic(b);
    assert_int_equal(ta->elements_sent, tb->elements_sent);
    assert_int_equal(ta->elements_removed, tb->elements_removed);
    for (guint g = 0; g < 2; g++)
        assert_int_equal(scene_db_len(wl_pphigs_dist_gp(a, g), root),
                         scene_db_len(wl_pphigs_dist_gp(b, g), root));
    /* execute(prim) -> execute(root) inside mid: a cycle, refused */
    add(db, mid, scene_elem_execute(prim));
    wl_pphigs_dist_free(a);
    a = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
    uint64_t sent = wl_pphigs_dist_traffic(a)->elements_sent;
    SceneElem loop = scene_elem_execute(root);
    GError *err = NULL;
    assert_false(wl_pphigs_dist_modify(a, mid, 1, &loop, &err));
    assert_non_null(err);
    g_clear_error(&err);
    const SceneDb *h = wl_pphigs_dist_host(a);
    assert_int_equal(scene_db_len(h, mid), 2);
    assert_int_equal(scene_db_elem(h, mid, 1)->child, prim);
    assert_int_equal(wl_pphigs_dist_traffic(a)->elements_sent, sent);
    wl_pphigs_dist_free(a);
    wl_pphigs_dist_free(b);
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nonprim_cost),
        cmocka_unit_test(test_shading),
        cmocka_unit_test(test_box_clamped_to_screen),
        cmocka_unit_test(test_far_plane_first_element_draws),
        cmocka_unit_test(test_largest_fan_triangle),
        cmocka_unit_test(test_modify_64_gps),
        cmocka_unit_test(test_near_cut_on_edge),
        cmocka_unit_test(test_box_from_vertex_0),
        cmocka_unit_test(test_clipped_past_max_edges),
        cmocka_unit_test(test_modify_as_insert_delete),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
