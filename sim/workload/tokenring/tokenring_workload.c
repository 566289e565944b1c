/* tokenring_workload.c — N nodes pass a token around a ring for R rounds.
 *
 * Each visit: the node computes for c_i (phase "compute"; c_i drawn from
 * the node's own RNG stream when jitter > 0), then serialises the token
 * onto its outgoing link for bytes / bandwidth (phase "send"); the token
 * arrives at the next node one link latency later.  A round (a frame)
 * ends when the token is back at node 0.  Without jitter a frame lasts
 * exactly N * (compute + bytes/bandwidth + latency): the tests use that.
 *
 * State is O(N): one busy record per node (kept in the result) and one
 * SimLinkStats per link.  Two events per hop, O(log 1) queue work since
 * only one event is ever pending.
 */
#include "sim/workload/tokenring/tokenring_workload.h"
#include "sim/core/record.h"
#include "sim/core/trace.h"
#include <string.h>

typedef struct {
    uint64_t nodes;
    uint64_t token; /* bytes */
    SimTime compute;
    double jitter; /* 0 .. 1 */
    SimTime latency;
    double bandwidth; /* bytes/s */
} TrParams;

typedef struct {
    const TrParams *p;
    SimResult *res;
    SimLinkStats *links; /* links[i]: node i -> node i+1 */
    unsigned send_phase;
    int frames_left;
    gboolean started; /* the token has left node 0 once */
    SimTime frame_start;
} TrState;

static void *tr_parse(const CfgNode *sec, GError **err)
{
    TrParams *p = g_new0(TrParams, 1);
    *p = (TrParams){.nodes = 8,
                    .token = 1000,
                    .compute = 20 * SIM_US,
                    .jitter = 0.0,
                    .latency = 5 * SIM_US,
                    .bandwidth = 2.8e6};
    const CfgNode *link = cfg_get(sec, "link");
    gboolean ok =
        cfg_get_count(sec, "nodes", FALSE, 2, 1000000, &p->nodes, err) &&
        cfg_get_size(sec, "token", FALSE, &p->token, err) &&
        cfg_get_time(sec, "compute", FALSE, &p->compute, err) &&
        cfg_get_double(sec, "jitter", FALSE, 0.0, 1.0, &p->jitter, err) &&
        cfg_get_time(link, "latency", FALSE, &p->latency, err) &&
        cfg_get_bandwidth(link, "bandwidth", FALSE, &p->bandwidth, err);
    if (ok && p->bandwidth <= 0) {
        cfg_error(err, cfg_get(link, "bandwidth"), "a zero bandwidth",
                  "a bandwidth above 0 B/s");
        ok = FALSE;
    }
    if (!ok) {
        g_free(p);
        return NULL;
    }
    return p;
}

static void tr_free(void *params)
{
    g_free(params);
}

/* Own memory (WlOps.mem_bytes): a result record and a link record per
 * node, plus 256 B for its name, kind, phase array, allocator overhead
 * and its lines in the report (fitted: `run` peaked 64 MB higher at
 * 200,000 nodes than at 8, 328 B a node). */
static double tr_mem_bytes(const void *params, GString *what)
{
    const TrParams *p = params;
    g_string_append_printf(what, "%" G_GUINT64_FORMAT " nodes", p->nodes);
    return (double)p->nodes *
           (sizeof(SimNodeResult) + sizeof(SimLinkStats) + 256.0);
}

static void arrive(SimEngine *eng, void *ctx, void *arg);

/* A recording (`pgsim run --record`, sim/core/record.h): the ring has no
 * machine model, so the workload tells the recorder itself what each
 * node does.  Work (a visit's compute, a token's serialisation) is a time
 * of the ring's nodes, recorded as that many `tick`s (1 ps each on
 * models/ring-8.yaml, the ring as a model); then(eng, s, arg) runs at
 * now + t as without a recorder.  Returns FALSE when not recording. */
static gboolean record_work(SimEngine *eng, uint64_t i, unsigned phase,
                            SimTime t, SimHandler then, TrState *s, void *arg)
{
    SimRecorder *rec = sim_engine_recorder(eng);
    if (!rec)
        return FALSE;
    SimOp tick = {"tick", t};
    SimTime now = sim_now(eng), end = sim_time_add_sat(now, t);
    SimWork w = {&tick, 1, NULL, 0};
    uint64_t id = rec->ops->compute(rec, now, (uint32_t)i, phase, t, end, &w,
                                    then != NULL);
    sim_record_schedule_done(eng, rec, id, end, then, s, arg);
    return TRUE;
}

/* The token from i to next as a recorded message, arriving after d. */
static gboolean record_send(SimEngine *eng, uint64_t i, uint64_t next,
                            uint64_t bytes, SimTime d, TrState *s)
{
    SimRecorder *rec = sim_engine_recorder(eng);
    if (!rec)
        return FALSE;
    uint64_t id = rec->ops->send(rec, sim_now(eng), (uint32_t)i, (uint32_t)next,
                                 bytes, TRUE);
    sim_record_schedule_done(eng, rec, id, sim_time_add_sat(sim_now(eng), d),
                             arrive, s, (void *)(uintptr_t)next);
    return TRUE;
}

static SimNodeResult *node_at(TrState *s, uint64_t i)
{
    return g_ptr_array_index(s->res->nodes, i);
}

static SimTime compute_time(SimEngine *eng, const TrParams *p, uint64_t i)
{
    if (p->jitter <= 0.0)
        return p->compute;
    double u = sim_rng_uniform(sim_entity_rng(eng, (uint32_t)i));
    double f = 1.0 + p->jitter * (2.0 * u - 1.0);
    return (SimTime)llround((double)p->compute * f);
}

/* Node i has computed: it serialises the token to node i+1. */
static void send(SimEngine *eng, void *ctx, void *arg)
{
    TrState *s = ctx;
    uint64_t i = (uintptr_t)arg;
    SimTime ser = sim_time_for_bytes((double)s->p->token, s->p->bandwidth);
    SimLinkStats *l = &s->links[i];
    l->bytes += s->p->token;
    l->messages++;
    l->busy += ser;
    sim_busy_add(&node_at(s, i)->busy, s->send_phase, ser);
    SimTime d;
    if (!sim_time_add(ser, s->p->latency, &d))
        d = SIM_TIME_MAX;
    uint64_t next = (i + 1) % s->p->nodes;
    SimTime now = sim_now(eng);
    SimTrace *tr = sim_engine_trace(eng);
    sim_trace_span(tr, (uint32_t)i, node_at(s, i)->name, "send", now,
                   sim_time_add_sat(now, ser));
    sim_trace_flow(tr, (uint32_t)i, node_at(s, i)->name, (uint32_t)next,
                   node_at(s, next)->name, s->p->token, now,
                   sim_time_add_sat(now, d));
    record_work(eng, i, s->send_phase, ser, NULL, s, NULL);
    if (!record_send(eng, i, next, s->p->token, d, s))
        sim_schedule_in(eng, d, arrive, s, (void *)(uintptr_t)next);
}

static gboolean round_done(SimEngine *eng, TrState *s)
{
    SimTime now = sim_now(eng);
    sim_result_add_frame(s->res, now - s->frame_start);
    wl_mark_frame(eng, s->res->frame_times->len - 1, now);
    s->frame_start = now;
    return --s->frames_left <= 0;
}

/* The token reaches node i (node 0 after a full round ends a frame). */
static void arrive(SimEngine *eng, void *ctx, void *arg)
{
    TrState *s = ctx;
    uint64_t i = (uintptr_t)arg;
    if (i == 0 && s->started && round_done(eng, s))
        return;
    s->started = TRUE;
    SimTime c = compute_time(eng, s->p, i), now = sim_now(eng);
    sim_busy_add(&node_at(s, i)->busy, 0, c);
    sim_trace_span(sim_engine_trace(eng), (uint32_t)i, node_at(s, i)->name,
                   "compute", now, sim_time_add_sat(now, c));
    if (!record_work(eng, i, 0, c, send, s, arg))
        sim_schedule_in(eng, c, send, s, arg);
}

static void fill_comm(TrState *s)
{
    SimResult *r = s->res;
    uint64_t best = 0;
    SimTime link_busy = 0;
    for (uint64_t i = 0; i < s->p->nodes; i++) {
        r->comm_bytes += s->links[i].bytes;
        r->comm_messages += s->links[i].messages;
        link_busy += s->links[i].busy;
        if (s->links[i].bytes > s->links[best].bytes)
            best = i;
    }
    if (r->comm_messages) {
        r->busiest_link =
            g_strdup_printf("node%" G_GUINT64_FORMAT "->node%" G_GUINT64_FORMAT,
                            best, (best + 1) % s->p->nodes);
        r->busiest_link_bytes = s->links[best].bytes;
    }
    double el = sim_time_to_s(r->elapsed);
    sim_result_set_metric(r, "hops", (double)r->comm_messages, "");
    sim_result_set_metric(r, "hop_time_mean",
                          r->comm_messages ? el / r->comm_messages : 0, "s");
    sim_result_set_metric(
        r, "link_utilisation_mean",
        el > 0 ? sim_time_to_s(link_busy) / (el * (double)s->p->nodes) : 0, "");
}

static gboolean tr_run(const WlContext *ctx, void *params, SimResult *out,
                       GError **err)
{
    const TrParams *p = params; /* no machine: the runner refuses one */
    TrState s = {.p = p, .res = out, .frames_left = ctx->frames};
    s.links = g_new0(SimLinkStats, p->nodes);
    s.send_phase = sim_engine_phase(ctx->eng, "send");
    for (uint64_t i = 0; i < p->nodes; i++) {
        char *name = g_strdup_printf("node%" G_GUINT64_FORMAT, i);
        sim_entity_add(ctx->eng, name);
        sim_result_add_node(out, name, "node");
        g_free(name);
    }
    g_free(out->machine);
    out->machine = g_strdup_printf("ring-%" G_GUINT64_FORMAT, p->nodes);
    sim_schedule_at(ctx->eng, 0, arrive, &s, (void *)(uintptr_t)0);
    gboolean ok = sim_engine_run(ctx->eng, ctx->until, err);
    out->elapsed = sim_now(ctx->eng);
    sim_result_set_phases(out, ctx->eng);
    fill_comm(&s);
    g_free(s.links);
    return ok;
}

/* Every metric tr_run sets (docs/config.md, "tokenring"). */
static const WlMetric tr_metrics[] = {
    {"hops", "", "token hops run (messages sent)"},
    {"hop_time_mean", "s", "simulated time / hops"},
    {"link_utilisation_mean", "",
     "busy time of the links / (links x simulated time)"},
    {NULL, NULL, NULL},
};

const WlOps wl_tokenring_ops = {
    .name = "tokenring",
    .summary = "a token passed around a ring of nodes (a test of the engine)",
    .parse = tr_parse,
    .free_params = tr_free,
    .run = tr_run,
    .mem_bytes = tr_mem_bytes,
    .metrics = tr_metrics,
};
