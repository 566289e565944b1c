/* test_hostile_db.c — hostile structure database files through the
 * pgsim binary (issue 32): `validate` and `run` of the sort-first and
 * PPHIGS workloads with `--set workload.database=FILE`.
 *
 * Each file under tests/data/bad/structdb/ ("# expect: <message>" on
 * its first line) used to crash, abort or exit 0 with a meaningless
 * result (matrices and vertices of 1e300, products of matrices beyond
 * any coordinate, nothing posted, no primitive: a NaN metric).  Two are
 * generated: an execute chain 100,000 deep (the traversals recursed
 * once per level and overflowed the stack) and 40 levels each executing
 * the next twice (2^40 instances: hours and terabytes).  Now each is a
 * located error, exit 2, nothing on stdout, under a 4 GiB limit. */
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

/* `pgsim CMD CONFIG --set workload.database=db` exits 2 with `want`
 * (and nothing on stdout); else prints why and returns FALSE. */
static gboolean refused(const char *cmd, const char *config, const char *db,
                        const char *want)
{
    char *set = g_strconcat("workload.database=", db, NULL);
    const char *argv[] = {pgsim_binary(), cmd, config, "--set", set,
                          "--set", "run.frames=1", NULL};
    char **env = g_environ_setenv(g_get_environ(), "PGSIM_MEM_LIMIT", "4G",
                                  TRUE);
    char *out = NULL, *err = NULL;
    int wait = 0;
    gboolean ok = g_spawn_sync(NULL, (char **)argv, env, G_SPAWN_DEFAULT, NULL,
                               NULL, &out, &err, &wait, NULL) &&
                  WIFEXITED(wait) && WEXITSTATUS(wait) == 2 && !*out &&
                  strstr(err, want);
    if (!ok)
        print_error("%s %s on %s: status %d, stderr '%.300s', expected exit 2 "
                    "and '%s'\n",
                    cmd, config, db, wait, err ? err : "", want);
    g_strfreev(env);
    g_free(out);
    g_free(err);
    g_free(set);
    return ok;
}

/* validate on both workloads, run on sort-first. */
static guint failures(const char *db, const char *want)
{
    return !refused("validate", "configs/sortfirst-vehicle.yaml", db, want) +
           !refused("validate", "configs/pphigs-flock.yaml", db, want) +
           !refused("run", "configs/sortfirst-vehicle.yaml", db, want);
}

static void test_bad_files(void **s)
{
    (void)s;
    const char *root = "tests/data/bad/structdb";
    GDir *dir = g_dir_open(root, 0, NULL);
    assert_non_null(dir);
    const char *f;
    guint n = 0, bad = 0;
    while ((f = g_dir_read_name(dir))) {
        char *path = g_build_filename(root, f, NULL), *text = NULL;
        assert_true(g_file_get_contents(path, &text, NULL, NULL));
        char *nl = strchr(text, '\n');
        assert_true(g_str_has_prefix(text, "# expect: ") && nl);
        *nl = 0;
        gboolean sf_only = g_str_has_prefix(f, "no"); /* nothing to render */
        if (sf_only) /* PPHIGS renders an empty network, refuses none posted */
            bad += !refused("run", "configs/sortfirst-vehicle.yaml", path,
                            text + 10);
        else
            bad += failures(path, text + 10);
        g_free(text);
        g_free(path);
        n++;
    }
    g_dir_close(dir);
    if (bad)
        fail_msg("%u refusals missing over %u files", bad, n);
    assert_true(n >= 5);
}

/* Writes a database of n structures, structure i executing i + 1 `fan`
 * times, the last one holding a triangle; s0 posted. */
static char *chain(const char *dir, const char *name, guint n, guint fan)
{
    GString *t = g_string_new("structure_database: 1\nstructures:\n");
    for (guint i = 0; i + 1 < n; i++) {
        g_string_append_printf(t, "  - {name: s%u, elements: [", i);
        for (guint k = 0; k < fan; k++)
            g_string_append_printf(t, "%s{execute: s%u}", k ? ", " : "",
                                   i + 1);
        g_string_append(t, "]}\n");
    }
    g_string_append_printf(t, "  - {name: s%u, elements: [{triangle: [[0, 0, "
                              "0], [1, 0, 0], [0, 1, 0]]}]}\nposted: [s0]\n",
                           n - 1);
    char *p = g_build_filename(dir, name, NULL);
    assert_true(g_file_set_contents(p, t->str, (gssize)t->len, NULL));
    g_string_free(t, TRUE);
    return p;
}

static void test_deep_and_shared(void **s)
{
    (void)s;
    char *dir = g_dir_make_tmp("pgsim-hostile-db-XXXXXX", NULL);
    char *deep = chain(dir, "deep.yaml", 100000, 1);
    char *wide = chain(dir, "shared.yaml", 40, 2);
    guint bad = failures(deep, "deep.yaml:100002:5: found structure "
                               "'s99999' 100000 levels down an execute "
                               "chain, expected at most 256 levels") +
                failures(wide, "shared.yaml:43:9: found a network of "
                               "1.1e+12 structure instances and 1.65e+12 "
                               "element instances (executes expanded) "
                               "needing about");
    g_remove(deep);
    g_remove(wide);
    g_rmdir(dir);
    g_free(deep);
    g_free(wide);
    g_free(dir);
    if (bad)
        fail_msg("%u refusals missing", bad);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_files),
        cmocka_unit_test(test_deep_and_shared),
    };
    return cmocka_run_group_tests_name("hostile_db", tests, NULL, NULL);
}
