/* test_docs.c — what a reader is told is what there is (issue 33, point
 * 8): README.md names every command of the table and every workload of
 * the registry, traces/ and the root switch of mpirun; no help text says
 * "seed 00N" where a paper's name belongs; and a speed-up above P is
 * explained in the run's own report (the quickstart's 18 on 16 nodes:
 * the serial reference's sorted-row insertion).  Runs the built binary. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>

#include "sim/app/cli/commands.h"
#include "sim/output/json.h"
#include "sim/workload/workload.h"
#include "tests/app/cli/pgsim_spawn.h"

static void test_readme_lists_everything(void **state)
{
    (void)state;
    char *readme = NULL;
    assert_true(g_file_get_contents("README.md", &readme, NULL, NULL));
    for (const CliCommand *c = cli_commands; c->name; c++) {
        char *use = g_strdup_printf("build/pgsim %s", c->name);
        if (!strstr(readme, use))
            fail_msg("README.md shows no '%s'", use);
        g_free(use);
    }
    for (guint i = 0; wl_all[i]; i++) {
        char *name = g_strdup_printf("`%s`", wl_all[i]->name);
        if (!strstr(readme, name))
            fail_msg("README.md names no workload %s", name);
        g_free(name);
    }
    assert_non_null(strstr(readme, "`traces/`"));
    assert_non_null(strstr(readme, "mpirun --allow-run-as-root"));
    g_free(readme);
}

/* Every help text: paper names, not the seed numbers of the sources. */
static void test_help_names_papers(void **state)
{
    (void)state;
    for (const CliCommand *c = cli_commands; c->name; c++) {
        const char *args[] = {"help", c->name, NULL};
        char *out, *err;
        test_pgsim(args, &out, &err);
        if (strstr(out, "seed 00") || strstr(err, "seed 00"))
            fail_msg("pgsim help %s says 'seed 00...'", c->name);
        g_free(out);
        g_free(err);
    }
}

static void test_speedup_above_p_explained(void **state)
{
    (void)state;
    const char *args[] = {"run", "configs/quickstart.yaml", "-q",
                          "--format=json", NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(args, &out, &err), 0);
    JsonNode *n = js_parse(out, -1, NULL, NULL);
    JsonArray *notes =
        json_object_get_array_member(json_node_get_object(n), "notes");
    assert_non_null(notes);
    const char *note = json_array_get_string_element(notes, 0);
    assert_non_null(strstr(note, "speed-up 18.1 is above P = 16 because of "
                                 "the serial reference's cost"));
    assert_non_null(strstr(note, "inserting spans into sorted row lists"));
    json_node_unref(n);
    g_free(out);
    g_free(err);
    /* the text report says it too */
    const char *text[] = {"run", "configs/quickstart.yaml", "-q", NULL};
    assert_int_equal(test_pgsim(text, &out, &err), 0);
    assert_non_null(strstr(out, "\nnote          speed-up 18.1 is above P"));
    g_free(out);
    g_free(err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_readme_lists_everything),
        cmocka_unit_test(test_help_names_papers),
        cmocka_unit_test(test_speedup_above_p_explained),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
