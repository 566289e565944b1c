/* partition.c — node counts for a partition of N endpoints (partition.h).
 *
 * Reads the merged, checked model tree of the section, decides the counts
 * by topology and applies them with cfg_set_override() under
 * "machine.": the result is exactly what a user's --set would give.
 * Proportional split: every scalable kind first gets one processor, the
 * rest is shared by largest remainder (ties to the earlier kind), so the
 * counts always sum to N and the split is deterministic.
 * Cost: O(model size).
 */
#include "sim/machine/partition.h"
#include "sim/core/error.h"
#include "sim/machine/machine.h"
#include "sim/machine/mnet.h"
#include "sim/machine/model.h"
#include <string.h>

typedef struct {
    const char *name; /* borrowed from the tree */
    uint64_t count;   /* model count */
    uint64_t want;    /* partition count */
    gboolean scalable;
} PartKind;

static gboolean fail(GError **err, char *found, const char *expected)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "found %s, expected %s", found,
                expected);
    g_free(found);
    return FALSE;
}

static gboolean set(CfgNode *root, GError **err, const char *fmt, ...)
    G_GNUC_PRINTF(3, 4);

static gboolean set(CfgNode *root, GError **err, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *a = g_strdup_vprintf(fmt, ap);
    va_end(ap);
    gboolean ok = cfg_set_override(root, a, err);
    g_free(a);
    return ok;
}

static gboolean machine_sets(CfgNode *root, const char *who,
                             const char *const *sets, GError **err)
{
    for (; sets && *sets; sets++) {
        if (!g_str_has_prefix(*sets, "machine.")) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "%s: found --set %s, expected --set "
                        "machine.KEY=VALUE",
                        who, *sets);
            return FALSE;
        }
        if (!cfg_set_override(root, *sets, err))
            return FALSE;
    }
    return TRUE;
}

CfgNode *mach_partition_root(const char *who, const char *model,
                             const char *const *sets, guint nodes,
                             char **desc, GError **err)
{
    CfgNode *root = cfg_load_string("machine: {}\n", who, err);
    char *path = root ? mach_model_path(model, err) : NULL;
    gboolean ok = path && set(root, err, "machine.model=%s", model) &&
                  machine_sets(root, who, sets, err) &&
                  (!nodes || mach_partition(root, nodes, desc, err));
    g_free(path);
    if (!ok)
        g_clear_pointer(&root, cfg_free);
    return root;
}

static GArray *read_kinds(const CfgNode *tree)
{
    const CfgNode *nodes = cfg_get(tree, "nodes");
    GArray *ks = g_array_new(FALSE, TRUE, sizeof(PartKind));
    for (guint i = 0; i < cfg_map_len(nodes); i++) {
        PartKind k = {.name = cfg_map_key(nodes, i)};
        mach_param_count(cfg_map_value(nodes, i), "count", TRUE, &k.count,
                         NULL);
        k.want = k.count;
        g_array_append_val(ks, k);
    }
    return ks;
}

/* Marks the kinds that scale: those of more than one processor, else the
 * first largest one.  Returns how many; *fixed: processors of the rest. */
static guint mark_scalable(GArray *ks, uint64_t *fixed)
{
    guint n = 0, big = 0;
    *fixed = 0;
    for (guint i = 0; i < ks->len; i++) {
        PartKind *k = &g_array_index(ks, PartKind, i);
        k->scalable = k->count > 1;
        n += k->scalable;
        if (k->count > g_array_index(ks, PartKind, big).count)
            big = i;
    }
    if (n == 0) {
        g_array_index(ks, PartKind, big).scalable = TRUE;
        n = 1;
    }
    for (guint i = 0; i < ks->len; i++) {
        const PartKind *k = &g_array_index(ks, PartKind, i);
        *fixed += k->scalable ? 0 : k->count;
    }
    return n;
}

static uint64_t weight(const PartKind *k)
{
    return k->count ? k->count : 1;
}

/* One each, then the rest by largest remainder of rest * count / sum. */
static void split(GArray *ks, uint64_t rest)
{
    uint64_t sum = 0, given = 0, *rem = g_new0(uint64_t, ks->len);
    for (guint i = 0; i < ks->len; i++) {
        PartKind *k = &g_array_index(ks, PartKind, i);
        if (k->scalable) {
            sum += weight(k);
            k->want = 1;
            rest--;
        }
    }
    for (guint i = 0; i < ks->len; i++) {
        PartKind *k = &g_array_index(ks, PartKind, i);
        if (k->scalable) {
            k->want += rest * weight(k) / sum;
            given += rest * weight(k) / sum;
            rem[i] = rest * weight(k) % sum + 1; /* 0: not a candidate */
        }
    }
    for (; given < rest; given++) { /* fewer extras than kinds */
        guint best = 0;
        for (guint i = 1; i < ks->len; i++)
            best = rem[i] > rem[best] ? i : best;
        g_array_index(ks, PartKind, best).want++;
        rem[best] = 0;
    }
    g_free(rem);
}

static char *kinds_desc(const GArray *ks)
{
    GString *s = g_string_new("");
    for (guint i = 0; i < ks->len; i++) {
        const PartKind *k = &g_array_index(ks, PartKind, i);
        g_string_append_printf(s, "%s%s %" G_GUINT64_FORMAT, i ? ", " : "",
                               k->name, k->want);
    }
    return g_string_free(s, FALSE);
}

static gboolean apply_kinds(CfgNode *root, const GArray *ks,
                            const uint64_t *model_counts, GError **err)
{
    for (guint i = 0; i < ks->len; i++) {
        const PartKind *k = &g_array_index(ks, PartKind, i);
        if (k->want != model_counts[i] &&
            !set(root, err, "machine.nodes.%s.count=%" G_GUINT64_FORMAT,
                 k->name, k->want))
            return FALSE;
    }
    return TRUE;
}

static gboolean by_kinds(CfgNode *root, const CfgNode *tree, guint nodes,
                         const char *topo, char **desc, GError **err)
{
    GArray *ks = read_kinds(tree);
    uint64_t fixed, *model = g_new(uint64_t, ks->len ? ks->len : 1);
    for (guint i = 0; i < ks->len; i++)
        model[i] = g_array_index(ks, PartKind, i).count;
    guint n_scal = mark_scalable(ks, &fixed);
    gboolean ok = nodes >= fixed + n_scal;
    if (!ok) {
        char *exp = g_strdup_printf("at least %" G_GUINT64_FORMAT " (the "
                                    "single-processor kinds plus one of "
                                    "each other kind)",
                                    fixed + n_scal);
        fail(err, g_strdup_printf("%u nodes for a %s", nodes, topo), exp);
        g_free(exp);
    }
    if (ok) {
        split(ks, nodes - fixed);
        ok = apply_kinds(root, ks, model, err);
    }
    const CfgNode *net = cfg_get(tree, "network");
    if (ok && mach_param_node(net, "dimension") && nodes > 0 &&
        (nodes & (nodes - 1)) == 0)
        ok = set(root, err, "machine.network.dimension=%d",
                 g_bit_storage(nodes) - 1);
    if (ok && desc) {
        char *k = kinds_desc(ks);
        *desc = k;
    }
    g_free(model);
    g_array_free(ks, TRUE);
    return ok;
}

/* CM-200: lanes of the widest kind; router_nodes follows. */
static gboolean by_lanes(CfgNode *root, const CfgNode *tree, guint nodes,
                         char **desc, GError **err)
{
    const CfgNode *kinds = cfg_get(tree, "nodes"), *net;
    const char *wide = NULL;
    uint64_t best = 0, group = 0;
    for (guint i = 0; i < cfg_map_len(kinds); i++) {
        uint64_t lanes = 1;
        mach_param_count(cfg_map_value(kinds, i), "lanes", FALSE, &lanes, NULL);
        if (!wide || lanes > best) {
            wide = cfg_map_key(kinds, i);
            best = lanes;
        }
    }
    net = cfg_get(tree, "network");
    mach_param_count(net, "procs_per_router", FALSE, &group, NULL);
    uint64_t routers = group ? nodes / group : 0;
    if (!group || nodes % group || !routers || (routers & (routers - 1)))
        return fail(
            err,
            g_strdup_printf("%u lanes for a cm-router of %" G_GUINT64_FORMAT
                            " per router",
                            nodes, group),
            "procs_per_router x a power of two");
    if (!set(root, err, "machine.nodes.%s.lanes=%u", wide, nodes) ||
        (mach_param_node(net, "router_nodes") &&
         !set(root, err, "machine.network.router_nodes=%" G_GUINT64_FORMAT,
              routers)))
        return FALSE;
    if (desc)
        *desc = g_strdup_printf("%s lanes %u = %" G_GUINT64_FORMAT
                                " routers x %" G_GUINT64_FORMAT,
                                wide, nodes, routers, group);
    return TRUE;
}

/* A model with partition `shapes` or several endpoints per node
 * (`node_size`): the machine layer picks the shape (mnet.c), so N fits
 * when that topology builds. */
static gboolean by_shapes(CfgNode *root, const CfgNode *tree, guint nodes,
                          const char *topo, char **desc, GError **err)
{
    NetTopo *t = mach_topo_new(cfg_get(tree, "network"), nodes, NULL, err);
    if (!t)
        return FALSE;
    net_topo_free(t);
    char *k = NULL;
    gboolean ok = by_kinds(root, tree, nodes, topo, &k, err);
    if (ok && desc)
        *desc = g_strdup_printf("%s from the model's shapes; %s", topo, k);
    g_free(k);
    return ok;
}

/* Mesh/torus: the shape is the model's (or the user's override). */
static gboolean by_extents(CfgNode *root, const CfgNode *tree, guint nodes,
                           const char *topo, char **desc, GError **err)
{
    GArray *ext = NULL;
    const CfgNode *net = cfg_get(tree, "network");
    if (mach_param_node(net, "shapes") || mach_param_node(net, "node_size"))
        return by_shapes(root, tree, nodes, topo, desc, err);
    if (!mach_param_count_list(net, "extents", TRUE, &ext, err))
        return FALSE;
    uint64_t prod = 1;
    GString *shape = g_string_new("");
    for (guint i = 0; i < ext->len; i++) {
        prod *= g_array_index(ext, uint64_t, i);
        g_string_append_printf(shape, "%s%" G_GUINT64_FORMAT, i ? "x" : "",
                               g_array_index(ext, uint64_t, i));
    }
    g_array_unref(ext);
    gboolean ok = prod == nodes;
    if (!ok) {
        char *exp = g_strdup_printf("%" G_GUINT64_FORMAT " = the product of "
                                    "extents %s, or other extents with "
                                    "--set machine.network.extents=[x, y]",
                                    prod, shape->str);
        fail(err, g_strdup_printf("%u nodes for a %s", nodes, topo), exp);
        g_free(exp);
    }
    char *k = NULL;
    if (ok)
        ok = by_kinds(root, tree, nodes, topo, &k, err);
    if (ok && desc)
        *desc = g_strdup_printf("extents %s; %s", shape->str, k);
    g_free(k);
    g_string_free(shape, TRUE);
    return ok;
}

gboolean mach_partition(CfgNode *root, guint nodes, char **desc, GError **err)
{
    const CfgNode *section = cfg_get(root, "machine");
    char *file = NULL;
    if (desc)
        *desc = NULL;
    if (!section)
        return fail(err, g_strdup("a config without machine:"),
                    "machine: {model: NAME}");
    CfgNode *tree = mach_section_tree(section, &file, err);
    gboolean ok = tree && mach_model_check(tree, file, err);
    if (ok) {
        const char *topo =
            mach_param_word(cfg_get(tree, "network"), "topology");
        if (g_strcmp0(topo, "cm-router") == 0)
            ok = by_lanes(root, tree, nodes, desc, err);
        else if (!g_strcmp0(topo, "mesh") || !g_strcmp0(topo, "torus"))
            ok = by_extents(root, tree, nodes, topo, desc, err);
        else
            ok = by_kinds(root, tree, nodes, topo, desc, err);
    }
    cfg_free(tree);
    g_free(file);
    return ok;
}
