/* test_model_find.c — the model search path with a caller's extra
 * folders (model_find.h): a model in an extra folder is found with no
 * environment variable set, by name, by the loader and by the machine
 * builder; the order is ./models, $PGSIM_MODELS, the extra folders, then
 * the data roots' models. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>
#include <glib/gstdio.h>

#include "sim/machine/machine.h"
#include "sim/machine/model.h"
#include "tests/support.h"

static const char *const test_dirs[] = {"tests/data/models", NULL};

static void test_extra_dir_without_env(void **state)
{
    (void)state;
    g_unsetenv("PGSIM_MODELS");
    GError *err = NULL;
    assert_null(mach_model_path("tiny", &err));
    g_clear_error(&err);
    char *p = mach_model_path_in("tiny", test_dirs, &err);
    g_assert_no_error(err);
    assert_string_equal(p, "tests/data/models/tiny.yaml");
    g_free(p);
    CfgNode *m = mach_load_model_in("tiny", test_dirs, &err);
    g_assert_no_error(err);
    cfg_free(m);
    /* nothing was passed through the environment */
    assert_null(g_getenv("PGSIM_MODELS"));
    assert_null(mach_load_model("tiny", &err));
    g_clear_error(&err);
}

static CfgNode *tiny_run(void)
{
    CfgNode *root = cfg_load_string(
        "machine: {model: tiny, nodes: {cpu: {count: 2}}}\n", "run.yaml", NULL);
    assert_non_null(root);
    return root;
}

static void test_builder_takes_extra_dirs(void **state)
{
    (void)state;
    g_unsetenv("PGSIM_MODELS");
    GError *err = NULL;
    CfgNode *root = tiny_run();
    const CfgNode *sec = cfg_get(root, "machine");
    assert_false(mach_check_section(sec, &err));
    assert_non_null(strstr(err->message, "found no model 'tiny'"));
    g_clear_error(&err);
    assert_true(mach_check_section_in(sec, test_dirs, &err));
    g_assert_no_error(err);
    assert_true(cfg_check_unused(root, &err));
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        mach_new_from_cfg_in(eng, sec, "analytic", test_dirs, &err);
    g_assert_no_error(err);
    assert_string_equal(mach_name(m), "tiny");
    assert_int_equal(mach_proc_total(m), 2); /* the override applied */
    mach_free(m);
    assert_null(mach_new_from_cfg(eng, sec, "analytic", &err));
    g_clear_error(&err);
    sim_engine_free(eng);
    char *file = NULL;
    CfgNode *tree = mach_section_tree_in(sec, test_dirs, &file, &err);
    assert_string_equal(file, "tests/data/models/tiny.yaml");
    cfg_free(tree);
    g_free(file);
    cfg_free(root);
}

/* ./models, then $PGSIM_MODELS, then the extra folders (empty entries
 * and folders already listed skipped), then the data roots. */
static void test_extra_dirs_order(void **state)
{
    (void)state;
    g_setenv("PGSIM_MODELS", "tests/data/bad/models", TRUE);
    const char *const extra[] = {"tests/data/models", "", "models",
                                 "tests/data/bad/models/", NULL};
    GPtrArray *d = mach_model_dirs_in(extra);
    GPtrArray *plain = mach_model_dirs();
    assert_int_equal(d->len, plain->len + 1);
    assert_string_equal(d->pdata[0], "models");
    assert_string_equal(d->pdata[1], "tests/data/bad/models");
    assert_string_equal(d->pdata[2], "tests/data/models");
    for (guint i = 3; i < d->len; i++)
        assert_string_equal(d->pdata[i], plain->pdata[i - 1]);
    g_ptr_array_free(d, TRUE);
    g_ptr_array_free(plain, TRUE);
    g_unsetenv("PGSIM_MODELS");
}

static char *write_model(const char *dir, const char *name)
{
    assert_int_equal(g_mkdir_with_parents(dir, 0777), 0);
    char *file = g_strconcat(name, ".yaml", NULL);
    char *path = g_build_filename(dir, file, NULL);
    assert_true(g_file_set_contents(path, "x", -1, NULL));
    g_free(file);
    return path;
}

/* The user's $PGSIM_MODELS wins over an extra folder, and an extra
 * folder over the shipped models (a data root's). */
static void test_extra_dirs_precedence(void **state)
{
    (void)state;
    char *repo = g_get_current_dir();
    char *tmp = g_dir_make_tmp("pgsim-find-XXXXXX", NULL);
    char *user = g_build_filename(tmp, "user", NULL);
    char *extra_dir = g_build_filename(tmp, "extra", NULL);
    char *f1 = write_model(user, "tiny");
    char *f2 = write_model(extra_dir, "cm5");
    const char *const extra[] = {"tests/data/models", extra_dir, NULL};
    g_setenv("PGSIM_MODELS", user, TRUE);
    GError *err = NULL;
    char *p = mach_model_path_in("tiny", extra, &err);
    assert_string_equal(p, f1);
    g_free(p);
    g_unsetenv("PGSIM_MODELS");
    g_setenv("PGSIM_DATA", repo, TRUE);
    assert_int_equal(g_chdir(tmp), 0); /* no ./models here */
    p = mach_model_path_in("cm5", extra, &err);
    assert_string_equal(p, f2);
    g_free(p);
    p = mach_model_path("cm5", &err); /* without it, the shipped one */
    char *shipped = g_build_filename(repo, "models", "cm5.yaml", NULL);
    assert_string_equal(p, shipped);
    assert_int_equal(g_chdir(repo), 0);
    g_unsetenv("PGSIM_DATA");
    g_remove(f1);
    g_remove(f2);
    g_rmdir(user);
    g_rmdir(extra_dir);
    g_rmdir(tmp);
    g_free(p);
    g_free(shipped);
    g_free(f1);
    g_free(f2);
    g_free(user);
    g_free(extra_dir);
    g_free(tmp);
    g_free(repo);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_extra_dir_without_env),
        cmocka_unit_test(test_builder_takes_extra_dirs),
        cmocka_unit_test(test_extra_dirs_order),
        cmocka_unit_test(test_extra_dirs_precedence),
    };
    return cmocka_run_group_tests_name("machine_model_find", tests, NULL, NULL);
}
