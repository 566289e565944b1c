/* test_dp_model.c — the dpscan cost model's YAML (dp_model.c): every
 * parameter read into its field, the bounds of msg_bytes (1 B to 64 KiB),
 * arity, router_procs and level_bandwidth taken at their edges, and each
 * input error located with its message (issue 21: the loader's error
 * paths had no test).  Provenance is the machine layer's (model.h): a
 * value without one is refused when the runner builds the machine; a
 * model without a dpscan: section, or not on the search path, is refused
 * by the runner at the config's model key. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/dpscan/dp_model.h"
#include "sim/run/run.h"
#include "tests/support.h"
#include <glib/gstdio.h>

typedef struct {
    const char *key, *text;
} Entry;

static const Entry spmd[] = {
    {"arch", "{value: spmd, source: s}"},
    {"op", "{value: 1 us, source: s}"},
    {"step", "{value: 2 us, assumption: a}"},
    {"scan_slice", "{value: 3 us, calibrated: c, note: n}"},
    {"net_latency", "{value: 4 us, source: s}"},
    {"msg_overhead", "{value: 5 us, source: s}"},
    {"msg_bytes", "{value: 64 KiB, source: s}"},
    {"arity", "{value: 2, source: s}"},
    {"level_bandwidth", "{value: [20 MB/s, 10 MB/s], source: s}"},
    {NULL, NULL}};

static const Entry simd[] = {
    {"arch", "{value: simd, source: s}"},
    {"op", "{value: 1 us, source: s}"},
    {"step", "{value: 2 us, source: s}"},
    {"scan_slice", "{value: 3 us, source: s}"},
    {"vp_pow2", "{value: true, source: s}"},
    {"news_slice", "{value: 6 us, source: s}"},
    {"router_procs", "{value: 16, source: s}"},
    {"send_setup", "{value: 7 us, source: s}"},
    {"send_slice", "{value: 8 us, source: s}"},
    {"send_vp", "{value: 9 us, source: s}"},
    {"send_msg", "{value: 10 us, source: s}"},
    {NULL, NULL}};

/* The section, one key a line ("key: text"), with `key` given `text`
 * instead (NULL text: left out; a key not in the table: added last). */
static char *section(const Entry *e, const char *key, const char *text)
{
    GString *s = g_string_new("dpscan:\n");
    gboolean seen = FALSE;
    for (; e->key; e++) {
        const char *t = e->text;
        if (key && !strcmp(key, e->key)) {
            seen = TRUE;
            t = text;
        }
        if (t)
            g_string_append_printf(s, "  %s: %s\n", e->key, t);
    }
    if (key && !seen)
        g_string_append_printf(s, "  %s: %s\n", key, text);
    return g_string_free(s, FALSE);
}

static gboolean load(const Entry *e, const char *key, const char *text,
                     WlDpMachine *m, GError **err)
{
    char *y = section(e, key, text);
    CfgNode *root = cfg_load_string(y, "m.yaml", err);
    g_free(y);
    assert_non_null(root);
    memset(m, 0, sizeof *m);
    gboolean ok = wl_dp_machine_from_cfg(cfg_get(root, "dpscan"), m, err);
    cfg_free(root);
    return ok;
}

static void test_spmd_fields(void **state)
{
    (void)state;
    WlDpMachine m;
    GError *err = NULL;
    if (!load(spmd, NULL, NULL, &m, &err))
        fail_msg("%s", err->message);
    assert_int_equal(m.arch, WL_DP_SPMD);
    assert_int_equal(m.op, SIM_US);
    assert_int_equal(m.step, 2 * SIM_US);
    assert_int_equal(m.scan_slice, 3 * SIM_US);
    assert_int_equal(m.net_latency, 4 * SIM_US);
    assert_int_equal(m.msg_overhead, 5 * SIM_US);
    assert_int_equal(m.msg_bytes, 65536);
    assert_int_equal(m.arity, 2);
    assert_int_equal(m.levels, 2);
    assert_true(m.level_bw[0] == 20e6 && m.level_bw[1] == 10e6);
    assert_int_equal(m.router_procs, 1);
    assert_false(m.vp_pow2);
    assert_int_equal(m.news_slice, 0);
    /* the other edges of the ranges */
    assert_true(load(spmd, "msg_bytes", "{value: 1 B, source: s}", &m, &err));
    assert_int_equal(m.msg_bytes, 1);
    assert_true(load(spmd, "arity", "{value: 64, source: s}", &m, &err));
    assert_int_equal(m.arity, 64);
    assert_true(load(spmd, "router_procs", "{value: 1, source: s}", &m, &err));
    assert_int_equal(m.router_procs, 1);
    assert_true(load(spmd, "router_procs", "{value: 1024, source: s}", &m,
                     &err));
    assert_int_equal(m.router_procs, 1024);
    assert_true(load(spmd, "level_bandwidth",
                     "{value: [1 MB/s, 2 MB/s, 3 MB/s, 4 MB/s, 5 MB/s, "
                     "6 MB/s, 7 MB/s, 8 MB/s], source: s}",
                     &m, &err));
    assert_int_equal(m.levels, 8);
    assert_true(m.level_bw[7] == 8e6);
    assert_true(load(spmd, "level_bandwidth", "{value: [3 MB/s], source: s}",
                     &m, &err));
    assert_int_equal(m.levels, 1);
}

static void test_simd_fields(void **state)
{
    (void)state;
    WlDpMachine m;
    GError *err = NULL;
    if (!load(simd, NULL, NULL, &m, &err))
        fail_msg("%s", err->message);
    assert_int_equal(m.arch, WL_DP_SIMD);
    assert_true(m.vp_pow2);
    assert_int_equal(m.news_slice, 6 * SIM_US);
    assert_int_equal(m.router_procs, 16);
    assert_int_equal(m.send_setup, 7 * SIM_US);
    assert_int_equal(m.send_slice, 8 * SIM_US);
    assert_int_equal(m.send_vp, 9 * SIM_US);
    assert_int_equal(m.send_msg, 10 * SIM_US);
    /* optional keys left out */
    assert_true(load(simd, "send_vp", NULL, &m, &err));
    assert_int_equal(m.send_vp, 0);
    assert_true(load(simd, "vp_pow2", NULL, &m, &err));
    assert_false(m.vp_pow2);
    assert_true(load(simd, "router_procs", NULL, &m, &err));
    assert_int_equal(m.router_procs, 1);
}

static void bad(const Entry *e, const char *key, const char *text,
                const char *message)
{
    WlDpMachine m;
    GError *err = NULL;
    assert_false(load(e, key, text, &m, &err));
    assert_non_null(err);
    if (strcmp(err->message, message))
        fail_msg("%s: %s: message '%s', expected '%s'", key,
                 text ? text : "(none)", err->message, message);
    g_error_free(err);
}

static void test_errors(void **state)
{
    (void)state;
    bad(spmd, "msg_bytes", "{value: 65537 B, source: s}",
        "m.yaml:8:22: found a size out of range, expected 1 B to 64 KiB");
    bad(spmd, "msg_bytes", "{value: 0 B, source: s}",
        "m.yaml:8:22: found a size out of range, expected 1 B to 64 KiB");
    bad(spmd, "msg_bytes", NULL,
        "m.yaml:2:3: found no 'msg_bytes', expected the parameter in the "
        "section");
    bad(spmd, "arity", "{value: 1, source: s}",
        "m.yaml:9:18: found '1', expected a count in [2, 64]");
    bad(spmd, "arity", "{value: 65, source: s}",
        "m.yaml:9:18: found '65', expected a count in [2, 64]");
    bad(spmd, "arity", NULL,
        "m.yaml:2:3: found no 'arity', expected the parameter in the "
        "section");
    bad(spmd, "router_procs", "{value: 0, source: s}",
        "m.yaml:11:25: found '0', expected a count in [1, 1024]");
    bad(spmd, "level_bandwidth", "{value: [], source: s}",
        "m.yaml:10:28: found not a list of 1 to 8 bandwidths, expected "
        "[20 MB/s, 10 MB/s, ...]");
    bad(spmd, "level_bandwidth",
        "{value: [1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, "
        "1 MB/s, 1 MB/s], source: s}",
        "m.yaml:10:28: found not a list of 1 to 8 bandwidths, expected "
        "[20 MB/s, 10 MB/s, ...]");
    bad(spmd, "level_bandwidth", "{value: 5 MB/s, source: s}",
        "m.yaml:10:28: found not a list of 1 to 8 bandwidths, expected "
        "[20 MB/s, 10 MB/s, ...]");
    bad(spmd, "level_bandwidth", "{value: [2 MB/s, 0 MB/s], source: s}",
        "m.yaml:10:37: found 0 MB/s, expected a bandwidth > 0");
    bad(spmd, "level_bandwidth", "{value: [fast], source: s}",
        "m.yaml:10:29: found fast, expected a bandwidth > 0");
    bad(spmd, "level_bandwidth", "{value: [[1]], source: s}",
        "m.yaml:10:29: found a non-scalar, expected a bandwidth > 0");
    bad(spmd, "level_bandwidth", NULL,
        "m.yaml:2:3: found no 'level_bandwidth', expected the parameter in "
        "the section");
    bad(spmd, "net_latency", NULL,
        "m.yaml:2:3: found no 'net_latency', expected the parameter in the "
        "section");
    bad(spmd, "op", "{source: s}",
        "m.yaml:3:7: found no key 'value' in this map, expected "
        "'value': a non-negative time with a unit (ps, ns, us, \u00b5s, ms, "
        "s, min, h)");
    bad(spmd, "arch", NULL,
        "m.yaml:2:3: found no 'arch', expected the parameter in the section");
    bad(spmd, "arch", "{value: mimd, source: s}",
        "m.yaml:2:17: found 'mimd', expected one of: simd, spmd");
    bad(spmd, "vp_pow2", "maybe",
        "m.yaml:11:12: found 'maybe', expected true or false");
    bad(simd, "send_setup", NULL,
        "m.yaml:2:3: found no 'send_setup', expected the parameter in the "
        "section");
    bad(simd, "send_msg", "{value: soon, source: s}",
        "m.yaml:12:21: found 'soon', expected a non-negative time with a "
        "unit (ps, ns, us, \u00b5s, ms, s, min, h)");
}

/* A config with an inline machine whose dpscan: section has `op` given
 * as `op`, run through the runner: refused with `want`. */
static void refused_op(const char *op, const char *want)
{
    char *yaml = g_strdup_printf(
        "machine:\n"
        "  name: t\n"
        "  nodes: {array: {count: {value: 2, source: s},"
        " lanes: {value: 16, source: s}}}\n"
        "  network: {topology: {value: ring, source: s},"
        " bandwidth: {value: 1 MB/s, source: s}}\n"
        "  dpscan:\n"
        "    arch: {value: simd, source: s}\n"
        "    op: %s\n"
        "    step: {value: 1 us, source: s}\n"
        "    scan_slice: {value: 1 us, source: s}\n"
        "    send_setup: {value: 1 us, source: s}\n"
        "    send_slice: {value: 1 us, source: s}\n"
        "workload: {type: dpscan, width: 4, height: 4}\n"
        "scene: {generator: isosurface, grid: 4}\n",
        op);
    GError *err = NULL;
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    SimResult *r = support_run_text(yaml, &o, &err);
    g_free(yaml);
    if (!want) {
        if (!r)
            fail_msg("%s: %s", op, err->message);
        sim_result_free(r);
        return;
    }
    assert_null(r);
    assert_non_null(err);
    if (!strstr(err->message, want))
        fail_msg("%s: '%s' lacks '%s'", op, err->message, want);
    g_error_free(err);
}

/* The provenance dp_model.c's own checker used to demand, now the
 * machine layer's, when the runner builds the machine. */
static void test_provenance_at_runner(void **state)
{
    (void)state;
    refused_op("{value: 1 us, source: s}", NULL);
    refused_op("1 us", "test.yaml:7:9: found workload parameter 'op' "
                       "without a value");
    refused_op("{source: s}", "test.yaml:7:9: found workload parameter "
                              "'op' without a value");
    refused_op("{value: 1 us}", "test.yaml:7:9: found parameter 'op' "
                                "without a provenance");
}

static void test_not_a_map_and_load(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string("dpscan: 3\n", "m.yaml", &err);
    WlDpMachine m;
    assert_false(wl_dp_machine_from_cfg(cfg_get(root, "dpscan"), &m, &err));
    assert_string_equal(err->message, "m.yaml:1:9: found not a map, expected "
                                      "a dpscan: section");
    g_clear_error(&err);
    cfg_free(root);
    /* a machine model without a dpscan: section, through the runner */
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    assert_null(support_run_text("machine: {model: ipsc2}\n"
                                 "workload: {type: dpscan}\n"
                                 "scene: {generator: isosurface, grid: 4}\n",
                                 &o, &err));
    assert_non_null(strstr(err->message, "test.yaml:1:18: found machine "
                                         "'ipsc2' without a dpscan: section, "
                                         "expected a model with the "
                                         "data-parallel costs of dpscan"));
    g_clear_error(&err);
    assert_null(support_run_text("workload: {type: dpscan, model: "
                                 "no_such_model}\n"
                                 "scene: {generator: isosurface, grid: 4}\n",
                                 &o, &err));
    assert_non_null(strstr(err->message, "no_such_model"));
    g_clear_error(&err);
}

/* models/cm200.yaml as model `name` in folder dir (created). */
static char *user_model(const char *dir, const char *name)
{
    char *text = NULL;
    assert_true(g_file_get_contents("models/cm200.yaml", &text, NULL, NULL));
    char **parts = g_strsplit(text, "\nname: cm200\n", -1);
    assert_int_equal(g_strv_length(parts), 2);
    char *line = g_strdup_printf("\nname: %s\n", name);
    char *mine = g_strjoinv(line, parts);
    char *file = g_strdup_printf("%s.yaml", name);
    char *path = g_build_filename(dir, file, NULL);
    assert_int_equal(g_mkdir_with_parents(dir, 0700), 0);
    assert_true(g_file_set_contents(path, mine, -1, NULL));
    g_strfreev(parts);
    g_free(text), g_free(line), g_free(mine), g_free(file);
    return path;
}

static const char *const user_cfg =
    "schema_version: 1\n"
    "workload: {type: dpscan, model: %s, processors: 64, width: 16, "
    "height: 12}\n"
    "scene: {generator: isosurface, grid: 4}\n";

/* A dpscan config using a model from the user's own folder — the
 * models/ beside the config (an extra folder of the runner) or a
 * PGSIM_MODELS folder — validates and runs, like any machine workload
 * (dpscan's own reader looked in ./models only). */
static void test_user_model_folder(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("dpmodel-XXXXXX", NULL);
    char *mdir = g_build_filename(dir, "models", NULL);
    char *udir = g_build_filename(dir, "mine", NULL);
    char *m1 = user_model(mdir, "cm200beside");
    char *m2 = user_model(udir, "cm200env");
    char *cfg = g_build_filename(dir, "run.yaml", NULL);
    char *text = g_strdup_printf(user_cfg, "cm200beside");
    assert_true(g_file_set_contents(cfg, text, -1, NULL));
    GError *err = NULL;
    CfgRun *r = cfg_run_load(cfg, NULL, &err);
    if (!r)
        fail_msg("%s", err->message);
    CfgRunOpts vo = {.quiet = TRUE, .dry_run = TRUE}; /* pgsim validate */
    assert_null(cfg_run_exec(r, &vo, &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_DRY_RUN));
    g_clear_error(&err);
    cfg_run_free(r);
    r = cfg_run_load(cfg, NULL, &err);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = r ? cfg_run_exec(r, &o, &err) : NULL;
    if (!res)
        fail_msg("%s", err->message);
    assert_true(res->frame_times->len == 1 && res->elapsed > 0);
    sim_result_free(res);
    cfg_run_free(r);
    /* the same through PGSIM_MODELS */
    g_setenv("PGSIM_MODELS", udir, TRUE);
    g_free(text);
    text = g_strdup_printf(user_cfg, "cm200env");
    SupportRun so = {.fidelity = "analytic", .frames = 1};
    res = support_run_text(text, &so, &err);
    g_unsetenv("PGSIM_MODELS");
    if (!res)
        fail_msg("%s", err->message);
    assert_true(res->elapsed > 0);
    sim_result_free(res);
    g_remove(m1), g_remove(m2), g_remove(cfg);
    g_rmdir(mdir), g_rmdir(udir), g_rmdir(dir);
    g_free(m1), g_free(m2), g_free(cfg), g_free(text);
    g_free(mdir), g_free(udir), g_free(dir);
}

int main(void)
{
    /* a GLib warning or critical (an error set over another) fails */
    g_log_set_always_fatal(G_LOG_LEVEL_WARNING | G_LOG_LEVEL_CRITICAL);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spmd_fields),
        cmocka_unit_test(test_simd_fields),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_provenance_at_runner),
        cmocka_unit_test(test_not_a_map_and_load),
        cmocka_unit_test(test_user_model_folder),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
