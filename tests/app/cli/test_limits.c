/* test_limits.c — sizes that would exhaust memory or mean nothing, given
 * on the command line (issue 32), through the pgsim binary.
 *
 * Each used to abort in an allocation, run for hours or exit 0: `bench
 * raster --grid=100000`, `--size 16384` or 2e9 `--frames` (the image
 * buffers and timings are estimated), `bench phold` with 4000M LPs or 4e9 pending
 * events per LP, `--remote=nan`, and `run --trace-cap` large enough to
 * exhaust memory (which also left FILE.tmp).  Now each exits 2 at once
 * with its message, under a 4 GiB limit, prints nothing on stdout and
 * writes no file. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <string.h>
#include <sys/wait.h>

static const char *pgsim_binary(void)
{
    return g_getenv("PGSIM_SANITIZE") ? "build-san/pgsim" : "build/pgsim";
}

typedef struct {
    const char *args, *want;
} Case;

static const Case cases[] = {
    {"bench raster --scene isosurface --grid=100000",
     "--grid: found grid 100000, expected 2 to 1024 cells"},
    {"bench phold --lps=4000M",
     "found 4000000000 LPs with 1 pending events each needing about"},
    {"bench phold --pending-per-lp=4000000000",
     "found 1024 LPs with 4000000000 pending events each needing about"},
    {"bench phold --lps=4000M --pending-per-lp=4000M",
     "expected at most 4.0 GiB"},
    {"bench phold --remote=nan", "--remote outside [0, 1]"},
    {"bench raster --size 16384 --zbuffer full --mem-limit 1G",
     "--size, --frames: found a 16384x16384 image and 20 frames needing "
     "about 4.0 GiB, expected at most 1.0 GiB"},
    {"bench raster --frames 2000000000",
     "found a 640x640 image and 2000000000 frames needing about"},
    {"run configs/tokenring.yaml --trace {} --trace-cap 2000000000",
     "--trace-cap: found a cap of 2000000000 events needing about"},
};

static void test_refused(void **s)
{
    (void)s;
    char *dir = g_dir_make_tmp("pgsim-limits-XXXXXX", NULL);
    char *trace = g_build_filename(dir, "t.json", NULL);
    char *tmp = g_strconcat(trace, ".tmp", NULL);
    char **env = g_environ_setenv(g_get_environ(), "PGSIM_MEM_LIMIT", "4G",
                                  TRUE);
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++) {
        char **argv = NULL;
        assert_true(g_shell_parse_argv(cases[i].args, NULL, &argv, NULL));
        GPtrArray *av = g_ptr_array_new();
        g_ptr_array_add(av, (char *)pgsim_binary());
        for (char **a = argv; *a; a++)
            g_ptr_array_add(av, strcmp(*a, "{}") ? *a : trace);
        g_ptr_array_add(av, NULL);
        char *out = NULL, *err = NULL;
        int wait = 0;
        assert_true(g_spawn_sync(NULL, (char **)av->pdata, env,
                                 G_SPAWN_DEFAULT, NULL, NULL, &out, &err,
                                 &wait, NULL));
        if (!WIFEXITED(wait) || WEXITSTATUS(wait) != 2 || *out ||
            !strstr(err, cases[i].want))
            fail_msg("%s: status %d, stdout '%.200s', stderr '%s'",
                     cases[i].args, wait, out, err);
        assert_false(g_file_test(trace, G_FILE_TEST_EXISTS));
        assert_false(g_file_test(tmp, G_FILE_TEST_EXISTS));
        g_free(out);
        g_free(err);
        g_ptr_array_free(av, TRUE);
        g_strfreev(argv);
    }
    g_strfreev(env);
    g_rmdir(dir);
    g_free(tmp);
    g_free(trace);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests_name("limits", tests, NULL, NULL);
}
