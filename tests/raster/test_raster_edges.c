/* test_raster_edges.c — boundaries of sim/raster that mutation testing
 * (make mutate, docs/testing.md) showed unchecked: clipping is
 * independent of the direction in which an edge is traversed even when
 * its ends differ only in z or w (clip.h), a polygon cut away entirely
 * without a trivial reject, the fan split of polygons above
 * RAST_POLY_MAX (pipeline.h: each piece counted once), and the image
 * readers' and writers' errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>
#include <glib/gstdio.h>

#include "rast_testutil.h"
#include "sim/raster/clip.h"
#include "sim/raster/spanlist.h"

static gboolean same_vert(const RastVert *a, const RastVert *b)
{
    return memcmp(&a->pos, &b->pos, sizeof a->pos) == 0 &&
           memcmp(&a->col, &b->col, sizeof a->col) == 0;
}

/* Every vertex of x[0..n) appears bit for bit in y[0..m). */
static gboolean all_in(const RastVert *x, int n, const RastVert *y, int m)
{
    for (int i = 0; i < n; i++) {
        gboolean found = FALSE;
        for (int j = 0; !found && j < m; j++)
            found = same_vert(&x[i], &y[j]);
        if (!found)
            return FALSE;
    }
    return TRUE;
}

static RastVert vert(SimRng *r, double lo, double hi)
{
    RastVert v;
    v.pos.x = lo + (hi - lo) * sim_rng_uniform(r);
    v.pos.y = lo + (hi - lo) * sim_rng_uniform(r);
    v.pos.z = lo + (hi - lo) * sim_rng_uniform(r);
    v.pos.w = 0.2 + 2.0 * sim_rng_uniform(r);
    v.col.r = (float)sim_rng_uniform(r);
    v.col.g = (float)sim_rng_uniform(r);
    v.col.b = (float)sim_rng_uniform(r);
    return v;
}

/* A triangle and the same triangle wound the other way clip to the same
 * vertices, bit for bit, when two of its corners share x; x and y; x, y
 * and z (the lexicographic order decides on the later coordinates). */
static void test_clip_direction_independent(void **state)
{
    (void)state;
    SimRng rng, *r = &rng;
    sim_rng_init(r, 2101, 0);
    int cut = 0;
    for (int share = 0; share < 4; share++) {
        for (int k = 0; k < 400; k++) {
            RastVert t[3] = {vert(r, -3, 3), vert(r, -3, 3), vert(r, -1, 1)};
            if (share >= 1)
                t[1].pos.x = t[0].pos.x;
            if (share >= 2)
                t[1].pos.y = t[0].pos.y;
            if (share >= 3) {
                t[1].pos.z = t[0].pos.z;
                t[0].pos.w = -0.5 + 3.0 * sim_rng_uniform(r);
            }
            RastVert u[3] = {t[1], t[0], t[2]};
            RastVert a[RAST_CLIP_MAX], b[RAST_CLIP_MAX];
            int na = rast_clip_polygon(t, 3, 1.0, a);
            int nb = rast_clip_polygon(u, 3, 1.0, b);
            assert_int_equal(na, nb);
            if (!all_in(a, na, b, nb) || !all_in(b, nb, a, na))
                fail_msg("share %d, triangle %d: the clipped vertices "
                         "depend on the winding",
                         share, k);
            cut += na > 3;
        }
    }
    assert_true(cut > 100); /* the triangles were cut, not kept whole */
}

/* Every vertex is outside one plane or another, but no single plane
 * has them all: clipping leaves nothing, counted as rejected. */
static void test_clipped_to_nothing(void **state)
{
    (void)state;
    RastVert t[3] = {tu_cv(3, -0.5, 0, 1), tu_cv(-0.5, 3, 0, 1),
                     tu_cv(3, 3, 0, 1)};
    RastVert out[RAST_CLIP_MAX];
    assert_int_equal(rast_clip_polygon(t, 3, 1.0, out), 0);
    unsigned a = rast_clip_outcode(t[0].pos, 1.0),
             b = rast_clip_outcode(t[1].pos, 1.0);
    assert_int_equal(a & b, 0);
    /* through the pipeline, with a guard band at the viewport */
    RastView v = rast_view_make(mat4_identity(), 64, 64);
    v.cull_back = FALSE;
    double g = rast_guard_band(64, 64);
    RastVert far[3] = {tu_cv(2 * g + 1, -0.5, 0, 1),
                       tu_cv(-0.5, 2 * g + 1, 0, 1),
                       tu_cv(2 * g + 1, 2 * g + 1, 0, 1)};
    RastCounters c = {0};
    TuCoverage *cv = tu_coverage_new(64, 64);
    rast_draw_clip_polygon(&v, far, 3, 0, tu_coverage_sink(cv), &c);
    assert_int_equal(c.prims, 1);
    assert_int_equal(c.rejected, 1);
    assert_int_equal(c.clipped, 0);
    assert_int_equal(c.pixels, 0);
    tu_coverage_free(cv);
}

/* A convex n-gon in the view, n = 3 .. 16. */
static SceneMesh *ngon(int n)
{
    SceneMesh *m = scene_mesh_new();
    uint32_t idx[16];
    for (int i = 0; i < n; i++) {
        double a = 2 * G_PI * i / n;
        idx[i] = scene_mesh_add_vertex(m, vec3(0.8 * cos(a), 0.8 * sin(a), 0));
    }
    scene_mesh_add_poly(m, idx, (guint)n, scene_color(1, 1, 1), 0);
    return m;
}

/* Up to RAST_POLY_MAX vertices a polygon is one primitive; above, n - 2
 * fan triangles of 3 transformed vertices each, which cover the same
 * pixels exactly once. */
static void test_fan_split_counts(void **state)
{
    (void)state;
    RastView v = rast_view_make(mat4_identity(), 96, 96);
    uint64_t area = 0;
    for (int n = 8; n <= 16; n++) {
        SceneMesh *m = ngon(n);
        RastCounters c = {0};
        TuCoverage *cv = tu_coverage_new(96, 96);
        rast_draw_mesh(&v, m, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                       tu_coverage_sink(cv), &c);
        gboolean whole = n <= RAST_POLY_MAX;
        assert_int_equal(c.prims, whole ? 1 : (uint64_t)(n - 2));
        assert_int_equal(c.verts, whole ? (uint64_t)n : 3 * (uint64_t)(n - 2));
        assert_int_equal(c.degenerate, 0);
        assert_int_equal(c.culled, 0);
        assert_int_equal(c.clipped, 0); /* inside every plane */
        assert_int_equal(c.rejected, 0);
        assert_int_equal(tu_coverage_max(cv), 1);
        uint64_t px = tu_coverage_count(cv, 1);
        assert_int_equal(c.pixels, px);
        assert_true(px > area); /* more sides, more of the circle */
        area = px;
        tu_coverage_free(cv);
        scene_mesh_free(m);
    }
}

static char *scratch(const char *name, char **dir)
{
    *dir = g_dir_make_tmp("rast-edges-XXXXXX", NULL);
    assert_non_null(*dir);
    return g_build_filename(*dir, name, NULL);
}

static void test_image_errors(void **state)
{
    (void)state;
    char *dir, *path = scratch("x.png", &dir);
    GError *err = NULL;
    /* missing */
    assert_null(rast_image_read_png(path, &err));
    assert_int_equal(err->code, SIM_ERROR_IO);
    assert_true(g_str_has_prefix(err->message, path));
    g_clear_error(&err);
    /* not a PNG */
    assert_true(g_file_set_contents(path, "P6\n1 1\n255\nabc", -1, NULL));
    assert_null(rast_image_read_png(path, &err));
    assert_true(g_str_has_prefix(err->message, path));
    g_clear_error(&err);
    /* a PNG cut short: the header reads, the pixels do not */
    RastImage *img = rast_image_new(40, 30);
    rast_image_fill(img, (RastColor){0.2f, 0.5f, 0.9f});
    for (int i = 0; i < 40; i++)
        rast_image_set(img, i, i % 30, 0xff00ffu + (uint32_t)i * 977u);
    assert_true(rast_image_write_png(img, path, &err));
    gchar *data;
    gsize len;
    assert_true(g_file_get_contents(path, &data, &len, NULL));
    assert_true(g_file_set_contents(path, data, (gssize)(len * 2 / 3), NULL));
    assert_null(rast_image_read_png(path, &err));
    assert_non_null(err);
    assert_true(g_str_has_prefix(err->message, path));
    g_clear_error(&err);
    assert_true(g_file_set_contents(path, data, (gssize)len, NULL));
    RastImage *back = rast_image_read_png(path, &err);
    assert_non_null(back);
    assert_true(rast_image_equal(img, back));
    rast_image_free(back);
    g_free(data);
    /* writing into a missing folder */
    char *nowhere = g_build_filename(dir, "no", "such", "x.png", NULL);
    assert_false(rast_image_write_png(img, nowhere, &err));
    assert_non_null(err);
    g_clear_error(&err);
    assert_false(rast_image_write(img, nowhere, &err));
    g_clear_error(&err);
    g_free(nowhere);
    /* PPM headers: maxval, size, pixel count */
    char *ppm = g_build_filename(dir, "x.ppm", NULL);
    static const char *const bad[] = {"P6\n1 1\n254\nabc", "P6\n0 1\n255\n",
                                      "P6\n1 0\n255\n", "P5\n1 1\n255\nabc",
                                      "P6\n16385 1\n255\n"};
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        assert_true(g_file_set_contents(ppm, bad[i], -1, NULL));
        assert_null(rast_image_read_ppm(ppm, &err));
        assert_non_null(strstr(err->message, "a malformed header"));
        g_clear_error(&err);
    }
    assert_true(g_file_set_contents(ppm, "P6\n1 1\n255\nabcd", -1, NULL));
    assert_null(rast_image_read_ppm(ppm, &err));
    assert_non_null(strstr(err->message, "a pixel array of the wrong size"));
    g_clear_error(&err);
    assert_true(g_file_set_contents(ppm, "P6\n1 1\n255\nab", -1, NULL));
    assert_null(rast_image_read_ppm(ppm, &err));
    g_clear_error(&err);
    assert_true(g_file_set_contents(ppm, "P6\n16384 1\n255\n", -1, NULL));
    assert_null(rast_image_read_ppm(ppm, &err));
    assert_non_null(strstr(err->message, "wrong size")); /* size passed */
    g_clear_error(&err);
    assert_true(g_file_set_contents(ppm, "P6\n1 1\n255\nabc", -1, NULL));
    back = rast_image_read_ppm(ppm, &err);
    assert_non_null(back);
    assert_int_equal(rast_image_get(back, 0, 0) & 0xffffffu,
                     rast_image_get(back, 0, 0) & 0xffffffu);
    assert_int_equal(back->rgb[0], 'a');
    assert_int_equal(back->rgb[2], 'c');
    rast_image_free(back);
    g_unlink(ppm);
    g_unlink(path);
    g_rmdir(dir);
    g_free(ppm);
    g_free(path);
    g_free(dir);
    rast_image_free(img);
}

/* Pixels: channels in place, fill, equality of sizes and contents,
 * differing pixels counted once whatever channel differs; write picks
 * PPM by the suffix and PNG otherwise. */
static void test_image_pixels(void **state)
{
    (void)state;
    RastImage *a = rast_image_new(3, 2), *b = rast_image_new(3, 2);
    rast_image_fill(a, (RastColor){0.0f, 1.0f, 0.5f});
    assert_int_equal(rast_image_get(a, 2, 1), 0xff80ff00u);
    assert_int_equal(a->rgb[0], 0);
    assert_int_equal(a->rgb[1], 255);
    assert_int_equal(a->rgb[2], 128);
    assert_int_equal(a->rgb[17], 128);
    rast_image_fill(b, (RastColor){0.0f, 1.0f, 0.5f});
    assert_true(rast_image_equal(a, b));
    assert_int_equal(rast_image_diff(a, b), 0);
    rast_image_set(b, 0, 0, 0x00000001u);
    rast_image_set(b, 2, 1, 0x00020000u | 0xff00u);
    assert_int_equal(rast_image_get(b, 0, 0), 0xff000001u);
    assert_int_equal(b->rgb[15], 0);
    assert_int_equal(b->rgb[16], 0xff);
    assert_int_equal(b->rgb[17], 2);
    assert_false(rast_image_equal(a, b));
    assert_int_equal(rast_image_diff(a, b), 2);
    rast_image_set(b, 1, 0, 0x0080ff01u); /* only its red differs */
    assert_int_equal(rast_image_diff(a, b), 3);
    RastImage *wide = rast_image_new(2, 3), *tall = rast_image_new(3, 3);
    assert_false(rast_image_equal(a, wide));
    assert_false(rast_image_equal(a, tall));
    char *dir = g_dir_make_tmp("rast-px-XXXXXX", NULL);
    char *ppm = g_build_filename(dir, "b.ppm", NULL);
    char *png = g_build_filename(dir, "b.png", NULL);
    GError *err = NULL;
    assert_true(rast_image_write(b, ppm, &err));
    assert_true(rast_image_write(b, png, &err));
    RastImage *r1 = rast_image_read_ppm(ppm, &err);
    RastImage *r2 = rast_image_read_png(png, &err);
    assert_non_null(r1);
    assert_non_null(r2);
    assert_true(rast_image_equal(r1, b));
    assert_true(rast_image_equal(r2, b));
    assert_null(rast_image_read_png(ppm, &err)); /* really a PPM */
    g_clear_error(&err);
    rast_image_free(r1);
    rast_image_free(r2);
    g_unlink(ppm);
    g_unlink(png);
    g_rmdir(dir);
    g_free(ppm);
    g_free(png);
    g_free(dir);
    rast_image_free(a);
    rast_image_free(b);
    rast_image_free(wide);
    rast_image_free(tall);
    rast_image_free(NULL);
}

/* A span list sorted, cleared and filled again, then added to and
 * sorted again: its last row's bounds are recomputed each time, not
 * left from the sort before. */
static void test_spanlist_reuse(void **state)
{
    (void)state;
    RastSpanList *sl = rast_spanlist_new(8, 4);
    RastSpan s = {0};
    s.y = 3;
    s.x0 = 1;
    s.x1 = 2;
    rast_spanlist_add(sl, &s);
    rast_spanlist_sort(sl);
    size_t n = 9;
    rast_spanlist_row(sl, 3, &n);
    assert_int_equal(n, 1);
    rast_spanlist_clear(sl);
    s.x0 = 4;
    s.x1 = 5;
    rast_spanlist_add(sl, &s);
    s.x0 = 2;
    s.x1 = 3;
    rast_spanlist_add(sl, &s);
    s.y = 0;
    rast_spanlist_add(sl, &s);
    rast_spanlist_sort(sl);
    assert_int_equal(rast_spanlist_len(sl), 3);
    const RastSpan *row = rast_spanlist_row(sl, 3, &n);
    assert_int_equal(n, 2);
    assert_int_equal(row[0].x0, 2);
    assert_int_equal(row[1].x0, 4);
    rast_spanlist_row(sl, 0, &n);
    assert_int_equal(n, 1);
    rast_spanlist_row(sl, 1, &n);
    assert_int_equal(n, 0);
    rast_spanlist_row(sl, 2, &n);
    assert_int_equal(n, 0);
    /* more spans after a sort, no clear: sorted again from scratch */
    s.y = 3;
    s.x0 = 6;
    s.x1 = 7;
    rast_spanlist_add(sl, &s);
    rast_spanlist_sort(sl);
    rast_spanlist_row(sl, 3, &n);
    assert_int_equal(n, 3);
    rast_spanlist_row(sl, 0, &n);
    assert_int_equal(n, 1);
    assert_int_equal(rast_spanlist_len(sl), 4);
    rast_spanlist_free(sl);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clip_direction_independent),
        cmocka_unit_test(test_clipped_to_nothing),
        cmocka_unit_test(test_fan_split_counts),
        cmocka_unit_test(test_image_errors),
        cmocka_unit_test(test_image_pixels),
        cmocka_unit_test(test_spanlist_reuse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
