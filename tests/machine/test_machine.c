/* test_machine.c — machines built from models: kinds, costs, processors
 * (FIFO serialisation, busy time per phase, trace spans), network, result.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/trace.h"
#include "sim/machine/machine.h"
#include "sim/machine/shmem.h"
#include "tests/support.h"

typedef struct {
    SimEngine *eng;
    MachMachine *m;
    GArray *log; /* completion records */
} Fix;

typedef struct {
    int tag;
    SimTime at;
} Done;

static int setup_tiny(void **state)
{
    Fix *f = g_new0(Fix, 1);
    GError *err = NULL;
    g_setenv("PGSIM_MODELS", "tests/data/models", TRUE);
    f->eng = sim_engine_new(7);
    f->m = mach_new_from_model(f->eng, "tiny", "analytic", &err);
    if (!f->m)
        fail_msg("%s", err->message);
    f->log = g_array_new(FALSE, FALSE, sizeof(Done));
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    Fix *f = *state;
    mach_free(f->m);
    sim_engine_free(f->eng);
    g_array_free(f->log, TRUE);
    g_free(f);
    return 0;
}

static void record(SimEngine *eng, void *ctx, void *arg)
{
    Fix *f = ctx;
    Done d = {GPOINTER_TO_INT(arg), sim_now(eng)};
    g_array_append_val(f->log, d);
}

static Done logged(const Fix *f, guint i)
{
    assert_true(i < f->log->len);
    return g_array_index(f->log, Done, i);
}

static void test_all_models_build(void **state)
{
    (void)state;
    static const char *const names[] = {"ipsc2", "pixel-planes-5", "cm200",
                                        "cm5",   "cluster-ib",     NULL};
    static const char *const fids[] = {"analytic", "flow", "packet"};
    for (const char *const *n = names; *n; n++) {
        for (guint i = 0; i < G_N_ELEMENTS(fids); i++) {
            SimEngine *eng = sim_engine_new(1);
            GError *err = NULL;
            MachMachine *m = mach_new_from_model(eng, *n, fids[i], &err);
            if (!m)
                fail_msg("%s/%s: %s", *n, fids[i], err->message);
            assert_string_equal(mach_name(m), *n);
            assert_string_equal(mach_fidelity(m), fids[i]);
            assert_true(mach_proc_total(m) > 0);
            mach_free(m);
            sim_engine_free(eng);
        }
    }
}

static void test_model_contents(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m = mach_new_from_model(eng, "pixel-planes-5", "flow", NULL);
    assert_non_null(m);
    assert_int_equal(mach_kind_count(m), 4);
    assert_string_equal(mach_kind_at(m, 0)->name, "host");
    const MachKindInfo *gp = mach_kind(m, "gp");
    const MachKindInfo *r = mach_kind(m, "renderer");
    assert_int_equal(gp->first, 1);
    assert_int_equal(gp->count, 16);
    assert_int_equal(r->first, 17);
    assert_int_equal(r->lanes, 128 * 128);
    assert_true(r->clock_hz == 40e6);
    assert_int_equal(mach_proc_total(m), 1 + 16 + 16 + 1);
    assert_string_equal(mach_proc_name(mach_proc(m, "renderer", 2)),
                        "renderer2");
    assert_int_equal(mach_proc_id(mach_proc(m, "renderer", 2)), 19);
    double bw = 0;
    assert_true(mach_net_bandwidth(m, "total_bandwidth", &bw));
    assert_true(bw == 640e6);
    uint64_t ch = 0;
    assert_true(mach_net_count(m, "channels", &ch));
    assert_int_equal(ch, 8);
    mach_free(m);
    m = mach_new_from_model(eng, "cm5", "analytic", NULL);
    GArray *lv = mach_net_bw_list(m, "level_bandwidth");
    assert_non_null(lv);
    assert_int_equal(lv->len, 3);
    assert_true(g_array_index(lv, double, 0) == 20e6);
    assert_true(g_array_index(lv, double, 2) == 5e6);
    g_array_unref(lv);
    assert_null(mach_net_bw_list(m, "no_such_list"));
    assert_string_equal(mach_net_word(m, "topology"), "fat-tree");
    mach_free(m);
    sim_engine_free(eng);
}

static void test_costs(void **state)
{
    Fix *f = *state;
    assert_int_equal(mach_cost(f->m, "cpu", "work"), 10 * SIM_US);
    assert_int_equal(mach_cost(f->m, "cpu", "tiny_op"), 3 * SIM_NS);
    static const char *const ok[] = {"work", "tiny_op", NULL};
    static const char *const missing[] = {"work", "teleport", NULL};
    GError *err = NULL;
    assert_true(mach_require_costs(f->m, "cpu", ok, &err));
    assert_false(mach_require_costs(f->m, "cpu", missing, &err));
    assert_true(g_str_has_prefix(err->message, "tests/data/models/tiny.yaml:"));
    assert_non_null(strstr(err->message, "teleport"));
    g_clear_error(&err);
    SimTime t;
    assert_false(mach_cost_lookup(f->m, "gpu", "work", &t, &err));
    assert_non_null(strstr(err->message, "no node kind 'gpu'"));
    g_clear_error(&err);
    /* the network section as checked, and entities registered once */
    const CfgNode *net = mach_network_cfg(f->m);
    assert_non_null(cfg_get(net, "bandwidth"));
    MachProc *p = mach_proc_at(f->m, 2);
    uint32_t e = mach_proc_entity(p);
    assert_int_equal(mach_proc_entity(p), e);
    assert_int_not_equal(mach_proc_entity(mach_proc_at(f->m, 3)), e);
    /* shared memory: 100 bytes at 1 MB/s hold it 100 us of 400 */
    MachShmem sh;
    mach_shmem_init_with(&sh, 1e6, 0);
    mach_shmem_transfer(&sh, 0, 100);
    assert_true(fabs(mach_shmem_utilisation(&sh, 400 * SIM_US) - 0.25) < 1e-9);
    assert_true(sh.bytes == 100 && sh.transfers == 1);
    assert_true(mach_shmem_utilisation(&sh, 0) == 0);
}

/* Three requests submitted at once run back to back, in order. */
static void test_fifo_serialisation(void **state)
{
    Fix *f = *state;
    unsigned a = sim_engine_phase(f->eng, "raster");
    unsigned b = sim_engine_phase(f->eng, "merge");
    MachProc *p = mach_proc(f->m, "cpu", 1);
    assert_true(mach_proc_idle(p));
    assert_true(
        mach_proc_compute(p, 10 * SIM_US, a, record, f, GINT_TO_POINTER(1)));
    assert_true(
        mach_proc_compute(p, 20 * SIM_US, b, record, f, GINT_TO_POINTER(2)));
    assert_true(
        mach_proc_compute(p, 5 * SIM_US, a, record, f, GINT_TO_POINTER(3)));
    assert_false(mach_proc_idle(p));
    assert_int_equal(mach_proc_free_at(p), 35 * SIM_US);
    /* another processor is independent */
    MachProc *q = mach_proc(f->m, "cpu", 2);
    assert_true(
        mach_proc_compute(q, 7 * SIM_US, a, record, f, GINT_TO_POINTER(4)));
    assert_true(sim_engine_run(f->eng, SIM_TIME_MAX, NULL));
    assert_int_equal(f->log->len, 4);
    assert_int_equal(logged(f, 0).tag, 4);
    assert_int_equal(logged(f, 0).at, 7 * SIM_US);
    assert_int_equal(logged(f, 1).tag, 1);
    assert_int_equal(logged(f, 1).at, 10 * SIM_US);
    assert_int_equal(logged(f, 2).tag, 2);
    assert_int_equal(logged(f, 2).at, 30 * SIM_US);
    assert_int_equal(logged(f, 3).tag, 3);
    assert_int_equal(logged(f, 3).at, 35 * SIM_US);
    assert_int_equal(mach_proc_busy(p), 35 * SIM_US);
    assert_int_equal(mach_proc_busy_phase(p, a), 15 * SIM_US);
    assert_int_equal(mach_proc_busy_phase(p, b), 20 * SIM_US);
    assert_int_equal(mach_proc_busy_phase(p, 0), 0);
    assert_int_equal(mach_proc_requests(p), 3);
    assert_true(mach_proc_idle(p));
}

/* Work submitted from a completion handler queues behind earlier work;
 * work submitted after an idle gap starts at once. */
typedef struct {
    Fix *f;
    MachProc *p;
} Chain;

static void resubmit(SimEngine *eng, void *ctx, void *arg)
{
    Chain *c = ctx;
    record(eng, c->f, arg);
    if (GPOINTER_TO_INT(arg) == 1)
        mach_proc_compute(c->p, 1 * SIM_US, 0, record, c->f,
                          GINT_TO_POINTER(9));
}

static void late_submit(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    Chain *c = ctx;
    mach_proc_compute(c->p, 5 * SIM_US, 0, record, c->f, GINT_TO_POINTER(7));
}

static void test_fifo_from_handlers_and_idle_gap(void **state)
{
    Fix *f = *state;
    Chain c = {f, mach_proc(f->m, "cpu", 0)};
    mach_proc_compute(c.p, 10 * SIM_US, 0, resubmit, &c, GINT_TO_POINTER(1));
    mach_proc_compute(c.p, 4 * SIM_US, 0, resubmit, &c, GINT_TO_POINTER(2));
    sim_schedule_at(f->eng, 100 * SIM_US, late_submit, &c, NULL);
    assert_true(sim_engine_run(f->eng, SIM_TIME_MAX, NULL));
    assert_int_equal(f->log->len, 4);
    assert_int_equal(logged(f, 0).tag, 1);
    assert_int_equal(logged(f, 1).tag, 2);
    assert_int_equal(logged(f, 1).at, 14 * SIM_US);
    assert_int_equal(logged(f, 2).tag, 9);
    assert_int_equal(logged(f, 2).at, 15 * SIM_US);
    assert_int_equal(logged(f, 3).tag, 7);
    assert_int_equal(logged(f, 3).at, 105 * SIM_US);
    assert_int_equal(mach_proc_busy(c.p), 20 * SIM_US);
}

static void test_zero_cost_and_null_done(void **state)
{
    Fix *f = *state;
    MachProc *p = mach_proc(f->m, "cpu", 3);
    assert_true(mach_proc_compute(p, 2 * SIM_US, 0, NULL, NULL, NULL));
    assert_true(mach_proc_compute(p, 0, 0, record, f, GINT_TO_POINTER(5)));
    assert_true(sim_engine_run(f->eng, SIM_TIME_MAX, NULL));
    assert_int_equal(f->log->len, 1);
    assert_int_equal(logged(f, 0).at, 2 * SIM_US);
}

static void test_overflow_stops_engine(void **state)
{
    Fix *f = *state;
    MachProc *p = mach_proc(f->m, "cpu", 0);
    assert_true(mach_proc_compute(p, SIM_TIME_MAX - 5, 0, NULL, NULL, NULL));
    assert_false(mach_proc_compute(p, 10, 0, record, f, NULL));
    GError *err = NULL;
    assert_false(sim_engine_run(f->eng, SIM_TIME_MAX, &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_OVERFLOW));
    assert_non_null(strstr(err->message, "cpu0"));
    g_error_free(err);
}

/* At SIM_TIME_MAX - 5 an idle processor is asked for 10 ps: its
 * completion time overflows though its busy time would not. */
static void late_compute(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    MachProc *p = ctx;
    *(gboolean *)arg = mach_proc_compute(p, 10, 0, NULL, NULL, NULL);
}

static void test_late_overflow_charges_nothing(void **state)
{
    Fix *f = *state;
    MachProc *p = mach_proc(f->m, "cpu", 1);
    gboolean ok = TRUE;
    assert_true(sim_schedule_at(f->eng, SIM_TIME_MAX - 5, late_compute, p,
                                &ok));
    GError *err = NULL;
    assert_false(sim_engine_run(f->eng, SIM_TIME_MAX, &err));
    assert_false(ok);
    assert_int_equal(mach_proc_busy(p), 0);
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_OVERFLOW));
    assert_non_null(strstr(err->message, "completion time of processor cpu1"));
    g_error_free(err);
}

/* A trace sink that keeps the spans it is given. */
typedef struct {
    GString *text;
} SpanLog;

static void span_cb(SimTrace *tr, uint32_t node, const char *name,
                    const char *phase, SimTime start, SimTime end)
{
    SpanLog *l = tr->state;
    g_string_append_printf(
        l->text, "%u:%s:%s:%" G_GUINT64_FORMAT "-%" G_GUINT64_FORMAT ";", node,
        name, phase, start / SIM_US, end / SIM_US);
}

static void test_trace_spans(void **state)
{
    Fix *f = *state;
    static const SimTraceOps ops = {.span = span_cb};
    SpanLog l = {g_string_new("")};
    SimTrace tr = {&ops, &l};
    sim_engine_set_trace(f->eng, &tr);
    unsigned ph = sim_engine_phase(f->eng, "zbuf");
    MachProc *p = mach_proc(f->m, "cpu", 2);
    mach_proc_compute(p, 10 * SIM_US, ph, NULL, NULL, NULL);
    mach_proc_compute(p, 5 * SIM_US, 0, NULL, NULL, NULL);
    assert_true(sim_engine_run(f->eng, SIM_TIME_MAX, NULL));
    /* spans carry the processor id: the number flows use */
    uint32_t e = mach_proc_id(p);
    char *want =
        g_strdup_printf("%u:cpu2:zbuf:0-10;%u:cpu2:compute:10-15;", e, e);
    assert_string_equal(l.text->str, want);
    assert_string_equal(sim_engine_node_name(f->eng, e), "cpu2");
    g_free(want);
    g_string_free(l.text, TRUE);
    sim_engine_set_trace(f->eng, NULL);
}

static void test_fill_result(void **state)
{
    Fix *f = *state;
    unsigned ph = sim_engine_phase(f->eng, "merge");
    mach_proc_compute(mach_proc(f->m, "cpu", 1), 8 * SIM_US, ph, NULL, NULL,
                      NULL);
    mach_proc_compute(mach_proc(f->m, "cpu", 3), 3 * SIM_US, 0, NULL, NULL,
                      NULL);
    net_send(mach_net(f->m), 0, 3, 500, NULL, NULL, NULL);
    assert_true(sim_engine_run(f->eng, SIM_TIME_MAX, NULL));
    SimResult *r = sim_result_new("test", "x");
    mach_fill_result(f->m, r);
    assert_string_equal(r->machine, "tiny");
    assert_string_equal(r->fidelity, "analytic");
    /* cpu1 and cpu3 computed; cpu0 and cpu2 (a send is the network's
     * time, not a processor's) did nothing and are only counted, in one
     * idle line for their kind */
    assert_int_equal(r->nodes->len, 2);
    assert_int_equal(r->idle->len, 1);
    SimIdleResult *idle = g_ptr_array_index(r->idle, 0);
    assert_string_equal(idle->kind, "cpu");
    assert_int_equal(idle->count, 2);
    SimNodeResult *n1 = g_ptr_array_index(r->nodes, 0);
    SimNodeResult *n3 = g_ptr_array_index(r->nodes, 1);
    assert_string_equal(n1->name, "cpu1");
    assert_string_equal(n1->kind, "cpu");
    assert_int_equal(n1->busy.total, 8 * SIM_US);
    assert_int_equal(sim_busy_phase(&n1->busy, ph), 8 * SIM_US);
    assert_int_equal(n3->busy.total, 3 * SIM_US);
    assert_int_equal(sim_busy_phase(&n3->busy, 0), 3 * SIM_US);
    assert_string_equal(g_ptr_array_index(r->phases, ph), "merge");
    assert_int_equal(r->comm_bytes, 500);
    assert_int_equal(r->comm_messages, 1);
    sim_result_free(r);
}

/* The network is built from the model: startup + hops x per_hop +
 * bytes / bandwidth for a lone message on the iPSC/2. */
static void arrived(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    *(SimTime *)ctx = d->arrived;
}

static void test_network_from_model(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m = mach_new_from_model(eng, "ipsc2", "packet", NULL);
    assert_non_null(m);
    NetNet *net = mach_net(m);
    assert_non_null(net);
    assert_true(mach_require_net(m, NULL));
    assert_int_equal(net_nodes(net), 16);
    assert_int_equal(net_fidelity(net), NET_PACKET);
    const NetParams *p = net_params(net);
    assert_true(p->bandwidth == 2.8e6);
    assert_int_equal(p->startup, 350 * SIM_US);
    assert_int_equal(p->per_hop, 10 * SIM_US);
    assert_int_equal(p->switching, NET_SW_CIRCUIT);
    /* The NX long-message protocol comes from the model: a message above
     * long_threshold pays startup_long, one of exactly long_threshold
     * bytes the short start-up (disjoint paths: 0->1->3, 5->4->6). */
    SimTime slong = 0;
    uint64_t th = 0;
    assert_true(mach_net_time(m, "startup_long", &slong));
    assert_true(mach_net_size(m, "long_threshold", &th));
    assert_int_equal(p->startup_long, slong);
    assert_int_equal(p->long_threshold, th);
    assert_true(slong > p->startup && th < 1000);
    SimTime at = 0, at_short = 0;
    net_send(net, 0, 3, 1000, NULL, arrived, &at);
    net_send(net, 5, 6, th, NULL, arrived, &at_short);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    SimTime want = slong + 2 * 10 * SIM_US + sim_time_for_bytes(1000, 2.8e6);
    assert_true(at + 1 >= want && at <= want + 1);
    want = 350 * SIM_US + 2 * 10 * SIM_US + sim_time_for_bytes(th, 2.8e6);
    assert_true(at_short + 1 >= want && at_short <= want + 1);
    mach_free(m);
    /* A topology the machine layer cannot build says so. */
    GError *err = NULL;
    CfgNode *root = cfg_load_string("machine:\n  model: ipsc2\n"
                                    "  network: {topology: dragonfly}\n",
                                    "run.yaml", &err);
    m = mach_new_from_cfg(eng, cfg_get(root, "machine"), "flow", &err);
    assert_non_null(m);
    assert_null(mach_net(m));
    assert_false(mach_require_net(m, &err));
    assert_true(g_str_has_prefix(err->message, "run.yaml:3:"));
    assert_non_null(strstr(err->message, "dragonfly"));
    g_error_free(err);
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
}

/* Each shipped model's network has the endpoints and parameters its
 * model file describes. */
static NetNet *net_of(SimEngine *eng, const char *name, MachMachine **m)
{
    GError *err = NULL;
    *m = mach_new_from_model(eng, name, "flow", &err);
    if (!*m)
        fail_msg("%s: %s", name, err->message);
    if (!mach_require_net(*m, &err))
        fail_msg("%s: %s", name, err->message);
    return mach_net(*m);
}

static void test_shipped_networks(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m;
    NetNet *n = net_of(eng, "pixel-planes-5", &m);
    assert_int_equal(net_nodes(n), 34);
    assert_int_equal(net_params(n)->channels, 8);
    assert_true(net_params(n)->bandwidth == 80e6);
    assert_int_equal(net_params(n)->switching, NET_SW_RING_SLOTS);
    assert_string_equal(net_topo(n)->ops->name, "ring");
    mach_free(m);
    n = net_of(eng, "cm5", &m);
    assert_true(net_nodes(n) >= 256);
    assert_true(net_params(n)->level_bw[1] == 10e6);
    assert_true(net_params(n)->bandwidth == 20e6);
    assert_int_equal(net_params(n)->packet_bytes, 20);
    mach_free(m);
    n = net_of(eng, "cm200", &m);
    assert_int_equal(net_nodes(n), 65536);
    assert_int_equal(net_params(n)->switching, NET_SW_STORE_FORWARD);
    mach_free(m);
    n = net_of(eng, "cluster-ib", &m);
    assert_true(net_nodes(n) >= 64);
    assert_int_equal(net_params(n)->per_hop, 90 * SIM_NS);
    mach_free(m);
    sim_engine_free(eng);
}

/* "faithful" takes each model's network.fidelity: circuit switching
 * (packet) on the iPSC/2, and says so; a bad word there is located. */
static void test_faithful_fidelity(void **state)
{
    (void)state;
    static const char *const names[] = {"ipsc2", "pixel-planes-5", "cm200",
                                        "cm5", "cluster-ib", NULL};
    for (const char *const *n = names; *n; n++) {
        SimEngine *eng = sim_engine_new(1);
        MachMachine *m = mach_new_from_model(eng, *n, "faithful", NULL);
        assert_non_null(m);
        assert_string_equal(mach_fidelity(m), "packet (faithful)");
        assert_int_equal(net_fidelity(mach_net(m)), NET_PACKET);
        mach_free(m);
        sim_engine_free(eng);
    }
    SimEngine *eng = sim_engine_new(1);
    CfgNode *sec = cfg_load_string(
        "machine: {model: ipsc2, network: {fidelity: {value: exact, "
        "assumption: test}}}\n",
        "t.yaml", NULL);
    GError *err = NULL;
    assert_null(mach_new_from_cfg(eng, cfg_get(sec, "machine"), "faithful",
                                  &err));
    assert_non_null(strstr(err->message, "fidelity 'exact'"));
    g_error_free(err);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(sec, "machine"), "flow", NULL);
    assert_string_equal(mach_fidelity(m), "flow"); /* asked: not the model's */
    mach_free(m);
    cfg_free(sec);
    sim_engine_free(eng);
}

/* Each kind is under 16M processors, the two together are not. */
static void test_too_many_processors(void **state)
{
    (void)state;
    g_setenv("PGSIM_MODELS", "tests/data/models", TRUE);
    SimEngine *eng = sim_engine_new(1);
    GError *err = NULL;
    assert_null(mach_new_from_model(eng, "too-many", "analytic", &err));
    assert_non_null(strstr(err->message, "more than 16M processors in all"));
    g_error_free(err);
    sim_engine_free(eng);
}

static void test_bad_fidelity(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    GError *err = NULL;
    assert_null(mach_new_from_model(eng, "ipsc2", "quantum", &err));
    assert_non_null(strstr(err->message, "quantum"));
    g_error_free(err);
    mach_free(NULL);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_models_build),
        cmocka_unit_test(test_faithful_fidelity),
        cmocka_unit_test(test_too_many_processors),
        cmocka_unit_test(test_model_contents),
        cmocka_unit_test_setup_teardown(test_costs, setup_tiny, teardown),
        cmocka_unit_test_setup_teardown(test_fifo_serialisation, setup_tiny,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_fifo_from_handlers_and_idle_gap,
                                        setup_tiny, teardown),
        cmocka_unit_test_setup_teardown(test_zero_cost_and_null_done,
                                        setup_tiny, teardown),
        cmocka_unit_test_setup_teardown(test_overflow_stops_engine, setup_tiny,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_late_overflow_charges_nothing,
                                        setup_tiny, teardown),
        cmocka_unit_test_setup_teardown(test_trace_spans, setup_tiny, teardown),
        cmocka_unit_test_setup_teardown(test_fill_result, setup_tiny, teardown),
        cmocka_unit_test(test_network_from_model),
        cmocka_unit_test(test_shipped_networks),
        cmocka_unit_test(test_bad_fidelity),
    };
    return cmocka_run_group_tests_name("machine", tests, NULL, NULL);
}
