/* net.c — the network: lazy link table, message life cycle, statistics,
 * and the analytic transport.
 *
 * Links live in a hash table keyed by link id and are created the first
 * time a message's route crosses them, so memory grows with the traffic,
 * not with the machine (a 65,536-node hypercube carrying one message holds
 * a handful of links).  Every message is routed once at send time; its
 * path holds borrowed NetLink pointers.  The transport (chosen from the
 * fidelity and NetParams.switching) takes it from there and calls
 * net_msg_deliver() at arrival.
 *
 * Analytic time: startup + hops * per_hop + bytes / min channel bandwidth
 * (startup: NetParams.startup_long for messages above long_threshold)
 * on the path (the classical linear model, e.g. Hockney, Parallel
 * Computing 20, 1994).  Cost: O(hops) per send, O(1) per delivery;
 * memory O(links touched + messages in flight).
 */
#include "sim/net/net_internal.h"
#include "sim/core/record.h"
#include "sim/core/trace.h"
#include <string.h>

typedef struct {
    NetLinkId id;
    NetLink *l; /* NULL: empty slot */
} LinkSlot;

struct NetNet {
    SimEngine *eng;
    const NetTopo *topo;
    NetParams par;
    NetFidelity fid;
    const NetTransportOps *tp;
    void *tp_state;
    LinkSlot *links; /* open addressing by link id, NetLink * owned */
    guint links_n, links_cap; /* links_cap a power of two, load <= 1/2 */
    NetLinkId *route;  /* scratch, max_hops entries */
    uint64_t seq;
    uint64_t bytes, messages, delivered;
    gssize mem; /* bytes held by links and messages in flight */
    NetMsg *live;      /* messages in flight, a doubly linked list */
    GHashTable *owned; /* objects freed with the net (net_own) */
};

static const NetTransportOps *pick_transport(const NetParams *p,
                                             NetFidelity fid)
{
    if (fid == NET_ANALYTIC)
        return &net_analytic_transport;
    if (fid == NET_FLOW)
        return p->switching == NET_SW_CIRCUIT ? &net_circuit_flow_transport
                                              : &net_flow_transport;
    switch (p->switching) {
    case NET_SW_CIRCUIT:
        return &net_circuit_transport;
    case NET_SW_RING_SLOTS:
        return &net_ringslot_transport;
    default:
        return &net_packet_transport;
    }
}

/* The link table: open addressing with linear probing, ids inline (one
 * cache line per lookup in the common case, no comparison callback).
 * Link ids are topology-packed (node, dimension or level fields); a
 * 64-bit finaliser spreads them (Stafford's mix13, the splitmix64
 * finaliser). */
static uint64_t link_hash(uint64_t x)
{
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

static NetLink *links_find(const NetNet *n, NetLinkId id)
{
    guint mask = n->links_cap - 1;
    for (guint i = (guint)link_hash(id) & mask;; i = (i + 1) & mask) {
        const LinkSlot *s = &n->links[i];
        if (!s->l || s->id == id)
            return s->l;
    }
}

static void links_put(LinkSlot *tab, guint cap, NetLink *l)
{
    guint i = (guint)link_hash(l->id) & (cap - 1);
    while (tab[i].l)
        i = (i + 1) & (cap - 1);
    tab[i] = (LinkSlot){l->id, l};
}

/* Doubles the table when it would pass half full. */
static void links_grow(NetNet *n)
{
    if (2 * (n->links_n + 1) <= n->links_cap)
        return;
    guint cap = 2 * n->links_cap;
    LinkSlot *tab = g_new0(LinkSlot, cap);
    for (guint i = 0; i < n->links_cap; i++)
        if (n->links[i].l)
            links_put(tab, cap, n->links[i].l);
    g_free(n->links);
    n->mem += (gssize)((cap - n->links_cap) * sizeof *tab);
    n->links = tab;
    n->links_cap = cap;
}

static void link_free(NetLink *l)
{
    g_free(l->flows);
    g_free(l->holder);
    g_queue_clear(&l->wait);
    g_free(l);
}

NetNet *net_new(SimEngine *eng, const NetTopo *topo, const NetParams *params,
                NetFidelity fid)
{
    g_assert(eng && topo && params);
    g_assert(params->bandwidth > 0.0);
    NetNet *n = g_new0(NetNet, 1);
    n->owned = g_hash_table_new(g_direct_hash, g_direct_equal);
    n->eng = eng;
    n->topo = topo;
    n->par = *params;
    if (n->par.channels == 0)
        n->par.channels = 1;
    if (n->par.packet_bytes == 0)
        n->par.packet_bytes = 1024;
    n->fid = fid;
    n->tp = pick_transport(&n->par, fid);
    n->links_cap = 16;
    n->links = g_new0(LinkSlot, n->links_cap);
    n->mem += (gssize)(n->links_cap * sizeof(LinkSlot));
    n->route = g_new(NetLinkId, topo->ops->max_hops(topo->state));
    return n;
}

static void live_unlink(NetNet *n, NetMsg *m)
{
    if (m->live_prev)
        m->live_prev->live_next = m->live_next;
    else
        n->live = m->live_next;
    if (m->live_next)
        m->live_next->live_prev = m->live_prev;
}

static void msg_free(NetMsg *m)
{
    g_free(m->path);
    g_free(m->chan);
    g_free(m);
}

void net_own(NetNet *n, void *obj, GDestroyNotify free_fn)
{
    g_hash_table_insert(n->owned, obj, free_fn);
}

void net_disown(NetNet *n, void *obj)
{
    g_hash_table_remove(n->owned, obj);
}

/* A run stopped early (run.until, a failed run) leaves messages in
 * flight and collectives unfinished; the net frees them. */
static void free_in_flight(NetNet *n)
{
    while (n->live) {
        NetMsg *m = n->live;
        live_unlink(n, m);
        msg_free(m);
    }
    GHashTableIter it;
    gpointer obj, fn;
    g_hash_table_iter_init(&it, n->owned);
    while (g_hash_table_iter_next(&it, &obj, &fn))
        ((GDestroyNotify)fn)(obj);
    g_hash_table_destroy(n->owned);
}

void net_free(NetNet *n)
{
    if (!n)
        return;
    if (n->tp->free)
        n->tp->free(n);
    free_in_flight(n);
    for (guint i = 0; i < n->links_cap; i++)
        if (n->links[i].l)
            link_free(n->links[i].l);
    g_free(n->links);
    g_free(n->route);
    g_free(n);
}

SimEngine *net_engine(const NetNet *n)
{
    return n->eng;
}
SimEngine *net_eng(NetNet *n)
{
    return n->eng;
}
const NetTopo *net_topo(const NetNet *n)
{
    return n->topo;
}
const NetParams *net_params(const NetNet *n)
{
    return &n->par;
}
const NetParams *net_par(NetNet *n)
{
    return &n->par;
}
NetFidelity net_fidelity(const NetNet *n)
{
    return n->fid;
}
void **net_tp_slot(NetNet *n)
{
    return &n->tp_state;
}
void net_account(NetNet *n, gssize b)
{
    n->mem += b;
}

uint32_t net_nodes(const NetNet *n)
{
    return net_topo_nodes(n->topo);
}

static NetLink *link_get(NetNet *n, NetLinkId id)
{
    NetLink *l = links_find(n, id);
    if (l)
        return l;
    links_grow(n);
    l = g_new0(NetLink, 1);
    l->id = id;
    l->bw = n->topo->ops->link_bw(n->topo->state, id, &n->par);
    l->channels = n->par.channels;
    g_assert(l->bw > 0.0);
    g_queue_init(&l->wait);
    links_put(n->links, n->links_cap, l);
    n->links_n++;
    n->mem += sizeof *l;
    return l;
}

static guint route(const NetNet *n, uint32_t src, uint32_t dst)
{
    if (src == dst)
        return 0;
    return n->topo->ops->route(n->topo->state, src, dst, n->route);
}

static SimTime latency(const NetParams *p, guint hops, uint64_t bytes)
{
    return net_startup(p, bytes) + sim_time_mul_sat(p->per_hop, hops);
}

SimTime net_msg_latency(const NetNet *n, const NetMsg *m)
{
    return latency(&n->par, m->hops, m->bytes);
}

SimTime net_ideal_time(const NetNet *n, uint32_t src, uint32_t dst,
                       uint64_t bytes)
{
    guint h = route(n, src, dst);
    double bw = n->par.bandwidth;
    for (guint i = 0; i < h; i++) {
        double b = n->topo->ops->link_bw(n->topo->state, n->route[i], &n->par);
        bw = i == 0 || b < bw ? b : bw;
    }
    SimTime t = latency(&n->par, h, bytes);
    if (h > 0 && bytes > 0)
        t = sim_time_add_sat(t, sim_time_for_bytes((double)bytes, bw));
    return t;
}

static void account_path(NetNet *n, NetMsg *m)
{
    for (guint i = 0; i < m->hops; i++) {
        NetLink *l = link_get(n, n->route[i]);
        m->path[i] = l;
        m->bw = i == 0 || l->bw < m->bw ? l->bw : m->bw;
        l->st.bytes += m->bytes;
        l->st.messages++;
        l->st.busy += sim_time_for_bytes((double)m->bytes, l->bw);
    }
}

void net_send(NetNet *n, uint32_t src, uint32_t dst, uint64_t bytes,
              void *payload, NetArriveFn cb, void *ctx)
{
    uint32_t nn = net_nodes(n);
    g_assert(src < nn && dst < nn);
    NetMsg *m = g_new0(NetMsg, 1);
    *m = (NetMsg){.net = n,
                  .seq = n->seq++,
                  .src = src,
                  .dst = dst,
                  .bytes = bytes,
                  .payload = payload,
                  .cb = cb,
                  .ctx = ctx,
                  .sent = sim_now(n->eng)};
    SimRecorder *rec = sim_engine_recorder(n->eng);
    if (rec)
        m->rec_id = rec->ops->send(rec, m->sent, src, dst, bytes, cb != NULL);
    m->live_next = n->live;
    if (n->live)
        n->live->live_prev = m;
    n->live = m;
    m->hops = route(n, src, dst);
    m->path = g_new(NetLink *, m->hops ? m->hops : 1);
    m->bw = n->par.bandwidth;
    account_path(n, m);
    n->mem += sizeof *m + m->hops * sizeof(NetLink *);
    n->bytes += bytes;
    n->messages++;
    if (m->hops == 0) {
        net_analytic_transport.start(n, m);
        return;
    }
    n->tp->start(n, m);
}

/* The trace's per-link view: the message on every link of its route
 * from its send to now (names are built only when a trace asks). */
static void trace_links(NetNet *n, SimTrace *tr, const NetMsg *m,
                        SimTime now)
{
    if (!sim_trace_wants_links(tr))
        return;
    char name[64];
    for (guint i = 0; i < m->hops; i++) {
        net_link_name(n, m->path[i]->id, name, sizeof name);
        sim_trace_link(tr, m->path[i]->id, name, m->bytes, m->sent, now);
    }
}

void net_msg_deliver(NetNet *n, NetMsg *m)
{
    SimTime now = sim_now(n->eng);
    NetDelivery d = {m->src,  m->dst, m->bytes, m->payload,
                     m->sent, now,    m->hops};
    n->delivered++;
    n->mem -= sizeof *m + m->hops * sizeof(NetLink *);
    SimTrace *tr = sim_engine_trace(n->eng);
    if (tr)
        sim_trace_flow(tr, m->src, sim_engine_node_name(n->eng, m->src),
                       m->dst, sim_engine_node_name(n->eng, m->dst), m->bytes,
                       m->sent, now);
    trace_links(n, tr, m, now);
    NetArriveFn cb = m->cb;
    void *ctx = m->ctx;
    uint64_t rec_id = m->rec_id;
    live_unlink(n, m);
    msg_free(m);
    SimRecorder *rec = sim_engine_recorder(n->eng);
    if (rec)
        rec->ops->begin(rec, rec_id, now);
    if (cb)
        cb(n, &d, ctx);
    if (rec)
        rec->ops->end(rec, rec_id);
}

/* ---- analytic transport ---- */

static void analytic_arrive(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    net_msg_deliver(ctx, arg);
}

static void analytic_start(NetNet *n, NetMsg *m)
{
    SimTime t = latency(&n->par, m->hops, m->bytes);
    if (m->hops > 0 && m->bytes > 0)
        t += sim_time_for_bytes((double)m->bytes, m->bw);
    sim_schedule_in(n->eng, t, analytic_arrive, n, m);
}

const NetTransportOps net_analytic_transport = {
    .name = "analytic",
    .start = analytic_start,
    .free = NULL,
};

/* ---- names and statistics ---- */

static const char *const fid_names[] = {"analytic", "flow", "packet"};

const char *net_fidelity_name(NetFidelity f)
{
    g_assert((unsigned)f < G_N_ELEMENTS(fid_names));
    return fid_names[f];
}

gboolean net_fidelity_parse(const char *s, NetFidelity *out)
{
    for (unsigned i = 0; i < G_N_ELEMENTS(fid_names); i++) {
        if (strcmp(s, fid_names[i]) == 0) {
            *out = (NetFidelity)i;
            return TRUE;
        }
    }
    return FALSE;
}

const SimLinkStats *net_link_stats(const NetNet *n, NetLinkId id)
{
    NetLink *l = links_find(n, id);
    return l ? &l->st : NULL;
}

guint net_links_touched(const NetNet *n)
{
    return n->links_n;
}

uint64_t net_total_bytes(const NetNet *n)
{
    return n->bytes;
}
uint64_t net_total_messages(const NetNet *n)
{
    return n->messages;
}
uint64_t net_delivered(const NetNet *n)
{
    return n->delivered;
}

gboolean net_busiest_link(const NetNet *n, NetLinkId *out)
{
    gboolean found = FALSE;
    uint64_t best = 0;
    for (guint i = 0; i < n->links_cap; i++) {
        NetLink *l = n->links[i].l;
        if (!l) /* a link exists once a message crossed it (account_path) */
            continue;
        if (!found || l->st.bytes > best ||
            (l->st.bytes == best && l->id < *out)) {
            best = l->st.bytes;
            *out = l->id;
            found = TRUE;
        }
    }
    return found;
}

void net_link_name(const NetNet *n, NetLinkId l, char *buf, size_t len)
{
    n->topo->ops->link_name(n->topo->state, l, buf, len);
}

void net_fill_result(const NetNet *n, SimResult *r)
{
    NetLinkId l;
    r->comm_bytes = n->bytes;
    r->comm_messages = n->messages;
    g_free(r->busiest_link);
    r->busiest_link = NULL;
    r->busiest_link_bytes = 0;
    if (net_busiest_link(n, &l)) {
        char buf[64];
        net_link_name(n, l, buf, sizeof buf);
        r->busiest_link = g_strdup(buf);
        r->busiest_link_bytes = net_link_stats(n, l)->bytes;
    }
    g_free(r->fidelity);
    r->fidelity = g_strdup(net_fidelity_name(n->fid));
}

size_t net_tracked_bytes(const NetNet *n)
{
    size_t fixed = sizeof *n + n->topo->state_bytes +
                   n->topo->ops->max_hops(n->topo->state) * sizeof(NetLinkId);
    return fixed + (size_t)n->mem;
}
