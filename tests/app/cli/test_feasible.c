/* test_feasible.c — infeasible configurations are flagged in every run
 * (issue 33, point 7): ZBUF-EXC at 1024^2 needs about 13 MiB per node on
 * the iPSC/2's 4 MiB nodes, so `run` warns (the report says DOES NOT FIT,
 * JSON memory.fits is false), `run --strict` fails with exit 2, a sweep
 * row carries memory_fits 0 (1 at 400^2) and `sweep --strict` makes the
 * point an error.  Runs the built binary, like test_cli. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>
#include <glib/gstdio.h>

#include "sim/output/json.h"
#include "tests/app/cli/pgsim_spawn.h"

#define CONFIG "configs/pixelmerge-2pot.yaml"
#define ZX "--set=workload.scheme=zbuf-exc"

static void test_run_warns(void **state)
{
    (void)state;
    const char *big[] = {"run", CONFIG, ZX, "--set=workload.resolution=1024",
                         "-q", NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(big, &out, &err), 0);
    assert_non_null(strstr(err, "warning: " CONFIG ": per-node memory "));
    assert_non_null(strstr(err, "of a node (kind node): this configuration "
                                "does not fit on ipsc2"));
    assert_non_null(strstr(out, "of 4.00 MiB (kind node): DOES NOT FIT"));
    g_free(out);
    g_free(err);
    const char *fits[] = {"run", CONFIG, ZX, "-q", NULL};
    assert_int_equal(test_pgsim(fits, &out, &err), 0);
    assert_null(strstr(err, "warning"));
    assert_non_null(strstr(out, "of 4.00 MiB (kind node): fits\n"));
    g_free(out);
    g_free(err);
}

static void test_run_strict_and_json(void **state)
{
    (void)state;
    const char *strict[] = {"run", CONFIG, ZX, "--set=workload.resolution=1024",
                            "-q", "--strict", NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(strict, &out, &err), 2);
    assert_non_null(strstr(err, "error: " CONFIG ": per-node memory "));
    assert_string_equal(out, ""); /* no report of an infeasible run */
    g_free(out);
    g_free(err);
    const char *json[] = {"run", CONFIG, ZX, "--set=workload.resolution=1024",
                          "-q", "--format=json", NULL};
    assert_int_equal(test_pgsim(json, &out, &err), 0);
    JsonNode *n = js_parse(out, -1, NULL, NULL);
    JsonObject *m = json_object_get_object_member(json_node_get_object(n),
                                                  "memory");
    assert_false(json_object_get_boolean_member(m, "fits"));
    assert_int_equal(json_object_get_int_member(m, "node_B"), 4194304);
    assert_true(json_object_get_double_member(m, "peak_per_node_B") >
                3 * 4194304.0);
    json_node_unref(n);
    g_free(out);
    g_free(err);
}

/* The sweep's rows in point order: "resolution:memory_fits:status". */
static char *sweep_rows(const char *dir, gboolean strict, int *status)
{
    char *cwd = g_get_current_dir();
    char *path = g_build_filename(dir, "s.yaml", NULL);
    char *text = g_strdup_printf("name: s\nbase: %s/" CONFIG "\n"
                                 "parameters:\n  workload.scheme: [zbuf-exc]\n"
                                 "  workload.resolution: [400, 1024]\n",
                                 cwd);
    assert_true(g_file_set_contents(path, text, -1, NULL));
    char *out_dir = g_build_filename(dir, "out", NULL);
    char *out_arg = g_strdup_printf("--out=%s", out_dir);
    const char *args[] = {"sweep", path, "-q", "--jobs=1", out_arg,
                          strict ? "--strict" : NULL, NULL};
    char *out, *err;
    *status = test_pgsim(args, &out, &err);
    char *jl = g_build_filename(out_dir, "results.jsonl", NULL), *rows = NULL;
    assert_true(g_file_get_contents(jl, &rows, NULL, NULL));
    GString *s = g_string_new(NULL);
    char **lines = g_strsplit(rows, "\n", -1);
    for (guint i = 0; lines[i] && *lines[i]; i++) {
        JsonNode *n = js_parse(lines[i], -1, NULL, NULL);
        JsonObject *o = json_node_get_object(n);
        JsonNode *fit = json_object_get_member(o, "memory_fits");
        g_string_append_printf(
            s, "%s%" G_GINT64_FORMAT ":%s:%s", i ? " " : "",
            json_object_get_int_member(o, "workload.resolution"),
            fit ? json_node_get_value_type(fit) == G_TYPE_INVALID
                      ? "null"
                      : (json_object_get_int_member(o, "memory_fits") ? "1"
                                                                      : "0")
                : "-",
            json_object_get_string_member(o, "status"));
        json_node_unref(n);
    }
    g_strfreev(lines);
    g_free(rows);
    g_free(jl);
    g_free(out);
    g_free(err);
    g_free(out_arg);
    g_free(out_dir);
    g_free(text);
    g_free(path);
    g_free(cwd);
    return g_string_free(s, FALSE);
}

static void rm_tree(const char *dir, gboolean keep_dir)
{
    char *cmd = g_strdup_printf(keep_dir ? "rm -rf '%s'/*" : "rm -rf '%s'",
                                dir);
    assert_int_equal(system(cmd), 0);
    g_free(cmd);
}

static void test_sweep_column_and_strict(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-feasible-XXXXXX", NULL);
    int st;
    char *rows = sweep_rows(dir, FALSE, &st);
    assert_int_equal(st, 0);
    assert_string_equal(rows, "400:1:ok 1024:0:ok");
    g_free(rows);
    rm_tree(dir, TRUE);
    rows = sweep_rows(dir, TRUE, &st);
    assert_int_equal(st, 1); /* a point failed */
    assert_string_equal(rows, "400:1:ok 1024:-:error");
    g_free(rows);
    rm_tree(dir, FALSE);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_run_warns),
        cmocka_unit_test(test_run_strict_and_json),
        cmocka_unit_test(test_sweep_column_and_strict),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
