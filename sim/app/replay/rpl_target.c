/* rpl_target.c — building the replay machine, mapping, pricing
 * (rpl_target.h).  Cost: O(model) to build, O(trace processors) for the
 * map, O(1) per priced action (one hash lookup per operation name).
 */
#include "sim/app/replay/rpl_target.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include "sim/machine/model.h"
#include "sim/machine/partition.h"
#include <math.h>
#include <string.h>

guint rpl_map_block(guint p, guint n, guint t)
{
    guint per = (n + t - 1) / t;
    return p / MAX(per, 1);
}

guint rpl_map_cyclic(guint p, guint n, guint t)
{
    (void)n;
    return p % t;
}

/* The model tree with the overrides of root's machine section, kept for
 * the costs named by a model path (`dpscan.op`); NULL if it fails. */
static CfgNode *model_tree(const CfgNode *root)
{
    char *file = NULL;
    CfgNode *tree = mach_section_tree(cfg_get(root, "machine"), &file, NULL);
    g_free(file);
    return tree;
}

/* The model o->machine, sized to o->nodes (its partition into *desc), at
 * fidelity fid (NULL: the model's faithful rung); *tree (if asked): the
 * model's tree with the overrides. */
static MachMachine *build(SimEngine *eng, char **desc, CfgNode **tree,
                          const RplReplayOpts *o, const char *fid,
                          GError **err)
{
    CfgNode *root = mach_partition_root("replay", o->machine, o->sets,
                                        o->nodes, desc, err);
    MachMachine *m =
        root ? mach_new_from_cfg(eng, cfg_get(root, "machine"),
                                 fid ? fid : MACH_FIDELITY_FAITHFUL, err)
             : NULL;
    if (m && tree)
        *tree = model_tree(root);
    cfg_free(root);
    return m;
}

/* One map-file line: "TRACE_PROC TARGET_PROC", each trace processor
 * once; FALSE with *err located. */
static gboolean map_line(RplTarget *t, RplLines *l, int n, GError **err)
{
    uint64_t p, q;
    guint total = mach_proc_total(t->m);
    char *pw = g_strdup_printf("a trace processor id below %u", t->n_trace);
    char *qw = g_strdup_printf("a target processor below %u", total);
    gboolean ok = rpl_lines_u64(l, 0, t->n_trace - 1, &p, pw, err) &&
                  rpl_lines_u64(l, 1, total - 1, &q, qw, err);
    g_free(pw);
    g_free(qw);
    if (ok && n > 2)
        g_propagate_error(err, rpl_lines_error(l, 2, "the end of the line"));
    else if (ok && t->map[p])
        g_propagate_error(
            err, rpl_lines_error(l, 0,
                                 "a trace processor not given on an earlier "
                                 "line (one line per trace processor)"));
    else if (ok)
        t->map[p] = (guint)q + 1;
    return ok && !(err && *err);
}

/* The map file: lines "TRACE_PROC TARGET_PROC" ('#' comments), one per
 * trace processor.  Memory: 4 bytes per trace processor, checked. */
static gboolean map_file(RplTarget *t, const char *path, GError **err)
{
    char *where = g_strdup_printf("%s:1:1", path);
    char *what = g_strdup_printf("a map of %u trace processors", t->n_trace);
    gboolean fits = t->n_trace > 0 &&
                    sim_mem_check(4.0 * t->n_trace, where, what, err);
    g_free(where);
    g_free(what);
    RplLines *l = fits ? rpl_lines_open(path, err) : NULL;
    if (!l) {
        if (t->n_trace == 0)
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "%s:0:0: found a trace with no processors, expected "
                        "'procs N' above 0 to map",
                        path);
        return FALSE;
    }
    t->map = g_new0(guint, t->n_trace);
    int n;
    while ((n = rpl_lines_next(l, err)) > 0 && map_line(t, l, n, err))
        ;
    for (guint i = 0; n == 0 && i < t->n_trace; i++)
        if (!t->map[i]) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "%s:%u:1: found the end of the file, expected a line "
                        "'%u TARGET_PROC' (one line per trace processor)",
                        path, rpl_lines_number(l) + 1, i);
            n = -1;
        }
    rpl_lines_free(l);
    return n == 0;
}

static gboolean make_map(RplTarget *t, const char *map, GError **err)
{
    if (map && strcmp(map, "block") && strcmp(map, "cyclic"))
        return map_file(t, map, err);
    t->cyclic = map && !strcmp(map, "cyclic");
    return TRUE;
}

guint rpl_target_map(const RplTarget *t, guint p)
{
    guint total = mach_proc_total(t->m);
    if (t->map)
        return t->map[p] - 1;
    return t->cyclic ? rpl_map_cyclic(p, t->n_trace, total)
                     : rpl_map_block(p, t->n_trace, total);
}

/* --clock KIND=HZ (HZ, kHz, MHz or GHz) into *hz; FALSE with *err. */
static gboolean parse_clock(const char *s, char **kind, double *hz,
                            GError **err)
{
    static const struct {
        const char *unit;
        double scale;
    } units[] = {{"", 1}, {"Hz", 1}, {"kHz", 1e3}, {"MHz", 1e6}, {"GHz", 1e9}};
    const char *eq = strchr(s, '=');
    char *end;
    double v = eq ? g_ascii_strtod(eq + 1, &end) : 0;
    while (eq && *end == ' ')
        end++;
    for (guint i = 0; eq && eq > s && v > 0 && i < G_N_ELEMENTS(units); i++)
        if (!strcmp(end, units[i].unit) && v * units[i].scale >= RPL_CLOCK_MIN &&
            v * units[i].scale <= RPL_CLOCK_MAX) {
            *kind = g_strndup(s, eq - s);
            *hz = v * units[i].scale;
            return TRUE;
        }
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "replay: --clock: found '%s', expected KIND=FREQUENCY from "
                "1 Hz to 1e15 Hz (40MHz, 2.5 GHz ...)",
                s);
    return FALSE;
}

static gboolean parse_clocks(RplTarget *t, const char *const *clocks,
                             GError **err)
{
    t->clocks = g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free);
    for (; clocks && *clocks; clocks++) {
        char *kind;
        double hz;
        if (!parse_clock(*clocks, &kind, &hz, err))
            return FALSE;
        g_hash_table_insert(t->clocks, kind, g_memdup2(&hz, sizeof hz));
    }
    return TRUE;
}

double rpl_target_scale(const RplTarget *t, guint p)
{
    const RplKind *rk = rpl_header_kind_of(&t->rec, p);
    MachProc *q = mach_proc_at(t->m, rpl_target_map(t, p));
    const MachKindInfo *tk = mach_kind(t->m, mach_proc_kind(q));
    const double *given = rk ? g_hash_table_lookup(t->clocks, rk->name) : NULL;
    double rhz = given ? *given : rk ? rk->clock_hz : 0;
    if (rhz > 0 && tk->clock_hz > 0)
        return rhz == tk->clock_hz ? 1 : rhz / tk->clock_hz;
    gboolean same = t->rec.machine && !strcmp(t->rec.machine, t->model) &&
                    (!rk || !strcmp(rk->name, tk->name));
    return same ? 1 : NAN;
}

/* A copy of the trace's machine name and kinds (the header need not
 * outlive the target). */
static void copy_rec(RplHeader *rec, const RplHeader *h)
{
    rec->machine = g_strdup(h->machine);
    rec->kinds = g_array_new(FALSE, FALSE, sizeof(RplKind));
    for (guint i = 0; h->kinds && i < h->kinds->len; i++) {
        RplKind k = g_array_index(h->kinds, RplKind, i);
        k.name = g_strdup(k.name);
        g_array_append_val(rec->kinds, k);
    }
}

RplTarget *rpl_target_new(const RplReplayOpts *o, const RplHeader *h,
                          GError **err)
{
    RplTarget *t = g_new0(RplTarget, 1);
    t->eng = sim_engine_new(1);
    t->n_trace = h->procs;
    t->model = g_strdup(o->machine);
    copy_rec(&t->rec, h);
    t->costs = g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free);
    /* --fidelity, else the rung the trace was recorded at (its header),
     * else the target's faithful rung (docs/traces.md, Replaying). */
    t->m = build(t->eng, &t->desc, &t->tree, o,
                 o->fidelity ? o->fidelity : h->fidelity, err);
    RplReplayOpts from = {.machine = o->costs_from};
    if (o->costs_from) {
        t->from_eng = sim_engine_new(1);
        t->from = t->m ? build(t->from_eng, NULL, NULL, &from, NULL, err) : NULL;
    }
    if (!t->m || (o->costs_from && !t->from) || !make_map(t, o->map, err) ||
        !parse_clocks(t, o->clocks, err)) {
        rpl_target_free(t);
        return NULL;
    }
    t->phase = g_new(unsigned, h->phases->len);
    for (guint i = 0; i < h->phases->len; i++)
        t->phase[i] = sim_engine_phase(t->eng, h->phases->pdata[i]);
    t->has_shm = mach_shmem_init(&t->shm, t->m, NULL);
    return t;
}

void rpl_target_free(RplTarget *t)
{
    if (!t)
        return;
    mach_free(t->m);
    sim_engine_free(t->eng);
    cfg_free(t->tree);
    if (t->from_eng) {
        mach_free(t->from);
        sim_engine_free(t->from_eng);
    }
    g_hash_table_destroy(t->costs);
    if (t->clocks)
        g_hash_table_destroy(t->clocks);
    rpl_header_clear(&t->rec);
    g_free(t->model);
    g_free(t->desc);
    g_free(t->map);
    g_free(t->phase);
    g_free(t);
}

/* --costs-from: the cost of op on kind `from` (the recording kind) of
 * that model, scaled by its clock (else --clock) / the target kind's (an
 * assumption: the operation's time scales with clock); NULL when that
 * model or either clock lacks it. */
static SimTime *borrowed_cost(const RplTarget *t, const char *kind,
                              const char *from, const char *op)
{
    const MachKindInfo *fk = mach_kind(t->from, from);
    const MachKindInfo *tk = mach_kind(t->m, kind);
    const double *given = g_hash_table_lookup(t->clocks, from);
    double fhz = fk && fk->clock_hz > 0 ? fk->clock_hz : given ? *given : 0;
    const MachCost *mc = mach_cost_info(t->from, from, op);
    if (!fk || fhz <= 0 || tk->clock_hz <= 0 || !mc)
        return NULL;
    double v = round((double)mc->value * (fhz / tk->clock_hz));
    SimTime c = v >= (double)SIM_TIME_MAX ? SIM_TIME_MAX : (SimTime)v;
    return g_memdup2(&c, sizeof c);
}

/* An operation named by a model path, SECTION.KEY: the time of that
 * parameter of the target model (a workload's own section, e.g. dpscan's
 * `dpscan.op`: docs/traces.md); NULL when absent or not a time.  No
 * node kind, no --costs-from. */
static SimTime *path_cost(const RplTarget *t, const char *op)
{
    const char *dot = strchr(op, '.');
    char *name = g_strndup(op, dot - op);
    const CfgNode *sec = t->tree ? cfg_get(t->tree, name) : NULL;
    SimTime c;
    gboolean ok = sec && cfg_kind(sec) == CFG_MAP &&
                  mach_param_node(sec, dot + 1) &&
                  mach_param_time(sec, dot + 1, TRUE, &c, NULL);
    g_free(name);
    return ok ? g_memdup2(&c, sizeof c) : NULL;
}

const SimTime *rpl_target_op_cost(RplTarget *t, guint p, const char *op,
                                  gboolean *fresh)
{
    const char *kind = mach_proc_kind(mach_proc_at(t->m, rpl_target_map(t, p)));
    const RplKind *rk = rpl_header_kind_of(&t->rec, p);
    const char *from = rk ? rk->name : kind;
    char *key = g_strconcat(kind, "\t", from, "\t", op, NULL);
    gpointer v;
    *fresh = !g_hash_table_lookup_extended(t->costs, key, NULL, &v);
    if (!*fresh) {
        g_free(key);
        return v;
    }
    SimTime *cp = NULL;
    const MachCost *mc =
        strchr(op, '.') ? NULL : mach_cost_info(t->m, kind, op);
    if (strchr(op, '.'))
        cp = path_cost(t, op);
    else if (mc)
        cp = g_memdup2(&mc->value, sizeof mc->value);
    else if (t->from)
        cp = borrowed_cost(t, kind, from, op);
    g_hash_table_insert(t->costs, key, cp);
    return cp;
}

/* Costs missing for counts priced on trace processor p's target kind. */
static void check_ops(RplTarget *t, guint p, const char *const *op,
                      const int *col, guint n, guint line, const char *path,
                      GString *bad)
{
    const char *kind = mach_proc_kind(mach_proc_at(t->m, rpl_target_map(t, p)));
    gboolean fresh;
    for (guint i = 0; i < n; i++)
        if (!rpl_target_op_cost(t, p, op[i], &fresh) && fresh)
            g_string_append_printf(bad, "\n  %s:%u:%d: %s%s%s%s", path, line,
                                   col[i], strchr(op[i], '.') ? "" : "nodes.",
                                   strchr(op[i], '.') ? "" : kind,
                                   strchr(op[i], '.') ? "" : ".costs.", op[i]);
}

/* A `|` term: its counts' costs, or a shared memory for a bus term. */
static void check_term(RplTarget *t, const RplTerm *term, guint line,
                       const char *path, GString *bad)
{
    if (!term->bus) {
        check_ops(t, term->proc, term->op, term->op_col, term->n_ops, line,
                  path, bad);
        return;
    }
    if (!t->has_shm && !t->shm_missing) {
        t->shm_missing = TRUE; /* reported once */
        g_string_append_printf(bad,
                               "\n  %s:%u:%d: a shared memory (network "
                               "{topology: bus, bandwidth, startup}) to price "
                               "the transfer time of a '| b' term",
                               path, line, term->col);
    }
}

/* Adds the problems of one item to `bad` (one line each, first seen). */
static void check_item(RplTarget *t, const RplItem *it, const char *path,
                       GString *bad, gboolean *net_missing)
{
    if (it->type != RPL_COMPUTE && it->type != RPL_WORK &&
        it->type != RPL_SEND && it->type != RPL_BUS)
        return; /* group lines and waits: nothing to price */
    const char *kind =
        mach_proc_kind(mach_proc_at(t->m, rpl_target_map(t, it->proc)));
    if (it->type == RPL_COMPUTE)
        check_ops(t, it->proc, it->op, it->op_col, it->n_ops, it->line, path,
                  bad);
    for (guint k = 0; it->type == RPL_COMPUTE && k < it->n_terms; k++)
        check_term(t, &it->term[k], it->line, path, bad);
    if (it->type == RPL_WORK && !t->clock_missing &&
        isnan(rpl_target_scale(t, it->proc))) {
        t->clock_missing = TRUE; /* reported once */
        g_string_append_printf(bad,
                               "\n  %s:%u:1: a clock to scale `w` work of "
                               "processor %u: its recording clock (a 'kind' "
                               "header line, or --clock KIND=HZ) and "
                               "nodes.%s.clock (or a 'machine %s' header: "
                               "recorded here)",
                               path, it->line, it->proc, kind, mach_name(t->m));
    }
    if ((it->type == RPL_SEND || (it->type == RPL_BUS && !t->has_shm)) &&
        !mach_net(t->m) && !*net_missing) {
        *net_missing = TRUE;
        g_string_append_printf(bad, "\n  %s:%u:1: a network (this trace sends)",
                               path, it->line);
    }
}

/* TRUE when a `c` or `w` item records some work (a count or time). */
static gboolean has_work(const RplItem *it)
{
    gboolean any = it->type == RPL_WORK && it->value > 0;
    for (guint i = 0; it->type == RPL_COMPUTE && i < it->n_ops; i++)
        any = any || it->count[i] > 0;
    for (guint k = 0; it->type == RPL_COMPUTE && k < it->n_terms; k++) {
        const RplTerm *term = &it->term[k];
        any = any || (term->bus && term->bytes > 0);
        for (guint i = 0; !term->bus && i < term->n_ops; i++)
            any = any || term->count[i] > 0;
    }
    return any;
}

/* Counts recorded work and the part the target prices at 0 ps (once
 * every cost and clock it needs was found). */
static void note_work(RplTarget *t, const RplItem *it)
{
    if (!has_work(it))
        return;
    t->work++;
    if (rpl_target_price(t, it) == 0 && !t->zero_work++)
        t->zero_line = it->line;
}

/* Recorded work that every clock and cost turns into 0 ps would replay
 * as a run that took no time: an input error, not a result. */
static gboolean work_survives(const RplTarget *t, const char *path,
                              GError **err)
{
    if (t->work == 0 || t->zero_work < t->work)
        return TRUE;
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "%s:%u:1: found all %" G_GUINT64_FORMAT " actions' recorded "
                "work priced at 0 ps on machine '%s', expected clocks and "
                "costs that keep work above 0 ps (--clock KIND=HZ, the "
                "'kind' lines' clocks, nodes.KIND.clock and costs)",
                path, t->zero_line, t->work, mach_name(t->m));
    return FALSE;
}

gboolean rpl_target_check(RplTarget *t, const char *path, GError **err)
{
    RplReader *r = rpl_reader_open(path, err);
    if (!r)
        return FALSE;
    GString *bad = g_string_new(NULL);
    gboolean net_missing = FALSE;
    RplItem it;
    while (rpl_reader_next(r, &it, err)) {
        check_item(t, &it, path, bad, &net_missing);
        if (bad->len == 0)
            note_work(t, &it);
    }
    gboolean ok = !(err && *err) && bad->len == 0 &&
                  work_survives(t, path, err);
    if (!(err && *err) && bad->len)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found work the machine '%s' cannot price, expected "
                    "these in its model (first use shown):%s",
                    path, mach_name(t->m), bad->str);
    g_string_free(bad, TRUE);
    rpl_reader_free(r);
    return ok;
}

/* Counts priced on trace processor p's target kind (checked). */
static SimTime ops_price(RplTarget *t, guint p, const char *const *op,
                         const uint64_t *count, guint n)
{
    SimTime sum = 0;
    gboolean fresh;
    for (guint i = 0; i < n; i++) {
        const SimTime *cp = rpl_target_op_cost(t, p, op[i], &fresh);
        g_assert(cp); /* rpl_target_check() passed */
        sum = sim_time_add_sat(sum, sim_time_mul_sat(*cp, count[i]));
    }
    return sum;
}

SimTime rpl_target_price(RplTarget *t, const RplItem *it)
{
    if (it->type == RPL_WORK) {
        double s = rpl_target_scale(t, it->proc);
        if (s == 1)
            return it->value;
        double v = round((double)it->value * s);
        return v >= (double)SIM_TIME_MAX ? SIM_TIME_MAX : (SimTime)v;
    }
    SimTime c = ops_price(t, it->proc, it->op, it->count, it->n_ops);
    for (guint k = 0; k < it->n_terms; k++) {
        const RplTerm *term = &it->term[k];
        c = MAX(c, term->bus ? mach_shmem_time(&t->shm, term->bytes)
                             : ops_price(t, term->proc, term->op, term->count,
                                         term->n_ops));
    }
    return c;
}
