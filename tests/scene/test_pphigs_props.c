/* test_pphigs_props.c — the geometry of seed 001's PPHIGS databases
 * (sim/scene/pphigs_db.c), which test_pphigs_db.c checks element by
 * element but not by place: every polygon regular and planar, of the
 * spec's size, its centre inside the region its generator draws from in
 * x, y and z; colours in [0.2, 1]; boids on their ring facing outwards;
 * a figure's joints turned both ways about z by at most a radian; the
 * overlay's panel and labels (exactly `overlays` of them) facing the eye
 * in the lower left; the off-screen test plane by plane; the standard
 * views.  Found unchecked by make mutate (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/pphigs_db.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static ScenePphigsSpec spec(ScenePphigsKind k)
{
    ScenePphigsSpec s = {0};
    s.kind = k;
    s.seed = 11;
    s.verts = 5;
    s.size = 40;
    s.polygons = 30;
    s.attributes = 4;
    s.fov_deg = 50;
    s.boids = 6;
    s.boid_polygons = 4;
    s.boid_colors = 2;
    s.well_structs = 2;
    s.well_polygons = 20;
    s.well_attributes = 3;
    s.figures = 2;
    s.structures = 12;
    s.levels = 3;
    return s;
}

static SceneDb *gen(const ScenePphigsSpec *s, SceneCamera *cam)
{
    ScenePphigsDb d;
    GError *err = NULL;
    gboolean ok = scene_pphigs_generate(s, &d, &err);
    if (!ok)
        print_error("%s\n", err->message);
    assert_true(ok);
    if (cam)
        *cam = d.camera;
    return d.db;
}

/* A regular planar polygon: its vertices at radius r about their mean,
 * equal sides, all in one plane.  Returns the centre. */
static Vec3 check_regular(const SceneElem *e, guint verts, double r)
{
    assert_int_equal(e->nverts, verts);
    Vec3 c = vec3(0, 0, 0);
    for (guint i = 0; i < verts; i++)
        c = vec3_add(c, e->verts[i]);
    c = vec3_scale(c, 1.0 / verts);
    Vec3 n = vec3_norm(vec3_cross(vec3_sub(e->verts[0], c),
                                  vec3_sub(e->verts[1], c)));
    double side = vec3_len(vec3_sub(e->verts[1], e->verts[0]));
    NEAR(side, 2 * r * sin(G_PI / verts), 1e-9 * r);
    for (guint i = 0; i < verts; i++) {
        NEAR(vec3_len(vec3_sub(e->verts[i], c)), r, 1e-9 * r);
        NEAR(vec3_dot(vec3_sub(e->verts[i], c), n), 0, 1e-9 * r);
        NEAR(vec3_len(vec3_sub(e->verts[(i + 1) % verts], e->verts[i])), side,
             1e-9 * r);
    }
    return c;
}

static void check_color(const SceneElem *e)
{
    assert_int_equal(e->kind, SCENE_EL_COLOR);
    assert_true(e->color.x >= 0.2 && e->color.x <= 1);
    assert_true(e->color.y >= 0.2 && e->color.y <= 1);
    assert_true(e->color.z >= 0.2 && e->color.z <= 1);
}

/* Station and lobby: objects' polygons of radius size/80 (size/120 for
 * the lobby) centred within r of the object centres, which are drawn in
 * the generator's box; tags 1, 2, 3 ... */
static void check_objects(SceneDb *db, guint sid, const ScenePphigsSpec *s,
                          Vec3 lo, Vec3 hi, double r)
{
    SceneBox seen = scene_box_empty(), obj = scene_box_empty();
    uint64_t tag = 1;
    double spread = 0;
    guint in_obj = 0;
    for (guint i = 1; i <= scene_db_len(db, sid); i++) {
        const SceneElem *e =
            i < scene_db_len(db, sid) ? scene_db_elem(db, sid, i) : NULL;
        if (!e || e->kind == SCENE_EL_COLOR) {
            /* an object's polygons spread over its [-r, r] cube on
             * every axis (over r: all of it, not one half) */
            Vec3 d = scene_box_size(obj);
            assert_true(in_obj < 8 || (d.x > r && d.y > r && d.z > r));
            obj = scene_box_empty();
            in_obj = 0;
            if (e)
                check_color(e);
            continue;
        }
        assert_int_equal(e->kind, SCENE_EL_POLYGON);
        assert_int_equal(e->tag, tag++);
        Vec3 c = check_regular(e, s->verts, r * 0.5);
        assert_true(c.x >= lo.x - r && c.x <= hi.x + r);
        assert_true(c.y >= lo.y - r && c.y <= hi.y + r);
        assert_true(c.z >= lo.z - r && c.z <= hi.z + r);
        seen = scene_box_add_point(seen, c);
        obj = scene_box_add_point(obj, c);
        in_obj++;
    }
    assert_int_equal(tag - 1, s->polygons);
    /* and (30 objects) they spread over the box: more than half of it on
     * each axis */
    Vec3 sz = scene_box_size(seen), want = vec3_sub(hi, lo);
    spread = fmin(sz.x / want.x, fmin(sz.y / want.y, sz.z / want.z));
    assert_true(s->attributes < 31 || spread > 0.5);
}

static void test_station_and_lobby(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_STATION);
    s.attributes = 31; /* 30 objects of one polygon */
    SceneCamera cam;
    SceneDb *db = gen(&s, &cam);
    assert_int_equal(scene_db_struct_count(db), 1);
    assert_string_equal(scene_db_struct_name(db, 0), "station");
    const SceneElem *m = scene_db_elem(db, 0, 0);
    assert_int_equal(m->kind, SCENE_EL_MATRIX);
    assert_int_equal(m->mode, SCENE_MAT_REPLACE);
    check_objects(db, 0, &s, vec3(-20, -5, -5), vec3(20, 5, 5), 1);
    scene_db_free(db);
    s.attributes = 3; /* 2 objects of 15 polygons */
    db = gen(&s, &cam);
    check_objects(db, 0, &s, vec3(-20, -5, -5), vec3(20, 5, 5), 1);
    /* the standard view: fitted to the structure's box, fill 0.9 */
    Vec3 c = scene_box_center(scene_db_struct_bbox(db, 0));
    NEAR(cam.target.x, c.x, 1e-9);
    NEAR(cam.target.y, c.y, 1e-9);
    NEAR(cam.target.z, c.z, 1e-9);
    scene_db_free(db);
    s = spec(SCENE_PPHIGS_LOBBY);
    s.attributes = 31;
    db = gen(&s, &cam);
    assert_string_equal(scene_db_struct_name(db, 0), "lobby");
    check_objects(db, 0, &s, vec3(-20, 0, -20), vec3(20, 20.0 / 3, 20),
                  40.0 / 60);
    /* the lobby's view stands in the room: eye at the back wall */
    assert_true(cam.eye.x == 0 && cam.eye.y == 20.0 / 6 && cam.eye.z == -20);
    assert_true(cam.target.x == 0 && cam.target.y == 20.0 / 6 &&
                cam.target.z == 20);
    assert_true(cam.fov_deg == 50 && cam.near == 0.04 && cam.far == 160);
    scene_db_free(db);
}

static void test_flock(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_FLOCK);
    SceneDb *db = gen(&s, NULL);
    guint root, boid, w0, w1;
    assert_true(scene_db_find(db, "flock", &root));
    assert_true(scene_db_find(db, "boid", &boid));
    assert_true(scene_db_find(db, "well_0", &w0));
    assert_true(scene_db_find(db, "well_1", &w1));
    assert_int_equal(scene_db_posted_count(db), 1);
    assert_int_equal(scene_db_posted_at(db, 0), root);
    assert_true(scene_db_is_primitive(db, boid));
    assert_false(scene_db_is_primitive(db, root));
    /* the root: the well's structures, then per boid a matrix and an
     * execute */
    assert_int_equal(scene_db_len(db, root), 2 + 2 * s.boids);
    assert_int_equal(scene_db_elem(db, root, 0)->child, w0);
    assert_int_equal(scene_db_elem(db, root, 1)->child, w1);
    double h = 20;
    for (guint b = 0; b < s.boids; b++) {
        const SceneElem *m = scene_db_elem(db, root, 2 + 2 * b);
        const SceneElem *x = scene_db_elem(db, root, 3 + 2 * b);
        assert_int_equal(m->kind, SCENE_EL_MATRIX);
        assert_int_equal(m->mode, SCENE_MAT_REPLACE);
        assert_int_equal(x->kind, SCENE_EL_EXECUTE);
        assert_int_equal(x->child, boid);
        Vec4 o = mat4_apply_point(m->matrix, vec3(0, 0, 0));
        double t = 2 * G_PI * b / s.boids, rad = hypot(o.x, o.z);
        assert_true(rad >= h / 3 - 1e-9 && rad <= h + 1e-9);
        assert_true(o.y >= 0 && o.y <= h / 2);
        NEAR(o.x, rad * cos(t), 1e-9);
        NEAR(o.z, rad * sin(t), 1e-9);
        /* the boid's +x points outwards along its ring radius */
        Vec4 ax = mat4_apply(m->matrix, (Vec4){1, 0, 0, 0});
        NEAR(ax.x, cos(t), 1e-9);
        NEAR(ax.y, 0, 1e-9);
        NEAR(ax.z, sin(t), 1e-9);
    }
    /* the boid: colours first and spread, polygons of radius 0.6 about
     * centres in [-1, 1] x [-0.3, 0.3] x [-1, 1] */
    guint colors = 0, polys = 0;
    for (guint i = 0; i < scene_db_len(db, boid); i++) {
        const SceneElem *e = scene_db_elem(db, boid, i);
        if (e->kind == SCENE_EL_COLOR) {
            check_color(e);
            colors++;
            continue;
        }
        Vec3 c = check_regular(e, s.verts, 0.6);
        assert_true(fabs(c.x) <= 1 && fabs(c.y) <= 0.3 && fabs(c.z) <= 1);
        polys++;
    }
    assert_int_equal(scene_db_elem(db, boid, 0)->kind, SCENE_EL_COLOR);
    assert_int_equal(scene_db_elem(db, boid, 3)->kind, SCENE_EL_COLOR);
    assert_int_equal(colors, 2);
    assert_int_equal(polys, 4);
    /* the well: polygons of radius h/40 within 1 in x, y and z of their
     * column, column `obj` (one per colour) standing on the ring of
     * radius h/8 at angle 2 pi obj / well_attributes, up to h/4 high */
    guint wp = 0, wc = 0;
    double lo[3][3], hi[3][3]; /* per column: offsets in x, y, z */
    for (guint j = 0; j < 9; j++) {
        lo[j / 3][j % 3] = HUGE_VAL;
        hi[j / 3][j % 3] = -HUGE_VAL;
    }
    for (guint k = 0; k < 2; k++) {
        guint w = k ? w1 : w0;
        for (guint i = 0; i < scene_db_len(db, w); i++) {
            const SceneElem *e = scene_db_elem(db, w, i);
            if (e->kind == SCENE_EL_COLOR) {
                wc++;
                continue;
            }
            Vec3 c = check_regular(e, s.verts, h / 40);
            double t = 2 * G_PI * (wc - 1) / 3;
            assert_true(fabs(c.x - h / 8 * cos(t)) <= 1 + 1e-9);
            assert_true(fabs(c.z - h / 8 * sin(t)) <= 1 + 1e-9);
            assert_true(c.y >= -1 - 1e-9 && c.y <= h / 4 + 1 + 1e-9);
            const double off[3] = {c.x - h / 8 * cos(t), c.y, c.z - h / 8 * sin(t)};
            for (guint a = 0; a < 3; a++) {
                lo[wc - 1][a] = fmin(lo[wc - 1][a], off[a]);
                hi[wc - 1][a] = fmax(hi[wc - 1][a], off[a]);
            }
            wp++;
        }
    }
    assert_int_equal(wp, 20);
    assert_int_equal(wc, 3);
    /* the offsets drawn from all of [-1, 1]: x and z both sides of the
     * column, y (about the column's one height) spread over more than 1 */
    for (guint j = 0; j < 3; j++)
        assert_true(lo[j][0] < -0.2 && hi[j][0] > 0.2 && lo[j][2] < -0.2 &&
                    hi[j][2] > 0.2 && hi[j][1] - lo[j][1] > 1);
    assert_int_equal(scene_db_len(db, w0), 1 + 10); /* share 1 of 3 colours */
    assert_int_equal(scene_db_len(db, w1), 2 + 10);
    scene_db_free(db);
}

/* Humans: a joint's matrix is translate(x in [-seg, seg], seg, 0) times a
 * turn about z by an angle in [-1, 1] radian, both signs drawn. */
static void test_humans_joints(void **st)
{
    (void)st;
    ScenePphigsSpec s = spec(SCENE_PPHIGS_HUMANS);
    s.figures = 3;
    s.structures = 30;
    s.polygons = 60;
    SceneCamera cam;
    SceneDb *db = gen(&s, &cam);
    /* the view is fitted to every figure, not the first only */
    assert_int_equal(scene_db_posted_count(db), 3);
    SceneBox all = scene_box_empty();
    for (guint i = 0; i < 3; i++)
        all = scene_box_union(
            all, scene_db_struct_bbox(db, scene_db_posted_at(db, i)));
    Vec3 mid = scene_box_center(all);
    NEAR(cam.target.x, mid.x, 1e-9);
    NEAR(cam.target.y, mid.y, 1e-9);
    NEAR(cam.target.z, mid.z, 1e-9);
    double seg = 2, lo = 9, hi = -9;
    guint roots = 0;
    for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
        const SceneElem *m = scene_db_elem(db, sid, 0);
        assert_int_equal(m->kind, SCENE_EL_MATRIX);
        check_color(scene_db_elem(db, sid, 1));
        for (guint i = 2; i < scene_db_len(db, sid); i++) {
            const SceneElem *e = scene_db_elem(db, sid, i);
            if (e->kind == SCENE_EL_EXECUTE)
                continue;
            Vec3 c = check_regular(e, s.verts, seg / 8);
            assert_true(fabs(c.x) <= seg / 4 && fabs(c.z) <= seg / 4);
            assert_true(c.y >= 0 && c.y <= seg);
        }
        if (m->mode == SCENE_MAT_REPLACE) { /* a figure's root */
            Vec4 o = mat4_apply_point(m->matrix, vec3(0, 0, 0));
            assert_true(o.x == roots * 20 && o.y == 0 && o.z == 0);
            roots++;
            continue;
        }
        Vec4 o = mat4_apply_point(m->matrix, vec3(0, 0, 0));
        assert_true(fabs(o.x) <= seg && o.y == seg && o.z == 0);
        double a = atan2(m->matrix.m[1][0], m->matrix.m[0][0]);
        assert_true(m->matrix.m[2][2] == 1 && fabs(a) <= 1 + 1e-12);
        lo = fmin(lo, a);
        hi = fmax(hi, a);
    }
    assert_int_equal(roots, 3);
    assert_true(lo < -0.3 && hi > 0.3); /* turned both ways */
    scene_db_free(db);
}

/* The overlay: a panel, then exactly `overlays` labels, each after its
 * colour; all quads lie on one plane facing the eye, in the lower left
 * of the view; the labels overlap the panel. */
static void test_overlay(void **st)
{
    (void)st;
    for (ScenePphigsKind k = 0; k < SCENE_PPHIGS_NKINDS; k++) {
        ScenePphigsSpec s = spec(k);
        s.overlays = 3;
        SceneCamera cam;
        SceneDb *db = gen(&s, &cam);
        guint ov;
        assert_true(scene_db_find(db, "overlay", &ov));
        assert_int_equal(scene_db_posted_at(db, scene_db_posted_count(db) - 1),
                         ov);
        assert_int_equal(scene_db_len(db, ov), 2 + 2 * 3);
        Mat4 vp = scene_camera_view_proj(&cam);
        Vec3 f = vec3_norm(vec3_sub(cam.target, cam.eye));
        double depth = -1;
        for (guint i = 0; i < 8; i++) {
            const SceneElem *e = scene_db_elem(db, ov, i);
            if (i % 2 == 0) {
                check_color(e);
                continue;
            }
            assert_int_equal(e->kind, SCENE_EL_POLYGON2D);
            assert_int_equal(e->nverts, 4);
            Vec3 c = vec3(0, 0, 0);
            for (guint v = 0; v < 4; v++) {
                double d = vec3_dot(vec3_sub(e->verts[v], cam.eye), f);
                if (depth < 0)
                    depth = d;
                NEAR(d, depth, 1e-9 * depth);
                c = vec3_add(c, vec3_scale(e->verts[v], 0.25));
            }
            assert_true(depth > cam.near);
            Vec4 q = mat4_apply_point(vp, c);
            if (i == 1) { /* the panel: centred half-way to the corner */
                NEAR(q.x / q.w, -0.5 / cam.aspect, 1e-9);
                NEAR(q.y / q.w, -0.5, 1e-9);
            }
            assert_true(q.x / q.w < 0 && q.y / q.w < 0);
            assert_true(q.x / q.w > -1 && q.y / q.w > -1);
            /* a rectangle: opposite sides equal, a right angle */
            Vec3 a = vec3_sub(e->verts[1], e->verts[0]);
            Vec3 b = vec3_sub(e->verts[3], e->verts[0]);
            NEAR(vec3_dot(a, b), 0, 1e-9 * depth * depth);
            NEAR(vec3_len(vec3_sub(e->verts[2], e->verts[3])), vec3_len(a),
                 1e-9 * depth);
        }
        scene_db_free(db);
    }
}

/* One vertex per case: a polygon is off-screen when all its vertices lie
 * beyond one plane of the clip cube; an ODP ignores near and far. */
static gboolean off(SceneElemKind kind, Vec3 a, Vec3 b, Vec3 c)
{
    Vec3 p[3] = {a, b, c};
    SceneElem e = scene_elem_prim(kind, p, 3);
    return scene_pphigs_prim_offscreen(mat4_identity(), &e);
}

static void test_offscreen(void **st)
{
    (void)st;
    const SceneElemKind P = SCENE_EL_POLYGON, O = SCENE_EL_POLYGON2D;
    for (int axis = 0; axis < 3; axis++)
        for (int sign = -1; sign <= 1; sign += 2) {
            double v[3] = {0, 0, 0};
            v[axis] = 1.5 * sign;
            Vec3 a = vec3(v[0], v[1], v[2]);
            Vec3 b = vec3_add(a, vec3(axis ? 0.3 : 0, axis ? 0 : 0.3, 0));
            Vec3 c = vec3_add(a, vec3(0, axis == 1 ? 0 : -0.4,
                                      axis == 1 ? 0.2 : 0));
            assert_true(off(P, a, b, c));
            assert_true(off(O, a, b, c) == (axis < 2));
            /* on the plane itself: inside */
            v[axis] = sign;
            Vec3 on = vec3(v[0], v[1], v[2]);
            assert_false(off(P, on, on, on));
        }
    /* beyond different planes: a triangle that may cross the screen */
    assert_false(off(P, vec3(2, 0, 0), vec3(0, -2, 0), vec3(2, -2, 0)));
    assert_false(off(P, vec3(-2, 0, 0), vec3(0, 2, 0), vec3(0, 0, 2)));
    assert_false(off(P, vec3(0, 0, 0), vec3(0, 0, 0), vec3(0, 0, 0)));
    /* and under a matrix: translated off to the right */
    Vec3 p[3] = {vec3(0, 0, 0), vec3(0.5, 0, 0), vec3(0, 0.5, 0)};
    SceneElem e = scene_elem_prim(P, p, 3);
    assert_true(scene_pphigs_prim_offscreen(mat4_translate(1.01, 0, 0), &e));
    assert_false(scene_pphigs_prim_offscreen(mat4_translate(0.99, 0, 0), &e));
}

/* The share of primitive instances off-screen. */
static void test_offscreen_share(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    assert_true(scene_pphigs_offscreen_share(db, mat4_identity()) == 0);
    guint sid = scene_db_add_struct(db, "s");
    for (int i = 0; i < 4; i++) {
        Vec3 p[3] = {vec3(i == 3 ? 5 : 0, 0, 0), vec3(i == 3 ? 6 : 0.1, 0, 0),
                     vec3(i == 3 ? 5 : 0, 0.1, 0)};
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, p, 3);
        assert_true(scene_db_append(db, sid, &e, NULL));
    }
    scene_db_post(db, sid);
    assert_true(scene_pphigs_offscreen_share(db, mat4_identity()) == 0.25);
    assert_true(scene_pphigs_offscreen_share(db, mat4_translate(-5, 0, 0)) ==
                0.75);
    scene_db_free(db);
}

static void test_names_and_spec(void **st)
{
    (void)st;
    const char *names[] = {"space_station", "building_lobby",
                           "flock_old_well", "two_human_figures"};
    for (ScenePphigsKind k = 0; k < SCENE_PPHIGS_NKINDS; k++) {
        assert_string_equal(scene_pphigs_kind_name(k), names[k]);
        ScenePphigsKind got = SCENE_PPHIGS_NKINDS;
        assert_true(scene_pphigs_kind_parse(names[k], &got));
        assert_int_equal(got, k);
    }
    /* a database with nothing posted: the default camera */
    SceneDb *empty = scene_db_new();
    scene_db_add_struct(empty, "unposted");
    SceneCamera fv = scene_pphigs_fit_view(empty), def = scene_camera_default();
    assert_true(fv.proj == def.proj && fv.eye.z == def.eye.z &&
                fv.target.z == def.target.z && fv.fov_deg == def.fov_deg &&
                fv.near == def.near && fv.far == def.far);
    scene_db_free(empty);
    ScenePphigsKind got = SCENE_PPHIGS_FLOCK;
    assert_false(scene_pphigs_kind_parse("space", &got));
    assert_int_equal(got, SCENE_PPHIGS_FLOCK);
    ScenePphigsSpec s = spec(SCENE_PPHIGS_NKINDS);
    ScenePphigsDb d;
    GError *err = NULL;
    assert_false(scene_pphigs_generate(&s, &d, &err));
    assert_string_equal(err->message, "found an unknown database kind, "
                                      "expected one of four");
    g_clear_error(&err);
    /* the scene: one white instance of the flattened database, two-sided,
     * the database's view */
    s = spec(SCENE_PPHIGS_STATION);
    Scene *sc = scene_pphigs_scene_new(&s, &err);
    assert_non_null(sc);
    assert_int_equal(scene_n_instances(sc), 1);
    SceneColor w = scene_instance(sc, 0)->color;
    assert_true(w.r == 1 && w.g == 1 && w.b == 1);
    assert_true(sc->two_sided);
    assert_int_equal(scene_n_polys(sc), 30);
    SceneCamera cam;
    SceneDb *db = gen(&s, &cam);
    assert_true(sc->camera.eye.x == cam.eye.x && sc->camera.eye.z == cam.eye.z &&
                sc->camera.far == cam.far);
    scene_db_free(db);
    scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_station_and_lobby),
        cmocka_unit_test(test_flock),
        cmocka_unit_test(test_humans_joints),
        cmocka_unit_test(test_overlay),
        cmocka_unit_test(test_offscreen),
        cmocka_unit_test(test_offscreen_share),
        cmocka_unit_test(test_names_and_spec),
    };
    return cmocka_run_group_tests_name("pphigs_props", tests, NULL, NULL);
}
