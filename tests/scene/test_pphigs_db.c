/* test_pphigs_db.c — the four PPHIGS database generators, checked element
 * by element on small specs: structure counts, depth, matrix modes,
 * colours per object, boid instancing, and the spec limits at their
 * boundaries (one value accepted, the next rejected); the in-plane axes
 * of a polygon on both sides of their switch at |n.x| = 0.9.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/scene/mesh_check.h"
#include "sim/scene/pphigs_db.h"
#include <math.h>

static ScenePphigsSpec spec(ScenePphigsKind k)
{
    ScenePphigsSpec s = {0};
    s.kind = k;
    s.seed = 7;
    s.verts = 4;
    s.size = 100;
    s.polygons = 40;
    s.attributes = 6;
    s.fov_deg = 50;
    s.boids = 3;
    s.boid_polygons = 5;
    s.boid_colors = 2;
    s.well_structs = 2;
    s.well_polygons = 9;
    s.well_attributes = 3;
    s.figures = 2;
    s.structures = 11;
    s.levels = 4;
    return s;
}

/* Humans: each figure's root holds a REPLACE matrix, every joint below a
 * CONCATENATE one (so a joint moves with its parent); the figure is
 * exactly `levels` deep; structures and polygons add up to the spec. */
static void test_humans(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_HUMANS);
    ScenePphigsDb d;
    assert_true(scene_pphigs_generate(&s, &d, NULL));
    assert_int_equal(scene_db_struct_count(d.db), s.structures);
    assert_int_equal(scene_db_posted_count(d.db), s.figures);
    guint polys = 0;
    for (guint sid = 0; sid < scene_db_struct_count(d.db); sid++) {
        const SceneElem *m = scene_db_elem(d.db, sid, 0);
        assert_int_equal(m->kind, SCENE_EL_MATRIX);
        assert_int_equal(m->mode, scene_db_is_posted(d.db, sid)
                                      ? SCENE_MAT_REPLACE
                                      : SCENE_MAT_CONCAT);
        assert_int_equal(mesh_check_count_kind(d.db, sid, SCENE_EL_COLOR), 1);
        polys += mesh_check_count_kind(d.db, sid, SCENE_EL_POLYGON);
    }
    assert_int_equal(polys, s.polygons);
    for (guint f = 0; f < s.figures; f++) { /* figures side by side in x */
        const SceneElem *m = scene_db_elem(d.db, scene_db_posted_at(d.db, f), 0);
        Vec4 o = mat4_apply_point(m->matrix, vec3(0, 0, 0));
        assert_true(o.x == f * s.size / 2 && o.y == 0 && o.z == 0);
    }
    for (guint f = 0; f < s.figures; f++)
        assert_int_equal(scene_db_height(d.db, scene_db_posted_at(d.db, f)),
                         s.levels);
    SceneDbStats stats;
    scene_db_stats(d.db, &stats);
    assert_int_equal(stats.depth, s.levels);
    assert_int_equal(stats.primitives, s.polygons);
    scene_pphigs_db_clear(&d);
}

/* Station: one posted structure, a REPLACE matrix first, then
 * attributes - 1 objects each opened by a colour. */
static void test_station(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_STATION);
    ScenePphigsDb d;
    assert_true(scene_pphigs_generate(&s, &d, NULL));
    assert_int_equal(scene_db_struct_count(d.db), 1);
    const SceneElem *m = scene_db_elem(d.db, 0, 0);
    assert_int_equal(m->kind, SCENE_EL_MATRIX);
    assert_int_equal(m->mode, SCENE_MAT_REPLACE);
    assert_int_equal(scene_db_elem(d.db, 0, 1)->kind, SCENE_EL_COLOR);
    assert_int_equal(mesh_check_count_kind(d.db, 0, SCENE_EL_COLOR), s.attributes - 1);
    assert_int_equal(mesh_check_count_kind(d.db, 0, SCENE_EL_POLYGON), s.polygons);
    /* every polygon is regular: its corners at the object radius
     * (size / 80) from their centre */
    for (guint i = 0; i < scene_db_len(d.db, 0); i++) {
        const SceneElem *e = scene_db_elem(d.db, 0, i);
        if (e->kind != SCENE_EL_POLYGON)
            continue;
        assert_int_equal(e->nverts, s.verts);
        Vec3 c = vec3(0, 0, 0);
        for (guint k = 0; k < e->nverts; k++)
            c = vec3_add(c, vec3_scale(e->verts[k], 1.0 / e->nverts));
        for (guint k = 0; k < e->nverts; k++)
            assert_true(fabs(vec3_len(vec3_sub(e->verts[k], c)) -
                             s.size / 80) < 1e-9);
    }
    scene_pphigs_db_clear(&d);
}

/* Flock: the root executes the well's structures, then per boid a
 * REPLACE matrix and an execute of the primitive structure "boid". */
static void test_flock(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_FLOCK);
    ScenePphigsDb d;
    assert_true(scene_pphigs_generate(&s, &d, NULL));
    guint root = scene_db_posted_at(d.db, 0), boid;
    assert_true(scene_db_find(d.db, "boid", &boid));
    assert_true(scene_db_is_primitive(d.db, boid));
    assert_int_equal(scene_db_execute_count(d.db, root, boid), s.boids);
    assert_int_equal(mesh_check_count_kind(d.db, root, SCENE_EL_MATRIX), s.boids);
    assert_int_equal(mesh_check_count_kind(d.db, boid, SCENE_EL_COLOR), s.boid_colors);
    assert_int_equal(mesh_check_count_kind(d.db, boid, SCENE_EL_POLYGON),
                     s.boid_polygons);
    assert_int_equal(scene_db_elem(d.db, boid, 0)->kind, SCENE_EL_COLOR);
    for (guint i = 0; i < scene_db_len(d.db, root); i++) {
        const SceneElem *e = scene_db_elem(d.db, root, i);
        if (e->kind == SCENE_EL_MATRIX) {
            assert_int_equal(e->mode, SCENE_MAT_REPLACE);
            assert_int_equal(scene_db_elem(d.db, root, i + 1)->child, boid);
        }
    }
    SceneDbStats stats;
    scene_db_stats(d.db, &stats);
    assert_int_equal(stats.primitives,
                     s.well_polygons + s.boids * s.boid_polygons);
    assert_int_equal(stats.structures, 2 + s.well_structs);
    scene_pphigs_db_clear(&d);
}

typedef struct {
    ScenePphigsKind kind;
    guint *field;
    guint ok, bad;
} Limit;

/* Each limit of the spec at its edge: `ok` is generated, `bad` refused. */
static void test_limits(void **st)
{
    (void)st;
    ScenePphigsSpec s;
    const Limit lim[] = {
        {SCENE_PPHIGS_STATION, &s.verts, 3, 2},
        {SCENE_PPHIGS_STATION, &s.attributes, 41, 42},
        {SCENE_PPHIGS_LOBBY, &s.attributes, 2, 1},
        {SCENE_PPHIGS_FLOCK, &s.boid_colors, 1, 0},
        {SCENE_PPHIGS_FLOCK, &s.well_structs, 1, 0},
        {SCENE_PPHIGS_HUMANS, &s.structures, 8, 7},
        {SCENE_PPHIGS_HUMANS, &s.figures, 1, 0},
    };
    for (guint i = 0; i < G_N_ELEMENTS(lim); i++)
        for (int pass = 0; pass < 2; pass++) {
            s = spec(lim[i].kind);
            *lim[i].field = pass ? lim[i].bad : lim[i].ok;
            ScenePphigsDb d;
            GError *err = NULL;
            gboolean ok = scene_pphigs_generate(&s, &d, &err);
            if (ok != !pass)
                print_error("limit %u pass %d\n", i, pass);
            assert_int_equal(ok, !pass);
            if (ok)
                scene_pphigs_db_clear(&d);
            else
                g_error_free(err);
        }
    s = spec(SCENE_PPHIGS_HUMANS);
    s.levels = 1; /* a figure needs a spine and a joint */
    s.structures = 2;
    ScenePphigsDb d;
    assert_false(scene_pphigs_generate(&s, &d, NULL));
}

static void assert_vec(Vec3 a, double x, double y, double z)
{
    assert_true(fabs(a.x - x) < 1e-15 && fabs(a.y - y) < 1e-15 &&
                fabs(a.z - z) < 1e-15);
}

/* n = z: u = z x x = y, v = z x y = -x.  n = (0.9, sqrt 0.19, 0), at the
 * switch: a = y, u = n x y = (0, 0, 0.9) normalised = z, v = n x z =
 * (n.y, -0.9, 0); just under 0.9: a = x, u = n x x = (0, 0, -n.y)
 * normalised = -z, v = n x -z = (-n.y, n.x, 0). */
static void test_plane_basis(void **st)
{
    (void)st;
    Vec3 u, v;
    scene_pphigs_plane_basis(vec3(0, 0, 1), &u, &v);
    assert_vec(u, 0, 1, 0);
    assert_vec(v, -1, 0, 0);
    double y = sqrt(1 - 0.9 * 0.9);
    scene_pphigs_plane_basis(vec3(0.9, y, 0), &u, &v);
    assert_vec(u, 0, 0, 1);
    assert_vec(v, y, -0.9, 0);
    double x = nextafter(0.9, 0);
    scene_pphigs_plane_basis(vec3(x, y, 0), &u, &v);
    assert_vec(u, 0, 0, -1);
    assert_vec(v, -y, x, 0);
    scene_pphigs_plane_basis(vec3(-0.9, y, 0), &u, &v); /* |n.x| */
    assert_vec(u, 0, 0, -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_humans),
        cmocka_unit_test(test_station),
        cmocka_unit_test(test_flock),
        cmocka_unit_test(test_limits),
        cmocka_unit_test(test_plane_basis),
    };
    return cmocka_run_group_tests_name("pphigs_db", tests, NULL, NULL);
}
