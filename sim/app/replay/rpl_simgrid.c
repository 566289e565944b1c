/* rpl_simgrid.c — SimGrid trace replay (rpl_simgrid.h).
 *
 * Ranks are small state machines: step() runs a rank's actions until one
 * blocks (work, a blocking send or receive, a wait, a collective); the
 * completion that unblocks it calls step() again.  Messages carry their
 * send request; arrivals go to a mailbox per (src, dst, tag) holding
 * either unclaimed arrivals or posted receives.  Cost: O(1) per action
 * plus the network's own.
 *
 * Memory follows what is held: actions read ahead of the rank that
 * needs its next one, and requests not yet waited for; both are checked
 * against the memory limit as they grow (a trace whose receives never
 * come is an input error, not an exhausted machine).  Every rank must
 * finish and every message must be received.
 */

/* Bytes a rank's state takes (SgRank, its flop cost, the map), about. */
#define SG_RANK_BYTES 128.0
/* Bytes one held action or request takes (with its list node), about. */
#define SG_HELD_BYTES 160.0
#include "sim/app/replay/rpl_simgrid.h"
#include "sim/app/replay/rpl_sgparse.h"
#include "sim/app/replay/rpl_target.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include "sim/net/collective.h"
#include <math.h>
#include <string.h>

typedef struct SgRank SgRank;

typedef struct {
    gboolean recv, complete;
    guint src, dst;
    int64_t tag;
    guint line; /* the send or receive */
    SgRank *owner;
} SgReq;

struct SgRank {
    guint id;
    GQueue q;         /* SgAct *, read ahead for this rank */
    GQueue reqs;      /* SgReq *, outstanding isend/irecv */
    SgReq *wait;      /* blocked on this request, or NULL */
    gboolean waitall; /* blocked on every outstanding request */
    gboolean doubles, finished;
    double flops;     /* computation after the current collective */
};

typedef struct {
    GQueue arrived; /* unclaimed arrivals (counted by length) */
    GQueue posted;  /* SgReq *, receives waiting */
} SgBox;

typedef struct {
    RplTarget *t;
    RplLines *l;
    gboolean eof;
    guint n;
    SgRank *ranks;
    GHashTable *boxes; /* "src dst tag" -> SgBox * */
    SimTime *flop; /* per rank: time per flop (0 when no compute) */
    /* the collective being formed */
    guint entered;
    SgAct coll;
    GError *error;
    uint64_t actions;
    guint64 ahead, live; /* actions read ahead, requests in rank queues */
    guint64 grown;       /* additions to either (checked every 65,536) */
} Sg;

static void step(Sg *sg, SgRank *r);

static void fail(Sg *sg, GError *e)
{
    if (!sg->error)
        sg->error = e;
    else
        g_error_free(e);
    sim_engine_stop(sg->t->eng);
}

/* What is held fits the memory limit (checked every 65,536 additions);
 * else the run stops with a located error. */
static void held_grew(Sg *sg)
{
    if (++sg->grown % 65536 || sg->error)
        return;
    GError *e = NULL;
    char *where = g_strdup_printf("%s:%u:1", rpl_lines_path(sg->l),
                                  rpl_lines_number(sg->l));
    char *what = g_strdup_printf(
        "%" G_GUINT64_FORMAT " actions read ahead of ranks that wait and "
        "%" G_GUINT64_FORMAT " requests not yet waited for",
        sg->ahead, sg->live);
    if (!sim_mem_check((sg->ahead + sg->live) * SG_HELD_BYTES, where, what,
                       &e))
        fail(sg, e);
    g_free(where);
    g_free(what);
}

/* The next action of rank r, reading ahead; NULL when it has none. */
static SgAct *next_act(Sg *sg, SgRank *r)
{
    while (g_queue_is_empty(&r->q) && !sg->eof && !sg->error) {
        GError *e = NULL;
        int n = rpl_lines_next(sg->l, &e);
        SgAct *a = g_new(SgAct, 1);
        if (n <= 0 || !rpl_sg_parse(sg->l, a, &e)) {
            g_free(a);
            sg->eof = TRUE;
            if (e)
                fail(sg, e);
            break;
        }
        g_queue_push_tail(&sg->ranks[a->rank].q, a);
        sg->ahead++;
        held_grew(sg);
    }
    SgAct *a = g_queue_pop_head(&r->q);
    sg->ahead -= a != NULL;
    return a;
}

static SgBox *box(Sg *sg, guint src, guint dst, int64_t tag)
{
    char key[64];
    g_snprintf(key, sizeof key, "%u %u %" G_GINT64_FORMAT, src, dst, tag);
    SgBox *b = g_hash_table_lookup(sg->boxes, key);
    if (!b) {
        b = g_new0(SgBox, 1);
        g_hash_table_insert(sg->boxes, g_strdup(key), b);
    }
    return b;
}

/* A request completed: unblock its owner if it waits for it. */
static void req_done(Sg *sg, SgReq *q)
{
    SgRank *r = q->owner;
    q->complete = TRUE;
    if (r->wait == q) {
        sg->live -= g_queue_remove(&r->reqs, q);
        g_free(q);
        r->wait = NULL;
        step(sg, r);
        return;
    }
    if (!r->waitall)
        return;
    for (GList *i = r->reqs.head; i; i = i->next)
        if (!((SgReq *)i->data)->complete)
            return;
    sg->live -= g_queue_get_length(&r->reqs);
    g_queue_clear_full(&r->reqs, g_free);
    r->waitall = FALSE;
    step(sg, r);
}

static void arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Sg *sg = ctx;
    SgReq *send = d->payload;
    SgBox *b = box(sg, send->src, send->dst, send->tag);
    SgReq *recv = g_queue_pop_head(&b->posted);
    if (!recv)
        g_queue_push_tail(&b->arrived, GUINT_TO_POINTER(send->line));
    req_done(sg, send);
    if (recv)
        req_done(sg, recv);
}

static void resume(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    step(ctx, arg);
}

static uint64_t bytes_of(const SgRank *r, double elems)
{
    double b = elems * (r->doubles ? 8 : 1);
    return b >= 1.8e19 ? G_MAXUINT64 : (uint64_t)llround(b);
}

static SimTime flops_cost(const Sg *sg, const SgRank *r, double flops)
{
    double t = round(flops * (double)sg->flop[r->id]);
    return t >= (double)SIM_TIME_MAX ? SIM_TIME_MAX : (SimTime)t;
}

static MachProc *proc_of(Sg *sg, const SgRank *r)
{
    return mach_proc_at(sg->t->m, rpl_target_map(sg->t, r->id));
}

static SgReq *new_req(SgRank *r, gboolean recv, const SgAct *a)
{
    SgReq *q = g_new0(SgReq, 1);
    *q = (SgReq){.recv = recv,
                 .src = recv ? a->peer : r->id,
                 .dst = recv ? r->id : a->peer,
                 .tag = a->tag,
                 .line = a->line,
                 .owner = r};
    return q;
}

static SgReq *send(Sg *sg, SgRank *r, const SgAct *a)
{
    SgReq *q = new_req(r, FALSE, a);
    net_send(mach_net(sg->t->m), rpl_target_map(sg->t, r->id), rpl_target_map(sg->t, a->peer),
             bytes_of(r, a->size), q, arrived, sg);
    return q;
}

/* Posts a receive; returns NULL if a matching message was already there
 * (claimed), else the request (complete later). */
static SgReq *recv(Sg *sg, SgRank *r, const SgAct *a)
{
    SgBox *b = box(sg, a->peer, r->id, a->tag);
    SgReq *q = new_req(r, TRUE, a);
    if (g_queue_pop_head(&b->arrived))
        q->complete = TRUE;
    else
        g_queue_push_tail(&b->posted, q);
    return q;
}

/* The outstanding request a wait names (NULL: none, SimGrid ignores it). */
static SgReq *find_req(SgRank *r, const SgAct *a)
{
    if (!a->matched)
        return g_queue_peek_tail(&r->reqs);
    for (GList *i = r->reqs.tail; i; i = i->prev) {
        SgReq *q = i->data;
        if (q->src == a->src && q->dst == a->dst && q->tag == a->tag)
            return q;
    }
    return NULL;
}

/* Blocks r on q unless it is complete (then frees it). */
static gboolean block_on(Sg *sg, SgRank *r, SgReq *q)
{
    if (!q)
        return FALSE;
    if (q->complete) {
        sg->live -= g_queue_remove(&r->reqs, q);
        g_free(q);
        return FALSE;
    }
    r->wait = q;
    return TRUE;
}

static gboolean all_complete(const SgRank *r)
{
    for (GList *i = r->reqs.head; i; i = i->next)
        if (!((SgReq *)i->data)->complete)
            return FALSE;
    return TRUE;
}

/* Work or a sleep of d from `from` ends within the 64-bit clock; else
 * the run stops with an error located at the action's argument (a
 * saturated end would report the end of time as a result). */
static gboolean fits_clock(Sg *sg, const SgAct *a, SimTime from, SimTime d)
{
    SimTime end;
    from = MAX(from, sim_now(sg->t->eng));
    if (d < SIM_TIME_MAX && sim_time_add(from, d, &end))
        return TRUE;
    fail(sg, g_error_new(SIM_ERROR, SIM_ERROR_INPUT,
                         "%s:%u:%d: found %s ending past the simulated clock's "
                         "end (%.0f s) at %.6g s, expected work and sleeps "
                         "that end within it",
                         rpl_lines_path(sg->l), a->line, a->arg_col,
                         a->type == SG_SLEEP     ? "a sleep"
                         : a->type == SG_COMPUTE ? "a compute"
                                                 : "a reduction's compute",
                         sim_time_to_s(SIM_TIME_MAX), sim_time_to_s(from)));
    return FALSE;
}

static void coll_done(NetNet *net, void *ctx)
{
    (void)net;
    Sg *sg = ctx;
    double flops = sg->coll.flops;
    gboolean comp = sg->coll.type == SG_REDUCE || sg->coll.type == SG_ALLREDUCE;
    sg->entered = 0;
    for (guint i = 0; i < sg->n; i++) {
        SgRank *r = &sg->ranks[i];
        if (comp && flops > 0) {
            SimTime d = flops_cost(sg, r, flops);
            if (!fits_clock(sg, &sg->coll, mach_proc_free_at(proc_of(sg, r)),
                            d))
                return;
            mach_proc_compute(proc_of(sg, r), d, 0, resume, sg, r);
        } else
            step(sg, r);
    }
}

static void coll_start(Sg *sg, const SgRank *r)
{
    NetNet *net = mach_net(sg->t->m);
    uint64_t b = bytes_of(r, sg->coll.size);
    switch (sg->coll.type) {
    case SG_BARRIER:
        net_barrier(net, coll_done, sg);
        break;
    case SG_BCAST:
    case SG_REDUCE: /* the same tree, reversed (rpl_simgrid.h) */
        net_broadcast(net, sg->coll.peer, b, coll_done, sg);
        break;
    case SG_ALLREDUCE:
        net_allreduce(net, b, coll_done, sg);
        break;
    default:
        net_alltoall_uniform(net, b, NET_A2A_SHIFT, coll_done, sg);
        break;
    }
}

/* Rank r reaches collective a; the last rank to arrive starts it. */
static void coll_enter(Sg *sg, SgRank *r, const SgAct *a)
{
    if (sg->entered == 0)
        sg->coll = *a;
    else if (sg->coll.type != a->type) {
        fail(sg, g_error_new(SIM_ERROR, SIM_ERROR_INPUT,
                             "%s:%u:2: found a different collective than "
                             "line %u of another rank, expected every rank's "
                             "collectives in the same order",
                             rpl_lines_path(sg->l), a->line, sg->coll.line));
        return;
    }
    if (++sg->entered == sg->n)
        coll_start(sg, r);
}

/* Runs action a of rank r; TRUE when r must wait. */
static gboolean run_act(Sg *sg, SgRank *r, const SgAct *a)
{
    sg->actions++;
    switch (a->type) {
    case SG_NOP:
        r->doubles = r->doubles || a->doubles;
        return FALSE;
    case SG_COMPUTE:
        if (fits_clock(sg, a, mach_proc_free_at(proc_of(sg, r)),
                       flops_cost(sg, r, a->flops)))
            mach_proc_compute(proc_of(sg, r), flops_cost(sg, r, a->flops), 0,
                              resume, sg, r);
        return TRUE;
    case SG_SLEEP:
        {
            SimTime t;
            if (!sim_time_from_s(a->seconds, &t))
                t = SIM_TIME_MAX;
            if (fits_clock(sg, a, sim_now(sg->t->eng), t))
                sim_schedule_in(sg->t->eng, t, resume, sg, r);
        }
        return TRUE;
    case SG_SEND:
        return block_on(sg, r, send(sg, r, a));
    case SG_RECV:
        return block_on(sg, r, recv(sg, r, a));
    case SG_ISEND:
    case SG_IRECV:
        g_queue_push_tail(&r->reqs, a->type == SG_ISEND ? send(sg, r, a)
                                                        : recv(sg, r, a));
        sg->live++;
        held_grew(sg);
        return FALSE;
    case SG_WAIT:
        return block_on(sg, r, find_req(r, a));
    case SG_WAITALL:
        if (all_complete(r)) {
            sg->live -= g_queue_get_length(&r->reqs);
            g_queue_clear_full(&r->reqs, g_free);
            return FALSE;
        }
        r->waitall = TRUE;
        return TRUE;
    default:
        coll_enter(sg, r, a);
        return TRUE;
    }
}

static void step(Sg *sg, SgRank *r)
{
    SgAct *a;
    while (!sg->error && (a = next_act(sg, r))) {
        gboolean wait = run_act(sg, r, a);
        g_free(a);
        if (wait)
            return;
    }
    r->finished = TRUE;
}

/* What the check pass learns: ranks, first compute and collective. */
typedef struct {
    guint ranks;
    guint compute_line, coll_line; /* 0: none */
    guint rank_line, root_line;    /* where ranks and the largest root
                                      were set */
    int rank_col, root_col;
    guint root;
} SgScan;

/* Rank (or peer) id v at line a->line, column col, may raise the count. */
static void see_rank(SgScan *s, const SgAct *a, guint v, int col)
{
    if (v + 1 > s->ranks) {
        s->ranks = v + 1;
        s->rank_line = a->line;
        s->rank_col = col;
    }
}

/* Every root names a rank, and the ranks' state fits the memory limit
 * (a rank id near 2^32 is an input error, not a failed allocation). */
static gboolean scan_fits(const char *path, const SgScan *s, GError **err)
{
    if (s->root_line && s->root >= s->ranks) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s:%u:%d: found root %u, expected a root below the %u "
                    "ranks of the trace",
                    path, s->root_line, s->root_col, s->root, s->ranks);
        return FALSE;
    }
    char *where = g_strdup_printf("%s:%u:%d", path, s->rank_line, s->rank_col);
    char *what = g_strdup_printf("rank %u (%u ranks)", s->ranks - 1, s->ranks);
    gboolean ok = sim_mem_check(s->ranks * SG_RANK_BYTES, where, what, err);
    g_free(where);
    g_free(what);
    return ok;
}

static void scan_act(SgScan *s, const SgAct *a, const RplLines *l)
{
    see_rank(s, a, a->rank, rpl_lines_col(l, 0));
    if (a->type == SG_SEND || a->type == SG_ISEND || a->type == SG_RECV ||
        a->type == SG_IRECV)
        see_rank(s, a, a->peer, a->arg_col);
    if (a->root_col && (!s->root_line || a->peer > s->root)) {
        s->root = a->peer;
        s->root_line = a->line;
        s->root_col = a->root_col;
    }
    if ((a->type == SG_COMPUTE || a->flops > 0) && !s->compute_line)
        s->compute_line = a->line;
    if (a->type >= SG_BARRIER && !s->coll_line)
        s->coll_line = a->line;
}

static gboolean scan(const char *path, SgScan *s, GError **err)
{
    RplLines *l = rpl_lines_open(path, err);
    SgAct a;
    int n = 0;
    memset(s, 0, sizeof *s);
    while (l && (n = rpl_lines_next(l, err)) > 0 && rpl_sg_parse(l, &a, err))
        scan_act(s, &a, l);
    gboolean ok = l && n == 0 && !(err && *err);
    rpl_lines_free(l);
    if (ok && s->ranks == 0)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found no actions, expected RANK ACTION lines", path);
    return ok && s->ranks > 0 && scan_fits(path, s, err);
}

/* The flop cost of every rank's processor kind, and the network shape
 * collectives need. */
static gboolean check_target(Sg *sg, const SgScan *s, const char *path,
                             GError **err)
{
    RplTarget *t = sg->t;
    gboolean fresh;
    for (guint r = 0; s->compute_line && r < sg->n; r++) {
        const SimTime *c = rpl_target_op_cost(t, r, "flop", &fresh);
        if (!c) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "%s:%u:1: found compute with no flop rate on machine "
                        "'%s', expected nodes.%s.costs.flop in its model "
                        "(time per flop; --set machine.nodes.%s.costs.flop=1ns)",
                        path, s->compute_line, mach_name(t->m),
                        mach_proc_kind(mach_proc_at(t->m, rpl_target_map(t, r))),
                        mach_proc_kind(mach_proc_at(t->m, rpl_target_map(t, r))));
            return FALSE;
        }
        sg->flop[r] = *c;
    }
    NetNet *net = mach_net(t->m);
    gboolean ident = TRUE;
    for (guint r = 0; r < sg->n; r++)
        ident = ident && rpl_target_map(t, r) == r;
    if (s->coll_line && (!net || net_nodes(net) != sg->n || !ident)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s:%u:1: found a collective over %u ranks on %u network "
                    "endpoints, expected one rank per endpoint in order "
                    "(--nodes %u --map block)",
                    path, s->coll_line, sg->n, net ? net_nodes(net) : 0,
                    sg->n);
        return FALSE;
    }
    return net || mach_require_net(t->m, err);
}

static void box_free(gpointer p)
{
    SgBox *b = p;
    g_queue_clear(&b->arrived);
    g_queue_clear(&b->posted); /* owned by their ranks (sg_clear) */
    g_free(b);
}

static SimResult *sg_result(Sg *sg, const RplReplayOpts *o)
{
    SimResult *res = sim_result_new("replay", o->machine);
    g_free(res->fidelity);
    res->fidelity = g_strdup(mach_fidelity(sg->t->m));
    res->seed = 1;
    mach_fill_result(sg->t->m, res);
    res->elapsed = sim_now(sg->t->eng);
    sim_result_add_frame(res, res->elapsed);
    res->events = sim_engine_events(sg->t->eng);
    res->config_path = g_strdup(o->trace);
    sim_result_set_metric(res, "actions", (double)sg->actions, "");
    sim_result_set_metric(res, "ranks", sg->n, "");
    return res;
}

/* A message nobody received, or a receive no message came for, left in
 * a mailbox when every rank finished: the earliest in the file, or
 * NULL. */
static GError *unmatched(Sg *sg)
{
    GHashTableIter it;
    gpointer key, val;
    guint line = 0;
    const char *what = NULL;
    g_hash_table_iter_init(&it, sg->boxes);
    while (g_hash_table_iter_next(&it, &key, &val)) {
        SgBox *b = val;
        guint sent = GPOINTER_TO_UINT(g_queue_peek_head(&b->arrived));
        SgReq *q = g_queue_peek_head(&b->posted);
        if (sent && (!line || sent < line))
            line = sent, what = "a send no rank receives";
        if (q && (!line || q->line < line))
            line = q->line, what = "a receive no rank sends to";
    }
    if (!line)
        return NULL;
    return g_error_new(SIM_ERROR, SIM_ERROR_INPUT,
                       "%s:%u:1: found %s, expected every send matched by a "
                       "receive (same ranks and tag)",
                       rpl_lines_path(sg->l), line, what);
}

static gboolean sg_run(Sg *sg, GError **err)
{
    for (guint i = 0; i < sg->n; i++)
        step(sg, &sg->ranks[i]);
    GError *e = NULL;
    if (!sim_engine_run(sg->t->eng, SIM_TIME_MAX, &e) && !sg->error)
        sg->error = e;
    else if (e)
        g_error_free(e);
    for (guint i = 0; !sg->error && i < sg->n; i++)
        if (!sg->ranks[i].finished)
            sg->error = g_error_new(
                SIM_ERROR, SIM_ERROR_INPUT,
                "%s: found rank %u blocked at the end (a receive without its "
                "send, or a collective some rank never reaches), expected "
                "every rank to finish",
                rpl_lines_path(sg->l), i);
    if (!sg->error)
        sg->error = unmatched(sg);
    if (sg->error) {
        g_propagate_error(err, sg->error);
        return FALSE;
    }
    return TRUE;
}

static void sg_clear(Sg *sg)
{
    for (guint i = 0; sg->ranks && i < sg->n; i++) {
        SgRank *r = &sg->ranks[i];
        if (r->wait && !g_queue_find(&r->reqs, r->wait))
            g_free(r->wait); /* a blocking send or receive */
        g_queue_clear_full(&sg->ranks[i].q, g_free);
        g_queue_clear_full(&sg->ranks[i].reqs, g_free);
    }
    g_free(sg->ranks);
    g_free(sg->flop);
    if (sg->boxes)
        g_hash_table_destroy(sg->boxes);
    rpl_lines_free(sg->l);
    rpl_target_free(sg->t);
}

SimResult *rpl_replay_simgrid(const RplReplayOpts *o, GError **err)
{
    SgScan s;
    if (!scan(o->trace, &s, err))
        return NULL;
    GPtrArray *phases = g_ptr_array_new();
    g_ptr_array_add(phases, "compute");
    RplHeader h = {.procs = s.ranks,
                   .phases = phases,
                   .kinds = g_array_new(FALSE, FALSE, sizeof(RplKind))};
    Sg sg = {.n = s.ranks, .flop = g_new0(SimTime, s.ranks)};
    sg.t = rpl_target_new(o, &h, err);
    g_ptr_array_free(phases, TRUE);
    g_array_free(h.kinds, TRUE);
    SimResult *res = NULL;
    if (sg.t && check_target(&sg, &s, o->trace, err) &&
        (sg.l = rpl_lines_open(o->trace, err))) {
        sg.ranks = g_new0(SgRank, sg.n);
        for (guint i = 0; i < sg.n; i++)
            sg.ranks[i].id = i;
        sg.boxes = g_hash_table_new_full(g_str_hash, g_str_equal, g_free,
                                         box_free);
        if (sg_run(&sg, err))
            res = sg_result(&sg, o);
    }
    sg_clear(&sg);
    return res;
}
