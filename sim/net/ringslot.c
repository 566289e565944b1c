/* ringslot.c — ring slots: the Pixel-Planes 5 ring network.
 *
 * The ring has `channels` parallel channels, each a unidirectional ring of
 * station-to-station segments (Fuchs et al., "Pixel-Planes 5: a
 * heterogeneous multiprocessor graphics system using processor-enhanced
 * memories", SIGGRAPH 1989: several simultaneous messages on a 640 MB/s
 * ring).  A message travels on one channel: after the start-up it claims,
 * atomically, the same channel on every segment from source to
 * destination (the lowest-numbered channel whose segments are all free),
 * then its words stream one station per slot time (per_hop) at the channel
 * bandwidth, so it holds the segments for hops * per_hop + bytes / bw.
 * A message that finds no channel free waits in one FIFO per ring; every
 * release rescans that FIFO in order and starts each waiter that now fits
 * (first fit: a later message whose segments are free may pass a blocked
 * earlier one, but never one with the same path, so each source-
 * destination pair delivers in send order).  Atomic claims cannot
 * deadlock, unlike hop-by-hop holding on a cycle.
 *
 * Trace hook (sim/core/trace.h): when the engine's trace listens, a
 * claim reports the hold of its channel on every segment of the path
 * over [claim, release) with the message's bytes, and a message that
 * found no channel free reports its wait [request, claim) on its first
 * segment (where it waits: its source station's queue).  The reports
 * add no events (docs/traces.md).
 *
 * Invariants: a lone message takes the analytic time.  Cost per release:
 * O(waiters * hops * channels).
 */
#include "sim/net/net_internal.h"
#include "sim/core/trace.h"

typedef struct {
    GQueue wait; /* NetMsg *, FIFO by request */
} RingNet;

static RingNet *ring_net(NetNet *n)
{
    void **slot = net_tp_slot(n);
    if (!*slot) {
        RingNet *r = g_new0(RingNet, 1);
        g_queue_init(&r->wait);
        *slot = r;
    }
    return *slot;
}

static void ring_free_net(NetNet *n)
{
    RingNet *r = *net_tp_slot(n);
    if (!r)
        return;
    g_queue_clear(&r->wait);
    g_free(r);
}

static gboolean channel_free(NetMsg *m, uint32_t c)
{
    for (guint i = 0; i < m->hops; i++) {
        NetLink *l = m->path[i];
        if (!l->holder)
            l->holder = g_new0(NetMsg *, l->channels);
        if (c >= l->channels || l->holder[c])
            return FALSE;
    }
    return TRUE;
}

static void ring_done(SimEngine *eng, void *ctx, void *arg);

/* m claims its path now until now + t: tells the trace. */
static void trace_claim(NetNet *n, const NetMsg *m, SimTime t)
{
    SimTrace *tr = sim_engine_trace(net_eng(n));
    if (!sim_trace_wants_holds(tr))
        return;
    SimTime now = sim_now(net_eng(n));
    SimTime asked = m->sent + net_startup(net_par(n), m->bytes);
    char name[64];
    for (guint i = 0; i < m->hops; i++) {
        net_link_name(n, m->path[i]->id, name, sizeof name);
        if (i == 0 && now > asked)
            sim_trace_wait(tr, m->path[i]->id, name, asked, now);
        sim_trace_hold(tr, m->path[i]->id, name, m->bytes, now, now + t);
    }
}

static gboolean try_claim(NetNet *n, NetMsg *m)
{
    uint32_t channels = m->path[0]->channels;
    for (uint32_t c = 0; c < channels; c++) {
        if (!channel_free(m, c))
            continue;
        for (guint i = 0; i < m->hops; i++)
            m->path[i]->holder[c] = m;
        m->step = c;
        SimTime t = sim_time_mul_sat(net_par(n)->per_hop, m->hops);
        if (m->bytes)
            t += sim_time_for_bytes((double)m->bytes, m->bw);
        trace_claim(n, m, t);
        sim_schedule_in(net_eng(n), t, ring_done, n, m);
        return TRUE;
    }
    return FALSE;
}

static void rescan(NetNet *n, RingNet *r)
{
    GList *it = r->wait.head;
    while (it) {
        GList *next = it->next;
        if (try_claim(n, it->data))
            g_queue_delete_link(&r->wait, it);
        it = next;
    }
}

static void ring_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    NetNet *n = ctx;
    NetMsg *m = arg;
    for (guint i = 0; i < m->hops; i++)
        m->path[i]->holder[m->step] = NULL;
    net_msg_deliver(n, m);
    rescan(n, ring_net(n));
}

static void ring_request(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    NetNet *n = ctx;
    /* Nothing was released since the waiters were last scanned, so only
     * the newcomer can fit now. */
    if (!try_claim(n, arg))
        g_queue_push_tail(&ring_net(n)->wait, arg);
}

static void ring_start(NetNet *n, NetMsg *m)
{
    sim_schedule_in(net_eng(n), net_startup(net_par(n), m->bytes), ring_request,
                    n, m);
}

const NetTransportOps net_ringslot_transport = {
    .name = "ring-slots",
    .start = ring_start,
    .free = ring_free_net,
};
