/* test_tokenring.c — the quickstart workload against its closed form:
 * without jitter a round takes N * (compute + bytes/bandwidth + latency);
 * busy time, messages and bytes add up; a jitter-free compute is exact to
 * the picosecond; run.until stops it early. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/tokenring/tokenring_workload.h"
#include "tests/support.h"

static const char *ring =
    "workload: {type: tokenring, nodes: 5, token: 1000 B, compute: 10 us,\n"
    "           jitter: 0, link: {latency: 2 us, bandwidth: 100 MB/s}}\n"
    "run: {frames: 3}\n";

static SimResult *run_ring(const char *text, int frames, GError **err)
{
    CfgNode *root = cfg_load_string(text, "ring.yaml", err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = frames};
    SimResult *r = support_run_tree(root, &o, err);
    assert_non_null(r);
    return r;
}

static void test_closed_form(void **state)
{
    (void)state;
    GError *e = NULL;
    SimResult *r = run_ring(ring, 3, &e);
    /* 1000 B at 100 MB/s = 10 us; hop = 10 + 10 + 2 us; round = 5 hops */
    SimTime round = 5 * 22 * SIM_US;
    assert_int_equal(r->frame_times->len, 3);
    for (guint i = 0; i < 3; i++)
        assert_int_equal(g_array_index(r->frame_times, SimTime, i), round);
    assert_int_equal(r->elapsed, 3 * round);
    assert_int_equal(r->comm_messages, 15);
    assert_int_equal(r->comm_bytes, 15000);
    assert_string_equal(r->busiest_link, "node0->node1");
    assert_int_equal(r->nodes->len, 5);
    const SimNodeResult *n = g_ptr_array_index(r->nodes, 4);
    assert_int_equal(n->busy.total, 3 * 20 * SIM_US);
    assert_true(fabs(sim_result_node_util(r, n) - 60.0 / 330) < 1e-12);
    assert_int_equal(sim_busy_phase(&n->busy, 0), 3 * 10 * SIM_US);
    assert_string_equal(g_ptr_array_index(r->phases, 1), "send");
    assert_string_equal(r->machine, "ring-5");
    double hops = 0;
    assert_true(sim_result_get_metric(r, "hops", &hops));
    assert_true(hops == 15);
    sim_result_free(r);
}

/* jitter 0.5: each compute is drawn in [5, 15] us around 10 us, so a
 * node's 3 computes sum to 15..45 us, and they are not all 10 us. */
static void test_jitter_bounds(void **state)
{
    (void)state;
    GError *e = NULL;
    gchar **parts = g_strsplit(ring, "jitter: 0", 2);
    char *t = g_strjoinv("jitter: 0.5", parts);
    g_strfreev(parts);
    SimResult *r = run_ring(t, 3, &e);
    gboolean varied = FALSE;
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        SimTime c = sim_busy_phase(&n->busy, 0);
        assert_true(c >= 15 * SIM_US && c <= 45 * SIM_US);
        varied |= c != 30 * SIM_US;
    }
    assert_true(varied);
    sim_result_free(r);
    g_free(t);
}

/* Without jitter a compute is the configured time to the picosecond, even
 * where a double cannot hold it: 2^53 + 1 ps (about 2.5 hours) would round
 * to 2^53 through the jitter formula's llround((double)compute * f). */
static void test_exact_compute(void **state)
{
    (void)state;
    GError *e = NULL;
    SimResult *r = run_ring(
        "workload: {type: tokenring, nodes: 2, token: 1000 B,\n"
        "  compute: 9007199254740993 ps, jitter: 0,\n"
        "  link: {latency: 2 us, bandwidth: 100 MB/s}}\nrun: {frames: 1}\n",
        1, &e);
    const SimTime c = ((SimTime)1 << 53) + 1;
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        assert_int_equal(sim_busy_phase(&n->busy, 0), c);
    }
    assert_int_equal(g_array_index(r->frame_times, SimTime, 0),
                     2 * (c + 12 * SIM_US));
    sim_result_free(r);
}

static void test_until(void **state)
{
    (void)state;
    GError *e = NULL;
    /* stop after 1.5 rounds: one frame recorded */
    char *t2 = g_strdup("workload: {type: tokenring, nodes: 5, token: 1000 "
                        "B, compute: 10 us, jitter: 0,\n  link: {latency: 2 "
                        "us, bandwidth: 100 MB/s}}\nrun: {until: 165 us}\n");
    SimResult *r = run_ring(t2, 3, &e);
    assert_int_equal(r->frame_times->len, 1);
    assert_true(r->elapsed <= 165 * SIM_US);
    sim_result_free(r);
    g_free(t2);
}

static void test_parse_errors(void **state)
{
    (void)state;
    GError *e = NULL;
    CfgNode *root = cfg_load_string("{nodes: 1}", "w.yaml", &e);
    assert_null(wl_tokenring_ops.parse(root, &e));
    assert_string_equal(e->message, "w.yaml:1:9: found '1', expected a count "
                                    "in [2, 1000000]");
    g_clear_error(&e);
    cfg_free(root);
    root = cfg_load_string("{link: {bandwidth: 0 B/s}}", "w.yaml", &e);
    assert_null(wl_tokenring_ops.parse(root, &e));
    assert_non_null(strstr(e->message, "w.yaml:1:20: found a zero "
                                       "bandwidth"));
    g_clear_error(&e);
    cfg_free(root);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_form),
        cmocka_unit_test(test_jitter_bounds),
        cmocka_unit_test(test_exact_compute),
        cmocka_unit_test(test_until),
        cmocka_unit_test(test_parse_errors),
    };
    return cmocka_run_group_tests_name("tokenring", tests, NULL, NULL);
}
