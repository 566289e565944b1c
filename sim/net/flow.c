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
 * Incremental: a start or an end marks the links it touches dirty and asks
 * for one recomputation at the current instant (so all starts and ends at
 * the same time are batched).  The recomputation visits only the connected
 * component of links and flows reachable from dirty links; flows elsewhere
 * keep their rates and their completion events.  The engine cannot cancel
 * events: each flow has a generation, bumped whenever its rate changes, and
 * a completion event whose generation is stale does nothing.  A flow is
 * freed when it is done and no event refers to it any more.
 *
 * Invariants: a lone flow finishes at exactly the analytic time; every
 * link's flows' rates sum to at most its capacity (up to rounding).
 * Cost per recomputation: O(E log E) for E = sum of path lengths of the
 * component's flows.
 */
#include "sim/net/net_internal.h"

struct NetFlow {
    NetNet *net;
    NetMsg *m;        /* NULL once delivered */
    double remaining; /* bytes still to move */
    double rate;      /* B/s; 0 until first computed */
    SimTime last;     /* when remaining was last brought up to date */
    uint32_t gen;     /* current completion event's generation */
    uint32_t events;  /* scheduled events that refer to this flow */
    gboolean done;
    gboolean fixed;   /* max-min scratch */
    uint64_t mark;    /* component-search epoch */
    guint hops;       /* path length (m is gone once done) */
    guint *pos;       /* index of this flow in each path link's array */
};

typedef struct {
    double share;
    NetLink *l;
    guint ver;
} HeapEnt;

typedef struct {
    uint64_t epoch;
    gboolean pending;  /* a recomputation is scheduled at now */
    GPtrArray *dirty;  /* NetLink *, may repeat */
    GPtrArray *clinks; /* component scratch */
    GPtrArray *cflows;
    GArray *heap;      /* HeapEnt, binary min-heap on share */
} FlowNet;

static FlowNet *flow_net(NetNet *n)
{
    void **slot = net_tp_slot(n);
    if (!*slot) {
        FlowNet *fn = g_new0(FlowNet, 1);
        fn->dirty = g_ptr_array_new();
        fn->clinks = g_ptr_array_new();
        fn->cflows = g_ptr_array_new();
        fn->heap = g_array_new(FALSE, FALSE, sizeof(HeapEnt));
        *slot = fn;
    }
    return *slot;
}

static void flow_free_net(NetNet *n)
{
    FlowNet *fn = *net_tp_slot(n);
    if (!fn)
        return;
    g_ptr_array_free(fn->dirty, TRUE);
    g_ptr_array_free(fn->clinks, TRUE);
    g_ptr_array_free(fn->cflows, TRUE);
    g_array_free(fn->heap, TRUE);
    g_free(fn);
}

/* ---- link membership ---- */

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

/* ---- max-min by progressive filling ---- */

static void heap_push(GArray *h, HeapEnt e)
{
    g_array_append_val(h, e);
    HeapEnt *a = (HeapEnt *)h->data;
    guint i = h->len - 1;
    while (i > 0 && a[(i - 1) / 2].share > a[i].share) {
        HeapEnt t = a[i];
        a[i] = a[(i - 1) / 2];
        a[(i - 1) / 2] = t;
        i = (i - 1) / 2;
    }
}

static HeapEnt heap_pop(GArray *h)
{
    HeapEnt *a = (HeapEnt *)h->data, top = a[0];
    a[0] = a[h->len - 1];
    g_array_set_size(h, h->len - 1);
    guint i = 0, n = h->len;
    for (;;) {
        guint c = 2 * i + 1, m = i;
        if (c < n && a[c].share < a[m].share)
            m = c;
        if (c + 1 < n && a[c + 1].share < a[m].share)
            m = c + 1;
        if (m == i)
            break;
        HeapEnt t = a[i];
        a[i] = a[m];
        a[m] = t;
        i = m;
    }
    return top;
}

static void push_link(GArray *h, NetLink *l)
{
    if (l->unfixed == 0)
        return;
    l->hpos++;
    HeapEnt e = {l->rem / l->unfixed, l, l->hpos};
    heap_push(h, e);
}

static void fix_flow(GArray *h, NetFlow *f, double rate)
{
    f->fixed = TRUE;
    f->rate = rate;
    for (guint i = 0; i < f->m->hops; i++) {
        NetLink *l = f->m->path[i];
        l->rem = l->rem > rate ? l->rem - rate : 0.0;
        l->unfixed--;
        push_link(h, l);
    }
}

static gint by_bound(gconstpointer a, gconstpointer b)
{
    const NetFlow *x = *(NetFlow *const *)a, *y = *(NetFlow *const *)b;
    if (x->m->bw != y->m->bw)
        return x->m->bw < y->m->bw ? -1 : 1;
    return x->m->seq < y->m->seq ? -1 : (x->m->seq > y->m->seq);
}

static void maxmin(FlowNet *fn)
{
    GArray *h = fn->heap;
    g_array_set_size(h, 0);
    for (guint i = 0; i < fn->clinks->len; i++) {
        NetLink *l = g_ptr_array_index(fn->clinks, i);
        l->rem = l->bw * l->channels;
        l->unfixed = l->n_flows;
        push_link(h, l);
    }
    g_ptr_array_sort(fn->cflows, by_bound);
    guint next = 0, nf = fn->cflows->len;
    for (guint i = 0; i < nf; i++)
        ((NetFlow *)g_ptr_array_index(fn->cflows, i))->fixed = FALSE;
    while (next < nf) {
        NetFlow *bf = g_ptr_array_index(fn->cflows, next);
        if (bf->fixed) {
            next++;
            continue;
        }
        while (h->len > 0) {
            HeapEnt top = g_array_index(h, HeapEnt, 0);
            if (top.ver == top.l->hpos && top.l->unfixed > 0)
                break;
            heap_pop(h);
        }
        if (h->len == 0 || bf->m->bw <= g_array_index(h, HeapEnt, 0).share) {
            fix_flow(h, bf, bf->m->bw);
            continue;
        }
        HeapEnt top = heap_pop(h);
        for (guint i = 0; i < top.l->n_flows; i++) {
            NetFlow *f = top.l->flows[i].f;
            if (!f->fixed)
                fix_flow(h, f, top.share);
        }
    }
}

/* ---- component search ---- */

static void visit_link(FlowNet *fn, NetLink *l)
{
    if (l->mark == fn->epoch || l->n_flows == 0)
        return;
    l->mark = fn->epoch;
    g_ptr_array_add(fn->clinks, l);
}

static void collect_component(FlowNet *fn)
{
    fn->epoch++;
    g_ptr_array_set_size(fn->clinks, 0);
    g_ptr_array_set_size(fn->cflows, 0);
    for (guint i = 0; i < fn->dirty->len; i++)
        visit_link(fn, g_ptr_array_index(fn->dirty, i));
    g_ptr_array_set_size(fn->dirty, 0);
    for (guint i = 0; i < fn->clinks->len; i++) {
        NetLink *l = g_ptr_array_index(fn->clinks, i);
        for (guint j = 0; j < l->n_flows; j++) {
            NetFlow *f = l->flows[j].f;
            if (f->mark == fn->epoch)
                continue;
            f->mark = fn->epoch;
            g_ptr_array_add(fn->cflows, f);
            for (guint k = 0; k < f->m->hops; k++)
                visit_link(fn, f->m->path[k]);
        }
    }
}

/* ---- events ---- */

static void flow_release(NetNet *n, NetFlow *f)
{
    if (!f->done || f->events > 0)
        return;
    net_account(n, -(gssize)(sizeof *f + f->hops * sizeof(guint)));
    g_free(f->pos);
    g_free(f);
}

static void request_recompute(NetNet *n, FlowNet *fn);

static void flow_complete(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    NetFlow *f = ctx;
    NetNet *n = f->net;
    f->events--;
    if (GPOINTER_TO_UINT(arg) != f->gen || f->done) {
        flow_release(n, f);
        return;
    }
    NetMsg *m = f->m;
    FlowNet *fn = flow_net(n);
    for (guint i = 0; i < m->hops; i++) {
        link_remove_flow(m->path[i], f, i);
        g_ptr_array_add(fn->dirty, m->path[i]);
    }
    request_recompute(n, fn);
    f->done = TRUE;
    f->m = NULL;
    net_msg_deliver(n, m);
    flow_release(n, f);
}

static void schedule_completion(NetNet *n, NetFlow *f)
{
    SimTime dt = f->remaining > 0.0
                     ? sim_time_for_bytes(f->remaining, f->rate)
                     : 0;
    f->gen++;
    f->events++;
    sim_schedule_in(net_eng(n), dt, flow_complete, f,
                    GUINT_TO_POINTER(f->gen));
}

static void recompute(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    NetNet *n = ctx;
    FlowNet *fn = flow_net(n);
    fn->pending = FALSE;
    SimTime now = sim_now(eng);
    collect_component(fn);
    for (guint i = 0; i < fn->cflows->len; i++) {
        NetFlow *f = g_ptr_array_index(fn->cflows, i);
        f->remaining -= f->rate * (double)(now - f->last) * 1e-12;
        if (f->remaining < 0.0)
            f->remaining = 0.0;
        f->last = now;
    }
    GArray *old = g_array_sized_new(FALSE, FALSE, sizeof(double),
                                    fn->cflows->len);
    for (guint i = 0; i < fn->cflows->len; i++) {
        NetFlow *f = g_ptr_array_index(fn->cflows, i);
        g_array_append_val(old, f->rate);
    }
    maxmin(fn);
    for (guint i = 0; i < fn->cflows->len; i++) {
        NetFlow *f = g_ptr_array_index(fn->cflows, i);
        g_assert(f->rate > 0.0);
        if (f->rate != g_array_index(old, double, i))
            schedule_completion(n, f);
    }
    g_array_free(old, TRUE);
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
    NetFlow *f = g_new0(NetFlow, 1);
    f->net = n;
    f->m = m;
    f->hops = m->hops;
    f->remaining = (double)m->bytes;
    f->last = sim_now(eng);
    f->pos = g_new(guint, m->hops);
    net_account(n, (gssize)(sizeof *f + m->hops * sizeof(guint)));
    for (guint i = 0; i < m->hops; i++) {
        link_add_flow(n, m->path[i], f, i);
        g_ptr_array_add(fn->dirty, m->path[i]);
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
