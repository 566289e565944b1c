/* test_wl_registry.c — the workload table and the helpers every workload
 * shares (sim/workload/registry.c): lookup by name, run.until (the
 * runner's ctx->until and engine horizon, sim/run/run.h), the frame
 * log's path and write, which frames go out as images and where. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <string.h>

#include "sim/run/run.h"
#include "sim/workload/workload.h"

extern const WlOps *const wl_all[];

static void test_find(void **st)
{
    (void)st;
    guint n = 0;
    for (int i = 0; wl_all[i]; i++, n++)
        assert_ptr_equal(wl_find(wl_all[i]->name), wl_all[i]);
    assert_true(n >= 7);
    assert_string_equal(wl_all[0]->name, "pphigs");
    assert_ptr_equal(wl_find("pphigs"), wl_all[0]);
    assert_null(wl_find("nosuch"));
    assert_null(wl_find(""));
}

/* What a probe workload saw of its context (probe_run). */
static SimTime seen_until;
static SimTime seen_horizon;
static const WlOps *probed; /* the workload the probe stands in for */

static gboolean probe_run(const WlContext *ctx, void *params, SimResult *out,
                          GError **err)
{
    seen_until = ctx->until;
    seen_horizon = sim_engine_horizon(ctx->eng);
    return probed->run(ctx, params, out, err);
}

/* Loads `yaml` through the runner, runs it with tokenring's run wrapped
 * by probe_run (every other op tokenring's own), and returns its result;
 * *until is the CfgRun's run.until. */
static SimResult *probe(const char *yaml, SimTime *until)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(yaml, "u.yaml", &err);
    assert_non_null(root);
    CfgRun *run = cfg_run_from_tree(root, NULL, &err);
    if (!run)
        fail_msg("%s", err->message);
    probed = run->wl;
    WlOps ops = *run->wl;
    ops.run = probe_run;
    run->wl = &ops;
    *until = run->until;
    seen_until = seen_horizon = 0;
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *r = cfg_run_exec(run, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    cfg_run_free(run);
    return r;
}

/* run.until reaches the workload as ctx->until and is the engine's
 * horizon, so a workload that runs to its own end stops there: a
 * tokenring round of the defaults is 8 x (20 us + 1000 B / 2.8 MB/s +
 * 5 us), about 3.06 ms, so 5 ms holds one of 100 rounds. */
static void test_until(void **st)
{
    (void)st;
    SimTime until = 0;
    SimResult *r = probe("schema_version: 1\n"
                         "workload: {type: tokenring}\n"
                         "run: {frames: 100, until: 5 ms}\n",
                         &until);
    assert_true(until == 5 * SIM_MS);
    assert_true(seen_until == 5 * SIM_MS);
    assert_true(seen_horizon == 5 * SIM_MS);
    assert_int_equal(r->frame_times->len, 1);
    assert_true(r->elapsed <= 5 * SIM_MS);
    sim_result_free(r);
    /* without run.until: no horizon, and every round runs */
    r = probe("schema_version: 1\n"
              "workload: {type: tokenring}\n"
              "run: {frames: 100}\n",
              &until);
    assert_true(until == SIM_TIME_MAX);
    assert_true(seen_until == SIM_TIME_MAX);
    assert_true(seen_horizon == SIM_TIME_MAX);
    assert_int_equal(r->frame_times->len, 100);
    assert_true(r->elapsed > 5 * SIM_MS);
    sim_result_free(r);
}

static void test_frame_log(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("wlreg-XXXXXX", NULL);
    assert_non_null(dir);
    char *sub = g_build_filename(dir, "out", NULL);
    WlContext ctx = {.out_dir = NULL};
    char *p = wl_frame_log_path(&ctx, "given.csv", "x.csv");
    assert_string_equal(p, "given.csv");
    g_free(p);
    assert_null(wl_frame_log_path(&ctx, NULL, "x.csv"));
    ctx.out_dir = sub;
    p = wl_frame_log_path(&ctx, NULL, "x.csv");
    char *want = g_build_filename(sub, "x.csv", NULL);
    assert_string_equal(p, want);
    assert_true(g_file_test(sub, G_FILE_TEST_IS_DIR));
    GString *text = g_string_new("a,b\n1,2\n");
    assert_true(wl_frame_log_write(p, text, "wl", NULL));
    char *back = NULL;
    assert_true(g_file_get_contents(p, &back, NULL, NULL));
    assert_string_equal(back, "a,b\n1,2\n");
    g_free(back);
    /* a directory under a file cannot be made */
    char *bad = g_build_filename(p, "deeper", NULL);
    ctx.out_dir = bad;
    assert_null(wl_frame_log_path(&ctx, NULL, "x.csv"));
    char *badfile = g_build_filename(bad, "f.csv", NULL);
    GError *e = NULL;
    assert_false(wl_frame_log_write(badfile, text, "wl", &e));
    assert_non_null(strstr(e->message, "wl: found an unwritable frame_log"));
    g_clear_error(&e);
    g_string_free(text, TRUE);
    g_remove(p);
    g_rmdir(sub);
    g_rmdir(dir);
    g_free(badfile);
    g_free(bad);
    g_free(want);
    g_free(p);
    g_free(sub);
    g_free(dir);
}

static void test_frames_out(void **st)
{
    (void)st;
    assert_false(wl_wants_frame(NULL, 0));
    WlContext ctx = {.frames = 4};
    assert_false(wl_wants_frame(&ctx, 3)); /* no out_dir */
    char *dir = g_dir_make_tmp("wlreg-XXXXXX", NULL);
    ctx.out_dir = dir;
    assert_true(wl_wants_frame(&ctx, 3)); /* the last frame only */
    assert_false(wl_wants_frame(&ctx, 2));
    assert_false(wl_wants_frame(&ctx, 4));
    RastImage *img = rast_image_new(2, 2);
    char *png = g_build_filename(dir, "frame.png", NULL);
    assert_true(wl_emit_frame(&ctx, 2, img, NULL)); /* not wanted: nothing */
    assert_false(g_file_test(png, G_FILE_TEST_EXISTS));
    assert_true(wl_emit_frame(&ctx, 3, img, NULL));
    assert_true(g_file_test(png, G_FILE_TEST_EXISTS));
    g_remove(png);
    ctx.all_frames = TRUE;
    assert_true(wl_wants_frame(&ctx, 0));
    char *png1 = g_build_filename(dir, "frame-0001.png", NULL);
    assert_true(wl_emit_frame(&ctx, 1, img, NULL));
    assert_true(g_file_test(png1, G_FILE_TEST_EXISTS));
    g_remove(png1);
    /* an out_dir under a regular file: refused with an error */
    char *file = g_build_filename(dir, "plain", NULL);
    assert_true(g_file_set_contents(file, "x", 1, NULL));
    char *under = g_build_filename(file, "d", NULL);
    ctx.out_dir = under;
    GError *e = NULL;
    assert_false(wl_emit_frame(&ctx, 1, img, &e));
    assert_non_null(e);
    assert_non_null(strstr(e->message, "cannot create"));
    g_clear_error(&e);
    g_remove(file);
    g_rmdir(dir);
    /* no trace: marking a frame is a no-op */
    SimEngine *eng = sim_engine_new(1);
    wl_mark_frame(eng, 0, SIM_MS);
    sim_engine_free(eng);
    rast_image_free(img);
    g_free(under);
    g_free(file);
    g_free(png1);
    g_free(png);
    g_free(dir);
}

/* pphigs' parameters free function takes NULL (its file database and
 * dump path are freed only for real parameters). */
static void test_free_params_null(void **st)
{
    (void)st;
    wl_find("pphigs")->free_params(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_params_null),
        cmocka_unit_test(test_find),
        cmocka_unit_test(test_until),
        cmocka_unit_test(test_frame_log),
        cmocka_unit_test(test_frames_out),
    };
    return cmocka_run_group_tests_name("wl_registry", tests, NULL, NULL);
}
