/* test_render.c — `pgsim render`: YAML scene files (configs/scenes/, run
 * configs), OBJ and PLY input, PNG output, camera-path frames, and bad
 * files (tests/data/bad/render/, each naming its expected message in a
 * first-line comment) and bad flags: exit 2, a located message, and no
 * image written.  Run from the repository root (make test does). */
#include "sim/core/memlimit.h"
#include "sim/app/cli/commands.h"
#include "sim/scene/obj.h"
#include "sim/scene/ply.h"
#include "sim/scene/scene_cfg.h"
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

static int run_argv(int argc, const char *const *args)
{
    char **argv = g_new0(char *, argc + 1);
    for (int i = 0; i < argc; i++)
        argv[i] = (char *)args[i];
    int r = cmd_render(argc, argv);
    g_free(argv);
    return r;
}

/* Pixels of img that differ from its corner (the background). */
static uint64_t covered(const RastImage *img)
{
    uint32_t bg = rast_image_get(img, 0, 0);
    uint64_t n = 0;
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++)
            n += rast_image_get(img, x, y) != bg;
    return n;
}

static const char *small_yaml =
    "scene:\n"
    "  generator: teapots\n"
    "  count: 2\n"
    "  polygons_per_teapot: 288\n"
    "  view: {azimuth: 0, elevation: 15, fill: 0.9, fit: box}\n"
    "  path: {kind: orbit, frames: 8}\n";

/* Renders `yaml` (written to dir/name) with extra flags; returns the
 * image or NULL, and the exit status in *rc. */
static RastImage *render_yaml(const char *dir, const char *name,
                              const char *yaml, const char *flag,
                              const char *value, int *rc)
{
    char *path = g_build_filename(dir, name, NULL);
    char *png = g_build_filename(dir, "out.png", NULL);
    g_file_set_contents(path, yaml, -1, NULL);
    const char *args[] = {"render", path,       "-o", png,  "--width",
                          "96",     "--height", "80", flag, value};
    *rc = run_argv(flag ? 10 : 8, args);
    RastImage *img = *rc == 0 ? rast_image_read_png(png, NULL) : NULL;
    g_unlink(png);
    g_unlink(path);
    g_free(png);
    g_free(path);
    return img;
}

static void test_render_yaml(void **state)
{
    (void)state;
    char *d = g_dir_make_tmp("rast-render-XXXXXX", NULL);
    int rc;
    RastImage *a = render_yaml(d, "s.yaml", small_yaml, NULL, NULL, &rc);
    assert_int_equal(rc, 0);
    assert_non_null(a);
    assert_int_equal(a->width, 96);
    assert_int_equal(a->height, 80);
    uint64_t n = covered(a);
    assert_true(n > 96 * 80 / 20 && n < 96 * 80 * 9 / 10);
    /* the full z-buffer draws the same picture */
    RastImage *b =
        render_yaml(d, "s.yaml", small_yaml, "--zbuffer", "full", &rc);
    assert_non_null(b);
    assert_true(rast_image_equal(a, b));
    rast_image_free(b);
    /* a later frame of the orbit path looks from elsewhere */
    b = render_yaml(d, "s.yaml", small_yaml, "--frame", "2", &rc);
    assert_non_null(b);
    assert_true(rast_image_diff(a, b) > 100);
    rast_image_free(b);
    /* a run config's scene: section renders the same scene */
    char *run = g_strconcat("schema_version: 1\nworkload: {type: x}\n",
                            small_yaml, NULL);
    b = render_yaml(d, "run.yml", run, NULL, NULL, &rc);
    assert_non_null(b);
    assert_true(rast_image_equal(a, b));
    rast_image_free(b);
    g_free(run);
    rast_image_free(a);
    g_rmdir(d);
    g_free(d);
}

/* Every scene in configs/scenes/ loads and is drawn: at least 32 pixels
 * of 64 x 64 (the flock, 144 boids of ~1 % of the view each, has ~70). */
static void test_render_config_scenes(void **state)
{
    (void)state;
    GDir *dir = g_dir_open("configs/scenes", 0, NULL);
    assert_non_null(dir);
    const char *f;
    guint files = 0;
    while ((f = g_dir_read_name(dir))) {
        char *path = g_build_filename("configs/scenes", f, NULL);
        GError *err = NULL;
        Scene *s = scene_load(path, &err);
        if (!s)
            print_error("%s: %s\n", path, err->message);
        assert_non_null(s);
        SceneCamera cam = scene_camera_at(s, 0);
        RastView v = rast_view_for_camera(&cam, 64, 64);
        v.cull_back = !s->two_sided;
        RastZBuffer *zb = rast_zbuffer_new(64, 64);
        RastCounters c = {0};
        rast_draw_scene(&v, s, rast_zbuffer_sink(zb), &c);
        uint64_t cov = rast_zbuffer_covered(zb);
        if (cov < 32)
            print_error("%s: only %" G_GUINT64_FORMAT " pixels\n", path, cov);
        assert_true(cov >= 32);
        rast_zbuffer_free(zb);
        scene_free(s);
        g_free(path);
        files++;
    }
    g_dir_close(dir);
    assert_true(files >= 14);
}

/* The expected message: the first line "# expect: ...". */
static char *expected_message(const char *text)
{
    const char *p = strstr(text, "# expect: ");
    assert_non_null(p);
    p += strlen("# expect: ");
    return g_strndup(p, strcspn(p, "\n"));
}

static void test_render_bad_files(void **state)
{
    (void)state;
    const char *root = "tests/data/bad/render";
    sim_mem_set_limit((guint64)8 << 30); /* messages independent of RAM */
    GDir *dir = g_dir_open(root, 0, NULL);
    assert_non_null(dir);
    char *tmp = g_dir_make_tmp("rast-render-XXXXXX", NULL);
    char *png = g_build_filename(tmp, "bad.png", NULL);
    const char *f;
    guint n = 0;
    while ((f = g_dir_read_name(dir))) {
        char *path = g_build_filename(root, f, NULL), *text = NULL;
        assert_true(g_file_get_contents(path, &text, NULL, NULL));
        char *want = expected_message(text);
        GError *err = NULL;
        assert_null(scene_load(path, &err));
        assert_non_null(err);
        if (!strstr(err->message, want) ||
            !g_str_has_prefix(err->message, root))
            print_error("%s: got %s\n  want %s\n", f, err->message, want);
        assert_non_null(strstr(err->message, want));
        assert_true(g_str_has_prefix(err->message, root));
        assert_int_equal(sim_error_exit_status(err), 2);
        g_error_free(err);
        assert_int_equal(run_render("render", path, "-o", png), 2);
        assert_false(g_file_test(png, G_FILE_TEST_EXISTS));
        g_free(want);
        g_free(text);
        g_free(path);
        n++;
    }
    g_dir_close(dir);
    assert_true(n >= 10);
    g_rmdir(tmp);
    g_free(png);
    g_free(tmp);
    sim_mem_set_limit(0);
}

static void test_render_bad_flags(void **state)
{
    (void)state;
    char *d = g_dir_make_tmp("rast-render-XXXXXX", NULL);
    const char *bad[][2] = {
        {"--frame", "8"}, /* the path has frames 0 .. 7 */
        {"--frame", "-1"},      {"--width", "0"},
        {"--height", "20000"},  {"--zbuffer", "odd"},
        {"--shading", "phong"}, {"--teapots", "2"}, /* two scenes */
    };
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        int rc = 0;
        RastImage *img =
            render_yaml(d, "s.yaml", small_yaml, bad[i][0], bad[i][1], &rc);
        assert_null(img);
        assert_int_equal(rc, 2);
    }
    char *yaml = g_build_filename(d, "s.yaml", NULL);
    char *jpg = g_build_filename(d, "out.jpg", NULL);
    g_file_set_contents(yaml, small_yaml, -1, NULL);
    assert_int_equal(run_render("render", yaml, "-o", jpg), 2);
    assert_false(g_file_test(jpg, G_FILE_TEST_EXISTS));
    g_unlink(yaml);
    g_free(yaml);
    g_free(jpg);
    g_rmdir(d);
    g_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_render_obj),
        cmocka_unit_test(test_render_errors),
        cmocka_unit_test(test_render_yaml),
        cmocka_unit_test(test_render_config_scenes),
        cmocka_unit_test(test_render_bad_files),
        cmocka_unit_test(test_render_bad_flags),
    };
    return cmocka_run_group_tests_name("render", tests, NULL, NULL);
}
