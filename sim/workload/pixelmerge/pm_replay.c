/* pm_replay.c — event-driven replay of the merge steps (seed 003 §3–4).
 *
 * The steps are flattened into RStep records (one message per processor
 * per exchange step, pre- and post-compute per processor).  A processor
 * is in exactly one of: computing (an event pending), waiting for its
 * step's message (waiting[p]), or done.  got[s * n + p] records that the
 * message of step s for p has arrived, so an early arrival is never lost.
 * Invariant: cur[p] only increases; p's post-compute of step s starts at
 * max(own send, arrival of its step-s message).
 */
#include "sim/workload/pixelmerge/pm_replay.h"
#include <math.h>

/* A compute as named counts (wl_pm_cost_ops), for mach_proc_compute_ops. */
typedef struct {
    MachOp op[3];
    guint n;
} OpList;

typedef struct {
    gboolean exchange;
    uint32_t *dst;
    uint64_t *bytes;
    SimTime *pre, *post;
    OpList *pre_ops, *post_ops; /* the counts priced into pre / post */
} RStep;

typedef struct {
    NetNet *net;
    MachProc *const *procs; /* NULL: schedule on the engine directly */
    SimEngine *eng;
    guint n, n_steps;
    RStep *steps;
    guint *cur;
    gboolean *waiting;
    guint8 *got;
    SimBusy *busy;
    unsigned phase;
    SimTime *done;
    gboolean overflow;
} Replay;

/* n x unit; a saturated product sets *overflow (reported by the caller). */
static SimTime times(SimTime unit, uint64_t n, gboolean *overflow)
{
    SimTime t = sim_time_mul_sat(unit, n);
    if (t == SIM_TIME_MAX)
        *overflow = TRUE;
    return t;
}

static void rstep_init(RStep *s, guint n, gboolean exchange)
{
    s->exchange = exchange;
    s->dst = g_new0(uint32_t, n);
    s->bytes = g_new0(uint64_t, n);
    s->pre = g_new0(SimTime, n);
    s->post = g_new0(SimTime, n);
    s->pre_ops = g_new0(OpList, n);
    s->post_ops = g_new0(OpList, n);
}

static void rstep_clear(RStep *s)
{
    g_free(s->dst);
    g_free(s->bytes);
    g_free(s->pre);
    g_free(s->post);
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
                              guint height, const WlPmMergeCosts *c,
                              gboolean *ovf)
{
    if (bal == WL_PM_BAL_STRIPS)
        return 0;
    guint d = log2u(n), k = 0;
    SimTime add = times(c->sum_elem, height, ovf);
    for (; k < d; k++) {
        rstep_init(&out[k], n, TRUE);
        for (guint p = 0; p < n; p++) {
            out[k].dst[p] = p ^ (1u << k);
            out[k].bytes[p] = (uint64_t)height * c->count_bytes;
            out[k].post[p] = add;
            out[k].pre_ops[p] = (OpList){{{"sum_elem", 0}}, 1}; /* none */
            out[k].post_ops[p] = (OpList){{{"sum_elem", height}}, 1};
        }
    }
    rstep_init(&out[k], n, FALSE);
    uint64_t lg = MAX(1u, log2u(height));
    SimTime t = bal == WL_PM_BAL_HBP
                    ? times(c->sort_elem, (uint64_t)height * lg, ovf) +
                          times(c->assign_step, (uint64_t)height * n, ovf)
                    : times(c->sort_elem, (uint64_t)d * lg, ovf);
    OpList o = bal == WL_PM_BAL_HBP
                   ? (OpList){{{"sort_elem", (uint64_t)height * lg},
                               {"assign_step", (uint64_t)height * n}},
                              2}
                   : (OpList){{{"sort_elem", (uint64_t)d * lg}}, 1};
    for (guint p = 0; p < n; p++) {
        out[k].post[p] = t;
        out[k].pre_ops[p] = (OpList){{{"sort_elem", 0}}, 1}; /* none */
        out[k].post_ops[p] = o;
    }
    return k + 1;
}

static void merge_step(RStep *r, const WlPmStep *st, guint n,
                       const WlPmMergeCosts *c, gboolean *ovf)
{
    rstep_init(r, n, st->exchange);
    for (guint p = 0; p < n; p++) {
        const WlPmWork *w = &st->work[p];
        r->dst[p] = st->msg[p].dst;
        r->bytes[p] = st->msg[p].bytes;
        r->pre[p] = times(c->pack, w->pack, ovf);
        r->post[p] = times(c->scatter, w->scatter, ovf) +
                     times(c->compare, w->compare, ovf) +
                     times(c->gather, w->gather, ovf);
        r->pre_ops[p] = (OpList){{{"pack", w->pack}}, 1};
        r->post_ops[p] = (OpList){{{"scatter", w->scatter},
                                   {"compare", w->compare},
                                   {"gather", w->gather}},
                                  3};
    }
}

static void proc_step(SimEngine *eng, void *ctx, void *arg);

/* `cost` is the price of `ops`: a machine processor is given the counts
 * (a recording names them), plain engine events the time. */
static void compute_then(Replay *r, guint p, SimTime cost, const OpList *ops,
                         SimHandler next)
{
    if (!sim_busy_add(&r->busy[p], r->phase, cost))
        r->overflow = TRUE;
    if (r->procs) {
        if (!mach_proc_compute_ops(r->procs[p], ops->op, ops->n, r->phase, next,
                                   r, GUINT_TO_POINTER(p)))
            r->overflow = TRUE;
    } else
        sim_schedule_in(r->eng, cost, next, r, GUINT_TO_POINTER(p));
}

static void proc_post_done(SimEngine *eng, void *ctx, void *arg)
{
    Replay *r = ctx;
    guint p = GPOINTER_TO_UINT(arg);
    r->cur[p]++;
    proc_step(eng, ctx, arg);
}

static void proc_post(Replay *r, guint p)
{
    r->waiting[p] = FALSE;
    const RStep *st = &r->steps[r->cur[p]];
    compute_then(r, p, st->post[p], &st->post_ops[p], proc_post_done);
}

static void on_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Replay *r = ctx;
    guint s = GPOINTER_TO_UINT(d->payload);
    r->got[(gsize)s * r->n + d->dst] = 1;
    if (r->waiting[d->dst] && r->cur[d->dst] == s)
        proc_post(r, d->dst);
}

static void proc_send(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Replay *r = ctx;
    guint p = GPOINTER_TO_UINT(arg), s = r->cur[p];
    const RStep *st = &r->steps[s];
    if (!st->exchange) {
        proc_post(r, p);
        return;
    }
    net_send(r->net, p, st->dst[p], st->bytes[p], GUINT_TO_POINTER(s),
             on_arrive, r);
    if (r->got[(gsize)s * r->n + p])
        proc_post(r, p);
    else
        r->waiting[p] = TRUE;
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
    compute_then(r, p, st->pre[p], &st->pre_ops[p], proc_send);
}

static void build_steps(Replay *r, const WlPmMerge *m, WlPmBalance bal,
                        guint height, const WlPmMergeCosts *c)
{
    guint max = log2u(r->n) + 1 + m->steps->len;
    r->steps = g_new0(RStep, max);
    r->n_steps = global_sum_steps(r->steps, r->n, bal, height, c, &r->overflow);
    for (guint s = 0; s < m->steps->len; s++)
        merge_step(&r->steps[r->n_steps++], g_ptr_array_index(m->steps, s),
                   r->n, c, &r->overflow);
}

static void replay_clear(Replay *r)
{
    for (guint s = 0; s < r->n_steps; s++)
        rstep_clear(&r->steps[s]);
    g_free(r->steps);
    g_free(r->cur);
    g_free(r->waiting);
    g_free(r->got);
}

gboolean wl_pm_replay(NetNet *net, const WlPmMerge *m, WlPmBalance bal,
                      guint height, const WlPmMergeCosts *costs,
                      const SimTime *ready, SimBusy *busy, unsigned phase,
                      WlPmReplayOut *out, GError **err)
{
    return wl_pm_replay_procs(net, NULL, m, bal, height, costs, ready, busy,
                              phase, out, err);
}

gboolean wl_pm_replay_procs(NetNet *net, MachProc *const *procs,
                            const WlPmMerge *m, WlPmBalance bal, guint height,
                            const WlPmMergeCosts *costs, const SimTime *ready,
                            SimBusy *busy, unsigned phase, WlPmReplayOut *out,
                            GError **err)
{
    guint n = m->n_procs;
    g_assert(net_nodes(net) >= n);
    Replay r = {.net = net,
                .procs = procs,
                .eng = net_engine(net),
                .n = n,
                .busy = busy,
                .phase = phase};
    build_steps(&r, m, bal, height, costs);
    r.cur = g_new0(guint, n);
    r.waiting = g_new0(gboolean, n);
    r.got = g_new0(guint8, (gsize)(r.n_steps + 1) * n);
    out->done = g_new0(SimTime, n);
    r.done = out->done;
    SimTime now = sim_now(r.eng);
    for (guint p = 0; p < n; p++)
        sim_schedule_at(r.eng, MAX(now, ready[p]), proc_step, &r,
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
