/* dp_exec.c — a frame as engine events on a machine (dp_exec.h).
 *
 * One state machine drives the frame: issue() takes the next step from
 * the schedule and submits it; the completion handler of that step calls
 * issue() again.  SIMD steps cost exactly what dp_cost.h says (so the
 * event-driven frame equals the closed form, tested); SPMD sends go
 * through the machine's network.  O(steps) events (SIMD), O(steps x
 * messages per step) (SPMD).
 */
#include "sim/workload/dpscan/dp_exec.h"
#include <string.h>

typedef struct {
    MachMachine *mach;
    const WlDpMachine *m;
    WlDpSched *s;
    WlDpLayout *l;
    WlDpFrame *f;
    SimEngine *eng;
    NetNet *net;
    unsigned phase[WL_DP_N_PHASES];
    guint first;          /* global id of node / array 0 */
    uint64_t outstanding; /* messages and handlers of the current send */
    GHashTable *pairs;    /* (src * p + dst) -> words, per send */
    WlDpPhase cur;        /* phase of the current send */
    WlDpStep pending;     /* SPMD: step taken but not issued yet */
    gboolean has_pending;
} DpExec;

static void issue(SimEngine *eng, void *ctx, void *arg);

static MachProc *proc(DpExec *x, uint64_t i)
{
    return mach_proc_at(x->mach, x->first + (guint)i);
}

/* Every node (SPMD) or the array (SIMD) works `cost`; then issue(). */
static void all_compute(DpExec *x, SimTime cost, WlDpPhase ph)
{
    uint64_t n = x->m->arch == WL_DP_SIMD ? 1 : x->m->procs;
    for (uint64_t i = 0; i + 1 < n; i++)
        mach_proc_compute(proc(x, i), cost, x->phase[ph], NULL, NULL, NULL);
    mach_proc_compute(proc(x, n - 1), cost, x->phase[ph], issue, x, NULL);
}

static void add_pair(DpExec *x, uint64_t src, uint64_t dst, uint64_t words)
{
    gpointer key = GSIZE_TO_POINTER(src * x->m->procs + dst + 1);
    gsize old = GPOINTER_TO_SIZE(g_hash_table_lookup(x->pairs, key));
    g_hash_table_insert(x->pairs, key, GSIZE_TO_POINTER(old + words));
}

/* Source and destination node of every message of this send. */
static void collect_pairs(DpExec *x, const WlDpStep *st)
{
    uint64_t p = x->m->procs;
    if (st->zbuf) {
        uint32_t j;
        const WlDpSeg *seg = wl_dp_sched_live(x->s, &j);
        for (uint64_t k = 0; k < st->active; k++) {
            uint32_t px = seg[k].x0 + j, py = seg[k].y;
            if (px >= x->l->width || py >= x->l->height)
                continue; /* clipped */
            add_pair(x, seg[k].slot % p, wl_dp_layout_owner(x->l, px, py),
                     st->words);
        }
        return;
    }
    const WlDpSeg *seg = wl_dp_sched_sent(x->s);
    for (uint64_t k = 0; k < st->active; k++)
        add_pair(x, seg[k].poly % p, seg[k].slot % p, st->words);
}

/* More pairs than 2p: merge destinations into the two halves. */
static void merge_pairs(DpExec *x)
{
    uint64_t p = x->m->procs, g = p / 2;
    if (g == 0 || g_hash_table_size(x->pairs) <= 2 * p)
        return;
    GHashTable *old = x->pairs;
    x->pairs = g_hash_table_new(g_direct_hash, g_direct_equal);
    GHashTableIter it;
    gpointer k, v;
    g_hash_table_iter_init(&it, old);
    while (g_hash_table_iter_next(&it, &k, &v)) {
        uint64_t key = GPOINTER_TO_SIZE(k) - 1;
        uint64_t src = key / p, half = (key % p) / g;
        uint64_t dst = half * g + (src % g + g / 2) % g;
        add_pair(x, src, dst, GPOINTER_TO_SIZE(v));
    }
    g_hash_table_destroy(old);
}

static void send_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng, (void)arg;
    DpExec *x = ctx;
    g_assert(x->outstanding > 0);
    if (--x->outstanding == 0)
        all_compute(x, x->m->step + x->m->net_latency, x->cur);
}

static void arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    DpExec *x = ctx;
    uint64_t words = d->bytes / x->m->msg_bytes;
    SimTime cost = (x->m->msg_overhead / 2) * words;
    mach_proc_compute(proc(x, d->dst), cost, x->phase[x->cur], send_done, x,
                      NULL);
}

static void inject(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    DpExec *x = ctx;
    uint64_t key = GPOINTER_TO_SIZE(arg) >> 32,
             words = GPOINTER_TO_SIZE(arg) & 0xffffffffu;
    uint64_t p = x->m->procs;
    net_send(x->net, x->first + (uint32_t)(key / p),
             x->first + (uint32_t)(key % p), words * x->m->msg_bytes, NULL,
             arrived, x);
}

/* SPMD send: senders' software, messages, receivers' handlers. */
static void spmd_send(DpExec *x, const WlDpStep *st)
{
    collect_pairs(x, st);
    merge_pairs(x);
    x->cur = st->phase;
    x->outstanding = g_hash_table_size(x->pairs);
    if (x->outstanding == 0) {
        all_compute(x, x->m->step, st->phase);
        return;
    }
    GHashTableIter it;
    gpointer k, v;
    g_hash_table_iter_init(&it, x->pairs);
    while (g_hash_table_iter_next(&it, &k, &v)) {
        uint64_t key = GPOINTER_TO_SIZE(k) - 1, words = GPOINTER_TO_SIZE(v);
        g_assert(words <= 0xffffffffu && key < (1ull << 31));
        SimTime soft = (x->m->msg_overhead - x->m->msg_overhead / 2) * words;
        mach_proc_compute(proc(x, key / x->m->procs), soft, x->phase[st->phase],
                          inject, x, GSIZE_TO_POINTER((key << 32) | words));
    }
    g_hash_table_remove_all(x->pairs);
}

static gboolean take(DpExec *x, WlDpStep *st)
{
    if (x->has_pending) {
        *st = x->pending;
        x->has_pending = FALSE;
        return TRUE;
    }
    if (!wl_dp_sched_next(x->s, st))
        return FALSE;
    x->f->steps++;
    return TRUE;
}

/* SPMD: a run of compute steps of one phase is one piece of work on
 * every node (they are identical on all nodes, so nothing is lost). */
static void spmd_batch(DpExec *x, const WlDpStep *first)
{
    SimTime sum = wl_dp_step_time(x->m, x->l, x->s, first, &x->f->coef);
    WlDpStep st;
    while (take(x, &st)) {
        if (st.kind == WL_DP_SEND || st.phase != first->phase) {
            x->pending = st;
            x->has_pending = TRUE;
            break;
        }
        SimTime t = wl_dp_step_time(x->m, x->l, x->s, &st, &x->f->coef);
        gboolean ok = sim_time_add(sum, t, &sum);
        g_assert(ok);
    }
    all_compute(x, sum, first->phase);
}

static void issue(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng, (void)arg;
    DpExec *x = ctx;
    WlDpStep st;
    if (!take(x, &st))
        return;
    if (x->m->arch == WL_DP_SPMD) {
        if (st.kind == WL_DP_SEND)
            spmd_send(x, &st);
        else
            spmd_batch(x, &st);
        return;
    }
    all_compute(x, wl_dp_step_time(x->m, x->l, x->s, &st, &x->f->coef),
                st.phase);
}

static gboolean find_procs(DpExec *x, GError **err)
{
    const char *kind = x->m->arch == WL_DP_SIMD ? "array" : "node";
    uint64_t want = x->m->arch == WL_DP_SIMD ? 1 : x->m->procs;
    const MachKindInfo *k = mach_kind(x->mach, kind);
    if (!k || k->count < want) {
        g_set_error(
            err, SIM_ERROR, SIM_ERROR_INPUT,
            "machine %s: found %u '%s' processors, expected %" G_GUINT64_FORMAT
            " for the dpscan model",
            mach_name(x->mach), k ? k->count : 0, kind, want);
        return FALSE;
    }
    x->first = k->first;
    x->net = mach_net(x->mach);
    if (x->m->arch == WL_DP_SPMD && !x->net)
        return mach_require_net(x->mach, err);
    return TRUE;
}

static void fill_phases(DpExec *x, SimTime start)
{
    MachProc *p0 = proc(x, 0);
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++)
        x->f->phase[ph] = mach_proc_busy_phase(p0, x->phase[ph]);
    x->f->total = sim_now(x->eng) - start;
}

gboolean wl_dp_exec_frame(MachMachine *mach, const WlDpMachine *m,
                          const WlDpGeom *g, const WlDpAlgo *a, WlDpFrame *out,
                          GError **err)
{
    memset(out, 0, sizeof(*out));
    DpExec x = {.mach = mach, .m = m, .f = out, .eng = mach_engine(mach)};
    if (!find_procs(&x, err))
        return FALSE;
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++)
        x.phase[ph] = sim_engine_phase(x.eng, wl_dp_phase_name(ph));
    SimTime start = sim_now(x.eng);
    SimTime busy0[WL_DP_N_PHASES];
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++)
        busy0[ph] = mach_proc_busy_phase(proc(&x, 0), x.phase[ph]);
    x.s = wl_dp_sched_new(g, a);
    x.l = wl_dp_layout_new(m->procs, (uint32_t)g->width, (uint32_t)g->height);
    x.pairs = g_hash_table_new(g_direct_hash, g_direct_equal);
    gboolean ok = sim_schedule_in(x.eng, 0, issue, &x, NULL) &&
                  sim_engine_run(x.eng, SIM_TIME_MAX, err);
    if (ok) {
        fill_phases(&x, start);
        for (int ph = 0; ph < WL_DP_N_PHASES; ph++)
            out->phase[ph] -= busy0[ph];
        out->counts = *wl_dp_sched_counts(x.s);
    }
    g_hash_table_destroy(x.pairs);
    wl_dp_layout_free(x.l);
    wl_dp_sched_free(x.s);
    return ok;
}

MachMachine *wl_dp_exec_machine(SimEngine *eng, const char *model,
                                const WlDpMachine *m, const char *fidelity,
                                GError **err)
{
    char *text;
    if (m->arch == WL_DP_SIMD)
        text = g_strdup_printf(
            "model: %s\nnodes: {array: {lanes: %" G_GUINT64_FORMAT
            "}}\nnetwork: "
            "{router_nodes: %" G_GUINT64_FORMAT "}\n",
            model, m->procs, MAX(m->procs / 16, 1));
    else
        text = g_strdup_printf(
            "model: %s\nnodes: {node: {count: %" G_GUINT64_FORMAT "}}\n", model,
            m->procs);
    CfgNode *sec = cfg_load_string(text, "dpscan machine", err);
    g_free(text);
    if (!sec)
        return NULL;
    MachMachine *mach = mach_new_from_cfg(eng, sec, fidelity, err);
    cfg_free(sec);
    return mach;
}
