/* test_run_out.c — `pgsim run --out DIR` replaces DIR wholly or not at
 * all (issue 32, sim/app/run/outdir.h): a run that fails after it has
 * drawn its frame image leaves an earlier run's folder byte for byte as
 * it was and no staging folder; a run that succeeds replaces every file
 * of the earlier run, the images too, and removes the earlier run's
 * files it did not write (frame.png after a --frames all run), keeping
 * the user's own files. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>
#include <glib/gstdio.h>

#include "sim/app/run/outdir.h"
#include "tests/app/cli/pgsim_spawn.h"
#include "tests/support.h"

static gint by_text(gconstpointer a, gconstpointer b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* "name=sha256 ..." of every file in dir, sorted (g_free). */
static char *snapshot(const char *dir)
{
    GPtrArray *lines = g_ptr_array_new_with_free_func(g_free);
    GDir *d = g_dir_open(dir, 0, NULL);
    assert_non_null(d);
    for (const char *n; (n = g_dir_read_name(d));) {
        char *path = g_build_filename(dir, n, NULL), *text = NULL;
        gsize len = 0;
        assert_true(g_file_get_contents(path, &text, &len, NULL));
        char *sum = g_compute_checksum_for_data(G_CHECKSUM_SHA256,
                                                (const guchar *)text, len);
        g_ptr_array_add(lines, g_strdup_printf("%s=%s", n, sum));
        g_free(sum);
        g_free(text);
        g_free(path);
    }
    g_dir_close(d);
    g_ptr_array_sort(lines, by_text);
    g_ptr_array_add(lines, NULL);
    char *s = g_strjoinv(" ", (char **)lines->pdata);
    g_ptr_array_free(lines, TRUE);
    return s;
}

static int run(const char *out, const char *set1, const char *set2,
               const char *more)
{
    const char *args[] = {"run", "configs/sortfirst-vehicle.yaml", "-q",
                          "--set", "run.frames=2", "--out", out,
                          "--set", set1, "--set", set2, more, NULL};
    char *o = NULL, *e = NULL;
    int st = test_pgsim(args, &o, &e);
    g_free(o);
    g_free(e);
    return st;
}

static void test_failed_run_leaves_folder(void **state)
{
    (void)state;
    char *top = g_dir_make_tmp("pgsim-runout-XXXXXX", NULL);
    char *out = g_build_filename(top, "o", NULL);
    char *bad = g_build_filename(top, "no", "such", "log.csv", NULL);
    assert_int_equal(run(out, "scene.fov=30", "workload.grid=64", NULL), 0);
    char *mine = g_build_filename(out, "notes.txt", NULL);
    assert_true(g_file_set_contents(mine, "mine", -1, NULL));
    char *before = snapshot(out);
    assert_non_null(strstr(before, "frame.png="));
    /* another view, so another image; the frame log at the end fails */
    char *log = g_strconcat("workload.frame_log=", bad, NULL);
    assert_int_equal(run(out, "scene.fov=50", log, NULL), 2);
    char *after = snapshot(out);
    assert_string_equal(after, before);
    assert_int_equal(support_entries(top), 1); /* no staging folder left */
    g_free(after);
    /* a run that succeeds replaces all, images included */
    assert_int_equal(run(out, "scene.fov=50", "workload.grid=64", NULL), 0);
    after = snapshot(out);
    char **was = g_strsplit(before, " ", -1);
    for (char **w = was; *w; w++)
        if (!g_str_has_prefix(*w, "notes.txt="))
            assert_null(strstr(after, *w)); /* each file is new */
    assert_non_null(strstr(after, "notes.txt="));
    g_strfreev(was);
    g_free(after);
    /* --frames all: frame-0000.png, frame-0001.png; the old frame.png goes */
    assert_int_equal(run(out, "scene.fov=50", "workload.grid=64",
                         "--frames=all"), 0);
    after = snapshot(out);
    assert_null(strstr(after, "frame.png="));
    assert_non_null(strstr(after, "frame-0001.png="));
    assert_non_null(strstr(after, "notes.txt="));
    assert_int_equal(support_entries(top), 1);
    g_free(after);
    g_free(before);
    g_free(log);
    g_free(mine);
    g_free(bad);
    g_free(out);
    support_rm_tree(top);
    g_free(top);
}

static void test_run_file_names(void **state)
{
    (void)state;
    const char *yes[] = {"summary.txt", "result.json", "result.csv",
                         "frame.png", "frame-0000.png", "frame-12345.png",
                         "sortfirst_frames.csv",
                         "performer_frames_stages.csv"};
    const char *no[] = {"notes.txt", "frame-.png", "frame-12a.png",
                        "frame.png.bak", "result.json~", "frames.csv"};
    for (guint i = 0; i < G_N_ELEMENTS(yes); i++)
        assert_true(out_is_run_file(yes[i]));
    for (guint i = 0; i < G_N_ELEMENTS(no); i++)
        if (out_is_run_file(no[i]))
            fail_msg("%s taken for a run's file", no[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_run_file_names),
        cmocka_unit_test(test_failed_run_leaves_folder),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
