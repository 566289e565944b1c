/* test_reproduce_jobs.c — `pgsim reproduce A,B -j 2` prints what -j 1
 * prints, byte for byte, and writes the same report and charts (the
 * report's wall-time figures aside, which no two runs share).  Two fast
 * papers, listed so that the second finishes first under -j 2
 * (igehy98 takes about twice as long as ellsworth90): joining in
 * completion order instead of list order would fail this test.  Also: a
 * list naming a paper twice, or an unknown one, is refused with exit 2.
 * Runs the built binary, like test_cli. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>
#include <glib/gstdio.h>

#include "tests/app/cli/pgsim_spawn.h"

#define PAPERS "igehy98,ellsworth90"

/* The report with every "wall time N s" figure replaced by "wall time". */
static char *report_sans_wall(const char *path)
{
    char *md = NULL;
    assert_true(g_file_get_contents(path, &md, NULL, NULL));
    GRegex *re = g_regex_new("wall time [0-9.]+ s", 0, 0, NULL);
    char *out = g_regex_replace_literal(re, md, -1, 0, "wall time", 0, NULL);
    g_regex_unref(re);
    g_free(md);
    return out;
}

/* Runs the list with -j jobs into dir/r.md; returns stdout. */
static char *run_list(const char *dir, const char *jobs)
{
    char *doc = g_build_filename(dir, "r.md", NULL);
    const char *args[] = {"reproduce", PAPERS, "-q", "-j", jobs,
                          "--doc",     doc,    NULL};
    char *out, *err;
    int rc = test_pgsim(args, &out, &err);
    if (rc != 0)
        fail_msg("pgsim reproduce -j %s: exit %d: %s", jobs, rc, err);
    g_free(err);
    g_free(doc);
    return out;
}

static void assert_same_file(const char *a, const char *b)
{
    char *x = NULL, *y = NULL;
    gsize nx = 0, ny = 0;
    assert_true(g_file_get_contents(a, &x, &nx, NULL));
    assert_true(g_file_get_contents(b, &y, &ny, NULL));
    if (nx != ny || memcmp(x, y, nx) != 0)
        fail_msg("%s and %s differ", a, b);
    g_free(x);
    g_free(y);
}

/* Every chart file of one/reproduction/ equals the one of two/. */
static void assert_same_charts(const char *one, const char *two)
{
    char *d1 = g_build_filename(one, "reproduction", NULL);
    GDir *d = g_dir_open(d1, 0, NULL);
    assert_non_null(d);
    guint n = 0;
    for (const char *f; (f = g_dir_read_name(d)); n++) {
        char *a = g_build_filename(d1, f, NULL);
        char *b = g_build_filename(two, "reproduction", f, NULL);
        assert_same_file(a, b);
        g_free(a);
        g_free(b);
    }
    g_dir_close(d);
    assert_true(n >= 2); /* one chart per paper at least */
    g_free(d1);
}

static void test_jobs_output_equals_serial(void **state)
{
    (void)state;
    char *tmp = g_dir_make_tmp("pgsim-rpj-XXXXXX", NULL);
    char *one = g_build_filename(tmp, "j1", NULL);
    char *two = g_build_filename(tmp, "j2", NULL);
    char *o1 = run_list(one, "1"), *o2 = run_list(two, "2");
    assert_true(strlen(o1) > 0);
    assert_string_equal(o1, o2);
    /* list order, not registry order: igehy98 comes first */
    const char *ig = strstr(o1, "igehy98 ("), *el = strstr(o1, "ellsworth90 (");
    assert_true(ig == o1 && el > ig);
    char *r1p = g_build_filename(one, "r.md", NULL);
    char *r2p = g_build_filename(two, "r.md", NULL);
    char *r1 = report_sans_wall(r1p), *r2 = report_sans_wall(r2p);
    assert_string_equal(r1, r2);
    assert_same_charts(one, two);
    char *rm[] = {"rm", "-rf", tmp, NULL};
    g_spawn_sync(NULL, rm, NULL, G_SPAWN_SEARCH_PATH, NULL, NULL, NULL, NULL,
                 NULL, NULL);
    g_free(r1);
    g_free(r2);
    g_free(r1p);
    g_free(r2p);
    g_free(o1);
    g_free(o2);
    g_free(one);
    g_free(two);
    g_free(tmp);
}

static void test_bad_lists_refused(void **state)
{
    (void)state;
    const char *bad[][2] = {{"ellsworth90,ellsworth90", "twice"},
                            {"ellsworth90,nope", "'nope'"}};
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        const char *args[] = {"reproduce", bad[i][0], "-q", NULL};
        char *out, *err;
        assert_int_equal(test_pgsim(args, &out, &err), 2);
        assert_string_equal(out, "");
        assert_non_null(strstr(err, bad[i][1]));
        g_free(out);
        g_free(err);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_lists_refused),
        cmocka_unit_test(test_jobs_output_equals_serial),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
