/* test_sweep_mpi.c — a sweep spread over 2 Open MPI ranks gives the same
 * rows as the local pool.  The binary is its own MPI program: started by
 * mpirun it runs the sweep into argv[1]; started plainly it is the cmocka
 * suite, which runs the local sweep and then itself under
 * `mpirun -np 2`.  Skipped when MPI support or mpirun is missing. */
#include "sim/app/sweep/sweep_mpi.h"
#include "tests/app/sweep/sweep_fake.h"
#include <glib/gstdio.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static const char yaml[] = "base: {run: {seed: 5}, a: 0, b: 0}\n"
                           "parameters:\n"
                           "  a: [1, 2, 3, 4, 6]\n"
                           "  b: {from: 0, to: 2, step: 1}\n"
                           "repetitions: 2\n";
static const char *self;

static SweepSpec *spec(void)
{
    SweepSpec *s = sweep_spec_parse(yaml, "/tmp/mpi.yaml", NULL);
    g_assert(s);
    return s;
}

/* Not inlined: GCC 12's -Wdangling-pointer, inlining it, took the
 * buffer returned through &csv for the local csv itself. */
static G_GNUC_NO_INLINE char *results(const char *dir)
{
    char *path = g_build_filename(dir, "results.csv", NULL), *csv = NULL;
    g_file_get_contents(path, &csv, NULL, NULL);
    g_free(path);
    return csv;
}

static void local_sweep(const char *dir)
{
    SweepSpec *s = spec();
    SweepLog *log = sweep_log_open(dir, s, FALSE, NULL);
    SweepJob j;
    sweep_job_init(&j, s, log, sweep_fake_run, FALSE);
    assert_true(sweep_run_local(&j, 2, NULL));
    sweep_job_clear(&j);
    sweep_log_close(log);
    assert_true(sweep_log_finish(dir, s, NULL, NULL));
    sweep_spec_free(s);
}

static int mpi_main(int argc, char **argv)
{
    int rank, size;
    sweep_mpi_init(&argc, &argv, &rank, &size);
    SweepSpec *s = spec();
    if (rank > 0) {
        sweep_mpi_worker(s, sweep_fake_run);
    } else {
        SweepLog *log = sweep_log_open(argv[1], s, FALSE, NULL);
        SweepJob j;
        sweep_job_init(&j, s, log, sweep_fake_run, FALSE);
        sweep_mpi_master(&j, size, NULL);
        sweep_job_clear(&j);
        sweep_log_close(log);
    }
    sweep_mpi_finalize();
    if (rank == 0)
        sweep_log_finish(argv[1], s, NULL, NULL);
    sweep_spec_free(s);
    return 0;
}

static char *mpirun_path(void)
{
#ifdef PGSIM_HAVE_MPI
    return g_find_program_in_path("mpirun");
#else
    return NULL;
#endif
}

/* Runs argv (NULL-terminated) under `timeout 120`; fails the test on a
 * non-zero exit. */
static void run_ok(char **argv)
{
    int status = -1;
    char *out = NULL, *errs = NULL;
    GError *err = NULL;
    /* Open MPI's own allocations are not ours to report under ASan */
    char **env = g_environ_setenv(g_get_environ(), "ASAN_OPTIONS",
                                  "detect_leaks=0", TRUE);
    assert_true(g_spawn_sync(NULL, argv, env, G_SPAWN_SEARCH_PATH, NULL, NULL,
                             &out, &errs, &status, &err));
    g_strfreev(env);
    if (!g_spawn_check_wait_status(status, NULL))
        fail_msg("%s failed: %s%s", argv[2], out, errs);
    g_free(out);
    g_free(errs);
}

static void test_mpi_equals_local(void **state)
{
    (void)state;
    char *mpirun = mpirun_path();
    if (!mpirun)
        skip();
    char *dl = g_dir_make_tmp("pgsim-mpi-XXXXXX", NULL);
    char *dm = g_dir_make_tmp("pgsim-mpi-XXXXXX", NULL);
    local_sweep(dl);
    char *argv[] = {"timeout",
                    "120",
                    mpirun,
                    "--allow-run-as-root",
                    "--oversubscribe",
                    "-np",
                    "2",
                    (char *)self,
                    dm,
                    NULL};
    run_ok(argv);
    char *a = results(dl), *b = results(dm);
    assert_non_null(a);
    assert_non_null(b);
    assert_string_equal(a, b);
    assert_non_null(strstr(a, ",error,a is 4,"));
    g_free(a);
    g_free(b);
    g_free(mpirun);
    sweep_test_rm_out(dl);
    sweep_test_rm_out(dm);
}

/* The pgsim binary of this test's build: BUILD/pgsim, found by climbing
 * from BUILD/tests/app/sweep/ (so a deeper or shallower test folder does
 * not silently turn the test into a skip). */
static char *pgsim_path(void)
{
    char *dir = g_path_get_dirname(self);
    for (int up = 0; up < 6; up++) {
        char *p = g_build_filename(dir, "pgsim", NULL);
        if (g_file_test(p, G_FILE_TEST_IS_EXECUTABLE) &&
            !g_file_test(p, G_FILE_TEST_IS_DIR)) {
            g_free(dir);
            return p;
        }
        g_free(p);
        char *parent = g_path_get_dirname(dir);
        g_free(dir);
        dir = parent;
    }
    g_free(dir);
    return NULL;
}

static void rm_charts(const char *dir)
{
    const char *stems[] = {"frame-vs-nodes", "events-vs-nodes"};
    const char *ext[] = {".png", ".svg", ".gp", ".dat"};
    for (int s = 0; s < 2; s++)
        for (int e = 0; e < 4; e++) {
            char *f = g_strconcat(dir, "/", stems[s], ext[e], NULL);
            g_remove(f);
            g_free(f);
        }
}

/* `pgsim sweep` of the example sweep: under mpirun -np 2 = with -j 2. */
static void test_cli_mpi_equals_local(void **state)
{
    (void)state;
    char *mpirun = mpirun_path(), *pgsim = pgsim_path();
    if (!mpirun || !pgsim) {
        g_free(mpirun);
        g_free(pgsim);
        skip();
    }
    char *dl = g_dir_make_tmp("pgsim-mpi-XXXXXX", NULL);
    char *dm = g_dir_make_tmp("pgsim-mpi-XXXXXX", NULL);
    char *local[] = {"timeout", "120", pgsim, "sweep",
                     "-q",      "-j",  "2",   "configs/sweep-tokenring.yaml",
                     "--out",   dl,    NULL};
    char *mpi[] = {"timeout",
                   "120",
                   mpirun,
                   "--allow-run-as-root",
                   "--oversubscribe",
                   "-np",
                   "2",
                   pgsim,
                   "sweep",
                   "-q",
                   "configs/sweep-tokenring.yaml",
                   "--out",
                   dm,
                   NULL};
    run_ok(local);
    run_ok(mpi);
    char *a = results(dl), *b = results(dm);
    assert_non_null(a);
    assert_string_equal(a, b);
    assert_true(g_str_has_prefix(a, "# pgsim_version: "));
    assert_true(g_str_has_prefix(strstr(a, "\npoint,") + 1, "point,repetition,seed,workload.nodes,"
                                    "workload.link.bandwidth,status,"));
    g_free(a);
    g_free(b);
    rm_charts(dl);
    rm_charts(dm);
    sweep_test_rm_out(dl);
    sweep_test_rm_out(dm);
    g_free(mpirun);
    g_free(pgsim);
}

int main(int argc, char **argv)
{
    if (sweep_mpi_launched())
        return mpi_main(argc, argv);
    self = argv[0];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mpi_equals_local),
        cmocka_unit_test(test_cli_mpi_equals_local),
    };
    return cmocka_run_group_tests_name("sweep_mpi", tests, NULL, NULL);
}
