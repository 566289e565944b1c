/* test_pphigs_spread.c — where sim/scene/pphigs_db.c's random draws land,
 * over many draws: polygon normals spread evenly over the sphere (no
 * axis or sign favoured) and each polygon's first corner along n x a
 * (a = x unless n is near x, then y); station and lobby objects,
 * boid polygons, boid placements,
 * figure joints and figure polygons, and overlay labels fill their whole
 * ranges on both sides; an Old Well of one colour over two structures
 * keeps the uncoloured structure's polygons on the one column, and one
 * of no colour keeps them all there.
 * test_pphigs_props.c checks that every draw is inside its range; this
 * one that the ranges are the spec's, not narrower or shifted. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/pphigs_db.h"

/* Large counts, so that each range is drawn from many times. */
static ScenePphigsSpec spec(ScenePphigsKind k)
{
    return (ScenePphigsSpec){
        .kind = k, .seed = 5, .verts = 4, .size = 40, .fov_deg = 50,
        .polygons = 400, .attributes = 5, /* station, lobby */
        .boids = 80, .boid_polygons = 80, .boid_colors = 1, /* flock */
        .well_structs = 2, .well_polygons = 40, .well_attributes = 1,
        .figures = 1, .structures = 40, .levels = 3, /* humans */
    };
}

static SceneDb *gen(const ScenePphigsSpec *s, SceneCamera *cam)
{
    ScenePphigsDb d = {NULL, scene_camera_default()};
    GError *err = NULL;
    if (!scene_pphigs_generate(s, &d, &err))
        fail_msg("%s", err->message);
    if (cam != NULL)
        *cam = d.camera;
    return d.db;
}

static Vec3 centre(const SceneElem *e)
{
    Vec3 c = vec3(0, 0, 0);
    for (guint i = 0; i < e->nverts; i++)
        c = vec3_add(c, vec3_scale(e->verts[i], 1.0 / e->nverts));
    return c;
}

typedef struct {
    Vec3 lo, hi;
} Range;

static Range range_new(void)
{
    return (Range){vec3(HUGE_VAL, HUGE_VAL, HUGE_VAL),
                   vec3(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL)};
}

static void range_add(Range *r, Vec3 p)
{
    r->lo = vec3(fmin(r->lo.x, p.x), fmin(r->lo.y, p.y), fmin(r->lo.z, p.z));
    r->hi = vec3(fmax(r->hi.x, p.x), fmax(r->hi.y, p.y), fmax(r->hi.z, p.z));
}

/* Every range's ends within `slack` of [lo, hi] on each axis. */
static void fills(const Range *r, Vec3 lo, Vec3 hi, double slack)
{
    const double got[6] = {r->lo.x, r->lo.y, r->lo.z, r->hi.x, r->hi.y, r->hi.z};
    const double want[6] = {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z};
    for (int i = 0; i < 6; i++)
        if (fabs(got[i] - want[i]) > slack)
            fail_msg("end %d: %g, expected %g within %g", i, got[i], want[i],
                     slack);
}

/* Station polygons: normals even over the sphere; first corner along
 * n x a. */
static void test_polygon_orientation(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_STATION);
    SceneDb *db = gen(&s, NULL);
    Vec3 sum = vec3(0, 0, 0);
    Range nr = range_new();
    guint n = 0;
    for (guint i = 0; i < scene_db_len(db, 0); i++) {
        const SceneElem *e = scene_db_elem(db, 0, i);
        if (e->kind != SCENE_EL_POLYGON)
            continue;
        Vec3 c = centre(e), p0 = vec3_sub(e->verts[0], c);
        Vec3 nn = vec3_norm(vec3_cross(p0, vec3_sub(e->verts[1], c)));
        Vec3 a = fabs(nn.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0);
        Vec3 u = vec3_norm(vec3_cross(nn, a));
        Vec3 d = vec3_sub(vec3_norm(p0), u);
        if (vec3_len(d) > 1e-9)
            fail_msg("polygon %u: first corner off n x a by %g", n, vec3_len(d));
        sum = vec3_add(sum, nn);
        range_add(&nr, nn);
        n++;
    }
    assert_int_equal(n, 400);
    /* the mean normal of 400 even draws: about 0.03 on each axis */
    assert_true(fabs(sum.x / n) < 0.12 && fabs(sum.y / n) < 0.12 &&
                fabs(sum.z / n) < 0.12);
    fills(&nr, vec3(-1, -1, -1), vec3(1, 1, 1), 0.1);
    scene_db_free(db);
}

/* Station and lobby objects: polygon centres over the generator's box
 * widened by the object radius r (station [-h, h] x [-h/4, h/4]^2,
 * r = size/40; lobby [-h, h] x [0, h/3] x [-h, h], r = size/60). */
static void test_object_ranges(void **st)
{
    (void)st;
    for (int lobby = 0; lobby < 2; lobby++) {
        ScenePphigsSpec s = spec(lobby ? SCENE_PPHIGS_LOBBY : SCENE_PPHIGS_STATION);
        s.attributes = 201; /* 200 objects of 2 polygons */
        SceneDb *db = gen(&s, NULL);
        Range r = range_new();
        for (guint i = 0; i < scene_db_len(db, 0); i++)
            if (scene_db_elem(db, 0, i)->kind == SCENE_EL_POLYGON)
                range_add(&r, centre(scene_db_elem(db, 0, i)));
        double rr = lobby ? 40.0 / 60 : 1;
        Vec3 lo = lobby ? vec3(-20, 0, -20) : vec3(-20, -5, -5);
        Vec3 hi = lobby ? vec3(20, 20.0 / 3, 20) : vec3(20, 5, 5);
        const double got[6] = {r.lo.x, r.lo.y, r.lo.z, r.hi.x, r.hi.y, r.hi.z};
        const double want[6] = {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z};
        for (int k = 0; k < 6; k++) {
            double sign = k < 3 ? -1 : 1;
            /* within r outside the box, and reaching past r/2 inside it */
            assert_true(sign * (got[k] - want[k]) <= rr + 1e-9);
            if (sign * (got[k] - want[k]) < -rr / 2)
                fail_msg("lobby %d end %d: %g, box %g", lobby, k, got[k],
                         want[k]);
        }
        scene_db_free(db);
    }
}

static void test_flock_ranges(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_FLOCK);
    SceneDb *db = gen(&s, NULL);
    guint root, boid, w0, w1;
    assert_true(scene_db_find(db, "flock", &root) &&
                scene_db_find(db, "boid", &boid));
    assert_true(scene_db_find(db, "well_0", &w0) &&
                scene_db_find(db, "well_1", &w1));
    /* boid polygons: centres over [-1, 1] x [-0.3, 0.3] x [-1, 1] */
    Range r = range_new();
    for (guint i = 0; i < scene_db_len(db, boid); i++) {
        const SceneElem *e = scene_db_elem(db, boid, i);
        if (e->kind == SCENE_EL_POLYGON)
            range_add(&r, centre(e));
    }
    fills(&r, vec3(-1, -0.3, -1), vec3(1, 0.3, 1), 0.12);
    /* boids: ring radius over [h/3, h], height over [0, h/2] (h = 20) */
    double rlo = HUGE_VAL, rhi = 0, ylo = HUGE_VAL, yhi = 0;
    for (guint i = 0; i < scene_db_len(db, root); i++) {
        const SceneElem *e = scene_db_elem(db, root, i);
        if (e->kind != SCENE_EL_MATRIX)
            continue;
        Vec4 o = mat4_apply_point(e->matrix, vec3(0, 0, 0));
        double rad = hypot(o.x, o.z);
        rlo = fmin(rlo, rad), rhi = fmax(rhi, rad);
        ylo = fmin(ylo, o.y), yhi = fmax(yhi, o.y);
    }
    assert_true(rlo < 20.0 / 3 + 1 && rhi > 19 && ylo < 0.5 && yhi > 9.5);
    assert_true(rlo >= 20.0 / 3 && rhi <= 20 && ylo >= 0 && yhi <= 10);
    /* one colour over two structures: well_0 has none, yet its share of
     * the polygons, on the one column at angle 0 (x = h/8, z = 0) */
    assert_int_equal(scene_db_len(db, w0), 20);
    assert_int_equal(scene_db_len(db, w1), 1 + 20);
    for (guint k = 0; k < 2; k++) {
        guint w = k ? w1 : w0;
        double ylo = HUGE_VAL, yhi = -HUGE_VAL; /* one object: one height */
        for (guint i = k; i < scene_db_len(db, w); i++) {
            Vec3 c = centre(scene_db_elem(db, w, i));
            assert_true(fabs(c.x - 2.5) <= 1 + 1e-9 && fabs(c.z) <= 1 + 1e-9);
            ylo = fmin(ylo, c.y), yhi = fmax(yhi, c.y);
        }
        assert_true(yhi - ylo <= 2 + 1e-9 && yhi - ylo > 1.5);
    }
    scene_db_free(db);
    /* no colour at all: the polygons still stand on the column at 0 */
    s.well_attributes = 0;
    db = gen(&s, NULL);
    assert_true(scene_db_find(db, "well_0", &w0));
    for (guint i = 0; i < scene_db_len(db, w0); i++) {
        Vec3 c = centre(scene_db_elem(db, w0, i));
        assert_true(fabs(c.x - 2.5) <= 1 + 1e-9 && fabs(c.z) <= 1 + 1e-9);
    }
    scene_db_free(db);
}

/* Boid colours spread as the shares of the later elements fall:
 * 3 colours among 8 elements stand at 0, 2 and 5; and the smallest
 * figure (2 levels: a spine and a joint) is a figure like any other. */
static void test_layouts(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_FLOCK);
    s.boid_colors = 3;
    s.boid_polygons = 5;
    SceneDb *db = gen(&s, NULL);
    guint boid;
    assert_true(scene_db_find(db, "boid", &boid));
    assert_int_equal(scene_db_len(db, boid), 8);
    for (guint i = 0; i < 8; i++)
        assert_int_equal(scene_db_elem(db, boid, i)->kind == SCENE_EL_COLOR,
                         i == 0 || i == 2 || i == 5);
    scene_db_free(db);
    s = spec(SCENE_PPHIGS_HUMANS);
    s.levels = 2;
    s.structures = 2;
    db = gen(&s, NULL);
    assert_int_equal(scene_db_height(db, scene_db_posted_at(db, 0)), 2);
    scene_db_free(db);
}

/* One figure of 8 structures, 4 levels: the chain 0-1-2-3, then 4..7
 * hung round-robin under chain members 0, 1, 2, 0; structure k holds
 * share(k) of the 7 polygons (0, 1, 1, 1, 1, 1, 1, 1). */
static void test_figure_tree(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_HUMANS);
    s.levels = 4;
    s.structures = 8;
    s.polygons = 7;
    SceneDb *db = gen(&s, NULL);
    const guint parent[8] = {0, 0, 1, 2, 0, 1, 2, 0};
    for (guint i = 1; i < 8; i++)
        for (guint p = 0; p < 8; p++)
            assert_int_equal(scene_db_execute_count(db, p, i),
                             p == parent[i]);
    for (guint k = 0; k < 8; k++) {
        guint polys = 0;
        for (guint i = 0; i < scene_db_len(db, k); i++)
            polys += scene_db_elem(db, k, i)->kind == SCENE_EL_POLYGON;
        assert_int_equal(polys, k > 0);
    }
    scene_db_free(db);
}

/* A primitive spanning the clip cube between two opposite planes (one
 * vertex beyond each) is on screen: each plane has its own bit. */
static void test_offscreen_spans(void **st)
{
    (void)st;
    for (int axis = 0; axis < 3; axis++) {
        double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
        a[axis] = -2, b[axis] = 2;
        Vec3 p[3] = {vec3(a[0], a[1], a[2]), vec3(b[0], b[1], b[2]),
                     vec3(0.1, 0.1, 0.1)};
        p[2] = vec3_add(p[1], vec3(axis ? 0.1 : 0, axis ? 0 : 0.1, 0));
        SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, p, 3);
        assert_false(scene_pphigs_prim_offscreen(mat4_identity(), &e));
        /* and both beyond the same plane: off */
        p[0] = p[1];
        p[0].x += 0.05;
        e = scene_elem_prim(SCENE_EL_POLYGON, p, 3);
        assert_true(scene_pphigs_prim_offscreen(mat4_identity(), &e));
    }
    /* each pair of planes across axes too: right and above, left and far */
    Vec3 q[3] = {vec3(2, 0, 0), vec3(0, 2, 0), vec3(2, 2, 0)};
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, q, 3);
    assert_false(scene_pphigs_prim_offscreen(mat4_identity(), &e));
    Vec3 r[3] = {vec3(-2, 0, 0), vec3(0, 0, 2), vec3(-2, 0, 2)};
    e = scene_elem_prim(SCENE_EL_POLYGON, r, 3);
    assert_false(scene_pphigs_prim_offscreen(mat4_identity(), &e));
    Vec3 t[3] = {vec3(0, -2, 0), vec3(0, 0, -2), vec3(0, -2, -2)};
    e = scene_elem_prim(SCENE_EL_POLYGON, t, 3);
    assert_false(scene_pphigs_prim_offscreen(mat4_identity(), &e));
}

/* Figures: joints shifted over [-seg, seg] in x, polygons centred over
 * [-seg/4, seg/4] x [0, seg] x [-seg/4, seg/4] (seg = size / 20 = 2). */
static void test_figure_ranges(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_HUMANS);
    SceneDb *db = gen(&s, NULL);
    Range r = range_new();
    double xlo = HUGE_VAL, xhi = -HUGE_VAL;
    for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
        const SceneElem *m = scene_db_elem(db, sid, 0);
        if (m->mode == SCENE_MAT_CONCAT) {
            double x = mat4_apply_point(m->matrix, vec3(0, 0, 0)).x;
            xlo = fmin(xlo, x), xhi = fmax(xhi, x);
        }
        for (guint i = 2; i < scene_db_len(db, sid); i++)
            if (scene_db_elem(db, sid, i)->kind == SCENE_EL_POLYGON)
                range_add(&r, centre(scene_db_elem(db, sid, i)));
    }
    assert_true(xlo < -1.5 && xhi > 1.5);
    fills(&r, vec3(-0.5, 0, -0.5), vec3(0.5, 2, 0.5), 0.15);
    scene_db_free(db);
}

/* Overlay labels: centres over +-0.45 h across and +-0.35 h up about the
 * panel's centre; half-sides over [0.05, 0.12] h and [0.02, 0.05] h. */
static void test_overlay_ranges(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_STATION);
    s.overlays = 60;
    SceneCamera cam;
    SceneDb *db = gen(&s, &cam);
    guint ov;
    assert_true(scene_db_find(db, "overlay", &ov));
    const SceneElem *panel = scene_db_elem(db, ov, 1);
    Vec3 pc = centre(panel);
    Vec3 rx = vec3_sub(panel->verts[1], panel->verts[0]); /* 2 a along r */
    Vec3 uy = vec3_sub(panel->verts[3], panel->verts[0]); /* 2 b along up */
    double h = vec3_len(rx) / 0.8; /* the panel: a = 0.4 h */
    assert_true(fabs(vec3_len(uy) - 0.6 * h) < 1e-9 * h);
    rx = vec3_norm(rx), uy = vec3_norm(uy);
    double lo[4] = {HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL};
    double hi[4] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (guint i = 3; i < scene_db_len(db, ov); i += 2) {
        const SceneElem *e = scene_db_elem(db, ov, i);
        Vec3 d = vec3_sub(centre(e), pc);
        const double v[4] = {
            vec3_dot(d, rx) / h, vec3_dot(d, uy) / h,
            vec3_len(vec3_sub(e->verts[1], e->verts[0])) / 2 / h,
            vec3_len(vec3_sub(e->verts[3], e->verts[0])) / 2 / h};
        for (int k = 0; k < 4; k++)
            lo[k] = fmin(lo[k], v[k]), hi[k] = fmax(hi[k], v[k]);
    }
    const double wlo[4] = {-0.45, -0.35, 0.05, 0.02};
    const double whi[4] = {0.45, 0.35, 0.12, 0.05};
    for (int k = 0; k < 4; k++) {
        assert_true(lo[k] >= wlo[k] - 1e-9 && hi[k] <= whi[k] + 1e-9);
        assert_true(lo[k] < wlo[k] + 0.15 * (whi[k] - wlo[k]) &&
                    hi[k] > whi[k] - 0.15 * (whi[k] - wlo[k]));
    }
    scene_db_free(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_polygon_orientation),
        cmocka_unit_test(test_object_ranges),
        cmocka_unit_test(test_flock_ranges),
        cmocka_unit_test(test_layouts),
        cmocka_unit_test(test_figure_tree),
        cmocka_unit_test(test_offscreen_spans),
        cmocka_unit_test(test_figure_ranges),
        cmocka_unit_test(test_overlay_ranges),
    };
    return cmocka_run_group_tests_name("pphigs_spread", tests, NULL, NULL);
}
