/* test_render.c — `pgsim render`: OBJ input, PNG output, errors. */
#include "sim/app/commands.h"
#include "sim/scene/obj.h"
#include "sim/scene/ply.h"
#include "tests/raster/rast_testutil.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>

static const char *cube_obj =
    "# unit cube\n"
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2 3 7 6\n"
    "f -8 -4 -1 -5\n";

static int run_render(char *a0, char *a1, char *a2, char *a3)
{
    char *argv[] = {a0, a1, a2, a3, NULL};
    return cmd_render(4, argv);
}

static void test_render_obj(void **state)
{
    (void)state;
    char *d = g_dir_make_tmp("rast-render-XXXXXX", NULL);
    char *obj = g_build_filename(d, "cube.obj", NULL);
    char *png = g_build_filename(d, "cube.png", NULL);
    g_file_set_contents(obj, cube_obj, -1, NULL);
    assert_int_equal(run_render("render", obj, "-o", png), 0);
    RastImage *img = rast_image_read_png(png, NULL);
    assert_non_null(img);
    assert_int_equal(img->width, 640);
    /* The cube fills the middle; the corners show the background. */
    uint32_t bg = rast_image_get(img, 0, 0);
    assert_true(rast_image_get(img, 320, 320) != bg);
    uint64_t covered = 0;
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++)
            covered += rast_image_get(img, x, y) != bg;
    assert_true(covered > 640 * 640 / 8 && covered < 640 * 640 * 3 / 4);
    /* The same cube as binary PLY renders the same picture. */
    char *ply = g_build_filename(d, "cube.ply", NULL);
    char *png2 = g_build_filename(d, "cube2.png", NULL);
    SceneMesh *m = scene_obj_load(obj, NULL);
    assert_true(scene_ply_save(m, ply, SCENE_PLY_BINARY_LE, NULL));
    assert_int_equal(run_render("render", ply, "-o", png2), 0);
    RastImage *img2 = rast_image_read_png(png2, NULL);
    assert_true(rast_image_equal(img, img2));
    rast_image_free(img2);
    scene_mesh_free(m);
    g_unlink(ply);
    g_unlink(png2);
    g_free(ply);
    g_free(png2);
    rast_image_free(img);
    g_unlink(png);
    g_unlink(obj);
    g_rmdir(d);
    g_free(obj);
    g_free(png);
    g_free(d);
}

static void test_render_errors(void **state)
{
    (void)state;
    char *d = g_dir_make_tmp("rast-render-XXXXXX", NULL);
    char *obj = g_build_filename(d, "bad.obj", NULL);
    char *png = g_build_filename(d, "bad.png", NULL);
    g_file_set_contents(obj, "v 0 0 0\nv 1 0 0\nf 1 2 7\n", -1, NULL);
    assert_int_equal(run_render("render", obj, "-o", png), 2);
    assert_false(g_file_test(png, G_FILE_TEST_EXISTS));
    g_file_set_contents(obj, "v 0 zero 0\n", -1, NULL);
    assert_int_equal(run_render("render", obj, "-o", png), 2);
    assert_int_equal(run_render("render", "/nonexistent.obj", "-o", png), 2);
    assert_int_equal(run_render("render", obj, "--zbuffer", "odd"), 2);
    g_unlink(obj);
    g_rmdir(d);
    g_free(obj);
    g_free(png);
    g_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_render_obj),
        cmocka_unit_test(test_render_errors),
    };
    return cmocka_run_group_tests_name("render", tests, NULL, NULL);
}
