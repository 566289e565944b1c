/* test_dp_wire.c — dpscan's SPMD sends priced on a network (dp_array.h
 * WlDpWireFn): the hook gets each send's node pairs with their message
 * counts, its time replaces the analytic fat tree only when it is the
 * slower of wire and software, and the workload hands the pairs to the
 * machine's network at the run's fidelity (flow sharing makes the same
 * sends slower on the wire than contention-free analytic messages). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <math.h>

#include "sim/workload/dpscan/dp_array.h"
#include "sim/workload/workload.h"
#include "tests/support.h"

typedef struct {
    guint calls;
    size_t pairs;
    uint64_t msgs, self;
    SimTime answer;
} Seen;

static SimTime fake_wire(void *ctx, const WlDpTraffic *t)
{
    Seen *s = ctx;
    s->calls++;
    s->pairs = t->n;
    s->msgs = 0;
    for (size_t k = 0; k < t->n; k++) {
        s->msgs += t->msgs[k];
        s->self += t->src[k] == t->dst[k] ? t->msgs[k] : 0;
    }
    return s->answer;
}

static WlDpMachine spmd4(void)
{
    return (WlDpMachine){.arch = WL_DP_SPMD,
                         .procs = 4,
                         .op = 1,
                         .step = 10,
                         .net_latency = 100,
                         .msg_overhead = 1000,
                         .msg_bytes = 20,
                         .arity = 4,
                         .levels = 1,
                         .level_bw = {20e6}};
}

static void test_hook_gets_pairs_and_prices(void **state)
{
    (void)state;
    WlDpMachine m = spmd4();
    WlDpVm *vm = wl_dp_vm_new(&m, 1, 4, 2);
    Seen seen = {.answer = 7 * SIM_US};
    wl_dp_vm_set_wire(vm, 0, fake_wire, &seen);
    /* 8 source elements on 4 nodes (2 each) to 8 destinations (2 each):
     * elements 0,1 -> node 3 twice; 2 -> 0; 3 -> 1; 4..7 -> their own
     * node.  Pairs: (0,3) x2, (1,0), (1,1), (2,2) x2, (3,3) x2. */
    uint64_t dst[] = {6, 7, 0, 2, 4, 5, 6, 7};
    WlDpSend s = {.phase = WL_DP_PH_ROUTER, .n_src = 8, .n_dst = 8,
                  .lay = WL_DP_LAYOUT_LINEAR, .dst = dst, .count = 8,
                  .words = 2, .comb = WL_DP_COMBINE_OVERWRITE};
    wl_dp_send(vm, &s);
    const WlDpTarget *t = wl_dp_vm_target(vm, 0);
    assert_int_equal(seen.calls, 1);
    assert_int_equal(seen.pairs, 5);
    assert_int_equal(seen.msgs, 8);
    assert_int_equal(seen.self, 5);
    /* Load 4 (node 3 receives 4): software 4 ns < 7 us of wire. */
    assert_int_equal(t->total, 2 * (10 + 100 + 7 * SIM_US));
    assert_int_equal(t->wire_total, 2 * 7 * SIM_US);
    assert_int_equal(t->soft_total, 2 * 4 * 1000);
    /* A fast wire: the software bounds the send. */
    seen.answer = 1;
    SimTime before = t->total;
    wl_dp_send(vm, &s);
    assert_int_equal(t->total - before, 2 * (10 + 100 + 4 * 1000));
    wl_dp_vm_free(vm);
}

/* One dpscan frame of `yml` at `fid` (its result, elapsed included). */
static SimResult *dp_frame(const char *yml, const char *fid)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(yml, "run.yaml", &err);
    assert_non_null(root);
    SupportRun o = {.fidelity = fid, .frames = 1};
    SimResult *r = support_run_tree(root, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    return r;
}

/* router_wire_s of one dpscan frame of `yml` at `fid`. */
static double run_wire_s(const char *yml, const char *fid, double *frame,
                         double *messages)
{
    SimResult *r = dp_frame(yml, fid);
    double w = 0;
    assert_true(sim_result_get_metric(r, "router_wire_s", &w));
    *frame = sim_time_to_s(r->elapsed);
    assert_true(sim_result_get_metric(r, "messages", messages));
    assert_true(r->comm_messages > 0);
    sim_result_free(r);
    return w;
}

/* router_wire_s of a small dpscan frame on a 16-node CM-5 at `fid`. */
static double wire_s(const char *fid, double *frame)
{
    double msgs;
    return run_wire_s("workload: {type: dpscan, model: cm5, "
                      "processors: 16, width: 96, height: 64}\n"
                      "scene: {generator: isosurface, grid: 8}\n",
                      fid, frame, &msgs);
}

/* One triangle on a one-pixel screen over 2 nodes: its segment and its
 * pixel both stay on node 0, so each send's network time is the
 * start-up alone, which the model's net_latency already holds: no wire
 * time at all (not a picosecond per word). */
static void test_self_sends_no_wire(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("dpwire-XXXXXX", NULL);
    char *obj = g_build_filename(dir, "tri.obj", NULL);
    assert_true(g_file_set_contents(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                         "f 1 2 3\n", -1, NULL));
    char *yml = g_strdup_printf("workload: {type: dpscan, model: cm5, "
                                "processors: 2, width: 1, height: 1}\n"
                                "scene: {file: %s}\n", obj);
    double frame, msgs;
    assert_true(run_wire_s(yml, "analytic", &frame, &msgs) == 0.0);
    assert_true(msgs == 2 && frame > 0);
    /* On 2 x 2 pixels some of the 5 messages (20 B each, 1 us a link at
     * 20 MB/s) cross to node 1: a few microseconds of wire in all, less
     * than the one 10 us start-up that is charged in net_latency instead
     * (removed from each send's network time, never added). */
    g_free(yml);
    yml = g_strdup_printf("workload: {type: dpscan, model: cm5, "
                          "processors: 2, width: 2, height: 2}\n"
                          "scene: {file: %s}\n", obj);
    double w = run_wire_s(yml, "analytic", &frame, &msgs);
    assert_true(msgs == 5 && w >= 1e-6 && w < 10e-6);
    g_remove(obj);
    g_rmdir(dir);
    g_free(yml);
    g_free(obj);
    g_free(dir);
}

static void test_workload_uses_fidelity(void **state)
{
    (void)state;
    double fa, ff;
    double a = wire_s("analytic", &fa), f = wire_s("flow", &ff);
    assert_true(a > 0);
    /* Sharing the leaf links makes the same traffic slower on the wire. */
    assert_true(f > a);
    assert_true(ff >= fa);
}

/* The CM-5 with a per-message software cost of 1 ns (a model written to
 * a temporary data root): the wire, not the software, bounds a send
 * that crosses nodes, so the router phase's counts carry wire time.
 * The frame played on the machine then lasts exactly the sum of its
 * counted phases (the compute part and the wire part of a phase add up
 * to the phase, never more). */
static void test_wire_bound_phases_add_up(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("dpwire-XXXXXX", NULL);
    char *mdir = g_build_filename(dir, "models", NULL);
    assert_int_equal(g_mkdir(mdir, 0700), 0);
    char *text = NULL;
    assert_true(g_file_get_contents("models/cm5.yaml", &text, NULL, NULL));
    char **parts = g_strsplit(text, "value: 5.68 us", -1);
    assert_int_equal(g_strv_length(parts), 2); /* msg_overhead, once */
    char *fast = g_strjoinv("value: 1 ns", parts);
    char *model = g_build_filename(mdir, "cm5fast.yaml", NULL);
    assert_true(g_file_set_contents(model, fast, -1, NULL));
    char *obj = g_build_filename(dir, "tri.obj", NULL);
    assert_true(g_file_set_contents(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                         "f 1 2 3\n", -1, NULL));
    g_setenv("PGSIM_DATA", dir, TRUE);
    char *yml = g_strdup_printf("workload: {type: dpscan, model: cm5fast, "
                                "processors: 2, width: 2, height: 2}\n"
                                "scene: {file: %s}\n", obj);
    SimResult *r = dp_frame(yml, "analytic");
    static const char *const ph[] = {"transform_s", "scan_s", "pixel_s",
                                     "router_s", "display_s"};
    double sum = 0, v, wire, soft;
    for (guint i = 0; i < G_N_ELEMENTS(ph); i++) {
        assert_true(sim_result_get_metric(r, ph[i], &v));
        sum += v;
    }
    assert_true(sim_result_get_metric(r, "router_wire_s", &wire));
    assert_true(sim_result_get_metric(r, "router_soft_s", &soft));
    assert_true(wire > 1e-6 && soft < wire); /* the wire bounds */
    double frame = sim_time_to_s(r->elapsed);
    assert_true(fabs(frame - sum) <= 1e-12 * sum);
    g_unsetenv("PGSIM_DATA");
    sim_result_free(r);
    g_remove(model);
    g_remove(obj);
    g_rmdir(mdir);
    g_rmdir(dir);
    g_strfreev(parts);
    g_free(text), g_free(fast), g_free(model), g_free(obj), g_free(yml);
    g_free(mdir), g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hook_gets_pairs_and_prices),
        cmocka_unit_test(test_workload_uses_fidelity),
        cmocka_unit_test(test_self_sends_no_wire),
        cmocka_unit_test(test_wire_bound_phases_add_up),
    };
    return cmocka_run_group_tests_name("dp_wire", tests, NULL, NULL);
}
