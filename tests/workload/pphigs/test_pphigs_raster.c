/* test_pphigs_raster.c — the PPHIGS pixel commands on an 8 x 8 screen
 * worked out by hand (identity view: screen X = 4 (x + 1), Y = 4 (1 - y),
 * every coordinate a binary fraction, so the arithmetic is exact): the
 * pixel box (pixel centres X + 0.5 inside the polygon's bounds, a bound
 * exactly on a centre included), the fill rule (a centre exactly on an
 * edge is drawn for left and top edges only, whatever the winding; a
 * repeated vertex changes nothing), the per-command expression count and
 * the depth key. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>

#include "sim/workload/pphigs/pphigs_pixels.h"

#define N 8

typedef struct {
    Vec3 v[8];
    SceneElem el;
    ScenePrimInst pi;
} Poly;

/* A polygon of n screen points (X, Y), z = 0. */
static void poly(Poly *p, const double (*xy)[2], guint n)
{
    for (guint i = 0; i < n; i++)
        p->v[i] = vec3(xy[i][0] / 4 - 1, 1 - xy[i][1] / 4, 0);
    p->el = scene_elem_prim(n == 3 ? SCENE_EL_TRIANGLE : SCENE_EL_POLYGON,
                            p->v, n);
    p->pi = (ScenePrimInst){.el = &p->el,
                            .matrix = mat4_identity(),
                            .color = vec3(1, 1, 1)};
}

/* The screen rectangle [x0, x1] x [y0, y1] as a quad, clockwise on the
 * screen when cw (Y grows downwards). */
static void rect(Poly *p, double x0, double y0, double x1, double y1,
                 gboolean cw)
{
    const double a[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    const double b[4][2] = {{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}};
    poly(p, cw ? a : b, 4);
}

/* The commands of p; their count must be `want`. */
static GArray *cmds(const Poly *p, guint want)
{
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&p->pi, mat4_identity(), N, N, out),
                     want);
    assert_int_equal(out->len, want);
    return out;
}

static void expect_box(const WlPphigsCmd *c, int x0, int y0, int x1, int y1)
{
    assert_int_equal(c->x0, x0);
    assert_int_equal(c->y0, y0);
    assert_int_equal(c->x1, x1);
    assert_int_equal(c->y1, y1);
}

/* Draws p's one command on a fresh screen; the pixels drawn must be
 * exactly `mask` (bit y * 8 + x). */
static void expect_pixels(const Poly *p, uint64_t mask)
{
    GArray *c = cmds(p, 1);
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, N, N, 0);
    assert_int_equal(
        wl_pphigs_region_draw(r, &g_array_index(c, WlPphigsCmd, 0)),
        __builtin_popcountll(mask));
    for (int i = 0; i < N * N; i++)
        if ((r->key[i] != 0) != ((mask >> i) & 1))
            fail_msg("pixel (%d, %d): key %llu", i % N, i / N,
                     (unsigned long long)r->key[i]);
    wl_pphigs_region_free(r);
    g_array_unref(c);
}

#define PX(x, y) (UINT64_C(1) << ((y) * N + (x)))

/* [0.5, 2.5]^2: centres 0.5, 1.5, 2.5 each way; the left (X = 0.5) and
 * top (Y = 0.5) edges draw their centres, the right and bottom do not:
 * pixels (0..1, 0..1), in either winding. */
static void test_fill_rule(void **st)
{
    (void)st;
    const uint64_t want = PX(0, 0) | PX(1, 0) | PX(0, 1) | PX(1, 1);
    for (int cw = 0; cw < 2; cw++) {
        Poly p;
        rect(&p, 0.5, 0.5, 2.5, 2.5, cw);
        GArray *c = cmds(&p, 1);
        expect_box(&g_array_index(c, WlPphigsCmd, 0), 0, 0, 2, 2);
        assert_int_equal(g_array_index(c, WlPphigsCmd, 0).nedges, 4);
        assert_int_equal(wl_pphigs_cmd_exprs(&g_array_index(c, WlPphigsCmd, 0)),
                         4 + 1 + 3);
        g_array_unref(c);
        expect_pixels(&p, want);
    }
    /* a triangle: the diagonal X + Y = 4 through centres (0.5, 3.5),
     * (1.5, 2.5), (2.5, 1.5), (3.5, 0.5) is a right-bottom edge: not
     * drawn; the centres with X + Y = 1, 2, 3 are */
    static const double tri[3][2] = {{0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5}};
    static const double tri_ccw[3][2] = {{0.5, 0.5}, {0.5, 3.5}, {3.5, 0.5}};
    const uint64_t t = PX(0, 0) | PX(1, 0) | PX(2, 0) | PX(0, 1) | PX(1, 1) |
                       PX(0, 2);
    Poly p;
    poly(&p, tri, 3);
    expect_pixels(&p, t);
    GArray *c = cmds(&p, 1);
    assert_int_equal(wl_pphigs_cmd_exprs(&g_array_index(c, WlPphigsCmd, 0)),
                     3 + 1 + 3);
    g_array_unref(c);
    poly(&p, tri_ccw, 3);
    expect_pixels(&p, t);
    /* the same triangle given as a quad with a repeated vertex */
    static const double dup[4][2] = {{0.5, 0.5}, {0.5, 0.5}, {3.5, 0.5},
                                     {0.5, 3.5}};
    poly(&p, dup, 4);
    expect_pixels(&p, t);
    static const double dup2[4][2] = {{0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5},
                                      {0.5, 3.5}};
    poly(&p, dup2, 4);
    expect_pixels(&p, t);
}

/* A bound exactly on the first or last pixel centre keeps the command
 * (its box is that one column or row; the fill rule decides the pixels);
 * a tenth past it there is no command. */
static void test_box_edges(void **st)
{
    (void)st;
    Poly p;
    rect(&p, -1, 0.5, 0.5, 2.5, TRUE); /* right edge on centre 0.5 */
    GArray *c = cmds(&p, 1);
    expect_box(&g_array_index(c, WlPphigsCmd, 0), 0, 0, 0, 2);
    g_array_unref(c);
    expect_pixels(&p, 0);
    rect(&p, 0.5, -1, 2.5, 0.5, TRUE); /* bottom edge on centre 0.5 */
    c = cmds(&p, 1);
    expect_box(&g_array_index(c, WlPphigsCmd, 0), 0, 0, 2, 0);
    g_array_unref(c);
    expect_pixels(&p, 0);
    rect(&p, 7.5, 0.5, 9, 2.5, TRUE); /* left edge on centre 7.5 */
    c = cmds(&p, 1);
    expect_box(&g_array_index(c, WlPphigsCmd, 0), 7, 0, 7, 2);
    g_array_unref(c);
    expect_pixels(&p, PX(7, 0) | PX(7, 1));
    rect(&p, 0.5, 7.5, 2.5, 9, TRUE); /* top edge on centre 7.5 */
    c = cmds(&p, 1);
    expect_box(&g_array_index(c, WlPphigsCmd, 0), 0, 7, 2, 7);
    g_array_unref(c);
    expect_pixels(&p, PX(0, 7) | PX(1, 7));
    /* the whole screen and more: the box clamps to it */
    rect(&p, -4, -4, 12, 12, TRUE);
    c = cmds(&p, 1);
    expect_box(&g_array_index(c, WlPphigsCmd, 0), 0, 0, 7, 7);
    g_array_unref(c);
    expect_pixels(&p, ~UINT64_C(0));
    /* just outside each side: nothing */
    rect(&p, -1, 0.5, 0.25, 2.5, TRUE);
    g_array_unref(cmds(&p, 0));
    rect(&p, 0.5, -1, 2.5, 0.25, TRUE);
    g_array_unref(cmds(&p, 0));
    rect(&p, 7.75, 0.5, 9, 2.5, TRUE);
    g_array_unref(cmds(&p, 0));
    rect(&p, 0.5, 7.75, 2.5, 9, TRUE);
    g_array_unref(cmds(&p, 0));
    /* between two centres: a box with no centre, no command */
    rect(&p, 1.75, 1.75, 2.25, 2.25, TRUE);
    g_array_unref(cmds(&p, 0));
}

/* z = 0 maps to depth llrint(0.5 (2^32 - 1)) = 2^31 (ties to even), the
 * key depth << 31 | tag = 2^62 | tag. */
static void test_depth_key(void **st)
{
    (void)st;
    Poly p;
    rect(&p, 0.5, 0.5, 1.5, 1.5, TRUE);
    p.el.tag = 5;
    GArray *c = cmds(&p, 1);
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, N, N, 0x12345678u);
    assert_int_equal(wl_pphigs_region_draw(r, &g_array_index(c, WlPphigsCmd, 0)),
                     1);
    assert_true(r->key[0] == ((UINT64_C(1) << 62) | 5));
    assert_int_equal(r->rgba[1], 0x12345678u);
    /* drawn again: an equal key does not win */
    assert_int_equal(wl_pphigs_region_draw(r, &g_array_index(c, WlPphigsCmd, 0)),
                     0);
    wl_pphigs_region_free(r);
    g_array_unref(c);
}

/* A triangle of twice-area 0.5625 (under one pixel) still draws the
 * centre it covers, in either winding. */
static void test_tiny_triangle(void **st)
{
    (void)st;
    static const double t[3][2] = {{0.25, 0.25}, {1, 0.25}, {0.25, 1}};
    static const double u[3][2] = {{0.25, 0.25}, {0.25, 1}, {1, 0.25}};
    Poly p;
    poly(&p, t, 3);
    expect_pixels(&p, PX(0, 0));
    poly(&p, u, 3);
    expect_pixels(&p, PX(0, 0));
}

/* Depth follows the plane through the vertices: a rectangle over the
 * whole width with z = x (NDC), so z = X / 4 - 1 at a pixel centre X:
 * the key's depth is llrint((1 - z) / 2 (2^32 - 1)), largest on the
 * left (nearest). */
static void test_sloped_depth(void **st)
{
    (void)st;
    Poly p;
    rect(&p, 0, 0, 8, 1, TRUE);
    for (int i = 0; i < 4; i++)
        p.v[i].z = p.v[i].x;
    GArray *c = cmds(&p, 1);
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, N, N, 0);
    assert_int_equal(wl_pphigs_region_draw(r, &g_array_index(c, WlPphigsCmd, 0)),
                     8);
    for (int x = 0; x < N; x++) {
        double z = (x + 0.5) / 4 - 1;
        uint64_t depth = (uint64_t)llrint((1 - z) / 2 * (double)UINT32_MAX);
        assert_true(r->key[x] == depth << 31);
    }
    wl_pphigs_region_free(r);
    g_array_unref(c);
}

/* The depth plane z = a X + b Y + c through screen points (4, 4), (8, 4),
 * (4, 8) at z 0.5, 0.25, 0.75: a = -1/16, b = 1/16, c = 0.5 + 4/16 -
 * 4/16 = 0.5. */
static void test_depth_plane(void **st)
{
    (void)st;
    static const double xy[3][2] = {{4, 4}, {8, 4}, {4, 8}};
    Poly p;
    poly(&p, xy, 3);
    p.v[0].z = 0.5, p.v[1].z = 0.25, p.v[2].z = 0.75;
    GArray *c = cmds(&p, 1);
    const WlPphigsCmd *k = &g_array_index(c, WlPphigsCmd, 0);
    assert_true(k->z.a == -1.0 / 16 && k->z.b == 1.0 / 16 && k->z.c == 0.5);
    g_array_unref(c);
}

/* Flat shading: s = 0.3 + 0.7 |n.z| / |n| with n the normal in NDC.
 * Screen points (0.5, 0.5), (4.5, 2.5), (2.5, 6.5) at z 0.125, 0.5,
 * -0.25: u = (1, -0.5, 0.375), v = (0.5, -1.5, -0.375),
 * n = u x v = (0.75, 0.5625, -1.25), |n| = 1.5625, s = 0.86; colour
 * (1, 0.5, 0.25) -> 219.3, 109.65, 54.825 -> 0xff376edb (0xAABBGGRR). */
static void test_shading_exact(void **st)
{
    (void)st;
    static const double t[3][2] = {{0.5, 0.5}, {4.5, 2.5}, {2.5, 6.5}};
    static const double z[3] = {0.125, 0.5, -0.25};
    Poly p;
    poly(&p, t, 3);
    for (int i = 0; i < 3; i++)
        p.v[i].z = z[i];
    p.pi.color = vec3(1, 0.5, 0.25);
    GArray *c = cmds(&p, 1);
    assert_int_equal(g_array_index(c, WlPphigsCmd, 0).rgba, 0xff376edbu);
    g_array_unref(c);
}

/* The depth plane and the shading come from the fan triangle (0, i,
 * i + 1) of largest area: on the convex pentagon (0, 0) (4, 0) (8, 1)
 * (8, 8) (0, 4) the fan triangles have twice-areas 4, 56 and 32, so
 * (0, 2, 3), whose three vertices have z = 0, gives z = 0 everywhere
 * although vertex 4 has z = 0.5 (a non-planar polygon). */
static void test_largest_fan(void **st)
{
    (void)st;
    static const double xy[5][2] = {{0, 0}, {4, 0}, {8, 1}, {8, 8}, {0, 4}};
    Poly p;
    poly(&p, xy, 5);
    p.v[4].z = 0.5;
    GArray *c = cmds(&p, 1);
    const WlPphigsCmd *k = &g_array_index(c, WlPphigsCmd, 0);
    assert_true(k->z.a == 0 && k->z.b == 0 && k->z.c == 0);
    assert_int_equal(k->rgba, 0xffffffffu); /* facing the eye */
    g_array_unref(c);
}

/* Near clipping: a view that takes w from z (x, y kept, z' = 0) and a
 * triangle A (0, 0, 1), B (0.375, 0, 1), C (0, 0.5, -1) with C behind
 * the eye.  Clipped at w = 1e-6 the edges BC and CA end at w ~ 0, far
 * off the screen: the polygon is A (4, 4), B (5.5, 4) and two points
 * far up along the projections of BC (X = 5.5 + 0.75 (4 - Y)) and CA
 * (X = 4).  Pixel centres (no centre within 0.125 of an edge): rows
 * Y = 3.5: X 4.5, 5.5; 2.5 and 1.5: 4.5 .. 6.5; 0.5: 4.5 .. 7.5. */
static void test_near_clip(void **st)
{
    (void)st;
    Mat4 wz = mat4_identity();
    wz.m[2][2] = 0;
    wz.m[3][2] = 1;
    wz.m[3][3] = 0;
    Vec3 v[3] = {vec3(0, 0, 1), vec3(0.375, 0, 1), vec3(0, 0.5, -1)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1)};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, wz, N, N, out), 1);
    const WlPphigsCmd *c = &g_array_index(out, WlPphigsCmd, 0);
    assert_int_equal(c->nedges, 4);
    expect_box(c, 4, 0, 7, 3);
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, N, N, 0);
    uint64_t mask = PX(4, 3) | PX(5, 3) | PX(4, 2) | PX(5, 2) | PX(6, 2) |
                    PX(4, 1) | PX(5, 1) | PX(6, 1) | PX(4, 0) | PX(5, 0) |
                    PX(6, 0) | PX(7, 0);
    assert_int_equal(wl_pphigs_region_draw(r, c), 12);
    for (int i = 0; i < N * N; i++)
        assert_int_equal(r->key[i] != 0, (mask >> i) & 1);
    wl_pphigs_region_free(r);
    /* a polygon of more vertices than a command has edges: nothing */
    Vec3 ring[WL_PPHIGS_MAX_EDGES + 1];
    for (int i = 0; i <= WL_PPHIGS_MAX_EDGES; i++)
        ring[i] = vec3(0.5 * cos(i * 2 * G_PI / (WL_PPHIGS_MAX_EDGES + 1)),
                       0.5 * sin(i * 2 * G_PI / (WL_PPHIGS_MAX_EDGES + 1)), 0);
    SceneElem big = scene_elem_prim(SCENE_EL_POLYGON, ring,
                                    WL_PPHIGS_MAX_EDGES + 1);
    ScenePrimInst bp = {.el = &big, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1)};
    g_array_set_size(out, 0);
    assert_int_equal(wl_pphigs_cmds(&bp, mat4_identity(), N, N, out), 0);
    assert_int_equal(out->len, 0);
    big.nverts = WL_PPHIGS_MAX_EDGES; /* the largest that draws */
    assert_int_equal(wl_pphigs_cmds(&bp, mat4_identity(), N, N, out), 1);
    assert_int_equal(g_array_index(out, WlPphigsCmd, 0).nedges,
                     WL_PPHIGS_MAX_EDGES); /* every vertex kept */
    /* wholly behind the eye: nothing */
    for (int i = 0; i < 3; i++)
        v[i].z = -1;
    g_array_set_size(out, 0);
    assert_int_equal(wl_pphigs_cmds(&pi, wz, N, N, out), 0);
    g_array_unref(out);
}

/* A vertex exactly on the near plane (w = 1e-6, the clip's bound) is
 * outside: both edges through it are cut there, so the polygon keeps two
 * copies of it (one from each cut) and the command has 4 edges, 8
 * expressions. */
static void test_vertex_on_near_plane(void **st)
{
    (void)st;
    Mat4 wz = mat4_identity();
    wz.m[2][2] = 0;
    wz.m[3][2] = 1;
    wz.m[3][3] = 0;
    Vec3 v[3] = {vec3(0, 0, 1), vec3(0.375, 0, 1), vec3(0, 0.5, 1e-6)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    ScenePrimInst pi = {.el = &e, .matrix = mat4_identity(),
                        .color = vec3(1, 1, 1)};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(&pi, wz, N, N, out), 1);
    const WlPphigsCmd *c = &g_array_index(out, WlPphigsCmd, 0);
    assert_int_equal(c->nedges, 4);
    assert_int_equal(wl_pphigs_cmd_exprs(c), 8);
    /* just in front of the plane the vertex is kept once */
    v[2].z = 2e-6;
    g_array_set_size(out, 0);
    assert_int_equal(wl_pphigs_cmds(&pi, wz, N, N, out), 1);
    assert_int_equal(g_array_index(out, WlPphigsCmd, 0).nedges, 3);
    /* on the plane again, with A behind the eye: the edge C A is wholly
     * outside and adds nothing; the polygon is the cut of A B, B and the
     * cut of B C (3 edges; C kept as inside would add itself and a cut
     * of C A at C: 5) */
    v[2].z = 1e-6;
    v[0].z = -1;
    g_array_set_size(out, 0);
    assert_int_equal(wl_pphigs_cmds(&pi, wz, N, N, out), 1);
    assert_int_equal(g_array_index(out, WlPphigsCmd, 0).nedges, 3);
    g_array_unref(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fill_rule),
        cmocka_unit_test(test_box_edges),
        cmocka_unit_test(test_depth_key),
        cmocka_unit_test(test_tiny_triangle),
        cmocka_unit_test(test_sloped_depth),
        cmocka_unit_test(test_shading_exact),
        cmocka_unit_test(test_near_clip),
        cmocka_unit_test(test_vertex_on_near_plane),
        cmocka_unit_test(test_largest_fan),
        cmocka_unit_test(test_depth_plane),
    };
    return cmocka_run_group_tests_name("pphigs_raster", tests, NULL, NULL);
}
