/* test_replay_cli.c — `pgsim replay TRACE --machine M` on a shipped
 * trace, run as a command with no --fidelity, gives the recorded run's
 * figures: it replays at the fidelity of the trace's header, not at the
 * model's faithful rung (docs/traces.md, Replaying).  The run's figures
 * are computed here by running the trace's config; the same command with
 * --fidelity faithful is shown to differ (the comparison can fail). */
#include "sim/app/run/report.h"
#include "sim/run/run.h"
#include "tests/app/cli/pgsim_spawn.h"
#include <json-glib/json-glib.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

/* sort-first's config runs the cluster at the analytic rung; the
 * cluster model's faithful rung is packet (docs/traces.md). */
#define CONFIG "configs/sortfirst-vehicle.yaml"
#define TRACE "traces/sortfirst-vehicle.pgt.gz"
#define MACHINE "cluster-ib"

/* The figures first, the fidelity's name last. */
static const char *const members[] = {"elapsed_s", "frames", "nodes",
                                      "comm",      "fidelity", NULL};

static JsonParser *parse(const char *text)
{
    JsonParser *p = json_parser_new();
    GError *e = NULL;
    json_parser_load_from_data(p, text, -1, &e);
    g_assert_no_error(e);
    return p;
}

/* The run of CONFIG as `pgsim run --format json` reports it. */
static JsonParser *run_json(void)
{
    GError *e = NULL;
    CfgRun *r = cfg_run_load(CONFIG, NULL, &e);
    g_assert_no_error(e);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = cfg_run_exec(r, &o, &e);
    g_assert_no_error(e);
    char *text = rpt_render(res, RPT_JSON, FALSE);
    JsonParser *p = parse(text);
    g_free(text);
    sim_result_free(res);
    cfg_run_free(r);
    return p;
}

/* The replay command's JSON report; extra: one more argument or NULL. */
static JsonParser *replay_json(const char *extra)
{
    const char *args[] = {"replay", TRACE,    "--machine", MACHINE,
                          "--format", "json", extra,       NULL};
    char *out = NULL, *err = NULL;
    int status = test_pgsim(args, &out, &err);
    if (status != 0)
        fail_msg("pgsim replay exited %d: %s", status, err);
    JsonParser *p = parse(out);
    g_free(out);
    g_free(err);
    return p;
}

/* The first of members[] on which the two reports differ, or NULL. */
static const char *differs(JsonParser *a, JsonParser *b)
{
    JsonObject *x = json_node_get_object(json_parser_get_root(a));
    JsonObject *y = json_node_get_object(json_parser_get_root(b));
    for (guint i = 0; members[i]; i++) {
        JsonNode *m = json_object_get_member(x, members[i]);
        JsonNode *n = json_object_get_member(y, members[i]);
        assert_non_null(m);
        assert_non_null(n);
        if (!json_node_equal(m, n))
            return members[i];
    }
    return NULL;
}

static void test_default_fidelity_round_trip(void **s)
{
    (void)s;
    JsonParser *run = run_json();
    JsonParser *rep = replay_json(NULL);
    const char *d = differs(run, rep);
    if (d)
        fail_msg("%s replayed without --fidelity: '%s' differs from the run",
                 TRACE, d);
    JsonParser *faithful = replay_json("--fidelity=faithful");
    d = differs(run, faithful); /* 1.360 ms against 1.272 ms in frame 0 */
    assert_non_null(d);
    assert_string_not_equal(d, "fidelity");
    g_object_unref(faithful);
    g_object_unref(rep);
    g_object_unref(run);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_fidelity_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
