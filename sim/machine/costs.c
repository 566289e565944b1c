/* costs.c — a machine's cost tables with provenance, and workloads' cost
 * sets (costs.h).
 *
 * Invariants: every table value is a MachCost read from a checked model
 * parameter (its value, the file and place it was written, its
 * provenance); a set holds exactly the costs its MachNeed table declared,
 * in declaration order, each borrowed from the machine's tables.
 * Cost: O(costs) to read a table; O(declared) to build a set.
 */
#include "sim/machine/costs.h"
#include "sim/core/error.h"
#include "sim/machine/machine.h"
#include <string.h>

/* ---- the machine's tables ------------------------------------------------ */

/* costs.OP of a checked tree into *c. */
static gboolean read_cost(const char *kind, const CfgNode *costs,
                          const char *op, MachCost *c, GError **err)
{
    if (!mach_param_time(costs, op, TRUE, &c->value, err))
        return FALSE;
    const CfgNode *v = mach_param_node(costs, op);
    c->from = MACH_COST_MODEL;
    c->prov = mach_param_provenance(costs, op, &c->text);
    c->kind = kind;
    c->op = op;
    c->file = cfg_file(v);
    c->line = cfg_line(v);
    c->col = cfg_col(v);
    return TRUE;
}

GHashTable *mach_cost_table_new(const char *kind, const CfgNode *costs,
                                GError **err)
{
    GHashTable *t = g_hash_table_new_full(g_str_hash, g_str_equal, NULL, g_free);
    for (guint i = 0; costs && i < cfg_map_len(costs); i++) {
        const char *op = cfg_map_key(costs, i);
        MachCost *c = g_new0(MachCost, 1);
        if (!read_cost(kind, costs, op, c, err)) {
            g_free(c);
            g_hash_table_destroy(t);
            return NULL;
        }
        g_hash_table_insert(t, (gpointer)op, c);
    }
    return t;
}

const MachCost *mach_cost_info(const MachMachine *m, const char *kind,
                               const char *op)
{
    const MachKindInfo *k = mach_kind(m, kind);
    return k && k->costs ? g_hash_table_lookup(k->costs, op) : NULL;
}

/* Where a missing cost of `kind` would go: the kind's `costs` map, else
 * the kind, else the model's `nodes` (or the model itself). */
static const CfgNode *missing_at(const MachMachine *m, const char *kind)
{
    const CfgNode *nodes = cfg_get(mach_model_cfg(m), "nodes");
    const CfgNode *k = nodes ? cfg_get(nodes, kind) : NULL;
    const CfgNode *costs = k ? cfg_get(k, "costs") : NULL;
    return costs ? costs : k ? k : nodes ? nodes : mach_model_cfg(m);
}

/* The located error for a first missing (kind, op), with what to add. */
static void first_missing(GError **err, const MachMachine *m,
                          const char *kind, const char *op, const char *rest)
{
    gboolean has_kind = mach_kind(m, kind) != NULL;
    char *found = has_kind
                      ? g_strdup_printf("no cost for '%s' on '%s'", op, kind)
                      : g_strdup_printf("no node kind '%s'", kind);
    char *exp = g_strdup_printf("costs: {%s: {value: <time>, source: ...}} "
                                "under nodes.%s in model %s%s",
                                op, kind, mach_name(m), rest ? rest : "");
    cfg_error(err, missing_at(m, kind), found, exp);
    g_free(found);
    g_free(exp);
}

SimTime mach_cost(const MachMachine *m, const char *kind, const char *op)
{
    const MachCost *c = mach_cost_info(m, kind, op);
    if (!c)
        g_error("mach_cost: no cost for '%s' on '%s' in model %s", op, kind,
                mach_name(m));
    return c->value;
}

gboolean mach_cost_lookup(const MachMachine *m, const char *kind,
                          const char *op, SimTime *out, GError **err)
{
    const MachCost *c = mach_cost_info(m, kind, op);
    if (c) {
        *out = c->value;
        return TRUE;
    }
    first_missing(err, m, kind, op, NULL);
    return FALSE;
}

gboolean mach_require_costs(const MachMachine *m, const char *kind,
                            const char *const *ops, GError **err)
{
    const MachNeed needs[] = {{kind, ops, NULL}, {NULL, NULL, NULL}};
    return mach_costs_check(m, needs, err);
}

/* ---- a workload's cost set ----------------------------------------------- */

struct MachCosts {
    GPtrArray *costs; /* const MachCost *, borrowed, declaration order */
};

/* The work `needs` declares for (kind, op), or NULL. */
static const MachWork *declared_work(const MachNeed *needs, const char *kind,
                                     const char *op)
{
    for (const MachNeed *k = needs; k->kind; k++)
        if (!strcmp(k->kind, kind) && mach_work_find(k->work, op))
            return mach_work_find(k->work, op);
    return NULL;
}

/* A derived cost and its text in one block (g_free frees both). */
typedef struct {
    MachCost c;
    char text[];
} DerivedCost;

/* Derives (kind, op) from w on the kind's processor description into
 * the kind's table; FALSE and *missing when some class is unpriced. */
static gboolean derive(const MachKindInfo *k, const MachWork *w,
                       MachWorkClass *missing)
{
    SimTime t;
    if (!mach_work_price(&k->desc, w, &t, missing) || !k->desc.any)
        return FALSE; /* no description: *missing is w's first class */
    char *work = mach_work_describe(w);
    char *text = g_strdup_printf("%s on the processor description of "
                                 "nodes.%s",
                                 work, k->name);
    DerivedCost *d = g_malloc0(sizeof *d + strlen(text) + 1);
    strcpy(d->text, text);
    d->c = (MachCost){.value = t,
                      .from = MACH_COST_DERIVED,
                      .prov = MACH_PROV_ASSUMPTION,
                      .kind = k->name,
                      .op = w->op,
                      .file = cfg_file(k->desc.at),
                      .line = cfg_line(k->desc.at),
                      .col = cfg_col(k->desc.at),
                      .text = d->text};
    memcpy(d->c.work, w->n, sizeof d->c.work);
    g_hash_table_insert(k->costs, (gpointer)w->op, d);
    g_free(work);
    g_free(text);
    return TRUE;
}

/* The cost of (kind, op): explicit, derived before, or derived now from
 * the declared work; NULL when none.  *missing: the unpriced class, or
 * MACH_W_N when the op declares no work or the kind no description. */
static const MachCost *resolve(const MachMachine *m, const MachNeed *needs,
                               const char *kind, const char *op,
                               MachWorkClass *missing)
{
    *missing = MACH_W_N;
    const MachCost *c = mach_cost_info(m, kind, op);
    const MachKindInfo *k = mach_kind(m, kind);
    const MachWork *w = declared_work(needs, kind, op);
    if (c || !k || !w || !derive(k, w, missing))
        return c;
    return mach_cost_info(m, kind, op);
}

/* One line of the list of missing costs. */
static void list_missing(GString *s, const MachMachine *m, const char *kind,
                         const char *op, MachWorkClass missing)
{
    const CfgNode *at = missing_at(m, kind);
    g_string_append_printf(s, "\n  %s:%d:%d: nodes.%s.costs.%s",
                           cfg_file(at), cfg_line(at), cfg_col(at), kind, op);
    if (missing < MACH_W_N)
        g_string_append_printf(s, " (or nodes.%s.cycles.%s to derive it)",
                               kind,
                               missing == MACH_W_MEMBYTE
                                   ? "memory_bandwidth"
                                   : mach_work_class_name(missing));
}

/* Every missing cost of needs in one located error (the first one's
 * place), listing each; FALSE when some is missing.  Derives what the
 * declared work and the kinds' descriptions allow. */
static gboolean report_missing(const MachMachine *m, const MachNeed *needs,
                               GError **err)
{
    GString *list = g_string_new(NULL);
    const char *kind0 = NULL, *op0 = NULL;
    guint n = 0;
    for (const MachNeed *k = needs; k->kind; k++)
        for (const char *const *op = k->ops; *op; op++) {
            MachWorkClass missing;
            if (resolve(m, needs, k->kind, *op, &missing))
                continue;
            if (!n++) {
                kind0 = k->kind;
                op0 = *op;
            }
            list_missing(list, m, k->kind, *op, missing);
        }
    if (n) {
        char *rest = g_strdup_printf("; %u missing in all:%s", n, list->str);
        first_missing(err, m, kind0, op0, rest);
        g_free(rest);
    }
    g_string_free(list, TRUE);
    return n == 0;
}

MachCosts *mach_costs_new(const MachMachine *m, const MachNeed *needs,
                          GError **err)
{
    if (!report_missing(m, needs, err))
        return NULL;
    MachCosts *c = g_new0(MachCosts, 1);
    c->costs = g_ptr_array_new();
    for (const MachNeed *k = needs; k->kind; k++)
        for (const char *const *op = k->ops; *op; op++)
            if (!mach_costs_find(c, k->kind, *op)) /* declared twice: once */
                g_ptr_array_add(c->costs,
                                (gpointer)mach_cost_info(m, k->kind, *op));
    return c;
}

void mach_costs_free(MachCosts *c)
{
    if (!c)
        return;
    g_ptr_array_free(c->costs, TRUE);
    g_free(c);
}

gboolean mach_costs_check(const MachMachine *m, const MachNeed *needs,
                          GError **err)
{
    return report_missing(m, needs, err);
}

const MachCost *mach_costs_find(const MachCosts *c, const char *kind,
                                const char *op)
{
    for (guint i = 0; i < c->costs->len; i++) {
        const MachCost *k = g_ptr_array_index(c->costs, i);
        if (!strcmp(k->op, op) && !strcmp(k->kind, kind))
            return k;
    }
    return NULL;
}

SimTime mach_costs_get(const MachCosts *c, const char *kind, const char *op)
{
    const MachCost *k = mach_costs_find(c, kind, op);
    g_assert(k); /* declared in the workload's MachNeed table */
    return k->value;
}

SimTime mach_costs_times(const MachCosts *c, const char *kind, const char *op,
                         uint64_t n)
{
    return sim_time_mul_sat(mach_costs_get(c, kind, op), n);
}

void mach_costs_fill(const MachCosts *c, const char *kind,
                     const char *const *ops, SimTime *const *dst)
{
    for (guint i = 0; ops[i]; i++)
        *dst[i] = mach_costs_get(c, kind, ops[i]);
}

guint mach_costs_len(const MachCosts *c)
{
    return c->costs->len;
}

const MachCost *mach_costs_nth(const MachCosts *c, guint i)
{
    g_assert(i < c->costs->len);
    return g_ptr_array_index(c->costs, i);
}

/* A short time for a note: "2.667 ns", "95.56 us". */
static void append_time(GString *s, SimTime t)
{
    double ns = (double)t / 1e3;
    if (ns < 1e3)
        g_string_append_printf(s, "%.4g ns", ns);
    else if (ns < 1e6)
        g_string_append_printf(s, "%.4g us", ns / 1e3);
    else
        g_string_append_printf(s, "%.4g ms", ns / 1e6);
}

static gint by_op(gconstpointer a, gconstpointer b)
{
    return strcmp((*(const MachCost *const *)a)->op,
                  (*(const MachCost *const *)b)->op);
}

void mach_costs_note_derived(const MachKindInfo *k, SimResult *r)
{
    GPtrArray *d = g_ptr_array_new();
    GHashTableIter it;
    gpointer v;
    g_hash_table_iter_init(&it, k->costs);
    while (g_hash_table_iter_next(&it, NULL, &v))
        if (((const MachCost *)v)->from == MACH_COST_DERIVED)
            g_ptr_array_add(d, v);
    g_ptr_array_sort(d, by_op);
    GString *s = g_string_new(NULL);
    for (guint i = 0; i < d->len; i++) {
        const MachCost *c = g_ptr_array_index(d, i);
        MachWork w = {c->op, {0}};
        memcpy(w.n, c->work, sizeof w.n);
        char *work = mach_work_describe(&w);
        g_string_append_printf(s, "%s%s ", i ? "; " : "", c->op);
        append_time(s, c->value);
        g_string_append_printf(s, " (%s)", work);
        g_free(work);
    }
    if (d->len) {
        const MachCost *c0 = g_ptr_array_index(d, 0);
        char *base = g_path_get_basename(c0->file);
        char *note = g_strdup_printf(
            "costs derived on %s from its processor description (%s:%d:%d): "
            "%s",
            k->name, base, c0->line, c0->col, s->str);
        g_free(base);
        sim_result_add_note(r, note);
        g_free(note);
    }
    g_string_free(s, TRUE);
    g_ptr_array_free(d, TRUE);
}

const char *mach_cost_from_name(MachCostFrom f)
{
    return f == MACH_COST_DERIVED ? "derived" : "model";
}

char *mach_cost_describe(const MachCost *c)
{
    return g_strdup_printf("nodes.%s.costs.%s = %.6g us (%s, %s, %s:%d:%d)",
                           c->kind, c->op, sim_time_to_us(c->value),
                           mach_cost_from_name(c->from),
                           mach_provenance_name(c->prov), c->file, c->line,
                           c->col);
}
