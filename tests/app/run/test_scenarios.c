/* test_scenarios.c — whole configs against golden results.
 *
 * Each scenario runs `pgsim run CONFIG --format json` twice: the two
 * outputs must be byte-identical (determinism) and equal to the golden
 * file tests/data/golden/<name>.json (no model changed by accident).
 * After a deliberate model change, `make golden` rewrites the files
 * (PGSIM_UPDATE_GOLDEN=1); review the diff before committing it.
 * JSON output carries no wall-clock figures unless --timing is given.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include <glib.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    const char *name;
    const char *config;
} Scenario;

static const Scenario scenarios[] = {
    {"quickstart", "configs/quickstart.yaml"},
    {"tokenring", "configs/tokenring.yaml"},
    {"pixelmerge-2pot", "configs/pixelmerge-2pot.yaml"},
    {"pphigs-flock", "configs/pphigs-flock.yaml"},
    {"sortfirst-vehicle", "configs/sortfirst-vehicle.yaml"},
    {"dpscan-cm200", "configs/dpscan-cm200.yaml"},
    {"performer-town", "configs/performer-town.yaml"},
    {"pn-onyx", "configs/pn-onyx.yaml"},
    {NULL, NULL},
};

static const char *pgsim_bin(void)
{
    return g_getenv("PGSIM_SANITIZE") ? "build-san/pgsim" : "build/pgsim";
}

/* Runs the config; returns its stdout (g_free), failing the test if the
 * run does not exit 0. */
static char *run_json(const char *config)
{
    const char *argv[] = {pgsim_bin(), "run",  config, "--quiet",
                          "--format",  "json", NULL};
    char *out = NULL, *err = NULL;
    int status = 0;
    GError *e = NULL;
    assert_true(g_spawn_sync(NULL, (char **)argv, NULL, G_SPAWN_DEFAULT, NULL,
                             NULL, &out, &err, &status, &e));
    if (!g_spawn_check_wait_status(status, NULL))
        fail_msg("%s exited with status %d: %s", config, status, err);
    g_free(err);
    return out;
}

/* s with every match of pattern replaced by with (s taken). */
static char *replace(char *s, const char *pattern, const char *with)
{
    GRegex *re = g_regex_new(pattern, 0, 0, NULL);
    char *out = g_regex_replace_literal(re, s, -1, 0, with, 0, NULL);
    g_regex_unref(re);
    g_free(s);
    return out;
}

/* The build's version moves with every commit, an input file's hash with
 * every edit of a model's comments or sources: the golden files hold "X"
 * in their places (the rest of the provenance, the input paths among it,
 * is compared; test_run_inputs checks the hashes). */
static char *without_version(char *json)
{
    json = replace(json, "\"pgsim_version\" : \"[^\"]*\"",
                   "\"pgsim_version\" : \"X\"");
    return replace(json, "\"sha256\" : \"[0-9a-f]{64}\"",
                   "\"sha256\" : \"X\"");
}

static void check_scenario(const Scenario *s)
{
    char *a = without_version(run_json(s->config));
    char *b = without_version(run_json(s->config));
    if (strcmp(a, b) != 0)
        fail_msg("%s: two runs with the same seed differ", s->config);
    char *path = g_strdup_printf("tests/data/golden/%s.json", s->name);
    if (g_getenv("PGSIM_UPDATE_GOLDEN")) {
        assert_true(g_file_set_contents(path, a, -1, NULL));
        printf("golden: wrote %s\n", path);
    } else {
        char *want = NULL;
        if (!g_file_get_contents(path, &want, NULL, NULL))
            fail_msg("%s missing: run make golden", path);
        if (strcmp(a, want) != 0)
            fail_msg("%s: result differs from %s (a model changed? "
                     "review, then make golden)",
                     s->config, path);
        g_free(want);
    }
    g_free(path);
    g_free(a);
    g_free(b);
}

static void test_scenarios_match_golden(void **state)
{
    (void)state;
    for (int i = 0; scenarios[i].name; i++)
        check_scenario(&scenarios[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scenarios_match_golden),
    };
    return cmocka_run_group_tests_name("scenarios", tests, NULL, NULL);
}
