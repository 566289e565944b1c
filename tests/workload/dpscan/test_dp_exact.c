/* test_dp_exact.c — the data-parallel cost formulas (dp_cost.h) and the
 * array layer's counts and charges (dp_array.h) against values worked
 * out by hand from small machine constants (issue 21: every result
 * checked exactly, boundaries included: an empty array, an exact
 * multiple of the processors, one word, one message, zero guards).
 *
 * The machine: 8 processors, every constant a different number of
 * picoseconds so that a term counted with the wrong constant shows.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/workload/dpscan/dp_array.h"
#include "sim/workload/dpscan/dp_cost.h"
#include "sim/workload/dpscan/dp_render.h"

static WlDpMachine simd(void)
{
    WlDpMachine m = {.arch = WL_DP_SIMD,
                     .procs = 8,
                     .op = 7,
                     .step = 1000,
                     .scan_slice = 11,
                     .send_setup = 13,
                     .send_slice = 17,
                     .send_vp = 19,
                     .send_msg = 23,
                     .news_slice = 29};
    return m;
}

static WlDpMachine spmd(void)
{
    WlDpMachine m = simd();
    m.arch = WL_DP_SPMD;
    m.net_latency = 31;
    m.msg_overhead = 37;
    m.msg_bytes = 4;
    m.arity = 4;
    m.levels = 2;
    m.level_bw[0] = 1e9;
    m.level_bw[1] = 5e8;
    return m;
}

static void test_vp_ratio(void **state)
{
    (void)state;
    WlDpMachine m = simd();
    const uint64_t n[] = {0, 1, 7, 8, 9, 16, 17, 33};
    const uint64_t v[] = {0, 1, 1, 1, 2, 2, 3, 5};
    const uint64_t v2[] = {0, 1, 1, 1, 2, 2, 4, 8};
    for (guint i = 0; i < G_N_ELEMENTS(n); i++) {
        m.vp_pow2 = FALSE;
        assert_int_equal(wl_dp_vp_ratio(&m, n[i]), v[i]);
        m.vp_pow2 = TRUE;
        assert_int_equal(wl_dp_vp_ratio(&m, n[i]), v2[i]);
    }
}

static void test_step_scan_news(void **state)
{
    (void)state;
    WlDpMachine m = simd();
    WlDpCoef k = {0};
    /* n = 17: v = 3 */
    assert_int_equal(wl_dp_step_cost(&m, 17, 5, &k), 1000 + 7 * 15);
    assert_true(k.steps == 1 && k.op_slices == 15);
    assert_int_equal(wl_dp_scan_cost(&m, 17, &k), 1000 + 11 * 3);
    assert_true(k.steps == 2 && k.scan_slices == 3);
    assert_int_equal(wl_dp_news_cost(&m, 16, &k), 1000 + 29 * 2);
    assert_true(k.steps == 3 && k.news_slices == 2);
    assert_true(k.op_slices == 15 && k.scan_slices == 3);
    assert_true(k.sends == 0 && k.slices == 0 && k.vp_slices == 0 &&
                k.msg_slices == 0);
    /* no coefficients asked for: the same times */
    assert_int_equal(wl_dp_step_cost(&m, 8, 1, NULL), 1007);
    assert_int_equal(wl_dp_scan_cost(&m, 0, NULL), 1000);
}

/* SIMD router: words x (step + send_setup + vps send_vp
 * + ceil(active / procs) send_msg + load send_slice). */
static void test_send_simd(void **state)
{
    (void)state;
    WlDpMachine m = simd();
    WlDpCoef k = {0};
    /* n = 17 (v 3), 9 messages (2 a processor on average), load 3 */
    SimTime one = 1000 + 13 + 19 * 3 + 23 * 2 + 17 * 3;
    assert_int_equal(wl_dp_send_cost(&m, 2, 17, 9, 3, &k), 2 * one);
    assert_true(k.steps == 2 && k.sends == 2 && k.slices == 6 &&
                k.vp_slices == 6 && k.msg_slices == 4);
    /* 8 messages: exactly one a processor */
    WlDpCoef k1 = {0};
    assert_int_equal(wl_dp_send_cost(&m, 1, 8, 8, 1, &k1),
                     1000 + 13 + 19 + 23 + 17);
    assert_true(k1.msg_slices == 1 && k1.vp_slices == 1 && k1.slices == 1);
    /* nothing sent: no time, nothing counted */
    WlDpCoef z = {0};
    assert_int_equal(wl_dp_send_cost(&m, 1, 8, 8, 0, &z), 0);
    assert_int_equal(wl_dp_send_cost(&m, 0, 8, 8, 1, &z), 0);
    assert_int_equal(wl_dp_send_cost(&m, 1, 8, 0, 1, &z), 0);
    assert_true(z.steps == 0 && z.sends == 0 && z.msg_slices == 0);
}

/* Fat tree: the fraction 1 - a^l / p of messages leaving a level-l
 * subtree, over that level's bandwidth; the worst level bounds. */
static void test_fattree(void **state)
{
    (void)state;
    assert_true(wl_dp_fattree_escape(4, 8, 0) == 0.875);
    assert_true(wl_dp_fattree_escape(4, 8, 1) == 0.5);
    assert_true(wl_dp_fattree_escape(4, 8, 2) == 0);
    assert_true(wl_dp_fattree_escape(2, 8, 3) == 0);
    assert_true(wl_dp_fattree_escape(2, 8, 2) == 0.5);
    assert_true(wl_dp_fattree_escape(2, 1, 0) == 0);
    WlDpMachine m = spmd();
    /* 1000 messages of 4 B: level 0 0.875 x 4000 B / 1 GB/s = 3.5 us,
     * level 1 (and up, at level 1's bandwidth) 0.5 x 4000 / 0.5 GB/s = 4 us */
    SimTime w = wl_dp_fattree_wire(&m, 1000);
    assert_true(w >= 4000000 && w <= 4000001);
    /* level 0 the slower one */
    m.level_bw[1] = 1e10;
    w = wl_dp_fattree_wire(&m, 1000);
    assert_true(w >= 3500000 && w <= 3500001);
    /* one level given: it holds for every level */
    m.levels = 1;
    w = wl_dp_fattree_wire(&m, 1000);
    assert_true(w >= 3500000 && w <= 3500001);
    assert_int_equal(wl_dp_fattree_wire(&m, 0), 0);
}

/* SPMD: words x (step + net_latency + max(load x msg_overhead, wire)). */
static void test_send_spmd(void **state)
{
    (void)state;
    WlDpMachine m = spmd();
    WlDpCoef k = {0};
    SimTime wire = wl_dp_fattree_wire(&m, 1000);
    assert_int_equal(wl_dp_send_cost(&m, 2, 16, 9, 1000, &k),
                     2 * (1000 + 31 + wire));
    assert_true(k.steps == 2 && k.sends == 2 && k.slices == 2000 &&
                k.vp_slices == 4 && k.msg_slices == 4);
    m.msg_overhead = 5000; /* software slower than the wire */
    assert_int_equal(wl_dp_send_cost(&m, 1, 16, 9, 1000, NULL),
                     1000 + 31 + 5000000);
    /* the wire measured elsewhere; one word, one message */
    WlDpCoef kw = {0};
    assert_int_equal(wl_dp_send_cost_wired(&m, 1, 1, 1, 1, 123456, &kw),
                     1000 + 31 + 123456);
    assert_true(kw.steps == 1 && kw.slices == 1 && kw.msg_slices == 1 &&
                kw.vp_slices == 1);
    assert_int_equal(wl_dp_send_cost_wired(&m, 3, 1, 1, 2, 7, NULL),
                     3 * (1000 + 31 + 10000));
    WlDpCoef z = {0};
    assert_int_equal(wl_dp_send_cost_wired(&m, 1, 1, 1, 0, 9, &z), 0);
    assert_int_equal(wl_dp_send_cost_wired(&m, 0, 1, 1, 1, 9, &z), 0);
    assert_int_equal(wl_dp_send_cost_wired(&m, 1, 1, 0, 1, 9, &z), 0);
    assert_true(z.steps == 0 && z.slices == 0);
}

static void owner_is(const WlDpLayout *l, uint32_t x, uint32_t y, uint64_t p)
{
    if (wl_dp_layout_owner(l, x, y) != p)
        fail_msg("(%u, %u): owner %lu, expected %lu", x, y,
                 (unsigned long)wl_dp_layout_owner(l, x, y), (unsigned long)p);
}

/* Power-of-two processors: a 2^ceil(d/2) x 2^floor(d/2) grid of blocks;
 * otherwise one row of blocks. */
static void test_layout(void **state)
{
    (void)state;
    WlDpLayout *l = wl_dp_layout_new(8, 100, 50);
    assert_true(l->px == 4 && l->py == 2 && l->bw == 25 && l->bh == 25);
    owner_is(l, 0, 0, 0);
    owner_is(l, 24, 24, 0);
    owner_is(l, 25, 24, 1);
    owner_is(l, 25, 25, 5);
    owner_is(l, 99, 49, 7);
    for (guint p = 0; p < 8; p++)
        assert_int_equal(l->count[p], 0);
    wl_dp_layout_free(l);
    l = wl_dp_layout_new(6, 100, 50);
    assert_true(l->px == 6 && l->py == 1 && l->bw == 17 && l->bh == 50);
    owner_is(l, 16, 49, 0);
    owner_is(l, 17, 0, 1);
    owner_is(l, 99, 49, 5);
    wl_dp_layout_free(l);
    /* blocks of one pixel */
    l = wl_dp_layout_new(4, 2, 2);
    assert_true(l->px == 2 && l->py == 2 && l->bw == 1 && l->bh == 1);
    owner_is(l, 1, 0, 1);
    owner_is(l, 0, 1, 2);
    owner_is(l, 1, 1, 3);
    wl_dp_layout_free(l);
    l = wl_dp_layout_new(1, 3, 3);
    assert_true(l->px == 1 && l->py == 1 && l->bw == 3 && l->bh == 3);
    owner_is(l, 2, 2, 0);
    wl_dp_layout_free(l);
    l = wl_dp_layout_new(2, 3, 3);
    assert_true(l->px == 2 && l->py == 1 && l->bw == 2 && l->bh == 3);
    wl_dp_layout_free(l);
}

/* Elementwise, scan, reduce and NEWS: counts and each target's charge
 * in the right phase. */
static void test_vm_ops(void **state)
{
    (void)state;
    WlDpMachine ms[2] = {simd(), simd()};
    ms[1].procs = 4;
    WlDpVm *vm = wl_dp_vm_new(ms, 2, 4, 3);
    assert_int_equal(wl_dp_vm_n_targets(vm), 2);
    assert_int_equal(wl_dp_vm_screen_elems(vm), 12);
    wl_dp_ew(vm, WL_DP_PH_PIXEL, 17, 5, 3);
    wl_dp_ew(vm, WL_DP_PH_PIXEL, 0, 0, 3);  /* nothing */
    wl_dp_ew(vm, WL_DP_PH_PIXEL, 17, 5, 0); /* nothing */
    const WlDpVmCounts *c = wl_dp_vm_counts(vm);
    assert_true(c->steps == 1 && c->ew_elems == 51 && c->ew_active == 15);
    /* v = 3 on 8 processors, 5 on 4 */
    const WlDpTarget *t0 = wl_dp_vm_target(vm, 0), *t1 = wl_dp_vm_target(vm, 1);
    assert_int_equal(t0->phase[WL_DP_PH_PIXEL], 1000 + 7 * 9);
    assert_int_equal(t1->phase[WL_DP_PH_PIXEL], 1000 + 7 * 15);
    wl_dp_ew(vm, WL_DP_PH_TRANSFORM, 8, 8, 1);
    assert_true(c->steps == 2 && c->ew_elems == 59 && c->ew_active == 23);
    assert_int_equal(t0->phase[WL_DP_PH_TRANSFORM], 1007);
    uint32_t in[4] = {3, 0, 5, 2}, out[4];
    assert_int_equal(wl_dp_scan_add(vm, WL_DP_PH_SCAN, 9, in, out, 4), 10);
    assert_true(out[0] == 0 && out[1] == 3 && out[2] == 3 && out[3] == 8);
    assert_int_equal(wl_dp_reduce_max(vm, WL_DP_PH_SCAN, 4, in, 4), 5);
    assert_int_equal(wl_dp_reduce_max(vm, WL_DP_PH_SCAN, 0, in, 0), 0);
    /* scans of 9 (v 2), 4 (v 1) and an empty array (costed as 1 element) */
    assert_int_equal(t0->phase[WL_DP_PH_SCAN], 3 * 1000 + 11 * (2 + 1 + 1));
    assert_int_equal(t1->phase[WL_DP_PH_SCAN], 3 * 1000 + 11 * (3 + 1 + 1));
    assert_int_equal(c->steps, 5);
    uint64_t g[12], o[12];
    for (int i = 0; i < 12; i++)
        g[i] = i + 1;
    wl_dp_news(vm, WL_DP_PH_DISPLAY, g, o, 1, 0, 99); /* out[x] = in[x-1] */
    assert_true(o[0] == 99 && o[1] == 1 && o[3] == 3 && o[4] == 99 &&
                o[11] == 11);
    wl_dp_news(vm, WL_DP_PH_DISPLAY, g, o, 0, -1, 77); /* out[y] = in[y+1] */
    assert_true(o[0] == 5 && o[7] == 12 && o[8] == 77 && o[11] == 77);
    wl_dp_news(vm, WL_DP_PH_DISPLAY, g, o, -1, 0, 55);
    assert_true(o[0] == 2 && o[2] == 4 && o[3] == 55 && o[11] == 55);
    wl_dp_news(vm, WL_DP_PH_DISPLAY, g, o, 0, 1, 44);
    assert_true(o[3] == 44 && o[4] == 1 && o[11] == 8);
    assert_true(c->news_moves == 4 && c->steps == 9);
    /* 12 elements: v 2 on 8 processors */
    assert_int_equal(t0->phase[WL_DP_PH_DISPLAY], 4 * (1000 + 29 * 2));
    SimTime sum = 0;
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++)
        sum += t0->phase[ph];
    assert_int_equal(t0->total, sum);
    assert_true(t0->coef.steps == 9 && t0->coef.op_slices == 9 + 1 &&
                t0->coef.scan_slices == 4 && t0->coef.news_slices == 8);
    assert_string_equal(wl_dp_phase_name(WL_DP_PH_TRANSFORM), "transform");
    assert_string_equal(wl_dp_phase_name(WL_DP_PH_DISPLAY), "display");
    wl_dp_vm_free(vm);
}

/* A scan of an empty array is costed as one element: on one processor
 * a VP ratio of 1, not 2 (nor 0). */
static void test_empty_scan_one_proc(void **state)
{
    (void)state;
    WlDpMachine m = simd();
    m.procs = 1;
    WlDpVm *vm = wl_dp_vm_new(&m, 1, 2, 2);
    uint32_t none[1] = {7};
    assert_int_equal(wl_dp_reduce_max(vm, WL_DP_PH_SCAN, 0, none, 0), 0);
    const WlDpCounts *k = &wl_dp_vm_target(vm, 0)->count[WL_DP_PH_SCAN];
    assert_int_equal(wl_dp_vm_target(vm, 0)->phase[WL_DP_PH_SCAN], 1000 + 11);
    assert_true(k->n[WL_DP_C_STEP] == 1 && k->n[WL_DP_C_SCAN_SLICE] == 1);
    assert_int_equal(wl_dp_counts_price(&m, k), 1000 + 11);
    uint32_t out[1] = {9};
    assert_int_equal(wl_dp_scan_add(vm, WL_DP_PH_SCAN, 3, none, out, 1), 7);
    assert_int_equal(out[0], 0);
    assert_int_equal(wl_dp_vm_target(vm, 0)->phase[WL_DP_PH_SCAN],
                     2 * 1000 + 11 + 11 * 3);
    assert_true(k->n[WL_DP_C_STEP] == 2 && k->n[WL_DP_C_SCAN_SLICE] == 4);
    wl_dp_vm_free(vm);
}

/* A send: combining, collisions, the deepest element, and the load
 * (the most messages one processor injects or receives) in the cost. */
static void test_vm_send(void **state)
{
    (void)state;
    WlDpMachine m = simd();
    m.procs = 4;
    WlDpVm *vm = wl_dp_vm_new(&m, 1, 4, 2);
    /* 8 sources (2 a processor) to 8 destinations (2 a processor) */
    uint64_t dst[6] = {0, 0, 0, 5, 6, 7}, val[6] = {4, 9, 2, 1, 8, 3};
    uint64_t dest[8] = {0};
    WlDpSend s = {.phase = WL_DP_PH_ROUTER,
                  .n_src = 8,
                  .n_dst = 8,
                  .lay = WL_DP_LAYOUT_LINEAR,
                  .dst = dst,
                  .val = val,
                  .count = 6,
                  .dest = dest,
                  .words = 2,
                  .comb = WL_DP_COMBINE_MAX};
    assert_int_equal(wl_dp_send(vm, &s), 2);
    assert_true(dest[0] == 9 && dest[5] == 1 && dest[6] == 8 && dest[7] == 3 &&
                dest[1] == 0);
    const WlDpVmCounts *c = wl_dp_vm_counts(vm);
    assert_true(c->max_depth == 3 && c->collisions == 2 && c->messages == 6 &&
                c->words == 12 && c->sends == 2 && c->steps == 2);
    /* processor 0 receives 3 (elements 0, 0, 0): load 3; sources 0..5
     * inject 2, 2, 2; v 2 for n 8; ceil(6 / 4) = 2 messages on average */
    const WlDpTarget *t = wl_dp_vm_target(vm, 0);
    assert_int_equal(t->max_load, 3);
    assert_int_equal(t->phase[WL_DP_PH_ROUTER],
                     2 * (1000 + 13 + 19 * 2 + 23 * 2 + 17 * 3));
    /* the counters are zero again: a send of one message has load 1 */
    s.comb = WL_DP_COMBINE_ADD;
    s.count = 1;
    s.words = 1;
    assert_int_equal(wl_dp_send(vm, &s), 0);
    assert_int_equal(dest[0], 13);
    assert_int_equal(t->phase[WL_DP_PH_ROUTER],
                     2 * (1000 + 13 + 19 * 2 + 23 * 2 + 17 * 3) +
                         (1000 + 13 + 19 * 2 + 23 + 17));
    assert_int_equal(c->max_depth, 3);
    s.comb = WL_DP_COMBINE_OVERWRITE;
    s.count = 3; /* three to element 0: the last one stays */
    assert_int_equal(wl_dp_send(vm, &s), 2);
    assert_int_equal(dest[0], 2);
    /* nothing to send: counted as a step, no time */
    SimTime before = t->total;
    s.count = 0;
    assert_int_equal(wl_dp_send(vm, &s), 0);
    assert_int_equal(t->total, before);
    assert_true(c->sends == 5 && c->messages == 10);
    /* on the screen: element y * width + x; 4 processors as 2 x 2 blocks
     * of 2 x 1 pixels; explicit sources, both from element 0 */
    uint64_t sc[2] = {0, 0}, sd[2] = {1, 2};
    WlDpSend q = {.phase = WL_DP_PH_PIXEL,
                  .n_src = 8,
                  .n_dst = 8,
                  .lay = WL_DP_LAYOUT_SCREEN,
                  .src = sc,
                  .dst = sd,
                  .count = 2,
                  .words = 1};
    assert_int_equal(wl_dp_send(vm, &q), 0);
    /* processor 0 injects both: load 2 */
    assert_int_equal(t->phase[WL_DP_PH_PIXEL],
                     1000 + 13 + 19 * 2 + 23 + 17 * 2);
    wl_dp_vm_free(vm);
}

/* Processors sharing a router node pool their messages. */
static void test_router_procs(void **state)
{
    (void)state;
    WlDpMachine m = simd();
    m.procs = 4;
    m.router_procs = 2;
    WlDpVm *vm = wl_dp_vm_new(&m, 1, 2, 2);
    uint64_t dst[2] = {0, 2}; /* processors 0 and 2: nodes 0 and 1 */
    uint64_t src[2] = {0, 1}; /* processors 0 and 1: both node 0 */
    WlDpSend s = {.phase = WL_DP_PH_ROUTER,
                  .n_src = 4,
                  .n_dst = 4,
                  .lay = WL_DP_LAYOUT_LINEAR,
                  .src = src,
                  .dst = dst,
                  .count = 2,
                  .words = 1};
    wl_dp_send(vm, &s);
    assert_int_equal(wl_dp_vm_target(vm, 0)->max_load, 2);
    wl_dp_vm_free(vm);
}

/* The SPMD send's wire and software totals, by the fat tree or a wire
 * function given the node pairs. */
static guint64 pairs_seen;

static SimTime wire_fn(void *ctx, const WlDpTraffic *t)
{
    (void)ctx;
    pairs_seen = t->n;
    uint64_t sum = 0;
    for (size_t k = 0; k < t->n; k++)
        sum += t->msgs[k] * (1 + t->src[k] + 10 * t->dst[k]);
    return sum;
}

static void test_vm_send_spmd(void **state)
{
    (void)state;
    WlDpMachine m = spmd();
    m.procs = 4;
    WlDpMachine ms[2] = {m, m};
    WlDpVm *vm = wl_dp_vm_new(ms, 2, 2, 2);
    wl_dp_vm_set_wire(vm, 1, wire_fn, NULL);
    uint64_t dst[3] = {3, 3, 1};
    WlDpSend s = {.phase = WL_DP_PH_ROUTER,
                  .n_src = 4,
                  .n_dst = 4,
                  .lay = WL_DP_LAYOUT_LINEAR,
                  .dst = dst,
                  .count = 3,
                  .words = 2};
    wl_dp_send(vm, &s);
    /* pairs (0,3) (1,3) (2,1): load 2 (processor 3 receives two) */
    assert_int_equal(pairs_seen, 3);
    SimTime w = (1 + 30) + (2 + 30) + (3 + 10);
    const WlDpTarget *t1 = wl_dp_vm_target(vm, 1);
    assert_int_equal(t1->wire_total, 2 * w);
    assert_int_equal(t1->soft_total, 2 * 37 * 2);
    assert_int_equal(t1->phase[WL_DP_PH_ROUTER], 2 * (1000 + 31 + w));
    const WlDpTarget *t0 = wl_dp_vm_target(vm, 0);
    SimTime f = wl_dp_fattree_wire(&m, 2);
    assert_int_equal(t0->wire_total, 2 * f);
    assert_int_equal(t0->phase[WL_DP_PH_ROUTER], 2 * (1000 + 31 + MAX(f, 74)));
    /* the same pair twice counts as one pair of two messages */
    uint64_t d2[3] = {0, 0, 0}, s2[3] = {0, 0, 1};
    s.src = s2;
    s.dst = d2;
    s.words = 1;
    wl_dp_send(vm, &s);
    assert_int_equal(pairs_seen, 2);
    assert_int_equal(t1->wire_total, 2 * w + (2 * 1 + 2));
    wl_dp_vm_free(vm);
}

/* Named counts (dp_cost.h): each counting function adds what the cost
 * function of the same arguments charges, as counts of the model's
 * constants, so that pricing the counts gives the same time; a NULL
 * counter is allowed; each count is named after its model key. */
static void test_named_counts(void **state)
{
    (void)state;
    WlDpMachine m = simd();
    WlDpCounts k = {0};
    wl_dp_count_step(&m, 17, 5, &k);
    wl_dp_count_step(&m, 17, 5, NULL);
    assert_true(k.n[WL_DP_C_STEP] == 1 && k.n[WL_DP_C_OP] == 15);
    assert_int_equal(wl_dp_counts_price(&m, &k),
                     wl_dp_step_cost(&m, 17, 5, NULL));
    wl_dp_count_slices(&m, 17, WL_DP_C_SCAN_SLICE, &k);
    wl_dp_count_slices(&m, 16, WL_DP_C_NEWS_SLICE, &k);
    wl_dp_count_slices(&m, 17, WL_DP_C_SCAN_SLICE, NULL);
    assert_true(k.n[WL_DP_C_STEP] == 3 && k.n[WL_DP_C_SCAN_SLICE] == 3 &&
                k.n[WL_DP_C_NEWS_SLICE] == 2);
    assert_int_equal(wl_dp_counts_price(&m, &k),
                     wl_dp_step_cost(&m, 17, 5, NULL) +
                         wl_dp_scan_cost(&m, 17, NULL) +
                         wl_dp_news_cost(&m, 16, NULL));
    /* a SIMD send: 2 words, v 3, 2 messages a processor, load 3 */
    WlDpCounts s = {0};
    wl_dp_count_send(&m, 2, 17, 9, 3, 0, &s);
    assert_true(s.n[WL_DP_C_STEP] == 2 && s.n[WL_DP_C_SEND_SETUP] == 2 &&
                s.n[WL_DP_C_SEND_VP] == 6 && s.n[WL_DP_C_SEND_MSG] == 4 &&
                s.n[WL_DP_C_SEND_SLICE] == 6 && s.wire == 0);
    /* nothing of the SPMD formula on the SIMD router */
    assert_true(s.n[WL_DP_C_NET_LATENCY] == 0 &&
                s.n[WL_DP_C_MSG_OVERHEAD] == 0);
    assert_int_equal(wl_dp_counts_price(&m, &s),
                     wl_dp_send_cost(&m, 2, 17, 9, 3, NULL));
    WlDpCounts z = {0};
    wl_dp_count_send(&m, 1, 8, 8, 0, 0, &z);
    wl_dp_count_send(&m, 0, 8, 8, 1, 0, &z);
    wl_dp_count_send(&m, 1, 8, 0, 1, 0, &z);
    wl_dp_count_send(&m, 1, 8, 8, 1, 0, NULL);
    assert_int_equal(wl_dp_counts_price(&m, &z), 0);
    /* SPMD: the wire bounds (a time), or the software does (a count);
     * software equal to the wire counts as software */
    WlDpMachine p = spmd();
    SimTime wire = wl_dp_fattree_wire(&p, 1000);
    WlDpCounts w = {0};
    wl_dp_count_send(&p, 2, 16, 9, 1000, wire, &w);
    assert_true(w.n[WL_DP_C_NET_LATENCY] == 2 && w.n[WL_DP_C_STEP] == 2 &&
                w.n[WL_DP_C_MSG_OVERHEAD] == 0 && w.wire == 2 * wire);
    assert_int_equal(wl_dp_counts_price(&p, &w),
                     wl_dp_send_cost(&p, 2, 16, 9, 1000, NULL));
    p.msg_overhead = 5000;
    WlDpCounts o = {0};
    wl_dp_count_send(&p, 2, 16, 9, 1000, wire, &o);
    assert_true(o.n[WL_DP_C_MSG_OVERHEAD] == 2000 && o.wire == 0);
    assert_int_equal(wl_dp_counts_price(&p, &o),
                     wl_dp_send_cost(&p, 2, 16, 9, 1000, NULL));
    WlDpCounts e = {0};
    wl_dp_count_send(&p, 1, 16, 9, 10, 50000, &e);
    assert_true(e.n[WL_DP_C_MSG_OVERHEAD] == 10 && e.wire == 0);
    /* names and values */
    const char *names[WL_DP_N_COSTS] = {
        "step",       "op",       "scan_slice", "news_slice",  "send_setup",
        "send_vp",    "send_msg", "send_slice", "net_latency", "msg_overhead"};
    const SimTime vals[WL_DP_N_COSTS] = {1000, 7, 11, 29, 13, 19, 23, 17, 31,
                                         5000};
    for (int c = 0; c < WL_DP_N_COSTS; c++) {
        assert_string_equal(wl_dp_cost_name((WlDpCost)c), names[c]);
        char *path = g_strconcat("dpscan.", names[c], NULL);
        assert_string_equal(wl_dp_cost_path((WlDpCost)c), path);
        g_free(path);
        assert_int_equal(wl_dp_cost_value(&p, (WlDpCost)c), vals[c]);
    }
}

/* Every free function of the array layer and the renderer takes NULL. */
static void test_free_null(void **state)
{
    (void)state;
    wl_dp_vm_free(NULL);
    wl_dp_layout_free(NULL);
    wl_dp_polys_free(NULL);
    wl_dp_image_free(NULL);
}

/* The renderer's statement costs (operations per element) by default,
 * and the z-buffer's extraction: a pixel's colour index is its key's low
 * byte, 0 where nothing was drawn (the first pixel included). */
static void test_render_defaults_and_extract(void **state)
{
    (void)state;
    WlDpOps o = wl_dp_ops_defaults();
    assert_true(o.transform == 35 && o.shade == 21 && o.cross == 12 &&
                o.swap == 6 && o.pair == 6 && o.pixel == 20 && o.line == 16 &&
                o.clear == 2 && o.extract == 2 && o.edge == 6);
    WlDpImage *img = wl_dp_image_new(3, 1);
    img->zbuf[0] = wl_dp_key(0.5, 7, 41);
    img->zbuf[2] = wl_dp_key(0.25, 9, 200);
    img->index[1] = 99; /* overwritten: nothing drawn there */
    wl_dp_image_extract(img);
    assert_true(img->index[0] == 41 && img->index[1] == 0 &&
                img->index[2] == 200);
    wl_dp_image_free(img);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_render_defaults_and_extract),
        cmocka_unit_test(test_free_null),
        cmocka_unit_test(test_vp_ratio),
        cmocka_unit_test(test_step_scan_news),
        cmocka_unit_test(test_send_simd),
        cmocka_unit_test(test_fattree),
        cmocka_unit_test(test_send_spmd),
        cmocka_unit_test(test_layout),
        cmocka_unit_test(test_vm_ops),
        cmocka_unit_test(test_vm_send),
        cmocka_unit_test(test_empty_scan_one_proc),
        cmocka_unit_test(test_router_procs),
        cmocka_unit_test(test_vm_send_spmd),
        cmocka_unit_test(test_named_counts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
