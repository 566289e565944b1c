/* collective.c — collectives as per-node step machines (collective.h).
 *
 * A NetColl holds a plan function mapping (node, step) to at most one
 * send and a number of receipts to wait for.  Node state: current step
 * and whether that step's send is unstarted, in flight or delivered;
 * receipts are counted per (node, step) because a fast partner's message
 * for step s can arrive while the node is still at an earlier step.
 * Receipts for a node's current step are a counter per node; the few
 * that arrive for a later step (a fast partner) wait in a hash table
 * keyed by (node, step), so memory is O(n) plus those early receipts,
 * never O(n * steps).  Byte counts and destinations come from a table
 * the caller gave, or are computed when the step starts (uniform
 * all-to-all, generated send lists): no n x n table is needed.
 * Messages carry their step number as payload and the NetColl as context.
 * The collective ends when every node has passed its last step and no
 * message is in flight; then the caller's callback runs and the NetColl
 * is freed.
 *
 * Invariants: a node never sends step s + 1 before its step s send is
 * delivered and its step s receipts are in; all schedules are
 * deterministic.  Cost: O(1) per step per node plus the messages.
 */
#include "sim/net/collective.h"
#include <string.h>

#define NO_SEND UINT32_MAX

typedef struct NetColl NetColl;

typedef struct {
    uint32_t to; /* NO_SEND: nothing to send at this step */
    uint64_t bytes;
    guint expect; /* receipts to wait for at this step */
} CollStep;

typedef CollStep (*CollPlan)(const NetColl *c, uint32_t node, guint step);

enum { ST_IDLE, ST_SENDING, ST_SENT };

struct NetColl {
    NetNet *net;
    uint32_t n;
    guint steps;
    unsigned dims;
    CollPlan plan;
    uint32_t root;
    uint64_t bytes;
    uint64_t *table; /* a2a matrix, pairwise steps or list sizes; NULL:
                        uniform c->bytes (a2a) or generated (lists) */
    NetGenFn gen;    /* generated send lists */
    void *gen_ctx;
    uint32_t *dst;   /* send lists */
    uint32_t *off, *count;
    guint *step;    /* per node */
    uint8_t *state; /* per node: ST_* of the current step */
    gboolean receipts; /* the schedule expects receipts */
    guint *recvd;      /* per node: receipts for its current step */
    GHashTable *early; /* (node * steps + step) -> receipts for later steps */
    uint32_t nodes_left;
    uint64_t inflight;
    NetCollDone done;
    void *ctx;
};

static unsigned log2_ceil(uint32_t n)
{
    unsigned d = 0;
    while (((uint32_t)1 << d) < n)
        d++;
    return d;
}

static void coll_discard(gpointer p);

static NetColl *coll_new(NetNet *net, guint steps, CollPlan plan,
                         gboolean receipts, NetCollDone done, void *ctx)
{
    NetColl *c = g_new0(NetColl, 1);
    c->net = net;
    c->n = net_nodes(net);
    c->dims = log2_ceil(c->n);
    c->steps = steps;
    c->plan = plan;
    c->step = g_new0(guint, c->n);
    c->state = g_new0(uint8_t, c->n);
    c->receipts = receipts;
    if (receipts) {
        c->recvd = g_new0(guint, c->n);
        c->early = g_hash_table_new(g_int64_hash, g_int64_equal);
    }
    c->nodes_left = c->n;
    c->done = done;
    c->ctx = ctx;
    net_own(net, c, coll_discard);
    return c;
}

/* Frees c whatever its state (a collective left unfinished). */
static void coll_discard(gpointer p)
{
    NetColl *c = p;
    g_free(c->table);
    g_free(c->dst);
    g_free(c->off);
    g_free(c->count);
    g_free(c->step);
    g_free(c->state);
    g_free(c->recvd);
    if (c->early) {
        GHashTableIter it;
        gpointer key;
        g_hash_table_iter_init(&it, c->early); /* keys are heap uint64 */
        while (g_hash_table_iter_next(&it, &key, NULL))
            g_free(key);
        g_hash_table_destroy(c->early);
    }
    g_free(c);
}

/* A finished collective: every early receipt was matched. */
static void coll_free(NetColl *c)
{
    g_assert(!c->early || g_hash_table_size(c->early) == 0);
    net_disown(c->net, c);
    coll_discard(c);
}

static void maybe_finish(NetColl *c)
{
    if (c->nodes_left > 0 || c->inflight > 0)
        return;
    NetCollDone done = c->done;
    void *ctx = c->ctx;
    NetNet *net = c->net;
    coll_free(c);
    if (done)
        done(net, ctx);
}

static void on_arrive(NetNet *net, const NetDelivery *d, void *ctx);

/* Keys of the early-receipt table live in the table's values' slot: a
 * key is a heap uint64 freed when its count is taken. */
static void early_add(NetColl *c, uint32_t i, guint s)
{
    uint64_t k = (uint64_t)i * c->steps + s;
    uint64_t *key = NULL;
    gpointer old = NULL;
    if (g_hash_table_lookup_extended(c->early, &k, (gpointer *)&key, &old)) {
        g_hash_table_insert(c->early, key, GUINT_TO_POINTER(GPOINTER_TO_UINT(old) + 1));
        return;
    }
    key = g_new(uint64_t, 1);
    *key = k;
    g_hash_table_insert(c->early, key, GUINT_TO_POINTER(1));
}

/* Node i has just reached step s: its early receipts become current. */
static void early_take(NetColl *c, uint32_t i, guint s)
{
    uint64_t k = (uint64_t)i * c->steps + s;
    uint64_t *key = NULL;
    gpointer v = NULL;
    c->recvd[i] = 0;
    if (!g_hash_table_lookup_extended(c->early, &k, (gpointer *)&key, &v))
        return;
    c->recvd[i] = GPOINTER_TO_UINT(v);
    g_hash_table_remove(c->early, &k);
    g_free(key);
}

static void start_step(NetColl *c, uint32_t i)
{
    CollStep s = c->plan(c, i, c->step[i]);
    if (s.to == NO_SEND) {
        c->state[i] = ST_SENT;
        return;
    }
    c->state[i] = ST_SENDING;
    c->inflight++;
    net_send(c->net, i, s.to, s.bytes, GUINT_TO_POINTER(c->step[i]), on_arrive,
             c);
}

/* Moves node i on as far as it can; returns TRUE if it just finished. */
static gboolean advance(NetColl *c, uint32_t i)
{
    while (c->step[i] < c->steps) {
        guint s = c->step[i];
        if (c->state[i] == ST_IDLE)
            start_step(c, i);
        if (c->state[i] != ST_SENT)
            return FALSE;
        guint want = c->plan(c, i, s).expect;
        if (want > 0 && c->recvd[i] < want)
            return FALSE;
        c->step[i]++;
        c->state[i] = ST_IDLE;
        if (c->receipts && c->step[i] < c->steps)
            early_take(c, i, c->step[i]);
    }
    c->nodes_left--;
    return TRUE;
}

static void on_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    NetColl *c = ctx;
    guint s = GPOINTER_TO_UINT(d->payload);
    c->inflight--;
    g_assert(c->step[d->src] == s && c->state[d->src] == ST_SENDING);
    c->state[d->src] = ST_SENT;
    if (c->receipts && c->step[d->dst] == s)
        c->recvd[d->dst]++;
    else if (c->receipts)
        early_add(c, d->dst, s);
    advance(c, d->src);
    if (d->dst != d->src && c->step[d->dst] == s)
        advance(c, d->dst);
    maybe_finish(c);
}

static void coll_run(NetColl *c)
{
    for (uint32_t i = 0; i < c->n; i++)
        advance(c, i);
    maybe_finish(c);
}

/* ---- control network ---- */

typedef struct {
    NetCollDone done;
    void *ctx;
    NetNet *net;
} CtrlDone;

static void ctrl_fire(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    CtrlDone cd = *(CtrlDone *)ctx;
    g_free(ctx);
    if (cd.done)
        cd.done(cd.net, cd.ctx);
}

/* Returns TRUE if the control network took the operation. */
static gboolean via_control(NetNet *net, uint64_t bytes, NetCollDone done,
                            void *ctx)
{
    const NetParams *p = net_params(net);
    if (p->ctrl_latency == 0)
        return FALSE;
    SimTime t = p->ctrl_latency;
    if (p->ctrl_bandwidth > 0.0 && bytes > 0)
        t += sim_time_for_bytes((double)bytes, p->ctrl_bandwidth);
    CtrlDone *cd = g_new(CtrlDone, 1);
    *cd = (CtrlDone){done, ctx, net};
    sim_schedule_in(net_engine(net), t, ctrl_fire, cd, NULL);
    return TRUE;
}

/* ---- plans ---- */

static CollStep plan_bcast(const NetColl *c, uint32_t i, guint k)
{
    uint32_t r = (i + c->n - c->root) % c->n, bit = (uint32_t)1 << k;
    CollStep s = {NO_SEND, c->bytes, 0};
    if (r < bit && r + bit < c->n)
        s.to = (r + bit + c->root) % c->n;
    else if (r >= bit && r < 2 * bit)
        s.expect = 1;
    return s;
}

static CollStep plan_doubling(const NetColl *c, uint32_t i, guint k)
{
    return (CollStep){i ^ ((uint32_t)1 << k), c->bytes, 1};
}

/* Bytes from i to `to` in an all-to-all: the matrix, or uniform. */
static uint64_t a2a_bytes(const NetColl *c, uint32_t i, uint32_t to)
{
    if (c->table)
        return c->table[(gsize)i * c->n + to];
    return i == to ? 0 : c->bytes;
}

static CollStep plan_a2a_xor(const NetColl *c, uint32_t i, guint s)
{
    uint32_t to = i ^ (s + 1);
    return (CollStep){to, a2a_bytes(c, i, to), 1};
}

static CollStep plan_a2a_shift(const NetColl *c, uint32_t i, guint s)
{
    uint32_t to = (i + s + 1) % c->n;
    uint64_t b = a2a_bytes(c, i, to);
    return (CollStep){b ? to : NO_SEND, b, 0};
}

static CollStep plan_a2a_naive(const NetColl *c, uint32_t i, guint s)
{
    uint32_t to = s < i ? s : s + 1; /* 0, 1, ... n-1, skipping i */
    uint64_t b = a2a_bytes(c, i, to);
    return (CollStep){b ? to : NO_SEND, b, 0};
}

static CollStep plan_pairwise(const NetColl *c, uint32_t i, guint s)
{
    uint32_t to = i ^ ((uint32_t)1 << (c->dims - 1 - s));
    return (CollStep){to, c->table[(gsize)i * c->dims + s], 1};
}

static CollStep plan_generated(const NetColl *c, uint32_t i, guint s)
{
    CollStep st = {NO_SEND, 0, 0};
    c->gen(c->gen_ctx, i, s, &st.to, &st.bytes);
    g_assert(st.to < c->n);
    return st;
}

static CollStep plan_lists(const NetColl *c, uint32_t i, guint s)
{
    if (s >= c->count[i])
        return (CollStep){NO_SEND, 0, 0};
    uint32_t k = c->off[i] + s;
    return (CollStep){c->dst[k], c->table[k], 0};
}

/* ---- public entry points ---- */

static gboolean power_of_two(uint32_t n)
{
    return n > 0 && (n & (n - 1)) == 0;
}

void net_broadcast(NetNet *net, uint32_t root, uint64_t bytes, NetCollDone done,
                   void *ctx)
{
    g_assert(root < net_nodes(net));
    if (via_control(net, bytes, done, ctx))
        return;
    NetColl *c =
        coll_new(net, log2_ceil(net_nodes(net)), plan_bcast, TRUE, done, ctx);
    c->root = root;
    c->bytes = bytes;
    coll_run(c);
}

static void doubling(NetNet *net, uint64_t bytes, NetCollDone done, void *ctx)
{
    g_assert(power_of_two(net_nodes(net)));
    if (via_control(net, bytes, done, ctx))
        return;
    NetColl *c = coll_new(net, log2_ceil(net_nodes(net)), plan_doubling, TRUE,
                          done, ctx);
    c->bytes = bytes;
    coll_run(c);
}

void net_allreduce(NetNet *net, uint64_t bytes, NetCollDone done, void *ctx)
{
    doubling(net, bytes, done, ctx);
}

void net_prefix_sum(NetNet *net, uint64_t bytes, NetCollDone done, void *ctx)
{
    doubling(net, bytes, done, ctx);
}

void net_barrier(NetNet *net, NetCollDone done, void *ctx)
{
    doubling(net, 0, done, ctx);
}

static NetColl *a2a_new(NetNet *net, NetA2ASchedule sched, NetCollDone done,
                        void *ctx)
{
    uint32_t n = net_nodes(net);
    gboolean xor = sched == NET_A2A_XOR;
    g_assert(!xor || power_of_two(n));
    CollPlan plan = xor                      ? plan_a2a_xor
                    : sched == NET_A2A_SHIFT ? plan_a2a_shift
                                             : plan_a2a_naive;
    return coll_new(net, n - 1, plan, xor, done, ctx);
}

void net_alltoall(NetNet *net, const uint64_t *bytes, NetA2ASchedule sched,
                  NetCollDone done, void *ctx)
{
    uint32_t n = net_nodes(net);
    NetColl *c = a2a_new(net, sched, done, ctx);
    c->table = g_memdup2(bytes, (gsize)n * n * sizeof *bytes);
    coll_run(c);
}

void net_alltoall_uniform(NetNet *net, uint64_t bytes, NetA2ASchedule sched,
                          NetCollDone done, void *ctx)
{
    NetColl *c = a2a_new(net, sched, done, ctx);
    c->bytes = bytes;
    coll_run(c);
}

void net_send_generated(NetNet *net, guint per_node, NetGenFn gen,
                        void *gen_ctx, NetCollDone done, void *ctx)
{
    NetColl *c = coll_new(net, per_node, plan_generated, FALSE, done, ctx);
    c->gen = gen;
    c->gen_ctx = gen_ctx;
    coll_run(c);
}

void net_pairwise_exchange(NetNet *net, const uint64_t *bytes, NetCollDone done,
                           void *ctx)
{
    uint32_t n = net_nodes(net);
    g_assert(power_of_two(n));
    unsigned d = log2_ceil(n);
    NetColl *c = coll_new(net, d, plan_pairwise, TRUE, done, ctx);
    c->table = g_memdup2(bytes, (gsize)n * d * sizeof *bytes);
    coll_run(c);
}

void net_send_lists(NetNet *net, const uint32_t *count, const uint32_t *dst,
                    const uint64_t *size, NetCollDone done, void *ctx)
{
    uint32_t n = net_nodes(net), total = 0, most = 0;
    uint32_t *off = g_new(uint32_t, n);
    for (uint32_t i = 0; i < n; i++) {
        off[i] = total;
        total += count[i];
        most = count[i] > most ? count[i] : most;
    }
    NetColl *c = coll_new(net, most, plan_lists, FALSE, done, ctx);
    c->off = off;
    c->count = g_memdup2(count, n * sizeof *count);
    c->dst = g_memdup2(dst, (gsize)total * sizeof *dst);
    c->table = g_memdup2(size, (gsize)total * sizeof *size);
    coll_run(c);
}
