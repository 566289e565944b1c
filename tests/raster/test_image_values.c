/* test_image_values.c — the bytes sim/raster/image.c writes (issue 21).
 *
 * A 3x2 PNG starts with the signature, an IHDR of width 3, height 2, 8-bit
 * RGB, then an sRGB chunk (the simplified API's 8-bit sRGB default,
 * which a stray image flag would drop); a PPM is exactly its header and
 * the rows; pixels pack as 0xAABBGGRR and fill rounds to the nearest
 * 1/255; readers take sides from 1 to RAST_MAX_SIDE and refuse more. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>
#include <glib/gstdio.h>

#include "sim/raster/image.h"
#include "tests/support.h"

static uint32_t be32(const guchar *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 |
           p[3];
}

static void test_written_bytes(void **state)
{
    (void)state;
    char *d = g_dir_make_tmp("rast-imgv-XXXXXX", NULL);
    char *png = g_build_filename(d, "a.png", NULL);
    char *ppm = g_build_filename(d, "a.ppm", NULL);
    RastImage *img = rast_image_new(3, 2);
    rast_image_fill(img, (RastColor){0.5f, 0.0f, 1.0f});
    rast_image_set(img, 2, 1, 0xff030201u);
    assert_int_equal(rast_image_get(img, 0, 0), 0xffff0080u);
    assert_int_equal(rast_image_get(img, 2, 1), 0xff030201u);
    GError *err = NULL;
    assert_true(rast_image_write(img, png, &err));
    assert_true(rast_image_write(img, ppm, &err));
    gchar *data;
    gsize len;
    assert_true(g_file_get_contents(png, &data, &len, NULL));
    const guchar *b = (const guchar *)data;
    assert_true(len > 8 + 25 + 13);
    assert_memory_equal(b, "\x89PNG\r\n\x1a\n", 8);
    assert_int_equal(be32(b + 8), 13);
    assert_memory_equal(b + 12, "IHDR", 4);
    assert_int_equal(be32(b + 16), 3);
    assert_int_equal(be32(b + 20), 2);
    assert_int_equal(b[24], 8); /* bit depth */
    assert_int_equal(b[25], 2); /* colour type: RGB */
    assert_int_equal(be32(b + 33), 1);
    assert_memory_equal(b + 37, "sRGB", 4);
    g_free(data);
    assert_true(g_file_get_contents(ppm, &data, &len, NULL));
    const char head[] = "P6\n3 2\n255\n";
    assert_int_equal(len, strlen(head) + 18);
    assert_memory_equal(data, head, strlen(head));
    const guchar px[18] = {128, 0, 255, 128, 0, 255, 128, 0, 255,
                           128, 0, 255, 128, 0, 255, 1,   2, 3};
    assert_memory_equal(data + strlen(head), px, 18);
    g_free(data);
    rast_image_free(img);
    g_unlink(png);
    g_unlink(ppm);
    g_rmdir(d);
    g_free(png);
    g_free(ppm);
    g_free(d);
}

static char *write_png(const char *d, const char *name, int w, int h)
{
    char *path = g_build_filename(d, name, NULL);
    RastImage *img = rast_image_new(w, h);
    rast_image_set(img, w - 1, h - 1, 0xff0a0b0cu);
    GError *err = NULL;
    assert_true(rast_image_write_png(img, path, &err));
    rast_image_free(img);
    return path;
}

/* Sides of 1 and of exactly RAST_MAX_SIDE read back; one more is "bad
 * size"; missing files are I/O errors; a 1 x RAST_MAX_SIDE PPM reads.
 * GLib warnings are fatal here (main), so an error set twice fails. */
static void test_read_limits(void **state)
{
    (void)state;
    char *d = g_dir_make_tmp("rast-imgl-XXXXXX", NULL);
    const int sides[3][2] = {{RAST_MAX_SIDE, 1}, {1, RAST_MAX_SIDE}, {1, 1}};
    for (int k = 0; k < 3; k++) {
        char *path = write_png(d, "ok.png", sides[k][0], sides[k][1]);
        GError *err = NULL;
        RastImage *back = rast_image_read_png(path, &err);
        assert_non_null(back);
        assert_int_equal(back->width, sides[k][0]);
        assert_int_equal(back->height, sides[k][1]);
        assert_int_equal(rast_image_get(back, back->width - 1, back->height - 1),
                         0xff0a0b0cu);
        rast_image_free(back);
        g_unlink(path);
        g_free(path);
    }
    for (int k = 0; k < 2; k++) {
        char *path = write_png(d, "big.png", k ? 1 : RAST_MAX_SIDE + 1,
                               k ? RAST_MAX_SIDE + 1 : 1);
        GError *err = NULL;
        assert_null(rast_image_read_png(path, &err));
        assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_IO));
        assert_true(g_str_has_suffix(err->message, ": bad size"));
        g_clear_error(&err);
        g_unlink(path);
        g_free(path);
    }
    char *none = g_build_filename(d, "none.png", NULL);
    GError *err = NULL;
    assert_null(rast_image_read_png(none, &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_IO));
    g_clear_error(&err);
    assert_null(rast_image_read_ppm(none, &err));
    assert_non_null(err);
    g_clear_error(&err);
    /* a PPM one pixel wide and RAST_MAX_SIDE high */
    char *ppm = g_build_filename(d, "tall.ppm", NULL);
    RastImage *tall = rast_image_new(1, RAST_MAX_SIDE);
    rast_image_set(tall, 0, RAST_MAX_SIDE - 1, 0xff030201u);
    assert_true(rast_image_write_ppm(tall, ppm, &err));
    RastImage *back = rast_image_read_ppm(ppm, &err);
    assert_non_null(back);
    assert_true(rast_image_equal(back, tall));
    rast_image_free(back);
    rast_image_free(tall);
    g_unlink(ppm);
    g_free(ppm);
    g_free(none);
    g_rmdir(d);
    g_free(d);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_written_bytes),
        cmocka_unit_test(test_read_limits),
    };
    return cmocka_run_group_tests_name("image_values", tests, NULL, NULL);
}
