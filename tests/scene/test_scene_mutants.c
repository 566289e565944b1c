/* test_scene_mutants.c — claims of sim/scene that mutation testing (make
 * mutate, docs/testing.md) found unchecked: an instance's projective
 * transform divides by w when flattened, seed 004's huge polygons are
 * centred about the screen centre, and the PPHIGS scene and the
 * isosurface, large-polygon, march and NURBS generators keep their
 * colours (one white instance). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/isosurface.h"
#include "sim/scene/march.h"
#include "sim/scene/nurbs.h"
#include "sim/scene/pn_triangles.h"
#include "sim/scene/pphigs_db.h"
#include "sim/scene/scene.h"
#include "sim/scene/scene_cfg.h"
#include "sim/scene/teapots.h"

/* One triangle under `xf`, flattened: its first vertex. */
static Vec3 flatten_first(Mat4 xf)
{
    Scene *s = scene_new("t");
    SceneMesh *m = scene_mesh_new();
    uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(2, 4, 6)),
                     scene_mesh_add_vertex(m, vec3(8, 4, 6)),
                     scene_mesh_add_vertex(m, vec3(2, 10, 6))};
    scene_mesh_add_poly(m, v, 3, scene_color(1, 1, 1), 0);
    scene_add_instance(s, scene_add_mesh(s, m), xf, scene_color(1, 1, 1), 0);
    SceneMesh *f = scene_flatten(s);
    Vec3 p = scene_mesh_vertex(f, 0);
    scene_mesh_free(f);
    scene_free(s);
    return p;
}

static void test_projective_instance(void **state)
{
    (void)state;
    Mat4 xf = mat4_identity();
    xf.m[3][3] = 2; /* w = 2: the point is (x, y, z) / 2 */
    Vec3 p = flatten_first(xf);
    assert_true(p.x == 1 && p.y == 2 && p.z == 3);
    xf.m[3][3] = 0; /* w = 0 (a point at infinity): left as it is */
    p = flatten_first(xf);
    assert_true(p.x == 2 && p.y == 4 && p.z == 6);
}

/* Seed 004 §6's huge polygons: regular polygons whose centres are drawn
 * in [-0.2, 0.2]^2 about the screen centre (isosurface.c huge_polygon);
 * a polygon's vertex mean is its centre. */
static void test_huge_polygons_centred(void **state)
{
    (void)state;
    SceneBigPolyParams p = scene_bigpoly_defaults();
    p.count = 600;
    p.huge_fraction = 0.5;
    Scene *s = scene_bigpoly_new(&p);
    const SceneMesh *m = g_ptr_array_index(s->meshes, 0);
    double sx = 0, sy = 0;
    guint huge = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *v = scene_mesh_poly(m, i);
        guint n = scene_mesh_poly_len(m, i);
        Vec3 c = vec3(0, 0, 0), lo = vec3(1e9, 1e9, 0), hi = vec3(-1e9, -1e9, 0);
        for (guint k = 0; k < n; k++) {
            Vec3 q = scene_mesh_vertex(m, v[k]);
            c = vec3_add(c, q);
            lo = vec3(MIN(lo.x, q.x), MIN(lo.y, q.y), 0);
            hi = vec3(MAX(hi.x, q.x), MAX(hi.y, q.y), 0);
        }
        if ((hi.x - lo.x) * (hi.y - lo.y) < 3) /* not a huge one */
            continue;
        c = vec3_scale(c, 1.0 / n);
        assert_true(fabs(c.x) <= 0.2 + 1e-9 && fabs(c.y) <= 0.2 + 1e-9);
        sx += c.x;
        sy += c.y;
        huge++;
    }
    assert_true(huge > 200);
    /* the small ones are centred anywhere on the screen: uniform on
     * [-1, 1]^2, so their vertex means average to about 0 */
    double ux = 0, uy = 0;
    guint small = 0;
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *v = scene_mesh_poly(m, i);
        guint n = scene_mesh_poly_len(m, i);
        Vec3 c = vec3(0, 0, 0);
        double w = 0;
        for (guint k = 0; k < n; k++) {
            Vec3 q = scene_mesh_vertex(m, v[k]);
            c = vec3_add(c, q);
            w = MAX(w, fabs(q.x - scene_mesh_vertex(m, v[0]).x));
        }
        if (w > 1.2) /* a huge one */
            continue;
        ux += c.x / n;
        uy += c.y / n;
        small++;
    }
    assert_true(small > 200);
    assert_true(fabs(ux / small) < 0.15 && fabs(uy / small) < 0.15);
    /* uniform on [-0.2, 0.2]: the mean is 0 within 5 standard errors */
    assert_true(fabs(sx / huge) < 0.04 && fabs(sy / huge) < 0.04);
    scene_free(s);
}

/* The PPHIGS scene is the database flattened under one white instance:
 * every polygon keeps the colour the database gave it. */
static void test_pphigs_scene_white(void **state)
{
    (void)state;
    ScenePphigsSpec sp = {0};
    sp.kind = SCENE_PPHIGS_STATION;
    sp.seed = 7;
    sp.verts = 4;
    sp.size = 100;
    sp.polygons = 40;
    sp.attributes = 6;
    GError *err = NULL;
    Scene *s = scene_pphigs_scene_new(&sp, &err);
    assert_non_null(s);
    assert_int_equal(s->instances->len, 1);
    const SceneInstance *in = scene_instance(s, 0);
    assert_true(in->color.r == 1 && in->color.g == 1 && in->color.b == 1);
    scene_free(s);
}

/* One white, untransformed instance of mesh 0 (the generators' own
 * colours stand as made). */
static void check_one_white(Scene *s)
{
    assert_non_null(s);
    assert_int_equal(scene_n_instances(s), 1);
    const SceneInstance *in = scene_instance(s, 0);
    assert_true(in->color.r == 1 && in->color.g == 1 && in->color.b == 1);
    assert_int_equal(in->mesh, 0);
    Mat4 id = mat4_identity();
    assert_memory_equal(&in->xform, &id, sizeof id);
    scene_free(s);
}

static void test_generators_white(void **state)
{
    (void)state;
    SceneIsoParams ip = scene_iso_defaults();
    ip.grid = 6;
    check_one_white(scene_iso_new(&ip));
    SceneBigPolyParams bp = scene_bigpoly_defaults();
    bp.count = 5;
    check_one_white(scene_bigpoly_new(&bp));
    SceneMarchParams mp = scene_march_defaults();
    mp.iso.grid = 8;
    mp.cell = 4;
    check_one_white(scene_march_new(&mp));
    SceneNurbsParams np = scene_nurbs_defaults();
    np.tess = 2;
    check_one_white(scene_nurbs_new(&np));
}

/* A view fitted to a single vertex (fit_points takes n >= 1) aims at
 * it: the camera target moves from the origin to the vertex. */
static void test_fit_one_vertex(void **state)
{
    (void)state;
    Scene *s = scene_new("t");
    SceneMesh *m = scene_mesh_new();
    scene_mesh_add_vertex(m, vec3(3, 4, 5));
    scene_add_instance(s, scene_add_mesh(s, m), mat4_identity(),
                       scene_color(1, 1, 1), 0);
    SceneView v = scene_view_default();
    v.fit_vertices = TRUE;
    scene_apply_view(s, &v);
    Vec3 t = s->camera.target;
    assert_true(fabs(t.x - 3) < 1e-9 && fabs(t.y - 4) < 1e-9 &&
                fabs(t.z - 5) < 1e-9);
    scene_free(s);
}

/* The teapots share one white mesh (288 polygons, the least: 32 patches
 * of 3 x 3 quads): the colours are the instances'. */
static void test_teapot_mesh_white(void **state)
{
    (void)state;
    SceneTeapotsParams p = scene_teapots_defaults();
    p.count = 2;
    p.polygons_per_teapot = 288;
    GError *err = NULL;
    Scene *s = scene_teapots_new(&p, "t", &err);
    if (!s)
        fail_msg("%s", err->message);
    const SceneMesh *m = scene_instance_mesh(s, 0);
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        SceneColor c = g_array_index(m->poly_color, SceneColor, i);
        assert_true(c.r == 1 && c.g == 1 && c.b == 1);
    }
    scene_free(s);
}

/* Both teapot layouts centre a full grid on the origin (teapots.h): the
 * teapots' box centres average to 0 on every axis. */
static void check_centred(SceneTeapotLayout layout, guint count, guint columns)
{
    SceneTeapotsParams p = scene_teapots_defaults();
    p.layout = layout;
    p.count = count;
    p.columns = columns;
    GError *err = NULL;
    Scene *s = scene_teapots_new(&p, "t", &err);
    assert_non_null(s);
    Vec3 sum = vec3(0, 0, 0);
    for (guint i = 0; i < s->instances->len; i++) {
        SceneBox b = scene_instance_bbox(s, i);
        sum = vec3_add(sum, vec3_scale(vec3_add(b.min, b.max), 0.5));
    }
    sum = vec3_scale(sum, 1.0 / count);
    if (fabs(sum.x) > 1e-6 || fabs(sum.y) > 1e-6 || fabs(sum.z) > 1e-6)
        fail_msg("layout %d, %u teapots, %u columns: centre (%g, %g, %g)",
                 layout, count, columns, sum.x, sum.y, sum.z);
    scene_free(s);
}

static void test_teapot_layouts_centred(void **state)
{
    (void)state;
    check_centred(SCENE_TEAPOTS_SPREAD, 4, 1);
    check_centred(SCENE_TEAPOTS_SPREAD, 6, 1);
    check_centred(SCENE_TEAPOTS_SPREAD, 9, 1);
    check_centred(SCENE_TEAPOTS_DEPTH, 4, 2);
    check_centred(SCENE_TEAPOTS_DEPTH, 6, 3);
    check_centred(SCENE_TEAPOTS_DEPTH, 3, 1);
}

static void keep_first(const ScenePrimInst *pi, void *ud)
{
    ScenePrimInst *first = ud;
    if (!first->el)
        *first = *pi;
}

/* A posted structure's primitives before any colour element inherit the
 * default colour (1, 1, 1) at depth 1 (structdb.h, ScenePrimInst). */
static void test_traverse_defaults(void **state)
{
    (void)state;
    SceneDb *db = scene_db_new();
    guint root = scene_db_add_struct(db, "root");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    assert_true(scene_db_append(db, root, &e, NULL));
    scene_db_post(db, root);
    ScenePrimInst first = {0};
    scene_db_traverse(db, keep_first, &first);
    assert_non_null(first.el);
    assert_true(first.color.x == 1 && first.color.y == 1 && first.color.z == 1);
    assert_int_equal(first.depth, 1);
    scene_db_free(db);
}

/* An instance's exact box holds every vertex, the first one included. */
static void test_instance_bbox_first_vertex(void **state)
{
    (void)state;
    Scene *s = scene_new("t");
    SceneMesh *m = scene_mesh_new();
    uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(-5, -6, -7)),
                     scene_mesh_add_vertex(m, vec3(1, 0, 0)),
                     scene_mesh_add_vertex(m, vec3(0, 1, 0))};
    scene_mesh_add_poly(m, v, 3, scene_color(1, 1, 1), 0);
    scene_add_instance(s, scene_add_mesh(s, m), mat4_translate(1, 1, 1),
                       scene_color(1, 1, 1), 0);
    Vec3 e = scene_box_center(scene_box_empty()); /* empty: the origin */
    assert_true(e.x == 0 && e.y == 0 && e.z == 0);
    /* boxes are closed: sharing a face on any axis is overlapping */
    SceneBox u = {vec3(0, 0, 0), vec3(1, 1, 1)};
    for (int ax = 0; ax < 3; ax++) {
        SceneBox w = u;
        double *lo = ax == 0 ? &w.min.x : ax == 1 ? &w.min.y : &w.min.z;
        double *hi = ax == 0 ? &w.max.x : ax == 1 ? &w.max.y : &w.max.z;
        *lo = 1, *hi = 2; /* touches u at its max face */
        assert_true(scene_box_overlaps(u, w) && scene_box_overlaps(w, u));
        *lo = 1.5; /* a gap */
        assert_false(scene_box_overlaps(u, w) || scene_box_overlaps(w, u));
    }
    SceneBox b = scene_instance_bbox(s, 0);
    assert_true(b.min.x == -4 && b.min.y == -5 && b.min.z == -6);
    assert_true(b.max.x == 2 && b.max.y == 2 && b.max.z == 1);
    scene_free(s);
}

/* A camera one unit from its target is a camera like any other; only
 * eye = target is degenerate. */
static Scene *with_camera(const char *eye, GError **err)
{
    char *y = g_strdup_printf("{generator: teapots, count: 1, polygons_per_"
                              "teapot: 300, camera: {eye: %s, target: [0, 0, "
                              "0], near: 0.1, far: 50}}\n",
                              eye);
    CfgNode *n = cfg_load_string(y, "c.yaml", err);
    g_free(y);
    assert_non_null(n);
    Scene *s = scene_from_cfg(n, err);
    cfg_free(n);
    return s;
}

static void test_camera_unit_distance(void **state)
{
    (void)state;
    GError *err = NULL;
    Scene *s = with_camera("[0, 0, 1]", &err);
    if (!s)
        fail_msg("%s", err->message);
    scene_free(s);
    assert_null(with_camera("[0, 0, 0]", &err));
    assert_non_null(strstr(err->message, "a degenerate camera"));
    g_clear_error(&err);
}

/* The Nurbs torus's tube radius is 0.45 modulated by a sum of sinusoids
 * (nurbs.h): over the whole control grid the modulation averages to 0,
 * and one sinusoid keeps the radius within 0.45 (1 +- amplitude). */
static double tube_radius(const SceneNurbsParams *p, guint i, guint j)
{
    Vec3 q = scene_nurbs_control(p, i, j);
    double ph = atan2(q.z, q.x);
    return vec3_len(vec3_sub(q, vec3(cos(ph), 0, sin(ph))));
}

static void test_nurbs_bumps_zero_mean(void **state)
{
    (void)state;
    SceneNurbsParams p = scene_nurbs_defaults();
    guint nu = 0, nv = 0;
    /* the grid repeats: find its size from the control points */
    Vec3 q0 = scene_nurbs_control(&p, 0, 0);
    for (nu = 1; nu < 1000; nu++)
        if (vec3_len(vec3_sub(scene_nurbs_control(&p, nu, 0), q0)) < 1e-12)
            break;
    for (nv = 1; nv < 1000; nv++)
        if (vec3_len(vec3_sub(scene_nurbs_control(&p, 0, nv), q0)) < 1e-12)
            break;
    assert_true(nu > 4 && nu < 1000 && nv > 4 && nv < 1000);
    double sum = 0;
    for (guint i = 0; i < nu; i++)
        for (guint j = 0; j < nv; j++)
            sum += tube_radius(&p, i, j);
    assert_true(fabs(sum / (nu * nv) - 0.45) < 1e-9);
    p.bumps = 1;
    for (guint i = 0; i < nu; i++)
        for (guint j = 0; j < nv; j++) {
            double r = tube_radius(&p, i, j);
            assert_true(r >= 0.45 * (1 - p.amplitude) - 1e-12 &&
                        r <= 0.45 * (1 + p.amplitude) + 1e-12);
        }
}

/* camera.h: "A perspective camera at (0, 0, 5) looking at the origin, +y
 * up, 45°, near 0.1, far 100, aspect 1." */
static void test_default_camera(void **state)
{
    (void)state;
    SceneCamera c = scene_camera_default();
    assert_int_equal(c.proj, SCENE_PERSPECTIVE);
    assert_true(c.eye.x == 0 && c.eye.y == 0 && c.eye.z == 5);
    assert_true(c.target.x == 0 && c.target.y == 0 && c.target.z == 0);
    assert_true(c.up.x == 0 && c.up.y == 1 && c.up.z == 0);
    assert_true(c.fov_deg == 45 && c.near == 0.1 && c.far == 100);
    assert_true(c.aspect == 1);
}

/* The march generator's fill is any fraction in [0.05, 1]. */
static void test_march_fill(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *n = cfg_load_string("{generator: march, grid: 8, cell: 4, "
                                 "fill: 0.5}\n", "m.yaml", &err);
    Scene *s = scene_from_cfg(n, &err);
    if (!s)
        fail_msg("%s", err->message);
    scene_free(s);
    cfg_free(n);
}

/* A PN triangle whose corner normals are the face normal is the flat
 * triangle: its centre control point b111 = E + (E - V) / 2 is the
 * centroid, E (the mean of the six edge points) being the centroid too. */
static void test_pn_flat_centre(void **state)
{
    (void)state;
    Vec3 P[3] = {vec3(1, 2, 3), vec3(4, 2, 3), vec3(1, 6, 3)};
    Vec3 N[3] = {vec3(0, 0, 1), vec3(0, 0, 1), vec3(0, 0, 1)};
    ScenePnPatch pt;
    scene_pn_patch(&pt, P, N);
    assert_true(fabs(pt.b111.x - 2) < 1e-12 && fabs(pt.b111.y - 10.0 / 3) < 1e-12 &&
                fabs(pt.b111.z - 3) < 1e-12);
}

/* The Old Well's objects sit on a ring of columns at heights spread over
 * a quarter of the half-size (pphigs_db.c gen_well): with 20 objects of
 * a size-100 model their polygons' centres span more than 6 units in y
 * (the polygons themselves reach only about 1 + 1.25 from their object's
 * centre). */
static void test_old_well_heights(void **state)
{
    (void)state;
    ScenePphigsSpec sp = {0};
    sp.kind = SCENE_PPHIGS_FLOCK;
    sp.seed = 7;
    sp.verts = 4;
    sp.size = 100;
    sp.boids = 2;
    sp.boid_polygons = 3;
    sp.boid_colors = 1;
    sp.well_structs = 2;
    sp.well_polygons = 40;
    sp.well_attributes = 20;
    ScenePphigsDb d;
    GError *err = NULL;
    assert_true(scene_pphigs_generate(&sp, &d, &err));
    double lo = 1e9, hi = -1e9;
    for (guint k = 0; k < 2; k++) {
        char name[16];
        guint sid;
        g_snprintf(name, sizeof name, "well_%u", k);
        assert_true(scene_db_find(d.db, name, &sid));
        for (guint i = 0; i < scene_db_len(d.db, sid); i++) {
            const SceneElem *e = scene_db_elem(d.db, sid, i);
            if (!e->nverts)
                continue;
            double y = 0;
            for (guint v = 0; v < e->nverts; v++)
                y += e->verts[v].y / e->nverts;
            lo = MIN(lo, y), hi = MAX(hi, y);
        }
    }
    assert_true(hi - lo > 6);
    scene_pphigs_db_clear(&d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_projective_instance),
        cmocka_unit_test(test_huge_polygons_centred),
        cmocka_unit_test(test_pphigs_scene_white),
        cmocka_unit_test(test_generators_white),
        cmocka_unit_test(test_fit_one_vertex),
        cmocka_unit_test(test_teapot_mesh_white),
        cmocka_unit_test(test_teapot_layouts_centred),
        cmocka_unit_test(test_traverse_defaults),
        cmocka_unit_test(test_instance_bbox_first_vertex),
        cmocka_unit_test(test_camera_unit_distance),
        cmocka_unit_test(test_nurbs_bumps_zero_mean),
        cmocka_unit_test(test_default_camera),
        cmocka_unit_test(test_march_fill),
        cmocka_unit_test(test_pn_flat_centre),
        cmocka_unit_test(test_old_well_heights),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
