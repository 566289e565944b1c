/* test_sweep_lock.c — nothing of a sweep is lost (issue 32): two
 * different sweeps cannot write to one output folder at once (the second
 * is refused, naming the folder; the same sweep twice shares the lock; a
 * lock left by an ended sweep is no obstacle), `pgsim sweep` takes the
 * lock, and a results log on a filling disk reports the system's reason,
 * not "Success" (a short write, then the error, as RLIMIT_FSIZE makes
 * them). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <errno.h>
#include <glib/gstdio.h>
#include <signal.h>
#include <sys/resource.h>

#include "sim/app/sweep/sweep_lock.h"
#include "sim/app/sweep/sweep_log.h"
#include "tests/app/cli/pgsim_spawn.h"
#include "tests/support.h"

#define FP_A "aaaaaaaaaaaaaaaa0000"
#define FP_B "bbbbbbbbbbbbbbbb0000"

static void test_other_sweep_refused(void **state)
{
    (void)state;
    char *top = g_dir_make_tmp("pgsim-lock-XXXXXX", NULL);
    char *dir = g_build_filename(top, "out", NULL);
    GError *err = NULL;
    SweepLock *a = sweep_lock_take(dir, FP_A, &err);
    g_assert_no_error(err);
    assert_null(sweep_lock_take(dir, FP_B, &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_IO));
    if (!strstr(err->message, "found another sweep writing there"))
        fail_msg("got: %s", err->message);
    assert_true(g_str_has_prefix(err->message, dir));
    g_clear_error(&err);
    /* the same sweep twice at once shares it */
    SweepLock *a2 = sweep_lock_take(dir, FP_A, &err);
    g_assert_no_error(err);
    sweep_lock_release(a);
    assert_null(sweep_lock_take(dir, FP_B, &err)); /* a2 still runs */
    g_clear_error(&err);
    sweep_lock_release(a2);
    /* A has ended: B runs, and A's lock file is gone */
    SweepLock *b = sweep_lock_take(dir, FP_B, &err);
    g_assert_no_error(err);
    char *a_file = g_build_filename(dir, ".sweep-aaaaaaaaaaaaaaaa.lock", NULL);
    assert_false(g_file_test(a_file, G_FILE_TEST_EXISTS));
    sweep_lock_release(b);
    g_free(a_file);
    g_free(dir);
    support_rm_tree(top);
    g_free(top);
}

/* `pgsim sweep --out DIR` while another sweep holds DIR: exit 2 and the
 * folder named; once it has ended, the sweep runs. */
static void test_cli_takes_the_lock(void **state)
{
    (void)state;
    char *top = g_dir_make_tmp("pgsim-lock-XXXXXX", NULL);
    char *sweep = test_ring_sweep(top, "4, 8");
    char *od = g_build_filename(top, "o", NULL);
    GError *e = NULL;
    SweepLock *other = sweep_lock_take(od, FP_B, &e);
    g_assert_no_error(e);
    const char *run[] = {"sweep", sweep, "-q", "-j", "1", "--out", od, NULL};
    char *out, *err;
    assert_int_equal(test_pgsim(run, &out, &err), 2);
    if (!strstr(err, "found another sweep writing there"))
        fail_msg("got: %s", err);
    g_free(out);
    g_free(err);
    char *csv = g_build_filename(od, "results.csv", NULL);
    assert_false(g_file_test(csv, G_FILE_TEST_EXISTS));
    sweep_lock_release(other);
    assert_int_equal(test_pgsim(run, &out, &err), 0);
    assert_true(g_file_test(csv, G_FILE_TEST_EXISTS));
    g_free(out);
    g_free(err);
    g_free(csv);
    g_free(od);
    g_free(sweep);
    support_rm_tree(top);
    g_free(top);
}

static void test_full_disk_reason(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("pgsim-lock-XXXXXX", NULL);
    GError *err = NULL;
    SweepSpec *s = sweep_spec_parse("base: {a: 1}\nparameters: {a: [1]}\n",
                                    "t.yaml", &err);
    g_assert_no_error(err);
    SweepLog *log = sweep_log_open(dir, s, FALSE, &err);
    g_assert_no_error(err);
    char line[200];
    memset(line, 'x', sizeof line - 1);
    line[sizeof line - 2] = '\n';
    line[sizeof line - 1] = '\0';
    struct rlimit old, lim;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &old), 0);
    lim = old;
    lim.rlim_cur = 100; /* the line fits half */
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
    errno = 0;
    gboolean ok = sweep_log_append(log, line, &err);
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, prev);
    assert_false(ok);
    if (!strstr(err->message, g_strerror(EFBIG)) ||
        strstr(err->message, "Success"))
        fail_msg("got: %s", err->message);
    g_clear_error(&err);
    sweep_log_close(log);
    sweep_spec_free(s);
    support_rm_tree(dir);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_other_sweep_refused),
        cmocka_unit_test(test_cli_takes_the_lock),
        cmocka_unit_test(test_full_disk_reason),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
