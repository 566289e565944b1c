/* test_model.c — model files: the shipped models load and are cited,
 * malformed models are rejected with located errors, overrides apply. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>
#include <glib/gstdio.h>

#include "sim/machine/machine.h"
#include "sim/machine/model.h"
#include "tests/support.h"

static const char *const shipped[] = {"ipsc2", "pixel-planes-5", "cm200",
                                      "cm5",   "cluster-ib",     NULL};

static void test_shipped_models_check(void **state)
{
    (void)state;
    for (const char *const *n = shipped; *n; n++) {
        GError *err = NULL;
        CfgNode *root = mach_load_model(*n, &err);
        if (!root)
            fail_msg("%s: %s", *n, err->message);
        const char *name = NULL;
        assert_true(cfg_get_str(root, "name", TRUE, &name, NULL));
        assert_string_equal(name, *n);
        cfg_free(root);
    }
}

/* A model may carry a workload's own top-level section: it is checked
 * for a value and a provenance and kept for the workload to parse. */
static void test_workload_section_kept(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "schema_version: 1\nname: t\n"
        "nodes: {node: {count: {value: 2, source: s}}}\n"
        "network: {topology: {value: ring, source: s},\n"
        "          bandwidth: {value: 1 MB/s, source: s}}\n"
        "wl: {weight: {value: 0.6, unit: us, calibrated: [a.b, c.d]}}\n",
        "t.yaml", NULL);
    assert_non_null(root);
    assert_true(mach_model_check(root, "t.yaml", &err));
    const CfgNode *w = cfg_path(root, "wl.weight.value");
    assert_non_null(w);
    assert_string_equal(cfg_scalar(w), "0.6");
    assert_int_equal(cfg_kind(cfg_path(root, "wl.weight.calibrated")), CFG_SEQ);
    cfg_free(root);
    /* pixel-planes-5 has one GP cost table, with calibrated entries */
    root = mach_load_model("pixel-planes-5", &err);
    assert_non_null(root);
    assert_null(cfg_get(root, "pphigs"));
    const char *text = NULL;
    assert_int_equal(
        mach_param_provenance(cfg_path(root, "nodes.gp.costs"), "color", &text),
        MACH_PROV_CALIBRATED);
    assert_non_null(strstr(text, "4-GP"));
    cfg_free(root);
}

static void test_unknown_model_name(void **state)
{
    (void)state;
    GError *err = NULL;
    assert_null(mach_load_model("no-such-machine", &err));
    assert_non_null(err);
    /* the folders searched, in order, from ./models (the working tree) */
    assert_true(g_str_has_prefix(
        err->message, "found no model 'no-such-machine', expected "
                      "models/no-such-machine.yaml (model folders searched: "
                      "models"));
    g_clear_error(&err);
    assert_null(mach_load_model("../models/ipsc2", &err));
    assert_non_null(strstr(err->message, "plain name"));
    g_error_free(err);
}

/* Loads tests/data/bad/models/<file> and expects a rejection located at
 * `line` whose message contains `needle`. */
static void expect_bad(const char *file, int line, const char *needle)
{
    char *path = g_strconcat("tests/data/bad/models/", file, NULL);
    GError *err = NULL;
    CfgNode *root = cfg_load_file(path, &err);
    if (!root)
        fail_msg("%s did not parse as YAML: %s", path, err->message);
    assert_false(mach_model_check(root, cfg_file(root), &err));
    assert_non_null(err);
    char *loc = g_strdup_printf("%s:%d:", path, line);
    if (!g_str_has_prefix(err->message, loc) || !strstr(err->message, needle))
        fail_msg("%s: got '%s', want prefix '%s' and '%s'", file, err->message,
                 loc, needle);
    g_free(loc);
    g_error_free(err);
    cfg_free(root);
    g_free(path);
}

static void test_bad_models_rejected(void **state)
{
    (void)state;
    expect_bad("missing-unit.yaml", 7, "without a unit");
    expect_bad("cost-missing-unit.yaml", 9, "without a unit");
    expect_bad("missing-source.yaml", 11, "without a provenance");
    expect_bad("empty-source.yaml", 6, "empty provenance");
    expect_bad("bare-value.yaml", 8, "bare value");
    expect_bad("unknown-key.yaml", 10, "unknown key 'bandwith'");
    expect_bad("misspelt-provenance.yaml", 6, "without a provenance");
    expect_bad("bad-version.yaml", 2, "found");
    expect_bad("workload-no-provenance.yaml", 11, "without a provenance");
    expect_bad("extents-unit.yaml", 9, "4 MB");
    expect_bad("workload-no-value.yaml", 11, "without a value");
    expect_bad("costs-not-a-map.yaml", 7, "a non-map costs section");
    expect_bad("kind-name-space.yaml", 6, "node kind name 'graphics processor'");
    expect_bad("cycles-unknown-class.yaml", 9, "work class 'texel'");
    expect_bad("cycles-no-clock.yaml", 8, "cycles: without the kind's clock");
    expect_bad("cycles-with-unit.yaml", 9, "'2 ns'");
}

static void test_models_path_from_env(void **state)
{
    (void)state;
    GError *err = NULL;
    g_setenv("PGSIM_MODELS", "/nonexistent:tests/data/models", TRUE);
    char *path = mach_model_path("tiny", &err);
    assert_non_null(path);
    assert_string_equal(path, "tests/data/models/tiny.yaml");
    g_free(path);
    /* ./models wins over $PGSIM_MODELS */
    path = mach_model_path("ipsc2", &err);
    assert_string_equal(path, "models/ipsc2.yaml");
    g_free(path);
    g_unsetenv("PGSIM_MODELS");
    assert_null(mach_model_path("tiny", &err));
    g_error_free(err);
}

/* A ./models folder holding one user model adds to the shipped models
 * (issue 18: it used to hide all of them), and a user model of the same
 * name as a shipped one wins. */
static void test_models_path_is_a_union(void **state)
{
    (void)state;
    char *repo = g_get_current_dir();
    char *tmp = g_dir_make_tmp("pgsim-models-XXXXXX", NULL);
    char *mine = g_build_filename(tmp, "models", NULL);
    assert_int_equal(g_mkdir(mine, 0777), 0);
    char *f1 = g_build_filename(mine, "mine.yaml", NULL);
    char *f2 = g_build_filename(mine, "ipsc2.yaml", NULL);
    assert_true(g_file_set_contents(f1, "x", -1, NULL));
    assert_true(g_file_set_contents(f2, "x", -1, NULL));
    g_setenv("PGSIM_DATA", repo, TRUE);
    assert_int_equal(g_chdir(tmp), 0);
    GError *err = NULL;
    char *p = mach_model_path("mine", &err);
    assert_string_equal(p, "models/mine.yaml");
    g_free(p);
    p = mach_model_path("ipsc2", &err); /* the user's copy first */
    assert_string_equal(p, "models/ipsc2.yaml");
    g_free(p);
    p = mach_model_path("cm5", &err); /* the shipped one, still found */
    g_assert_no_error(err);
    char *want = g_build_filename(repo, "models", "cm5.yaml", NULL);
    assert_string_equal(p, want);
    assert_null(mach_model_path("nothere", &err));
    assert_non_null(strstr(err->message, "found no model 'nothere'"));
    g_clear_error(&err);
    assert_int_equal(g_chdir(repo), 0);
    g_unsetenv("PGSIM_DATA");
    g_remove(f1);
    g_remove(f2);
    g_rmdir(mine);
    g_rmdir(tmp);
    g_free(want);
    g_free(p);
    g_free(f1);
    g_free(f2);
    g_free(mine);
    g_free(tmp);
    g_free(repo);
}

/* A user's what-if model: `provenance: assumption` lets values go
 * without a source (bare or as {value}); without it, the same text is
 * refused; a shipped model may not declare it (issue 18, point 7). */
static void test_provenance_default(void **state)
{
    (void)state;
    const char *body = "schema_version: 1\nname: whatif\nnodes:\n  cpu:\n"
                       "    count: 4\n    costs:\n      work: 10 us\n"
                       "      op: {value: 2 us}\nnetwork:\n"
                       "  topology: hypercube\n  bandwidth: 1 MB/s\n";
    GError *err = NULL;
    char *text = g_strconcat("provenance: assumption\n", body, NULL);
    CfgNode *root = cfg_load_string(text, "mine.yaml", &err);
    assert_true(mach_model_check(root, "mine.yaml", &err));
    g_assert_no_error(err);
    cfg_free(root);
    root = cfg_load_string(body, "mine.yaml", &err);
    assert_false(mach_model_check(root, "mine.yaml", &err));
    assert_non_null(strstr(err->message, "provenance: assumption"));
    g_clear_error(&err);
    cfg_free(root);
    g_free(text);
    text = g_strconcat("provenance: guess\n", body, NULL);
    root = cfg_load_string(text, "mine.yaml", &err);
    assert_false(mach_model_check(root, "mine.yaml", &err));
    g_clear_error(&err);
    cfg_free(root);
    g_free(text);
    /* the project's own models/ (a data root's) */
    char *repo = g_get_current_dir();
    g_setenv("PGSIM_DATA", repo, TRUE);
    text = g_strconcat("provenance: assumption\n", body, NULL);
    root = cfg_load_string(text, "models/whatif.yaml", &err);
    assert_false(mach_model_check(root, "models/whatif.yaml", &err));
    assert_non_null(strstr(err->message, "shipped model"));
    g_clear_error(&err);
    g_unsetenv("PGSIM_DATA");
    g_free(repo);
    cfg_free(root);
    g_free(text);
}

static MachMachine *from_text(SimEngine *eng, const char *text, CfgNode **root,
                              GError **err)
{
    *root = cfg_load_string(text, "run.yaml", err);
    assert_non_null(*root);
    return mach_new_from_cfg(eng, cfg_get(*root, "machine"), "analytic", err);
}

static void test_overrides_apply(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    MachMachine *m = from_text(eng,
                               "machine:\n"
                               "  model: ipsc2\n"
                               "  nodes:\n"
                               "    node:\n"
                               "      count: 8\n"
                               "      costs:\n"
                               "        span: 33 us\n"
                               "  network:\n"
                               "    startup: {value: 390 us,\n"
                               "              calibrated: \"a test\"}\n",
                               &root, &err);
    if (!m)
        fail_msg("%s", err->message);
    assert_int_equal(mach_kind(m, "node")->count, 8);
    assert_int_equal(mach_proc_total(m), 8);
    assert_int_equal(mach_cost(m, "node", "span"), 33 * SIM_US);
    /* untouched costs keep the model's value (whatever it is now) */
    MachMachine *plain = mach_new_from_model(eng, "ipsc2", "analytic", &err);
    assert_non_null(plain);
    assert_int_equal(mach_cost(m, "node", "compare"),
                     mach_cost(plain, "node", "compare"));
    assert_int_not_equal(mach_cost(plain, "node", "span"), 33 * SIM_US);
    mach_free(plain);
    SimTime t = 0;
    assert_true(mach_net_time(m, "startup", &t));
    assert_int_equal(t, 390 * SIM_US);
    /* the network follows the override: 8 nodes, a 3-cube */
    assert_non_null(mach_net(m));
    assert_int_equal(net_nodes(mach_net(m)), 8);
    /* provenance: overrides are reported as such, the rest keeps its own */
    const CfgNode *tree = mach_model_cfg(m);
    const CfgNode *kind = cfg_path(tree, "nodes.node");
    const CfgNode *net = cfg_path(tree, "network");
    const char *text = NULL;
    assert_int_equal(mach_param_provenance(kind, "count", &text),
                     MACH_PROV_OVERRIDE);
    assert_null(text);
    assert_int_equal(mach_param_provenance(kind, "clock", &text),
                     MACH_PROV_SOURCE);
    assert_non_null(strstr(text, "dunigan91"));
    assert_int_equal(mach_param_provenance(net, "per_hop", NULL),
                     MACH_PROV_ASSUMPTION);
    assert_int_equal(mach_param_provenance(net, "startup", &text),
                     MACH_PROV_CALIBRATED);
    assert_string_equal(text, "a test");
    assert_int_equal(mach_param_provenance(net, "nothing", NULL),
                     MACH_PROV_NONE);
    assert_string_equal(mach_provenance_name(MACH_PROV_CALIBRATED),
                        "calibrated");
    /* the config's keys are marked read for cfg_check_unused() */
    assert_true(cfg_check_unused(root, &err));
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
}

static void expect_bad_override(const char *text, const char *needle)
{
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    MachMachine *m = from_text(eng, text, &root, &err);
    assert_null(m);
    assert_non_null(err);
    if (!g_str_has_prefix(err->message, "run.yaml:") ||
        !strstr(err->message, needle))
        fail_msg("got '%s', want run.yaml:... and '%s'", err->message, needle);
    g_error_free(err);
    cfg_free(root);
    sim_engine_free(eng);
}

static void test_bad_overrides_rejected(void **state)
{
    (void)state;
    expect_bad_override("machine:\n  model: ipsc2\n  network:\n"
                        "    startup: 300\n",
                        "without a unit");
    expect_bad_override("machine:\n  model: ipsc2\n  nodes:\n"
                        "    node:\n      colour: 3\n",
                        "unknown key 'colour'");
    expect_bad_override("machine:\n  model: ipsc2\n  nodes:\n"
                        "    node:\n      count: 12\n",
                        "power of two");
    expect_bad_override("machine:\n  model: not-a-model\n", "not-a-model");
    expect_bad_override("machine:\n  model: cm5\n  network:\n    arity: 65\n",
                        "an unusable fat-tree arity");
    SimEngine *eng = sim_engine_new(1); /* 64 is the largest arity */
    CfgNode *root;
    MachMachine *m = from_text(
        eng, "machine:\n  model: cm5\n  network:\n    arity: 64\n", &root, NULL);
    assert_non_null(m);
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
}

static void test_check_section_marks_read(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string("machine:\n  model: cm5\n"
                                    "  nodes: {node: {count: 64}}\n",
                                    "run.yaml", &err);
    assert_non_null(root);
    assert_true(mach_check_section(cfg_get(root, "machine"), &err));
    assert_true(cfg_check_unused(root, &err));
    cfg_free(root);
}

/* mach_param_provenance: each of the three words, the first in key order
 * when there are several, none for a scalar or a list, and a provenance in
 * another file than the value (the model's source under a --set value)
 * is not the value's: an override. */
static void test_provenance_kinds(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "a: {value: 1 us, assumption: z}\nb: {value: 2 us, calibrated: k}\n"
        "c: {value: 3 us, assumption: y, source: s}\nd: [1, 2]\n"
        "e: {value: 4 us, source: t}\nf: {source: only}\n",
        "p.yaml", &err);
    assert_non_null(root);
    const char *text = NULL;
    assert_int_equal(mach_param_provenance(root, "a", &text),
                     MACH_PROV_ASSUMPTION);
    assert_string_equal(text, "z");
    assert_int_equal(mach_param_provenance(root, "b", &text),
                     MACH_PROV_CALIBRATED);
    assert_string_equal(text, "k");
    assert_int_equal(mach_param_provenance(root, "c", &text), MACH_PROV_SOURCE);
    assert_string_equal(text, "s");
    assert_int_equal(mach_param_provenance(root, "d", &text),
                     MACH_PROV_OVERRIDE);
    assert_null(text);
    assert_int_equal(mach_param_provenance(root, "f", NULL), MACH_PROV_SOURCE);
    assert_int_equal(mach_param_provenance(root, "zz", &text), MACH_PROV_NONE);
    assert_int_equal(mach_param_provenance(root, "e", &text), MACH_PROV_SOURCE);
    assert_true(cfg_set_override(root, "e.value=5 us", &err));
    text = "x";
    assert_int_equal(mach_param_provenance(root, "e", &text),
                     MACH_PROV_OVERRIDE);
    assert_null(text);
    /* a whole parameter set in one --set carries its own provenance */
    assert_true(cfg_set_override(root, "e={value: 6 us, source: u}", &err));
    assert_int_equal(mach_param_provenance(root, "e", &text), MACH_PROV_SOURCE);
    assert_string_equal(text, "u");
    /* a value merged over the model's from another file, whose name sorts
     * after ("q.yaml") or before ("o.yaml") the model's: an override */
    CfgNode *over = cfg_load_string("a: {value: 9 us}\n", "q.yaml", &err);
    cfg_merge(root, over);
    cfg_free(over);
    assert_int_equal(mach_param_provenance(root, "a", &text),
                     MACH_PROV_OVERRIDE);
    over = cfg_load_string("b: {value: 8 us}\n", "o.yaml", &err);
    cfg_merge(root, over);
    cfg_free(over);
    assert_int_equal(mach_param_provenance(root, "b", &text),
                     MACH_PROV_OVERRIDE);
    assert_string_equal(mach_provenance_name(MACH_PROV_NONE), "none");
    assert_string_equal(mach_provenance_name(MACH_PROV_ASSUMPTION),
                        "assumption");
    assert_string_equal(mach_provenance_name(MACH_PROV_OVERRIDE), "override");
    cfg_free(root);
}

/* A value of blanks only has no unit (and is not read before its start);
 * nor has a list item without one, wherever it stands. */
static void test_blank_value(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "schema_version: 1\nname: t\n"
        "nodes: {node: {count: {value: 2, source: s}}}\n"
        "network: {topology: {value: ring, source: s},\n"
        "          bandwidth: {value: '  ', source: s}}\n",
        "b.yaml", &err);
    assert_non_null(root);
    assert_false(mach_model_check(root, "b.yaml", &err));
    assert_string_equal(err->message,
                        "b.yaml:5:30: found '  ' without a unit, expected a "
                        "bandwidth with its unit, e.g. '2.8 MB/s'");
    g_clear_error(&err);
    cfg_free(root);
    /* each list item needs its unit, the first and the last */
    static const char *const lists[] = {"[4, 1 MB/s]", "[1 MB/s, 4]"};
    static const int cols[] = {37, 45};
    for (int i = 0; i < 2; i++) {
        char *text = g_strdup_printf(
            "schema_version: 1\nname: t\n"
            "nodes: {node: {count: {value: 2, source: s}}}\n"
            "network: {topology: {value: fat-tree, source: s},\n"
            "          level_bandwidth: {value: %s, source: s}}\n",
            lists[i]);
        root = cfg_load_string(text, "b.yaml", &err);
        g_free(text);
        assert_false(mach_model_check(root, "b.yaml", &err));
        char *want = g_strdup_printf(
            "b.yaml:5:%d: found '4' without a unit, expected a bandwidth "
            "with its unit, e.g. '2.8 MB/s'",
            cols[i]);
        assert_string_equal(err->message, want);
        g_free(want);
        g_clear_error(&err);
        cfg_free(root);
    }
}

/* A workload section's entries: {value, provenance}; a bare value only as
 * an override from another file (--set), not in the model's own file,
 * wherever the section stands in the document. */
static void test_workload_overrides(void **state)
{
    (void)state;
    GError *err = NULL;
    const char *body = "schema_version: 1\nname: t\n"
                       "nodes: {node: {count: {value: 2, source: s}}}\n"
                       "network: {topology: {value: ring, source: s},\n"
                       "          bandwidth: {value: 1 MB/s, source: s}}\n";
    char *text = g_strconcat("wl: {w: {value: 3, source: s}}\n", body, NULL);
    CfgNode *root = cfg_load_string(text, "t.yaml", &err);
    g_free(text);
    assert_true(cfg_set_override(root, "wl.w=5", &err));
    assert_true(mach_model_check(root, "t.yaml", &err));
    cfg_free(root);
    /* the same bare value written in the model itself, first in the file */
    text = g_strconcat("wl: {w: 5}\n", body, NULL);
    root = cfg_load_string(text, "t.yaml", &err);
    g_free(text);
    assert_false(mach_model_check(root, "t.yaml", &err));
    assert_string_equal(err->message,
                        "t.yaml:1:9: found workload parameter 'w' without a "
                        "value, expected {value: ..., unit: ..., "
                        "source|calibrated|assumption: ...}");
    g_clear_error(&err);
    cfg_free(root);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_models_check),
        cmocka_unit_test(test_workload_section_kept),
        cmocka_unit_test(test_unknown_model_name),
        cmocka_unit_test(test_bad_models_rejected),
        cmocka_unit_test(test_models_path_from_env),
        cmocka_unit_test(test_models_path_is_a_union),
        cmocka_unit_test(test_provenance_default),
        cmocka_unit_test(test_overrides_apply),
        cmocka_unit_test(test_bad_overrides_rejected),
        cmocka_unit_test(test_check_section_marks_read),
        cmocka_unit_test(test_provenance_kinds),
        cmocka_unit_test(test_blank_value),
        cmocka_unit_test(test_workload_overrides),
    };
    return cmocka_run_group_tests_name("machine_model", tests, NULL, NULL);
}
