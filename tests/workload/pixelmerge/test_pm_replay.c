/* test_pm_replay.c — timing replay of merge steps on an analytic
 * hypercube: exact times on hand-checked cases (packing, a message that
 * arrives before its receiver sends, the global sum and partitioning of
 * RS and HBP on 2 and 4 processors). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pixelmerge/pm_replay.h"

enum { W = 8, H = 4 };

static const WlPmFormat fmt = {8, 5, 2, 0, 0};
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
    WlPmReplayRig r = {.net = rig.net,
                       .costs = &costs,
                       .ready = ready,
                       .busy = busy,
                       .bal = WL_PM_BAL_STRIPS,
                       .height = H};
    assert_true(wl_pm_replay(&r, m, &out, NULL));
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
    WlPmReplayRig r = {.net = rig.net,
                       .costs = &costs,
                       .ready = ready,
                       .busy = busy,
                       .bal = WL_PM_BAL_RS,
                       .height = H};
    assert_true(wl_pm_replay(&r, m, &out, NULL));
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

/* Runs the replay of m with balancing `bal` from ready[] on a fresh
 * analytic hypercube of `dims`; fills done[] and busy[] (merge phase). */
static void replay(const WlPmMerge *m, WlPmBalance bal, unsigned dims,
                   const WlPmMergeCosts *c, const SimTime *ready, SimTime *done,
                   SimTime *busy)
{
    Rig rig;
    rig_init(&rig, dims);
    guint n = m->n_procs;
    SimBusy b[4];
    WlPmReplayOut out;
    for (guint p = 0; p < n; p++)
        sim_busy_init(&b[p]);
    GError *err = NULL;
    WlPmReplayRig r = {.net = rig.net,
                       .costs = c,
                       .ready = ready,
                       .busy = b,
                       .bal = bal,
                       .height = H};
    if (!wl_pm_replay(&r, m, &out, &err))
        fail_msg("%s", err->message);
    SimTime end = 0;
    for (guint p = 0; p < n; p++) {
        done[p] = out.done[p];
        busy[p] = sim_busy_phase(&b[p], 0);
        end = MAX(end, done[p]);
        sim_busy_clear(&b[p]);
    }
    assert_true(out.end == end);
    wl_pm_replay_out_clear(&out);
    rig_clear(&rig);
}

/* Owners 0 1 0 1 (not banded), PAIR, no global sum (strips).  p0 packs
 * its 2 pixels of rows 1, 3 (2 us) and sends 2 x 8 + 2 x 2 = 20 B (130
 * us); p1 packs 4 (4 us) and sends 36 B (146 us).  From ready 0: p1's
 * message reaches p0 at 150 us; p0 scatters 2 (4), compares 4 (12),
 * gathers 4 (20): 186 us; p0's reaches p1 at 132 us: scatter 4 (8),
 * compare 2 (6), gather 4 (20): 166 us.  Busy 2 + 36 and 4 + 34.  With
 * p0 ready at 200 us, p1's message is there before p0 sends (202 us):
 * p0 goes straight on, 238 us; p1 waits for 202 + 130: 366 us. */
static void test_pack_and_early_arrival(void **state)
{
    (void)state;
    static guint owner[H] = {0, 1, 0, 1};
    WlPmPartition part = {2, H, owner, FALSE};
    WlPmWpa *local[2];
    make_local(local, 2);
    WlPmMerge *m = wl_pm_merge_run(WL_PM_PAIR, local, 2, &part, &fmt);
    SimTime done[2], busy[2];
    const SimTime at0[2] = {0, 0}, late[2] = {200 * SIM_US, 0};
    replay(m, WL_PM_BAL_STRIPS, 1, &costs, at0, done, busy);
    assert_true(done[0] == 186 * SIM_US && done[1] == 166 * SIM_US);
    assert_true(busy[0] == 38 * SIM_US && busy[1] == 38 * SIM_US);
    replay(m, WL_PM_BAL_STRIPS, 1, &costs, late, done, busy);
    assert_true(done[0] == 238 * SIM_US && done[1] == 366 * SIM_US);
    wl_pm_merge_free(m);
    wl_pm_wpa_free(local[0]);
    wl_pm_wpa_free(local[1]);
}

/* The global sum and partitioning shift the same merge by a fixed time.
 * Each exchange of H = 4 counts (16 B): 100 + 10 + 16 us, then 4 x 7 us
 * of additions: 154 us a stage.  RS: d log2 H = 2d sort steps (11 us);
 * HBP: H log2 H = 8 sort steps and H P assign steps (13 us).  P = 2:
 * RS 154 + 22 = 176, HBP 154 + 88 + 104 = 346 us; P = 4: RS 308 + 44 =
 * 352, HBP 308 + 88 + 208 = 604 us.  The busy time grows by all but the
 * messages. */
static void test_balance_prefix(void **state)
{
    (void)state;
    WlPmMergeCosts c = costs;
    c.assign_step = 13 * SIM_US;
    const SimTime ready[4] = {0, 0, 0, 0};
    for (unsigned dims = 1; dims <= 2; dims++) {
        guint n = 1u << dims;
        WlPmWpa *local[4];
        make_local(local, n);
        WlPmPartition *strips =
            wl_pm_partition_new(WL_PM_BAL_STRIPS, n, NULL, H);
        WlPmMerge *m = wl_pm_merge_run(WL_PM_AAPC, local, n, strips, &fmt);
        SimTime d0[4], b0[4], d1[4], b1[4], d2[4], b2[4];
        replay(m, WL_PM_BAL_STRIPS, dims, &c, ready, d0, b0);
        replay(m, WL_PM_BAL_RS, dims, &c, ready, d1, b1);
        replay(m, WL_PM_BAL_HBP, dims, &c, ready, d2, b2);
        SimTime rs = dims == 1 ? 176 : 352, hbp = dims == 1 ? 346 : 604;
        SimTime msgs = dims * 126;
        for (guint p = 0; p < n; p++) {
            assert_true(d1[p] - d0[p] == rs * SIM_US);
            assert_true(d2[p] - d0[p] == hbp * SIM_US);
            assert_true(b1[p] - b0[p] == (rs - msgs) * SIM_US);
            assert_true(b2[p] - b0[p] == (hbp - msgs) * SIM_US);
        }
        wl_pm_merge_free(m);
        wl_pm_partition_free(strips);
        for (guint p = 0; p < n; p++)
            wl_pm_wpa_free(local[p]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_aapc_two),
        cmocka_unit_test(test_rs_global_sum),
        cmocka_unit_test(test_pack_and_early_arrival),
        cmocka_unit_test(test_balance_prefix),
    };
    return cmocka_run_group_tests_name("pm_replay", tests, NULL, NULL);
}
