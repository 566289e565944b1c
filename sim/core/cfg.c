/* cfg.c — YAML into located configuration trees (libyaml event API).
 *
 * Every node keeps its file name (interned), 1-based line and column from
 * libyaml's start mark.  Plain scalars "", "~", "null" become CFG_NULL.
 * Aliases are resolved by deep copy of the anchored node (at most a
 * million copied nodes per file, against "billion laughs" inputs); merge
 * keys and multiple documents are rejected.  Duplicate keys in a map are an
 * error located at the second occurrence.  Nesting deeper than CFG_MAX_DEPTH is
 * rejected so hostile input cannot exhaust the stack.
 *
 * Read tracking: each map entry has a `read` flag and each map a list of
 * the keys consumers asked for (present or not), which is what
 * cfg_check_unused() offers in "expected one of: ...".  The flags are the
 * only mutable state behind a const CfgNode * (they are bookkeeping, not
 * configuration).  Map lookup is a linear scan: config maps are small.
 *
 * Typed getters, overrides and merging are in cfg_get.c.
 */
#include "sim/core/cfg_impl.h"
#include "sim/core/datapath.h"
#include <string.h>
#include <yaml.h>

#define CFG_MAX_DEPTH 200
#define CFG_MAX_ALIAS_NODES 1000000 /* nodes copied by aliases, per file */

typedef struct {
    yaml_parser_t parser;
    const char *file;    /* interned */
    GHashTable *anchors; /* name -> CfgNode * (owned copies) */
    int depth;
    gboolean ended;      /* the stream end was seen */
    guint64 alias_nodes; /* nodes created by alias copies so far */
} Loader;

static void entry_free(gpointer p)
{
    CfgEntry *e = p;
    g_free(e->key);
    cfg_free(e->value);
    g_free(e);
}

CfgNode *cfg_node_new(CfgKind kind, const char *file, int line, int col)
{
    CfgNode *n = g_new0(CfgNode, 1);
    n->kind = kind;
    n->file = g_intern_string(file ? file : "<input>");
    n->line = line;
    n->col = col;
    if (kind == CFG_MAP) {
        n->items = g_ptr_array_new_with_free_func(entry_free);
        n->asked = g_ptr_array_new();
    } else if (kind == CFG_SEQ) {
        n->items = g_ptr_array_new_with_free_func((GDestroyNotify)cfg_free);
    }
    return n;
}

static void node_clear(CfgNode *n)
{
    g_free(n->text);
    if (n->items)
        g_ptr_array_free(n->items, TRUE);
    if (n->asked)
        g_ptr_array_free(n->asked, TRUE);
}

void cfg_free(CfgNode *n)
{
    if (!n)
        return;
    node_clear(n);
    g_free(n);
}

void cfg_node_assign(CfgNode *dst, CfgNode *src)
{
    node_clear(dst);
    *dst = *src;
    g_free(src);
}

CfgEntry *cfg_map_add(CfgNode *map, const char *key, const char *file, int line,
                      int col, CfgNode *value)
{
    CfgEntry *e = g_new0(CfgEntry, 1);
    e->key = g_strdup(key);
    e->file = g_intern_string(file);
    e->line = line;
    e->col = col;
    e->value = value;
    g_ptr_array_add(map->items, e);
    return e;
}

CfgEntry *cfg_map_find(const CfgNode *map, const char *key)
{
    for (guint i = 0; i < map->items->len; i++) {
        CfgEntry *e = g_ptr_array_index(map->items, i);
        if (strcmp(e->key, key) == 0)
            return e;
    }
    return NULL;
}

CfgNode *cfg_copy(const CfgNode *n)
{
    if (!n)
        return NULL;
    CfgNode *c = cfg_node_new(n->kind, n->file, n->line, n->col);
    c->text = g_strdup(n->text);
    c->quoted = n->quoted;
    for (guint i = 0; n->items && i < n->items->len; i++) {
        if (n->kind == CFG_SEQ) {
            g_ptr_array_add(c->items, cfg_copy(g_ptr_array_index(n->items, i)));
        } else {
            const CfgEntry *e = g_ptr_array_index(n->items, i);
            cfg_map_add(c, e->key, e->file, e->line, e->col,
                        cfg_copy(e->value));
        }
    }
    return c;
}

/* ---- loading ---------------------------------------------------------- */

static void syntax_error(Loader *L, GError **err)
{
    const yaml_parser_t *p = &L->parser;
    char *found = p->context ? g_strdup_printf("YAML syntax error '%s' %s",
                                               p->problem, p->context)
                             : g_strdup_printf("YAML syntax error '%s'",
                                               p->problem ? p->problem : "?");
    sim_error_located(err, L->file, (int)p->problem_mark.line + 1,
                      (int)p->problem_mark.column + 1, found,
                      "well-formed YAML");
    g_free(found);
}

static gboolean next_event(Loader *L, yaml_event_t *ev, GError **err)
{
    if (yaml_parser_parse(&L->parser, ev))
        return TRUE;
    syntax_error(L, err);
    return FALSE;
}

static void ev_error(Loader *L, const yaml_event_t *ev, const char *found,
                     const char *expected, GError **err)
{
    sim_error_located(err, L->file, (int)ev->start_mark.line + 1,
                      (int)ev->start_mark.column + 1, found, expected);
}

static gboolean is_null_text(const char *s)
{
    return !*s || strcmp(s, "~") == 0 || strcmp(s, "null") == 0 ||
           strcmp(s, "Null") == 0 || strcmp(s, "NULL") == 0;
}

static CfgNode *load_node(Loader *L, yaml_event_t *ev, GError **err);

static CfgNode *load_scalar(Loader *L, const yaml_event_t *ev)
{
    const char *text = (const char *)ev->data.scalar.value;
    gboolean plain = ev->data.scalar.style == YAML_PLAIN_SCALAR_STYLE;
    CfgKind k = plain && is_null_text(text) ? CFG_NULL : CFG_SCALAR;
    CfgNode *n = cfg_node_new(k, L->file, (int)ev->start_mark.line + 1,
                              (int)ev->start_mark.column + 1);
    if (k == CFG_SCALAR)
        n->text = g_strndup(text, ev->data.scalar.length);
    n->quoted = !plain;
    return n;
}

static guint64 count_nodes(const CfgNode *n)
{
    guint64 c = 1;
    for (guint i = 0; n->items && i < n->items->len; i++) {
        const void *it = g_ptr_array_index(n->items, i);
        c += count_nodes(n->kind == CFG_SEQ ? it
                                            : ((const CfgEntry *)it)->value);
    }
    return c;
}

static CfgNode *load_alias(Loader *L, const yaml_event_t *ev, GError **err)
{
    const char *name = (const char *)ev->data.alias.anchor;
    CfgNode *target = g_hash_table_lookup(L->anchors, name);
    if (!target) {
        char *found = g_strdup_printf("alias '*%s'", name);
        ev_error(L, ev, found, "an anchor defined earlier", err);
        g_free(found);
        return NULL;
    }
    L->alias_nodes += count_nodes(target);
    if (L->alias_nodes > CFG_MAX_ALIAS_NODES) {
        ev_error(L, ev, "aliases expanding to over a million nodes",
                 "a smaller document", err);
        return NULL;
    }
    CfgNode *n = cfg_copy(target);
    n->line = (int)ev->start_mark.line + 1;
    n->col = (int)ev->start_mark.column + 1;
    return n;
}

/* Reads the events of one map key: a scalar, or an error. */
static char *load_key(Loader *L, yaml_event_t *ev, GError **err)
{
    if (ev->type != YAML_SCALAR_EVENT) {
        ev_error(L, ev, "a complex key", "a plain key", err);
        return NULL;
    }
    const char *k = (const char *)ev->data.scalar.value;
    if (strcmp(k, "<<") == 0 &&
        ev->data.scalar.style == YAML_PLAIN_SCALAR_STYLE) {
        ev_error(L, ev, "merge key '<<'",
                 "a plain key (merge keys are not "
                 "supported)",
                 err);
        return NULL;
    }
    return g_strndup(k, ev->data.scalar.length);
}

static gboolean add_pair(Loader *L, CfgNode *map, yaml_event_t *kev,
                         GError **err)
{
    char *key = load_key(L, kev, err);
    if (!key)
        return FALSE;
    int line = (int)kev->start_mark.line + 1;
    int col = (int)kev->start_mark.column + 1;
    CfgEntry *dup = cfg_map_find(map, key);
    if (dup) {
        char *found = g_strdup_printf("duplicate key '%s' (first at line "
                                      "%d)",
                                      key, dup->line);
        sim_error_located(err, L->file, line, col, found,
                          "each key once per map");
        g_free(found);
        g_free(key);
        return FALSE;
    }
    yaml_event_t vev;
    CfgNode *v = next_event(L, &vev, err) ? load_node(L, &vev, err) : NULL;
    if (v)
        cfg_map_add(map, key, L->file, line, col, v);
    g_free(key);
    return v != NULL;
}

static CfgNode *load_children(Loader *L, CfgNode *n, yaml_event_type_t end,
                              GError **err)
{
    for (;;) {
        yaml_event_t ev;
        if (!next_event(L, &ev, err))
            break;
        if (ev.type == end) {
            yaml_event_delete(&ev);
            return n;
        }
        gboolean ok;
        if (n->kind == CFG_MAP) {
            ok = add_pair(L, n, &ev, err);
            yaml_event_delete(&ev);
        } else {
            CfgNode *c = load_node(L, &ev, err);
            if (c)
                g_ptr_array_add(n->items, c);
            ok = c != NULL;
        }
        if (!ok)
            break;
    }
    cfg_free(n);
    return NULL;
}

static void remember_anchor(Loader *L, const yaml_char_t *anchor,
                            const CfgNode *n)
{
    if (anchor && n)
        g_hash_table_replace(L->anchors, g_strdup((const char *)anchor),
                             cfg_copy(n));
}

/* Builds the node that starts with *ev (consumed) and its children. */
static CfgNode *load_node(Loader *L, yaml_event_t *ev, GError **err)
{
    CfgNode *n = NULL;
    int line = (int)ev->start_mark.line + 1;
    int col = (int)ev->start_mark.column + 1;
    if (++L->depth > CFG_MAX_DEPTH) {
        ev_error(L, ev, "nesting deeper than 200 levels",
                 "a shallower "
                 "document",
                 err);
    } else if (ev->type == YAML_SCALAR_EVENT) {
        n = load_scalar(L, ev);
        remember_anchor(L, ev->data.scalar.anchor, n);
    } else if (ev->type == YAML_ALIAS_EVENT) {
        n = load_alias(L, ev, err);
    } else if (ev->type == YAML_MAPPING_START_EVENT) {
        n = load_children(L, cfg_node_new(CFG_MAP, L->file, line, col),
                          YAML_MAPPING_END_EVENT, err);
        remember_anchor(L, ev->data.mapping_start.anchor, n);
    } else if (ev->type == YAML_SEQUENCE_START_EVENT) {
        n = load_children(L, cfg_node_new(CFG_SEQ, L->file, line, col),
                          YAML_SEQUENCE_END_EVENT, err);
        remember_anchor(L, ev->data.sequence_start.anchor, n);
    } else {
        ev_error(L, ev, "an unexpected YAML event", "a value", err);
    }
    L->depth--;
    yaml_event_delete(ev);
    return n;
}

/* Skips to the first node event; an empty stream gives a CFG_NULL. */
static CfgNode *load_document(Loader *L, GError **err)
{
    yaml_event_t ev;
    for (;;) {
        if (!next_event(L, &ev, err))
            return NULL;
        if (ev.type == YAML_STREAM_END_EVENT) {
            yaml_event_delete(&ev);
            L->ended = TRUE;
            return cfg_node_new(CFG_NULL, L->file, 1, 1);
        }
        if (ev.type != YAML_STREAM_START_EVENT &&
            ev.type != YAML_DOCUMENT_START_EVENT)
            return load_node(L, &ev, err);
        yaml_event_delete(&ev);
    }
}

/* After the root: exactly one document, then the end of the stream. */
static gboolean load_tail(Loader *L, GError **err)
{
    yaml_event_t ev;
    while (next_event(L, &ev, err)) {
        yaml_event_type_t t = ev.type;
        if (t == YAML_DOCUMENT_START_EVENT)
            ev_error(L, &ev, "a second YAML document",
                     "one document per "
                     "file",
                     err);
        yaml_event_delete(&ev);
        if (t == YAML_DOCUMENT_START_EVENT)
            return FALSE;
        if (t == YAML_STREAM_END_EVENT || t == YAML_NO_EVENT)
            return TRUE;
    }
    return FALSE;
}

static CfgNode *load(const unsigned char *text, size_t len, const char *name,
                     GError **err)
{
    Loader L = {.file = g_intern_string(name)};
    L.anchors = g_hash_table_new_full(g_str_hash, g_str_equal, g_free,
                                      (GDestroyNotify)cfg_free);
    yaml_parser_initialize(&L.parser);
    yaml_parser_set_input_string(&L.parser, text, len);
    CfgNode *root = load_document(&L, err);
    if (root && !L.ended && !load_tail(&L, err)) {
        cfg_free(root);
        root = NULL;
    }
    yaml_parser_delete(&L.parser);
    g_hash_table_destroy(L.anchors);
    return root;
}

CfgNode *cfg_load_string(const char *text, const char *name, GError **err)
{
    return load((const unsigned char *)text, strlen(text), name, err);
}

CfgNode *cfg_load_file(const char *name, GError **err)
{
    char *text = NULL, *path = sim_data_path(name);
    gsize len = 0;
    CfgNode *root = NULL;
    if (sim_file_read(path, &text, &len, err))
        root = load((const unsigned char *)text, len, path, err);
    g_free(text);
    g_free(path);
    return root;
}

/* ---- accessors -------------------------------------------------------- */

CfgKind cfg_kind(const CfgNode *n)
{
    return n->kind;
}

const char *cfg_file(const CfgNode *n)
{
    return n->file;
}

int cfg_line(const CfgNode *n)
{
    return n->line;
}

int cfg_col(const CfgNode *n)
{
    return n->col;
}

const char *cfg_scalar(const CfgNode *n)
{
    return n && n->kind == CFG_SCALAR ? n->text : NULL;
}

static void note_asked(const CfgNode *map, const char *key)
{
    GPtrArray *a = map->asked;
    const char *k = g_intern_string(key);
    for (guint i = 0; i < a->len; i++)
        if (g_ptr_array_index(a, i) == k)
            return;
    g_ptr_array_add(a, (gpointer)k);
}

const CfgNode *cfg_get(const CfgNode *map, const char *key)
{
    if (!map || map->kind != CFG_MAP)
        return NULL;
    note_asked(map, key);
    CfgEntry *e = cfg_map_find(map, key);
    if (!e)
        return NULL;
    e->read = TRUE;
    return e->value;
}

gboolean cfg_has(const CfgNode *map, const char *key)
{
    return map && map->kind == CFG_MAP && cfg_map_find(map, key);
}

guint cfg_map_len(const CfgNode *map)
{
    return map && map->kind == CFG_MAP ? map->items->len : 0;
}

const char *cfg_map_key(const CfgNode *map, guint i)
{
    g_assert(map->kind == CFG_MAP && i < map->items->len);
    CfgEntry *e = g_ptr_array_index(map->items, i);
    e->read = TRUE;
    return e->key;
}

const CfgNode *cfg_map_value(const CfgNode *map, guint i)
{
    g_assert(map->kind == CFG_MAP && i < map->items->len);
    const CfgEntry *e = g_ptr_array_index(map->items, i);
    return e->value;
}

guint cfg_seq_len(const CfgNode *seq)
{
    return seq && seq->kind == CFG_SEQ ? seq->items->len : 0;
}

const CfgNode *cfg_seq_at(const CfgNode *seq, guint i)
{
    g_assert(seq->kind == CFG_SEQ && i < seq->items->len);
    return g_ptr_array_index(seq->items, i);
}

/* "12" -> 12 for sequence indices in paths; -1 if not an index. */
gint64 cfg_path_index(const char *s, size_t len)
{
    gint64 v = 0;
    if (len == 0 || len > 9)
        return -1;
    for (size_t i = 0; i < len; i++) {
        if (s[i] < '0' || s[i] > '9')
            return -1;
        v = v * 10 + (s[i] - '0');
    }
    return v;
}

const CfgNode *cfg_path(const CfgNode *root, const char *path)
{
    char **parts = g_strsplit(path, ".", -1);
    const CfgNode *n = root;
    for (int i = 0; n && parts[i]; i++) {
        if (n->kind == CFG_MAP) {
            n = cfg_get(n, parts[i]);
        } else if (n->kind == CFG_SEQ) {
            gint64 k = cfg_path_index(parts[i], strlen(parts[i]));
            n = k >= 0 && k < (gint64)n->items->len
                    ? g_ptr_array_index(n->items, k)
                    : NULL;
        } else {
            n = NULL;
        }
    }
    g_strfreev(parts);
    return n;
}

/* ---- unknown keys ------------------------------------------------------ */

static char *asked_list(const CfgNode *map)
{
    if (map->asked->len == 0)
        return g_strdup("no key here (nothing reads this map)");
    GString *s = g_string_new("one of: ");
    for (guint i = 0; i < map->asked->len; i++)
        g_string_append_printf(s, "%s%s", i ? ", " : "",
                               (const char *)g_ptr_array_index(map->asked, i));
    return g_string_free(s, FALSE);
}

static gboolean check_entry(const CfgNode *map, const CfgEntry *e, GError **err)
{
    if (e->read)
        return cfg_check_unused(e->value, err);
    char *found = g_strdup_printf("unknown key '%s'", e->key);
    char *expected = asked_list(map);
    sim_error_located(err, e->file, e->line, e->col, found, expected);
    g_free(found);
    g_free(expected);
    return FALSE;
}

gboolean cfg_check_unused_except(const CfgNode *n, const char *const *skip,
                                 GError **err)
{
    if (!n)
        return TRUE;
    for (guint i = 0; n->kind == CFG_SEQ && i < n->items->len; i++)
        if (!cfg_check_unused(g_ptr_array_index(n->items, i), err))
            return FALSE;
    for (guint i = 0; n->kind == CFG_MAP && i < n->items->len; i++) {
        const CfgEntry *e = g_ptr_array_index(n->items, i);
        if (e->read && skip && g_strv_contains(skip, e->key))
            continue;
        if (!check_entry(n, e, err))
            return FALSE;
    }
    return TRUE;
}

gboolean cfg_check_unused(const CfgNode *n, GError **err)
{
    return cfg_check_unused_except(n, NULL, err);
}

void cfg_mark_read(const CfgNode *n)
{
    for (guint i = 0; n && n->items && i < n->items->len; i++) {
        if (n->kind == CFG_SEQ) {
            cfg_mark_read(g_ptr_array_index(n->items, i));
        } else {
            CfgEntry *e = g_ptr_array_index(n->items, i);
            e->read = TRUE;
            cfg_mark_read(e->value);
        }
    }
}
