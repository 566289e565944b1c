/* roles.c — carving the node kinds a workload needs out of the kinds a
 * machine has (roles.h).
 *
 * Invariant: carving keeps the machine's processor count: a kind that
 * plays roles loses exactly the processors the roles take.  A stub (a
 * kind that is only a count, written by a workload's override such as
 * pphigs `gps`) is a role still to carve, with its count.  Cost: one
 * merged model tree and O(kinds x roles).
 */
#include "sim/machine/roles.h"
#include "sim/machine/machine.h"
#include <string.h>

typedef struct {
    const char *role, *kind; /* kind borrowed from the merged tree */
    uint64_t count;          /* 0: not set */
} Role;

/* A kind the model does not have: absent, or a stub written by
 * overrides (a workload's count, a config's own costs for it): nothing
 * but `count` and `costs`, and no count with a provenance (a model's). */
static gboolean lacking(const CfgNode *nodes, const char *name)
{
    const CfgNode *k = cfg_get(nodes, name);
    if (!k || cfg_kind(k) != CFG_MAP)
        return TRUE;
    for (guint i = 0; i < cfg_map_len(k); i++)
        if (strcmp(cfg_map_key(k, i), "count") &&
            strcmp(cfg_map_key(k, i), "costs"))
            return FALSE;
    const CfgNode *n = cfg_get(k, "count");
    return !n || cfg_kind(n) != CFG_MAP;
}

/* The machine's only full kind, or NULL. */
static const char *only_kind(const CfgNode *nodes)
{
    const char *one = NULL;
    for (guint i = 0; i < cfg_map_len(nodes); i++) {
        const char *name = cfg_map_key(nodes, i);
        if (lacking(nodes, name))
            continue;
        if (one)
            return NULL;
        one = name;
    }
    return one;
}

/* The kind that plays `role`: roles.ROLE, else the only kind; NULL when
 * none (not an error).  FALSE with *err when roles.ROLE names no kind. */
static gboolean player(const CfgNode *tree, const char *role,
                       const char **out, GError **err)
{
    const CfgNode *nodes = cfg_get(tree, "nodes");
    const CfgNode *roles = cfg_get(tree, "roles");
    const CfgNode *at = roles ? mach_param_node(roles, role) : NULL;
    *out = at ? cfg_scalar(at) : only_kind(nodes);
    if (!at || (*out && !lacking(nodes, *out)))
        return TRUE;
    char *found = g_strdup_printf("role '%s' played by '%s'", role,
                                  *out ? *out : "a non-word");
    char *exp = g_strdup_printf("a node kind of model %s (%s)",
                                cfg_scalar(cfg_get(tree, "name")),
                                "roles: {ROLE: {value: KIND, source: ...}}");
    cfg_error(err, at, found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

/* The roles to carve, or an empty array when one has no player. */
static GArray *roles_to_carve(const CfgNode *tree, const char *const *needed,
                              GError **err)
{
    const CfgNode *nodes = cfg_get(tree, "nodes");
    GArray *a = g_array_new(FALSE, TRUE, sizeof(Role));
    gboolean all = TRUE;
    for (guint i = 0; needed && needed[i]; i++) {
        gboolean seen = FALSE;
        for (guint j = 0; j < a->len; j++)
            seen = seen || !strcmp(g_array_index(a, Role, j).role, needed[i]);
        if (seen || !lacking(nodes, needed[i]))
            continue;
        Role r = {needed[i], NULL, 0};
        if (!player(tree, needed[i], &r.kind, err)) {
            g_array_free(a, TRUE);
            return NULL;
        }
        if (cfg_get(nodes, r.role))
            mach_param_count(cfg_get(nodes, r.role), "count", TRUE, &r.count,
                             NULL);
        all = all && r.kind;
        g_array_append_val(a, r);
    }
    if (!all)
        g_array_set_size(a, 0);
    return a;
}

/* Counts: the only unset role of a kind the workload does not need
 * itself takes all of it, others one; returns what kind `kind` keeps, or
 * FALSE with *err when it has too few. */
static gboolean share_out(const CfgNode *tree, GArray *a, const char *kind,
                          const char *const *needed, uint64_t *rest,
                          GError **err)
{
    const CfgNode *k = cfg_get(cfg_get(tree, "nodes"), kind);
    uint64_t have = 0, taken = 0;
    guint players = 0;
    mach_param_count(k, "count", TRUE, &have, NULL);
    for (guint i = 0; i < a->len; i++)
        players += !strcmp(g_array_index(a, Role, i).kind, kind);
    for (guint i = 0; needed[i]; i++)
        players += !strcmp(needed[i], kind); /* it keeps processors too */
    for (guint i = 0; i < a->len; i++) {
        Role *r = &g_array_index(a, Role, i);
        if (strcmp(r->kind, kind))
            continue;
        if (!r->count)
            r->count = players == 1 ? have : 1;
        taken += r->count;
    }
    *rest = have - taken;
    if (taken <= have)
        return TRUE;
    char *found = g_strdup_printf("%" G_GUINT64_FORMAT " '%s' processors",
                                  have, kind);
    char *exp = g_strdup_printf("at least %" G_GUINT64_FORMAT
                                " for the roles they play (docs/models.md, "
                                "Roles)",
                                taken);
    cfg_error(err, mach_param_node(k, "count"), found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

static gboolean set_count(CfgNode *sec, const char *kind, uint64_t n,
                          GError **err)
{
    char *s = g_strdup_printf("nodes.%s.count=%" G_GUINT64_FORMAT, kind, n);
    gboolean ok = cfg_set_override(sec, s, err);
    g_free(s);
    return ok;
}

/* nodes.ROLE in sec: its count, and a copy of the rest of its player. */
static gboolean carve(CfgNode *sec, const CfgNode *tree, const Role *r,
                      GError **err)
{
    char *role = g_strdup_printf("roles.%s=%s", r->role, r->kind);
    gboolean ok = cfg_set_override(sec, role, err); /* says it is carved */
    g_free(role);
    if (!ok || !set_count(sec, r->role, r->count, err))
        return FALSE;
    const CfgNode *from = cfg_get(cfg_get(tree, "nodes"), r->kind);
    CfgNode *to = (CfgNode *)cfg_path(sec, "nodes");
    to = (CfgNode *)cfg_get(to, r->role);
    for (guint i = 0; i < cfg_map_len(from); i++) {
        const char *key = cfg_map_key(from, i);
        if (!strcmp(key, "count"))
            continue;
        /* the player's value, under what the stub says itself (a
         * config's own costs for the role win) */
        CfgNode *v = cfg_copy(cfg_map_value(from, i));
        const CfgNode *own = cfg_get(to, key);
        if (own)
            cfg_merge(v, own);
        cfg_map_put(to, key, v);
    }
    return TRUE;
}

/* "cpu by 1 and pipe by 1 of cluster-ib's 64 'node' processors" ... */
static char *describe(const CfgNode *tree, const GArray *a)
{
    GString *s = g_string_new("node kinds played by others (roles, "
                              "docs/models.md): ");
    for (guint i = 0; i < a->len; i++) {
        const Role *r = &g_array_index(a, Role, i);
        g_string_append_printf(s, "%s'%s' by %" G_GUINT64_FORMAT " '%s'",
                               i ? ", " : "", r->role, r->count, r->kind);
    }
    g_string_append_printf(s, " of model %s",
                           cfg_scalar(cfg_get(tree, "name")));
    return g_string_free(s, FALSE);
}

gboolean mach_section_roles(CfgNode *sec, const char *const *model_dirs,
                            const char *const *needed, GPtrArray *notes,
                            GError **err)
{
    char *model_file = NULL;
    CfgNode *tree = mach_section_tree_in(sec, model_dirs, &model_file, err);
    g_free(model_file);
    if (!tree)
        return FALSE;
    GArray *a = cfg_get(tree, "nodes") ? roles_to_carve(tree, needed, err)
                                       : g_array_new(FALSE, TRUE, sizeof(Role));
    gboolean ok = a != NULL;
    for (guint i = 0; ok && i < a->len; i++) {
        const char *kind = g_array_index(a, Role, i).kind;
        uint64_t rest;
        gboolean first = TRUE;
        for (guint j = 0; j < i; j++)
            first = first && strcmp(g_array_index(a, Role, j).kind, kind);
        ok = !first || (share_out(tree, a, kind, needed, &rest, err) &&
                        set_count(sec, kind, rest, err));
    }
    for (guint i = 0; ok && a && i < a->len; i++)
        ok = carve(sec, tree, &g_array_index(a, Role, i), err);
    if (ok && a->len)
        g_ptr_array_add(notes, describe(tree, a));
    if (a)
        g_array_free(a, TRUE);
    cfg_free(tree);
    return ok;
}
