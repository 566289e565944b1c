/* sorts_spec.c — reads and checks a one-scene-three-sorts comparison
 * file (sorts.h): its processor counts, shared sections and each sort's
 * workload, processor keys and the metrics it reads; located errors. */
#include "sim/app/sorts/sorts.h"
#include "sim/core/error.h"
#include "sim/output/plot.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SORTS_MAX_PROCS 65536

static void sort_free(gpointer p)
{
    SortsSort *s = p;
    if (!s)
        return;
    g_free(s->sort);
    g_ptr_array_unref(s->keys);
    g_array_unref(s->shares);
    g_free(s->overlap);
    g_free(s->bytes);
    g_free(s->frame);
    g_ptr_array_unref(s->balance);
    g_array_unref(s->bshares);
    g_free(s);
}

void sorts_spec_free(SortsSpec *s)
{
    if (!s)
        return;
    cfg_free(s->root);
    g_free(s->name);
    if (s->procs)
        g_array_unref(s->procs);
    if (s->sorts)
        g_ptr_array_unref(s->sorts);
    g_free(s);
}

/* A positive integer scalar at n, at most max. */
static gboolean read_count(const CfgNode *n, guint max, guint *out,
                           GError **err)
{
    const char *t = cfg_kind(n) == CFG_SCALAR ? cfg_scalar(n) : NULL;
    char *end = NULL;
    guint64 v = t && g_ascii_isdigit(*t) ? g_ascii_strtoull(t, &end, 10) : 0;
    if (!t || !end || *end || v < 1 || v > max) {
        char *d = cfg_describe(n);
        char *want = g_strdup_printf("a processor count 1 .. %u", max);
        cfg_error(err, n, d, want);
        g_free(want);
        g_free(d);
        return FALSE;
    }
    *out = (guint)v;
    return TRUE;
}

static gboolean read_procs(SortsSpec *s, GError **err)
{
    const CfgNode *seq = cfg_get(s->root, "processors");
    if (!seq || cfg_kind(seq) != CFG_SEQ || cfg_seq_len(seq) == 0) {
        char *d = seq ? cfg_describe(seq) : g_strdup("no 'processors'");
        cfg_error(err, seq ? seq : s->root, d,
                  "processors: a list of processor counts, e.g. [2, 4, 8]");
        g_free(d);
        return FALSE;
    }
    s->procs = g_array_new(FALSE, FALSE, sizeof(guint));
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        guint p;
        if (!read_count(cfg_seq_at(seq, i), SORTS_MAX_PROCS, &p, err))
            return FALSE;
        g_array_append_val(s->procs, p);
    }
    return TRUE;
}

/* KEY: {NAME: SHARE, ...}: names with their shares of P (at least one). */
static gboolean read_shares(const CfgNode *map, const char *key,
                            const char *what, GPtrArray *names,
                            GArray *shares, GError **err)
{
    const CfgNode *m;
    if (!cfg_get_map(map, key, TRUE, what, &m, err))
        return FALSE;
    if (cfg_map_len(m) == 0) {
        cfg_error(err, m, "an empty map", what);
        return FALSE;
    }
    for (guint i = 0; i < cfg_map_len(m); i++) {
        const char *k = cfg_map_key(m, i);
        double share;
        if (!cfg_get_double(m, k, TRUE, 1e-9, 64, &share, err))
            return FALSE;
        g_ptr_array_add(names, g_strdup(k));
        g_array_append_val(shares, share);
    }
    return TRUE;
}

static gboolean read_metric(const CfgNode *map, const char *key,
                            const char *def, char **out, GError **err)
{
    const char *v = def;
    if (!cfg_get_str(map, key, def == NULL, &v, err))
        return FALSE;
    *out = g_strdup(v);
    return TRUE;
}

static SortsSort *read_sort(const CfgNode *map, GError **err)
{
    SortsSort *o = g_new0(SortsSort, 1);
    o->keys = g_ptr_array_new_with_free_func(g_free);
    o->shares = g_array_new(FALSE, FALSE, sizeof(double));
    o->balance = g_ptr_array_new_with_free_func(g_free);
    o->bshares = g_array_new(FALSE, FALSE, sizeof(double));
    const char *name;
    static const char *const modes[] = {"section", "database", NULL};
    int m = 0;
    gboolean ok =
        cfg_get_str(map, "sort", TRUE, &name, err) &&
        cfg_get_map(map, "workload", TRUE, "a workload section {type, ...}",
                    &o->workload, err) &&
        cfg_get_enum(map, "scene", FALSE, modes, &m, err) &&
        read_shares(map, "processors",
                    "a map {KEY: share of P}, e.g. {workload.processors: 1}",
                    o->keys, o->shares, err) &&
        read_metric(map, "overlap", NULL, &o->overlap, err) &&
        read_metric(map, "bytes", NULL, &o->bytes, err) &&
        read_metric(map, "frame", "frame_ms", &o->frame, err) &&
        read_shares(map, "balance",
                    "a map {KIND: share of P}, the node kinds doing the "
                    "work, e.g. {node: 1}",
                    o->balance, o->bshares, err);
    if (!ok) {
        sort_free(o);
        return NULL;
    }
    o->sort = g_strdup(name);
    o->scene_as_db = m == 1;
    cfg_mark_read(o->workload);
    return o;
}

static gboolean read_sorts(SortsSpec *s, GError **err)
{
    const CfgNode *seq = cfg_get(s->root, "sorts");
    if (!seq || cfg_kind(seq) != CFG_SEQ || cfg_seq_len(seq) == 0) {
        char *d = seq ? cfg_describe(seq) : g_strdup("no 'sorts'");
        cfg_error(err, seq ? seq : s->root, d,
                  "sorts: a list of {sort, workload, processors, overlap, "
                  "bytes, balance}");
        g_free(d);
        return FALSE;
    }
    s->sorts = g_ptr_array_new_with_free_func(sort_free);
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        const CfgNode *n = cfg_seq_at(seq, i);
        if (cfg_kind(n) != CFG_MAP) {
            char *d = cfg_describe(n);
            cfg_error(err, n, d, "a map {sort, workload, processors, ...}");
            g_free(d);
            return FALSE;
        }
        SortsSort *o = read_sort(n, err);
        if (!o)
            return FALSE;
        for (guint j = 0; j < s->sorts->len; j++)
            if (!strcmp(((SortsSort *)s->sorts->pdata[j])->sort, o->sort)) {
                char *d = g_strdup_printf("a second sort named '%s'", o->sort);
                cfg_error(err, cfg_get(n, "sort"), d, "distinct sort names");
                g_free(d);
                sort_free(o);
                return FALSE;
            }
        g_ptr_array_add(s->sorts, o);
    }
    return TRUE;
}

/* An optional map section, taken whole (the runner checks its keys). */
static gboolean read_section(SortsSpec *s, const char *key,
                             const CfgNode **out, GError **err)
{
    *out = NULL;
    if (!cfg_has(s->root, key))
        return TRUE;
    if (!cfg_get_map(s->root, key, FALSE, "a map section", out, err))
        return FALSE;
    cfg_mark_read(*out);
    return TRUE;
}

static char *default_name(const char *path)
{
    char *base = g_path_get_basename(path);
    char *dot = strrchr(base, '.');
    if (dot && dot != base)
        *dot = '\0';
    return base;
}

SortsSpec *sorts_spec_load(const char *path, const char *const *sets,
                           GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return NULL;
    for (guint i = 0; sets && sets[i]; i++)
        if (!cfg_set_override(root, sets[i], err)) {
            cfg_free(root);
            return NULL;
        }
    SortsSpec *s = g_new0(SortsSpec, 1);
    s->root = root;
    int64_t version = 0;
    const char *name = NULL;
    gboolean ok = cfg_get_int(root, "three_sorts", TRUE, 0, 1000, &version, err);
    if (ok && version != 1) {
        char *d = g_strdup_printf("three_sorts: %lld", (long long)version);
        cfg_error(err, cfg_get(root, "three_sorts"), d, "three_sorts: 1");
        g_free(d);
        ok = FALSE;
    }
    ok = ok && cfg_get_str(root, "name", FALSE, &name, err);
    if (ok && name && !plot_cfg_name_ok(cfg_get(root, "name"), "comparison",
                                        name, err))
        ok = FALSE;
    ok = ok && read_procs(s, err) && read_section(s, "machine", &s->machine, err) &&
         read_section(s, "scene", &s->scene, err) &&
         read_section(s, "run", &s->run, err) && read_sorts(s, err) &&
         cfg_check_unused(root, err);
    for (guint i = 0; ok && s->sorts && i < s->sorts->len; i++) {
        SortsSort *o = s->sorts->pdata[i];
        if (o->scene_as_db && !s->scene) {
            cfg_error(err, root, "scene: database without a scene section",
                      "a scene: section holding a structure database");
            ok = FALSE;
        }
    }
    if (!ok) {
        sorts_spec_free(s);
        return NULL;
    }
    s->name = name ? g_strdup(name) : default_name(path);
    /* a name from the file's name stems the outputs too: refused before
     * anything runs or is written, not at the first chart */
    if (!name && !plot_cfg_name_ok(root, "comparison (from the file name)",
                                   s->name, err)) {
        sorts_spec_free(s);
        return NULL;
    }
    return s;
}
