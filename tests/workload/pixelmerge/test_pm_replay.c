/* test_pm_replay.c — timing replay of merge steps on an analytic
 * hypercube: exact times on hand-checked cases. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pixelmerge/pm_replay.h"

enum { W = 8, H = 4 };

static const WlPmFormat fmt = {8, 5, 2};
static const WlPmMergeCosts costs = {.pack = 1 * SIM_US,
                                     .scatter = 2 * SIM_US,
                                     .compare = 3 * SIM_US,
                                     .gather = 5 * SIM_US,
                                     .sum_elem = 7 * SIM_US,
                                     .sort_elem = 11 * SIM_US,
                                     .count_bytes = 4};

/* Processor p covers row p's first p + 1 pixels with depth p. */
static void make_local(WlPmWpa **local, guint n)
{
    for (guint p = 0; p < n; p++) {
        local[p] = wl_pm_wpa_new(W, H);
        for (guint y = 0; y < H; y++)
            for (guint x = 0; x <= p; x++) {
                WlPmPixel px = {(uint16_t)x, (uint16_t)y, p, p, p};
                wl_pm_wpa_push(local[p], &px);
            }
        wl_pm_wpa_finish(local[p]);
    }
}

typedef struct {
    SimEngine *eng;
    NetTopo *topo;
    NetNet *net;
} Rig;

static void rig_init(Rig *r, unsigned dims)
{
    NetParams np = {.bandwidth = 1e6,
                    .channels = 1,
                    .startup = 100 * SIM_US,
                    .per_hop = 10 * SIM_US,
                    .switching = NET_SW_CIRCUIT};
    r->eng = sim_engine_new(1);
    r->topo = net_hypercube_new(dims);
    r->net = net_new(r->eng, r->topo, &np, NET_ANALYTIC);
}

static void rig_clear(Rig *r)
{
    net_free(r->net);
    net_topo_free(r->topo);
    sim_engine_free(r->eng);
}

/* AAPC with strips on 2 processors: one exchange, then z-buffering. */
static void test_aapc_two(void **state)
{
    (void)state;
    Rig rig;
    rig_init(&rig, 1);
    WlPmWpa *local[2];
    make_local(local, 2);
    WlPmPartition *part = wl_pm_partition_new(WL_PM_BAL_STRIPS, 2, NULL, H);
    WlPmMerge *m = wl_pm_merge_run(WL_PM_AAPC, local, 2, part, &fmt);
    SimBusy busy[2];
    sim_busy_init(&busy[0]);
    sim_busy_init(&busy[1]);
    SimTime ready[2] = {0, 50 * SIM_US};
    WlPmReplayOut out;
    assert_true(wl_pm_replay(rig.net, m, WL_PM_BAL_STRIPS, H, &costs, ready,
                             busy, 0, &out, NULL));
    /* p0 owns rows 0-1, p1 rows 2-3.  p1 sends 2 rows x 2 pixels:
     * 4*8 + 2*2 = 36 B -> 100 + 10 + 36 us, sent at 50 us -> 196 us.
     * p0 then scatters its 2 own pixels, compares 4: 4 + 12 us = 212. */
    assert_int_equal(out.done[0], 212 * SIM_US);
    /* p0 sends 2 rows x 1 pixel: 2*8 + 4 = 20 B, arriving at 130 us;
     * p1 then scatters 4 pixels (8 us), compares 2 (6 us) -> 144 us. */
    assert_int_equal(out.done[1], 144 * SIM_US);
    assert_int_equal(out.end, 212 * SIM_US);
    assert_int_equal(sim_busy_phase(&busy[0], 0), 16 * SIM_US);
    wl_pm_replay_out_clear(&out);
    sim_busy_clear(&busy[0]);
    sim_busy_clear(&busy[1]);
    wl_pm_merge_free(m);
    wl_pm_partition_free(part);
    wl_pm_wpa_free(local[0]);
    wl_pm_wpa_free(local[1]);
    rig_clear(&rig);
}

/* RS adds the global sum: one exchange of H counts (16 B), H additions,
 * then d * log2 H = 2 sort units; every later step waits for it. */
static void test_rs_global_sum(void **state)
{
    (void)state;
    Rig rig;
    rig_init(&rig, 1);
    WlPmWpa *local[2];
    make_local(local, 2);
    uint64_t counts[H] = {0};
    wl_pm_wpa_add_row_counts(local[0], counts);
    wl_pm_wpa_add_row_counts(local[1], counts);
    WlPmPartition *rs = wl_pm_partition_new(WL_PM_BAL_RS, 2, counts, H);
    WlPmMerge *m = wl_pm_merge_run(WL_PM_PAIR, local, 2, rs, &fmt);
    SimBusy busy[2];
    sim_busy_init(&busy[0]);
    sim_busy_init(&busy[1]);
    SimTime ready[2] = {0, 0};
    WlPmReplayOut out;
    assert_true(wl_pm_replay(rig.net, m, WL_PM_BAL_RS, H, &costs, ready, busy,
                             0, &out, NULL));
    /* Sum: 100 + 10 + 16 us = 126, + 4 x 7 = 154, + 2 x 11 = 176 us.
     * Rows split 2 | 2: p0 sends 2 rows x 1 px = 20 B (130 us) and p1
     * 2 x 2 = 36 B (146 us).  p0: 176 + 146 = 322, then scatter 2 (4),
     * compare 4 (12), gather 4 (20) = 358 us. */
    assert_int_equal(out.done[0], 358 * SIM_US);
    wl_pm_replay_out_clear(&out);
    sim_busy_clear(&busy[0]);
    sim_busy_clear(&busy[1]);
    wl_pm_merge_free(m);
    wl_pm_partition_free(rs);
    wl_pm_wpa_free(local[0]);
    wl_pm_wpa_free(local[1]);
    rig_clear(&rig);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_aapc_two),
        cmocka_unit_test(test_rs_global_sum),
    };
    return cmocka_run_group_tests_name("pm_replay", tests, NULL, NULL);
}
