/* test_vehicle_parts.c — the parts of the procedural vehicle
 * (sim/scene/vehicle.c) one by one, against the shapes worked out from
 * its part list: every body triangle on a face of one of the two boxes
 * and wound outwards; every tube, ellipsoid band and tyre sector vertex
 * on its surface (centre, axis and radii by hand from the part's index),
 * each closed surface drawn all the way round and every triangle wound
 * to face outwards; the largest-remainder
 * budgets exact (T - 2n split by weight: body 1.5, chassis 0.6, tyre 2,
 * hub 1, interior 1, trim 0.4); the copies' placement matrices and the
 * orbiting camera exact.  Found unchecked by make mutate
 * (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim/scene/vehicle.h"

#define TOL 1e-9

enum { BODY, CHASSIS, WHEELS, INTERIOR, TRIM };
static const char *const group[5] = {"body", "chassis", "wheels", "interior",
                                     "trim"};

/* The vertices of structure sid (triangles only) into v; their count. */
static guint verts_of(const SceneDb *db, guint sid, GArray *v)
{
    g_array_set_size(v, 0);
    for (guint i = 0; i < scene_db_len(db, sid); i++) {
        const SceneElem *e = scene_db_elem(db, sid, i);
        if (e->kind == SCENE_EL_TRIANGLE)
            g_array_append_vals(v, e->verts, e->nverts);
    }
    return v->len;
}

/* Group and part index of a part structure "group.i"; FALSE otherwise. */
static gboolean part_of(const char *name, int *g, guint *i)
{
    for (int k = 0; k < 5; k++) {
        size_t n = strlen(group[k]);
        if (strncmp(name, group[k], n) == 0 && name[n] == '.') {
            *g = k;
            *i = (guint)atoi(name + n + 1);
            return TRUE;
        }
    }
    return FALSE;
}

/* ---- surfaces ---------------------------------------------------------- */

/* Triangle t's normal (by its winding) points along out, the outward
 * direction of the surface at the triangle's centroid d (relative to the
 * part's centre) that out() computes. */
static void wound_out(const GArray *v, Vec3 c, const void *arg,
                      Vec3 (*out)(Vec3 d, const void *arg))
{
    for (guint i = 0; i + 2 < v->len; i += 3) {
        const Vec3 *t = &g_array_index(v, Vec3, i);
        Vec3 n = vec3_cross(vec3_sub(t[1], t[0]), vec3_sub(t[2], t[0]));
        Vec3 d = vec3_sub(vec3_scale(vec3_add(vec3_add(t[0], t[1]), t[2]),
                                     1.0 / 3),
                          c);
        if (!(vec3_dot(n, out(d, arg)) > 0))
            fail_msg("part at (%g, %g, %g): triangle %u wound inwards", c.x,
                     c.y, c.z, i / 3);
    }
}

static Vec3 tube_out(Vec3 d, const void *axis)
{
    return *(const char *)axis == 'x' ? vec3(0, d.y, d.z) : vec3(d.x, d.y, 0);
}

static Vec3 ellipsoid_out(Vec3 d, const void *radii)
{
    const Vec3 *a = radii; /* the gradient of the ellipsoid's equation */
    return vec3(d.x / (a->x * a->x), d.y / (a->y * a->y), d.z / (a->z * a->z));
}

static Vec3 torus_out(Vec3 d, const void *unused)
{
    (void)unused;
    double rho = hypot(d.x, d.y); /* minus the tube's centre circle */
    return vec3_sub(d, vec3(0.28 * d.x / rho, 0.28 * d.y / rho, 0));
}

/* Every vertex at distance r from the axis through c along unit z or x
 * (axis 'x' or 'z'), within half the length h of c along it, and the
 * tube drawn all the way round (both cross directions span over 1.2 r: at most r for a half tube). */
static void on_tube(const GArray *v, Vec3 c, char axis, double h, double r)
{
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    double alo = HUGE_VAL, ahi = -HUGE_VAL;
    for (guint i = 0; i < v->len; i++) {
        Vec3 d = vec3_sub(g_array_index(v, Vec3, i), c);
        double along = axis == 'x' ? d.x : d.z;
        double p[2] = {d.y, axis == 'x' ? d.z : d.x};
        assert_true(fabs(along) <= h + TOL);
        alo = fmin(alo, along);
        ahi = fmax(ahi, along);
        if (fabs(hypot(p[0], p[1]) - r) > TOL)
            fail_msg("tube at (%g, %g, %g): vertex %u off radius %g", c.x, c.y,
                     c.z, i, r);
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], p[k]);
            hi[k] = fmax(hi[k], p[k]);
        }
    }
    wound_out(v, c, &axis, tube_out);
    assert_true(fabs(alo + h) < TOL && fabs(ahi - h) < TOL); /* end to end */
    if (!(hi[0] - lo[0] > 1.2 * r && hi[1] - lo[1] > 1.2 * r))
        fail_msg("tube at (%g, %g, %g): across %g and %g, radius %g", c.x, c.y,
                 c.z, hi[0] - lo[0], hi[1] - lo[1], r);
}

/* Every vertex on the ellipsoid of centre c and radii a, the band drawn
 * all the way round in x and z and both sides of c in y. */
static void on_ellipsoid(const GArray *v, Vec3 c, Vec3 a)
{
    Vec3 lo = vec3(HUGE_VAL, HUGE_VAL, HUGE_VAL), hi = vec3_scale(lo, -1);
    for (guint i = 0; i < v->len; i++) {
        Vec3 d = vec3_sub(g_array_index(v, Vec3, i), c);
        double s = (d.x / a.x) * (d.x / a.x) + (d.y / a.y) * (d.y / a.y) +
                   (d.z / a.z) * (d.z / a.z);
        if (fabs(s - 1) > TOL)
            fail_msg("ellipsoid at (%g, %g, %g): vertex %u at %g", c.x, c.y,
                     c.z, i, s);
        lo = vec3(fmin(lo.x, d.x), fmin(lo.y, d.y), fmin(lo.z, d.z));
        hi = vec3(fmax(hi.x, d.x), fmax(hi.y, d.y), fmax(hi.z, d.z));
    }
    wound_out(v, c, &a, ellipsoid_out);
    /* latitudes -0.45 pi to 0.45 pi, both reached */
    assert_true(fabs(hi.y - a.y * sin(0.45 * G_PI)) < TOL);
    assert_true(fabs(lo.y + a.y * sin(0.45 * G_PI)) < TOL);
    assert_true(lo.x < -0.5 * a.x && hi.x > 0.5 * a.x);
    assert_true(lo.z < -0.5 * a.z && hi.z > 0.5 * a.z);
    assert_true(lo.y < -0.5 * a.y && hi.y > 0.5 * a.y);
}

/* Sector j of `sectors` of the tyre torus (R 0.28, r 0.12) about c in
 * the xy plane: every vertex on the torus, at an angle about c inside
 * the sector, the tube drawn all the way round (both sides in z). */
static void on_sector(const GArray *v, Vec3 c, guint j, guint sectors)
{
    double a0 = 2 * G_PI * j / sectors, a1 = 2 * G_PI * (j + 1) / sectors;
    double zlo = HUGE_VAL, zhi = -HUGE_VAL, alo = HUGE_VAL, ahi = -HUGE_VAL;
    for (guint i = 0; i < v->len; i++) {
        Vec3 d = vec3_sub(g_array_index(v, Vec3, i), c);
        double rho = hypot(d.x, d.y) - 0.28;
        assert_true(fabs(rho * rho + d.z * d.z - 0.12 * 0.12) < TOL);
        double ang = atan2(d.y, d.x);
        while (ang < a0 - 1e-6)
            ang += 2 * G_PI;
        if (ang > a1 + 1e-6)
            fail_msg("sector %u of %u: vertex at %g rad, not in [%g, %g]", j,
                     sectors, ang, a0, a1);
        alo = fmin(alo, ang);
        ahi = fmax(ahi, ang);
        zlo = fmin(zlo, d.z);
        zhi = fmax(zhi, d.z);
    }
    wound_out(v, c, NULL, torus_out);
    assert_true(fabs(alo - a0) < 1e-6 && fabs(ahi - a1) < 1e-6); /* whole */
    assert_true(zlo < -0.1 && zhi > 0.1);
}

/* ---- the parts --------------------------------------------------------- */

/* Body panels: the 5 faces (no bottom) of boxes [-2.1, 2.1] x [0.5,
 * 1.2] x [-0.95, 0.95] and [-1.9, 0.4] x [1.2, 1.85] x [-0.9, 0.9]:
 * each triangle lies in a face plane and faces out of its box. */
static void body_tri(const Vec3 *t)
{
    Vec3 n = vec3_norm(vec3_cross(vec3_sub(t[1], t[0]), vec3_sub(t[2], t[0])));
    double pos[3] = {t[0].x, t[0].y, t[0].z}, nn[3] = {n.x, n.y, n.z};
    /* outward face values per axis: {-side of box 1, box 2, +side 1, 2} */
    const double face[3][4] = {{-2.1, -1.9, 2.1, 0.4},
                               {NAN, NAN, 1.2, 1.85},
                               {-0.95, -0.9, 0.95, 0.9}};
    int axis = -1;
    for (int k = 0; k < 3; k++)
        if (fabs(fabs(nn[k]) - 1) < TOL)
            axis = k;
    assert_true(axis >= 0);
    const double *f = face[axis] + (nn[axis] > 0 ? 2 : 0);
    assert_true(fabs(pos[axis] - f[0]) < TOL || fabs(pos[axis] - f[1]) < TOL);
    for (int k = 1; k < 3; k++) { /* flat in that plane */
        double q[3] = {t[k].x, t[k].y, t[k].z};
        assert_true(fabs(q[axis] - pos[axis]) < TOL);
    }
}

/* The faces (origin, then edges a and b) of the two boxes: 0-4 the
 * lower box's +z, -z, top, +x, -x faces, 5-9 the upper box's. */
static const Vec3 faces[10][3] = {
    {{-2.1, 0.5, 0.95}, {4.2, 0, 0}, {0, 0.7, 0}},
    {{2.1, 0.5, -0.95}, {-4.2, 0, 0}, {0, 0.7, 0}},
    {{-2.1, 1.2, 0.95}, {4.2, 0, 0}, {0, 0, -1.9}},
    {{2.1, 0.5, 0.95}, {0, 0, -1.9}, {0, 0.7, 0}},
    {{-2.1, 0.5, -0.95}, {0, 0, 1.9}, {0, 0.7, 0}},
    {{-1.9, 1.2, 0.9}, {2.3, 0, 0}, {0, 0.65, 0}},
    {{0.4, 1.2, -0.9}, {-2.3, 0, 0}, {0, 0.65, 0}},
    {{-1.9, 1.85, 0.9}, {2.3, 0, 0}, {0, 0, -1.8}},
    {{0.4, 1.2, 0.9}, {0, 0, -1.8}, {0, 0.65, 0}},
    {{-1.9, 1.2, -0.9}, {0, 0, 1.8}, {0, 0.65, 0}}};

/* Panel c of 70, 7 a face: the strip j = c % 7 of face c / 7, from
 * a j / 7 to a (j + 1) / 7 and across all of b. */
static void check_body(guint c, const GArray *v, SceneBox *box)
{
    for (guint i = 0; i + 2 < v->len; i += 3)
        body_tri(&g_array_index(v, Vec3, i));
    SceneBox got = scene_box_empty(), want = scene_box_empty();
    for (guint i = 0; i < v->len; i++)
        got = scene_box_add_point(got, g_array_index(v, Vec3, i));
    const Vec3 *f = faces[c / 7];
    for (guint k = 0; k < 4; k++)
        want = scene_box_add_point(
            want, vec3_add(vec3_add(f[0], vec3_scale(f[1], (c % 7 + k % 2) / 7.0)),
                           vec3_scale(f[2], k / 2)));
    if (vec3_len(vec3_sub(got.min, want.min)) > TOL ||
        vec3_len(vec3_sub(got.max, want.max)) > TOL)
        fail_msg("panel %u: box (%g %g %g)-(%g %g %g), expected (%g %g %g)-(%g "
                 "%g %g)",
                 c, got.min.x, got.min.y, got.min.z, got.max.x, got.max.y,
                 got.max.z, want.min.x, want.min.y, want.min.z, want.max.x,
                 want.max.y, want.max.z);
    *box = scene_box_union(*box, got);
}

/* The part's first vertex is its surface at (u, v) = (0, 0), where the
 * angles start: a tube at angle 0 on e1 = axis x (0, 1, 0) and at its
 * -axis end, an ellipsoid band at longitude 0 (+x) and latitude -0.45
 * pi, a tyre sector at its first angle on the tube's outer circle. */
static void first_is(const GArray *v, Vec3 want)
{
    Vec3 got = g_array_index(v, Vec3, 0);
    if (vec3_len(vec3_sub(got, want)) > TOL)
        fail_msg("first vertex (%g, %g, %g), expected (%g, %g, %g)", got.x,
                 got.y, got.z, want.x, want.y, want.z);
}

static Vec3 band_start(Vec3 c, Vec3 a)
{
    double ph = -0.45 * G_PI;
    return vec3_add(c, vec3(a.x * cos(ph), a.y * sin(ph), 0));
}

/* Part c of its group (the group's own count; nw wheel parts). */
static void check_part(int g, guint c, guint nw, const GArray *v, SceneBox *box)
{
    if (g == BODY) {
        check_body(c, v, box);
    } else if (g == CHASSIS && c % 2 == 0) { /* rails along x */
        Vec3 at = vec3(-1.75 + 0.5 * ((c / 4) % 8), 0.45,
                       (c / 2) % 2 ? 0.6 : -0.6);
        on_tube(v, at, 'x', 0.25, 0.06);
        first_is(v, vec3_add(at, vec3(-0.25, 0, 0.06)));
    } else if (g == CHASSIS) { /* cross members along z */
        Vec3 at = vec3(-1.9 + 3.8 * c / 50, 0.4, 0);
        on_tube(v, at, 'z', 0.6, 0.04);
        first_is(v, vec3_add(at, vec3(-0.04, 0, -0.6)));
    } else if (g == WHEELS) {
        guint per = nw / 4, w = c / per, j = c % per;
        double side = w % 2 ? 1 : -1;
        Vec3 centre = vec3(w < 2 ? 1.35 : -1.35, 0.4, 0.85 * side);
        if (j + 1 == per) { /* the hub, 0.1 outwards */
            Vec3 at = vec3(centre.x, 0.4, centre.z + 0.1 * side);
            on_ellipsoid(v, at, vec3(0.2, 0.2, 0.06));
            first_is(v, band_start(at, vec3(0.2, 0.2, 0.06)));
        } else {
            on_sector(v, centre, j, per - 1);
            double a0 = 2 * G_PI * j / (per - 1);
            first_is(v, vec3_add(centre, vec3(0.4 * cos(a0), 0.4 * sin(a0), 0)));
        }
    } else if (g == INTERIOR) {
        Vec3 at = vec3(-1.6 + 0.5 * (c % 4), 0.9 + 0.3 * ((c / 12) % 2),
                       0.5 * ((double)((c / 4) % 3) - 1));
        on_ellipsoid(v, at, vec3(0.25, 0.15, 0.2));
        first_is(v, band_start(at, vec3(0.25, 0.15, 0.2)));
    } else {
        double x = (c / 2) % 2 ? 2.14 : -2.14;
        if (c % 2) {
            Vec3 at = vec3(x > 0 ? 2.17 : -2.17, 0.55 + 0.05 * (c % 8), 0);
            on_tube(v, at, 'z', 0.9, 0.03);
            first_is(v, vec3_add(at, vec3(-0.03, 0, -0.9)));
        } else {
            Vec3 at = vec3(x, 0.8 + 0.1 * (c % 3), -0.8 + 1.6 * (c % 7) / 6.0);
            on_ellipsoid(v, at, vec3(0.04, 0.08, 0.1));
            first_is(v, band_start(at, vec3(0.04, 0.08, 0.1)));
        }
    }
}

/* 206 structures: 200 parts, of them (by vehicle.c's shares) 70 body
 * panels, 50 chassis tubes, 40 wheel parts (4 wheels of 9 tyre sectors
 * and a hub), 20 interior and 20 trim parts; group g's parts are
 * numbered from first[g]. */
static void test_part_shapes(void **st)
{
    (void)st;
    const guint first[5] = {0, 70, 120, 160, 180}, count[5] = {70, 50, 40, 20, 20};
    SceneDb *db = scene_db_new();
    guint root, seen[5] = {0};
    assert_true(scene_vehicle_build(db, 206, 60000, "x", &root, NULL));
    GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
    SceneBox body = scene_box_empty();
    for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
        int g;
        guint i;
        if (!part_of(scene_db_struct_name(db, sid), &g, &i))
            continue;
        assert_true(i >= first[g] && i < first[g] + count[g]);
        assert_true(verts_of(db, sid, v) >= 6);
        check_part(g, i - first[g], count[WHEELS], v, &body);
        seen[g]++;
    }
    for (int g = 0; g < 5; g++)
        assert_int_equal(seen[g], count[g]);
    const Vec3 lo = {-2.1, 0.5, -0.95}, hi = {2.1, 1.85, 0.95};
    assert_true(vec3_len(vec3_sub(body.min, lo)) < TOL &&
                vec3_len(vec3_sub(body.max, hi)) < TOL);
    g_array_free(v, TRUE);
    scene_db_free(db);
}

/* ---- budgets ----------------------------------------------------------- */

/* Number of distinct vertex coordinates along axis (0 x, 1 y, 2 z) in
 * structure sid. */
static guint n_distinct(const SceneDb *db, guint sid, int axis)
{
    GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
    GHashTable *seen = g_hash_table_new(g_double_hash, g_double_equal);
    verts_of(db, sid, v);
    double *vals = g_new(double, v->len);
    for (guint i = 0; i < v->len; i++) {
        Vec3 q = g_array_index(v, Vec3, i);
        vals[i] = axis == 0 ? q.x : axis == 1 ? q.y : q.z;
        g_hash_table_add(seen, &vals[i]);
    }
    guint n = g_hash_table_size(seen);
    g_hash_table_destroy(seen);
    g_free(vals);
    g_array_free(v, TRUE);
    return n;
}

/* The quad grid a part was cut into, seen in its distinct vertex
 * coordinates: a +z body panel's nx x values and n2 y values, or (nx =
 * 0) a trim tube's n2 z values. */
static void grid_shape(const SceneDb *db, guint sid, guint nx, guint n2)
{
    if (nx) { /* a +z panel: columns along x, rows along y */
        assert_int_equal(n_distinct(db, sid, 0), nx);
        assert_int_equal(n_distinct(db, sid, 1), n2);
    } else { /* a trim tube: rows along z */
        assert_int_equal(n_distinct(db, sid, 2), n2);
    }
}

/* 106 structures: 100 parts, weights 35 panels x 1.5 + 25 tubes x 0.6
 * + 16 tyre sectors x 2 + 4 hubs x 1 + 10 x 1 + 10 x 0.4 = 117.5.  1375
 * triangles leave 1175 = 10 x 117.5 beyond 2 a part: 17 a panel, 8 a
 * tube, 22 a sector, 12 a hub or interior part, 6 a trim part.  1376
 * leave one more, for the largest remainder (1176 w / 117.5 - floor: a
 * sector's 0.0170 beats a panel's 0.0128), of the tied sectors the
 * first.  Grids: panel body.0 (1.05 x 0.7: 4 of the first face's 35 /
 * 10 + 1 panels) takes ceil(sqrt(17 / 2 x 1.5)) = 4 columns and
 * ceil(17 / 8) = 3 rows; trim tube trim.91 (around 2 pi 0.03 = 0.19,
 * long 1.8) ceil(sqrt(6 / 2 x 0.105)) = 1 column, 3 rows.  And 2
 * triangles a part is the least: 10 structures (4 parts) take 8, not 7. */
static void test_budgets(void **st)
{
    (void)st;
    for (guint extra = 0; extra < 2; extra++) {
        SceneDb *db = scene_db_new();
        guint root;
        assert_true(scene_vehicle_build(db, 106, 1375 + extra, "x", &root, NULL));
        for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
            int g;
            guint i, want;
            if (!part_of(scene_db_struct_name(db, sid), &g, &i))
                continue;
            if (g == WHEELS)
                want = (i - 60) % 5 == 4 ? 12 : 22 + (extra && i == 60);
            else
                want = g == BODY ? 17 : g == CHASSIS ? 8 : g == TRIM ? 6 : 12;
            if (g == BODY && i == 0)
                grid_shape(db, sid, 5, 4);
            if (g == TRIM && i == 91)
                grid_shape(db, sid, 0, 4);
            if (scene_db_len(db, sid) != want)
                fail_msg("%s: %u triangles, expected %u",
                         scene_db_struct_name(db, sid), scene_db_len(db, sid),
                         want);
        }
        scene_db_free(db);
    }
    /* 1200: q = 1000 w / 117.5, floors 959, 41 left over by remainder:
     * the 35 panels (.766), then the 4 hubs and 2 of the 10 interior
     * parts (.511; the hubs come first), none to the trim (.404), tubes
     * (.106) or sectors (.021, the largest q) */
    const guint want_g[5] = {35 * 15, 25 * 7, 16 * 19 + 4 * 11, 10 * 10 + 2,
                             10 * 5};
    guint got_g[5] = {0};
    SceneDb *gdb = scene_db_new();
    guint groot;
    assert_true(scene_vehicle_build(gdb, 106, 1200, "x", &groot, NULL));
    for (guint sid = 0; sid < scene_db_struct_count(gdb); sid++) {
        int g;
        guint i;
        if (part_of(scene_db_struct_name(gdb, sid), &g, &i))
            got_g[g] += scene_db_len(gdb, sid);
    }
    for (int g = 0; g < 5; g++)
        assert_int_equal(got_g[g], want_g[g]);
    scene_db_free(gdb);
    GError *err = NULL;
    SceneDb *db = scene_db_new();
    guint root;
    assert_false(scene_vehicle_build(db, 10, 7, "v.yaml:4:5", &root, &err));
    assert_non_null(strstr(err->message, "v.yaml:4:5: found 10 structures and 7"));
    g_error_free(err);
    assert_false(scene_vehicle_build(db, 9, 100, "v", &root, NULL));
    /* at most 2^28 triangles (refused before anything is built) */
    err = NULL;
    assert_false(scene_vehicle_build(db, 106, (1u << 28) + 1, "v", &root, &err));
    assert_non_null(strstr(err->message, "v: found 106 structures and "
                                         "268435457 triangles, expected"));
    g_error_free(err);
    assert_int_equal(scene_db_struct_count(db), 0);
    scene_db_free(db);
}

/* An ellipsoid band's grid follows the lengths of its middle lines,
 * each an 8-segment polyline (vehicle.c, param_length): an interior part
 * (radii 0.25, 0.15, 0.2) measures 2.4825 times longer round (at latitude
 * 0) than from pole to pole (at longitude pi), so a budget of 20 takes
 * ceil(sqrt(20 / 2 x 2.4825)) = 5 columns round, 5 vertices on its lowest
 * latitude (the seam welds the ends), in ceil(20 / 10) = 2 strips.  (7 of
 * the 8 segments would give 2.5913 and 6 columns.)  106 structures and
 * 2315 triangles give every interior part 2 + (2315 - 200) / 117.5 = 20. */
static void test_ellipsoid_grid(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint root, parts = 0;
    assert_true(scene_vehicle_build(db, 106, 2315, "x", &root, NULL));
    GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
    for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
        int g;
        guint i;
        if (!part_of(scene_db_struct_name(db, sid), &g, &i) || g != INTERIOR)
            continue;
        assert_int_equal(verts_of(db, sid, v), 3 * 20);
        double ymin = HUGE_VAL;
        for (guint k = 0; k < v->len; k++)
            ymin = fmin(ymin, g_array_index(v, Vec3, k).y);
        GArray *low = g_array_new(FALSE, FALSE, sizeof(Vec3));
        for (guint k = 0; k < v->len; k++) {
            Vec3 q = g_array_index(v, Vec3, k);
            gboolean seen = q.y - ymin > 1e-12;
            for (guint j = 0; j < low->len && !seen; j++)
                seen = vec3_len(vec3_sub(g_array_index(low, Vec3, j), q)) < 1e-12;
            if (!seen)
                g_array_append_val(low, q);
        }
        assert_int_equal(low->len, 5);
        g_array_free(low, TRUE);
        assert_int_equal(n_distinct(db, sid, 1), 3); /* 2 strips */
        SceneBox unused = scene_box_empty(); /* on the band, pole to pole */
        check_part(g, i - 80, 20, v, &unused);
        parts++;
    }
    assert_int_equal(parts, 10);
    g_array_free(v, TRUE);
    scene_db_free(db);
}

/* A square panel's strips run along u, its first side: 164 structures
 * give 55 panels, 6 on the first face (4.2 / 6 = 0.7 by 0.7), whose
 * middle lines measure exactly equal (0.7 both) for body.0 to body.4;
 * the second quad follows the first along x (u), not up y (v). */
static void test_square_panels(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint root, seen = 0;
    assert_true(scene_vehicle_build(db, 164, 20000, "x", &root, NULL));
    GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
    for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
        int g;
        guint i;
        if (!part_of(scene_db_struct_name(db, sid), &g, &i) || g != BODY ||
            i > 4)
            continue;
        verts_of(db, sid, v);
        Vec3 a = g_array_index(v, Vec3, 0), b = g_array_index(v, Vec3, 6);
        assert_true(a.x == -2.1 + 0.7 * i || fabs(a.x - (-2.1 + 0.7 * i)) < TOL);
        assert_true(b.y == a.y && b.x > a.x + 0.01);
        seen++;
    }
    assert_int_equal(seen, 5);
    g_array_free(v, TRUE);
    scene_db_free(db);
}

/* One part a wheel (26 structures: 20 parts, 4 of them wheels): each is
 * a whole tyre, the torus all the way round (one sector, no hub). */
static void test_one_part_wheels(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint root, wheels = 0;
    assert_true(scene_vehicle_build(db, 26, 400, "x", &root, NULL));
    GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
    for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
        int g;
        guint i;
        if (!part_of(scene_db_struct_name(db, sid), &g, &i) || g != WHEELS)
            continue;
        guint w = i - 12;
        double side = w % 2 ? 1 : -1;
        Vec3 c = vec3(w < 2 ? 1.35 : -1.35, 0.4, 0.85 * side);
        verts_of(db, sid, v);
        SceneBox b = scene_box_empty();
        for (guint k = 0; k < v->len; k++) {
            Vec3 d = vec3_sub(g_array_index(v, Vec3, k), c);
            double rho = hypot(d.x, d.y) - 0.28;
            assert_true(fabs(rho * rho + d.z * d.z - 0.12 * 0.12) < TOL);
            b = scene_box_add_point(b, d);
        }
        assert_true(b.min.x < -0.3 && b.max.x > 0.3 && b.min.y < -0.3 &&
                    b.max.y > 0.3);
        wheels++;
    }
    assert_int_equal(wheels, 4);
    g_array_free(v, TRUE);
    scene_db_free(db);
}

/* ---- copies and camera -------------------------------------------------- */

/* Copy k of n sits at angle a = 2 pi k / n on the circle of radius R,
 * its length (+x) along the circle's tangent (-sin a, 0, cos a); the
 * camera starts at (camera_radius, camera_height, 0), looks at the
 * centre, far = camera_radius + R + 5, near = far / 1000, and revolves
 * about +y by degrees_per_frame. */
static void test_copies_and_camera(void **st)
{
    (void)st;
    SceneVehicleParams p = scene_vehicle_defaults();
    p.structures = 20;
    p.triangles = 600;
    p.instances = 5;
    Scene *s = scene_vehicle_new(&p, "t", NULL);
    assert_non_null(s);
    for (guint k = 0; k < 5; k++) {
        Mat4 m = scene_instance(s, k)->xform;
        double a = 2 * G_PI * k / 5, R = p.circle_radius;
        assert_true(fabs(m.m[0][3] - R * cos(a)) < TOL && m.m[1][3] == 0 &&
                    fabs(m.m[2][3] - R * sin(a)) < TOL);
        Vec4 x = mat4_apply(m, (Vec4){1, 0, 0, 0});
        Vec4 y = mat4_apply(m, (Vec4){0, 1, 0, 0});
        assert_true(fabs(x.x + sin(a)) < TOL && fabs(x.y) < TOL &&
                    fabs(x.z - cos(a)) < TOL);
        assert_true(fabs(y.x) < TOL && fabs(y.y - 1) < TOL && fabs(y.z) < TOL);
    }
    SceneCamera c = s->camera;
    double far = p.camera_radius + p.circle_radius + 5;
    assert_true(c.eye.x == p.camera_radius && c.eye.y == p.camera_height &&
                c.eye.z == 0);
    assert_true(c.target.x == 0 && c.target.y == 0 && c.target.z == 0);
    assert_true(c.fov_deg == p.fov_deg && c.far == far && c.near == far * 1e-3);
    assert_int_equal(scene_path_n_frames(s->path), p.frames);
    for (guint f = 0; f < 3; f++) {
        double th = f * p.degrees_per_frame * G_PI / 180;
        SceneCamera cf = scene_camera_at(s, f);
        assert_true(fabs(cf.eye.x - p.camera_radius * cos(th)) < TOL &&
                    fabs(cf.eye.y - p.camera_height) < TOL &&
                    fabs(cf.eye.z + p.camera_radius * sin(th)) < TOL);
        assert_true(vec3_len(cf.target) < TOL);
    }
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_part_shapes),
        cmocka_unit_test(test_budgets),
        cmocka_unit_test(test_ellipsoid_grid),
        cmocka_unit_test(test_one_part_wheels),
        cmocka_unit_test(test_square_panels),
        cmocka_unit_test(test_copies_and_camera),
    };
    return cmocka_run_group_tests_name("vehicle_parts", tests, NULL, NULL);
}
