/* test_validate.c — `pgsim validate` means "will run": each config under
 * tests/data/bad/validate/ (its first line "# expect: <message>") is one
 * that validate used to accept while run rejected it, or that made
 * validate itself abort.  Now validate and run both exit 2 with the same
 * located message, print nothing on stdout, and run writes nothing.
 * Good configs still validate, and a dry run writes nothing either. */
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
    const char *good[] = {"configs/quickstart.yaml",
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_configs),
        cmocka_unit_test(test_good_configs),
    };
    return cmocka_run_group_tests_name("validate", tests, NULL, NULL);
}
