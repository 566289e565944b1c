/* test_sf_regions.c — screen regions and the bounding-box bucket sort
 * (sf_regions.h) on cases worked out by hand: region rectangles, the
 * screen rectangle of a box (clip space = object space under the
 * identity), the outcode cull (a box is dropped only when all eight
 * corners are out on one same plane), corners on or behind the eye, and
 * which regions a screen rectangle touches (one pixel of margin, a
 * region's pixel centres). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/workload/sortfirst/sf_regions.h"

static SceneBox box(double x0, double y0, double z0, double x1, double y1,
                    double z1)
{
    return (SceneBox){vec3(x0, y0, z0), vec3(x1, y1, z1)};
}

static void expect_rect(const WlSfRegions *r, guint p, int x0, int y0, int x1,
                        int y1)
{
    WlSfRect q = wl_sf_region_rect(r, p);
    assert_int_equal(q.x0, x0);
    assert_int_equal(q.y0, y0);
    assert_int_equal(q.x1, x1);
    assert_int_equal(q.y1, y1);
}

/* 6 regions of 100 x 80: 3 columns (the first divisor >= sqrt 6) by 2
 * rows, edges at floor(col * 100 / 3) and row * 40. */
static void test_region_rects(void **st)
{
    (void)st;
    WlSfRegions r;
    wl_sf_regions_init(&r, 6, 100, 80);
    assert_int_equal(r.cols, 3);
    assert_int_equal(r.rows, 2);
    expect_rect(&r, 0, 0, 0, 33, 40);
    expect_rect(&r, 1, 33, 0, 66, 40);
    expect_rect(&r, 2, 66, 0, 100, 40);
    expect_rect(&r, 3, 0, 40, 33, 80);
    expect_rect(&r, 5, 66, 40, 100, 80);
    wl_sf_regions_init(&r, 1, 7, 5);
    expect_rect(&r, 0, 0, 0, 7, 5);
}

static void expect_screen(const WlSfRegions *r, SceneBox b, Mat4 m,
                          gboolean on, double x0, double y0, double x1,
                          double y1)
{
    double a, c, d, e;
    assert_int_equal(wl_sf_box_screen(r, b, m, &a, &c, &d, &e), on);
    if (!on)
        return;
    assert_true(a == x0 && c == y0 && d == x1 && e == y1);
    WlSfScreen s = wl_sf_screen_of(r, b, m);
    assert_true(s.on);
    assert_true(s.x0 == x0 && s.y0 == y0 && s.x1 == x1 && s.y1 == y1);
}

/* Identity on a 100 x 80 screen: x in [-0.5, 0.5] -> (x + 1) 50 in
 * [25, 75]; y in [-0.5, 0.5] -> (1 - y) 40 in [20, 60] (y flips). */
static void test_box_screen(void **st)
{
    (void)st;
    WlSfRegions r;
    wl_sf_regions_init(&r, 4, 100, 80);
    Mat4 id = mat4_identity();
    expect_screen(&r, box(-0.5, -0.5, -0.5, 0.5, 0.5, 0.5), id, TRUE, 25, 20,
                  75, 60);
    expect_screen(&r, box(0, 0.5, 0, 1, 1, 0.5), id, TRUE, 50, 0, 100, 20);
    /* straddling the screen: its corners are out left or out right, on
     * no one plane, so the box is kept: [-100, 200] x [20, 60] */
    expect_screen(&r, box(-3, -0.5, 0, 3, 0.5, 0), id, TRUE, -100, 20, 200,
                  60);
    expect_screen(&r, box(-0.5, -3, 0, 0.5, 3, 0), id, TRUE, 25, -80, 75,
                  160);
    expect_screen(&r, box(0, 0, -3, 0.5, 0.5, 3), id, TRUE, 50, 20, 75, 40);
    /* wholly out on one plane, each of the six */
    expect_screen(&r, box(-3, 0, 0, -1.5, 0.5, 0), id, FALSE, 0, 0, 0, 0);
    expect_screen(&r, box(1.5, 0, 0, 3, 0.5, 0), id, FALSE, 0, 0, 0, 0);
    expect_screen(&r, box(0, -3, 0, 0.5, -1.5, 0), id, FALSE, 0, 0, 0, 0);
    expect_screen(&r, box(0, 1.5, 0, 0.5, 3, 0), id, FALSE, 0, 0, 0, 0);
    expect_screen(&r, box(0, 0, -3, 0.5, 0.5, -1.5), id, FALSE, 0, 0, 0, 0);
    expect_screen(&r, box(0, 0, 1.5, 0.5, 0.5, 3), id, FALSE, 0, 0, 0, 0);
    /* exactly on the planes x = w and y = -w is not out */
    expect_screen(&r, box(1, -1, 1, 1, -1, 1), id, TRUE, 100, 80, 100, 80);
    expect_screen(&r, box(-1, 1, -1, -1, 1, -1), id, TRUE, 0, 0, 0, 0);
}

/* A square rotated 45 degrees about z, centred at (2, -2): its corners
 * (3.5, -2), (0.5, -2), (2, -0.5), (2, -3.5) are out right, out below,
 * or both, but not all on one plane: kept (the test is conservative). */
static void test_diamond_kept(void **st)
{
    (void)st;
    WlSfRegions r;
    wl_sf_regions_init(&r, 1, 100, 80);
    double h = 1.5 / sqrt(2.0);
    Mat4 m = mat4_mul(mat4_translate(2, -2, 0),
                      mat4_rotate(vec3(0, 0, 1), G_PI / 4));
    double x0, y0, x1, y1;
    assert_true(wl_sf_box_screen(&r, box(-h, -h, 0, h, h, 0), m, &x0, &y0, &x1,
                                 &y1));
    assert_true(fabs(x0 - 75) < 1e-9 && fabs(x1 - 225) < 1e-9);
    assert_true(fabs(y0 - 60) < 1e-9 && fabs(y1 - 180) < 1e-9);
    /* the same moved down-left: out right? no; out left or below, the
     * mirror image, kept too */
    m = mat4_mul(mat4_translate(-2, 2, 0),
                 mat4_rotate(vec3(0, 0, 1), G_PI / 4));
    assert_true(wl_sf_box_screen(&r, box(-h, -h, 0, h, h, 0), m, &x0, &y0, &x1,
                                 &y1));
}

/* w = z (row 3 of the matrix picks z): a corner at w = 0 or below is
 * behind the eye and makes the rectangle the whole plane. */
static void test_behind_eye(void **st)
{
    (void)st;
    WlSfRegions r;
    wl_sf_regions_init(&r, 1, 100, 80);
    Mat4 m = mat4_identity();
    m.m[3][2] = 1;
    m.m[3][3] = 0;
    m.m[2][2] = 0; /* clip z = 0: never out in z */
    double x0, y0, x1, y1;
    /* z in [1, 2]: w >= 1, x / w in [-0.5, 0.5] at z = 1 */
    assert_true(wl_sf_box_screen(&r, box(-0.5, -0.5, 1, 0.5, 0.5, 2), m, &x0,
                                 &y0, &x1, &y1));
    assert_true(x0 == 25 && x1 == 75 && y0 == 20 && y1 == 60);
    /* z in [0, 1]: four corners at w = 0 exactly (one at x = y = 0,
     * where x / w would be NaN) */
    assert_true(wl_sf_box_screen(&r, box(0, 0, 0, 0.5, 0.5, 1), m, &x0,
                                 &y0, &x1, &y1));
    assert_true(x0 == -INFINITY && y0 == -INFINITY);
    assert_true(x1 == INFINITY && y1 == INFINITY);
    /* z in [-1, 1]: behind too */
    assert_true(wl_sf_box_screen(&r, box(-0.5, -0.5, -1, 0.5, 0.5, 1), m, &x0,
                                 &y0, &x1, &y1));
    assert_true(x0 == -INFINITY && x1 == INFINITY);
}

/* Regions touched: 2 x 2 regions of 40 x 40 (edges at 20).  A rectangle
 * grows by one pixel each side; region p is touched when it reaches its
 * outermost pixel centres (x0 + 0.5 .. x1 - 0.5). */
static void test_screen_regions(void **st)
{
    (void)st;
    WlSfRegions r;
    wl_sf_regions_init(&r, 4, 40, 40);
    WlSfScreen s = {.on = TRUE, .x0 = 5, .y0 = 5, .x1 = 10, .y1 = 10};
    assert_int_equal(wl_sf_screen_regions(&r, &s), 0x1);
    s.x1 = 19.5; /* + 1 = 20.5: reaches region 1's first centre */
    assert_int_equal(wl_sf_screen_regions(&r, &s), 0x3);
    s.x1 = 19.4;
    assert_int_equal(wl_sf_screen_regions(&r, &s), 0x1);
    s.y1 = 19.5;
    assert_int_equal(wl_sf_screen_regions(&r, &s), 0x5);
    s = (WlSfScreen){.on = TRUE, .x0 = 20.5, .y0 = 20.5, .x1 = 30, .y1 = 30};
    /* - 1 = 19.5: region 0's last centre, both ways */
    assert_int_equal(wl_sf_screen_regions(&r, &s), 0xf);
    s.x0 = 20.6;
    assert_int_equal(wl_sf_screen_regions(&r, &s), 0xa);
    s.y0 = 20.6;
    assert_int_equal(wl_sf_screen_regions(&r, &s), 0x8);
    s.on = FALSE;
    assert_int_equal(wl_sf_screen_regions(&r, &s), 0);
    /* through a box: identity, x, y in [-0.5, 0.5] -> [10, 30]: all four;
     * an empty box none */
    assert_int_equal(wl_sf_box_regions(&r, box(-0.5, -0.5, 0, 0.5, 0.5, 0),
                                       mat4_identity()),
                     0xf);
    SceneBox e = scene_box_empty();
    assert_int_equal(wl_sf_box_regions(&r, e, mat4_identity()), 0);
    assert_false(wl_sf_screen_of(&r, e, mat4_identity()).on);
}

/* The screen-rectangle store: a key's array is made once (fresh), then
 * handed back as it is; clear forgets every key. */
static void test_screen_set(void **st)
{
    (void)st;
    WlSfScreenSet *s = wl_sf_screen_set_new();
    Mat4 m = mat4_identity();
    gboolean fresh = FALSE;
    WlSfScreen *a = wl_sf_screen_set_get(s, 2, 3, m, &fresh);
    assert_true(fresh);
    a[2].x0 = 7;
    WlSfScreen *b = wl_sf_screen_set_get(s, 2, 3, m, &fresh);
    assert_false(fresh);
    assert_ptr_equal(a, b);
    assert_true(b[2].x0 == 7);
    wl_sf_screen_set_get(s, 0, 0, m, &fresh);
    assert_true(fresh);
    wl_sf_screen_set_get(s, 0, 0, m, &fresh);
    assert_false(fresh);
    wl_sf_screen_set_clear(s);
    wl_sf_screen_set_get(s, 2, 3, m, &fresh);
    assert_true(fresh);
    wl_sf_screen_set_free(s);
    wl_sf_screen_set_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_region_rects),
        cmocka_unit_test(test_box_screen),
        cmocka_unit_test(test_diamond_kept),
        cmocka_unit_test(test_behind_eye),
        cmocka_unit_test(test_screen_regions),
        cmocka_unit_test(test_screen_set),
    };
    return cmocka_run_group_tests_name("sf_regions", tests, NULL, NULL);
}
