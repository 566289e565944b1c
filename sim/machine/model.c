/* model.c — checking machine model files, and loading one by name.
 *
 * Finding the file is model_find.c's; reading a checked tree's values
 * and their provenance is model_param.c's.  The checker walks the tree
 * once: top-level keys, each node kind, each cost, each network key.
 * Every parameter is looked up in a small type table; its value must
 * parse as that type, carry a unit when the type has one, and come with
 * a non-empty `source`, `calibrated` or `assumption` unless it is an
 * override from another file (model.h).  Errors are located:
 * "file:line:col: found <what>, expected <what>".
 *
 * Invariant: a tree that passed mach_model_check() has every accepted key
 * marked read, and the typed getters (model_param.h) cannot fail on it
 * except for a missing required key.  Cost: O(size of the tree).
 */
#include "sim/machine/model.h"
#include "sim/machine/work.h"
#include "sim/core/inputs.h"
#include "sim/core/datapath.h"
#include "sim/core/error.h"
#include <string.h>

typedef struct {
    const char *key;
    MachType type;
} MachKeyType;

/* Keys a node kind may have, besides `costs` (a map of times). */
static const MachKeyType kind_keys[] = {
    {"count", MACH_T_COUNT},      {"processor", MACH_T_WORD},
    {"clock", MACH_T_FREQ},       {"memory", MACH_T_SIZE},
    {"lanes", MACH_T_COUNT},      {"lane_memory", MACH_T_SIZE},
    {"fpa_lanes", MACH_T_COUNT},  {"cores", MACH_T_COUNT},
    {"peak_flops", MACH_T_COUNT}, {"memory_bandwidth", MACH_T_BANDWIDTH},
    {NULL, 0},
};

/* Keys the network section may have. */
static const MachKeyType net_keys[] = {
    {"topology", MACH_T_WORD},
    {"routing", MACH_T_WORD},
    {"switching", MACH_T_WORD},
    {"fidelity", MACH_T_WORD},
    {"duplex", MACH_T_WORD},
    {"bandwidth", MACH_T_BANDWIDTH},
    {"total_bandwidth", MACH_T_BANDWIDTH},
    {"aggregate_bandwidth", MACH_T_BANDWIDTH},
    {"level_bandwidth", MACH_T_BW_LIST},
    {"startup", MACH_T_TIME},
    {"startup_long", MACH_T_TIME},
    {"long_threshold", MACH_T_SIZE},
    {"per_hop", MACH_T_TIME},
    {"word_time", MACH_T_TIME},
    {"router_cycle", MACH_T_TIME},
    {"control_latency", MACH_T_TIME},
    {"packet_size", MACH_T_SIZE},
    {"channels", MACH_T_COUNT},
    {"arity", MACH_T_COUNT},
    {"dimension", MACH_T_COUNT},
    {"extents", MACH_T_COUNT_LIST},
    {"shapes", MACH_T_COUNT_LIST},
    {"torus_min", MACH_T_COUNT},
    {"node_size", MACH_T_COUNT},
    {"node_bandwidth", MACH_T_BANDWIDTH},
    {"node_ports", MACH_T_WORD},
    {"procs_per_router", MACH_T_COUNT},
    {"router_nodes", MACH_T_COUNT},
    {"router_link_bandwidth", MACH_T_BANDWIDTH},
    {"news_bandwidth", MACH_T_BANDWIDTH},
    {NULL, 0},
};

static gboolean lookup(const MachKeyType *t, const char *key, MachType *out)
{
    for (; t->key; t++) {
        if (strcmp(t->key, key) == 0) {
            *out = t->type;
            return TRUE;
        }
    }
    return FALSE;
}

gboolean mach_kind_key_type(const char *key, MachType *out)
{
    return lookup(kind_keys, key, out);
}

gboolean mach_net_key_type(const char *key, MachType *out)
{
    return lookup(net_keys, key, out);
}

static char *key_list(const MachKeyType *t, const char *extra)
{
    GString *s = g_string_new("one of: ");
    for (const MachKeyType *k = t; k->key; k++)
        g_string_append_printf(s, "%s%s", k == t ? "" : ", ", k->key);
    if (extra)
        g_string_append_printf(s, ", %s", extra);
    return g_string_free(s, FALSE);
}

/* ---- checking ----------------------------------------------------------- */

static gboolean has_unit(const char *s)
{
    size_t n = strlen(s);
    while (n > 0 && g_ascii_isspace(s[n - 1]))
        n--;
    return n > 0 && !g_ascii_isdigit(s[n - 1]) && s[n - 1] != '.';
}

static gboolean check_unit(const CfgNode *v, MachType t, GError **err)
{
    if (t == MACH_T_WORD || t == MACH_T_COUNT || t == MACH_T_NUMBER)
        return TRUE;
    const char *s = cfg_scalar(v);
    if (s && has_unit(s))
        return TRUE;
    char *found = s ? g_strdup_printf("'%s' without a unit", s)
                    : g_strdup("a non-scalar value");
    cfg_error(err, v, found, mach_type_example(t));
    g_free(found);
    return FALSE;
}

/* A list value: a non-empty sequence whose items pass check_unit. */
static gboolean check_list(const CfgNode *v, MachType t, GError **err)
{
    if (cfg_kind(v) != CFG_SEQ || cfg_seq_len(v) == 0) {
        cfg_error(err, v, "a non-list value", mach_type_example(t));
        return FALSE;
    }
    MachType item = t == MACH_T_BW_LIST ? MACH_T_BANDWIDTH : MACH_T_COUNT;
    for (guint i = 0; i < cfg_seq_len(v); i++)
        if (!check_unit(cfg_seq_at(v, i), item, err))
            return FALSE;
    return TRUE;
}

static gboolean is_list(MachType t)
{
    return t == MACH_T_BW_LIST || t == MACH_T_COUNT_LIST;
}

/* Parses the value in (map, key) as type t, discarding the result. */
static gboolean check_typed(const CfgNode *map, const char *key, MachType t,
                            GError **err)
{
    SimTime tm;
    uint64_t u;
    double d;
    const char *w;
    GArray *list = NULL;
    gboolean ok;
    switch (t) {
    case MACH_T_TIME:
        return cfg_get_time(map, key, TRUE, &tm, err);
    case MACH_T_BANDWIDTH:
        return cfg_get_bandwidth(map, key, TRUE, &d, err);
    case MACH_T_FREQ:
        return cfg_get_freq(map, key, TRUE, &d, err);
    case MACH_T_SIZE:
        return cfg_get_size(map, key, TRUE, &u, err);
    case MACH_T_COUNT:
        return cfg_get_count(map, key, TRUE, 0, UINT64_MAX, &u, err);
    case MACH_T_NUMBER:
        return mach_param_number(map, key, TRUE, &d, err);
    case MACH_T_BW_LIST:
    case MACH_T_COUNT_LIST:
        ok = t == MACH_T_BW_LIST
                 ? mach_param_bw_list(map, key, TRUE, &list, err)
                 : mach_param_count_list(map, key, TRUE, &list, err);
        if (list)
            g_array_unref(list);
        return ok;
    default:
        return cfg_get_str(map, key, TRUE, &w, err);
    }
}

/* A user's model may declare `provenance: assumption`: its values
 * without a source are then accepted and listed here, for one warning
 * (mach_model_check).  NULL while checking a model without it. */
static GPtrArray *assumed;

static gboolean assume(const char *name)
{
    if (!assumed)
        return FALSE;
    g_ptr_array_add(assumed, g_strdup(name));
    return TRUE;
}

static gboolean check_provenance(const CfgNode *p, const char *name,
                                 GError **err)
{
    gboolean found_any = FALSE;
    for (const char *const *k = mach_provenance_keys; *k; k++) {
        const CfgNode *v = cfg_get(p, *k); /* marks every one read */
        const char *s = v ? cfg_scalar(v) : NULL;
        if (v && (!s || !*s)) {
            cfg_error(err, v, "an empty provenance",
                      "a citation or an explanation in words");
            return FALSE;
        }
        found_any = found_any || s;
    }
    if (found_any || assume(name))
        return TRUE;
    char *found = g_strdup_printf("parameter '%s' without a provenance", name);
    cfg_error(err, p, found,
              "one of source:, calibrated: or assumption: (or, in your own "
              "model, provenance: assumption at the top)");
    g_free(found);
    return FALSE;
}

static gboolean check_param_map(const CfgNode *p, const char *name, MachType t,
                                GError **err)
{
    const CfgNode *v = cfg_get(p, "value");
    if (!v) {
        char *found = g_strdup_printf("parameter '%s' without a value", name);
        cfg_error(err, p, found, "value: <number with unit>");
        g_free(found);
        return FALSE;
    }
    if (!check_provenance(p, name, err))
        return FALSE;
    (void)cfg_get(p, "note"); /* optional free text */
    if (is_list(t) ? !check_list(v, t, err) : !check_unit(v, t, err))
        return FALSE;
    return check_typed(p, "value", t, err);
}

/* One parameter `key` of `map`: a provenance map, or a bare override. */
static gboolean check_param(const CfgNode *map, const char *key, MachType t,
                            const char *model_file, GError **err)
{
    const CfgNode *p = cfg_get(map, key);
    if (cfg_kind(p) == CFG_MAP)
        return check_param_map(p, key, t, err);
    gboolean override = model_file && g_strcmp0(cfg_file(p), model_file);
    if (!override && !assume(key)) {
        char *found = g_strdup_printf("bare value for '%s'", key);
        cfg_error(err, p, found,
                  "{value: ..., source|calibrated|assumption: ...} (or "
                  "provenance: assumption at the top of your own model)");
        g_free(found);
        return FALSE;
    }
    if (is_list(t) ? !check_list(p, t, err) : !check_unit(p, t, err))
        return FALSE;
    return check_typed(map, key, t, err);
}

/* A kind's `costs` (times) or `cycles` (numbers: work.h) map. */
static gboolean check_costs(const CfgNode *costs, MachType t,
                            const char *model_file, GError **err)
{
    if (cfg_kind(costs) != CFG_MAP) {
        cfg_error(err, costs,
                  t == MACH_T_TIME ? "a non-map costs section"
                                   : "a non-map cycles section",
                  t == MACH_T_TIME
                      ? "a map of operation: {value: <time>, source: ...}"
                      : "a map of work class: {value: <cycles>, source: "
                        "...}");
        return FALSE;
    }
    for (guint i = 0; i < cfg_map_len(costs); i++) {
        const char *op = cfg_map_key(costs, i);
        if (!check_param(costs, op, t, model_file, err))
            return FALSE;
    }
    return TRUE;
}

/* A kind's processor description (work.h): every cycles: key a work
 * class priced by cycles, and a clock to count them at. */
static gboolean check_cycles(const CfgNode *kind, const CfgNode *cycles,
                             GError **err)
{
    for (guint i = 0; cycles && i < cfg_map_len(cycles); i++) {
        const char *name = cfg_map_key(cycles, i);
        MachWorkClass c;
        if (!mach_work_class_find(name, &c) || c == MACH_W_MEMBYTE) {
            char *found = g_strdup_printf("work class '%s'", name);
            cfg_error(err, cfg_map_value(cycles, i), found,
                      "one of: vertex, setup, pixel, zcmp, flop, instr, "
                      "miss (membyte is priced by memory_bandwidth)");
            g_free(found);
            return FALSE;
        }
    }
    if (cycles && !cfg_get(kind, "clock")) {
        cfg_error(err, cycles, "cycles: without the kind's clock",
                  "clock: {value: <frequency>, source: ...} beside it");
        return FALSE;
    }
    return TRUE;
}

static gboolean unknown_key(const CfgNode *at, const char *key,
                            const MachKeyType *table, const char *extra,
                            GError **err)
{
    char *found = g_strdup_printf("unknown key '%s'", key);
    char *exp = key_list(table, extra);
    cfg_error(err, at, found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

static gboolean check_kind(const CfgNode *kind, const char *model_file,
                           GError **err)
{
    if (cfg_kind(kind) != CFG_MAP) {
        cfg_error(err, kind, "a non-map node kind",
                  "a map with count:, costs: ...");
        return FALSE;
    }
    if (!cfg_get(kind, "count")) {
        cfg_error(err, kind, "a node kind without count",
                  "count: {value: N, "
                  "source: ...}");
        return FALSE;
    }
    for (guint i = 0; i < cfg_map_len(kind); i++) {
        const char *key = cfg_map_key(kind, i);
        MachType t;
        if (!strcmp(key, "costs") || !strcmp(key, "cycles")) {
            if (!check_costs(cfg_map_value(kind, i),
                             key[1] == 'o' ? MACH_T_TIME : MACH_T_NUMBER,
                             model_file, err) ||
                (key[1] == 'y' &&
                 !check_cycles(kind, cfg_map_value(kind, i), err)))
                return FALSE;
        } else if (!mach_kind_key_type(key, &t)) {
            return unknown_key(cfg_map_value(kind, i), key, kind_keys,
                               "costs, cycles", err);
        } else if (!check_param(kind, key, t, model_file, err)) {
            return FALSE;
        }
    }
    return TRUE;
}

/* A kind's name is one step of a key path (--set machine.nodes.KIND.count,
 * which partitions write too): letters, digits, '_' and '-'. */
static gboolean check_kind_name(const CfgNode *nodes, guint i, GError **err)
{
    const char *name = cfg_map_key(nodes, i);
    if (*name && strspn(name, "abcdefghijklmnopqrstuvwxyz"
                              "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") ==
                     strlen(name))
        return TRUE;
    char *found = g_strdup_printf("node kind name '%s'", name);
    cfg_error(err, cfg_map_value(nodes, i), found,
              "a name of letters, digits, '_' and '-' (a step of "
              "--set machine.nodes.KIND.count)");
    g_free(found);
    return FALSE;
}

static gboolean check_nodes(const CfgNode *nodes, const char *model_file,
                            GError **err)
{
    if (cfg_kind(nodes) != CFG_MAP || cfg_map_len(nodes) == 0) {
        cfg_error(err, nodes, "an empty or non-map nodes section",
                  "a map of node kinds (gp:, renderer: ...)");
        return FALSE;
    }
    for (guint i = 0; i < cfg_map_len(nodes); i++) {
        if (!check_kind_name(nodes, i, err) ||
            !check_kind(cfg_map_value(nodes, i), model_file, err))
            return FALSE;
    }
    return TRUE;
}

static gboolean check_network(const CfgNode *net, const char *model_file,
                              GError **err)
{
    if (cfg_kind(net) != CFG_MAP || !cfg_get(net, "topology")) {
        cfg_error(
            err, net, "a network section without topology",
            "topology: {value: ring|hypercube|fat-tree|..., source: ...}");
        return FALSE;
    }
    for (guint i = 0; i < cfg_map_len(net); i++) {
        const char *key = cfg_map_key(net, i);
        MachType t;
        if (!mach_net_key_type(key, &t))
            return unknown_key(cfg_map_value(net, i), key, net_keys, NULL, err);
        if (!check_param(net, key, t, model_file, err))
            return FALSE;
    }
    return TRUE;
}

static gboolean check_references(const CfgNode *refs, GError **err)
{
    if (cfg_kind(refs) != CFG_MAP) {
        cfg_error(err, refs, "a non-map references section",
                  "a map of key: \"citation\"");
        return FALSE;
    }
    for (guint i = 0; i < cfg_map_len(refs); i++) {
        const char *key = cfg_map_key(refs, i);
        const char *s;
        if (!cfg_get_str(refs, key, TRUE, &s, err))
            return FALSE;
    }
    return TRUE;
}

/* A provenance value: a non-empty string or a non-empty list of cells. */
static gboolean provenance_ok(const CfgNode *v)
{
    if (cfg_kind(v) == CFG_SEQ)
        return cfg_seq_len(v) > 0;
    const char *s = cfg_scalar(v);
    return s && *s;
}

/* A workload's own section (e.g. `pphigs:`): entries {value, unit?,
 * provenance, note?}, or a bare scalar from another file than the
 * model's (an override: `--set machine.dpscan.op=3 us`, as for costs);
 * the workload parses the values. */
static gboolean check_workload_entry(const CfgNode *e, const char *name,
                                     const char *model_file, GError **err)
{
    if (cfg_kind(e) == CFG_SCALAR && model_file &&
        g_strcmp0(cfg_file(e), model_file))
        return TRUE;
    if (cfg_kind(e) != CFG_MAP || !cfg_get(e, "value")) {
        char *found = g_strdup_printf("workload parameter '%s' without a "
                                      "value",
                                      name);
        cfg_error(err, e, found,
                  "{value: ..., unit: ..., source|"
                  "calibrated|assumption: ...}");
        g_free(found);
        return FALSE;
    }
    cfg_mark_read(cfg_get(e, "value"));
    (void)cfg_get(e, "unit");
    (void)cfg_get(e, "note");
    gboolean found_any = FALSE;
    for (const char *const *k = mach_provenance_keys; *k; k++) {
        const CfgNode *v = cfg_get(e, *k);
        if (v && !provenance_ok(v)) {
            cfg_error(err, v, "an empty provenance",
                      "a citation, an explanation or a list of cells");
            return FALSE;
        }
        if (v)
            cfg_mark_read(v);
        found_any = found_any || v;
    }
    if (found_any)
        return TRUE;
    char *found = g_strdup_printf("parameter '%s' without a provenance", name);
    cfg_error(err, e, found, "one of source:, calibrated: or assumption:");
    g_free(found);
    return FALSE;
}

static gboolean check_workload_section(const CfgNode *sec,
                                       const char *model_file, GError **err)
{
    if (cfg_kind(sec) != CFG_MAP) {
        cfg_error(err, sec, "a non-map top-level section",
                  "nodes:, network:, references: or a workload's map of "
                  "parameters");
        return FALSE;
    }
    for (guint i = 0; i < cfg_map_len(sec); i++)
        if (!check_workload_entry(cfg_map_value(sec, i), cfg_map_key(sec, i),
                                  model_file, err))
            return FALSE;
    return TRUE;
}

static const char *const top_keys[] = {"schema_version", "name",  "description",
                                       "references",     "nodes", "network",
                                       "model",          "provenance",
                                       NULL};

static gboolean is_top_key(const char *k)
{
    for (const char *const *t = top_keys; *t; t++)
        if (strcmp(*t, k) == 0)
            return TRUE;
    return FALSE;
}

static gboolean check_workload_sections(const CfgNode *root,
                                        const char *model_file, GError **err)
{
    for (guint i = 0; i < cfg_map_len(root); i++) {
        const CfgNode *v = cfg_map_value(root, i);
        if (!is_top_key(cfg_map_key(root, i)) &&
            !check_workload_section(v, model_file, err))
            return FALSE;
    }
    return TRUE;
}

static gboolean check_header(const CfgNode *root, GError **err)
{
    int64_t version = 0;
    const char *s;
    if (cfg_kind(root) != CFG_MAP) {
        cfg_error(err, root, "a non-map document", "a machine model map");
        return FALSE;
    }
    if (!cfg_get_int(root, "schema_version", TRUE, 1, 1, &version, err) ||
        !cfg_get_str(root, "name", TRUE, &s, err) ||
        !cfg_get_str(root, "description", FALSE, &s, err) ||
        !cfg_get_str(root, "model", FALSE, &s, err))
        return FALSE;
    const CfgNode *refs = cfg_get(root, "references");
    return !refs || check_references(refs, err);
}

/* TRUE when path lies in a shipped models/ folder (under a data root). */
static gboolean shipped(const char *path)
{
    if (!path)
        return FALSE;
    char *dir = g_path_get_dirname(path);
    char *c = g_canonicalize_filename(dir, NULL);
    GPtrArray *roots = sim_data_roots();
    gboolean yes = FALSE;
    for (guint i = 0; !yes && i < roots->len; i++) {
        char *m = g_build_filename(roots->pdata[i], "models", NULL);
        char *cm = g_canonicalize_filename(m, NULL);
        yes = strcmp(cm, c) == 0;
        g_free(cm);
        g_free(m);
    }
    g_ptr_array_free(roots, TRUE);
    g_free(c);
    g_free(dir);
    return yes;
}

/* `provenance: assumption` at the top of a user's model; FALSE with *err
 * for another word or in a shipped model. */
static gboolean read_default(const CfgNode *root, const char *model_file,
                             gboolean *on, GError **err)
{
    const CfgNode *v = cfg_get(root, "provenance");
    *on = v != NULL;
    if (!v)
        return TRUE;
    if (g_strcmp0(cfg_scalar(v), "assumption") != 0) {
        cfg_error(err, v, "a provenance default other than 'assumption'",
                  "provenance: assumption");
        return FALSE;
    }
    if (shipped(model_file)) {
        cfg_error(err, v, "provenance: assumption in a shipped model",
                  "a source, calibration or assumption on every value");
        return FALSE;
    }
    return TRUE;
}

/* One warning per model file listing the values taken without a source. */
static void warn_assumed(const char *model_file)
{
    static GHashTable *warned;
    if (!assumed->len)
        return;
    if (!warned)
        warned = g_hash_table_new_full(g_str_hash, g_str_equal, g_free, NULL);
    const char *f = model_file ? model_file : "<inline machine>";
    if (!g_hash_table_add(warned, g_strdup(f)))
        return;
    GString *s = g_string_new(NULL);
    for (guint i = 0; i < assumed->len; i++)
        g_string_append_printf(s, "%s%s", i ? ", " : "",
                               (const char *)assumed->pdata[i]);
    g_printerr("pgsim: warning: %s: %u values without a source, taken as "
               "assumptions (provenance: assumption): %s\n",
               f, assumed->len, s->str);
    g_string_free(s, TRUE);
}

static gboolean check_body(const CfgNode *root, const char *model_file,
                           GError **err);

gboolean mach_model_check(const CfgNode *root, const char *model_file,
                          GError **err)
{
    gboolean on = FALSE;
    if (!check_header(root, err) || !read_default(root, model_file, &on, err))
        return FALSE;
    if (on)
        assumed = g_ptr_array_new_with_free_func(g_free);
    gboolean ok = check_body(root, model_file, err);
    if (on) {
        if (ok)
            warn_assumed(model_file);
        g_ptr_array_free(assumed, TRUE);
        assumed = NULL;
    }
    return ok;
}

static gboolean check_body(const CfgNode *root, const char *model_file,
                           GError **err)
{
    const CfgNode *nodes = cfg_get(root, "nodes");
    const CfgNode *net = cfg_get(root, "network");
    if (!nodes || !net) {
        cfg_error(err, root, nodes ? "no network section" : "no nodes section",
                  "both nodes: and network:");
        return FALSE;
    }
    if (!check_nodes(nodes, model_file, err) ||
        !check_network(net, model_file, err) ||
        !check_workload_sections(root, model_file, err))
        return FALSE;
    return cfg_check_unused(root, err);
}

/* ---- loading by name ---------------------------------------------------- */

CfgNode *mach_load_model_in(const char *name, const char *const *extra,
                            GError **err)
{
    char *path = mach_model_path_in(name, extra, err);
    if (!path)
        return NULL;
    CfgNode *root = cfg_load_file(path, err);
    if (root)
        sim_inputs_note_file("model", path);
    if (root && !mach_model_check(root, cfg_file(root), err)) {
        cfg_free(root);
        root = NULL;
    }
    g_free(path);
    return root;
}

CfgNode *mach_load_model(const char *name, GError **err)
{
    return mach_load_model_in(name, NULL, err);
}
