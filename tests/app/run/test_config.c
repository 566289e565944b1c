/* test_config.c — run configs: every error class has a malformed file in
 * tests/data/bad/ with its exact located message; the pgsim binary exits 2
 * on each; overrides; determinism of the quickstart's JSON and CSV. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>
#include <sys/wait.h>
#include <glib/gstdio.h>

#include "sim/run/run.h"
#include "sim/app/run/report.h"

typedef struct {
    const char *file; /* under tests/data/bad/ */
    const char *msg;  /* after "tests/data/bad/<file>:" */
} BadCase;

static const BadCase bad[] = {
    {"unknown_key.yaml", "6:3: found unknown key 'sede', expected one of: "
                         "seed, frames, fidelity, until"},
    {"unknown_top_key.yaml", "4:1: found unknown key 'runn', expected one "
                             "of: schema_version, run, workload, machine, "
                             "scene"},
    {"wrong_type.yaml", "4:10: found a sequence, expected a non-negative "
                        "integer, optionally with K (1e3) or M (1e6)"},
    {"bad_unit.yaml", "4:12: found '20 furlongs', expected a non-negative "
                      "time with a unit (ps, ns, us, \xc2\xb5s, ms, s, min, h)"},
    {"missing_unit.yaml", "5:14: found '5', expected a non-negative time "
                          "with a unit (ps, ns, us, \xc2\xb5s, ms, s, min, h)"},
    {"negative.yaml", "4:10: found '-1 KB', expected a non-negative size "
                      "with a unit (B, kB, KB, MB, GB, TB, KiB, MiB, GiB, TiB)"},
    {"overflow.yaml", "5:10: found '1e9 s', expected a time below 2^64 ps "
                      "(about 213 days)"},
    {"out_of_range.yaml", "4:11: found '1.5', expected a number in [0, 1]"},
    {"bad_enum.yaml", "5:13: found 'exact', expected one of: faithful, analytic, "
                      "flow, packet"},
    {"missing_required.yaml", "3:3: found no key 'type' in this map, "
                              "expected 'type': a string"},
    {"missing_workload.yaml", "1:1: found no key 'workload', expected "
                              "workload: {type: <name>, ...}"},
    {"unknown_workload.yaml", "3:9: found workload 'tokenrng', expected "
                              "one of: "},
    {"bad_schema_version.yaml", "1:17: found '2', expected 1 (the only "
                                "schema version)"},
    {"missing_schema_version.yaml", "1:1: found no key 'schema_version', "
                                    "expected schema_version: 1 at the "
                                    "top"},
    {"not_a_map.yaml", "1:1: found a sequence, expected a map starting "
                       "with schema_version: 1"},
    {"duplicate_key.yaml", "5:3: found duplicate key 'nodes' (first at "
                           "line 4), expected each key once per map"},
    {"yaml_syntax.yaml", "5:4: found YAML syntax error"},
    {"missing_model.yaml", "3:3: found no model 'no-such-machine', "
                           "expected models/no-such-machine.yaml"},
    {"dpscan_bad_mode.yaml", "4:9: found 'shaded', expected one of: flat, "
                             "gouraud, wireframe, hidden_line, contour, "
                             "points, lines"},
    {"dpscan_bad_wire.yaml", "4:9: found 'cable', expected one of: "
                             "network, formula"},
    {"dpscan_bad_palette.yaml", "4:12: found 2 colours, expected 15 "
                                "colours, each [r, g, b] in 0..1 or "
                                "\"#rrggbb\""},
    {"pixelmerge_radices_product.yaml", "6:12: found radices of product 16, "
                                        "expected radices whose product is "
                                        "the 12 processors"},
    {"pixelmerge_radices_scheme.yaml", "5:12: found 'radices' with scheme "
                                       "'binary_swap', expected scheme "
                                       "radix_k for radices"},
    {"pixelmerge_bad_operator.yaml", "5:13: found 'under', expected one "
                                     "of: z, over"},
};

static char *bad_path(const BadCase *c)
{
    return g_strconcat("tests/data/bad/", c->file, NULL);
}

static void test_bad_files(void **state)
{
    (void)state;
    for (size_t i = 0; i < G_N_ELEMENTS(bad); i++) {
        char *path = bad_path(&bad[i]);
        char *want = g_strdup_printf("%s:%s", path, bad[i].msg);
        GError *e = NULL;
        CfgRun *r = cfg_run_load(path, NULL, &e);
        if (r || !e)
            fail_msg("%s: accepted", path);
        assert_int_equal(sim_error_exit_status(e), 2);
        if (strncmp(e->message, want, strlen(want)) != 0)
            fail_msg("%s:\n got  %s\n want %s", path, e->message, want);
        g_error_free(e);
        g_free(want);
        g_free(path);
    }
}

static const char *pgsim_binary(void)
{
    return g_getenv("PGSIM_SANITIZE") ? "build-san/pgsim" : "build/pgsim";
}

/* Runs pgsim with args; returns the exit status, stderr in *err_out. */
static int run_pgsim(const char *const *args, char **out, char **err_out)
{
    GPtrArray *argv = g_ptr_array_new();
    g_ptr_array_add(argv, (gpointer)pgsim_binary());
    for (int i = 0; args[i]; i++)
        g_ptr_array_add(argv, (gpointer)args[i]);
    g_ptr_array_add(argv, NULL);
    int wait = 0;
    GError *e = NULL;
    if (!g_spawn_sync(NULL, (char **)argv->pdata, NULL, G_SPAWN_DEFAULT, NULL,
                      NULL, out, err_out, &wait, &e))
        fail_msg("cannot run %s: %s", pgsim_binary(), e->message);
    g_ptr_array_free(argv, TRUE);
    return WIFEXITED(wait) ? WEXITSTATUS(wait) : -1;
}

static void test_binary_exit_status(void **state)
{
    (void)state;
    if (!g_file_test(pgsim_binary(), G_FILE_TEST_IS_EXECUTABLE))
        fail_msg("%s not built (make builds it before the tests)",
                 pgsim_binary());
    for (size_t i = 0; i < G_N_ELEMENTS(bad); i++) {
        char *path = bad_path(&bad[i]);
        char *want = g_strdup_printf("pgsim: %s:%s", path, bad[i].msg);
        char *out = NULL, *err = NULL;
        const char *args[] = {"run", path, NULL};
        assert_int_equal(run_pgsim(args, &out, &err), 2);
        assert_string_equal(out, "");
        if (strncmp(err, want, strlen(want)) != 0)
            fail_msg("stderr: %s\nwant: %s", err, want);
        g_free(out);
        g_free(err);
        g_free(want);
        g_free(path);
    }
}

static void test_cli_errors(void **state)
{
    (void)state;
    char *out, *err;
    const char *seed[] = {"run", "configs/tokenring.yaml", "--seed", "x",
                          NULL};
    assert_int_equal(run_pgsim(seed, &out, &err), 2);
    assert_string_equal(err, "pgsim run: --seed: found 'x', expected a "
                             "non-negative integer\n");
    g_free(out);
    g_free(err);
    const char *fmt[] = {"run", "configs/tokenring.yaml", "--format=xml",
                         NULL};
    assert_int_equal(run_pgsim(fmt, &out, &err), 2);
    assert_non_null(strstr(err, "--format: found 'xml', expected one of"));
    g_free(out);
    g_free(err);
    const char *unk[] = {"run", "--bogus", "configs/tokenring.yaml", NULL};
    assert_int_equal(run_pgsim(unk, &out, &err), 2);
    assert_non_null(strstr(err, "found unknown option '--bogus'"));
    g_free(out);
    g_free(err);
    const char *none[] = {"run", NULL};
    assert_int_equal(run_pgsim(none, &out, &err), 2);
    g_free(out);
    g_free(err);
    const char *missing[] = {"validate", "tests/data/no-such.yaml", NULL};
    assert_int_equal(run_pgsim(missing, &out, &err), 2);
    assert_non_null(strstr(err, "tests/data/no-such.yaml:0:0: found an "
                                "unreadable file"));
    g_free(out);
    g_free(err);
    const char *ok[] = {"validate", "configs/tokenring.yaml", NULL};
    assert_int_equal(run_pgsim(ok, &out, &err), 0);
    assert_string_equal(out, "configs/tokenring.yaml: ok\n");
    g_free(out);
    g_free(err);
    const char *help[] = {"help", "run", NULL};
    assert_int_equal(run_pgsim(help, &out, &err), 0);
    assert_non_null(strstr(out, "--seed"));
    g_free(out);
    g_free(err);
}

static void test_overrides(void **state)
{
    (void)state;
    GError *e = NULL;
    const char *const ov[] = {"run.seed=9", "workload.nodes=3", "run.frames=2",
                              NULL};
    CfgRun *r = cfg_run_load("configs/tokenring.yaml", ov, &e);
    assert_non_null(r);
    assert_int_equal(r->seed, 9);
    assert_int_equal(r->frames, 2);
    SimResult *res = cfg_run_exec(r, NULL, &e);
    assert_non_null(res);
    assert_int_equal(res->nodes->len, 3);
    assert_int_equal(res->frame_times->len, 2);
    sim_result_free(res);
    cfg_run_free(r);
    const char *const typo[] = {"run.sede=9", NULL};
    assert_null(cfg_run_load("configs/tokenring.yaml", typo, &e));
    assert_string_equal(e->message, "--set run.sede=9:1:1: found unknown "
                                    "key 'sede', expected one of: seed, "
                                    "frames, fidelity, until");
    g_clear_error(&e);
    const char *const bad_val[] = {"workload.jitter=2", NULL};
    assert_null(cfg_run_load("configs/tokenring.yaml", bad_val, &e));
    assert_string_equal(e->message, "--set workload.jitter=2:1:1: found "
                                    "'2', expected a number in [0, 1]");
    g_clear_error(&e);
}

/* --set machine.* on a config without a machine section (issue 18,
 * point 7): a model makes a machine; other keys alone are refused at the
 * --set; a workload that builds its own machine refuses one. */
static void test_machine_from_set(void **state)
{
    (void)state;
    GError *e = NULL;
    const char *pm = "schema_version: 1\n"
                     "workload: {type: pixelmerge, processors: 4}\n"
                     "scene: {generator: teapots, teapots: 1}\n";
    const char *const model[] = {"machine.model=ipsc2", NULL};
    CfgRun *r = cfg_run_from_tree(cfg_load_string(pm, "pm.yaml", NULL), model,
                                  &e);
    g_assert_no_error(e);
    assert_string_equal(cfg_scalar(cfg_get(r->machine, "model")), "ipsc2");
    cfg_run_free(r);
    const char *const keys[] = {"machine.nodes=4", NULL};
    assert_null(
        cfg_run_from_tree(cfg_load_string(pm, "pm.yaml", NULL), keys, &e));
    assert_true(g_str_has_prefix(e->message,
                                 "--set machine.nodes=4:1:1: found a machine "
                                 "made by --set alone, with no model"));
    g_clear_error(&e);
    /* a machine the workload does not read: the runner refuses it at
     * load, where --set made it */
    assert_null(cfg_run_load("configs/tokenring.yaml", model, &e));
    assert_string_equal(e->message,
                        "--set machine.model=ipsc2:1:1: found a machine: "
                        "section, expected none: workload tokenring does not "
                        "read it with these settings ('pgsim help run')");
    g_clear_error(&e);
}

/* Renders the quickstart's result in format f with the given seed. */
static char *quickstart(RptFormat f, const char *seed)
{
    GError *e = NULL;
    const char *const ov[] = {seed, NULL};
    CfgRun *r = cfg_run_load("configs/tokenring.yaml", ov, &e);
    assert_non_null(r);
    SimResult *res = cfg_run_exec(r, NULL, &e);
    assert_non_null(res);
    char *s = rpt_render(res, f, FALSE);
    sim_result_free(res);
    cfg_run_free(r);
    return s;
}

static void test_determinism(void **state)
{
    (void)state;
    for (int f = RPT_JSON; f <= RPT_CSV; f++) {
        char *a = quickstart((RptFormat)f, "run.seed=5");
        char *b = quickstart((RptFormat)f, "run.seed=5");
        char *c = quickstart((RptFormat)f, "run.seed=6");
        assert_string_equal(a, b);
        assert_string_not_equal(a, c); /* the seed matters (jitter) */
        g_free(a);
        g_free(b);
        g_free(c);
    }
}

static char *slurp(const char *dir, const char *name)
{
    char *path = g_build_filename(dir, name, NULL), *text = NULL;
    if (!g_file_get_contents(path, &text, NULL, NULL))
        fail_msg("%s missing", path);
    g_free(path);
    return text;
}

static void rm_dir(char *dir)
{
    const char *names[] = {"summary.txt", "result.json", "result.csv"};
    for (int i = 0; i < 3; i++) {
        char *p = g_build_filename(dir, names[i], NULL);
        g_remove(p);
        g_free(p);
    }
    g_rmdir(dir);
    g_free(dir);
}

/* Two runs of the binary write byte-identical JSON and CSV files. */
static void test_binary_determinism(void **state)
{
    (void)state;
    char *d[2];
    for (int i = 0; i < 2; i++) {
        d[i] = g_dir_make_tmp("pgsim-det-XXXXXX", NULL);
        char *out, *err;
        const char *args[] = {
            "run", "configs/tokenring.yaml", "--quiet", "--out", d[i], NULL};
        assert_int_equal(run_pgsim(args, &out, &err), 0);
        assert_non_null(strstr(out, "tokenring on ring-8"));
        g_free(out);
        g_free(err);
    }
    const char *names[] = {"result.json", "result.csv", "summary.txt"};
    for (int i = 0; i < 3; i++) {
        char *a = slurp(d[0], names[i]), *b = slurp(d[1], names[i]);
        assert_true(strlen(a) > 100);
        assert_string_equal(a, b);
        g_free(a);
        g_free(b);
    }
    rm_dir(d[0]);
    rm_dir(d[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_files),
        cmocka_unit_test(test_binary_exit_status),
        cmocka_unit_test(test_cli_errors),
        cmocka_unit_test(test_overrides),
        cmocka_unit_test(test_machine_from_set),
        cmocka_unit_test(test_determinism),
        cmocka_unit_test(test_binary_determinism),
    };
    return cmocka_run_group_tests_name("config", tests, NULL, NULL);
}
