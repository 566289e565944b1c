/* flow.c — the flow-level (fluid) transport: max-min fair bandwidth sharing.
 *
 * A message first waits its latency (startup + hops * per_hop), then
 * becomes a flow that crosses its path's links at a rate given by max-min
 * fairness: the fluid model of SimGrid (Velho, Schnorr, Casanova & Legrand,
 * "On the validity of flow-level TCP network models for grid and cloud
 * simulations", ACM TOMACS 23(4), 2013), without SimGrid's empirical
 * latency/bandwidth factors.  Each link of capacity channels * bw is shared;
 * each flow is also bounded by its path's channel bandwidth (a message uses
 * one channel).  Rates are computed by progressive filling (Bertsekas &
 * Gallager, Data Networks, 1992, sec. 6.5.2): repeatedly saturate the
 * link (or flow bound) with the least fair share.
 *
 * Bottleneck order with a lazy heap: each link of the component is in a
 * min-heap once, keyed by its fair share rem / unfixed when pushed.  Fixing
 * a flow at a rate no larger than the current minimum share can only raise
 * the shares of the links it crosses, so a key is a lower bound of its
 * link's share; the top is re-keyed only when popped (SimGrid's lazy
 * bottleneck search follows the same idea).  Fixing a flow is O(hops), not
 * O(hops log L).
 *
 * Incremental: a start or an end marks the links it touches dirty and asks
 * for one recomputation at the current instant (so all starts and ends at
 * the same time are batched).  Flows whose rate is below the batch's
 * level keep it (collect_component says why); the recomputation visits
 * only the other flows on dirty links and those joined to them, by such
 * flows, through links that can bind (more flows than channels): a link
 * whose capacity covers all its flows' bounds constrains nobody, so it
 * does not couple their rates.  Flows elsewhere keep their rates and
 * predicted ends.  Predicted ends live in a private
 * min-heap of flows (by end time, then send sequence) and one engine timer
 * is armed for the earliest: a rate change moves a flow in that heap
 * instead of scheduling an engine event (the engine cannot cancel events;
 * a superseded timer is recognised by its generation and ignored).
 *
 * Invariants: a lone flow finishes at exactly the analytic time; every
 * link's flows' rates sum to at most its capacity (up to rounding); flows
 * with equal end times complete in send order.
 * Cost per recomputation: O(E + L log L + C log F) for E = sum of path
 * lengths of the component's flows, L its links, C the flows whose rate
 * changed and F the flows in flight (plus a sort when the component's
 * flows have different bounds).
 */
#include "sim/net/net_internal.h"
#include <stdlib.h>
#include <string.h>


/* The fields the recomputation reads are copied from the message (path,
 * hops, bound, sequence), the path into the flow's own block, so that it
 * touches one record per flow; the search's fields come first. */
struct NetFlow {
    uint64_t mark;  /* component-search epoch */
    NetLink **path; /* its links: a copy of m->path after pos[] */
    guint hops;     /* m->hops */
    gboolean fixed; /* max-min scratch */
    double bw;      /* m->bw: the flow's bound */
    double rate;    /* B/s; 0 until first computed */
    uint64_t seq;   /* m->seq */
    NetMsg *m;
    double remaining; /* bytes still to move */
    double prev;      /* rate before the current recomputation */
    SimTime last;     /* when remaining was last brought up to date */
    SimTime end;      /* predicted completion at the current rate */
    guint hidx;       /* index in the end heap; G_MAXUINT if not in it */
    guint pos[];      /* index of this flow in each path link's array;
                         then the path copy */
};

/* Bytes of a flow's block: the record, pos[] (padded to 8) and the path. */
static size_t flow_bytes(guint hops)
{
    return sizeof(NetFlow) + ((hops * sizeof(guint) + 7) & ~(size_t)7) +
           hops * sizeof(NetLink *);
}

typedef struct {
    double share;
    NetLink *l;
} HeapEnt;

/* A growable array of pointers (scratch; the inner loops push inline). */
typedef struct {
    void **a;
    guint n, cap;
} PtrVec;

static inline void vec_push(PtrVec *v, void *p)
{
    if (v->n == v->cap) {
        v->cap = v->cap ? 2 * v->cap : 64;
        v->a = g_renew(void *, v->a, v->cap);
    }
    v->a[v->n++] = p;
}

typedef struct {
    uint64_t epoch;
    gboolean pending; /* a recomputation is scheduled at now */
    PtrVec dirty;     /* NetLink *, may repeat */
    PtrVec clinks;    /* component scratch */
    PtrVec cflows;    /* NetFlow * */
    HeapEnt *lh;      /* link min-heap on share */
    guint lh_n, lh_cap;
    NetFlow **eh; /* end heap: flows in flight by (end, seq) */
    guint eh_n, eh_cap;
    uint32_t timer_gen; /* generation of the armed timer */
    gboolean armed;
    SimTime timer_at;
    /* Lower bound on the level of this batch's changes: the least rate of
     * an ended flow, bound of a new one (see collect_component). */
    double level;
} FlowNet;

static FlowNet *flow_net(NetNet *n)
{
    void **slot = net_tp_slot(n);
    if (!*slot) {
        *slot = g_new0(FlowNet, 1);
        ((FlowNet *)*slot)->level = G_MAXDOUBLE;
    }
    return *slot;
}

static void flow_free_net(NetNet *n)
{
    FlowNet *fn = *net_tp_slot(n);
    if (!fn)
        return;
    for (guint i = 0; i < fn->eh_n; i++) { /* flows still in flight */
        g_free(fn->eh[i]);
    }
    g_free(fn->dirty.a);
    g_free(fn->clinks.a);
    g_free(fn->cflows.a);
    g_free(fn->lh);
    g_free(fn->eh);
    g_free(fn);
}

/* ---- link membership ---- */

/* A link with no more flows than channels cannot constrain any of its
 * flows (its capacity covers every flow's bound), so it does not join
 * their rates: the search expands only through links that can. */
static gboolean can_bind(const NetLink *l)
{
    return l->n_flows > l->channels;
}


static void link_add_flow(NetNet *n, NetLink *l, NetFlow *f, guint hop)
{
    if (l->n_flows == l->cap_flows) {
        guint cap = l->cap_flows ? 2 * l->cap_flows : 4;
        l->flows = g_renew(NetFlowRef, l->flows, cap);
        net_account(n, (gssize)((cap - l->cap_flows) * sizeof(NetFlowRef)));
        l->cap_flows = cap;
    }
    f->pos[hop] = l->n_flows;
    l->flows[l->n_flows++] = (NetFlowRef){f, hop};
}

static void link_remove_flow(NetLink *l, NetFlow *f, guint hop)
{
    guint i = f->pos[hop];
    g_assert(i < l->n_flows && l->flows[i].f == f);
    NetFlowRef last = l->flows[--l->n_flows];
    if (i < l->n_flows) {
        l->flows[i] = last;
        last.f->pos[last.hop] = i;
    }
}

/* ---- link heap (min on share) ---- */

static void lh_push(FlowNet *fn, double share, NetLink *l)
{
    if (fn->lh_n == fn->lh_cap) {
        fn->lh_cap = fn->lh_cap ? 2 * fn->lh_cap : 64;
        fn->lh = g_renew(HeapEnt, fn->lh, fn->lh_cap);
    }
    HeapEnt *a = fn->lh, e = {share, l};
    guint i = fn->lh_n++;
    while (i > 0 && a[(i - 1) / 2].share > share) {
        a[i] = a[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    a[i] = e;
}

/* Places e at hole i of the heap a[0 .. n), moving smaller children up. */
static void lh_sift_down(HeapEnt *a, guint n, guint i, HeapEnt e)
{
    for (;;) {
        guint c = 2 * i + 1;
        if (c >= n)
            break;
        if (c + 1 < n && a[c + 1].share < a[c].share)
            c++;
        if (a[c].share >= e.share)
            break;
        a[i] = a[c];
        i = c;
    }
    a[i] = e;
}

static void lh_pop(FlowNet *fn)
{
    HeapEnt last = fn->lh[--fn->lh_n];
    if (fn->lh_n > 0)
        lh_sift_down(fn->lh, fn->lh_n, 0, last);
}

/* The link with the least current share, or NULL when every link is
 * saturated; *share gets that share.  Re-keys stale tops lazily. */
static NetLink *lh_min(FlowNet *fn, double *share)
{
    while (fn->lh_n > 0) {
        HeapEnt top = fn->lh[0];
        NetLink *l = top.l;
        if (l->unfixed == 0) {
            lh_pop(fn);
            continue;
        }
        double cur = l->rem / l->unfixed;
        if (cur > top.share) {
            lh_pop(fn);
            lh_push(fn, cur, l);
            continue;
        }
        *share = cur;
        return l;
    }
    return NULL;
}

/* ---- max-min by progressive filling ---- */

static void fix_flow(NetFlow *f, double rate)
{
    f->fixed = TRUE;
    f->rate = rate;
    for (guint i = 0; i < f->hops; i++) {
        NetLink *l = f->path[i];
        if (!can_bind(l))
            continue;
        l->rem = l->rem > rate ? l->rem - rate : 0.0;
        l->unfixed--;
    }
}

static int by_bound(const void *a, const void *b)
{
    const NetFlow *x = *(NetFlow *const *)a, *y = *(NetFlow *const *)b;
    if (x->bw != y->bw)
        return x->bw < y->bw ? -1 : 1;
    return x->seq < y->seq ? -1 : (x->seq > y->seq);
}

/* Flows in order of their bound (a flow's path channel bandwidth); with
 * one common bound (the usual case) any order gives the same rates. */
static void order_by_bound(PtrVec *flows)
{
    NetFlow **f = (NetFlow **)flows->a;
    for (guint i = 1; i < flows->n; i++) {
        if (f[0]->bw != f[i]->bw) {
            qsort(f, flows->n, sizeof *f, by_bound);
            return;
        }
    }
}

/* Floyd's bottom-up heap construction over lh[0 .. lh_n): O(L). */
static void lh_heapify(FlowNet *fn)
{
    HeapEnt *a = fn->lh;
    guint n = fn->lh_n;
    for (guint k = n / 2; k-- > 0;)
        lh_sift_down(a, n, k, a[k]);
}

/* The component's links start at their capacity less the rates of their
 * frozen flows (marked fixed by the search).  Only links that can bind
 * are in the component (a link with no more flows than channels has a
 * share >= bw, the bound of every flow crossing it, and shares only
 * rise); fix_flow charges only those. */
static void maxmin_links(FlowNet *fn)
{
    if (fn->lh_cap < fn->clinks.n) {
        fn->lh_cap = fn->clinks.n;
        fn->lh = g_renew(HeapEnt, fn->lh, fn->lh_cap);
    }
    fn->lh_n = 0;
    for (guint i = 0; i < fn->clinks.n; i++) {
        NetLink *l = fn->clinks.a[i];
        double rem = l->bw * l->channels;
        guint unfixed = 0;
        for (guint j = 0; j < l->n_flows; j++) {
            const NetFlow *f = l->flows[j].f;
            if (f->fixed)
                rem -= f->rate;
            else
                unfixed++;
        }
        l->rem = rem > 0.0 ? rem : 0.0;
        l->unfixed = unfixed;
        if (unfixed > 0)
            fn->lh[fn->lh_n++] = (HeapEnt){l->rem / unfixed, l};
    }
    lh_heapify(fn);
}

static void maxmin(FlowNet *fn)
{
    maxmin_links(fn); /* the search left collected flows unfixed */
    order_by_bound(&fn->cflows);
    NetFlow **flows = (NetFlow **)fn->cflows.a;
    guint nf = fn->cflows.n;
    for (guint next = 0; next < nf;) {
        NetFlow *bf = flows[next];
        if (bf->fixed) {
            next++;
            continue;
        }
        double share = 0.0;
        NetLink *l = lh_min(fn, &share);
        if (!l || bf->bw <= share) {
            fix_flow(bf, bf->bw);
            continue;
        }
        lh_pop(fn);
        for (guint i = 0; i < l->n_flows; i++)
            if (!l->flows[i].f->fixed)
                fix_flow(l->flows[i].f, share);
    }
}

/* ---- component search ---- */

static void visit_link(FlowNet *fn, NetLink *l)
{
    if (l->mark == fn->epoch || !can_bind(l))
        return;
    l->mark = fn->epoch;
    vec_push(&fn->clinks, l);
}

/* A flow whose rate is below the batch's level keeps it (with a margin
 * so that rounding can only make a flow unfrozen); a new flow has rate 0
 * and is never frozen. */
static gboolean frozen(const NetFlow *f, double level)
{
    return f->rate > 0.0 && f->rate < level * (1.0 - 1e-9);
}

static void visit_flow(FlowNet *fn, NetFlow *f, double level)
{
    if (f->mark == fn->epoch)
        return;
    f->mark = fn->epoch;
    f->fixed = frozen(f, level);
    if (f->fixed)
        return;
    vec_push(&fn->cflows, f);
    for (guint k = 0; k < f->hops; k++)
        visit_link(fn, f->path[k]);
}

/* The batch's level: at most the least rate of an ended flow, the least
 * bound of a new one, and capacity / flows on every dirty link. */
static double batch_level(FlowNet *fn)
{
    double level = fn->level;
    fn->level = G_MAXDOUBLE;
    for (guint i = 0; i < fn->dirty.n; i++) {
        const NetLink *l = fn->dirty.a[i];
        if (l->n_flows > 0 && l->bw * l->channels / l->n_flows < level)
            level = l->bw * l->channels / l->n_flows;
    }
    return level;
}

/* The flows whose rate can change.  Progressive filling runs identically
 * below the batch's level L in the old and the new problem: an ended flow
 * was unfixed below its rate, so no link of it saturated there; a new
 * flow's links carry at most n * t < capacity at a level t < L (L <=
 * capacity / n after the batch), so none saturates there, and in the old
 * problem those links carried less.  So a flow with a rate below L keeps
 * it (frozen: not collected, its rate taken off its links' capacity).
 * The rest: the unfrozen flows on dirty links (a link that stopped
 * binding frees them) and everything joined to them by unfrozen flows
 * through links that can bind; elsewhere the constraints are unchanged,
 * and a max-min allocation splits over independent constraint sets. */
static void collect_component(FlowNet *fn)
{
    double level = batch_level(fn);
    fn->epoch++;
    fn->clinks.n = 0;
    fn->cflows.n = 0;
    for (guint i = 0; i < fn->dirty.n; i++) {
        NetLink *l = fn->dirty.a[i];
        for (guint j = 0; j < l->n_flows; j++)
            visit_flow(fn, l->flows[j].f, level);
    }
    fn->dirty.n = 0;
    for (guint i = 0; i < fn->clinks.n; i++) {
        NetLink *l = fn->clinks.a[i];
        for (guint j = 0; j < l->n_flows; j++)
            visit_flow(fn, l->flows[j].f, level);
    }
}

/* ---- end heap: flows by (end, send sequence) ---- */

static gboolean ends_before(const NetFlow *a, const NetFlow *b)
{
    return a->end < b->end || (a->end == b->end && a->seq < b->seq);
}

static void eh_set(FlowNet *fn, guint i, NetFlow *f)
{
    fn->eh[i] = f;
    f->hidx = i;
}

static void eh_up(FlowNet *fn, guint i)
{
    NetFlow *f = fn->eh[i];
    while (i > 0 && ends_before(f, fn->eh[(i - 1) / 2])) {
        eh_set(fn, i, fn->eh[(i - 1) / 2]);
        i = (i - 1) / 2;
    }
    eh_set(fn, i, f);
}

static void eh_down(FlowNet *fn, guint i)
{
    NetFlow *f = fn->eh[i];
    for (;;) {
        guint c = 2 * i + 1;
        if (c >= fn->eh_n)
            break;
        if (c + 1 < fn->eh_n && ends_before(fn->eh[c + 1], fn->eh[c]))
            c++;
        if (!ends_before(fn->eh[c], f))
            break;
        eh_set(fn, i, fn->eh[c]);
        i = c;
    }
    eh_set(fn, i, f);
}

/* Inserts f, or moves it after its end changed. */
static void eh_update(FlowNet *fn, NetFlow *f)
{
    if (f->hidx == G_MAXUINT) {
        if (fn->eh_n == fn->eh_cap) {
            fn->eh_cap = fn->eh_cap ? 2 * fn->eh_cap : 64;
            fn->eh = g_renew(NetFlow *, fn->eh, fn->eh_cap);
        }
        f->hidx = fn->eh_n++;
        fn->eh[f->hidx] = f;
    }
    eh_up(fn, f->hidx);
    eh_down(fn, f->hidx);
}

static NetFlow *eh_pop(FlowNet *fn)
{
    NetFlow *top = fn->eh[0];
    top->hidx = G_MAXUINT;
    if (--fn->eh_n > 0) {
        eh_set(fn, 0, fn->eh[fn->eh_n]);
        eh_down(fn, 0);
    }
    return top;
}

/* ---- events ---- */

static void request_recompute(NetNet *n, FlowNet *fn);
static void on_timer(SimEngine *eng, void *ctx, void *arg);

/* Arms the engine timer for the earliest predicted end, unless one at or
 * before it is armed already (an early timer simply re-arms). */
static void arm_timer(NetNet *n, FlowNet *fn)
{
    if (fn->eh_n == 0)
        return;
    SimTime t = fn->eh[0]->end;
    if (fn->armed && fn->timer_at <= t)
        return;
    fn->armed = TRUE;
    fn->timer_at = t;
    fn->timer_gen++;
    sim_schedule_at(net_eng(n), t, on_timer, n,
                    GUINT_TO_POINTER(fn->timer_gen));
}

static void flow_finish(NetNet *n, FlowNet *fn, NetFlow *f)
{
    NetMsg *m = f->m;
    fn->level = f->rate < fn->level ? f->rate : fn->level;
    for (guint i = 0; i < m->hops; i++) {
        link_remove_flow(m->path[i], f, i);
        vec_push(&fn->dirty, m->path[i]);
    }
    request_recompute(n, fn);
    net_account(n, -(gssize)flow_bytes(m->hops));
    g_free(f);
    net_msg_deliver(n, m);
}

static void on_timer(SimEngine *eng, void *ctx, void *arg)
{
    NetNet *n = ctx;
    FlowNet *fn = flow_net(n);
    if (GPOINTER_TO_UINT(arg) != fn->timer_gen)
        return; /* superseded by an earlier timer */
    fn->armed = FALSE;
    SimTime now = sim_now(eng);
    while (fn->eh_n > 0 && fn->eh[0]->end <= now)
        flow_finish(n, fn, eh_pop(fn));
    arm_timer(n, fn);
}

/* Brings the component's flows up to now and remembers their rates. */
static void advance_flows(FlowNet *fn, SimTime now)
{
    for (guint i = 0; i < fn->cflows.n; i++) {
        NetFlow *f = fn->cflows.a[i];
        f->remaining -= f->rate * (double)(now - f->last) * 1e-12;
        if (f->remaining < 0.0)
            f->remaining = 0.0;
        f->last = now;
        f->prev = f->rate;
    }
}

static void recompute(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    NetNet *n = ctx;
    FlowNet *fn = flow_net(n);
    fn->pending = FALSE;
    SimTime now = sim_now(eng);
    collect_component(fn);
    advance_flows(fn, now);
    maxmin(fn);
    for (guint i = 0; i < fn->cflows.n; i++) {
        NetFlow *f = fn->cflows.a[i];
        g_assert(f->rate > 0.0);
        if (f->rate == f->prev)
            continue;
        f->end = now + (f->remaining > 0.0
                            ? sim_time_for_bytes(f->remaining, f->rate)
                            : 0);
        eh_update(fn, f);
    }
    arm_timer(n, fn);
}

static void request_recompute(NetNet *n, FlowNet *fn)
{
    if (fn->pending)
        return;
    fn->pending = TRUE;
    sim_schedule_in(net_eng(n), 0, recompute, n, NULL);
}

static void flow_begin(SimEngine *eng, void *ctx, void *arg)
{
    NetNet *n = ctx;
    NetMsg *m = arg;
    if (m->bytes == 0) {
        net_msg_deliver(n, m);
        return;
    }
    FlowNet *fn = flow_net(n);
    size_t bytes = flow_bytes(m->hops);
    NetFlow *f = g_malloc0(bytes);
    f->m = m;
    f->path = (NetLink **)((char *)f + bytes - m->hops * sizeof(NetLink *));
    memcpy(f->path, m->path, m->hops * sizeof(NetLink *));
    f->hops = m->hops;
    f->bw = m->bw;
    f->seq = m->seq;
    f->remaining = (double)m->bytes;
    f->last = sim_now(eng);
    f->hidx = G_MAXUINT;
    fn->level = f->bw < fn->level ? f->bw : fn->level;
    net_account(n, (gssize)bytes);
    for (guint i = 0; i < m->hops; i++) {
        link_add_flow(n, m->path[i], f, i);
        vec_push(&fn->dirty, m->path[i]);
    }
    request_recompute(n, fn);
}

static void flow_start(NetNet *n, NetMsg *m)
{
    sim_schedule_in(net_eng(n), net_msg_latency(n, m), flow_begin, n, m);
}

const NetTransportOps net_flow_transport = {
    .name = "flow",
    .start = flow_start,
    .free = flow_free_net,
};
