/* test_hostile.c — hostile traces and map files through the pgsim binary
 * (issue 32).
 *
 * Each trace under tests/data/bad/replay/ (.pgt, or a SimGrid .txt)
 * starts with "# expect: <message>" and optionally "# args: <command>"
 * ({} is the file; default "replay {} --machine ipsc2").  Each used to
 * crash, abort on an allocation, or exit 0 with a meaningless result;
 * now pgsim exits 2 with that located message and prints nothing on
 * stdout, under a 4 GiB memory limit.  Generated cases: a FIFO (refused
 * before it is opened), small gzip traces whose replies never come
 * (bounded by the memory limit), a header of 100,000 kinds (the kind
 * lookup is O(log kinds): it replays), and one of 10^9 processors
 * (nothing per processor; the estimate knows `ulimit -v`). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <gio/gio.h>
#include <glib/gstdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>

static const char *pgsim_binary(void)
{
    return g_getenv("PGSIM_SANITIZE") ? "build-san/pgsim" : "build/pgsim";
}

/* Runs `pgsim ARGS` ({} replaced by file) with PGSIM_MEM_LIMIT=limit;
 * exit status, stdout, stderr (g_free). */
static int run_pgsim(const char *args, const char *file, const char *limit,
                     char **out, char **err)
{
    char **argv = NULL;
    assert_true(g_shell_parse_argv(args, NULL, &argv, NULL));
    GPtrArray *av = g_ptr_array_new();
    g_ptr_array_add(av, (char *)pgsim_binary());
    for (char **a = argv; *a; a++)
        g_ptr_array_add(av, strcmp(*a, "{}") ? *a : (char *)file);
    g_ptr_array_add(av, NULL);
    char **env = g_environ_setenv(g_get_environ(), "PGSIM_MEM_LIMIT", limit,
                                  TRUE);
    int wait = 0;
    GError *e = NULL;
    if (!g_spawn_sync(NULL, (char **)av->pdata, env, G_SPAWN_DEFAULT, NULL,
                      NULL, out, err, &wait, &e))
        fail_msg("spawn: %s", e->message);
    g_ptr_array_free(av, TRUE);
    g_strfreev(argv);
    g_strfreev(env);
    return WIFEXITED(wait) ? WEXITSTATUS(wait) : 128 + WTERMSIG(wait);
}

/* Exit 2, nothing on stdout, `want` on stderr; else prints why. */
static gboolean refused(const char *args, const char *file, const char *limit,
                        const char *want)
{
    char *out = NULL, *err = NULL;
    int rc = run_pgsim(args, file, limit, &out, &err);
    gboolean ok = rc == 2 && !*out && strstr(err, want);
    if (!ok)
        print_error("%s on %s: exit %d, stdout '%.200s', stderr '%.300s', "
                    "expected exit 2 and '%s'\n",
                    args, file, rc, out, err, want);
    g_free(out);
    g_free(err);
    return ok;
}

static void expect_refused(const char *args, const char *file,
                           const char *limit, const char *want)
{
    if (!refused(args, file, limit, want))
        fail();
}

/* "# KEY: value" on one of the first lines of text, or NULL. */
static char *header_value(const char *text, const char *key)
{
    char *tag = g_strdup_printf("# %s: ", key);
    const char *p = strstr(text, tag);
    char *v = p ? g_strndup(p + strlen(tag), strcspn(p + strlen(tag), "\n"))
                : NULL;
    g_free(tag);
    return v;
}

static void test_bad_files(void **s)
{
    (void)s;
    const char *root = "tests/data/bad/replay";
    GDir *dir = g_dir_open(root, 0, NULL);
    assert_non_null(dir);
    const char *f;
    guint n = 0, bad = 0;
    while ((f = g_dir_read_name(dir))) {
        if (!g_str_has_suffix(f, ".pgt") && !g_str_has_suffix(f, ".txt"))
            continue; /* map files, used by the traces' args */
        char *path = g_build_filename(root, f, NULL), *text = NULL;
        assert_true(g_file_get_contents(path, &text, NULL, NULL));
        char *want = header_value(text, "expect");
        char *args = header_value(text, "args");
        if (!want)
            fail_msg("%s: no '# expect:' line", path);
        bad += !refused(args ? args : "replay {} --machine ipsc2", path,
                        "4G", want);
        g_free(want);
        g_free(args);
        g_free(text);
        g_free(path);
        n++;
    }
    g_dir_close(dir);
    if (bad)
        fail_msg("%u of %u hostile files not refused", bad, n);
    assert_true(n >= 20);
}

static char *tmp_dir;

static char *tmp_path(const char *name)
{
    return g_build_filename(tmp_dir, name, NULL);
}

/* A FIFO is refused at once (opening it would wait for a writer). */
static void test_fifo(void **s)
{
    (void)s;
    char *p = tmp_path("fifo.pgt");
    assert_int_equal(mkfifo(p, 0600), 0);
    expect_refused("replay {} --machine ipsc2", p, "4G",
                   "fifo.pgt:0:0: found a pipe, expected a regular file");
    char *map = tmp_path("fifo.map");
    assert_int_equal(mkfifo(map, 0600), 0);
    char *args = g_strdup_printf("replay {} --machine ipsc2 --map %s", map);
    expect_refused(args, "tests/data/traces/simgrid-4ranks.txt", "4G",
                   "fifo.map:0:0: found a pipe");
    g_remove(p);
    g_remove(map);
    g_free(args);
    g_free(map);
    g_free(p);
}

/* Writes head, then `line` n times, gzip-compressed, to tmp/name. */
static char *gz_trace(const char *name, const char *head, const char *line,
                      guint n)
{
    char *p = tmp_path(name);
    GFile *f = g_file_new_for_path(p);
    GOutputStream *raw = G_OUTPUT_STREAM(
        g_file_replace(f, NULL, FALSE, G_FILE_CREATE_NONE, NULL, NULL));
    GZlibCompressor *z = g_zlib_compressor_new(G_ZLIB_COMPRESSOR_FORMAT_GZIP, 9);
    GOutputStream *out = g_converter_output_stream_new(raw, G_CONVERTER(z));
    assert_true(g_output_stream_write_all(out, head, strlen(head), NULL, NULL,
                                          NULL));
    for (guint i = 0; i < n; i++)
        assert_true(g_output_stream_write_all(out, line, strlen(line), NULL,
                                              NULL, NULL));
    assert_true(g_output_stream_close(out, NULL, NULL));
    g_object_unref(out);
    g_object_unref(z);
    g_object_unref(raw);
    g_object_unref(f);
    return p;
}

/* Small compressed traces whose replies never come: a million actions
 * marked '+' with no 'on' group, and a SimGrid receive whose send never
 * comes while the other rank's actions pile up behind it.  Under a
 * 32 MiB limit both stop with a located error part way through. */
static void test_replies_never_come(void **s)
{
    (void)s;
    char *p = gz_trace("await.pgt.gz", "pgsim-trace 1\nmachine ipsc2\n"
                                       "procs 2\nat 0\n",
                       "w 0 0 1 +\n", 1000000);
    expect_refused("replay {} --machine ipsc2", p, "32M",
                   "actions marked '+' whose 'on' groups have not come "
                   "needing about");
    g_remove(p);
    g_free(p);
    p = gz_trace("ahead.txt.gz", "0 recv 1 100\n", "0 compute 1\n", 1000000);
    expect_refused("replay {} --machine ipsc2 --set "
                   "machine.nodes.node.costs.flop=1ns",
                   p, "32M", "actions read ahead of ranks that wait");
    g_remove(p);
    g_free(p);
}

/* 100,000 kind lines (one processor each) replay: the lookup of a
 * processor's kind no longer scans every kind. */
static void test_many_kinds(void **s)
{
    (void)s;
    const guint n = 100000;
    GString *t = g_string_new("pgsim-trace 1\nmachine ipsc2\n");
    g_string_append_printf(t, "procs %u\n", n);
    for (guint i = 0; i < n; i++)
        g_string_append_printf(t, "kind k%u %u 1 16000000\n", n - 1 - i,
                               n - 1 - i);
    g_string_append(t, "at 0\n");
    for (guint i = 0; i < n; i++)
        g_string_append_printf(t, "w %u 0 100\n", i);
    char *p = tmp_path("kinds.pgt");
    assert_true(g_file_set_contents(p, t->str, (gssize)t->len, NULL));
    g_string_free(t, TRUE);
    char *out = NULL, *err = NULL;
    int rc = run_pgsim("replay {} --machine ipsc2 --format csv", p, "4G", &out,
                       &err);
    if (rc != 0)
        fail_msg("exit %d: %s", rc, err);
    assert_non_null(strstr(out, "metric,actions,,value,100000,"));
    g_free(out);
    g_free(err);
    g_remove(p);
    g_free(p);
}

/* Sets the child's address-space limit (g_spawn child setup). */
static void limit_as(gpointer bytes)
{
    struct rlimit rl = {GPOINTER_TO_SIZE(bytes), GPOINTER_TO_SIZE(bytes)};
    setrlimit(RLIMIT_AS, &rl);
}

/* A header announcing 10^9 processors: with a block map nothing is kept
 * per trace processor, so it replays in little memory; under a 3 GiB
 * address-space limit (ulimit -v) and no --mem-limit, the estimate
 * knows the limit and refuses it at the `procs` line instead of failing
 * to allocate. */
static void test_huge_procs(void **s)
{
    (void)s;
    char *p = tmp_path("procs.pgt");
    assert_true(g_file_set_contents(p, "pgsim-trace 1\nmachine ipsc2\n"
                                       "procs 1000000000\nat 0\n"
                                       "w 999999999 0 5\n",
                                    -1, NULL));
    char *out = NULL, *err = NULL;
    int rc = run_pgsim("replay {} --machine ipsc2 --format csv", p, "64G", &out,
                       &err);
    if (rc != 0 || !strstr(out, "metric,actions,,value,1,"))
        fail_msg("exit %d: %s", rc, err);
    g_free(out);
    g_free(err);
    if (g_getenv("PGSIM_SANITIZE")) { /* ASan reserves terabytes */
        g_remove(p);
        g_free(p);
        return;
    }
    const char *argv[] = {pgsim_binary(), "replay", p, "--machine", "ipsc2",
                          NULL};
    char **env = g_environ_unsetenv(g_get_environ(), "PGSIM_MEM_LIMIT");
    int wait = 0;
    assert_true(g_spawn_sync(NULL, (char **)argv, env, G_SPAWN_DEFAULT,
                             limit_as, GSIZE_TO_POINTER((gsize)3 << 30), &out,
                             &err, &wait, NULL));
    if (!WIFEXITED(wait) || WEXITSTATUS(wait) != 2 || *out ||
        !strstr(err, "procs.pgt:3:7: found procs 1000000000 needing about "
                     "14.9 GiB, expected at most 3.0 GiB"))
        fail_msg("exit %d: '%s'", wait, err);
    g_strfreev(env);
    g_free(out);
    g_free(err);
    g_remove(p);
    g_free(p);
}

int main(void)
{
    tmp_dir = g_dir_make_tmp("pgsim-hostile-XXXXXX", NULL);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_files),
        cmocka_unit_test(test_fifo),
        cmocka_unit_test(test_replies_never_come),
        cmocka_unit_test(test_many_kinds),
        cmocka_unit_test(test_huge_procs),
    };
    int rc = cmocka_run_group_tests_name("hostile", tests, NULL, NULL);
    g_rmdir(tmp_dir);
    g_free(tmp_dir);
    return rc;
}
