/* test_image.c — images: PNG and PPM round trips, atomic writes. */
#include "tests/raster/rast_testutil.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>

static RastImage *pattern(int w, int h)
{
    RastImage *img = rast_image_new(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            rast_image_set(img, x, y,
                           (uint32_t)(x * 7) | (uint32_t)(y * 5) << 8 |
                               (uint32_t)((x ^ y) & 0xff) << 16);
    return img;
}

static char *tmpdir(void)
{
    char *d = g_dir_make_tmp("rast-image-XXXXXX", NULL);
    assert_non_null(d);
    return d;
}

/* Files in d (a leftover temporary would show up here). */
static int count_files(const char *d)
{
    GDir *dir = g_dir_open(d, 0, NULL);
    int n = 0;
    while (g_dir_read_name(dir))
        n++;
    g_dir_close(dir);
    return n;
}

static void test_round_trips(void **state)
{
    (void)state;
    char *d = tmpdir();
    char *png = g_build_filename(d, "a.png", NULL);
    char *ppm = g_build_filename(d, "a.ppm", NULL);
    RastImage *img = pattern(37, 23);
    GError *err = NULL;
    assert_true(rast_image_write(img, png, &err));
    assert_true(rast_image_write(img, ppm, &err));
    RastImage *a = rast_image_read_png(png, &err);
    RastImage *b = rast_image_read_ppm(ppm, &err);
    assert_non_null(a);
    assert_non_null(b);
    assert_true(rast_image_equal(img, a));
    assert_true(rast_image_equal(img, b));
    assert_int_equal(count_files(d), 2);
    /* Overwriting replaces the file in one step. */
    rast_image_fill(img, (RastColor){1, 0, 0});
    assert_true(rast_image_write(img, png, &err));
    RastImage *c = rast_image_read_png(png, &err);
    assert_int_equal(rast_image_get(c, 5, 5), 0xff0000ffu);
    assert_int_equal(count_files(d), 2);
    rast_image_free(a);
    rast_image_free(b);
    rast_image_free(c);
    rast_image_free(img);
    rast_image_free(NULL);
    g_unlink(png);
    g_unlink(ppm);
    g_rmdir(d);
    g_free(png);
    g_free(ppm);
    g_free(d);
}

static void test_write_errors(void **state)
{
    (void)state;
    RastImage *img = pattern(4, 4);
    GError *err = NULL;
    assert_false(rast_image_write(img, "/nonexistent-dir/x.png", &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_IO));
    g_clear_error(&err);
    char *d = tmpdir();
    char *bad = g_build_filename(d, "bad.ppm", NULL);
    g_file_set_contents(bad, "P6\n4 4\n255\nshort", -1, NULL);
    assert_null(rast_image_read_ppm(bad, &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_INPUT));
    assert_non_null(strstr(err->message, "bad.ppm:1:1: found"));
    g_clear_error(&err);
    g_file_set_contents(bad, "P3\n1 1\n255\n0 0 0\n", -1, NULL);
    assert_null(rast_image_read_ppm(bad, &err));
    g_clear_error(&err);
    assert_null(rast_image_read_png(bad, &err));
    g_clear_error(&err);
    g_unlink(bad);
    g_rmdir(d);
    g_free(bad);
    g_free(d);
    rast_image_free(img);
}

/* Images from both z-buffers: background where empty. */
static void test_from_buffers(void **state)
{
    (void)state;
    SceneMesh *m = tu_random_tris(2, 5, 0.3);
    RastView v = rast_view_make(mat4_identity(), 20, 20);
    v.cull_back = FALSE;
    v.lighting = FALSE;
    RastImage *f, *s;
    RastCounters c = {0};
    tu_render_both(&v, m, NULL, 0, &f, &s, &c, &c);
    assert_true(rast_image_equal(f, s));
    uint64_t bg = 0;
    for (int y = 0; y < 20; y++)
        for (int x = 0; x < 20; x++)
            bg += rast_image_get(f, x, y) == 0xff4d331au;
    assert_int_equal(bg + c.winners / 2, 400);
    rast_image_free(f);
    rast_image_free(s);
    scene_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trips),
        cmocka_unit_test(test_write_errors),
        cmocka_unit_test(test_from_buffers),
    };
    return cmocka_run_group_tests_name("image", tests, NULL, NULL);
}
