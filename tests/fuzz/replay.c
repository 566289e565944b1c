/* replay.c — main() for the regression build of a fuzz harness (fuzz.h).
 *
 * `replay_<name> [PATH...]` feeds every file under each PATH (a file or
 * a directory, read in sorted order) to LLVMFuzzerTestOneInput(); with
 * no PATH it replays tests/fuzz/corpus/<name>/ and tests/fuzz/crashes/
 * <name>/ (<name> from its own program name).  A harness that aborts or
 * trips a sanitizer fails the run; an empty corpus fails too, so a
 * corpus that went missing cannot pass unnoticed.  O(total input size).
 */
#include "tests/fuzz/fuzz.h"
#include <stdio.h>
#include <string.h>

static gint cmp_names(gconstpointer a, gconstpointer b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Replays one file or every file of a directory; returns the count. */
static guint replay_path(const char *path)
{
    char *data = NULL;
    gsize len = 0;
    if (!g_file_test(path, G_FILE_TEST_IS_DIR)) {
        if (!g_file_get_contents(path, &data, &len, NULL))
            return 0;
        LLVMFuzzerTestOneInput((const uint8_t *)data, len);
        g_free(data);
        return 1;
    }
    GDir *dir = g_dir_open(path, 0, NULL);
    GPtrArray *names = g_ptr_array_new_with_free_func(g_free);
    const char *f;
    while (dir && (f = g_dir_read_name(dir)))
        if (f[0] != '.')
            g_ptr_array_add(names, g_build_filename(path, f, NULL));
    if (dir)
        g_dir_close(dir);
    g_ptr_array_sort(names, cmp_names);
    guint n = 0;
    for (guint i = 0; i < names->len; i++)
        n += replay_path(g_ptr_array_index(names, i));
    g_ptr_array_free(names, TRUE);
    return n;
}

int main(int argc, char **argv)
{
    char *base = g_path_get_basename(argv[0]);
    const char *name = g_str_has_prefix(base, "replay_") ? base + 7 : base;
    guint n = 0;
    if (argc > 1) {
        for (int i = 1; i < argc; i++)
            n += replay_path(argv[i]);
    } else {
        char *corpus = g_build_filename("tests/fuzz/corpus", name, NULL);
        char *crashes = g_build_filename("tests/fuzz/crashes", name, NULL);
        n = replay_path(corpus) + replay_path(crashes);
        g_free(corpus);
        g_free(crashes);
    }
    printf("fuzz replay %s: %u inputs\n", name, n);
    g_free(base);
    return n > 0 ? 0 : 1;
}
