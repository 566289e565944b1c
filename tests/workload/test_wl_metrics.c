/* test_wl_metrics.c — declared metrics (sim/workload/metrics.h): every
 * workload declares a well-formed table; every metric name a workload's
 * sources set literally is declared (the branches a run may not reach);
 * the runner's check refuses an undeclared name or a different unit; a
 * read by a misspelt name aborts instead of giving NaN. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sim/core/error.h"
#include "sim/workload/metrics.h"

static void test_tables(void **st)
{
    (void)st;
    for (guint i = 0; wl_all[i]; i++) {
        const WlOps *w = wl_all[i];
        guint n = 0;
        assert_non_null(w->metrics);
        for (const WlMetric *m = w->metrics; m->name; m++, n++) {
            assert_non_null(m->unit);
            assert_true(m->meaning && *m->meaning);
            assert_true(*m->name);
            assert_ptr_equal(wl_metric_decl(w, m->name), m); /* no twin */
        }
        assert_true(n >= 3);
    }
}

/* Literal names set in `text` (sim_result_set_metric(r, "x", ...) or a
 * workload's set(out, "x", ...) shorthand) that w does not declare,
 * appended to `bad`; returns how many literal sets it saw. */
static guint scan_sets(const WlOps *w, const char *text, GString *bad)
{
    GRegex *re = g_regex_new("(?:sim_result_set_metric|\\bset)\\(\\s*\\w+,"
                             "\\s*\"([a-z0-9_]+)\"",
                             0, 0, NULL);
    GMatchInfo *mi = NULL;
    guint seen = 0;
    g_regex_match(re, text, 0, &mi);
    for (; g_match_info_matches(mi); g_match_info_next(mi, NULL), seen++) {
        char *name = g_match_info_fetch(mi, 1);
        if (!wl_metric_decl(w, name))
            g_string_append_printf(bad, " %s:%s", w->name, name);
        g_free(name);
    }
    g_match_info_free(mi);
    g_regex_unref(re);
    return seen;
}

static void test_sources_declared(void **st)
{
    (void)st;
    GString *bad = g_string_new(NULL);
    for (guint i = 0; wl_all[i]; i++) {
        char *dir = g_build_filename("sim/workload", wl_all[i]->name, NULL);
        GDir *d = g_dir_open(dir, 0, NULL);
        assert_non_null(d);
        guint seen = 0;
        for (const char *f; (f = g_dir_read_name(d));) {
            if (!g_str_has_suffix(f, ".c"))
                continue;
            char *path = g_build_filename(dir, f, NULL), *text = NULL;
            assert_true(g_file_get_contents(path, &text, NULL, NULL));
            seen += scan_sets(wl_all[i], text, bad);
            g_free(text);
            g_free(path);
        }
        g_dir_close(d);
        g_free(dir);
        assert_true(seen >= 3); /* the scan found the workload's sets */
    }
    if (bad->len)
        fail_msg("set but not declared:%s", bad->str);
    /* the scan can come out false */
    const WlOps *tr = wl_find("tokenring");
    assert_int_equal(scan_sets(tr, "set(out, \"hops\", 1, \"\");\n"
                                   "sim_result_set_metric(r, \"hopz\", 2, \"\");",
                               bad),
                     2);
    assert_string_equal(bad->str, " tokenring:hopz");
    g_string_free(bad, TRUE);
}

static void test_check(void **st)
{
    (void)st;
    const WlOps *tr = wl_find("tokenring");
    SimResult *r = sim_result_new("tokenring", "");
    GError *e = NULL;
    sim_result_set_metric(r, "hops", 4, "");
    sim_result_set_metric(r, "hop_time_mean", 1e-6, "s");
    assert_true(wl_check_metrics(tr, r, &e));
    /* an undeclared name */
    sim_result_set_metric(r, "hopz", 4, "");
    assert_false(wl_check_metrics(tr, r, &e));
    assert_true(g_error_matches(e, SIM_ERROR, SIM_ERROR_INTERNAL));
    assert_non_null(strstr(e->message, "workload 'tokenring': found metric "
                                       "'hopz' (unit ''), expected one it "
                                       "declares"));
    g_clear_error(&e);
    sim_result_free(r);
    /* a declared name with another unit */
    r = sim_result_new("tokenring", "");
    sim_result_set_metric(r, "hop_time_mean", 1e-3, "ms");
    assert_false(wl_check_metrics(tr, r, &e));
    assert_non_null(strstr(e->message, "expected its declared unit 's'"));
    g_clear_error(&e);
    sim_result_free(r);
}

static void test_read(void **st)
{
    (void)st;
    SimResult *r = sim_result_new("pixelmerge", "ipsc2");
    sim_result_set_metric(r, "span_ms", 2.5, "ms");
    double v = 0;
    assert_true(wl_metric(r, "span_ms") == 2.5);
    assert_true(isnan(wl_metric(r, "zbuf_ms"))); /* declared, not set */
    assert_true(wl_get_metric(r, "span_ms", &v) && v == 2.5);
    assert_false(wl_get_metric(r, "zbuf_ms", &v));
    sim_result_free(r);
}

/* Runs wl_metric(r, name) in a child; TRUE when the child died of it. */
static gboolean read_aborts(const char *workload, const char *name)
{
    SimResult *r = sim_result_new(workload, "");
    sim_result_set_metric(r, name, 1, "");
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        FILE *null = freopen("/dev/null", "w", stderr);
        (void)null;
        (void)wl_metric(r, name);
        _exit(0);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    sim_result_free(r);
    return WIFSIGNALED(status);
}

static void test_misspelt_read_aborts(void **st)
{
    (void)st;
    assert_true(read_aborts("pixelmerge", "span_msx"));
    assert_true(read_aborts("sortfirst", "chunk_overlaps"));
    assert_true(read_aborts("nosuch", "span_ms"));
    assert_false(read_aborts("pixelmerge", "span_ms"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tables),
        cmocka_unit_test(test_sources_declared),
        cmocka_unit_test(test_check),
        cmocka_unit_test(test_read),
        cmocka_unit_test(test_misspelt_read_aborts),
    };
    return cmocka_run_group_tests_name("wl_metrics", tests, NULL, NULL);
}
