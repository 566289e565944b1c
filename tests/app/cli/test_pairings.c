/* test_pairings.c — every shipped workload config on every shipped model
 * (issue 34, point 2): `pgsim models --pairings` runs each pairing at
 * its small size and agrees with configs/pairings/pairings.yaml both
 * ways (a listed pairing fails with a located error holding its text,
 * every other one runs), and docs/models.md holds the table it prints.
 * A list that calls a running pairing meaningless, or leaves out one
 * that fails, is refused naming the pairing.  Runs the built binary. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>
#include <glib/gstdio.h>

#include "tests/app/cli/pgsim_spawn.h"

#define LIST "configs/pairings/pairings.yaml"
#define BEGIN                                                                  \
    "<!-- begin: made by `pgsim models --pairings "                            \
    "configs/pairings/pairings.yaml` (scripts/gen-models-doc.sh); edit "      \
    "the list and models/*.yaml, not this -->\n"
#define END "<!-- end: pgsim models --pairings -->\n"

/* The doc's text between the markers (g_free). */
static char *doc_table(void)
{
    return test_doc_between("docs/models.md", BEGIN, END);
}

static int pairings(const char *list, char **out, char **err)
{
    const char *args[] = {"models", "--pairings", list, NULL};
    return test_pgsim(args, out, err);
}

/* Every pairing behaves as the list says, and the doc is the table:
 * quickstart on cluster-ib prints a frame from derived costs. */
static void test_doc_is_the_pairings(void **state)
{
    (void)state;
    char *out, *err;
    int rc = pairings(LIST, &out, &err);
    if (rc != 0)
        fail_msg("pgsim models --pairings: exit %d: %s", rc, err);
    char *doc = doc_table();
    if (strcmp(doc, out) != 0)
        fail_msg("docs/models.md's pairings table differs from `pgsim "
                 "models --pairings " LIST "`: run sh "
                 "scripts/gen-models-doc.sh");
    /* the cluster-ib column of the quickstart row: a time, derived */
    gchar **lines = g_strsplit(out, "\n", -1);
    gchar **head = g_strsplit(lines[0], "|", -1);
    const char *row = strstr(out, "| `quickstart` |");
    assert_non_null(row);
    gchar **cells = g_strsplit(row, "|", -1);
    guint col = 0;
    while (head[col] && strcmp(g_strstrip(head[col]), "cluster-ib"))
        col++;
    assert_non_null(head[col]);
    assert_true(g_ascii_isdigit(g_strstrip(cells[col])[0]));
    assert_non_null(strstr(cells[col], " d:"));
    g_strfreev(cells);
    g_strfreev(head);
    g_strfreev(lines);
    g_free(doc);
    g_free(out);
    g_free(err);
}

/* A copy of the list with `edit` applied (a sed expression) fails
 * naming `needle`. */
static void list_disagrees(const char *edit, const char *needle)
{
    char *dir = g_dir_make_tmp("pgsim-pairings-XXXXXX", NULL);
    char *list = g_build_filename(dir, "pairings.yaml", NULL);
    char *cmd = g_strdup_printf("sed '%s' " LIST " > '%s'", edit, list);
    assert_int_equal(system(cmd), 0);
    char *out, *err;
    assert_int_equal(pairings(list, &out, &err), 2);
    if (!strstr(err, needle))
        fail_msg("want '%s' in: %s", needle, err);
    assert_string_equal(out, "");
    g_free(out);
    g_free(err);
    g_free(cmd);
    cmd = g_strdup_printf("rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
    g_free(cmd);
    g_free(list);
    g_free(dir);
}

static void test_list_can_disagree(void **state)
{
    (void)state;
    /* a pairing that runs, listed as meaningless */
    list_disagrees("s/^meaningless:$/meaningless:\\n  - {configs: "
                   "[quickstart], models: [cluster-ib], error: found, "
                   "reason: x}/",
                   "quickstart on cluster-ib runs");
    /* a pairing that fails, not listed */
    list_disagrees("s/configs: \\[tokenring\\]/configs: [nothing]/",
                   "tokenring on cm5 fails and is not listed");
    /* listed, but the error does not say what the list says */
    list_disagrees("s/error: \"and no shared memory\"/error: \"teapot\"/",
                   "expected a located error with 'teapot'");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_doc_is_the_pairings),
        cmocka_unit_test(test_list_can_disagree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
