/* test_cli.c — what a new user meets first (issue 18): `pgsim help run`
 * lists every workload with the machine costs it needs and the metrics
 * it declares (issue 31), `pgsim help help`
 * succeeds, and `pgsim validate` checks sweep files as sweeps (every
 * point), so a sweep that validates runs, and one with a bad point does
 * not validate.  Runs the built binary, like test_scenarios. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>
#include <glib/gstdio.h>

#include "sim/output/json.h"
#include "sim/workload/workload.h"

#include "tests/app/cli/pgsim_spawn.h"

/* Each "KIND: op, op" line of `needs` is in the help text. */
static void assert_needs_listed(const char *out, const WlNeed *needs)
{
    for (const WlNeed *n = needs; n && n->kind; n++) {
        GString *line = g_string_new(NULL);
        g_string_printf(line, "%s:", n->kind);
        for (guint k = 0; n->ops[k]; k++)
            g_string_append_printf(line, "%s %s", k ? "," : "", n->ops[k]);
        g_string_append_c(line, '\n');
        if (!strstr(out, line->str))
            fail_msg("pgsim help run lacks the line '%s'", line->str);
        g_string_free(line, TRUE);
    }
}

/* Each declared metric is a line "NAME [UNIT] ... MEANING" of the help
 * after `out` (the workload's own heading: names recur across workloads). */
static void assert_metrics_listed(const char *out, const WlMetric *metrics)
{
    for (const WlMetric *m = metrics; m && m->name; m++) {
        char *head = *m->unit ? g_strdup_printf("\n        %s [%s] ",
                                                m->name, m->unit)
                              : g_strdup_printf("\n        %s ", m->name);
        const char *at = strstr(out, head);
        if (!at)
            fail_msg("pgsim help run does not list metric '%s'", m->name);
        const char *eol = strchr(at + 1, '\n');
        const char *meaning = strstr(at, m->meaning);
        assert_true(meaning && (!eol || meaning < eol));
        g_free(head);
    }
}

static void test_help_lists_workloads_and_costs(void **state)
{
    (void)state;
    const char *args[] = {"help", "run", NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(args, &out, &err), 0);
    for (guint i = 0; wl_all[i]; i++) {
        char *line = g_strdup_printf("\n  %-11s ", wl_all[i]->name);
        const char *at = strstr(out, line);
        if (!at)
            fail_msg("pgsim help run does not list workload '%s'",
                     wl_all[i]->name);
        g_free(line);
        assert_needs_listed(out, wl_all[i]->needs);
        assert_metrics_listed(at, wl_all[i]->metrics);
        for (const WlNeedAlt *a = wl_all[i]->needs_alt; a && a->when; a++) {
            assert_non_null(strstr(out, a->when));
            assert_needs_listed(out, a->needs);
        }
        /* "declares none" only for a workload that declares nothing */
        gboolean none = !wl_all[i]->needs && !wl_all[i]->needs_alt;
        char *head = g_strdup_printf("\n  %-11s %s\n      (declares none;",
                                     wl_all[i]->name, wl_all[i]->summary);
        assert_int_equal(strstr(out, head) != NULL, none);
        g_free(head);
    }
    g_free(out);
    g_free(err);
    const char *hh[] = {"help", "help", NULL};
    assert_int_equal(test_pgsim(hh, &out, &err), 0);
    assert_non_null(strstr(out, "pgsim help [COMMAND]"));
    g_free(out);
    g_free(err);
}

static void test_validate_sweeps(void **state)
{
    (void)state;
    const char *ok[] = {"validate", "configs/sweep-tokenring.yaml", NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(ok, &out, &err), 0);
    assert_non_null(strstr(out, "ok (sweep, "));
    g_free(out);
    g_free(err);
    /* one bad point among good ones: validate refuses it, located */
    char *dir = g_dir_make_tmp("pgsim-cli-XXXXXX", NULL);
    char *sweep = test_ring_sweep(dir, "4, 8, zero");
    const char *bad[] = {"validate", sweep, NULL};
    assert_int_equal(test_pgsim(bad, &out, &err), 2);
    assert_non_null(strstr(err, "point 2"));
    assert_non_null(strstr(err, "zero"));
    g_free(out);
    g_free(err);
    /* the same sweep without the bad value validates and runs */
    g_free(sweep);
    sweep = test_ring_sweep(dir, "4, 8");
    bad[1] = sweep;
    assert_int_equal(test_pgsim(bad, &out, &err), 0);
    g_free(out);
    g_free(err);
    char *od = g_build_filename(dir, "o", NULL);
    const char *run[] = {"sweep", sweep, "-q", "-j", "1", "--out", od, NULL};
    assert_int_equal(test_pgsim(run, &out, &err), 0);
    g_free(out);
    g_free(err);
    char *rm[] = {(char *)"rm", (char *)"-rf", dir, NULL};
    assert_true(g_spawn_sync(NULL, rm, NULL, G_SPAWN_SEARCH_PATH, NULL, NULL,
                             NULL, NULL, NULL, NULL));
    g_free(od);
    g_free(sweep);
    g_free(dir);
}

/* make run's quickstart: pixel merging on a 16-node iPSC/2 prints its
 * phase times, utilisation and communication, and writes the merged
 * frame, which matches the serial render. */
static void test_quickstart(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-qs-XXXXXX", NULL);
    const char *args[] = {"run", "configs/quickstart.yaml", "--out", dir,
                          NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(args, &out, &err), 0);
    const char *want[] = {"pixelmerge on ipsc2", "utilisation", "span_ms",
                          "zbuf_ms", "merge_ms", "communication",
                          "image_matches_serial         1", "node15"};
    for (guint i = 0; i < G_N_ELEMENTS(want); i++)
        if (!strstr(out, want[i]))
            fail_msg("quickstart report lacks '%s'", want[i]);
    assert_non_null(strstr(err, "frame.png"));
    char *png = g_build_filename(dir, "frame.png", NULL);
    char *data = NULL;
    gsize len = 0;
    assert_true(g_file_get_contents(png, &data, &len, NULL));
    assert_true(len > 1000 && memcmp(data, "\x89PNG", 4) == 0);
    /* width and height in the IHDR chunk: 400 x 400 */
    assert_int_equal(((guchar)data[18] << 8) | (guchar)data[19], 400);
    assert_int_equal(((guchar)data[22] << 8) | (guchar)data[23], 400);
    g_free(data);
    g_free(out);
    g_free(err);
    char *rm[] = {(char *)"rm", (char *)"-rf", dir, NULL};
    assert_true(g_spawn_sync(NULL, rm, NULL, G_SPAWN_SEARCH_PATH, NULL, NULL,
                             NULL, NULL, NULL, NULL));
    g_free(png);
    g_free(dir);
}

/* Quantities on the command line take units (issue 18): bench net's
 * flags and a --set value in micro-seconds with the micro sign. */
static void test_units_on_the_command_line(void **state)
{
    (void)state;
    const char *bench[] = {"bench",    "net",         "--nodes",   "4",
                           "--bytes",  "10KB",        "--bandwidth", "2.8MB/s",
                           "--startup", "350us",      "--fidelity", "analytic",
                           NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(bench, &out, &err), 0);
    assert_non_null(strstr(out, "10000 B"));
    assert_non_null(strstr(out, "2.8 MB/s"));
    assert_non_null(strstr(out, "start-up 350 us"));
    g_free(out);
    g_free(err);
    const char *bad[] = {"bench", "net", "--bytes", "10 furlongs", NULL};
    assert_int_equal(test_pgsim(bad, &out, &err), 2);
    assert_non_null(strstr(err, "--bytes: found '10 furlongs'"));
    g_free(out);
    g_free(err);
    const char *mu[] = {"run", "configs/tokenring.yaml", "-q", "--set",
                        "workload.compute=350 \xc2\xb5s", NULL};
    assert_int_equal(test_pgsim(mu, &out, &err), 0);
    g_free(out);
    g_free(err);
}

/* Removes dir/files[i] for i < n and dir; FALSE if any was missing or
 * dir is not empty then. */
static gboolean rm_files(char *dir, const char *const *files, int n)
{
    gboolean ok = TRUE;
    for (int i = 0; i < n; i++) {
        char *p = g_build_filename(dir, files[i], NULL);
        ok = g_remove(p) == 0 && ok;
        g_free(p);
    }
    ok = g_rmdir(dir) == 0 && ok;
    g_free(dir);
    return ok;
}

/* --out says when a workload drew no pixels instead of writing no image
 * silently (issue 18, point 9). */
static void test_out_without_pixels(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-out-XXXXXX", NULL);
    const char *args[] = {"run", "configs/tokenring.yaml", "--out", dir, NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(args, &out, &err), 0);
    assert_non_null(strstr(err, "; no frame image (this tokenring run drew "
                                "no pixels)"));
    g_free(out);
    g_free(err);
    const char *files[] = {"summary.txt", "result.json", "result.csv"};
    assert_true(rm_files(dir, files, 3)); /* nothing else was written */
}

static char *read_text(const char *dir, const char *name)
{
    char *path = g_build_filename(dir, name, NULL), *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    g_remove(path);
    g_free(path);
    return text;
}

/* plot --where keeps the matching rows (and says so in the title); labels come from the columns
 * with their units; a categorical x gets points, not joining lines. */
static void test_plot_where_and_labels(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-plot-XXXXXX", NULL);
    char *csv = g_build_filename(dir, "r.csv", NULL);
    char *png = g_build_filename(dir, "c.png", NULL);
    assert_true(g_file_set_contents(
        csv, "n,frame_s,scene\n1,2,a\n2,3,a\n1,5,b\n2,7.0,b\n", -1, NULL));
    const char *args[] = {"plot",  csv,       "--x", "n", "--y", "frame_s",
                          "--where", "scene=b", "-o", png, NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(args, &out, &err), 0);
    g_free(out);
    g_free(err);
    char *dat = read_text(dir, "c.dat"), *gp = read_text(dir, "c.gp");
    assert_non_null(strstr(dat, "\n1\t5\t5\t5\t"));
    assert_non_null(strstr(dat, "\n2\t7\t7\t7\t"));
    assert_null(strstr(dat, "\n1\t2\t"));
    assert_non_null(strstr(gp, "set title 'frame (s) against n (rows where scene=b)'"));
    assert_non_null(strstr(gp, "set ylabel 'frame (s)'"));
    g_free(dat);
    g_free(gp);
    const char *cat[] = {"plot", csv, "--x", "scene", "--y", "frame_s",
                         "--where", "n=2.0", "-o", png, NULL};
    assert_int_equal(test_pgsim(cat, &out, &err), 0);
    g_free(out);
    g_free(err);
    dat = read_text(dir, "c.dat");
    gp = read_text(dir, "c.gp");
    assert_non_null(strstr(gp, ":xtic(5) with points pointtype 7"));
    g_free(dat);
    g_free(gp);
    const char *bad[] = {"plot", csv, "--x", "n", "--y", "frame_s",
                         "--where", "colour=red", "-o", png, NULL};
    assert_int_equal(test_pgsim(bad, &out, &err), 2);
    assert_non_null(strstr(err, "r.csv:1:1: found no column 'colour' "
                                "(--where colour=red), expected"));
    g_free(out);
    g_free(err);
    const char *files[] = {"c.png", "c.svg", "r.csv"};
    assert_true(rm_files(dir, files, 3));
    g_free(png);
    g_free(csv);
}

/* result.json and result.csv say where they came from: the build, the
 * config file and its SHA-256, the overrides and the config they made,
 * the seed and the fidelity (issue 18, point 10). */
static void test_provenance(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-prov-XXXXXX", NULL);
    const char *args[] = {"run", "configs/tokenring.yaml", "-q", "--out", dir,
                          "--set", "workload.nodes=16", "--seed", "9", NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(args, &out, &err), 0);
    g_free(out);
    g_free(err);
    char *path = g_build_filename(dir, "result.json", NULL), *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    JsonNode *v = js_parse(text, -1, path, NULL);
    assert_non_null(v);
    JsonNode *p = js_get(v, "provenance");
    assert_non_null(p);
    assert_true(strlen(js_str(js_get(p, "pgsim_version"))) > 0);
    assert_string_equal(js_str(js_get(p, "config")), "configs/tokenring.yaml");
    char *bytes = NULL;
    gsize len = 0;
    assert_true(g_file_get_contents("configs/tokenring.yaml", &bytes, &len,
                                    NULL));
    char *sha = g_compute_checksum_for_data(G_CHECKSUM_SHA256,
                                            (const guchar *)bytes, len);
    assert_string_equal(js_str(js_get(p, "config_sha256")), sha);
    JsonNode *ov = js_get(p, "overrides");
    assert_int_equal(js_len(ov), 1);
    assert_string_equal(js_str(js_at(ov, 0)), "workload.nodes=16");
    JsonNode *eff = js_get(p, "effective_config");
    assert_string_equal(js_str(js_get(js_get(eff, "workload"), "nodes")),
                        "16");
    assert_int_equal((int)js_num(js_get(p, "seed")), 9);
    assert_string_equal(js_str(js_get(p, "fidelity")), "analytic");
    json_node_unref(v);
    g_free(text);
    g_free(path);
    path = g_build_filename(dir, "result.csv", NULL);
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    char *row = g_strdup_printf("provenance,,,config_sha256,%s,", sha);
    assert_non_null(strstr(text, row));
    assert_non_null(strstr(text, "provenance,0,,override,workload.nodes=16,"));
    g_free(row);
    g_free(text);
    g_free(path);
    g_free(sha);
    g_free(bytes);
    char *rm[] = {(char *)"rm", (char *)"-rf", dir, NULL};
    assert_true(g_spawn_sync(NULL, rm, NULL, G_SPAWN_SEARCH_PATH, NULL, NULL,
                             NULL, NULL, NULL, NULL));
    g_free(dir);
}

int main(void)
{
    g_setenv("LC_ALL", "C.UTF-8", TRUE); /* a UTF-8 terminal's locale */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_help_lists_workloads_and_costs),
        cmocka_unit_test(test_validate_sweeps),
        cmocka_unit_test(test_quickstart),
        cmocka_unit_test(test_units_on_the_command_line),
        cmocka_unit_test(test_provenance),
        cmocka_unit_test(test_plot_where_and_labels),
        cmocka_unit_test(test_out_without_pixels),
    };
    return cmocka_run_group_tests_name("cli", tests, NULL, NULL);
}
