/* test_validate.c — bad input through the pgsim binary.
 *
 * `pgsim validate` means "will run": each config under
 * tests/data/bad/validate/ (its first line "# expect: <message>") is one
 * that validate used to accept while run rejected it, or that made
 * validate itself abort.  Now validate and run both exit 2 with the same
 * located message, print nothing on stdout, and run writes nothing.
 * Good configs still validate.  A run that fails leaves neither its
 * trace nor its --out files; --trace-cap, plot -o and binary CSVs are
 * flag errors, not silent defaults. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>
#include <sys/wait.h>
#include <glib/gstdio.h>

static const char *pgsim_binary(void)
{
    return g_getenv("PGSIM_SANITIZE") ? "build-san/pgsim" : "build/pgsim";
}

/* Runs pgsim (memory limit fixed at 8 GiB so messages do not depend on
 * the machine); exit status, stdout and stderr (g_free). */
static int run_pgsim(const char *cmd, const char *file, const char *out_dir,
                     char **out, char **err)
{
    const char *argv[] = {pgsim_binary(), cmd,     "--mem-limit", "8G",
                          file,           out_dir ? "--out" : NULL, out_dir,
                          NULL};
    int wait = 0;
    GError *e = NULL;
    if (!g_spawn_sync(NULL, (char **)argv, NULL, G_SPAWN_DEFAULT, NULL, NULL,
                      out, err, &wait, &e))
        fail_msg("cannot run %s: %s", pgsim_binary(), e->message);
    return WIFEXITED(wait) ? WEXITSTATUS(wait) : -1;
}

static char *expected_message(const char *path)
{
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    const char *p = strstr(text, "# expect: ");
    assert_non_null(p);
    p += strlen("# expect: ");
    char *want = g_strndup(p, strcspn(p, "\n"));
    g_free(text);
    return want;
}

/* One bad config: command `cmd` exits 2 with the message, writes
 * nothing to stdout or to --out. */
static void expect_rejected(const char *cmd, const char *path,
                            const char *want, const char *out_dir)
{
    char *out = NULL, *err = NULL;
    int status = run_pgsim(cmd, path, out_dir, &out, &err);
    if (status != 2 || !strstr(err, want))
        fail_msg("pgsim %s %s: exit %d, stderr %s\nwant %s", cmd, path,
                 status, err, want);
    assert_string_equal(out, "");
    if (out_dir)
        assert_false(g_file_test(out_dir, G_FILE_TEST_EXISTS));
    g_free(out);
    g_free(err);
}

static void test_bad_configs(void **state)
{
    (void)state;
    const char *root = "tests/data/bad/validate";
    GDir *dir = g_dir_open(root, 0, NULL);
    assert_non_null(dir);
    char *tmp = g_dir_make_tmp("pgsim-validate-XXXXXX", NULL);
    char *out_dir = g_build_filename(tmp, "out", NULL);
    const char *f;
    guint n = 0;
    while ((f = g_dir_read_name(dir))) {
        char *path = g_build_filename(root, f, NULL);
        char *want = expected_message(path);
        expect_rejected("validate", path, want, NULL);
        expect_rejected("run", path, want, out_dir);
        g_free(want);
        g_free(path);
        n++;
    }
    g_dir_close(dir);
    assert_true(n >= 8);
    g_rmdir(tmp);
    g_free(out_dir);
    g_free(tmp);
}

/* Runnable configs still validate: "<file>: ok", exit 0. */
static void test_good_configs(void **state)
{
    (void)state;
    const char *good[] = {"configs/tokenring.yaml",
                          "configs/pixelmerge-2pot.yaml"};
    for (guint i = 0; i < G_N_ELEMENTS(good); i++) {
        char *out = NULL, *err = NULL;
        assert_int_equal(run_pgsim("validate", good[i], NULL, &out, &err), 0);
        char *want = g_strdup_printf("%s: ok\n", good[i]);
        assert_string_equal(out, want);
        assert_string_equal(err, "");
        g_free(want);
        g_free(out);
        g_free(err);
    }
}

/* Runs pgsim with a NULL-terminated argument list; exit status. */
static int run_args(const char *const *args, char **err)
{
    GPtrArray *argv = g_ptr_array_new();
    g_ptr_array_add(argv, (gpointer)pgsim_binary());
    for (int i = 0; args[i]; i++)
        g_ptr_array_add(argv, (gpointer)args[i]);
    g_ptr_array_add(argv, NULL);
    int wait = 0;
    assert_true(g_spawn_sync(NULL, (char **)argv->pdata, NULL,
                             G_SPAWN_STDOUT_TO_DEV_NULL, NULL, NULL, NULL, err,
                             &wait, NULL));
    g_ptr_array_free(argv, TRUE);
    return WIFEXITED(wait) ? WEXITSTATUS(wait) : -1;
}

static void expect_status(const char *const *args, int want, const char *msg)
{
    char *err = NULL;
    int status = run_args(args, &err);
    if (status != want || !strstr(err, msg))
        fail_msg("%s: exit %d, stderr %s\nwant %d, %s", args[0], status, err,
                 want, msg);
    g_free(err);
}

/* The event pool cannot grow within 10 KiB: the run fails after its
 * trace was opened; neither the trace nor --out may be left behind. */
static void test_failed_run_writes_nothing(void **state)
{
    (void)state;
    char *tmp = g_dir_make_tmp("pgsim-fail-XXXXXX", NULL);
    char *trace = g_build_filename(tmp, "t.json", NULL);
    char *out = g_build_filename(tmp, "out", NULL);
    const char *args[] = {"run",     "configs/tokenring.yaml", "--mem-limit",
                          "10k",     "--trace",                 trace,
                          "--out",   out,                       NULL};
    /* 1,024 events of 80 B: the queue's records with doubling slack. */
    expect_status(args, 2, "found 1024 pending events needing about 80.0");
    assert_false(g_file_test(trace, G_FILE_TEST_EXISTS));
    char *tmp_trace = g_strconcat(trace, ".tmp", NULL);
    assert_false(g_file_test(tmp_trace, G_FILE_TEST_EXISTS));
    assert_false(g_file_test(out, G_FILE_TEST_EXISTS));
    const char *ok[] = {"run", "configs/tokenring.yaml", "--trace", trace,
                        NULL};
    expect_status(ok, 0, ""); /* the same run with memory writes it */
    assert_true(g_file_test(trace, G_FILE_TEST_EXISTS));
    g_unlink(trace);
    g_rmdir(tmp);
    g_free(tmp_trace);
    g_free(trace);
    g_free(out);
    g_free(tmp);
}

static void test_bad_flags(void **state)
{
    (void)state;
    const char *cap0[] = {"run", "configs/tokenring.yaml", "--trace-cap",
                          "0", "--trace", "never.json", NULL};
    expect_status(cap0, 2, "--trace-cap: found 0, expected a positive");
    const char *capneg[] = {"run", "configs/tokenring.yaml", "--trace-cap",
                            "-5", "--trace", "never.json", NULL};
    expect_status(capneg, 2, "--trace-cap: found -5, expected a positive");
    assert_false(g_file_test("never.json", G_FILE_TEST_EXISTS));
    const char *mem[] = {"validate", "--mem-limit", "12X",
                         "configs/tokenring.yaml", NULL};
    expect_status(mem, 2, "--mem-limit: found '12X'");
    char *tmp = g_dir_make_tmp("pgsim-plot-XXXXXX", NULL);
    char *csv = g_build_filename(tmp, "r.csv", NULL);
    char *bin = g_build_filename(tmp, "bin.csv", NULL);
    char *txt = g_build_filename(tmp, "x.txt", NULL);
    char *nodir = g_build_filename(tmp, "none", "x.png", NULL);
    char *none = g_build_filename(tmp, "none", NULL);
    g_file_set_contents(csv, "a,b\n1,2\n2,3\n", -1, NULL);
    g_file_set_contents(bin, "a,b\n1,\0\xff\n", 10, NULL);
    const char *p1[] = {"plot", csv, "--x", "a", "--y", "b", "-o", nodir, NULL};
    expect_status(p1, 2, "expected an existing directory");
    assert_false(g_file_test(none, G_FILE_TEST_EXISTS)); /* not created */
    const char *p2[] = {"plot", csv, "--x", "a", "--y", "b", "-o", txt, NULL};
    expect_status(p2, 2, "expected a file name ending in .png");
    const char *p3[] = {"plot", bin, "--x", "a", "--y", "b", NULL};
    expect_status(p3, 2, "bin.csv:2:3: found the byte 0x00, expected UTF-8");
    g_unlink(csv);
    g_unlink(bin);
    g_rmdir(tmp);
    g_free(csv);
    g_free(bin);
    g_free(txt);
    g_free(nodir);
    g_free(none);
    g_free(tmp);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_configs),
        cmocka_unit_test(test_good_configs),
        cmocka_unit_test(test_failed_run_writes_nothing),
        cmocka_unit_test(test_bad_flags),
    };
    return cmocka_run_group_tests_name("validate", tests, NULL, NULL);
}
