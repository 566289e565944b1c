/* inputs.c — the input files of a run (inputs.h).
 *
 * A collector is an array of SimInput; the open collectors of a thread
 * form a stack linked through `outer` (C11 _Thread_local: reproductions
 * in worker processes and tests on threads each have their own).
 */
#include "sim/core/inputs.h"
#include "sim/core/datapath.h"
#include <stdlib.h>
#include <string.h>

struct SimInputs {
    GPtrArray *items; /* SimInput * */
    SimInputs *outer; /* the collector open below this one, while open */
};

static _Thread_local SimInputs *innermost;

static void input_free(gpointer p)
{
    SimInput *e = p;
    g_free(e->kind);
    g_free(e->path);
    g_free(e->sha256);
    g_free(e);
}

SimInputs *sim_inputs_new(void)
{
    SimInputs *in = g_new0(SimInputs, 1);
    in->items = g_ptr_array_new_with_free_func(input_free);
    return in;
}

void sim_inputs_free(SimInputs *in)
{
    if (!in)
        return;
    g_assert(innermost != in);
    g_ptr_array_free(in->items, TRUE);
    g_free(in);
}

guint sim_inputs_len(const SimInputs *in)
{
    return in ? in->items->len : 0;
}

const SimInput *sim_inputs_at(const SimInputs *in, guint i)
{
    g_assert(i < sim_inputs_len(in));
    return g_ptr_array_index(in->items, i);
}

void sim_inputs_add(SimInputs *in, const char *kind, const char *path,
                    const char *sha256, gboolean shipped)
{
    for (guint i = 0; i < in->items->len; i++) {
        const SimInput *e = g_ptr_array_index(in->items, i);
        if (strcmp(e->kind, kind) == 0 && strcmp(e->path, path) == 0)
            return;
    }
    SimInput *e = g_new0(SimInput, 1);
    e->kind = g_strdup(kind);
    e->path = g_strdup(path);
    e->sha256 = g_strdup(sha256);
    e->shipped = shipped;
    g_ptr_array_add(in->items, e);
}

void sim_inputs_merge(SimInputs *dst, const SimInputs *src)
{
    for (guint i = 0; i < sim_inputs_len(src); i++) {
        const SimInput *e = sim_inputs_at(src, i);
        sim_inputs_add(dst, e->kind, e->path, e->sha256, e->shipped);
    }
}

void sim_inputs_push(SimInputs *in)
{
    g_assert(in && !in->outer && in != innermost);
    in->outer = innermost;
    innermost = in;
}

void sim_inputs_pop(SimInputs *in)
{
    g_assert(in && innermost == in);
    innermost = in->outer;
    in->outer = NULL;
}

/* dir/models as a canonical path (g_free). */
static char *models_under(const char *root)
{
    char *m = g_build_filename(root, "models", NULL);
    char *c = g_canonicalize_filename(m, NULL);
    g_free(m);
    return c;
}

gboolean sim_inputs_model_shipped(const char *path)
{
    char *dir = g_path_get_dirname(path);
    gboolean shipped = sim_inputs_dir_shipped(dir);
    g_free(dir);
    return shipped;
}

gboolean sim_inputs_dir_shipped(const char *dir)
{
    char *abs = g_canonicalize_filename(dir, NULL);
    char *real = realpath(abs, NULL);
    GPtrArray *roots = sim_data_roots();
    gboolean shipped = FALSE;
    for (guint i = 0; !shipped && i < roots->len; i++) {
        char *m = models_under(roots->pdata[i]);
        char *rm = realpath(m, NULL);
        shipped = strcmp(m, abs) == 0 || (rm && real && strcmp(rm, real) == 0);
        free(rm);
        g_free(m);
    }
    g_ptr_array_free(roots, TRUE);
    free(real);
    g_free(abs);
    return shipped;
}

/* The name a file is recorded under (g_free): relative to the data root
 * that holds it ("models/ipsc2.yaml", whichever checkout or install it
 * came from), else its absolute real path. */
static char *record_name(const char *path)
{
    char *real = realpath(path, NULL);
    if (!real)
        return g_strdup(path);
    GPtrArray *roots = sim_data_roots();
    char *name = NULL;
    for (guint i = 0; !name && i < roots->len; i++) {
        char *root = realpath(roots->pdata[i], NULL);
        size_t n = root ? strlen(root) : 0;
        if (root && strncmp(real, root, n) == 0 && real[n] == '/')
            name = g_strdup(real + n + 1);
        free(root);
    }
    g_ptr_array_free(roots, TRUE);
    if (!name)
        name = g_strdup(real);
    free(real);
    return name;
}

void sim_inputs_note_bytes(const char *kind, const char *path,
                           const void *bytes, gsize len)
{
    if (!innermost)
        return;
    char *sha = g_compute_checksum_for_data(G_CHECKSUM_SHA256, bytes, len);
    gboolean shipped =
        strcmp(kind, "model") != 0 || sim_inputs_model_shipped(path);
    char *name = record_name(path);
    for (SimInputs *in = innermost; in; in = in->outer)
        sim_inputs_add(in, kind, name, sha, shipped);
    g_free(name);
    g_free(sha);
}

void sim_inputs_note_file(const char *kind, const char *path)
{
    if (!innermost)
        return;
    char *found = sim_data_path(path); /* as cfg_load_file() finds it */
    GMappedFile *f = g_mapped_file_new(found, FALSE, NULL);
    if (f) {
        sim_inputs_note_bytes(kind, found, g_mapped_file_get_contents(f),
                              g_mapped_file_get_length(f));
        g_mapped_file_unref(f);
    }
    g_free(found);
}
