/* pgsim_spawn.c — run the built pgsim from a test (pgsim_spawn.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib.h>
#include <string.h>
#include <sys/wait.h>

#include "tests/app/cli/pgsim_spawn.h"

const char *test_pgsim_bin(void)
{
    return g_getenv("PGSIM_SANITIZE") ? "build-san/pgsim" : "build/pgsim";
}

int test_pgsim(const char *const *args, char **out, char **err)
{
    GPtrArray *argv = g_ptr_array_new();
    g_ptr_array_add(argv, (gpointer)test_pgsim_bin());
    for (guint i = 0; args[i]; i++)
        g_ptr_array_add(argv, (gpointer)args[i]);
    g_ptr_array_add(argv, NULL);
    int status = 0;
    assert_true(g_spawn_sync(NULL, (char **)argv->pdata, NULL,
                             G_SPAWN_DEFAULT, NULL, NULL, out, err, &status,
                             NULL));
    g_ptr_array_free(argv, TRUE);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

char *test_ring_sweep(const char *dir, const char *values)
{
    char *base = g_build_filename(dir, "ring.yaml", NULL);
    char *sweep = g_build_filename(dir, "s.yaml", NULL);
    char *text = g_strdup_printf("name: s\nbase: ring.yaml\nparameters:\n"
                                 "  workload.nodes: {values: [%s]}\n",
                                 values);
    assert_true(g_file_set_contents(
        base,
        "schema_version: 1\nworkload: {type: tokenring, nodes: 4, token: 1 "
        "KB, compute: 20 us, jitter: 0, link: {latency: 5 us, bandwidth: "
        "20 MB/s}}\nrun: {frames: 2}\n",
        -1, NULL));
    assert_true(g_file_set_contents(sweep, text, -1, NULL));
    g_free(text);
    g_free(base);
    return sweep;
}

char *test_doc_between(const char *path, const char *begin, const char *end)
{
    char *doc = NULL;
    assert_true(g_file_get_contents(path, &doc, NULL, NULL));
    const char *b = strstr(doc, begin);
    assert_non_null(b);
    b += strlen(begin);
    const char *e = strstr(b, end);
    assert_non_null(e);
    char *t = g_strndup(b, (gsize)(e - b));
    g_free(doc);
    return t;
}
