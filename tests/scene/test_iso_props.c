/* test_iso_props.c — sim/scene/isosurface.c by its properties: the
 * defaults of isosurface.h, the two fields at points where their value is
 * known, a single metaball's surface (closed, every vertex near the
 * sphere, every triangle facing outwards, the enclosed volume), the
 * gyroid's cut-open surface (two-sided, inside the cube in x, y and z),
 * cells tagging the triangles of their own box, the memory estimates at
 * their limits, and the large polygons (regular, their sizes, centres and
 * depths in range, the huge ones covering over 3/4 of the screen, by an
 * exact clipped area, and each the first draw that does).
 * Found unchecked by make mutate (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/core/memlimit.h"
#include "sim/core/rng.h"
#include "sim/scene/isosurface.h"

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static void test_defaults_and_fields(void **st)
{
    (void)st;
    SceneIsoParams p = scene_iso_defaults();
    assert_int_equal(p.field, SCENE_FIELD_GYROID);
    assert_int_equal(p.grid, 32);
    assert_true(p.iso == 0 && p.periods == 2);
    assert_int_equal(p.balls, 12);
    assert_true(p.seed == 1);
    assert_true(p.color.r == 0.55f && p.color.g == 0.75f && p.color.b == 0.95f);
    /* gyroid, 2 periods: k = 2 pi; at (1/4, 0, 0) only sin(k x) cos(k y)
     * = 1 survives; at (1/4, 1/4, 1/4) every term is 1 x 0 */
    NEAR(scene_iso_field(&p, NULL, vec3(0.25, 0, 0)), 1, 1e-12);
    NEAR(scene_iso_field(&p, NULL, vec3(0, 0.25, 0)), 1, 1e-12);
    NEAR(scene_iso_field(&p, NULL, vec3(0, 0, 0.25)), 1, 1e-12);
    NEAR(scene_iso_field(&p, NULL, vec3(0.25, 0.25, 0.25)), 0, 1e-12);
    NEAR(scene_iso_field(&p, NULL, vec3(-0.25, 0, 0)), -1, 1e-12);
    p.periods = 1; /* k = pi: (1/2, 0, 0) */
    NEAR(scene_iso_field(&p, NULL, vec3(0.5, 0, 0)), 1, 1e-12);
    /* metaballs: 1/16 over the squared distance, summed */
    p.field = SCENE_FIELD_METABALLS;
    p.balls = 2;
    Vec3 c[2] = {{0, 0, 0}, {1, 0, 0}};
    NEAR(scene_iso_field(&p, c, vec3(0.5, 0, 0)), 0.5, 1e-9);
    NEAR(scene_iso_field(&p, c, vec3(0, 0.25, 0)), 1 + 0.0625 / 1.0625, 1e-9);
    p.balls = 1;
    NEAR(scene_iso_field(&p, c, vec3(0, 0, -0.5)), 0.25, 1e-9);
    /* exactly at a centre (d = 0) the 1e-12 guard sets the value:
     * 1/16 / 1e-12, finite and positive */
    NEAR(scene_iso_field(&p, c, vec3(0, 0, 0)), 0.0625e12, 1e-3);
}

/* The centre of the one metaball of seed `seed`: where the field peaks
 * on the lattice would be too coarse; the mean of the vertices is it. */
static Vec3 mean_vertex(const SceneMesh *m)
{
    Vec3 c = vec3(0, 0, 0);
    for (guint i = 0; i < scene_mesh_n_vertices(m); i++)
        c = vec3_add(c, scene_mesh_vertex(m, i));
    return vec3_scale(c, 1.0 / scene_mesh_n_vertices(m));
}

static void test_one_ball(void **st)
{
    (void)st;
    SceneIsoParams p = scene_iso_defaults();
    p.field = SCENE_FIELD_METABALLS;
    p.balls = 1;
    p.iso = 1; /* 1/16 / d^2 = 1: a sphere of radius 1/4 */
    p.grid = 24;
    SceneMesh *m = scene_iso_mesh(&p);
    Vec3 c = mean_vertex(m);
    double h = 2.0 / 24;
    assert_true(fabs(c.x) <= 0.6 && fabs(c.y) <= 0.6 && fabs(c.z) <= 0.6);
    for (guint i = 0; i < scene_mesh_n_vertices(m); i++) {
        double r = vec3_len(vec3_sub(scene_mesh_vertex(m, i), c));
        assert_true(r > 0.25 - h && r < 0.25 + h);
    }
    /* every triangle faces away from the centre; the volume by the
     * divergence theorem is the ball's, positive */
    double vol = 0;
    GHashTable *edges = g_hash_table_new(g_int64_hash, g_int64_equal);
    gint64 *keys = g_new(gint64, 3 * scene_mesh_n_polys(m));
    for (guint t = 0; t < scene_mesh_n_polys(m); t++) {
        const uint32_t *v = scene_mesh_poly(m, t);
        assert_int_equal(scene_mesh_poly_len(m, t), 3);
        Vec3 a = scene_mesh_vertex(m, v[0]), b = scene_mesh_vertex(m, v[1]),
             d = scene_mesh_vertex(m, v[2]);
        Vec3 n = vec3_cross(vec3_sub(b, a), vec3_sub(d, a));
        Vec3 mid = vec3_scale(vec3_add(vec3_add(a, b), d), 1.0 / 3);
        assert_true(vec3_dot(n, vec3_sub(mid, c)) >= 0);
        vol += vec3_dot(a, vec3_cross(b, d)) / 6;
        for (int k = 0; k < 3; k++) { /* each directed edge once */
            gint64 *key = &keys[3 * t + k];
            *key = (gint64)v[k] << 32 | v[(k + 1) % 3];
            assert_null(g_hash_table_lookup(edges, key));
            g_hash_table_add(edges, key);
        }
        assert_true(g_array_index(m->poly_color, SceneColor, t).g == 0.75f);
    }
    /* closed: every directed edge has its reverse */
    for (guint t = 0; t < 3 * scene_mesh_n_polys(m); t++) {
        gint64 rev = (keys[t] & 0xffffffff) << 32 | (keys[t] >> 32);
        assert_true(g_hash_table_contains(edges, &rev));
    }
    double want = 4.0 / 3 * G_PI * 0.25 * 0.25 * 0.25;
    assert_true(vol > 0.8 * want && vol < 1.05 * want);
    g_hash_table_destroy(edges);
    g_free(keys);
    scene_mesh_free(m);
    /* as a scene: closed, so one-sided; viewed from azimuth 30,
     * elevation 20 */
    Scene *s = scene_iso_new(&p);
    assert_false(s->two_sided);
    Vec3 d = vec3_norm(vec3_sub(s->camera.eye, s->camera.target));
    NEAR(d.y, sin(20 * G_PI / 180), 1e-9);
    NEAR(d.x / d.z, tan(30 * G_PI / 180), 1e-9);
    assert_int_equal(scene_n_instances(s), 1);
    scene_free(s);
}

/* The gyroid fills the cube and is cut open by it: vertices inside
 * [-1, 1]^3, reaching every face, the scene two-sided.  Cells: the same
 * triangles, each tagged with the cell whose box holds it. */
static void test_gyroid_cells(void **st)
{
    (void)st;
    SceneIsoParams p = scene_iso_defaults();
    p.grid = 8;
    SceneMesh *whole = scene_iso_mesh(&p), *m = scene_iso_mesh_cells(&p, 4);
    assert_int_equal(scene_mesh_n_polys(whole), scene_mesh_n_polys(m));
    SceneBox b = scene_mesh_bbox(m);
    NEAR(b.min.x, -1, 0.2);
    NEAR(b.max.x, 1, 0.2);
    NEAR(b.min.y, -1, 0.2);
    NEAR(b.max.y, 1, 0.2);
    NEAR(b.min.z, -1, 0.2);
    NEAR(b.max.z, 1, 0.2);
    assert_true(b.min.x >= -1 && b.max.z <= 1);
    guint per[8] = {0};
    for (guint t = 0; t < scene_mesh_n_polys(m); t++) {
        uint32_t tag = g_array_index(m->poly_tag, uint32_t, t);
        assert_true(tag < 8);
        per[tag]++;
        double lo[3] = {-1.0 + (tag & 1), -1.0 + (tag >> 1 & 1),
                        -1.0 + (tag >> 2)};
        const uint32_t *v = scene_mesh_poly(m, t);
        for (int k = 0; k < 3; k++) {
            Vec3 q = scene_mesh_vertex(m, v[k]);
            assert_true(q.x >= lo[0] - 1e-12 && q.x <= lo[0] + 1 + 1e-12);
            assert_true(q.y >= lo[1] - 1e-12 && q.y <= lo[1] + 1 + 1e-12);
            assert_true(q.z >= lo[2] - 1e-12 && q.z <= lo[2] + 1 + 1e-12);
        }
    }
    for (int c = 0; c < 8; c++)
        assert_true(per[c] > 0);
    /* one cell of the whole grid: tag 0 */
    for (guint t = 0; t < scene_mesh_n_polys(whole); t++)
        assert_int_equal(g_array_index(whole->poly_tag, uint32_t, t), 0);
    scene_mesh_free(whole);
    scene_mesh_free(m);
    Scene *s = scene_iso_new(&p);
    assert_true(s->two_sided);
    scene_free(s);
    /* fewer than one period counts as one, so the memory estimate of
     * 0.5 periods is that of 1 (below) */
}

/* Bytes: (grid + 1)^3 doubles + triangles x SCENE_POLY_BYTES, triangles
 * = min(12 g^3, 30 k g^2), k = max(1, periods) or max(1, balls / 12). */
static void check_limit(const SceneIsoParams *p, double tris)
{
    double n = p->grid + 1.0;
    guint64 bytes = (guint64)(n * n * n * 8 + tris * 512);
    GError *err = NULL;
    sim_mem_set_limit(bytes);
    assert_true(scene_iso_check(p, "w", &err));
    sim_mem_set_limit(bytes - 1);
    assert_false(scene_iso_check(p, "w", &err));
    char *want = g_strdup_printf("w: found grid %u needing", p->grid);
    assert_true(g_str_has_prefix(err->message, want));
    g_free(want);
    g_clear_error(&err);
    sim_mem_set_limit(0);
}

static void test_iso_check(void **st)
{
    (void)st;
    SceneIsoParams p = scene_iso_defaults();
    p.grid = 10;
    p.periods = 0.5;
    check_limit(&p, 30 * 100);
    p.periods = 3;
    check_limit(&p, 3 * 30 * 100);
    p.grid = 2; /* 12 g^3 = 96 < 30 x 3 x 4 */
    check_limit(&p, 96);
    p.grid = 10;
    p.field = SCENE_FIELD_METABALLS;
    p.balls = 6;
    check_limit(&p, 30 * 100);
    p.balls = 36;
    check_limit(&p, 3 * 30 * 100);
    GError *err = NULL;
    p.grid = 1;
    assert_false(scene_iso_check(&p, "w", &err));
    assert_string_equal(err->message, "w: found grid 1, expected 2 to 1024 cells");
    g_clear_error(&err);
    p.grid = 1025;
    assert_false(scene_iso_check(&p, "w", &err));
    assert_string_equal(err->message,
                        "w: found grid 1025, expected 2 to 1024 cells");
    g_clear_error(&err);
    p.grid = 2;
    assert_true(scene_iso_check(&p, "w", NULL));
    /* large polygons: SCENE_POLY_BYTES x max(1, (sides - 2) / 2) each */
    SceneBigPolyParams b = scene_bigpoly_defaults();
    assert_int_equal(b.count, 1000);
    assert_int_equal(b.max_sides, 6);
    assert_true(b.huge_fraction == 0.05 && b.min_size == 0.1 &&
                b.max_size == 0.5 && b.seed == 1);
    const guint sides[] = {3, 4, 6, 16};
    const double per[] = {512, 512, 1024, 3584};
    for (guint i = 0; i < 4; i++) {
        b.max_sides = sides[i];
        sim_mem_set_limit((guint64)(1000 * per[i]));
        assert_true(scene_bigpoly_check(&b, "w", NULL));
        sim_mem_set_limit((guint64)(1000 * per[i]) - 1);
        assert_false(scene_bigpoly_check(&b, "w", &err));
        char *want = g_strdup_printf("w: found 1000 polygons of up to %u "
                                     "sides needing",
                                     sides[i]);
        assert_true(g_str_has_prefix(err->message, want));
        g_free(want);
        g_clear_error(&err);
    }
    sim_mem_set_limit(0);
}

/* Clipped area of a convex polygon to [-1, 1]^2, by sampling a fine
 * grid of points (independent of the generator's own clipper). */
static double covered(const SceneMesh *m, guint i)
{
    const uint32_t *v = scene_mesh_poly(m, i);
    guint n = scene_mesh_poly_len(m, i), in = 0, N = 100;
    for (guint a = 0; a < N; a++)
        for (guint b = 0; b < N; b++) {
            double x = -1 + (a + 0.5) * 2 / N, y = -1 + (b + 0.5) * 2 / N;
            gboolean inside = TRUE;
            for (guint k = 0; k < n && inside; k++) {
                Vec3 p = scene_mesh_vertex(m, v[k]);
                Vec3 q = scene_mesh_vertex(m, v[(k + 1) % n]);
                inside = (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x) >= 0;
            }
            in += inside;
        }
    return 4.0 * in / (N * N);
}

/* Exact area of polygon i clipped to [-1, 1]^2: the polygon cut by each
 * of the four half-planes a x + b y <= 1 in turn, then the shoelace. */
static double clipped_area(const SceneMesh *m, guint i)
{
    Vec3 a[40], b[40];
    guint na = scene_mesh_poly_len(m, i);
    for (guint k = 0; k < na; k++)
        a[k] = scene_mesh_vertex(m, scene_mesh_poly(m, i)[k]);
    const double hp[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (guint h = 0; h < 4; h++) {
        guint nb = 0;
        for (guint k = 0; k < na; k++) {
            Vec3 p = a[k], q = a[(k + 1) % na];
            double sp = hp[h][0] * p.x + hp[h][1] * p.y - 1;
            double sq = hp[h][0] * q.x + hp[h][1] * q.y - 1;
            if (sp <= 0)
                b[nb++] = p;
            if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0))
                b[nb++] = vec3_add(p, vec3_scale(vec3_sub(q, p), sp / (sp - sq)));
        }
        memcpy(a, b, sizeof(Vec3) * (na = nb));
    }
    double area = 0;
    for (guint k = 0; k < na; k++)
        area += a[k].x * a[(k + 1) % na].y - a[(k + 1) % na].x * a[k].y;
    return area / 2;
}

/* The first huge polygon of a draw, by the rule of isosurface.c: after
 * the huge-or-small draw, corners 4 + below(5), radius 0.95 + 0.3 u,
 * turn 2 pi u, centre 0.2 (2 u - 1) in x and y, depth 2 u - 1, drawn
 * again until its exact clipped area exceeds 3; *n its corners. */
static void first_huge(guint64 seed, Vec3 *pts, guint *n)
{
    SimRng r;
    sim_rng_init(&r, seed, 0);
    (void)sim_rng_uniform(&r);
    SceneMesh *m = scene_mesh_new();
    for (;;) {
        *n = 4 + (guint)sim_rng_below(&r, 5);
        double rad = 0.95 + 0.3 * sim_rng_uniform(&r);
        double rot = 2 * G_PI * sim_rng_uniform(&r);
        double cx = 0.2 * (2 * sim_rng_uniform(&r) - 1);
        double cy = 0.2 * (2 * sim_rng_uniform(&r) - 1);
        double z = -1 + 2 * sim_rng_uniform(&r);
        uint32_t v[8];
        for (guint k = 0; k < *n; k++) {
            double a = rot + 2 * G_PI * k / *n;
            pts[k] = vec3(cx + rad * cos(a), cy + rad * sin(a), z);
            v[k] = scene_mesh_add_vertex(m, pts[k]);
        }
        scene_mesh_add_poly(m, v, *n, scene_color(1, 1, 1), 0);
        if (clipped_area(m, scene_mesh_n_polys(m) - 1) > 3.0)
            break;
    }
    scene_mesh_free(m);
}

/* Every polygon huge: each covers over 3/4 of the screen (3 of its 4
 * units), the rule being exact: the least of 400 is just above 3, and
 * the first polygon of each of 40 seeds is the first draw that covers
 * enough (a rule that turned good polygons down would skip it). */
static void test_huge_rule(void **st)
{
    (void)st;
    SceneBigPolyParams p = scene_bigpoly_defaults();
    p.count = 400;
    p.huge_fraction = 1;
    Scene *s = scene_bigpoly_new(&p);
    const SceneMesh *m = scene_instance_mesh(s, 0);
    double least = 4;
    for (guint i = 0; i < 400; i++) {
        double a = clipped_area(m, i);
        assert_true(a > 3.0);
        least = fmin(least, a);
    }
    print_message("least clipped area %.6f\n", least);
    assert_true(least < 3.01);
    scene_free(s);
    p.count = 1;
    for (p.seed = 1; p.seed <= 40; p.seed++) {
        Vec3 want[8];
        guint n;
        first_huge(p.seed, want, &n);
        s = scene_bigpoly_new(&p);
        m = scene_instance_mesh(s, 0);
        assert_int_equal(scene_mesh_poly_len(m, 0), n);
        for (guint k = 0; k < n; k++) {
            Vec3 got = scene_mesh_vertex(m, scene_mesh_poly(m, 0)[k]);
            assert_true(vec3_len(vec3_sub(got, want[k])) < 1e-12);
        }
        scene_free(s);
    }
}

/* Corners of polygon i turn counter-clockwise about c by exactly 2 pi /
 * n each (a regular polygon's corners in order). */
static void corners_step_evenly(const SceneMesh *m, guint i, Vec3 c)
{
    const uint32_t *v = scene_mesh_poly(m, i);
    guint n = scene_mesh_poly_len(m, i);
    for (guint k = 0; k < n; k++) {
        Vec3 a = vec3_sub(scene_mesh_vertex(m, v[k]), c);
        Vec3 b = vec3_sub(scene_mesh_vertex(m, v[(k + 1) % n]), c);
        double turn = atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y);
        NEAR(turn, 2 * G_PI / n, 1e-9);
    }
}

/* Counts the signs of centre x, y, depth and the first corner's offset
 * from the centre in y (its turn in [0, pi) or [pi, 2 pi)). */
static void count_signs(guint *sign, const SceneMesh *m, guint i, Vec3 c)
{
    Vec3 q = scene_mesh_vertex(m, scene_mesh_poly(m, i)[0]);
    const double d[4] = {c.x, c.y, c.z, q.y - c.y};
    for (guint k = 0; k < 4; k++)
        sign[2 * k + (d[k] < 0)]++;
}

static void test_bigpoly(void **st)
{
    (void)st;
    SceneBigPolyParams p = scene_bigpoly_defaults();
    p.count = 300;
    p.huge_fraction = 0.2;
    p.max_sides = 5;
    p.min_size = 0.2;
    p.max_size = 0.3;
    Scene *s = scene_bigpoly_new(&p);
    const SceneMesh *m = scene_instance_mesh(s, 0);
    assert_int_equal(scene_mesh_n_polys(m), 300);
    guint huge = 0, small_sides[6] = {0}, sign[2][8] = {{0}};
    for (guint i = 0; i < 300; i++) {
        assert_int_equal(g_array_index(m->poly_tag, uint32_t, i), i);
        const uint32_t *v = scene_mesh_poly(m, i);
        guint n = scene_mesh_poly_len(m, i);
        Vec3 c = vec3(0, 0, 0);
        for (guint k = 0; k < n; k++)
            c = vec3_add(c, vec3_scale(scene_mesh_vertex(m, v[k]), 1.0 / n));
        double r = vec3_len(vec3_sub(scene_mesh_vertex(m, v[0]), c));
        for (guint k = 0; k < n; k++) {
            Vec3 q = scene_mesh_vertex(m, v[k]);
            NEAR(vec3_len(vec3_sub(q, c)), r, 1e-9);
            assert_true(q.z == c.z || fabs(q.z - c.z) < 1e-12);
        }
        assert_true(c.z >= -1 && c.z <= 1);
        corners_step_evenly(m, i, c);
        count_signs(sign[r > 0.9], m, i, c);
        SceneColor col = g_array_index(m->poly_color, SceneColor, i);
        assert_true(col.r >= 0 && col.r <= 1 && col.b >= 0 && col.b <= 1);
        if (r > 0.9) { /* huge */
            huge++;
            assert_true(n >= 4 && n <= 8);
            assert_true(r >= 0.95 - 1e-9 && r <= 1.25 + 1e-9);
            assert_true(fabs(c.x) <= 0.2 + 1e-9 && fabs(c.y) <= 0.2 + 1e-9);
            assert_true(covered(m, i) > 0.75 * 4 - 0.05);
        } else {
            assert_true(n >= 3 && n <= 5);
            small_sides[n]++;
            assert_true(r >= 0.2 - 1e-9 && r <= 0.3 + 1e-9);
            assert_true(fabs(c.x) <= 1 && fabs(c.y) <= 1);
        }
    }
    assert_true(huge > 30 && huge < 90);
    assert_true(small_sides[3] > 0 && small_sides[4] > 0 && small_sides[5] > 0);
    /* up to 16 corners, the most the generator takes: every count drawn */
    SceneBigPolyParams q = p;
    q.count = 400;
    q.huge_fraction = 0;
    q.max_sides = 16;
    Scene *sq = scene_bigpoly_new(&q);
    const SceneMesh *mq = scene_instance_mesh(sq, 0);
    guint seen[17] = {0};
    for (guint i = 0; i < 400; i++) {
        guint n = scene_mesh_poly_len(mq, i);
        assert_true(n >= 3 && n <= 16);
        seen[n]++;
    }
    for (guint n = 3; n <= 16; n++)
        assert_true(seen[n] > 0);
    scene_free(sq);
    /* centres, depths and turns drawn over their whole ranges */
    for (guint h = 0; h < 2; h++)
        for (guint k = 0; k < 8; k++)
            if (sign[h][k] == 0)
                fail_msg("%s polygons: no sign case %u", h ? "huge" : "small", k);
    /* the camera: orthographic, the unit square filling the view */
    assert_int_equal(s->camera.proj, SCENE_ORTHOGRAPHIC);
    assert_true(s->camera.eye.z == 2 && s->camera.height == 2 &&
                s->camera.near == 0.5 && s->camera.far == 3.5);
    assert_true(s->camera.eye.x == 0 && s->camera.eye.y == 0);
    assert_true(s->camera.target.x == 0 && s->camera.target.y == 0 &&
                s->camera.target.z == 0); /* looking at the origin */
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_and_fields),
        cmocka_unit_test(test_one_ball),
        cmocka_unit_test(test_gyroid_cells),
        cmocka_unit_test(test_iso_check),
        cmocka_unit_test(test_bigpoly),
        cmocka_unit_test(test_huge_rule),
    };
    return cmocka_run_group_tests_name("iso_props", tests, NULL, NULL);
}
