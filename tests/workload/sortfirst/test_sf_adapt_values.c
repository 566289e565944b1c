/* test_sf_adapt_values.c — the adaptive grid's estimate, weights and
 * calibration (sf_adapt.h) on values worked out by hand.
 *
 * The estimate: the five triangles of sf_test_hand_db() (one chunk
 * each, chunk c mastered by c mod 2) seen by an orthographic camera of
 * height 2 (screen x = 8 (wx + 1), y = 8 (1 - wy) on 16 x 16 pixels),
 * on a 4 x 4 grid of 4-pixel cells: each on-screen instance adds its
 * polygons to the cell of its box's centre, clipped to the screen; with
 * prediction the centre moves to 2 c - c_last, clamped to the screen.
 * weight_in sums the cells whose corner pixel lies in a rectangle;
 * calibrate sets each cell's factor to its region's work per weight. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/sortfirst/sf_adapt.h"
#include "tests/workload/sortfirst/sf_testutil.h"

static Mat4 ortho(void)
{
    SceneCamera c = {.proj = SCENE_ORTHOGRAPHIC,
                     .eye = vec3(0, 0, 5),
                     .target = vec3(0, 0, 0),
                     .up = vec3(0, 1, 0),
                     .fov_deg = 45,
                     .height = 2,
                     .near = 1,
                     .far = 10,
                     .aspect = 1};
    return scene_camera_view_proj(&c);
}

/* The G x G weights, as "cell:weight" pairs of the non-zero ones. */
static void expect_weights(const WlSfAdapt *a, const char *want)
{
    GString *got = g_string_new("");
    for (guint i = 0; i < a->grid * a->grid; i++)
        if (a->weight[i])
            g_string_append_printf(got, "%s%u:%llu", got->len ? " " : "", i,
                                   (unsigned long long)a->weight[i]);
    if (strcmp(got->str, want))
        fail_msg("weights %s, expected %s", got->str, want);
    g_string_free(got, TRUE);
}

static void expect_procs(const uint64_t *v, uint64_t a, uint64_t b,
                         const char *what)
{
    if (v[0] != a || v[1] != b)
        fail_msg("%s %llu %llu, expected %llu %llu", what,
                 (unsigned long long)v[0], (unsigned long long)v[1],
                 (unsigned long long)a, (unsigned long long)b);
}

/* Scaled by 0.1 about the origin every triangle is on screen: box
 * centres (screen) T0 (7.6, 7.6) cell 5, T1 (8.4, 7.6) cell 6, T2 (8, 8)
 * cell 10, T3 (10.6, 7.8) cell 6, T4 (10.6, 8.6) cell 10.  Processor 0
 * masters T0, T2, T4 (3 added, in cells 5 and 10: 2 non-zero), 1
 * masters T1, T3 (2 added, both in cell 6: 1 non-zero).  At full scale
 * T3 and T4 are off: T0 (4, 4) cell 5 (a centre on a cell edge is in
 * the cell after it), T1 (12, 4) cell 7, T2 (8, 8) cell 10. */
static void test_estimate(void **st)
{
    (void)st;
    SceneDb *src = sf_test_hand_db();
    WlSfDb *db = wl_sf_db_new(src, 2, 1, WL_SF_CHUNK_UNSORTED, NULL);
    assert_non_null(db);
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16);
    WlSfAdapt *a = wl_sf_adapt_new(4, 2);
    for (int k = 0; k < 2; k++) { /* a second estimate starts afresh */
        wl_sf_adapt_estimate(a, db, &r,
                             mat4_mul(ortho(), mat4_scale(0.1, 0.1, 0.1)));
        expect_weights(a, "5:1 6:2 10:2");
        expect_procs(a->added, 3, 2, "added");
        expect_procs(a->nz, 2, 1, "nz");
        assert_int_equal(a->predicted, 0);
    }
    wl_sf_adapt_estimate(a, db, &r, ortho());
    expect_weights(a, "5:1 7:1 10:1");
    expect_procs(a->added, 2, 1, "added");
    expect_procs(a->nz, 2, 1, "nz");
    /* every cell's weight adds up in weight_in over the whole screen */
    assert_int_equal(wl_sf_adapt_weight_in(a, &r, (WlSfRect){0, 0, 16, 16}), 3);
    wl_sf_adapt_free(a);
    wl_sf_db_free(db);
    scene_db_free(src);
}

/* A right triangle over [x0, x1] x [y0, y1] at z = 0 (world). */
static void tri(SceneDb *db, guint sid, double x0, double y0, double x1,
                double y1)
{
    Vec3 v[3] = {vec3(x0, y0, 0), vec3(x1, y0, 0), vec3(x0, y1, 0)};
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    assert_true(scene_db_append(db, sid, &e, NULL));
}

/* A database of one posted structure of the n triangles t[i] = (x0, y0,
 * x1, y1) (tri()), one chunk and instance each, all mastered by one
 * processor.  *src gets the structure database (free both). */
static WlSfDb *tris_db(SceneDb **src, const double (*t)[4], guint n)
{
    *src = scene_db_new();
    guint root = scene_db_add_struct(*src, "root");
    for (guint i = 0; i < n; i++)
        tri(*src, root, t[i][0], t[i][1], t[i][2], t[i][3]);
    scene_db_post(*src, root);
    WlSfDb *db = wl_sf_db_new(*src, 1, 1, WL_SF_CHUNK_UNSORTED, NULL);
    assert_int_equal(wl_sf_n_insts(db), n);
    return db;
}

/* One processor's estimate of db on `grid` x `grid` cells of the 16 x
 * 16 screen under ortho(); its weights must be `want` (free it). */
static WlSfAdapt *estimate_one(const WlSfDb *db, guint grid,
                               const char *want)
{
    WlSfRegions r;
    wl_sf_regions_init(&r, 1, 16, 16);
    WlSfAdapt *a = wl_sf_adapt_new(grid, 1);
    wl_sf_adapt_estimate(a, db, &r, ortho());
    expect_weights(a, want);
    return a;
}

/* One processor masters three triangles: A and B with box centres at
 * screen (13.6, 5.6), C at (1, 5).  On 4 x 4 cells A and B share cell
 * 7 (counted once in nz: the 8th bit of the processor's first mark
 * byte), C is in cell 4.  On 16 x 16 cells of one pixel, C's centre
 * x = 1 is on the edge of column 1 and falls in it: cell 5 x 16 + 1.
 * D, flat at world x = 1, has its centre on the screen's right edge
 * (x = 16, y = 5.6): the last column of its row (cells 7 and 95). */
static void test_cells(void **st)
{
    (void)st;
    static const double t[4][4] = {
        {0.6, 0.2, 0.8, 0.4},
        {0.6, 0.2, 0.8, 0.4},
        {-0.9375, 0.3125, -0.8125, 0.4375},
        {1, 0.2, 1, 0.4}, /* flat, on the right edge x = 16 */
    };
    SceneDb *src;
    WlSfDb *db = tris_db(&src, t, 4);
    WlSfAdapt *a = estimate_one(db, 4, "4:1 7:3");
    assert_int_equal(a->added[0], 4);
    assert_int_equal(a->nz[0], 2);
    wl_sf_adapt_free(a);
    a = estimate_one(db, 16, "81:1 93:2 95:1");
    assert_int_equal(a->nz[0], 3);
    wl_sf_adapt_free(a);
    wl_sf_db_free(db);
    scene_db_free(src);
}

/* A box's centre is that of its part on screen (clamped at 0 and at
 * the size on each axis), on 4 x 4 cells of 4 pixels.  A over screen
 * [-4, 7.5] x [-4, 7.5]: centre (3.75, 3.75), cell 0 (clamped at 1
 * instead it would be 4.25: cell 1 or 4).  B over [2, 30] x [6, 20]:
 * centre (9, 11), cell 10 (unclamped (16, 13): cell 15). */
static void test_clamped_centres(void **st)
{
    (void)st;
    static const double t[3][4] = {{-1.5, 1.5, -0.0625, 0.0625},
                                   {-0.75, 0.25, 2.75, -1.5},
                                   {-0.75, 0.25, 2.75, -1.5}};
    SceneDb *src;
    WlSfDb *db = tris_db(&src, t, 3);
    wl_sf_adapt_free(estimate_one(db, 4, "0:1 10:2"));
    wl_sf_db_free(db);
    scene_db_free(src);
}

/* Prediction: frame 1 at full scale (centres as above, none predicted);
 * frame 2 moved 2 px right (world + 0.25): T0 (6, 4), T1 (14, 4), T2
 * (10, 8) extrapolate to (8, 4) cell 6, (16, 4) clamped cell 7, (12, 8)
 * cell 11; 3 predicted.  Without prediction: cells 5, 7, 10.  Frame 3
 * far off screen forgets every history, so frame 4 (back at frame 1's
 * view) predicts nothing. */
static void test_predict(void **st)
{
    (void)st;
    SceneDb *src = sf_test_hand_db();
    WlSfDb *db = wl_sf_db_new(src, 2, 1, WL_SF_CHUNK_UNSORTED, NULL);
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16);
    WlSfAdapt *a = wl_sf_adapt_new(4, 2), *plain = wl_sf_adapt_new(4, 2);
    wl_sf_adapt_predict(a, wl_sf_n_insts(db));
    Mat4 moved = mat4_mul(ortho(), mat4_translate(0.25, 0, 0));
    wl_sf_adapt_estimate(a, db, &r, ortho());
    expect_weights(a, "5:1 7:1 10:1");
    assert_int_equal(a->predicted, 0);
    wl_sf_adapt_estimate(a, db, &r, moved);
    expect_weights(a, "6:1 7:1 11:1");
    assert_int_equal(a->predicted, 3);
    wl_sf_adapt_estimate(plain, db, &r, moved);
    expect_weights(plain, "5:1 7:1 10:1");
    assert_int_equal(plain->predicted, 0);
    wl_sf_adapt_estimate(a, db, &r,
                         mat4_mul(ortho(), mat4_translate(50, 0, 0)));
    expect_weights(a, "");
    for (guint i = 0; i < 5; i++)
        assert_int_equal(a->last_ok[i], 0);
    wl_sf_adapt_estimate(a, db, &r, ortho());
    expect_weights(a, "5:1 7:1 10:1");
    assert_int_equal(a->predicted, 0);
    /* the history kept: the centres of the last estimate */
    assert_true(a->last_x[0] == 4 && a->last_y[0] == 4);
    assert_true(a->last_x[2] == 8 && a->last_y[2] == 8);
    assert_int_equal(a->last_ok[1], 1);
    assert_int_equal(a->last_ok[3], 0);
    wl_sf_adapt_free(plain);
    wl_sf_adapt_free(a);
    wl_sf_db_free(db);
    scene_db_free(src);
}

/* Cell i weighs 2^i, so a sum names its cells.  On 16 px a cell's
 * corner is at 4 x; on 10 px at 0, 2, 5, 7 (x w / G, rounded down). */
static void test_weight_in(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(4, 4);
    for (guint i = 0; i < 16; i++)
        a->weight[i] = 1u << i;
    WlSfRegions r;
    wl_sf_regions_init(&r, 4, 16, 16);
    static const struct {
        WlSfRect q;
        uint64_t want;
    } cases[] = {
        {{0, 0, 16, 16}, 0xffff},
        {{-5, -5, 21, 21}, 0xffff}, /* beyond the screen: each cell once */
        {{4, 4, 8, 8}, 1u << 5},
        {{0, 0, 4, 4}, 1},
        {{0, 0, 5, 5}, 1 | 2 | 16 | 32},
        {{5, 4, 12, 8}, 1u << 6},
        {{1, 1, 4, 4}, 0},
        {{12, 12, 16, 16}, 1u << 15},
        {{8, 0, 16, 8}, 4 | 8 | 64 | 128},
    };
    for (guint k = 0; k < G_N_ELEMENTS(cases); k++) {
        uint64_t got = wl_sf_adapt_weight_in(a, &r, cases[k].q);
        if (got != cases[k].want)
            fail_msg("case %u: %#llx, expected %#llx", k,
                     (unsigned long long)got,
                     (unsigned long long)cases[k].want);
    }
    wl_sf_regions_init(&r, 4, 10, 10);
    assert_int_equal(wl_sf_adapt_weight_in(a, &r, (WlSfRect){2, 0, 5, 10}),
                     2 | 32 | 512 | 8192);
    assert_int_equal(wl_sf_adapt_weight_in(a, &r, (WlSfRect){0, 5, 10, 7}),
                     0xf00);
    wl_sf_adapt_free(a);
}

/* Four 8 x 8 tiles over 4 x 4 cells.  Tile 0 weighs 10 (cell 0) and
 * worked 50: factor 5; tile 1 weighs 4 (cell 2), worked 8: 2; tile 2
 * weighs nothing: the mean of the others, 13 / 3; tile 3 weighs 5
 * (cell 15), worked 30: 6. */
static void test_calibrate_tiles(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(4, 4);
    a->weight[0] = 10;
    a->weight[2] = 4;
    a->weight[15] = 5;
    WlSfRegions r;
    wl_sf_regions_init(&r, 4, 16, 16);
    double work[4] = {50, 8, 99, 30};
    assert_false(a->calibrated);
    wl_sf_adapt_calibrate(a, &r, work);
    assert_true(a->calibrated);
    for (guint y = 0; y < 4; y++)
        for (guint x = 0; x < 4; x++) {
            guint tile = (y >= 2) * 2 + (x >= 2);
            double want[4] = {5, 2, 13.0 / 3, 6};
            if (a->factor[y * 4 + x] != want[tile])
                fail_msg("cell (%u, %u): %g, expected %g", x, y,
                         a->factor[y * 4 + x], want[tile]);
        }
    wl_sf_adapt_free(a);
}

/* Only the first P regions count: 2 processors (left and right halves
 * of 16 x 16), the rect[] entries past them left from a 4-way split
 * (region 2 the bottom-left tile, holding weight).  Left: cells 0 (10)
 * and 8 (4), worked 42: factor 3; right: no weight, the mean over the
 * two regions with weight, left's only: 3. */
static void test_calibrate_first_regions(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(4, 2);
    a->weight[0] = 10;
    a->weight[8] = 4;
    WlSfRegions r, four;
    wl_sf_regions_init(&four, 4, 16, 16);
    wl_sf_regions_init(&r, 2, 16, 16);
    r.rect[2] = four.rect[2];
    r.rect[3] = four.rect[3];
    double *work = g_new(double, 2); /* exactly P figures */
    work[0] = 42;
    work[1] = 7;
    wl_sf_adapt_calibrate(a, &r, work);
    for (guint i = 0; i < 16; i++)
        if (a->factor[i] != 3)
            fail_msg("cell %u: %g, expected 3", i, a->factor[i]);
    g_free(work);
    wl_sf_adapt_free(a);
}

/* 3 x 3 cells of weight 1 on 12 x 12 pixels, 6 processors.  The root
 * is cut at column 1 (columns 1 and 2 both leave 18 and lie 0.5 from the
 * proportional 1.5: the first stays); the left column (3 processors) is
 * too narrow for a vertical cut, so rows: 1 | 2, then the 2 at row 2;
 * the right 2 x 3 (3 processors) is cut at row 1 (max(2 x 2, 4 x 1) =
 * 4, against 8 at row 2), its lower 2 x 2 at column 2.  Visited: the 9
 * table cells and 2 x (3 + 3 + 2 + 3 + 2) marginal lines. */
static void test_split_narrow(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(3, 6);
    for (guint i = 0; i < 9; i++)
        a->weight[i] = 1;
    WlSfRegions r;
    wl_sf_regions_init(&r, 6, 12, 12);
    assert_int_equal(wl_sf_adapt_split(a, &r), 35);
    static const int want[6][4] = {{0, 0, 4, 4},  {0, 4, 4, 8},
                                   {0, 8, 4, 12}, {4, 0, 12, 4},
                                   {4, 4, 8, 12}, {8, 4, 12, 12}};
    for (guint p = 0; p < 6; p++) {
        WlSfRect q = r.rect[p];
        if (q.x0 != want[p][0] || q.y0 != want[p][1] || q.x1 != want[p][2] ||
            q.y1 != want[p][3])
            fail_msg("region %u: [%d, %d) x [%d, %d)", p, q.x0, q.x1, q.y0,
                     q.y1);
    }
    wl_sf_adapt_free(a);
}

/* 6 x 6 cells of uneven weight (regions in cells below), 23 processors: deep in
 * the tree some nodes away from the grid's edge (lo > 0) are too short
 * for the cut across their longer side and are cut the other way, and
 * such a refused axis scans no marginal.  The regions and the 174 cells
 * visited were worked out with a separate model of the split rule
 * (sf_adapt.c's, re-implemented outside the simulator). */
static void test_split_refused_inside(void **st)
{
    (void)st;
    static const uint64_t w[36] = {7, 7,  7, 0, 20, 20, 20, 7, 0, 3, 3, 0,
                                   1, 20, 7, 1, 7,  0,  0,  1, 3, 7, 1, 7,
                                   0, 20, 0, 0, 1,  0,  7,  3, 3, 1, 0, 0};
    static const int want[23][4] = {
        {0, 0, 1, 1}, {1, 0, 2, 1}, {0, 1, 1, 3}, {1, 1, 2, 2}, {1, 2, 2, 3},
        {0, 3, 1, 4}, {0, 4, 1, 5}, {0, 5, 1, 6}, {1, 3, 2, 4}, {1, 4, 2, 5},
        {1, 5, 2, 6}, {2, 0, 3, 2}, {3, 0, 4, 1}, {3, 1, 4, 2}, {4, 0, 5, 2},
        {5, 0, 6, 1}, {5, 1, 6, 2}, {2, 2, 4, 3}, {2, 3, 4, 4}, {2, 4, 4, 6},
        {4, 2, 6, 3}, {4, 3, 6, 4}, {4, 4, 6, 6}};
    WlSfAdapt *a = wl_sf_adapt_new(6, 23);
    memcpy(a->weight, w, sizeof w);
    WlSfRegions r;
    wl_sf_regions_init(&r, 23, 24, 24); /* 4 px a cell */
    assert_int_equal(wl_sf_adapt_split(a, &r), 174);
    for (guint p = 0; p < 23; p++) {
        WlSfRect q = r.rect[p];
        if (q.x0 != 4 * want[p][0] || q.y0 != 4 * want[p][1] ||
            q.x1 != 4 * want[p][2] || q.y1 != 4 * want[p][3])
            fail_msg("region %u: [%d, %d) x [%d, %d)", p, q.x0, q.x1, q.y0,
                     q.y1);
    }
    wl_sf_adapt_free(a);
}

/* Which grids can hold which processor counts (hand-worked): 3 x 3
 * cells hold 7 but not 8 or 9 (halves of 4 and 4 or 5 each need 2 of
 * the 3 lines); 5 x 5 holds 21, not 22; every grid the config allows
 * (8 .. 1024) holds every count it allows (1 .. 64). */
static void test_fits(void **st)
{
    (void)st;
    assert_true(wl_sf_adapt_fits(3, 7));
    assert_false(wl_sf_adapt_fits(3, 8));
    assert_false(wl_sf_adapt_fits(3, 9));
    assert_true(wl_sf_adapt_fits(5, 21));
    assert_false(wl_sf_adapt_fits(5, 22));
    assert_true(wl_sf_adapt_fits(1, 1));
    for (guint g = 8; g <= 1024; g = g < 16 ? g + 1 : g * 2)
        for (guint p = 1; p <= WL_SF_MAX_PROCS; p++)
            if (!wl_sf_adapt_fits(g, p))
                fail_msg("grid %u, %u processors", g, p);
}

/* 29 processors on an 8 x 8 grid whose weights once led the split into
 * a node it could not cut (3 x 3 cells for 9 processors: an abort on a
 * valid config).  Every cut now leaves each side enough lines for its
 * whole subtree: the 29 regions are non-empty and tile the screen. */
static void test_split_29_on_8(void **st)
{
    (void)st;
    static const uint64_t w[64] = {
        0, 0, 0, 0, 0, 5,  0, 0, 5,  0,  40, 0, 0, 0, 0, 0,
        5, 0, 5, 5, 40, 0, 1, 40, 1, 1, 0,  1, 40, 0, 0, 1,
        1, 0, 40, 0, 1, 40, 0, 40, 0, 0, 0,  5, 40, 0, 0, 0,
        0, 1, 1, 0, 1, 0,  40, 40, 0, 0, 0, 0, 0,  5, 0, 0};
    WlSfAdapt *a = wl_sf_adapt_new(8, 29);
    memcpy(a->weight, w, sizeof w);
    WlSfRegions r;
    wl_sf_regions_init(&r, 29, 64, 64); /* 8 px a cell */
    wl_sf_adapt_split(a, &r);
    guint8 owner[64 * 64] = {0};
    for (guint p = 0; p < 29; p++) {
        WlSfRect q = r.rect[p];
        assert_true(q.x0 < q.x1 && q.y0 < q.y1);
        for (int y = q.y0; y < q.y1; y++)
            for (int x = q.x0; x < q.x1; x++)
                assert_int_equal(owner[y * 64 + x]++, 0);
    }
    for (guint i = 0; i < 64 * 64; i++)
        assert_int_equal(owner[i], 1);
    wl_sf_adapt_free(a);
}

/* Renumbered instances keep their history: new i takes old map[i]'s
 * centre and flag (old 0 included), a new one (-1) starts without; a
 * remap to no instance keeps prediction on (a later remap still
 * carries histories). */
static void test_remap(void **st)
{
    (void)st;
    WlSfAdapt *a = wl_sf_adapt_new(4, 2);
    wl_sf_adapt_predict(a, 3);
    for (guint i = 0; i < 3; i++) {
        a->last_x[i] = 1.5f + (float)i;
        a->last_y[i] = 10.25f + (float)i;
        a->last_ok[i] = i != 1;
    }
    const gint64 map[4] = {2, -1, 0, 1};
    wl_sf_adapt_remap(a, map, 4);
    assert_int_equal(a->n_insts, 4);
    static const float x[4] = {3.5f, 0, 1.5f, 2.5f};
    static const float y[4] = {12.25f, 0, 10.25f, 11.25f};
    static const guint8 ok[4] = {1, 0, 1, 0};
    for (guint i = 0; i < 4; i++) {
        assert_true(a->last_x[i] == x[i] && a->last_y[i] == y[i]);
        assert_int_equal(a->last_ok[i], ok[i]);
    }
    wl_sf_adapt_remap(a, map, 0);
    assert_int_equal(a->n_insts, 0);
    assert_non_null(a->last_x); /* still predicting */
    assert_non_null(a->last_y);
    assert_non_null(a->last_ok);
    const gint64 fresh[2] = {-1, -1};
    wl_sf_adapt_remap(a, fresh, 2);
    assert_int_equal(a->n_insts, 2);
    assert_true(a->last_x[1] == 0 && a->last_ok[0] == 0 && a->last_ok[1] == 0);
    wl_sf_adapt_free(a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_estimate),
        cmocka_unit_test(test_cells),
        cmocka_unit_test(test_clamped_centres),
        cmocka_unit_test(test_predict),
        cmocka_unit_test(test_remap),
        cmocka_unit_test(test_weight_in),
        cmocka_unit_test(test_calibrate_tiles),
        cmocka_unit_test(test_calibrate_first_regions),
        cmocka_unit_test(test_split_narrow),
        cmocka_unit_test(test_split_refused_inside),
        cmocka_unit_test(test_fits),
        cmocka_unit_test(test_split_29_on_8),
    };
    return cmocka_run_group_tests_name("sf_adapt_values", tests, NULL, NULL);
}
