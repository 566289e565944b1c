/* test_pn_patch.c — sim/scene/pn_triangles.c against the construction of
 * Vlachos et al. (seed 002, "Curved PN Triangles") written out here
 * independently: every control point b_ijk and mid-edge normal n_ij of a
 * curved patch, the cubic point and both normal kinds at interior, edge
 * and corner parameters, and the tessellated grid (edges computed from
 * the edge alone, in either vertex order) -- each compared with the
 * paper's formula term by term, so a changed weight, index or sign in
 * any one term shows.  test_pn_props.c checks the grid against the
 * library's own evaluation; this one checks the evaluation itself. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/pn_triangles.h"

#define TOL 1e-12

static void near3(Vec3 a, Vec3 b)
{
    if (vec3_len(vec3_sub(a, b)) > TOL)
        fail_msg("(%.17g %.17g %.17g) != (%.17g %.17g %.17g)", a.x, a.y, a.z,
                 b.x, b.y, b.z);
}

/* A curved patch: no two vertices share a coordinate, normals tilted
 * differently, so every control point differs from every other. */
static const Vec3 P[3] = {{0.1, -0.2, 0.3}, {2.3, 0.4, -0.5}, {0.7, 1.9, 0.6}};
static const Vec3 Nraw[3] = {{-0.3, -0.2, 1}, {0.5, 0.1, 1}, {0.1, 0.6, 0.8}};

/* The paper's b_ij: (2 Pi + Pj - ((Pj - Pi).Ni) Ni) / 3. */
static Vec3 ref_b(int i, int j, const Vec3 N[3])
{
    double w = vec3_dot(vec3_sub(P[j], P[i]), N[i]);
    Vec3 s = vec3_add(vec3_scale(P[i], 2), P[j]);
    return vec3_scale(vec3_sub(s, vec3_scale(N[i], w)), 1.0 / 3);
}

/* The paper's n_ij: normalise(Ni + Nj - v_ij (Pj - Pi)),
 * v_ij = 2 (Pj - Pi).(Ni + Nj) / |Pj - Pi|^2. */
static Vec3 ref_n(int i, int j, const Vec3 N[3])
{
    Vec3 d = vec3_sub(P[j], P[i]), s = vec3_add(N[i], N[j]);
    double v = 2 * vec3_dot(d, s) / vec3_dot(d, d);
    return vec3_norm(vec3_sub(s, vec3_scale(d, v)));
}

typedef struct {
    Vec3 b300, b030, b003, b210, b120, b021, b012, b102, b201, b111;
    Vec3 n200, n020, n002, n110, n011, n101;
} Ref;

static Ref ref_patch(void)
{
    Vec3 N[3];
    for (int i = 0; i < 3; i++)
        N[i] = vec3_norm(Nraw[i]);
    Ref r = {.b300 = P[0], .b030 = P[1], .b003 = P[2]};
    r.b210 = ref_b(0, 1, N);
    r.b120 = ref_b(1, 0, N);
    r.b021 = ref_b(1, 2, N);
    r.b012 = ref_b(2, 1, N);
    r.b102 = ref_b(2, 0, N);
    r.b201 = ref_b(0, 2, N);
    Vec3 E = vec3_add(vec3_add(r.b210, r.b120), vec3_add(r.b021, r.b012));
    E = vec3_scale(vec3_add(E, vec3_add(r.b102, r.b201)), 1.0 / 6);
    Vec3 V = vec3_scale(vec3_add(vec3_add(P[0], P[1]), P[2]), 1.0 / 3);
    r.b111 = vec3_add(E, vec3_scale(vec3_sub(E, V), 0.5));
    r.n200 = N[0];
    r.n020 = N[1];
    r.n002 = N[2];
    r.n110 = ref_n(0, 1, N);
    r.n011 = ref_n(1, 2, N);
    r.n101 = ref_n(2, 0, N);
    return r;
}

/* b(u, v) = sum b_ijk 3!/(i!j!k!) w^i u^j v^k, w = 1 - u - v. */
static Vec3 ref_point(const Ref *r, double u, double v)
{
    double w = 1 - u - v;
    const struct {
        Vec3 b;
        double c;
    } t[10] = {
        {r->b300, w * w * w},     {r->b030, u * u * u},
        {r->b003, v * v * v},     {r->b210, 3 * w * w * u},
        {r->b120, 3 * w * u * u}, {r->b201, 3 * w * w * v},
        {r->b021, 3 * u * u * v}, {r->b102, 3 * w * v * v},
        {r->b012, 3 * u * v * v}, {r->b111, 6 * w * u * v},
    };
    Vec3 s = vec3(0, 0, 0);
    for (int i = 0; i < 10; i++)
        s = vec3_add(s, vec3_scale(t[i].b, t[i].c));
    return s;
}

static Vec3 ref_normal(const Ref *r, ScenePnNormals kind, double u, double v)
{
    double w = 1 - u - v;
    if (kind == SCENE_PN_LINEAR)
        return vec3_norm(vec3_add(vec3_add(vec3_scale(r->n200, w),
                                           vec3_scale(r->n020, u)),
                                  vec3_scale(r->n002, v)));
    Vec3 s = vec3_add(vec3_scale(r->n200, w * w), vec3_scale(r->n020, u * u));
    s = vec3_add(s, vec3_scale(r->n002, v * v));
    s = vec3_add(s, vec3_scale(r->n110, w * u));
    s = vec3_add(s, vec3_scale(r->n011, u * v));
    return vec3_norm(vec3_add(s, vec3_scale(r->n101, w * v)));
}

static void test_control_net(void **st)
{
    (void)st;
    ScenePnPatch pt;
    scene_pn_patch(&pt, P, Nraw);
    Ref r = ref_patch();
    for (int i = 0; i < 3; i++)
        near3(pt.p[i], P[i]);
    near3(pt.n[0], r.n200);
    near3(pt.n[1], r.n020);
    near3(pt.n[2], r.n002);
    near3(pt.b210, r.b210);
    near3(pt.b120, r.b120);
    near3(pt.b021, r.b021);
    near3(pt.b012, r.b012);
    near3(pt.b102, r.b102);
    near3(pt.b201, r.b201);
    near3(pt.b111, r.b111);
    near3(pt.n110, r.n110);
    near3(pt.n011, r.n011);
    near3(pt.n101, r.n101);
    /* the patch is curved: b111 is off the flat centroid */
    Vec3 V = vec3_scale(vec3_add(vec3_add(P[0], P[1]), P[2]), 1.0 / 3);
    assert_true(vec3_len(vec3_sub(r.b111, V)) > 0.01);
}

/* Interior, edge and corner parameters, both normal kinds. */
static const double uv[][2] = {{0.2, 0.3}, {0.1, 0.7}, {0.6, 0.15},
                               {1.0 / 3, 1.0 / 3}, {0.4, 0}, {0, 0.4},
                               {0.35, 0.65}, {0, 0}, {1, 0}, {0, 1}};

static void test_evaluation(void **st)
{
    (void)st;
    ScenePnPatch pt;
    scene_pn_patch(&pt, P, Nraw);
    Ref r = ref_patch();
    for (guint i = 0; i < G_N_ELEMENTS(uv); i++) {
        double u = uv[i][0], v = uv[i][1];
        near3(scene_pn_point(&pt, u, v), ref_point(&r, u, v));
        for (int k = 0; k < 2; k++) {
            ScenePnNormals kind = k ? SCENE_PN_QUADRATIC : SCENE_PN_LINEAR;
            near3(scene_pn_normal(&pt, kind, u, v), ref_normal(&r, kind, u, v));
        }
    }
    /* the two kinds differ inside the patch */
    assert_true(vec3_len(vec3_sub(ref_normal(&r, SCENE_PN_LINEAR, 0.2, 0.3),
                                  ref_normal(&r, SCENE_PN_QUADRATIC, 0.2,
                                             0.3))) > 1e-3);
}

/* The tessellation at level L: grid point (j, k) of row k is the patch at
 * (u, v) = (j, k) / (L + 1), computed from the paper's formulas.  P1 comes
 * before P2 in (x, y, z) order but P2 after P3 and P3 after P1, so one
 * edge is computed from its first vertex and two from their second. */
static void test_grid(void **st)
{
    (void)st;
    Ref r = ref_patch();
    Vec3 N[3];
    for (int i = 0; i < 3; i++)
        N[i] = vec3_norm(Nraw[i]);
    for (int k = 0; k < 2; k++) {
        ScenePnNormals kind = k ? SCENE_PN_QUADRATIC : SCENE_PN_LINEAR;
        for (guint L = 0; L < 4; L++) {
            SceneMesh *m = scene_mesh_new();
            for (int i = 0; i < 3; i++) {
                scene_mesh_add_vertex(m, P[i]);
                g_array_append_val(m->normals, N[i]);
            }
            scene_mesh_add_tri(m, 0, 1, 2, scene_color(1, 1, 1), 0);
            ScenePnParams p = {L, kind, FALSE};
            SceneMesh *t = scene_pn_tessellate(m, &p);
            guint n = L + 1, idx = 0;
            for (guint row = 0; row <= n; row++)
                for (guint j = 0; j + row <= n; j++, idx++) {
                    double u = (double)j / n, v = (double)row / n;
                    near3(scene_mesh_vertex(t, idx), ref_point(&r, u, v));
                    near3(g_array_index(t->normals, Vec3, idx),
                          ref_normal(&r, kind, u, v));
                }
            assert_int_equal(idx, scene_mesh_n_vertices(t));
            scene_mesh_free(t);
            scene_mesh_free(m);
        }
    }
}

/* The grid's triangles at level 1 (3 points a side): rows by weight of
 * P3, each cell split into an upright and (inside) an inverted one,
 * all wound like the input. */
static void test_connectivity(void **st)
{
    (void)st;
    SceneMesh *m = scene_mesh_new();
    Vec3 N[3];
    for (int i = 0; i < 3; i++) {
        N[i] = vec3_norm(Nraw[i]);
        scene_mesh_add_vertex(m, P[i]);
        g_array_append_val(m->normals, N[i]);
    }
    scene_mesh_add_tri(m, 0, 1, 2, scene_color(1, 1, 1), 0);
    ScenePnParams p = {1, SCENE_PN_LINEAR, FALSE};
    SceneMesh *t = scene_pn_tessellate(m, &p);
    /* points: row 0: 0 1 2; row 1: 3 4; row 2: 5 */
    const uint32_t want[4][3] = {{0, 1, 3}, {1, 4, 3}, {1, 2, 4}, {3, 4, 5}};
    assert_int_equal(scene_mesh_n_polys(t), 4);
    for (guint i = 0; i < 4; i++) {
        assert_int_equal(scene_mesh_poly_len(t, i), 3);
        assert_memory_equal(scene_mesh_poly(t, i), want[i], sizeof want[i]);
    }
    scene_mesh_free(t);
    scene_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_control_net),
        cmocka_unit_test(test_evaluation),
        cmocka_unit_test(test_grid),
        cmocka_unit_test(test_connectivity),
    };
    return cmocka_run_group_tests_name("pn_patch", tests, NULL, NULL);
}
