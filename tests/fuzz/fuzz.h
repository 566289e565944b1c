/* fuzz.h — what every libFuzzer harness under tests/fuzz/ shares.
 *
 * Each fuzz_<name>.c defines LLVMFuzzerTestOneInput() for one input path
 * (config loader, machine model, OBJ, PLY, scene-to-image).  Built two
 * ways: with clang -fsanitize=fuzzer by `make fuzz` (scripts/fuzz.sh),
 * and with the normal compiler against replay.c, whose main() feeds
 * every file of tests/fuzz/corpus/<name>/ and tests/fuzz/crashes/<name>/
 * to the same function, so `make test` (and `make check`, under the
 * sanitizers) replays the corpora and every past crash input.
 *
 * A harness must never abort on any input: the code under test turns bad
 * input into a GError, which the harness frees.
 */
#ifndef PGSIM_TESTS_FUZZ_FUZZ_H
#define PGSIM_TESTS_FUZZ_FUZZ_H

#include "sim/core/memlimit.h"
#include <glib.h>
#include <glib/gstdio.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Limits that keep one input fast: 16 MiB of scene (about 32,000
 * polygons) and 1 MiB inputs; called at the start of every input. */
static inline void fuzz_setup(void)
{
    sim_mem_set_limit((guint64)16 << 20);
}

/* The input as a NUL-terminated string (g_free). */
static inline char *fuzz_text(const uint8_t *data, size_t size)
{
    return g_strndup((const char *)data, size);
}

/* The scratch file of fuzz_scratch() (one per harness). */
static inline char **fuzz_scratch_slot(void)
{
    static char *path;
    return &path;
}

static inline void fuzz_scratch_remove(void)
{
    char **path = fuzz_scratch_slot();
    char *dir = g_path_get_dirname(*path);
    g_remove(*path);
    g_rmdir(dir);
    g_free(dir);
    g_free(*path);
    *path = NULL;
}

/* A scratch file for readers that take a path: `name` in a temporary
 * folder made on first use from `tmpl` (g_dir_make_tmp), both removed
 * at exit.  Borrowed. */
static inline const char *fuzz_scratch(const char *tmpl, const char *name)
{
    char **path = fuzz_scratch_slot();
    if (!*path) {
        char *dir = g_dir_make_tmp(tmpl, NULL);
        *path = g_build_filename(dir, name, NULL);
        g_free(dir);
        atexit(fuzz_scratch_remove);
    }
    return *path;
}

#endif
