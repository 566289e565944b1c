/* test_trace.c — trace files: Chrome JSON parses and holds the spans,
 * flows, marks and counters; Paje is time-ordered; the cap truncates
 * with a note; a workload's frames are marks; a network's messages give
 * the links of their routes bandwidth-use tracks, and at the packet rung
 * each hop's holds and queue. */
#include "sim/output/json.h"
#include "sim/run/run.h"
#include <math.h>
#include "sim/app/trace/trace_file.h"
#include "sim/net/net.h"
#include <glib/gstdio.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static char *tmp_path(const char *ext)
{
    char *dir = g_dir_make_tmp("pgsim-trc-XXXXXX", NULL);
    char *p = g_strconcat(dir, "/t", ext, NULL);
    g_free(dir);
    return p;
}

static void rm_path(char *p)
{
    g_remove(p);
    char *dir = g_path_get_dirname(p);
    g_rmdir(dir);
    g_free(dir);
    g_free(p);
}

/* Node 1 computes, sends 64 B to node 0, which merges; then a mark. */
static void emit(SimTrace *tr)
{
    sim_trace_span(tr, 1, "gp1", "transform", 0, 3 * SIM_US);
    sim_trace_flow(tr, 1, "gp1", 0, NULL, 64, 3 * SIM_US, 5 * SIM_US + 250);
    sim_trace_span(tr, 0, "gp0", "merge", 5 * SIM_US + 250, 9 * SIM_US);
    sim_trace_mark(tr, "frame 0", 9 * SIM_US);
}

static JsonNode *load_json(const char *path)
{
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    GError *err = NULL;
    JsonNode *v = js_parse(text, -1, path, &err);
    g_assert_no_error(err);
    g_free(text);
    return v;
}

static JsonNode *find_ev(JsonNode *evs, const char *ph,
                              const char *name, guint *count)
{
    JsonNode *hit = NULL;
    *count = 0;
    for (guint i = 0; i < js_len(evs); i++) {
        JsonNode *e = js_at(evs, i);
        if (strcmp(js_str(js_get(e, "ph")), ph) == 0 &&
            (!name || strcmp(js_str(js_get(e, "name")), name) == 0)) {
            hit = hit ? hit : e;
            ++*count;
        }
    }
    return hit;
}

static void test_chrome(void **state)
{
    (void)state;
    char *path = tmp_path(".json");
    GError *err = NULL;
    SimTrace *tr = trc_open(path, 0, &err);
    g_assert_no_error(err);
    emit(tr);
    assert_int_equal(trc_events(tr), 4);
    assert_true(trc_close(tr, &err));
    JsonNode *v = load_json(path);
    JsonNode *evs = js_get(v, "traceEvents");
    guint n;
    JsonNode *x = find_ev(evs, "X", "merge", &n);
    assert_int_equal(n, 1);
    assert_int_equal((int)js_num(js_get(x, "tid")), 0);
    assert_true(fabs(js_num(js_get(x, "ts")) - 5.000250) < 1e-12);
    assert_true(fabs(js_num(js_get(x, "dur")) - 3.999750) < 1e-12);
    JsonNode *s = find_ev(evs, "s", NULL, &n);
    assert_int_equal(n, 1);
    JsonNode *f = find_ev(evs, "f", NULL, &n);
    assert_int_equal(n, 1);
    assert_true(js_num(js_get(s, "id")) == js_num(js_get(f, "id")));
    assert_int_equal((int)js_num(js_get(s, "tid")), 1);
    assert_int_equal((int)js_num(js_get(f, "tid")), 0);
    assert_string_equal(js_str(js_get(f, "bp")), "e");
    /* node 0 is first seen in the flow ("node0"), then named by its span;
     * the later thread_name wins in Perfetto */
    find_ev(evs, "M", "thread_name", &n);
    assert_int_equal(n, 3);
    JsonNode *last = js_at(evs, 0);
    for (guint i = 0; i < js_len(evs); i++) {
        JsonNode *e = js_at(evs, i);
        if (!strcmp(js_str(js_get(e, "name")), "thread_name") &&
            js_num(js_get(e, "tid")) == 0)
            last = e;
    }
    assert_string_equal(js_str(js_get(js_get(last, "args"), "name")), "gp0");
    find_ev(evs, "i", "frame 0", &n);
    assert_int_equal(n, 1);
    assert_false(
        json_node_get_boolean(js_get(js_get(v, "otherData"), "truncated")));
    json_node_unref(v);
    rm_path(path);
}

/* The counter tracks derived from flows: one 64 B message in flight over
 * [3 us, 5.00025 us). */
static void test_counters(void **state)
{
    (void)state;
    char *path = tmp_path(".json");
    SimTrace *tr = trc_open(path, 0, NULL);
    emit(tr);
    assert_true(trc_close(tr, NULL));
    JsonNode *v = load_json(path);
    JsonNode *evs = js_get(v, "traceEvents");
    const double want_t[] = {0, 3, 5.00025}, want_m[] = {0, 1, 0},
                 want_b[] = {0, 64, 0};
    guint nm = 0, nb = 0;
    for (guint i = 0; i < js_len(evs); i++) {
        JsonNode *e = js_at(evs, i);
        if (strcmp(js_str(js_get(e, "ph")), "C") != 0)
            continue;
        gboolean msgs = !strcmp(js_str(js_get(e, "name")), "messages in flight");
        guint k = msgs ? nm++ : nb++;
        assert_true(k < 3);
        assert_true(fabs(js_num(js_get(e, "ts")) - want_t[k]) < 1e-9);
        double val = js_num(js_get(js_get(e, "args"), msgs ? "messages" : "B"));
        assert_true(val == (msgs ? want_m[k] : want_b[k]));
    }
    assert_int_equal(nm, 3);
    assert_int_equal(nb, 3);
    json_node_unref(v);
    rm_path(path);
    path = tmp_path(".paje");
    tr = trc_open(path, 0, NULL);
    emit(tr);
    assert_true(trc_close(tr, NULL));
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    assert_non_null(strstr(text, "%EventDef PajeSetVariable 11\n"));
    assert_non_null(strstr(text, "11 0.000003000000 VT_0 machine 1\n"));
    assert_non_null(strstr(text, "11 0.000003000000 VT_1 machine 64\n"));
    assert_non_null(strstr(text, "11 0.000005000250 VT_1 machine 0\n"));
    g_free(text);
    rm_path(path);
}

/* tokenring marks each frame's end: "frame 0" .. "frame 2". */
static void test_frame_marks(void **state)
{
    (void)state;
    char *path = tmp_path(".json");
    GError *err = NULL;
    const char *const ov[] = {"run.frames=3", NULL};
    CfgRun *r = cfg_run_load("configs/tokenring.yaml", ov, &err);
    g_assert_no_error(err);
    CfgRunOpts o = {.trace = trc_open(path, 0, NULL), .quiet = TRUE};
    SimResult *res = cfg_run_exec(r, &o, &err);
    g_assert_no_error(err);
    assert_true(trc_close(o.trace, NULL));
    JsonNode *v = load_json(path);
    JsonNode *evs = js_get(v, "traceEvents");
    SimTime end = 0;
    for (guint f = 0; f < 3; f++) {
        char name[16];
        g_snprintf(name, sizeof name, "frame %u", f);
        guint n;
        JsonNode *m = find_ev(evs, "i", name, &n);
        assert_int_equal(n, 1);
        end += g_array_index(res->frame_times, SimTime, f);
        assert_true(fabs(js_num(js_get(m, "ts")) - (double)end / SIM_US) <
                    1e-6);
    }
    json_node_unref(v);
    sim_result_free(res);
    cfg_run_free(r);
    rm_path(path);
}

static void test_cap(void **state)
{
    (void)state;
    char *path = tmp_path(".json");
    SimTrace *tr = trc_open(path, 2, NULL);
    emit(tr);
    emit(tr);
    assert_int_equal(trc_events(tr), 2);
    assert_true(trc_truncated(tr));
    assert_true(trc_close(tr, NULL));
    JsonNode *v = load_json(path);
    guint n;
    JsonNode *evs = js_get(v, "traceEvents");
    find_ev(evs, "i",
            "trace truncated: cap of 2 events reached; later "
            "events are not recorded",
            &n);
    assert_int_equal(n, 1);
    find_ev(evs, "X", "merge", &n);
    assert_int_equal(n, 0);
    assert_true(
        json_node_get_boolean(js_get(js_get(v, "otherData"), "truncated")));
    json_node_unref(v);
    rm_path(path);
}

static void test_paje(void **state)
{
    (void)state;
    char *path = tmp_path(".paje");
    SimTrace *tr = trc_open(path, 0, NULL);
    emit(tr);
    assert_true(trc_close(tr, NULL));
    char *tmp = g_strconcat(path, ".tmp", NULL);
    assert_false(g_file_test(tmp, G_FILE_TEST_EXISTS));
    g_free(tmp);
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    assert_non_null(strstr(text, "%EventDef PajeSetState 6\n"));
    assert_non_null(strstr(text, "4 0.000000000000 n1 CT_Node machine "
                                 "\"gp1\"\n"));
    assert_non_null(strstr(text, "6 0.000005000250 ST_Phase n0 \"merge\"\n"));
    assert_non_null(strstr(text, "4 0.000000000000 n0 CT_Node machine "
                                 "\"gp0\"\n"));
    assert_non_null(strstr(text, "7 0.000003000000 LT_Msg machine \"64 B\" "
                                 "n1 m1\n"));
    assert_non_null(strstr(text, "8 0.000005000250 LT_Msg machine \"64 B\" "
                                 "n0 m1\n"));
    /* event lines are in time order */
    char **lines = g_strsplit(text, "\n", -1);
    double last = 0.0;
    for (char **l = lines; *l; l++) {
        if (**l < '4' || **l > '9' || (*l)[1] != ' ')
            continue;
        double t = g_ascii_strtod(*l + 2, NULL);
        assert_true(t >= last);
        last = t;
    }
    g_strfreev(lines);
    g_free(text);
    rm_path(path);
}

typedef struct {
    int n;
    SimTime sent[2], arrived[2];
    uint64_t bytes[2];
} Sent;

static void arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    Sent *s = ctx;
    s->sent[s->n] = d->sent;
    s->arrived[s->n] = d->arrived;
    s->bytes[s->n++] = d->bytes;
}

/* Messages 0 -> 1 on a 2-node hypercube (one link), `count` of them sent
 * at time 0 (1,000 and 3,000 B), at the flow fidelity (max-min sharing,
 * which reports no holds): they share the link.  The trace goes to
 * path. */
static void send_pair(const char *path, int count, Sent *s)
{
    NetTopo *topo = net_hypercube_new(1);
    NetParams p = {.bandwidth = 2.8e6, .channels = 1,
                   .startup = 350 * SIM_US, .per_hop = 10 * SIM_US,
                   .switching = NET_SW_CUT_THROUGH};
    SimEngine *eng = sim_engine_new(1);
    SimTrace *tr = trc_open(path, 0, NULL);
    sim_engine_set_trace(eng, tr);
    NetNet *net = net_new(eng, topo, &p, NET_FLOW);
    for (int i = 0; i < count; i++)
        net_send(net, 0, 1, 1000 + 2000 * (uint64_t)i, NULL, arrived, s);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(s->n, count);
    assert_true(trc_close(tr, NULL));
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(topo);
}

/* The use the messages put on their link at time t (their mean rates
 * while in flight), B/s. */
static double expected_use(const Sent *s, SimTime t)
{
    double sum = 0;
    for (int i = 0; i < s->n; i++)
        if (s->sent[i] <= t && t < s->arrived[i])
            sum += (double)s->bytes[i] /
                   sim_time_to_s(s->arrived[i] - s->sent[i]);
    return sum;
}

static void check_link_track(int count)
{
    char *path = tmp_path(".json");
    Sent s = {0};
    send_pair(path, count, &s);
    assert_true(s.arrived[0] > s.sent[0]);
    JsonNode *v = load_json(path);
    JsonNode *evs = js_get(v, "traceEvents");
    guint n;
    find_ev(evs, "C", "link n1->n0", &n);
    assert_int_equal(n, 0); /* no traffic, no track */
    find_ev(evs, "C", "link n0->n1", &n);
    assert_true(n >= 3);
    double peak = 0, last_t = -1, last_v = -1;
    for (guint i = 0; i < js_len(evs); i++) {
        JsonNode *e = js_at(evs, i);
        if (strcmp(js_str(js_get(e, "name")), "link n0->n1") != 0)
            continue;
        assert_true(js_num(js_get(e, "pid")) == 1);
        double ts = js_num(js_get(e, "ts"));
        double val = js_num(js_get(js_get(e, "args"), "B/s"));
        assert_true(ts >= last_t);
        if (ts > last_t && last_v >= 0) /* the value held before ts */
            assert_true(fabs(last_v - expected_use(&s, (SimTime)(last_t *
                        SIM_US) + 1)) <= 1e-6 * (last_v + 1));
        peak = MAX(peak, val);
        last_t = ts;
        last_v = val;
    }
    assert_true(peak > 0);
    assert_true(last_v == 0.0); /* back to 0 when the last one arrived */
    assert_true(fabs(last_t - sim_time_to_us(s.arrived[count - 1])) < 1e-6);
    json_node_unref(v);
    rm_path(path);
}

static void test_link_load(void **state)
{
    (void)state;
    check_link_track(1);
    check_link_track(2);
}

static void test_link_paje(void **state)
{
    (void)state;
    char *path = tmp_path(".paje");
    Sent s = {0};
    send_pair(path, 1, &s);
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    assert_non_null(strstr(text, "0 CT_Link CT_Machine \"LINK\"\n"));
    assert_non_null(strstr(text, "10 VT_bw CT_Link \"bandwidth_used\"\n"));
    assert_non_null(strstr(text, "4 0.000000000000 l0 CT_Link machine "
                                 "\"n0->n1\"\n"));
    assert_null(strstr(text, "\"n1->n0\""));
    char *rise = g_strdup_printf(
        "11 0.000000000000 VT_bw l0 %.17g\n",
        1000.0 / sim_time_to_s(s.arrived[0] - s.sent[0]));
    assert_non_null(strstr(text, rise));
    char *fall = g_strdup_printf(
        "11 %" G_GUINT64_FORMAT ".%012" G_GUINT64_FORMAT " VT_bw l0 0\n",
        s.arrived[0] / SIM_S, s.arrived[0] % SIM_S);
    assert_non_null(strstr(text, fall));
    g_free(rise);
    g_free(fall);
    g_free(text);
    rm_path(path);
}

/* Per-hop link load and queue depth at the packet
 * rung: two one-packet messages, 0 -> 3 (route n0->n1->n3) and 1 -> 3
 * (n1->n3), sent at time 0 on a 4-node cut-through hypercube.  Message
 * 1 -> 3 takes n1->n3 at injection; 0 -> 3's head reaches it one per-hop
 * later and waits until it is free, then holds it for one packet time.
 * So n1->n3 is in use from injection for two packet times (one step),
 * n0->n1 for one, and n1->n3's queue is 1 over the wait.  Every expected
 * time is computed from the parameters; a checker that compares a track
 * with a list of samples is also shown to reject wrong times. */
#define BYTES 1000

static const NetParams par = {.bandwidth = 1e6,
                              .channels = 1,
                              .startup = 10 * SIM_US,
                              .per_hop = 1 * SIM_US,
                              .packet_bytes = BYTES,
                              .switching = NET_SW_CUT_THROUGH};

typedef struct {
    double t_us, value;
} Sample;

static void count_arrival(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    SimTime *last = ctx;
    *last = MAX(*last, d->arrived);
}

/* Two messages of BYTES sent at time 0, src[i] -> dst[i], in that order,
 * on a 4-node topology with `par` switched by sw at fidelity fid. */
typedef struct {
    NetTopo *(*topo)(void);
    NetSwitching sw;
    NetFidelity fid;
    uint32_t src[2], dst[2];
} Pattern;

static NetTopo *cube4(void)
{
    return net_hypercube_new(2);
}

static NetTopo *ring4(void)
{
    return net_ring_new(4);
}

/* 0 -> 3 (n0->n1->n3) and 1 -> 3 (n1->n3) on the hypercube. */
static const Pattern packet_pt = {cube4, NET_SW_CUT_THROUGH, NET_PACKET,
                                  {0, 1}, {3, 3}};
static const Pattern circuit_pt = {cube4, NET_SW_CIRCUIT, NET_PACKET,
                                   {0, 1}, {3, 3}};
static const Pattern circuit_flow_pt = {cube4, NET_SW_CIRCUIT, NET_FLOW,
                                        {0, 1}, {3, 3}};
/* 0 -> 2 (s0->s1->s2) and 1 -> 2 (s1->s2) on the ring. */
static const Pattern ring_pt = {ring4, NET_SW_RING_SLOTS, NET_PACKET,
                                {0, 1}, {2, 2}};

/* Runs pt, tracing to path (NULL: no trace); returns the last arrival
 * and the engine's event count in *events. */
static SimTime run_two(const Pattern *pt, const char *path, uint64_t *events)
{
    NetTopo *topo = pt->topo();
    SimEngine *eng = sim_engine_new(1);
    SimTrace *tr = path ? trc_open(path, 0, NULL) : NULL;
    sim_engine_set_trace(eng, tr);
    NetParams p = par;
    p.switching = pt->sw;
    NetNet *net = net_new(eng, topo, &p, pt->fid);
    SimTime last = 0;
    for (int i = 0; i < 2; i++)
        net_send(net, pt->src[i], pt->dst[i], BYTES, NULL, count_arrival,
                 &last);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    *events = sim_engine_events(eng);
    if (tr)
        assert_true(trc_close(tr, NULL));
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(topo);
    return last;
}

static SimTime run_pattern(const char *path, uint64_t *events)
{
    return run_two(&packet_pt, path, events);
}

/* TRUE when the counter track `name` (series `series`) is exactly the n
 * samples of want, in order (times within 1 ps); says why not on stderr. */
static gboolean track_is(JsonNode *evs, const char *name, const char *series,
                         const Sample *want, int n)
{
    int k = 0;
    for (guint i = 0; i < js_len(evs); i++) {
        JsonNode *e = js_at(evs, i);
        if (strcmp(js_str(js_get(e, "ph")), "C") != 0 ||
            strcmp(js_str(js_get(e, "name")), name) != 0)
            continue;
        double ts = js_num(js_get(e, "ts"));
        double v = js_num(js_get(js_get(e, "args"), series));
        if (k >= n || fabs(ts - want[k].t_us) > 1e-6 ||
            fabs(v - want[k].value) > 1e-9 * (1 + fabs(want[k].value))) {
            fprintf(stderr, "# %s sample %d: found (%.6f us, %g), expected "
                            "(%.6f us, %g)\n",
                    name, k, ts, v, k < n ? want[k].t_us : -1.0,
                    k < n ? want[k].value : -1.0);
            return FALSE;
        }
        k++;
    }
    if (k != n)
        fprintf(stderr, "# %s: %d samples, expected %d\n", name, k, n);
    return k == n;
}

/* The times of the pattern, from the parameters. */
typedef struct {
    double inj, hop, pkt, rate; /* us, us, us, B/s */
} Times;

static Times times(void)
{
    SimTime pkt = sim_time_for_bytes(BYTES, par.bandwidth);
    return (Times){sim_time_to_us(net_startup(&par, BYTES) + par.per_hop),
                   sim_time_to_us(par.per_hop), sim_time_to_us(pkt),
                   BYTES / sim_time_to_s(pkt)};
}

static void test_hops_and_queue(void **state)
{
    (void)state;
    char *path = tmp_path(".json");
    uint64_t ev_traced, ev_plain;
    SimTime last = run_pattern(path, &ev_traced);
    /* tracing adds no events and moves nothing */
    assert_true(run_pattern(NULL, &ev_plain) == last);
    assert_true(ev_traced == ev_plain);
    Times x = times();
    assert_true(fabs(sim_time_to_us(last) - (x.inj + 2 * x.pkt)) < 1e-6);
    JsonNode *v = load_json(path);
    JsonNode *evs = js_get(v, "traceEvents");
    const Sample first[] = {{0, 0}, {x.inj, x.rate}, {x.inj + x.pkt, 0}};
    const Sample shared[] = {{0, 0}, {x.inj, x.rate}, {x.inj + 2 * x.pkt, 0}};
    const Sample queue[] = {{0, 0}, {x.inj + x.hop, 1}, {x.inj + x.pkt, 0}};
    assert_true(track_is(evs, "link n0->n1", "B/s", first, 3));
    assert_true(track_is(evs, "link n1->n3", "B/s", shared, 3));
    assert_true(track_is(evs, "queue n1->n3", "messages", queue, 3));
    assert_true(track_is(evs, "queue n0->n1", "messages", NULL, 0));
    json_node_unref(v);
    rm_path(path);
}

/* The checker rejects a track that is wrong by a hop's latency, the old
 * per-message average over the whole path, and an empty queue. */
static void test_wrong_times_detected(void **state)
{
    (void)state;
    char *path = tmp_path(".json");
    uint64_t ev;
    SimTime last = run_pattern(path, &ev);
    Times x = times();
    JsonNode *v = load_json(path);
    JsonNode *evs = js_get(v, "traceEvents");
    const Sample late[] = {{0, 0}, {x.inj + x.hop, x.rate},
                           {x.inj + 2 * x.pkt, 0}};
    double mean = BYTES / sim_time_to_s(last); /* about each message's */
    const Sample average[] = {{0, 0}, {0, 2 * mean}, {x.inj + x.pkt, mean},
                              {sim_time_to_us(last), 0}};
    const Sample no_queue[] = {{0, 0}};
    assert_false(track_is(evs, "link n1->n3", "B/s", late, 3));
    assert_false(track_is(evs, "link n1->n3", "B/s", average, 4));
    assert_false(track_is(evs, "queue n1->n3", "messages", no_queue, 1));
    json_node_unref(v);
    rm_path(path);
}

/* Circuits and ring slots: every sample of both links' load and of the
 * shared link's queue, from the parameters (S startup, H per hop, D one
 * message's data time), for the patterns above.  Tracing adds no events
 * and moves nothing. */
typedef struct {
    SimTime last;
    JsonNode *v; /* the trace */
    double s, h, d, rate; /* us, us, us, B/s (BYTES / D) */
} Traced;

static Traced traced(const Pattern *pt)
{
    char *path = tmp_path(".json");
    uint64_t ev_traced, ev_plain;
    Traced t = {.last = run_two(pt, path, &ev_traced)};
    assert_true(run_two(pt, NULL, &ev_plain) == t.last);
    assert_true(ev_traced == ev_plain);
    t.v = load_json(path);
    rm_path(path);
    SimTime d = sim_time_for_bytes(BYTES, par.bandwidth);
    t.s = sim_time_to_us(net_startup(&par, BYTES));
    t.h = sim_time_to_us(par.per_hop);
    t.d = sim_time_to_us(d);
    t.rate = BYTES / sim_time_to_s(d);
    return t;
}

/* The rate of BYTES held over `us` microseconds. */
static double over(double us)
{
    return BYTES / (us * 1e-6);
}

/* Packet rung: each header takes its first link at S + H; 1 -> 3 holds
 * n1->n3 for D; 0 -> 3's header reaches n1->n3 at S + 2H, waits until
 * S + H + D, holds it for D (the same rate: one merged step), and holds
 * n0->n1 from S + H to its tear-down at S + H + 2D. */
static void test_circuit_holds(void **state)
{
    (void)state;
    Traced x = traced(&circuit_pt);
    double end = x.s + x.h + 2 * x.d;
    assert_true(fabs(sim_time_to_us(x.last) - end) < 1e-6);
    JsonNode *evs = js_get(x.v, "traceEvents");
    const Sample first[] = {{0, 0}, {x.s + x.h, over(2 * x.d)}, {end, 0}};
    const Sample shared[] = {{0, 0}, {x.s + x.h, x.rate}, {end, 0}};
    const Sample queue[] = {{0, 0}, {x.s + 2 * x.h, 1}, {x.s + x.h + x.d, 0}};
    assert_true(track_is(evs, "link n0->n1", "B/s", first, 3));
    assert_true(track_is(evs, "link n1->n3", "B/s", shared, 3));
    assert_true(track_is(evs, "queue n1->n3", "messages", queue, 3));
    assert_true(track_is(evs, "queue n0->n1", "messages", NULL, 0));
    /* the checker rejects the route average (what these links showed
     * before), a hold counted only while the data streams, and a queue
     * from the send */
    const Sample average[] = {{0, 0}, {0, over(sim_time_to_us(x.last))},
                              {end, 0}};
    const Sample data_only[] = {{0, 0}, {x.s + x.h + x.d, x.rate}, {end, 0}};
    const Sample early_queue[] = {{0, 0}, {0, 1}, {x.s + x.h + x.d, 0}};
    assert_false(track_is(evs, "link n0->n1", "B/s", average, 3));
    assert_false(track_is(evs, "link n0->n1", "B/s", data_only, 3));
    assert_false(track_is(evs, "queue n1->n3", "messages", early_queue, 3));
    json_node_unref(x.v);
}

/* Flow rung of circuits and the ring: both requests come at S; the first
 * sender takes its two links at once for 2H + D; the second waits on the
 * shared link until then and holds it for H + D. */
static void check_two_at_once(const Pattern *pt, const char *first_link,
                              const char *shared_link)
{
    Traced x = traced(pt);
    double free_at = x.s + 2 * x.h + x.d, end = free_at + x.h + x.d;
    assert_true(fabs(sim_time_to_us(x.last) - end) < 1e-6);
    JsonNode *evs = js_get(x.v, "traceEvents");
    char *link1 = g_strconcat("link ", first_link, NULL);
    char *link2 = g_strconcat("link ", shared_link, NULL);
    char *q1 = g_strconcat("queue ", first_link, NULL);
    char *q2 = g_strconcat("queue ", shared_link, NULL);
    const Sample first[] = {{0, 0}, {x.s, over(2 * x.h + x.d)}, {free_at, 0}};
    const Sample shared[] = {{0, 0}, {x.s, over(2 * x.h + x.d)},
                             {free_at, over(x.h + x.d)}, {end, 0}};
    const Sample queue[] = {{0, 0}, {x.s, 1}, {free_at, 0}};
    assert_true(track_is(evs, link1, "B/s", first, 3));
    assert_true(track_is(evs, link2, "B/s", shared, 4));
    assert_true(track_is(evs, q2, "messages", queue, 3));
    assert_true(track_is(evs, q1, "messages", NULL, 0));
    /* rejected: the queue on the sender's first link, the second hold
     * a hop late */
    const Sample late[] = {{0, 0}, {x.s, over(2 * x.h + x.d)},
                           {free_at + x.h, over(x.h + x.d)}, {end, 0}};
    assert_false(track_is(evs, q1, "messages", queue, 3));
    assert_false(track_is(evs, link2, "B/s", late, 4));
    g_free(link1);
    g_free(link2);
    g_free(q1);
    g_free(q2);
    json_node_unref(x.v);
}

static void test_circuit_flow_holds(void **state)
{
    (void)state;
    check_two_at_once(&circuit_flow_pt, "n0->n1", "n1->n3");
}

static void test_ring_holds(void **state)
{
    (void)state;
    check_two_at_once(&ring_pt, "s0->s1", "s1->s2");
}

/* Paje: the queue is variable "messages_waiting" of the link container. */
static void test_paje_queue(void **state)
{
    (void)state;
    char *path = tmp_path(".paje");
    uint64_t ev;
    run_pattern(path, &ev);
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    assert_non_null(strstr(text, "10 VT_q CT_Link \"messages_waiting\"\n"));
    assert_non_null(strstr(text, "4 0.000000000000 l1 CT_Link machine "
                                 "\"n1->n3\"\n"));
    SimTime wait = net_startup(&par, BYTES) + 2 * par.per_hop;
    char *rise = g_strdup_printf("11 %" G_GUINT64_FORMAT ".%012" G_GUINT64_FORMAT
                                 " VT_q l1 1\n",
                                 wait / SIM_S, wait % SIM_S);
    assert_non_null(strstr(text, rise));
    assert_null(strstr(text, "VT_q l0"));
    g_free(rise);
    g_free(text);
    rm_path(path);
}

static void test_bad_name(void **state)
{
    (void)state;
    GError *err = NULL;
    assert_null(trc_open("/tmp/x.txt", 0, &err));
    assert_non_null(strstr(err->message, "expected a file ending in .json"));
    g_error_free(err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chrome),
        cmocka_unit_test(test_cap),
        cmocka_unit_test(test_paje),
        cmocka_unit_test(test_counters),
        cmocka_unit_test(test_frame_marks),
        cmocka_unit_test(test_link_load),
        cmocka_unit_test(test_link_paje),
        cmocka_unit_test(test_hops_and_queue),
        cmocka_unit_test(test_wrong_times_detected),
        cmocka_unit_test(test_paje_queue),
        cmocka_unit_test(test_circuit_holds),
        cmocka_unit_test(test_circuit_flow_holds),
        cmocka_unit_test(test_ring_holds),
        cmocka_unit_test(test_bad_name),
    };
    return cmocka_run_group_tests_name("trace", tests, NULL, NULL);
}
