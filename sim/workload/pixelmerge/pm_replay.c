/* pm_replay.c — event-driven replay of the merge steps (seed 003 §3–4).
 *
 * The steps are flattened into RStep records (per exchange step, each
 * processor's messages -- one in Kurç's schemes, any number in the
 * compositing schemes -- and the count it receives; pre- and
 * post-compute per processor).  A processor is in exactly one of:
 * computing (an event pending), waiting for its step's messages
 * (waiting[p]), or done.  got[s * n + p] counts the messages of step s
 * for p that have arrived, so an early arrival is never lost.
 * Invariant: cur[p] only increases; p's post-compute of step s starts at
 * max(own sends, arrival of its last step-s message).  In Kurç's schemes
 * that is a join of two completions: whichever comes last issues the
 * post-compute, and the first one's recorded action (first[s * n + p])
 * is named to the recorder with sim_record_after(), so that a replay on
 * another network waits for both (docs/traces.md, `after`).  With more
 * messages the recorder keeps two-way joins only: the last completion
 * and the one before it (first[] holds the latest earlier one), so a
 * recorded compositing merge replays exactly on the same machine but a
 * what-if may start a post-compute before an earlier message's arrival.
 */
#include "sim/workload/pixelmerge/pm_replay.h"
#include "sim/core/record.h"
#include <string.h>

/* A compute as named counts (wl_pm_cost_ops): the one description of
 * the work, priced by the processor's kind or, without processors, by
 * the rig's costs (op_price). */
typedef struct {
    MachOp op[3];
    guint n;
} OpList;

typedef struct {
    gboolean exchange;
    guint *first;    /* n + 1: p's messages are first[p] .. first[p + 1] */
    uint32_t *dst;   /* per message */
    uint64_t *bytes; /* per message */
    guint *expect;   /* n: messages p receives */
    OpList *pre_ops, *post_ops;
} RStep;

typedef struct {
    const WlPmReplayRig *rig;
    SimEngine *eng;
    guint n, n_steps;
    RStep *steps;
    guint *cur;
    gboolean *waiting;
    guint *got;
    uint64_t *first; /* the recorded completion that came first (join) */
    SimTime *done;
    gboolean overflow;
} Replay;

SimTime wl_pm_price(const void *costs, const WlPmUnit *units, const MachOp *o,
                    guint n)
{
    SimTime t = 0;
    for (guint i = 0; i < n; i++) {
        const WlPmUnit *u = units;
        while (strcmp(o[i].name, u->name) != 0)
            g_assert((++u)->name);
        t = sim_time_add_sat(
            t, sim_time_mul_sat(G_STRUCT_MEMBER(SimTime, costs, u->off),
                                o[i].count));
    }
    return t;
}

static const WlPmUnit merge_units[] = {
    {"pack", G_STRUCT_OFFSET(WlPmMergeCosts, pack)},
    {"scatter", G_STRUCT_OFFSET(WlPmMergeCosts, scatter)},
    {"compare", G_STRUCT_OFFSET(WlPmMergeCosts, compare)},
    {"gather", G_STRUCT_OFFSET(WlPmMergeCosts, gather)},
    {"sum_elem", G_STRUCT_OFFSET(WlPmMergeCosts, sum_elem)},
    {"sort_elem", G_STRUCT_OFFSET(WlPmMergeCosts, sort_elem)},
    {"assign_step", G_STRUCT_OFFSET(WlPmMergeCosts, assign_step)},
    {NULL, 0}};

/* The ops' price at c; a saturated sum sets *overflow (reported by the
 * caller). */
static SimTime ops_price(const WlPmMergeCosts *c, const OpList *o,
                         gboolean *overflow)
{
    SimTime t = wl_pm_price(c, merge_units, o->op, o->n);
    if (t == SIM_TIME_MAX)
        *overflow = TRUE;
    return t;
}

/* n processors, n_msgs messages; with n_msgs == n, message p is p's. */
static void rstep_init(RStep *s, guint n, guint n_msgs, gboolean exchange)
{
    s->exchange = exchange;
    s->first = g_new0(guint, n + 1);
    for (guint p = 0; n_msgs == n && p <= n; p++)
        s->first[p] = p;
    s->dst = g_new0(uint32_t, n_msgs);
    s->bytes = g_new0(uint64_t, n_msgs);
    s->expect = g_new0(guint, n);
    s->pre_ops = g_new0(OpList, n);
    s->post_ops = g_new0(OpList, n);
}

static void rstep_clear(RStep *s)
{
    g_free(s->first);
    g_free(s->expect);
    g_free(s->dst);
    g_free(s->bytes);
    g_free(s->pre_ops);
    g_free(s->post_ops);
}

static guint log2u(guint n)
{
    guint d = 0;
    while ((1u << d) < n)
        d++;
    return d;
}

/* Recursive doubling of the per-scanline counts, then the partitioning
 * itself as post-compute of the last exchange (or a compute step). */
static guint global_sum_steps(RStep *out, guint n, WlPmBalance bal,
                              guint height, uint32_t count_bytes)
{
    if (bal == WL_PM_BAL_STRIPS)
        return 0;
    guint d = log2u(n), k = 0;
    for (; k < d; k++) {
        rstep_init(&out[k], n, n, TRUE);
        for (guint p = 0; p < n; p++) {
            out[k].dst[p] = p ^ (1u << k);
            out[k].expect[p] = 1;
            out[k].bytes[p] = (uint64_t)height * count_bytes;
            out[k].pre_ops[p] = (OpList){{{"sum_elem", 0}}, 1}; /* none */
            out[k].post_ops[p] = (OpList){{{"sum_elem", height}}, 1};
        }
    }
    rstep_init(&out[k], n, n, FALSE);
    uint64_t lg = MAX(1u, log2u(height));
    OpList o = bal == WL_PM_BAL_HBP
                   ? (OpList){{{"sort_elem", (uint64_t)height * lg},
                               {"assign_step", (uint64_t)height * n}},
                              2}
                   : (OpList){{{"sort_elem", (uint64_t)d * lg}}, 1};
    for (guint p = 0; p < n; p++) {
        out[k].pre_ops[p] = (OpList){{{"sort_elem", 0}}, 1}; /* none */
        out[k].post_ops[p] = o;
    }
    return k + 1;
}

static void merge_step(RStep *r, const WlPmStep *st, guint n)
{
    guint nm = st->exchange ? st->n_msgs : 0;
    rstep_init(r, n, nm, st->exchange);
    memset(r->first, 0, (n + 1) * sizeof *r->first);
    for (guint i = 0; i < nm; i++) { /* messages come in sender order */
        const WlPmMsg *msg = &st->msg[i];
        g_assert(msg->src < n && msg->dst < n);
        g_assert(i == 0 || st->msg[i - 1].src <= msg->src);
        r->first[msg->src + 1]++;
        r->dst[i] = msg->dst;
        r->bytes[i] = msg->bytes;
        r->expect[msg->dst]++;
    }
    for (guint p = 0; p < n; p++)
        r->first[p + 1] += r->first[p];
    for (guint p = 0; p < n; p++) {
        const WlPmWork *w = &st->work[p];
        r->pre_ops[p] = (OpList){{{"pack", w->pack}}, 1};
        r->post_ops[p] = (OpList){{{"scatter", w->scatter},
                                   {"compare", w->compare},
                                   {"gather", w->gather}},
                                  3};
    }
}

static void proc_step(SimEngine *eng, void *ctx, void *arg);

/* Processor p computes `ops`, then next: charged once, to its machine
 * processor, or without processors as an engine event at the rig's
 * costs (its time into busy[p]). */
static void compute_then(Replay *r, guint p, const OpList *ops, SimHandler next)
{
    const WlPmReplayRig *rig = r->rig;
    if (rig->procs) {
        if (!mach_proc_compute_ops(rig->procs[p], ops->op, ops->n, rig->phase,
                                   next, r, GUINT_TO_POINTER(p)))
            r->overflow = TRUE;
        return;
    }
    SimTime cost = ops_price(rig->costs, ops, &r->overflow);
    if (!sim_busy_add(&rig->busy[p], rig->phase, cost))
        r->overflow = TRUE;
    sim_schedule_in(r->eng, cost, next, r, GUINT_TO_POINTER(p));
}

static void proc_post_done(SimEngine *eng, void *ctx, void *arg)
{
    Replay *r = ctx;
    guint p = GPOINTER_TO_UINT(arg);
    r->cur[p]++;
    proc_step(eng, ctx, arg);
}

/* p's post-compute of its step; `join`: the other completion it waits
 * for, as the recorder knows it (SIM_RECORD_NONE: none). */
static void proc_post(Replay *r, guint p, uint64_t join)
{
    r->waiting[p] = FALSE;
    const RStep *st = &r->steps[r->cur[p]];
    sim_record_after(r->eng, join);
    compute_then(r, p, &st->post_ops[p], proc_post_done);
}

static void on_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Replay *r = ctx;
    guint s = GPOINTER_TO_UINT(d->payload);
    gsize at = (gsize)s * r->n + d->dst;
    guint got = ++r->got[at];
    if (r->waiting[d->dst] && r->cur[d->dst] == s &&
        got == r->steps[s].expect[d->dst])
        proc_post(r, d->dst, r->first[at]);
    else
        r->first[at] = sim_record_cause(r->eng);
}

static void proc_send(SimEngine *eng, void *ctx, void *arg)
{
    Replay *r = ctx;
    guint p = GPOINTER_TO_UINT(arg), s = r->cur[p];
    const RStep *st = &r->steps[s];
    if (!st->exchange) {
        proc_post(r, p, SIM_RECORD_NONE);
        return;
    }
    gsize at = (gsize)s * r->n + p;
    uint64_t pre = sim_record_cause(eng); /* before the send is issued */
    for (guint i = st->first[p]; i < st->first[p + 1]; i++)
        net_send(r->rig->net, p, st->dst[i], st->bytes[i],
                 GUINT_TO_POINTER(s), on_arrive, r);
    if (r->got[at] >= st->expect[p]) {
        proc_post(r, p, st->expect[p] ? r->first[at] : SIM_RECORD_NONE);
    } else {
        r->waiting[p] = TRUE;
        r->first[at] = pre;
    }
}

static void proc_step(SimEngine *eng, void *ctx, void *arg)
{
    Replay *r = ctx;
    guint p = GPOINTER_TO_UINT(arg);
    if (r->cur[p] == r->n_steps) {
        r->done[p] = sim_now(eng);
        return;
    }
    const RStep *st = &r->steps[r->cur[p]];
    compute_then(r, p, &st->pre_ops[p], proc_send);
}

static void build_steps(Replay *r, const WlPmMerge *m)
{
    const WlPmReplayRig *rig = r->rig;
    guint max = log2u(r->n) + 1 + m->steps->len;
    r->steps = g_new0(RStep, max);
    r->n_steps = global_sum_steps(r->steps, r->n, rig->bal, rig->height,
                                  rig->costs->count_bytes);
    for (guint s = 0; s < m->steps->len; s++)
        merge_step(&r->steps[r->n_steps++], g_ptr_array_index(m->steps, s),
                   r->n);
}

static void replay_clear(Replay *r)
{
    for (guint s = 0; s < r->n_steps; s++)
        rstep_clear(&r->steps[s]);
    g_free(r->steps);
    g_free(r->cur);
    g_free(r->waiting);
    g_free(r->got);
    g_free(r->first);
}

gboolean wl_pm_replay(const WlPmReplayRig *rig, const WlPmMerge *m,
                      WlPmReplayOut *out, GError **err)
{
    guint n = m->n_procs;
    g_assert(net_nodes(rig->net) >= n && (rig->procs || rig->busy));
    Replay r = {.rig = rig, .eng = net_engine(rig->net), .n = n};
    build_steps(&r, m);
    r.cur = g_new0(guint, n);
    r.waiting = g_new0(gboolean, n);
    r.got = g_new0(guint, (gsize)(r.n_steps + 1) * n);
    r.first = g_new(uint64_t, (gsize)(r.n_steps + 1) * n);
    out->done = g_new0(SimTime, n);
    r.done = out->done;
    SimTime now = sim_now(r.eng);
    for (guint p = 0; p < n; p++)
        sim_schedule_at(r.eng, MAX(now, rig->ready[p]), proc_step, &r,
                        GUINT_TO_POINTER(p));
    gboolean ok = sim_engine_run(r.eng, SIM_TIME_MAX, err);
    if (ok && r.overflow) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_OVERFLOW,
                    "pixel merge: a compute time overflows SimTime");
        ok = FALSE;
    }
    out->end = 0;
    gboolean whole = !sim_engine_cut(r.eng); /* run.until cut it short */
    for (guint p = 0; ok && whole && p < n; p++) {
        g_assert(r.cur[p] == r.n_steps);
        out->end = MAX(out->end, out->done[p]);
    }
    replay_clear(&r);
    return ok;
}

void wl_pm_replay_out_clear(WlPmReplayOut *out)
{
    g_free(out->done);
    out->done = NULL;
}
