/* test_datapath.c — data files are found from any working directory. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim/core/cfg.h"
#include "sim/core/datapath.h"
#include <glib/gstdio.h>
#include <string.h>
#include <unistd.h>

static void test_name_as_given_when_it_exists(void **state)
{
    (void)state;
    char *p = sim_data_path("configs/quickstart.yaml"); /* run from root */
    assert_string_equal(p, "configs/quickstart.yaml");
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
    CfgNode *n = cfg_load_file("configs/quickstart.yaml", &err);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_name_as_given_when_it_exists),
        cmocka_unit_test(test_unknown_name_comes_back_unchanged),
        cmocka_unit_test(test_found_from_elsewhere),
    };
    return cmocka_run_group_tests_name("datapath", tests, NULL, NULL);
}
