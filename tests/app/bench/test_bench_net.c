/* test_bench_net.c — `pgsim bench net` without the clock: every fidelity
 * runs every pattern on every shipped machine (16-node partitions), every
 * message is delivered, contention-free traffic gives the same time at
 * every fidelity, and bad requests are refused with the reason.
 * (Nothing here looks at wall time.)
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/app/bench/bench_net.h"

static const char *const machines[] = {"ipsc2", "pixel-planes-5", "cm200",
                                       "cm5",   "cluster-ib",     NULL};

static void run_pattern(const char *machine, NetTraffic t)
{
    BenchNetSpec s = {.machine = machine,
                      .nodes = 16,
                      .pattern = t,
                      .bytes = 2000,
                      .seed = 3};
    GError *err = NULL;
    BenchNet *b = bench_net_new(&s, &err);
    if (!b)
        fail_msg("%s %s: %s", machine, net_traffic_name(t), err->message);
    assert_int_equal(bench_net_nodes(b), 16);
    SimTime end[3];
    for (int f = NET_ANALYTIC; f <= NET_PACKET; f++) {
        BenchNetRun r = {0};
        if (!bench_net_run(b, (NetFidelity)f, &r, &err))
            fail_msg("%s %s %s: %s", machine, net_traffic_name(t),
                     net_fidelity_name(f), err->message);
        assert_int_equal(r.messages, net_traffic_messages(t, 16));
        assert_int_equal(r.delivered, r.messages);
        assert_true(r.end > 0);
        end[f] = r.end;
    }
    /* the hypercube's circuits: shift and xor never share a link, nor
     * does pairwise (one dimension per step) */
    if (strcmp(machine, "ipsc2") == 0 &&
        (t == NET_TRAFFIC_XOR || t == NET_TRAFFIC_PAIRWISE ||
         t == NET_TRAFFIC_SHIFT)) {
        assert_int_equal(end[NET_FLOW], end[NET_ANALYTIC]);
        assert_int_equal(end[NET_PACKET], end[NET_ANALYTIC]);
    }
    /* contention can only slow a message down */
    assert_true(end[NET_FLOW] >= end[NET_ANALYTIC]);
    bench_net_free(b);
}

static void test_every_machine_pattern_fidelity(void **state)
{
    (void)state;
    for (const char *const *m = machines; *m; m++)
        for (int t = NET_TRAFFIC_ALLTOALL; t <= NET_TRAFFIC_HOTSPOT; t++)
            run_pattern(*m, (NetTraffic)t);
}

/* Same spec, same simulated times (the bench is deterministic). */
static void test_deterministic(void **state)
{
    (void)state;
    BenchNetSpec s = {.machine = "ipsc2",
                      .nodes = 64,
                      .pattern = NET_TRAFFIC_HOTSPOT,
                      .bytes = 10240,
                      .seed = 9};
    SimTime end[2];
    for (int i = 0; i < 2; i++) {
        BenchNet *b = bench_net_new(&s, NULL);
        assert_non_null(b);
        BenchNetRun r;
        assert_true(bench_net_run(b, NET_FLOW, &r, NULL));
        end[i] = r.end;
        bench_net_free(b);
    }
    assert_int_equal(end[0], end[1]);
}

/* Overrides reach the network: --startup 0 --per-hop 0 --bandwidth 1 on
 * a lone pairwise step of 2 nodes: 2 x 1000 B / 2 = 1000 B at 1 MB/s. */
static void test_overrides(void **state)
{
    (void)state;
    const char *const sets[] = {"machine.network.startup=0 us",
                                "machine.network.startup_long=0 us",
                                "machine.network.per_hop=0 us",
                                "machine.network.bandwidth=1 MB/s", NULL};
    BenchNetSpec s = {.machine = "ipsc2",
                      .nodes = 2,
                      .pattern = NET_TRAFFIC_PAIRWISE,
                      .bytes = 1000,
                      .sets = sets};
    GError *err = NULL;
    BenchNet *b = bench_net_new(&s, &err);
    if (!b)
        fail_msg("%s", err->message);
    assert_non_null(strstr(bench_net_describe(b), "1 MB/s"));
    BenchNetRun r;
    assert_true(bench_net_run(b, NET_PACKET, &r, NULL));
    assert_int_equal(r.end, 1000 * SIM_US);
    bench_net_free(b);
}

static void expect_refused(const BenchNetSpec *s, const char *needle)
{
    GError *err = NULL;
    assert_null(bench_net_new(s, &err));
    assert_non_null(err);
    if (!strstr(err->message, needle))
        fail_msg("got '%s', want '%s'", err->message, needle);
    g_error_free(err);
}

static void test_refused(void **state)
{
    (void)state;
    BenchNetSpec s = {
        .machine = "ipsc2", .nodes = 12, .pattern = NET_TRAFFIC_RANDOM};
    expect_refused(&s, "12 processors on a hypercube");
    s.machine = "pixel-planes-5"; /* 34 stations */
    s.nodes = 0;
    s.pattern = NET_TRAFFIC_XOR;
    expect_refused(&s, "pattern xor on 34 nodes, expected a power of two");
    s.machine = "ipsc2"; /* a 17-cube: beyond 32-bit message indices */
    s.nodes = 131072;
    s.pattern = NET_TRAFFIC_RANDOM;
    expect_refused(&s, "from 2 to 65536 nodes");
    s.nodes = 0;
    s.machine = "nonesuch";
    expect_refused(&s, "no model 'nonesuch'");
    const char *const bad[] = {"network.startup=1 us", NULL};
    s.machine = "ipsc2";
    s.sets = bad;
    expect_refused(&s, "expected --set machine.KEY=VALUE");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_machine_pattern_fidelity),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_overrides),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests_name("bench_net", tests, NULL, NULL);
}
