/* cfg_get.c — typed getters, string conversions, overrides and merging.
 *
 * Every getter follows one pattern: look the key up (marking it read),
 * insist on a scalar, convert, check the range; any failure is a located
 * SIM_ERROR_INPUT "file:line:col: found '<text>', expected <what>".  An
 * absent optional key leaves *out untouched (the caller's default).
 * Units are parsed by sim/core/units.c.
 *
 * Overrides ("--set a.b.c=value") parse the value as a YAML document whose
 * file name is "--set a.b.c=value", so later errors about it point at the
 * override.  Merge: maps merge key by key, anything else replaces.
 * Complexity: a lookup is linear in the map's size; merge and override
 * are linear in the nodes they touch.
 */
#include "sim/core/cfg_impl.h"
#include "sim/core/units.h"
#include <string.h>

char *cfg_describe(const CfgNode *n)
{
    switch (n->kind) {
    case CFG_MAP:
        return g_strdup("a map");
    case CFG_SEQ:
        return g_strdup("a sequence");
    case CFG_NULL:
        return g_strdup("an empty value");
    default:
        break;
    }
    if (g_utf8_strlen(n->text, -1) <= 60)
        return g_strdup_printf("'%s'", n->text);
    char *head = g_utf8_substring(n->text, 0, 57);
    char *s = g_strdup_printf("'%s...'", head);
    g_free(head);
    return s;
}

void cfg_error(GError **err, const CfgNode *at, const char *found,
               const char *expected)
{
    sim_error_located(err, at->file, at->line, at->col, found, expected);
}

static void error_at(GError **err, const CfgNode *at, const char *expected)
{
    char *found = cfg_describe(at);
    cfg_error(err, at, found, expected);
    g_free(found);
}

static void missing(GError **err, const CfgNode *map, const char *key,
                    const char *expected)
{
    char *found = g_strdup_printf("no key '%s' in this map", key);
    char *exp = g_strdup_printf("'%s': %s", key, expected);
    if (map)
        cfg_error(err, map, found, exp);
    else
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "found %s, expected %s",
                    found, exp);
    g_free(found);
    g_free(exp);
}

/* The node of kind `kind` at key; TRUE with *out NULL when absent and
 * optional. */
static gboolean lookup_kind(const CfgNode *map, const char *key,
                            gboolean required, CfgKind kind,
                            const char *expected, const CfgNode **out,
                            GError **err)
{
    *out = NULL;
    if (map && map->kind != CFG_MAP) {
        error_at(err, map, "a map");
        return FALSE;
    }
    const CfgNode *v = cfg_get(map, key);
    if (!v) {
        if (required)
            missing(err, map, key, expected);
        return !required;
    }
    if (v->kind != kind) {
        error_at(err, v, expected);
        return FALSE;
    }
    *out = v;
    return TRUE;
}

/* The scalar at key; TRUE with *out NULL when absent and optional. */
static gboolean lookup(const CfgNode *map, const char *key, gboolean required,
                       const char *expected, const CfgNode **out, GError **err)
{
    return lookup_kind(map, key, required, CFG_SCALAR, expected, out, err);
}

gboolean cfg_get_map(const CfgNode *map, const char *key, gboolean required,
                     const char *what, const CfgNode **out, GError **err)
{
    return lookup_kind(map, key, required, CFG_MAP, what, out, err);
}

gboolean cfg_get_str(const CfgNode *map, const char *key, gboolean required,
                     const char **out, GError **err)
{
    const CfgNode *v;
    if (!lookup(map, key, required, "a string", &v, err))
        return FALSE;
    if (v)
        *out = v->text;
    return TRUE;
}

static int bool_value(const char *s)
{
    static const char *const yes[] = {"true", "True", "TRUE",
                                      "yes",  "on",   NULL};
    static const char *const no[] = {"false", "False", "FALSE",
                                     "no",    "off",   NULL};
    return g_strv_contains(yes, s) ? 1 : g_strv_contains(no, s) ? 0 : -1;
}

gboolean cfg_get_bool(const CfgNode *map, const char *key, gboolean required,
                      gboolean *out, GError **err)
{
    const char *exp = "true or false";
    const CfgNode *v;
    if (!lookup(map, key, required, exp, &v, err))
        return FALSE;
    if (!v)
        return TRUE;
    int b = bool_value(v->text);
    if (b < 0) {
        error_at(err, v, exp);
        return FALSE;
    }
    *out = b;
    return TRUE;
}

static char *int_range_text(int64_t min, int64_t max)
{
    if (min == INT64_MIN && max == INT64_MAX)
        return g_strdup("an integer");
    if (max == INT64_MAX)
        return g_strdup_printf("an integer >= %" G_GINT64_FORMAT, min);
    return g_strdup_printf(
        "an integer in [%" G_GINT64_FORMAT ", %" G_GINT64_FORMAT "]", min, max);
}

gboolean cfg_get_int(const CfgNode *map, const char *key, gboolean required,
                     int64_t min, int64_t max, int64_t *out, GError **err)
{
    char *exp = int_range_text(min, max);
    const CfgNode *v;
    gboolean ok = lookup(map, key, required, exp, &v, err);
    gint64 x;
    if (ok && v && !g_ascii_string_to_signed(v->text, 10, min, max, &x, NULL)) {
        error_at(err, v, exp);
        ok = FALSE;
    } else if (ok && v) {
        *out = x;
    }
    g_free(exp);
    return ok;
}

/* A plain decimal floating-point number (no inf, nan or hex). */
static gboolean parse_real(const char *s, double *out)
{
    if (!*s || strspn(s, "0123456789+-.eE") != strlen(s))
        return FALSE;
    char *end;
    double d = g_ascii_strtod(s, &end);
    if (*end || end == s || !isfinite(d))
        return FALSE;
    *out = d;
    return TRUE;
}

gboolean cfg_get_double(const CfgNode *map, const char *key, gboolean required,
                        double min, double max, double *out, GError **err)
{
    char *exp = g_strdup_printf("a number in [%g, %g]", min, max);
    const CfgNode *v;
    gboolean ok = lookup(map, key, required, exp, &v, err);
    double d = 0;
    if (ok && v && (!parse_real(v->text, &d) || d < min || d > max)) {
        error_at(err, v, exp);
        ok = FALSE;
    } else if (ok && v) {
        *out = d;
    }
    g_free(exp);
    return ok;
}

static char *words_text(const char *const *words)
{
    GString *s = g_string_new("one of: ");
    for (int i = 0; words[i]; i++)
        g_string_append_printf(s, "%s%s", i ? ", " : "", words[i]);
    return g_string_free(s, FALSE);
}

gboolean cfg_get_enum(const CfgNode *map, const char *key, gboolean required,
                      const char *const *words, int *out, GError **err)
{
    char *exp = words_text(words);
    const CfgNode *v;
    gboolean ok = lookup(map, key, required, exp, &v, err);
    int i = 0;
    while (ok && v && words[i] && strcmp(words[i], v->text) != 0)
        i++;
    if (ok && v && !words[i]) {
        error_at(err, v, exp);
        ok = FALSE;
    } else if (ok && v) {
        *out = i;
    }
    g_free(exp);
    return ok;
}

/* Looks up a scalar and converts it with the units module: into *u, or
 * into *d when u is NULL. */
static gboolean get_unit(const CfgNode *map, const char *key,
                         gboolean required, CfgUnitKind kind, uint64_t *u,
                         double *d, GError **err)
{
    const CfgNode *v;
    const char *exp = cfg_units_expected(kind);
    if (!lookup(map, key, required, exp, &v, err))
        return FALSE;
    gboolean ok = !v || (u ? cfg_units_u64(v->text, kind, u, &exp)
                           : cfg_units_double(v->text, kind, d, &exp));
    if (!ok)
        error_at(err, v, exp);
    return ok;
}

static gboolean get_u64(const CfgNode *map, const char *key, gboolean required,
                        CfgUnitKind kind, uint64_t *out, GError **err)
{
    return get_unit(map, key, required, kind, out, NULL, err);
}

static gboolean get_real(const CfgNode *map, const char *key, gboolean required,
                         CfgUnitKind kind, double *out, GError **err)
{
    return get_unit(map, key, required, kind, NULL, out, err);
}

gboolean cfg_get_time(const CfgNode *map, const char *key, gboolean required,
                      SimTime *out, GError **err)
{
    return get_u64(map, key, required, CFG_UNIT_TIME, out, err);
}

gboolean cfg_get_bandwidth(const CfgNode *map, const char *key,
                           gboolean required, double *bytes_per_s, GError **err)
{
    return get_real(map, key, required, CFG_UNIT_BANDWIDTH, bytes_per_s, err);
}

gboolean cfg_get_freq(const CfgNode *map, const char *key, gboolean required,
                      double *hz, GError **err)
{
    return get_real(map, key, required, CFG_UNIT_FREQ, hz, err);
}

gboolean cfg_get_size(const CfgNode *map, const char *key, gboolean required,
                      uint64_t *bytes, GError **err)
{
    return get_u64(map, key, required, CFG_UNIT_SIZE, bytes, err);
}

gboolean cfg_get_count(const CfgNode *map, const char *key, gboolean required,
                       uint64_t min, uint64_t max, uint64_t *out, GError **err)
{
    uint64_t v = 0;
    const CfgNode *at;
    const char *exp = cfg_units_expected(CFG_UNIT_COUNT);
    if (!lookup(map, key, required, exp, &at, err))
        return FALSE;
    if (!at)
        return TRUE;
    if (!cfg_units_u64(at->text, CFG_UNIT_COUNT, &v, &exp)) {
        error_at(err, at, exp);
        return FALSE;
    }
    if (v < min || v > max) {
        char *range = g_strdup_printf("a count in [%" G_GUINT64_FORMAT
                                      ", %" G_GUINT64_FORMAT "]",
                                      min, max);
        error_at(err, at, range);
        g_free(range);
        return FALSE;
    }
    *out = v;
    return TRUE;
}

/* ---- bare strings (CLI flags) ---------------------------------------- */

static gboolean flag_error(GError **err, const char *what, const char *s,
                           const char *expected)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "%s: found '%s', expected %s",
                what, s, expected);
    return FALSE;
}

gboolean cfg_parse_time(const char *s, const char *what, SimTime *out,
                        GError **err)
{
    const char *exp;
    return cfg_units_u64(s, CFG_UNIT_TIME, out, &exp) ||
           flag_error(err, what, s, exp);
}

gboolean cfg_parse_bandwidth(const char *s, const char *what, double *out,
                             GError **err)
{
    const char *exp;
    return cfg_units_double(s, CFG_UNIT_BANDWIDTH, out, &exp) ||
           flag_error(err, what, s, exp);
}

gboolean cfg_parse_size(const char *s, const char *what, uint64_t *out,
                        GError **err)
{
    const char *exp;
    return cfg_units_u64(s, CFG_UNIT_SIZE, out, &exp) ||
           flag_error(err, what, s, exp);
}

gboolean cfg_parse_count(const char *s, const char *what, uint64_t *out,
                         GError **err)
{
    const char *exp;
    return cfg_units_u64(s, CFG_UNIT_COUNT, out, &exp) ||
           flag_error(err, what, s, exp);
}

/* ---- overrides and merge --------------------------------------------- */

/* The child of n named by one path component, or NULL. */
static CfgNode *child(CfgNode *n, const char *part, CfgEntry **entry)
{
    *entry = NULL;
    if (n->kind == CFG_MAP) {
        *entry = cfg_map_find(n, part);
        return *entry ? (*entry)->value : NULL;
    }
    gint64 i = cfg_path_index(part, strlen(part));
    if (n->kind == CFG_SEQ && i >= 0 && i < (gint64)n->items->len)
        return g_ptr_array_index(n->items, i);
    return NULL;
}

/* Puts `value` (owned) at parts[0..] below n, creating maps. */
static gboolean place(CfgNode *n, char **parts, CfgNode *value,
                      const char *name, GError **err)
{
    CfgEntry *e;
    CfgNode *c = child(n, parts[0], &e);
    if (!c && n->kind != CFG_MAP) {
        char *found =
            g_strdup_printf("'%s' below %s", parts[0],
                            n->kind == CFG_SEQ ? "a sequence" : "a scalar");
        sim_error_located(err, name, 1, 1, found,
                          n->kind == CFG_SEQ ? "an index in range"
                                             : "a path through maps");
        g_free(found);
        cfg_free(value);
        return FALSE;
    }
    if (!parts[1]) {
        if (c)
            cfg_node_assign(c, value);
        else
            cfg_map_add(n, parts[0], name, 1, 1, value);
        return TRUE;
    }
    if (!c)
        c = cfg_map_add(n, parts[0], name, 1, 1,
                        cfg_node_new(CFG_MAP, name, 1, 1))
                ->value;
    return place(c, parts + 1, value, name, err);
}

static gboolean valid_path(const char *path)
{
    if (!*path)
        return FALSE;
    char **parts = g_strsplit(path, ".", -1);
    gboolean ok = TRUE;
    for (int i = 0; parts[i]; i++)
        ok = ok && *parts[i] &&
             strspn(parts[i], "abcdefghijklmnopqrstuvwxyz"
                              "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") ==
                 strlen(parts[i]);
    g_strfreev(parts);
    return ok;
}

gboolean cfg_set_override(CfgNode *root, const char *assignment, GError **err)
{
    g_assert(root && root->kind == CFG_MAP);
    const char *eq = strchr(assignment, '=');
    char *path = eq ? g_strndup(assignment, eq - assignment) : NULL;
    if (!path || !valid_path(path)) {
        g_free(path);
        return flag_error(err, "--set", assignment, "key.path=value");
    }
    char *name = g_strdup_printf("--set %s", assignment);
    CfgNode *value = cfg_load_string(eq + 1, name, err);
    gboolean ok = value != NULL;
    if (ok) {
        char **parts = g_strsplit(path, ".", -1);
        ok = place(root, parts, value, name, err);
        g_strfreev(parts);
    }
    g_free(name);
    g_free(path);
    return ok;
}

void cfg_map_put(CfgNode *map, const char *key, CfgNode *value)
{
    g_assert(map->kind == CFG_MAP && value);
    CfgEntry *e = cfg_map_find(map, key);
    if (e)
        cfg_node_assign(e->value, value);
    else
        cfg_map_add(map, key, value->file, value->line, value->col, value);
}

void cfg_merge(CfgNode *base, const CfgNode *over)
{
    if (base->kind != CFG_MAP || over->kind != CFG_MAP) {
        cfg_node_assign(base, cfg_copy(over));
        return;
    }
    for (guint i = 0; i < over->items->len; i++) {
        const CfgEntry *o = g_ptr_array_index(over->items, i);
        CfgEntry *b = cfg_map_find(base, o->key);
        if (b)
            cfg_merge(b->value, o->value);
        else
            cfg_map_add(base, o->key, o->file, o->line, o->col,
                        cfg_copy(o->value));
    }
}
