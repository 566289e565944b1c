/* test_tr_checks.c — the tokenring workload's defaults and metrics
 * against its closed form (tokenring_workload.c's opening comment), the
 * test computing every expected value itself (issue 21): an empty
 * workload section is 8 nodes, 1000 B, 20 us, no jitter, 5 us and
 * 2.8 MB/s; hop_time_mean and link_utilisation_mean; a latency past
 * SimTime's range is an engine error, not a wrap; a machine section is
 * refused at its location (by the runner, sim/run/run.h); mem_bytes is a
 * record per node. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/core/rng.h"
#include "sim/workload/tokenring/tokenring_workload.h"
#include "tests/support.h"

static SimResult *run_ring(const char *text, int frames, GError **err)
{
    CfgNode *root = cfg_load_string(text, "ring.yaml", err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = frames};
    return support_run_tree(root, &o, err);
}

static double metric(const SimResult *r, const char *name)
{
    double v = NAN;
    assert_true(sim_result_get_metric(r, name, &v));
    return v;
}

static void test_defaults(void **state)
{
    (void)state;
    GError *err = NULL;
    SimResult *r = run_ring("workload: {type: tokenring}\n", 2, &err);
    assert_non_null(r);
    /* 1000 B at 2.8e6 B/s, rounded up to a picosecond */
    SimTime ser = (SimTime)ceil(1000 / 2.8e6 * 1e12);
    SimTime round = 8 * (20 * SIM_US + ser + 5 * SIM_US);
    assert_int_equal(r->frame_times->len, 2);
    assert_int_equal(g_array_index(r->frame_times, SimTime, 0), round);
    assert_int_equal(g_array_index(r->frame_times, SimTime, 1), round);
    assert_int_equal(r->elapsed, 2 * round);
    assert_int_equal(r->nodes->len, 8);
    assert_string_equal(r->machine, "ring-8");
    assert_int_equal(r->comm_bytes, 16 * 1000);
    /* every link carries the same bytes: the first one is named */
    assert_string_equal(r->busiest_link, "node0->node1");
    assert_int_equal(r->busiest_link_bytes, 2000);
    assert_true(metric(r, "hops") == 16);
    double el = 2 * round * 1e-12;
    assert_true(fabs(metric(r, "hop_time_mean") - el / 16) < 1e-15);
    double util = 16 * ser * 1e-12 / (el * 8);
    assert_true(fabs(metric(r, "link_utilisation_mean") - util) < 1e-12);
    sim_result_free(r);
}

static void test_two_nodes(void **state)
{
    (void)state;
    GError *err = NULL;
    SimResult *r = run_ring("workload: {type: tokenring, nodes: 2, token: 0 B,"
                            " compute: 1 us, link: {latency: 1 us}}\n",
                            1, &err);
    assert_non_null(r);
    assert_int_equal(r->elapsed, 2 * (SIM_US + SIM_US));
    assert_int_equal(r->comm_messages, 2);
    assert_true(metric(r, "link_utilisation_mean") == 0);
    sim_result_free(r);
}

/* run.until 0: only node 0's first arrival runs; nothing is sent, so
 * every rate is 0 rather than a division by a zero elapsed time. */
static void test_until_zero(void **state)
{
    (void)state;
    GError *err = NULL;
    SimResult *r = run_ring("workload: {type: tokenring, nodes: 3}\n"
                            "run: {until: 0 us}\n",
                            1, &err);
    assert_non_null(r);
    assert_int_equal(r->elapsed, 0);
    assert_int_equal(r->frame_times->len, 0);
    assert_int_equal(r->comm_messages, 0);
    assert_null(r->busiest_link);
    assert_true(metric(r, "hops") == 0);
    assert_true(metric(r, "hop_time_mean") == 0);
    assert_true(metric(r, "link_utilisation_mean") == 0);
    sim_result_free(r);
}

static void test_latency_overflow(void **state)
{
    (void)state;
    GError *err = NULL;
    SimResult *r = run_ring("workload: {type: tokenring, nodes: 2,\n"
                            "  link: {latency: 18446744073709 us}}\n",
                            1, &err);
    assert_null(r);
    assert_non_null(err);
    /* send() saturates serialisation + latency at SIM_TIME_MAX; the
     * engine refuses it at the first send (after 20 us of compute) */
    assert_string_equal(err->message,
                        "simulated time overflow: 20000000 ps + "
                        "18446744073709551615 ps exceeds the 64-bit clock");
    g_error_free(err);
}

static void test_machine_refused(void **state)
{
    (void)state;
    GError *err = NULL;
    SimResult *r = run_ring("machine: {model: ipsc2}\n"
                            "workload: {type: tokenring}\n",
                            1, &err);
    assert_null(r);
    assert_string_equal(err->message,
                        "ring.yaml:1:10: found a machine: section, expected "
                        "none: workload tokenring does not read it with "
                        "these settings ('pgsim help run')");
    g_error_free(err);
}

/* jitter j: node i's k-th compute is compute x (1 + j (2u - 1)), u the
 * k-th draw of node i's own stream (entity i of an engine of the same
 * seed), rounded to the picosecond; each node computes once a round. */
static void test_jitter_draws(void **state)
{
    (void)state;
    GError *err = NULL;
    SimResult *r = run_ring("workload: {type: tokenring, nodes: 4, "
                            "compute: 10 us, jitter: 0.25}\n", 3, &err);
    assert_non_null(r);
    SimEngine *eng = sim_engine_new(1);
    for (int i = 0; i < 4; i++) {
        char *name = g_strdup_printf("node%d", i);
        sim_entity_add(eng, name);
        g_free(name);
    }
    gboolean varied = FALSE;
    for (uint32_t i = 0; i < 4; i++) {
        SimTime want = 0;
        for (int k = 0; k < 3; k++) {
            double u = sim_rng_uniform(sim_entity_rng(eng, i));
            SimTime c = (SimTime)llround(10e6 * (1 + 0.25 * (2 * u - 1)));
            assert_true(c >= 7500000 && c <= 12500000);
            want += c;
        }
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        assert_int_equal(sim_busy_phase(&n->busy, 0), want);
        varied |= want != 30 * SIM_US;
    }
    assert_true(varied);
    sim_engine_free(eng);
    sim_result_free(r);
}

static void test_mem_bytes(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string("{nodes: 3}", "w.yaml", &err);
    void *p = wl_tokenring_ops.parse(root, &err);
    GString *what = g_string_new("");
    assert_true(wl_tokenring_ops.mem_bytes(p, what) ==
                3 * (sizeof(SimNodeResult) + sizeof(SimLinkStats) + 256.0));
    assert_string_equal(what->str, "3 nodes");
    g_string_free(what, TRUE);
    wl_tokenring_ops.free_params(p);
    cfg_free(root);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_two_nodes),
        cmocka_unit_test(test_until_zero),
        cmocka_unit_test(test_latency_overflow),
        cmocka_unit_test(test_machine_refused),
        cmocka_unit_test(test_mem_bytes),
        cmocka_unit_test(test_jitter_draws),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
