/* test_datapath.c — data files are found from any working directory. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim/core/cfg.h"
#include "sim/core/datapath.h"
#include "tests/support.h"
#include <glib/gstdio.h>
#include <string.h>
#include <unistd.h>

/* The input size limit: a file one byte over it is refused (located, an
 * I/O error), one at it is read; 0 restores the default. */
static void test_file_limit(void **state)
{
    (void)state;
    char *text;
    gsize len;
    GError *err = NULL;
    const char *f = "configs/quickstart.yaml";
    assert_true(sim_file_read(f, &text, &len, NULL));
    g_free(text);
    sim_file_set_limit(len);
    assert_true(sim_file_limit() == len);
    assert_true(sim_file_read(f, &text, &len, NULL));
    g_free(text);
    sim_file_set_limit(len - 1);
    assert_false(sim_file_read(f, &text, &len, &err));
    assert_true(g_str_has_prefix(err->message, "configs/quickstart.yaml:0:0: "
                                               "found "));
    g_error_free(err);
    sim_file_set_limit(0);
    assert_true(sim_file_limit() == SIM_FILE_LIMIT_DEFAULT ||
                g_getenv("PGSIM_MAX_INPUT"));
}

static void test_name_as_given_when_it_exists(void **state)
{
    (void)state;
    char *p = sim_data_path("configs/tokenring.yaml"); /* run from root */
    assert_string_equal(p, "configs/tokenring.yaml");
    g_free(p);
}

static void test_unknown_name_comes_back_unchanged(void **state)
{
    (void)state;
    char *p = sim_data_path("configs/no-such-file.yaml");
    assert_string_equal(p, "configs/no-such-file.yaml");
    g_free(p);
}

/* From another directory, $PGSIM_DATA and the executable's location both
 * lead back to the project's files, and cfg_load_file uses them. */
static void test_found_from_elsewhere(void **state)
{
    (void)state;
    char *root = g_get_current_dir();
    char *tmp = g_dir_make_tmp("pgsim-dp-XXXXXX", NULL);
    assert_non_null(tmp);
    assert_int_equal(chdir(tmp), 0);
    g_setenv("PGSIM_DATA", root, TRUE);
    char *p = sim_data_path("models/ipsc2.yaml");
    char *want = g_build_filename(root, "models/ipsc2.yaml", NULL);
    assert_string_equal(p, want);
    GError *err = NULL;
    CfgNode *n = cfg_load_file("configs/tokenring.yaml", &err);
    assert_null(err);
    assert_non_null(n);
    cfg_free(n);
    g_unsetenv("PGSIM_DATA");
    n = cfg_load_file("configs/no-such-file.yaml", &err);
    assert_null(n);
    assert_non_null(strstr(err->message, "configs/no-such-file.yaml:0:0"));
    g_error_free(err);
    assert_int_equal(chdir(root), 0);
    g_rmdir(tmp);
    g_free(p);
    g_free(want);
    g_free(tmp);
    g_free(root);
}

/* Expects sim_file_read(path) to fail with a message containing want. */
static void expect_unread(const char *path, const char *want)
{
    char *text = NULL;
    GError *e = NULL;
    assert_false(sim_file_read(path, &text, NULL, &e));
    assert_null(text);
    if (!strstr(e->message, want))
        fail_msg("%s: got %s, want %s", path, e->message, want);
    g_error_free(e);
}

/* Input files are regular files under the size limit, checked before
 * reading: devices (which never end), directories and big files fail. */
static void test_bounded_reads(void **state)
{
    (void)state;
    expect_unread("/dev/zero", "/dev/zero:0:0: found a character device, "
                               "expected a regular file");
    expect_unread("/dev/urandom", "found a character device");
    expect_unread("tests", "tests:0:0: found a directory");
    expect_unread("no/such/file", "found an unreadable file (");
    char *tmp = g_dir_make_tmp("pgsim-read-XXXXXX", NULL);
    char *f = g_build_filename(tmp, "f.yaml", NULL);
    g_file_set_contents(f, "0123456789abcdefghij", 20, NULL);
    sim_file_set_limit(19);
    expect_unread(f, "found 20 bytes, expected at most 19 bytes");
    GError *e = NULL;
    assert_null(cfg_load_file(f, &e)); /* the config loader too */
    assert_non_null(strstr(e->message, "found 20 bytes"));
    g_clear_error(&e);
    sim_file_set_limit(20);
    char *text = NULL;
    gsize len = 0;
    assert_true(sim_file_read(f, &text, &len, NULL));
    assert_int_equal(len, 20);
    assert_string_equal(text, "0123456789abcdefghij");
    sim_file_set_limit(0);
    g_free(text);
    g_unlink(f);
    g_rmdir(tmp);
    g_free(f);
    g_free(tmp);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_file_limit),
        cmocka_unit_test(test_name_as_given_when_it_exists),
        cmocka_unit_test(test_unknown_name_comes_back_unchanged),
        cmocka_unit_test(test_found_from_elsewhere),
        cmocka_unit_test(test_bounded_reads),
    };
    return cmocka_run_group_tests_name("datapath", tests, NULL, NULL);
}
