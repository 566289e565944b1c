/* machine.c — machine assembly from a checked model tree.
 *
 * mach_new_from_cfg(): resolve `model:` (load + deep-merge the section
 * over it, model.h), check the merged tree, then build node kinds (in
 * model order) with their cost tables and a page table of processors.
 *
 * Invariants: kinds[k].first + kinds[k].count == kinds[k+1].first; the
 * processor pages cover sum(count) ids, each page made on first use;
 * every cost table value is a SimTime read from a checked parameter; net
 * is NULL exactly when net_err is set.
 * Cost: O(model size + processors / 64) to build; O(processors) only for
 * mach_fill_result(); the network holds no per-link state until messages
 * flow.
 */
#include "sim/machine/machine.h"
#include "sim/machine/mnet.h"
#include "sim/machine/model.h"
#include <string.h>

typedef struct {
    MachKindInfo info;
    char *name;
    GHashTable *costs; /* op (borrowed from tree) -> MachCost * (costs.h) */
    const CfgNode *at;
} MachKind;

struct MachMachine {
    SimEngine *eng;
    CfgNode *tree; /* owned: merged, checked model */
    char *name;
    char *fidelity;
    GArray *kinds;    /* MachKind */
    MachProc **pages; /* PROC_PAGE processors each, NULL until used */
    guint n_procs;
    const CfgNode *network;
    NetTopo *topo; /* NULL when the topology is not built yet */
    NetNet *net;
    GError *net_err; /* why net is NULL */
};

/* Upper bound on processors: one page pointer per PROC_PAGE of them. */
#define MACH_MAX_PROCS (1u << 24)
/* Processors are allocated a page at a time, when one is first asked for
 * (model only what is touched: a 64K-node machine whose processors never
 * compute holds 1,024 NULL page pointers, not 64K MachProcs). */
#define PROC_PAGE 64u

/* ---- building ------------------------------------------------------------ */

static gboolean read_costs(MachKind *k, const CfgNode *kind, GError **err)
{
    k->costs = mach_cost_table_new(k->name, cfg_get(kind, "costs"), err);
    k->info.costs = k->costs; /* for mach_proc_compute_ops() */
    return k->costs != NULL && mach_proc_desc_read(kind, &k->info.desc, err);
}

static gboolean read_kind(MachKind *k, const char *name, const CfgNode *kind,
                          GError **err)
{
    uint64_t count = 0, lanes = 1;
    k->name = g_strdup(name);
    k->at = kind;
    k->info.name = k->name;
    if (!mach_param_count(kind, "count", TRUE, &count, err) ||
        !mach_param_freq(kind, "clock", FALSE, &k->info.clock_hz, err) ||
        !mach_param_size(kind, "memory", FALSE, &k->info.memory, err) ||
        !mach_param_count(kind, "lanes", FALSE, &lanes, err) ||
        !mach_param_size(kind, "lane_memory", FALSE, &k->info.lane_memory, err))
        return FALSE;
    if (count > MACH_MAX_PROCS || lanes == 0) {
        cfg_error(
            err,
            mach_param_node(kind, count > MACH_MAX_PROCS ? "count" : "lanes"),
            count > MACH_MAX_PROCS ? "more than 16M processors" : "zero lanes",
            "a count in 0 .. 16M (lanes >= 1)");
        return FALSE;
    }
    k->info.count = (guint)count;
    k->info.lanes = lanes;
    return read_costs(k, kind, err);
}

static gboolean build_kinds(MachMachine *m, GError **err)
{
    const CfgNode *nodes = cfg_get(m->tree, "nodes");
    const CfgNode *roles = cfg_get(m->tree, "roles");
    guint first = 0, n = cfg_map_len(nodes);
    for (guint j = 0; j < 2 * n; j++) {
        /* kinds carved for roles (roles.h) first: a workload's processor
         * i is then machine processor i, as on the papers' machines */
        guint i = j % n;
        if ((j < n) != (roles && cfg_get(roles, cfg_map_key(nodes, i))))
            continue;
        MachKind k = {0};
        gboolean ok =
            read_kind(&k, cfg_map_key(nodes, i), cfg_map_value(nodes, i), err);
        k.info.first = first;
        g_array_append_val(m->kinds, k);
        if (!ok)
            return FALSE;
        first += k.info.count;
        if (first > MACH_MAX_PROCS) {
            cfg_error(err, k.at, "more than 16M processors in all",
                      "fewer processors");
            return FALSE;
        }
    }
    g_assert(m->kinds->len <= G_MAXUINT16);
    m->n_procs = first;
    return TRUE;
}

static guint n_pages(const MachMachine *m)
{
    return (m->n_procs + PROC_PAGE - 1) / PROC_PAGE;
}

static void build_procs(MachMachine *m)
{
    m->pages = g_new0(MachProc *, n_pages(m)); /* NULL for no processors */
}

/* The kind index of processor id. */
static guint16 kind_of(const MachMachine *m, guint id)
{
    guint k = 0;
    while (id >= mach_kind_at(m, k)->first + mach_kind_at(m, k)->count)
        k++;
    return (guint16)k;
}

/* Processor id, its page made on first use. */
static MachProc *proc_get(const MachMachine *mc, guint id)
{
    MachMachine *m = (MachMachine *)mc;
    g_assert(id < m->n_procs);
    MachProc **pg = &m->pages[id / PROC_PAGE];
    if (!*pg) {
        guint base = id - id % PROC_PAGE;
        *pg = g_new0(MachProc, PROC_PAGE);
        for (guint i = 0; i < PROC_PAGE && base + i < m->n_procs; i++) {
            guint16 k = kind_of(m, base + i);
            mach_proc_init(&(*pg)[i], m, m->eng, mach_kind_at(m, k), base + i,
                           k);
        }
    }
    return &(*pg)[id % PROC_PAGE];
}

/* Network endpoints: the processors in id order; for the CM-200 router,
 * the lanes of the widest SIMD kind.  *count_at: the count behind it. */
static guint endpoint_count(const MachMachine *m, const char *topo,
                            const CfgNode **count_at)
{
    const MachKind *last =
        &g_array_index(m->kinds, MachKind, m->kinds->len - 1);
    *count_at = mach_param_node(last->at, "count");
    if (g_strcmp0(topo, "cm-router") != 0)
        return m->n_procs;
    const MachKind *wide = last;
    for (guint k = 0; k < m->kinds->len; k++) {
        const MachKind *kk = &g_array_index(m->kinds, MachKind, k);
        if (kk->info.lanes > wide->info.lanes)
            wide = kk;
    }
    *count_at = mach_param_node(wide->at, "lanes");
    if (!*count_at)
        *count_at = mach_param_node(wide->at, "count");
    return (guint)MIN(wide->info.lanes, G_MAXUINT);
}

/* "faithful": the model's network.fidelity (the transport that models
 * its hardware); a model that names none keeps the analytic model.  The
 * machine's fidelity becomes "<word> (faithful)". */
static gboolean resolve_faithful(MachMachine *m, GError **err)
{
    if (strcmp(m->fidelity, MACH_FIDELITY_FAITHFUL) != 0)
        return TRUE;
    const char *w = mach_param_word(m->network, "fidelity");
    NetFidelity fid;
    if (w && !net_fidelity_parse(w, &fid)) {
        char *found = g_strdup_printf("fidelity '%s'", w);
        cfg_error(err, mach_param_node(m->network, "fidelity"), found,
                  "analytic, flow or packet");
        g_free(found);
        return FALSE;
    }
    g_free(m->fidelity);
    m->fidelity = g_strdup_printf("%s (faithful)", w ? w : "analytic");
    return TRUE;
}

static gboolean build_net(MachMachine *m, GError **err)
{
    NetParams par;
    NetFidelity fid;
    if (!resolve_faithful(m, err))
        return FALSE;
    char *word = g_strndup(m->fidelity, strcspn(m->fidelity, " "));
    gboolean known = net_fidelity_parse(word, &fid);
    g_free(word);
    if (!known) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "found fidelity '%s', expected analytic, flow, packet "
                    "or faithful",
                    m->fidelity);
        return FALSE;
    }
    if (!mach_net_params(m->network, &par, err))
        return FALSE;
    const char *topo = mach_param_word(m->network, "topology");
    if (!mach_topo_supported(topo)) {
        const CfgNode *at = mach_param_node(m->network, "topology");
        char *found = g_strdup_printf("topology '%s' (not yet built by the "
                                      "machine layer)",
                                      topo);
        cfg_error(&m->net_err, at, found,
                  "hypercube, ring, fat-tree, cm-router, mesh, torus, "
                  "crossbar or bus");
        g_free(found);
        return TRUE;
    }
    const CfgNode *count_at;
    guint endpoints = endpoint_count(m, topo, &count_at);
    m->topo = mach_topo_new(m->network, endpoints, count_at, err);
    if (!m->topo)
        return FALSE;
    m->net = net_new(m->eng, m->topo, &par, fid);
    return TRUE;
}

CfgNode *mach_section_tree_in(const CfgNode *section,
                              const char *const *model_dirs, char **model_file,
                              GError **err)
{
    const char *model = NULL;
    if (cfg_kind(section) != CFG_MAP) {
        cfg_error(err, section, "a non-map machine section",
                  "a map with model: <name> and overrides");
        return NULL;
    }
    if (!cfg_get_str(section, "model", FALSE, &model, err))
        return NULL;
    if (!model) { /* inline: the run config's schema_version covers it */
        *model_file = g_strdup(cfg_file(section));
        CfgNode *copy = cfg_copy(section);
        if (!cfg_get(copy, "schema_version"))
            cfg_set_override(copy, "schema_version=1", NULL);
        return copy;
    }
    CfgNode *tree = mach_load_model_in(model, model_dirs, err);
    if (!tree) {
        g_prefix_error(err, "%s:%d:%d: ", cfg_file(section), cfg_line(section),
                       cfg_col(section));
        return NULL;
    }
    *model_file = g_strdup(cfg_file(tree));
    cfg_merge(tree, section);
    return tree;
}

static MachMachine *machine_alloc(SimEngine *eng, const char *fidelity)
{
    MachMachine *m = g_new0(MachMachine, 1);
    m->eng = eng;
    m->fidelity = g_strdup(fidelity ? fidelity : "analytic");
    m->kinds = g_array_new(FALSE, TRUE, sizeof(MachKind));
    return m;
}

/* Traces name network endpoints as the processors with those ids. */
static const char *node_name(void *ctx, uint32_t node)
{
    MachMachine *m = ctx;
    return node < m->n_procs ? mach_proc_name(mach_proc_at(m, node)) : NULL;
}

static MachMachine *build(SimEngine *eng, CfgNode *tree, const char *model_file,
                          const char *fidelity, GError **err)
{
    MachMachine *m = machine_alloc(eng, fidelity);
    m->tree = tree;
    const char *name = NULL;
    if (!mach_model_check(tree, model_file, err) ||
        !cfg_get_str(tree, "name", TRUE, &name, err) || !build_kinds(m, err)) {
        mach_free(m);
        return NULL;
    }
    m->name = g_strdup(name);
    m->network = cfg_get(tree, "network");
    build_procs(m);
    if (!build_net(m, err)) {
        mach_free(m);
        return NULL;
    }
    sim_engine_set_node_namer(eng, node_name, m);
    return m;
}

CfgNode *mach_section_tree(const CfgNode *section, char **model_file,
                           GError **err)
{
    return mach_section_tree_in(section, NULL, model_file, err);
}

MachMachine *mach_new_from_cfg_in(SimEngine *eng, const CfgNode *section,
                                  const char *fidelity,
                                  const char *const *model_dirs, GError **err)
{
    g_assert(eng && section);
    char *model_file = NULL;
    CfgNode *tree = mach_section_tree_in(section, model_dirs, &model_file, err);
    MachMachine *m = tree ? build(eng, tree, model_file, fidelity, err) : NULL;
    g_free(model_file);
    if (m)
        cfg_mark_read(section);
    return m;
}

MachMachine *mach_new_from_cfg(SimEngine *eng, const CfgNode *section,
                               const char *fidelity, GError **err)
{
    return mach_new_from_cfg_in(eng, section, fidelity, NULL, err);
}

gboolean mach_check_section_in(const CfgNode *section,
                               const char *const *model_dirs, GError **err)
{
    char *model_file = NULL;
    CfgNode *tree = mach_section_tree_in(section, model_dirs, &model_file, err);
    gboolean ok = tree && mach_model_check(tree, model_file, err);
    cfg_free(tree);
    g_free(model_file);
    if (ok)
        cfg_mark_read(section);
    return ok;
}

gboolean mach_check_section(const CfgNode *section, GError **err)
{
    return mach_check_section_in(section, NULL, err);
}

MachMachine *mach_new_from_model(SimEngine *eng, const char *name,
                                 const char *fidelity, GError **err)
{
    g_assert(eng);
    CfgNode *tree = mach_load_model(name, err);
    if (!tree)
        return NULL;
    char *file = g_strdup(cfg_file(tree));
    MachMachine *m = build(eng, tree, file, fidelity, err);
    g_free(file);
    return m;
}

void mach_free(MachMachine *m)
{
    if (!m)
        return;
    if (m->name) /* built: it named the engine's nodes */
        sim_engine_set_node_namer(m->eng, NULL, NULL);
    net_free(m->net);
    if (m->topo)
        net_topo_free(m->topo);
    if (m->net_err)
        g_error_free(m->net_err);
    for (guint pg = 0; m->pages && pg < n_pages(m); pg++) {
        /* slots past n_procs in the last page stay zero (g_new0), which
         * mach_proc_clear leaves alone */
        for (guint i = 0; m->pages[pg] && i < PROC_PAGE; i++)
            mach_proc_clear(&m->pages[pg][i]);
        g_free(m->pages[pg]);
    }
    g_free(m->pages);
    for (guint k = 0; k < m->kinds->len; k++) {
        MachKind *kk = &g_array_index(m->kinds, MachKind, k);
        g_free(kk->name);
        if (kk->costs)
            g_hash_table_destroy(kk->costs);
    }
    g_array_free(m->kinds, TRUE);
    cfg_free(m->tree);
    g_free(m->name);
    g_free(m->fidelity);
    g_free(m);
}

/* ---- queries ------------------------------------------------------------- */

const char *mach_name(const MachMachine *m)
{
    return m->name;
}
const char *mach_fidelity(const MachMachine *m)
{
    return m->fidelity;
}
SimEngine *mach_engine(const MachMachine *m)
{
    return m->eng;
}
const CfgNode *mach_model_cfg(const MachMachine *m)
{
    return m->tree;
}
guint mach_kind_count(const MachMachine *m)
{
    return m->kinds->len;
}
guint mach_proc_total(const MachMachine *m)
{
    return m->n_procs;
}

const MachKindInfo *mach_kind_at(const MachMachine *m, guint i)
{
    g_assert(i < m->kinds->len);
    return &g_array_index(m->kinds, MachKind, i).info;
}

static const MachKind *find_kind(const MachMachine *m, const char *kind)
{
    for (guint k = 0; k < m->kinds->len; k++) {
        const MachKind *kk = &g_array_index(m->kinds, MachKind, k);
        if (strcmp(kk->name, kind) == 0)
            return kk;
    }
    return NULL;
}

const MachKindInfo *mach_kind(const MachMachine *m, const char *kind)
{
    const MachKind *k = find_kind(m, kind);
    return k ? &k->info : NULL;
}

MachProc *mach_proc_at(MachMachine *m, guint id)
{
    return proc_get(m, id);
}

MachProc *mach_proc(MachMachine *m, const char *kind, guint i)
{
    const MachKind *k = find_kind(m, kind);
    g_assert(k && i < k->info.count);
    return proc_get(m, k->info.first + i);
}

/* ---- network parameters ------------------------------------------------ */

const CfgNode *mach_network_cfg(const MachMachine *m)
{
    return m->network;
}
NetNet *mach_net(const MachMachine *m)
{
    return m->net;
}

gboolean mach_require_net(const MachMachine *m, GError **err)
{
    if (m->net)
        return TRUE;
    g_propagate_error(err, g_error_copy(m->net_err));
    return FALSE;
}

const char *mach_net_word(const MachMachine *m, const char *key)
{
    return mach_param_word(m->network, key);
}

/* The tree was checked, so a present key always parses. */
#define NET_GET(fn, key, out)                                                  \
    do {                                                                       \
        if (!mach_param_node(m->network, key))                                 \
            return FALSE;                                                      \
        gboolean ok_ = fn(m->network, key, TRUE, out, NULL);                   \
        g_assert(ok_);                                                         \
        return TRUE;                                                           \
    } while (0)

gboolean mach_net_time(const MachMachine *m, const char *key, SimTime *out)
{
    NET_GET(mach_param_time, key, out);
}

gboolean mach_net_bandwidth(const MachMachine *m, const char *key, double *out)
{
    NET_GET(mach_param_bandwidth, key, out);
}

gboolean mach_net_size(const MachMachine *m, const char *key, uint64_t *out)
{
    NET_GET(mach_param_size, key, out);
}

gboolean mach_net_count(const MachMachine *m, const char *key, uint64_t *out)
{
    NET_GET(mach_param_count, key, out);
}

GArray *mach_net_bw_list(const MachMachine *m, const char *key)
{
    GArray *a = NULL;
    if (mach_param_node(m->network, key) &&
        !mach_param_bw_list(m->network, key, TRUE, &a, NULL))
        g_assert_not_reached();
    return a;
}

/* ---- results ------------------------------------------------------------- */

static void copy_busy(SimBusy *dst, const SimBusy *src)
{
    for (guint ph = 0; src->per_phase && ph < src->per_phase->len; ph++) {
        SimTime t = g_array_index(src->per_phase, SimTime, ph);
        if (t)
            sim_busy_add(dst, ph, t);
    }
}

/* Busy processors of one kind as nodes, the others as one idle count;
 * never-made pages (never-touched processors) are skipped whole, so this
 * is O(processors touched + pages). */
static void fill_kind(const MachMachine *m, const MachKindInfo *k,
                      SimResult *r)
{
    uint64_t idle = 0;
    guint end = k->first + k->count;
    for (guint i = k->first; i < end;) {
        const MachProc *pg = m->pages[i / PROC_PAGE];
        guint stop = MIN(end, (i / PROC_PAGE + 1) * PROC_PAGE);
        if (!pg) { /* never-touched processors were never busy */
            idle += stop - i;
            i = stop;
            continue;
        }
        for (; i < stop; i++) {
            const MachProc *p = &pg[i % PROC_PAGE];
            if (p->busy.total == 0) {
                idle++;
                continue;
            }
            char *name = g_strdup_printf("%s%u", k->name, i - k->first);
            copy_busy(&sim_result_add_node(r, name, k->name)->busy, &p->busy);
            g_free(name);
        }
    }
    if (idle)
        sim_result_add_idle(r, k->name, idle);
}

void mach_fill_result(const MachMachine *m, SimResult *r)
{
    g_free(r->machine);
    r->machine = g_strdup(m->name);
    g_free(r->fidelity);
    r->fidelity = g_strdup(m->fidelity);
    sim_result_set_phases(r, m->eng);
    for (guint k = 0; k < mach_kind_count(m); k++)
        fill_kind(m, mach_kind_at(m, k), r);
    if (m->net)
        net_fill_result(m->net, r);
    g_free(r->fidelity); /* the machine's word says "(faithful)" */
    r->fidelity = g_strdup(m->fidelity);
}
