/* test_models_doc.c — docs/models.md's parameter tables are the models'
 * (issue 33, point 8): the text between its marker lines is exactly what
 * `pgsim models --markdown models` prints, so a cost changed in a YAML
 * and not in the doc (or by hand in the doc) fails here; and the tables
 * follow a model that changes (a copy of models/ with one value edited
 * prints the new value).  Runs the built binary, like test_cli. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>
#include <glib/gstdio.h>

#include "tests/app/cli/pgsim_spawn.h"

#define BEGIN                                                                  \
    "<!-- begin: made by `pgsim models --markdown` "                           \
    "(scripts/gen-models-doc.sh); edit models/*.yaml, not this -->\n"
#define END "<!-- end: pgsim models --markdown -->\n"

/* The doc's text between the markers (g_free). */
static char *doc_tables(void)
{
    return test_doc_between("docs/models.md", BEGIN, END);
}

static char *tables_of(const char *dir)
{
    const char *args[] = {"models", "--markdown", dir, NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(args, &out, &err), 0);
    assert_string_equal(err, "");
    g_free(err);
    return out;
}

static void test_doc_is_the_models(void **state)
{
    (void)state;
    char *doc = doc_tables(), *made = tables_of("models");
    if (strcmp(doc, made) != 0)
        fail_msg("docs/models.md's tables differ from `pgsim models "
                 "--markdown`: edit models/*.yaml and run sh "
                 "scripts/gen-models-doc.sh");
    /* the example: the YAML's costs, not the old hand-made ones */
    assert_non_null(strstr(doc, "| `gp.costs.color` | 1.828 us |"));
    assert_non_null(strstr(doc, "| `gp.costs.matrix_concat` | 57.28 us |"));
    g_free(doc);
    g_free(made);
}

/* A model edited in a copy of models/: its tables print the new value,
 * so they differ from the doc. */
static void test_tables_follow_the_yaml(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-models-XXXXXX", NULL);
    char *cmd = g_strdup_printf(
        "cp models/*.yaml '%s' && sed -i 's/value: 1.828 us/value: 1.35 us/' "
        "'%s/pixel-planes-5.yaml'",
        dir, dir);
    assert_int_equal(system(cmd), 0);
    g_free(cmd);
    char *made = tables_of(dir), *doc = doc_tables();
    assert_non_null(strstr(made, "| `gp.costs.color` | 1.35 us |"));
    assert_string_not_equal(made, doc);
    g_free(made);
    g_free(doc);
    cmd = g_strdup_printf("rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
    g_free(cmd);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_doc_is_the_models),
        cmocka_unit_test(test_tables_follow_the_yaml),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
