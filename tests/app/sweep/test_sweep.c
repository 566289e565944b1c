/* test_sweep.c — sweep files (expansion, seeds, located errors), the local
 * worker pool, failing and crashing points, and resume after a kill. */
#include "sim/app/sweep/sweep_run.h"
#include "tests/app/sweep/sweep_fake.h"
#include "sim/core/rng.h"
#include "sim/output/json.h"
#include "sim/output/provenance.h"
#include "sim/output/table.h"
#include <glib/gstdio.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static SweepSpec *parse_ok(const char *text)
{
    GError *err = NULL;
    SweepSpec *s = sweep_spec_parse(text, "/tmp/t.yaml", &err);
    g_assert_no_error(err);
    return s;
}

static void assert_values(const SweepSpec *s, guint i, const char *a,
                          const char *b)
{
    SweepPoint pt = sweep_spec_point(s, i);
    assert_string_equal(sweep_spec_value(s, &pt, 0), a);
    assert_string_equal(sweep_spec_value(s, &pt, 1), b);
}

static void test_product(void **state)
{
    (void)state;
    SweepSpec *s = parse_ok("base: {run: {seed: 7}, a: 0, b: 0}\n"
                            "parameters:\n"
                            "  a: [1, 2, 3]\n"
                            "  b: {from: 0.5, to: 1.5, step: 0.5}\n"
                            "repetitions: 2\n");
    assert_int_equal(s->combos, 9);
    assert_int_equal(sweep_spec_points(s), 18);
    assert_values(s, 0, "1", "0.5");
    assert_values(s, 1, "1", "0.5"); /* repetition 1 of combination 0 */
    assert_values(s, 2, "1", "1");
    assert_values(s, 4, "1", "1.5");
    assert_values(s, 6, "2", "0.5");
    assert_values(s, 17, "3", "1.5");
    SweepPoint p0 = sweep_spec_point(s, 6), p1 = sweep_spec_point(s, 7);
    assert_int_equal(p0.seed, 7);
    assert_true(p1.seed == sim_rng_mix(7 + 1) >> 1);
    GError *err = NULL;
    CfgNode *cfg = sweep_spec_config(s, &p1, &err);
    g_assert_no_error(err);
    assert_string_equal(cfg_scalar(cfg_path(cfg, "a")), "2");
    assert_string_equal(cfg_scalar(cfg_path(cfg, "b")), "0.5");
    char seed[32];
    g_snprintf(seed, sizeof seed, "%" G_GUINT64_FORMAT, p1.seed);
    assert_string_equal(cfg_scalar(cfg_path(cfg, "run.seed")), seed);
    cfg_free(cfg);
    sweep_spec_free(s);
}

static void test_zip_and_ranges(void **state)
{
    (void)state;
    SweepSpec *s = parse_ok("base: {x: {y: 1}}\n"
                            "combine: zip\n"
                            "seed: 3\n"
                            "parameters:\n"
                            "  x.y: {from: 2, to: 16, factor: 2}\n"
                            "  name: {values: [a, b, c, d]}\n");
    assert_int_equal(sweep_spec_points(s), 4);
    assert_values(s, 0, "2", "a");
    assert_values(s, 3, "16", "d");
    assert_int_equal(sweep_spec_point(s, 2).seed, 3);
    sweep_spec_free(s);
    s = parse_ok("base: {n: 1}\nparameters: {n: {from: 10, to: 1, "
                 "step: -3}}\n");
    assert_int_equal(sweep_spec_points(s), 4);
    SweepPoint pt = sweep_spec_point(s, 3);
    assert_string_equal(sweep_spec_value(s, &pt, 0), "1");
    sweep_spec_free(s);
}

static void expect_bad(const char *text, const char *msg)
{
    GError *err = NULL;
    assert_null(sweep_spec_parse(text, "bad.yaml", &err));
    assert_non_null(err);
    if (!strstr(err->message, msg))
        fail_msg("got: %s\nwanted: %s", err->message, msg);
    g_error_free(err);
}

static void test_bad_files(void **state)
{
    (void)state;
    expect_bad("base: {a: 1}\nparameters: {a: [1, 2]}\nrepeat: 2\n",
               "bad.yaml:3:9: found unknown key 'repeat', expected one of:");
    expect_bad("base: {a: 1}\ncombine: zip\n"
               "parameters:\n  a: [1, 2]\n  b: [1, 2, 3]\n",
               "bad.yaml:5:6: found 3 values for 'b', expected 2");
    expect_bad("base: {a: 1}\nparameters:\n  a: {from: 1, to: 5, step: -1}\n",
               "bad.yaml:3:");
    expect_bad("base: {a: 1}\nparameters:\n  a: {from: 1, to: 5}\n",
               "found neither 'step' nor 'factor'");
    expect_bad("base: {a: 1}\nparameters:\n  a: []\n",
               "bad.yaml:3:6: found an empty list");
    expect_bad("parameters: {a: [1]}\n", "found no 'base'");
    expect_bad("base: {a: 1}\nplots:\n  - {x: a}\n", "bad.yaml:3:");
    expect_bad("base: {a: 1}\ncombine: cross\n", "bad.yaml:2:");
    /* names that would leave the output folder (issue 32) */
    expect_bad("name: ../../x\nbase: {a: 1}\nparameters: {a: [1]}\n",
               "bad.yaml:1:7: found the sweep name '../../x', expected a "
               "name of letters");
    expect_bad("base: {a: 1}\nparameters: {a: [1]}\n"
               "plots:\n  - {name: ../x, x: a, y: a}\n",
               "bad.yaml:4:12: found the plot name '../x', expected a "
               "name of letters");
    expect_bad("base: {a: 1}\nparameters: {a: [1]}\n"
               "plots:\n  - {name: \"a`touch M`\", x: a, y: a}\n",
               "bad.yaml:4:12: found the plot name 'a`touch M`'");
}

/* Every file under tests/data/bad/sweep/ fails with a located error. */
static void test_bad_data_files(void **state)
{
    (void)state;
    const char *cases[][2] = {
        {"unknown-key.yaml", ":4:10: found unknown key 'repeats'"},
        {"zip-lengths.yaml", ":5:6: found 3 values for 'b', expected 2"},
        {"bad-step.yaml", ":3:30: found a step that never reaches 'to'"},
        {"plot-key.yaml", ":3:18: found unknown key 'logz'"},
        {"missing-base.yaml", "no-such-base.yaml"},
        {"list-base.yaml", "list-base.txt:1:1: found a sequence, expected a run"},
    };
    for (size_t i = 0; i < G_N_ELEMENTS(cases); i++) {
        char *path =
            g_build_filename("tests/data/bad/sweep", cases[i][0], NULL);
        GError *err = NULL;
        assert_null(sweep_spec_load(path, &err));
        assert_non_null(err);
        if (!g_str_has_prefix(err->message, path) ||
            !strstr(err->message, cases[i][1]))
            fail_msg("%s: got '%s'", path, err->message);
        g_error_free(err);
        g_free(path);
    }
}

/* ---- running --------------------------------------------------------- */

static const char run_yaml[] = "base: {run: {seed: 11}, a: 0, b: 0}\n"
                               "parameters:\n"
                               "  a: [1, 2, 3]\n"
                               "  b: {from: 0, to: 4, step: 1}\n"
                               "repetitions: 2\n";

/* The text after a results.csv's leading comment lines (its provenance,
 * checked by test_results_provenance). */
static char *after_comments(char *csv)
{
    const char *p = csv;
    while (*p == '#')
        p = strchr(p, '\n') + 1;
    char *rows = g_strdup(p);
    g_free(csv);
    return rows;
}

/* Runs a sweep parsed from yaml as if read from `path` into dir; returns
 * results.csv. */
static char *run_sweep_at(const char *yaml, const char *path, int jobs,
                          gboolean resume, char *dir)
{
    GError *err = NULL;
    SweepSpec *s = sweep_spec_parse(yaml, path, &err);
    g_assert_no_error(err);
    SweepLog *log = sweep_log_open(dir, s, resume, &err);
    g_assert_no_error(err);
    SweepJob j;
    sweep_job_init(&j, s, log, sweep_fake_run, FALSE);
    assert_true(sweep_run_local(&j, jobs, &err));
    g_assert_no_error(err);
    sweep_job_clear(&j);
    sweep_log_close(log);
    assert_true(sweep_log_finish(dir, s, NULL, &err));
    sweep_spec_free(s);
    char *file = g_build_filename(dir, "results.csv", NULL), *csv = NULL;
    assert_true(g_file_get_contents(file, &csv, NULL, NULL));
    g_free(file);
    return csv;
}

/* results.csv without its provenance comment lines. */
static char *run_sweep(const char *yaml, int jobs, gboolean resume, char *dir)
{
    return after_comments(run_sweep_at(yaml, "/tmp/t.yaml", jobs, resume, dir));
}

static guint count_lines(const char *s)
{
    guint n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

/* DIR/provenance.json names the build, the sweep's seed and its base. */
static void check_provenance(const char *dir)
{
    char *path = g_build_filename(dir, "provenance.json", NULL), *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    GError *err = NULL;
    JsonNode *v = js_parse(text, -1, path, &err);
    g_assert_no_error(err);
    assert_int_equal((int)js_num(js_get(v, "points")), 30);
    JsonNode *p = js_get(v, "provenance");
    assert_true(strlen(js_str(js_get(p, "pgsim_version"))) > 0);
    assert_string_equal(js_str(js_get(p, "config")), "/tmp/t.yaml");
    assert_int_equal((int)js_num(js_get(p, "seed")), 11);
    JsonNode *eff = js_get(p, "effective_config");
    assert_string_equal(js_str(js_get(js_get(eff, "run"), "seed")), "11");
    json_node_unref(v);
    g_free(text);
    g_free(path);
}

static void test_jobs_same_rows(void **state)
{
    (void)state;
    char *d1 = g_dir_make_tmp("pgsim-sw-XXXXXX", NULL);
    char *d4 = g_dir_make_tmp("pgsim-sw-XXXXXX", NULL);
    char *c1 = run_sweep(run_yaml, 1, FALSE, d1);
    char *c4 = run_sweep(run_yaml, 4, FALSE, d4);
    assert_string_equal(c1, c4);
    assert_int_equal(count_lines(c1), 31);
    assert_true(g_str_has_prefix(c1, "point,repetition,seed,a,b,status,"
                                     "error,frames,mean_frame_s,"));
    assert_non_null(strstr(c1, "\n5,1,"));
    assert_non_null(strstr(c1, ",score,seedbits\n0,0,11,1,0,ok,,1,"));
    check_provenance(d1);
    g_free(c1);
    g_free(c4);
    sweep_test_rm_out(d1);
    sweep_test_rm_out(d4);
}

/* results.csv opens with the sweep's provenance as comment lines: the
 * build, the sweep file and the SHA-256 of its bytes, the base seed and
 * fidelity, the base config; a CSV reader skips them and finds 6 rows. */
static void test_results_provenance(void **state)
{
    (void)state;
    static const char yaml[] = "base: {run: {seed: 5, fidelity: flow}, a: 0}\n"
                               "parameters: {a: [1, 2, 3]}\n"
                               "repetitions: 2\n";
    char *d = g_dir_make_tmp("pgsim-sw-XXXXXX", NULL);
    char *file = g_build_filename(d, "s.yaml", NULL);
    assert_true(g_file_set_contents(file, yaml, -1, NULL));
    char *csv = run_sweep_at(yaml, file, 1, FALSE, d);
    char *sha = g_compute_checksum_for_string(G_CHECKSUM_SHA256, yaml, -1);
    char *want = g_strdup_printf(
        "# pgsim_version: %s\n# config: %s\n# config_sha256: %s\n"
        "# seed: 5\n# fidelity: flow\n# effective_config: "
        "{\"run\":{\"seed\":\"5\",\"fidelity\":\"flow\"},\"a\":\"0\"}\n"
        "point,",
        prov_version(), file, sha);
    if (!g_str_has_prefix(csv, want))
        fail_msg("results.csv begins\n%.400s\nexpected\n%s", csv, want);
    char *res = g_build_filename(d, "results.csv", NULL);
    GError *err = NULL;
    DataTable *t = dt_read_csv(res, &err);
    g_assert_no_error(err);
    assert_int_equal(t->rows->len, 6);
    assert_string_equal(g_ptr_array_index(t->cols, 0), "point");
    dt_free(t);
    g_remove(file);
    g_free(res);
    g_free(file);
    g_free(want);
    g_free(sha);
    g_free(csv);
    sweep_test_rm_out(d);
}

static void test_failures_recorded(void **state)
{
    (void)state;
    char *d = g_dir_make_tmp("pgsim-sw-XXXXXX", NULL);
    char *csv =
        run_sweep("base: {a: 0}\nparameters: {a: [3, 4, 5, 6]}\n", 2, FALSE, d);
    assert_int_equal(count_lines(csv), 5);
    assert_non_null(strstr(csv, "\n1,0,1,4,error,a is 4,"));
    assert_non_null(strstr(csv, "\n2,0,1,5,error,worker killed by "
                                "signal 6"));
    assert_non_null(strstr(csv, "\n3,0,1,6,ok,,"));
    g_free(csv);
    sweep_test_rm_out(d);
}

/* Keeps the first `keep` lines of the log and half of the next one, as a
 * kill during a write would leave it. */
static void cut_log(const char *dir, guint keep)
{
    char *path = g_build_filename(dir, "results.jsonl", NULL), *text;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    char *p = text;
    for (guint i = 0; i < keep; i++)
        p = strchr(p, '\n') + 1;
    p[(strchr(p, '\n') - p) / 2] = '\0';
    assert_true(g_file_set_contents(path, text, -1, NULL));
    g_free(text);
    g_free(path);
}

static void test_resume(void **state)
{
    (void)state;
    char *d = g_dir_make_tmp("pgsim-sw-XXXXXX", NULL);
    char *full = run_sweep(run_yaml, 3, FALSE, d);
    cut_log(d, 11);
    GError *err = NULL;
    SweepSpec *s = parse_ok(run_yaml);
    SweepLog *log = sweep_log_open(d, s, TRUE, &err);
    g_assert_no_error(err);
    assert_int_equal(sweep_log_n_done(log), 11);
    sweep_log_close(log);
    assert_null(sweep_log_open(d, s, FALSE, &err)); /* needs --resume */
    assert_non_null(strstr(err->message, "use --resume"));
    g_clear_error(&err);
    sweep_spec_free(s);
    char *resumed = run_sweep(run_yaml, 2, TRUE, d);
    assert_string_equal(full, resumed);
    char *path = g_build_filename(d, "results.jsonl", NULL), *jl;
    assert_true(g_file_get_contents(path, &jl, NULL, NULL));
    assert_int_equal(count_lines(jl), 30); /* nothing lost or doubled */
    g_free(jl);
    g_free(path);
    /* another sweep in the same directory is refused */
    s = parse_ok("base: {a: 0}\nparameters: {a: [1]}\n");
    assert_null(sweep_log_open(d, s, TRUE, &err));
    assert_non_null(strstr(err->message, "another sweep"));
    g_clear_error(&err);
    sweep_spec_free(s);
    g_free(full);
    g_free(resumed);
    sweep_test_rm_out(d);
}

/* A point that used 2 of a machine's 64 processors, each 99 % busy. */
static gboolean two_of_64(const CfgNode *cfg, uint64_t seed, SimResult **out,
                          GError **err)
{
    (void)cfg, (void)seed, (void)err;
    SimResult *r = sim_result_new("fake", "none");
    r->elapsed = 100 * SIM_US;
    for (int i = 0; i < 2; i++)
        sim_busy_add(&sim_result_add_node(r, i ? "n1" : "n0", "node")->busy,
                     0, 99 * SIM_US);
    sim_result_add_idle(r, "node", 62);
    *out = r;
    return TRUE;
}

/* util_mean is over the processors the point used (0.99, not 0.03 with
 * the 62 idle ones averaged in as zeros); they are counted apart. */
static void test_util_over_used(void **state)
{
    (void)state;
    SweepSpec *s = parse_ok("base: {a: 0}\nparameters:\n  a: [1]\n");
    char *line = sweep_point_line(s, 0, two_of_64);
    JsonNode *n = js_parse(line, -1, NULL, NULL);
    JsonObject *o = json_node_get_object(n);
    assert_true(fabs(json_object_get_double_member(o, "util_mean") - 0.99) <
                1e-12);
    assert_int_equal(json_object_get_int_member(o, "nodes_used"), 2);
    assert_int_equal(json_object_get_int_member(o, "nodes_idle"), 62);
    json_node_unref(n);
    g_free(line);
    sweep_spec_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_product),
        cmocka_unit_test(test_zip_and_ranges),
        cmocka_unit_test(test_bad_files),
        cmocka_unit_test(test_bad_data_files),
        cmocka_unit_test(test_jobs_same_rows),
        cmocka_unit_test(test_results_provenance),
        cmocka_unit_test(test_failures_recorded),
        cmocka_unit_test(test_resume),
        cmocka_unit_test(test_util_over_used),
    };
    return cmocka_run_group_tests_name("sweep", tests, NULL, NULL);
}
