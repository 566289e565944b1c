/* test_clip_values.c — exact results of sim/raster/clip.c (issue 21).
 *
 * Outcodes of points inside, on and just outside every plane (guard band
 * g = 2, so a swapped sign or a dropped g shows); for each plane a
 * triangle with one corner outside it by as much as the other two are
 * inside, so every cut is an exact midpoint, checked bit for bit with
 * its colour and its place in the output; a corner exactly on a plane
 * (Sutherland–Hodgman emits it twice); cuts of the w plane never below
 * RAST_CLIP_WMIN; cut points staying on the triangle's own plane in
 * homogeneous space even when a cut falls behind the eye; and direction
 * independence when an edge's ends differ in one coordinate only. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/core/rng.h"
#include "sim/raster/clip.h"

static RastVert cv(double x, double y, double z, double w, float r, float g,
                   float b)
{
    return (RastVert){{x, y, z, w}, {r, g, b}};
}

static RastVert mid(RastVert a, RastVert b)
{
    return cv((a.pos.x + b.pos.x) / 2, (a.pos.y + b.pos.y) / 2,
              (a.pos.z + b.pos.z) / 2, (a.pos.w + b.pos.w) / 2,
              (a.col.r + b.col.r) / 2, (a.col.g + b.col.g) / 2,
              (a.col.b + b.col.b) / 2);
}

static void assert_vert(const RastVert *got, const RastVert *want, int i)
{
    if (memcmp(&got->pos, &want->pos, sizeof got->pos) != 0 ||
        memcmp(&got->col, &want->col, sizeof got->col) != 0)
        fail_msg("vertex %d: (%g %g %g %g | %g %g %g), expected "
                 "(%g %g %g %g | %g %g %g)",
                 i, got->pos.x, got->pos.y, got->pos.z, got->pos.w, got->col.r,
                 got->col.g, got->col.b, want->pos.x, want->pos.y, want->pos.z,
                 want->pos.w, want->col.r, want->col.g, want->col.b);
}

static void test_outcodes(void **state)
{
    (void)state;
    const double g = 2.0;
    /* on every guard plane at once, and on near and far with w = 1 */
    assert_int_equal(rast_clip_outcode((Vec4){2, 2, 1, 1}, g), 0);
    assert_int_equal(rast_clip_outcode((Vec4){-2, -2, -1, 1}, g), 0);
    assert_int_equal(rast_clip_outcode((Vec4){0, 0, 0, 1}, g), 0);
    assert_int_equal(rast_clip_outcode((Vec4){0, 0, -1.5, 1}, g),
                     RAST_OUT_NEAR);
    assert_int_equal(rast_clip_outcode((Vec4){0, 0, 1.5, 1}, g), RAST_OUT_FAR);
    assert_int_equal(rast_clip_outcode((Vec4){-2.5, 0, 0, 1}, g),
                     RAST_OUT_LEFT);
    assert_int_equal(rast_clip_outcode((Vec4){2.5, 0, 0, 1}, g),
                     RAST_OUT_RIGHT);
    assert_int_equal(rast_clip_outcode((Vec4){0, -2.5, 0, 1}, g),
                     RAST_OUT_BOTTOM);
    assert_int_equal(rast_clip_outcode((Vec4){0, 2.5, 0, 1}, g), RAST_OUT_TOP);
    /* w = 0 at the origin: on near, far and the guard planes, below WMIN */
    assert_int_equal(rast_clip_outcode((Vec4){0, 0, 0, 0}, g), RAST_OUT_W);
    assert_int_equal(rast_clip_outcode((Vec4){0, 0, 0, RAST_CLIP_WMIN}, g), 0);
    /* the guard scales with w: x = 3 is inside at w = 2 (g w = 4) */
    assert_int_equal(rast_clip_outcode((Vec4){3, -3, 0, 2}, g), 0);
    assert_int_equal(rast_clip_outcode((Vec4){3, -3, 0, 2}, 1.0),
                     RAST_OUT_RIGHT | RAST_OUT_BOTTOM);
    /* behind the eye: every plane but far (w - z = 1) */
    assert_int_equal(rast_clip_outcode((Vec4){0.5, 0.5, -2, -1}, 1.0),
                     RAST_OUT_NEAR | RAST_OUT_W | RAST_OUT_LEFT |
                         RAST_OUT_RIGHT | RAST_OUT_BOTTOM | RAST_OUT_TOP);
    assert_int_equal(rast_clip_outcode((Vec4){NAN, 0, 0, 1}, 1.0),
                     RAST_OUT_LEFT | RAST_OUT_RIGHT);
}

/* One plane a time: t[1] is outside by 1 (d = -1), t[0] and t[2] inside
 * by 1, so both cuts are midpoints: out = t0, mid(t0, t1), mid(t2, t1), t2.
 * Every corner is inside every other plane. */
static void test_each_plane_midpoints(void **state)
{
    (void)state;
    const double g = 2.0;
    const struct {
        unsigned bit;
        RastVert t[3];
    } cases[] = {
        {RAST_OUT_NEAR,
         {cv(0, 0, 0, 1, 1, 0, 0), cv(0.5, 0, -2, 1, 0, 1, 0),
          cv(1, 1, 0, 1, 0, 0, 1)}},
        {RAST_OUT_FAR,
         {cv(0, 0, 0, 1, 1, 0, 0), cv(0.5, 0, 2, 1, 0, 1, 0),
          cv(1, 1, 0, 1, 0, 0, 1)}},
        {RAST_OUT_LEFT,
         {cv(-1, 0, 0, 1, 1, 0, 0), cv(-3, 0.5, 0, 1, 0, 1, 0),
          cv(-1, 1, 0, 1, 0, 0, 1)}},
        {RAST_OUT_RIGHT,
         {cv(1, 0, 0, 1, 1, 0, 0), cv(3, 0.5, 0, 1, 0, 1, 0),
          cv(1, 1, 0, 1, 0, 0, 1)}},
        {RAST_OUT_BOTTOM,
         {cv(0, -1, 0, 1, 1, 0, 0), cv(0.5, -3, 0, 1, 0, 1, 0),
          cv(1, -1, 0, 1, 0, 0, 1)}},
        {RAST_OUT_TOP,
         {cv(0, 1, 0, 1, 1, 0, 0), cv(0.5, 3, 0, 1, 0, 1, 0),
          cv(1, 1, 0, 1, 0, 0, 1)}},
        /* the guard band at w = 2: x = -5 is outside by 1 (g w = 4) */
        {RAST_OUT_LEFT,
         {cv(-3, 0, 0, 2, 1, 0, 0), cv(-5, 0.5, 0, 2, 0, 1, 0),
          cv(-3, 1, 0, 2, 0, 0, 1)}},
    };
    for (size_t k = 0; k < G_N_ELEMENTS(cases); k++) {
        const RastVert *t = cases[k].t;
        assert_int_equal(rast_clip_outcode(t[0].pos, g), 0);
        assert_int_equal(rast_clip_outcode(t[1].pos, g), cases[k].bit);
        assert_int_equal(rast_clip_outcode(t[2].pos, g), 0);
        RastVert want[4] = {t[0], mid(t[0], t[1]), mid(t[2], t[1]), t[2]};
        /* every rotation of the corners gives the same cycle */
        for (int rot = 0; rot < 3; rot++) {
            RastVert in[3] = {t[rot], t[(rot + 1) % 3], t[(rot + 2) % 3]};
            RastVert out[RAST_CLIP_MAX];
            int n = rast_clip_polygon(in, 3, g, out);
            if (n != 4)
                fail_msg("case %zu rotation %d: %d vertices", k, rot, n);
            const int firsts[3] = {0, 2, 3};
            int first = firsts[rot];
            for (int i = 0; i < 4; i++)
                assert_vert(&out[i], &want[(first + i) % 4], i);
        }
    }
}

/* Cut off one corner (x = 3, w = 1, outside the right plane x <= 1 by 2
 * with g = 1) of a triangle whose third corner lies exactly on the
 * plane: Sutherland-Hodgman emits that corner as the crossing of the edge
 * coming in and again as an inside vertex, bit for bit (t = 0). */
static void test_corner_on_plane(void **state)
{
    (void)state;
    RastVert t[3] = {cv(-1, 0, 0, 1, 1, 0, 0), cv(3, 0, 0, 1, 0, 1, 0),
                     cv(1, 0.5, 0, 1, 0, 0, 1)};
    RastVert out[RAST_CLIP_MAX];
    assert_int_equal(rast_clip_polygon(t, 3, 1.0, out), 4);
    RastVert cut = mid(t[0], t[1]); /* d = 2 and -2 */
    assert_vert(&out[0], &t[0], 0);
    assert_vert(&out[1], &cut, 1);
    assert_vert(&out[2], &t[2], 2);
    assert_vert(&out[3], &t[2], 3);
    /* the other winding: the corner on the plane now precedes the one
     * outside, is emitted, then again as the crossing of the edge out */
    RastVert u[3] = {t[0], t[2], t[1]};
    assert_int_equal(rast_clip_polygon(u, 3, 1.0, out), 4);
    assert_vert(&out[0], &t[0], 0);
    assert_vert(&out[1], &t[2], 1);
    assert_vert(&out[2], &t[2], 2);
    assert_vert(&out[3], &cut, 3);
    /* inside every plane: copied whole; outside one: nothing */
    RastVert in[3] = {t[0], t[2], cv(0, -1, 0.5, 1, 0.5f, 0.5f, 0.5f)};
    assert_int_equal(rast_clip_polygon(in, 3, 1.0, out), 3);
    for (int i = 0; i < 3; i++)
        assert_vert(&out[i], &in[i], i);
    RastVert far[3] = {cv(0, 0, 2, 1, 1, 1, 1), cv(1, 0, 3, 1, 1, 1, 1),
                       cv(0, 1, 1.5, 1, 1, 1, 1)};
    assert_int_equal(rast_clip_polygon(far, 3, 1.0, out), 0);
}

/* Two corners beyond the right plane: the polygon keeps the inside corner
 * and the two cuts, a triangle; a quad cut by two planes at once gains
 * one vertex per plane. */
static void test_two_outside_and_two_planes(void **state)
{
    (void)state;
    RastVert t[3] = {cv(0, 0, 0, 1, 0, 0, 0), cv(2, 0, 0, 1, 1, 1, 1),
                     cv(2, 1, 0, 1, 1, 1, 1)};
    RastVert out[RAST_CLIP_MAX];
    assert_int_equal(rast_clip_polygon(t, 3, 1.0, out), 3);
    RastVert a = mid(t[0], t[1]), b = mid(t[0], t[2]);
    assert_vert(&out[0], &t[0], 0);
    assert_vert(&out[1], &a, 1);
    assert_vert(&out[2], &b, 2);
    /* corner (3, 3) of a convex quad is outside right and top: the right
     * plane makes a pentagon, the top plane a hexagon; the other corners
     * stay in place and every cut lies on x = 1 or y = 1 */
    RastVert q[4] = {cv(-1, -1, 0, 1, 1, 1, 1), cv(0, -1, 0, 1, 1, 1, 1),
                     cv(3, 3, 0, 1, 1, 1, 1), cv(-1, 0, 0, 1, 1, 1, 1)};
    int n = rast_clip_polygon(q, 4, 1.0, out);
    assert_int_equal(n, 6);
    assert_vert(&out[0], &q[0], 0);
    assert_vert(&out[1], &q[1], 1);
    assert_vert(&out[5], &q[3], 5);
    for (int i = 2; i < 5; i++) {
        double x = out[i].pos.x, y = out[i].pos.y;
        assert_true(x <= 1 + 1e-12 && y <= 1 + 1e-12);
        assert_true(fabs(x - 1) < 1e-12 || fabs(y - 1) < 1e-12);
    }
    assert_true(fabs(out[2].pos.x - 1) < 1e-12); /* B-C on the right */
    assert_true(fabs(out[2].pos.y - 1.0 / 3) < 1e-12);
    assert_true(fabs(out[3].pos.x - 1) < 1e-12 && fabs(out[3].pos.y - 1) < 1e-12);
    assert_true(fabs(out[4].pos.y - 1) < 1e-12); /* C-D on the top */
    assert_true(fabs(out[4].pos.x - (-1 + 4.0 / 3)) < 1e-12);
}

/* Triangles reaching behind the eye (w down to -3) whose corners obey the
 * affine relation w = -0.5 + 0.6 x + 0.2 y - 0.25 z: clipping only interpolates, so
 * every output vertex obeys it too, none has w below RAST_CLIP_WMIN, and
 * every one is inside every plane up to rounding. */
static void test_behind_eye_cuts_stay_on_plane(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 4242, 0);
    int kept = 0;
    for (int k = 0; k < 2000; k++) {
        RastVert t[3];
        for (int i = 0; i < 3; i++) {
            double x = -3 + 6 * sim_rng_uniform(&r);
            double y = -3 + 6 * sim_rng_uniform(&r);
            double z = -4 + 8 * sim_rng_uniform(&r);
            t[i] = cv(x, y, z, -0.5 + 0.6 * x + 0.2 * y - 0.25 * z, 1, 1, 1);
        }
        RastVert out[RAST_CLIP_MAX];
        int n = rast_clip_polygon(t, 3, 3.0, out);
        kept += n > 0;
        for (int i = 0; i < n; i++) {
            Vec4 p = out[i].pos;
            double rel = -0.5 + 0.6 * p.x + 0.2 * p.y - 0.25 * p.z;
            if (fabs(p.w - rel) > 1e-9)
                fail_msg("triangle %d vertex %d: w %.17g, plane gives %.17g",
                         k, i, p.w, rel);
            assert_true(p.w >= RAST_CLIP_WMIN);
            assert_true(p.z + p.w >= -1e-9 && p.w - p.z >= -1e-9);
            assert_true(3.0 * p.w - fabs(p.x) >= -1e-9);
            assert_true(3.0 * p.w - fabs(p.y) >= -1e-9);
        }
    }
    assert_true(kept > 300);
}

/* The w plane alone: a corner at w = 0 on every other plane (x = y = z
 * = 0) is cut off at w = RAST_CLIP_WMIN or just above, never below. */
static void test_w_plane_cut(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 77, 0);
    for (int k = 0; k < 500; k++) {
        double w0 = 0.1 + sim_rng_uniform(&r), w2 = 0.1 + sim_rng_uniform(&r);
        RastVert t[3] = {cv(-0.05 * w0, 0, 0, w0, 1, 0, 0),
                         cv(0, 0, 0, 0, 0, 1, 0),
                         cv(0.05 * w2, 0.05 * w2, 0, w2, 0, 0, 1)};
        RastVert out[RAST_CLIP_MAX];
        int n = rast_clip_polygon(t, 3, 1.0, out);
        assert_int_equal(n, 4);
        assert_vert(&out[0], &t[0], 0);
        assert_vert(&out[3], &t[2], 3);
        for (int i = 1; i <= 2; i++) {
            assert_true(out[i].pos.w >= RAST_CLIP_WMIN);
            assert_true(out[i].pos.w < RAST_CLIP_WMIN * (1 + 1e-6));
            /* the colour is almost all the outside corner's */
            assert_true(out[i].col.g > 0.999f);
        }
    }
}

/* Only the planes some corner is outside of are applied: two corners on
 * the right plane (x = g w, g = 1.7) and one beyond the near plane; the
 * near cut on the edge along the right plane rounds 2e-16 past it, and
 * is kept as it is, not cut again (the polygon stays a quad). */
static void test_only_outcode_planes(void **state)
{
    (void)state;
    RastVert t[3] = {
        cv(2.4309753081198258, -0.16977793495316196, -0.43571258552789138,
           1.4299854753646033, 1, 1, 1),
        cv(1.3408351564419687, 0.29081897599213413, -1.3777739746111786,
           0.78872656261292273, 1, 1, 1),
        cv(0.15469342675443754, 0.48569348099674103, 0.088715405219625731,
           0.77346713377218757, 1, 1, 1)};
    assert_int_equal(rast_clip_outcode(t[0].pos, 1.7), 0);
    assert_int_equal(rast_clip_outcode(t[1].pos, 1.7), RAST_OUT_NEAR);
    assert_int_equal(rast_clip_outcode(t[2].pos, 1.7), 0);
    RastVert out[RAST_CLIP_MAX];
    assert_int_equal(rast_clip_polygon(t, 3, 1.7, out), 4);
    assert_vert(&out[0], &t[0], 0);
    assert_vert(&out[3], &t[2], 3);
    assert_true(1.7 * out[1].pos.w - out[1].pos.x < 0); /* the case is real */
}

static RastVert rand_vert(SimRng *r)
{
    return cv(-3 + 6 * sim_rng_uniform(r), -3 + 6 * sim_rng_uniform(r),
              -2 + 4 * sim_rng_uniform(r), -0.5 + 2.5 * sim_rng_uniform(r),
              (float)sim_rng_uniform(r), (float)sim_rng_uniform(r),
              (float)sim_rng_uniform(r));
}

/* The edge t0-t1 differs in coordinate c only; the triangle and its
 * mirror (t1, t0, t2) must clip to the same vertices bit for bit. */
static void test_single_coordinate_edges(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 9090, 0);
    for (int c = 0; c < 4; c++) {
        int differ = 0;
        for (int k = 0; k < 300; k++) {
            RastVert t[3] = {rand_vert(&r), rand_vert(&r), rand_vert(&r)};
            double *p0 = &t[0].pos.x, *p1 = &t[1].pos.x;
            for (int j = 0; j < 4; j++)
                if (j != c)
                    p1[j] = p0[j];
            RastVert u[3] = {t[1], t[0], t[2]};
            RastVert a[RAST_CLIP_MAX], b[RAST_CLIP_MAX];
            int na = rast_clip_polygon(t, 3, 1.0, a);
            int nb = rast_clip_polygon(u, 3, 1.0, b);
            assert_int_equal(na, nb);
            for (int i = 0; i < na; i++) {
                gboolean found = FALSE;
                for (int j = 0; j < nb && !found; j++)
                    found = memcmp(&a[i].pos, &b[j].pos, sizeof a[i].pos) == 0 &&
                            memcmp(&a[i].col, &b[j].col, sizeof a[i].col) == 0;
                if (!found)
                    fail_msg("coordinate %d, triangle %d: vertex %d of one "
                             "winding is not in the other",
                             c, k, i);
            }
            differ += na > 3;
        }
        assert_true(differ > 20);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_outcodes),
        cmocka_unit_test(test_each_plane_midpoints),
        cmocka_unit_test(test_corner_on_plane),
        cmocka_unit_test(test_two_outside_and_two_planes),
        cmocka_unit_test(test_behind_eye_cuts_stay_on_plane),
        cmocka_unit_test(test_w_plane_cut),
        cmocka_unit_test(test_single_coordinate_edges),
        cmocka_unit_test(test_only_outcode_planes),
    };
    return cmocka_run_group_tests_name("clip_values", tests, NULL, NULL);
}
