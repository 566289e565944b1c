/* test_pm_checks.c — pixelmerge results checked against values the test
 * computes itself (issue 21): the local phase times of pm_frame.h's cost
 * model recomputed from each processor's counts (zero costs give exactly
 * zero), the replay's overflow bound (a cost of SIM_TIME_MAX / n fits, one
 * more does not), the processor count's power-of-two rule at 1, a missing
 * `processors` taking the machine's nodes, and mem_bytes' formula. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/teapot.h"
#include "sim/workload/pixelmerge/pm_frame.h"
#include "sim/workload/pixelmerge/pm_workload.h"
#include "tests/support.h"

enum { N = 32 };

static Scene *one_teapot(void)
{
    SceneTeapotTess t;
    assert_true(scene_teapot_tess_for(300, "test", &t, NULL));
    Scene *s = scene_new("pot");
    guint m = scene_add_mesh(s, scene_teapot_mesh(t, scene_color(1, 1, 1)));
    scene_add_instance(s, m, mat4_identity(), scene_color(1, 0.5f, 0.5f), 0);
    s->camera = scene_camera_default();
    s->camera.eye = vec3(1.0, 4.0, 9.0);
    scene_camera_fit(&s->camera, scene_bbox(s), 0.9);
    return s;
}

static void frame(const Scene *sc, const WlPmSetup *s, const WlPmCosts *c,
                  WlPmFrameOut *out)
{
    NetParams np = {.bandwidth = 2.8e6,
                    .channels = 1,
                    .startup = 350 * SIM_US,
                    .per_hop = 10 * SIM_US,
                    .switching = NET_SW_CIRCUIT};
    SimEngine *eng = sim_engine_new(1);
    NetTopo *topo = net_hypercube_new(2);
    NetNet *net = net_new(eng, topo, &np, NET_ANALYTIC);
    GError *err = NULL;
    if (!wl_pm_frame_run(net, sc, s, c, out, &err))
        fail_msg("%s", err->message);
    net_free(net);
    net_topo_free(topo);
    sim_engine_free(eng);
}

/* The cost model of pm_frame.h, in integer nanoseconds. */
static uint64_t span_ns(const WlPmCounts *k, const WlPmCosts *c, int sorted)
{
    return c->polygon * k->polygons + c->span * k->rc.spans +
           (sorted ? c->insert_step * k->insert_steps : 0);
}

static uint64_t zbuf_ns(const WlPmCounts *k, const WlPmCosts *c, int full)
{
    uint64_t t = c->pixel * k->rc.pixels + c->scanline * N;
    if (full)
        return t + c->zbuf_init * N * N + c->zcompare * k->rc.pixels;
    return t + c->zcompare * k->rc.zcompares;
}

/* SimTime is in picoseconds */
static uint64_t ns(double ms)
{
    return (uint64_t)(ms * 1e9 + 0.5);
}

static void check_phases(const Scene *sc, WlPmScheme sch, guint P,
                         const WlPmCosts *c)
{
    WlPmSetup s = {
        sch,   WL_PM_BAL_RS,    P,    N, WL_PM_SPLIT_CYCLIC, {8, 4, 2, 0, 0}, FALSE,
        FALSE, RAST_SPAN_EXACT, FALSE, {{0}, 0, FALSE, FALSE, 0, 0, NULL}, {0},
        WL_PM_RUNG_PIXELS};
    WlPmFrameOut out;
    frame(sc, &s, c, &out);
    int full = sch == WL_PM_ZBUF_EXC;
    uint64_t span = 0, zbuf = 0, barrier = 0;
    for (guint p = 0; p < P; p++) {
        uint64_t ts = span_ns(&out.counts[p], c, !full);
        uint64_t tz = zbuf_ns(&out.counts[p], c, full);
        span = MAX(span, ts);
        zbuf = MAX(zbuf, tz);
        barrier = MAX(barrier, ts + tz);
    }
    if (ns(out.span_ms) != span || ns(out.zbuf_ms) != zbuf ||
        ns(out.frame_ms) - ns(out.merge_ms) != barrier)
        fail_msg("scheme %d P %u: span %.6f zbuf %.6f frame-merge %.6f ms, "
                 "expected %.6f %.6f %.6f",
                 sch, P, out.span_ms, out.zbuf_ms, out.frame_ms - out.merge_ms,
                 span * 1e-9, zbuf * 1e-9, barrier * 1e-9);
    assert_true(P == 1 || out.merge_ms > 0);
    wl_pm_frame_out_clear(&out, P);
}

static void test_local_phases_follow_costs(void **state)
{
    (void)state;
    Scene *sc = one_teapot();
    const WlPmCosts c = {.polygon = 900 * SIM_US,
                         .span = 20 * SIM_US,
                         .insert_step = 3 * SIM_US,
                         .pixel = 70 * SIM_US,
                         .zcompare = 2 * SIM_US,
                         .scanline = 5 * SIM_US,
                         .zbuf_init = SIM_US,
                         .merge = {.pack = SIM_US,
                                   .scatter = 2 * SIM_US,
                                   .compare = 10 * SIM_US,
                                   .gather = 2 * SIM_US,
                                   .sum_elem = SIM_US,
                                   .sort_elem = SIM_US,
                                   .count_bytes = 4}};
    for (int sch = 0; sch < 3; sch++)
        for (guint P = 1; P <= 4; P *= 2)
            check_phases(sc, (WlPmScheme)sch, P, &c);
    /* free local phases: both maxima stay exactly 0 */
    WlPmCosts z = {.merge = c.merge};
    for (int sch = 0; sch < 3; sch++)
        check_phases(sc, (WlPmScheme)sch, 4, &z);
    /* span work only, and z-buffer work only */
    WlPmCosts sp = z, zb = c;
    sp.polygon = c.polygon;
    zb.polygon = zb.span = zb.insert_step = 0;
    check_phases(sc, WL_PM_PAIR, 2, &sp);
    check_phases(sc, WL_PM_ZBUF_EXC, 2, &zb);
    scene_free(sc);
}

/* The same frame on machine processors (work charged once, priced by
 * the machine) and without them (wl_pm_frame_run at the costs read from
 * the same machine, on a fresh copy of its network): every processor's
 * busy time per phase and the frame's phase times agree, so the op lists
 * name every operation with its count and the machine's frame is the
 * cost model's, each piece of work counted once (a second charge would
 * delay the machine's barrier and lengthen its frame). */
static void test_machine_busy_matches_cost_model(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root =
        cfg_load_string("machine: {model: ipsc2}\n", "m.yaml", &err);
    Scene *sc = one_teapot();
    for (int sch = 0; sch < 3; sch++) {
        SimEngine *eng[2] = {sim_engine_new(1), sim_engine_new(1)};
        MachMachine *m[2];
        for (int i = 0; i < 2; i++) {
            m[i] = mach_new_from_cfg(eng[i], cfg_get(root, "machine"),
                                     "analytic", &err);
            assert_non_null(m[i]);
        }
        WlPmCosts c;
        assert_true(wl_pm_costs_from_machine(m[0], 4, &c, &err));
        MachProc *procs[4];
        for (guint q = 0; q < 4; q++)
            procs[q] = mach_proc(m[0], "node", q);
        WlPmSetup s = {(WlPmScheme)sch,    WL_PM_BAL_HBP, 4,     N,
                       WL_PM_SPLIT_CYCLIC, {8, 4, 2, 0, 0},     FALSE, FALSE,
                       RAST_SPAN_EXACT,    FALSE,
                       {{0}, 0, FALSE, FALSE, 0, 0, NULL}, {0},
                       WL_PM_RUNG_PIXELS};
        WlPmFrameOut on, off;
        if (!wl_pm_frame_run_procs(mach_net(m[0]), procs, 0, sc, &s, &c, &on,
                                   &err) ||
            !wl_pm_frame_run(mach_net(m[1]), sc, &s, &c, &off, &err))
            fail_msg("%s", err->message);
        const char *ph[] = {"span", "zbuf", "merge"};
        for (guint q = 0; q < 4; q++)
            for (guint k = 0; k < 3; k++) {
                SimTime got = mach_proc_busy_phase(
                    procs[q], sim_engine_phase(eng[0], ph[k]));
                SimTime want = sim_busy_phase(&off.busy[q],
                                              sim_engine_phase(eng[1], ph[k]));
                if (got != want)
                    fail_msg(
                        "scheme %d node %u phase %s: machine %" G_GUINT64_FORMAT
                        " ps, cost model %" G_GUINT64_FORMAT " ps",
                        sch, q, ph[k], got, want);
                assert_true(sim_busy_phase(&on.busy[q],
                                           sim_engine_phase(eng[0], ph[k])) ==
                            got);
                assert_true(k == 2 || want > 0);
            }
        assert_true(on.span_ms == off.span_ms && on.span_ms > 0);
        assert_true(on.zbuf_ms == off.zbuf_ms && on.zbuf_ms > 0);
        assert_true(on.merge_ms == off.merge_ms && on.merge_ms > 0);
        assert_true(on.frame_ms == off.frame_ms);
        wl_pm_frame_out_clear(&on, 4);
        wl_pm_frame_out_clear(&off, 4);
        for (int i = 0; i < 2; i++) {
            mach_free(m[i]);
            sim_engine_free(eng[i]);
        }
    }
    scene_free(sc);
    cfg_free(root);
}

/* ---- the replay's overflow bound --------------------------------------- */

enum { H = 4 };

/* One processor, balance HBP: the only computation is the partition's
 * sort of H log2 H = 8 elements, at time 0, so the replay ends at exactly
 * 8 x sort_elem (no message, no other cost). */
static gboolean replay_sort(SimTime sort_elem, SimTime *end, GError **err)
{
    const WlPmFormat fmt = {8, 5, 2, 0, 0};
    NetParams np = {.bandwidth = 1e6,
                    .channels = 1,
                    .startup = SIM_US,
                    .per_hop = SIM_US,
                    .switching = NET_SW_CIRCUIT};
    SimEngine *eng = sim_engine_new(1);
    NetTopo *topo = net_hypercube_new(0);
    NetNet *net = net_new(eng, topo, &np, NET_ANALYTIC);
    WlPmWpa *local[1] = {wl_pm_wpa_new(8, H)};
    uint64_t counts[H] = {0};
    WlPmPixel px = {1, 1, 0, 0, 0};
    wl_pm_wpa_push(local[0], &px);
    wl_pm_wpa_finish(local[0]);
    wl_pm_wpa_add_row_counts(local[0], counts);
    WlPmPartition *hbp = wl_pm_partition_new(WL_PM_BAL_HBP, 1, counts, H);
    WlPmMerge *m = wl_pm_merge_run(WL_PM_PAIR, local, 1, hbp, &fmt);
    WlPmMergeCosts c = {.sort_elem = sort_elem, .count_bytes = 4};
    SimBusy busy[1];
    sim_busy_init(&busy[0]);
    SimTime ready[1] = {0};
    WlPmReplayOut out = {0};
    WlPmReplayRig r = {.net = net,
                       .costs = &c,
                       .ready = ready,
                       .busy = busy,
                       .bal = WL_PM_BAL_HBP,
                       .height = H};
    gboolean ok = wl_pm_replay(&r, m, &out, err);
    *end = out.end;
    wl_pm_replay_out_clear(&out);
    sim_busy_clear(&busy[0]);
    wl_pm_merge_free(m);
    wl_pm_partition_free(hbp);
    wl_pm_wpa_free(local[0]);
    net_free(net);
    net_topo_free(topo);
    sim_engine_free(eng);
    return ok;
}

static void test_replay_overflow_bound(void **state)
{
    (void)state;
    SimTime end = 0;
    GError *err = NULL;
    if (!replay_sort(3 * SIM_US, &end, &err))
        fail_msg("%s", err->message);
    assert_true(end == 8 * 3 * SIM_US);
    /* 8 x (SIM_TIME_MAX / 8) = SIM_TIME_MAX - 7 still fits */
    if (!replay_sort(SIM_TIME_MAX / 8, &end, &err))
        fail_msg("%s", err->message);
    assert_true(end == SIM_TIME_MAX / 8 * 8);
    assert_false(replay_sort(SIM_TIME_MAX / 8 + 1, &end, &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_OVERFLOW));
    assert_string_equal(err->message,
                        "pixel merge: a compute time overflows SimTime");
    g_error_free(err);
}

/* ---- parameters ---------------------------------------------------------- */

static WlPmParams *parse(const char *w, GError **err)
{
    char *text = g_strdup_printf("workload: {type: pixelmerge, %s}\n", w);
    CfgNode *root = cfg_load_string(text, "pm.yaml", err);
    g_free(text);
    assert_non_null(root);
    WlPmParams *p = wl_pixelmerge_ops.parse(cfg_get(root, "workload"), err);
    cfg_free(root);
    return p;
}

static void test_processor_counts(void **state)
{
    (void)state;
    GError *err = NULL;
    for (guint P = 1; P <= 1024; P *= 2) {
        char *w = g_strdup_printf("processors: %u", P);
        WlPmParams *p = parse(w, &err);
        if (!p)
            fail_msg("%s: %s", w, err->message);
        assert_int_equal(p->setup.procs, P);
        wl_pixelmerge_ops.free_params(p);
        g_free(w);
    }
    const guint bad[] = {3, 5, 6, 7, 12, 1023};
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        char *w = g_strdup_printf("processors: %u", bad[i]);
        assert_null(parse(w, &err));
        char *want = g_strdup_printf("pm.yaml:1:42: found '%u', expected a "
                                     "power of two (a hypercube of 2^d "
                                     "nodes)",
                                     bad[i]);
        assert_string_equal(err->message, want);
        g_clear_error(&err);
        g_free(want);
        g_free(w);
    }
}

static double mem(const char *w, GString *what)
{
    GError *err = NULL;
    WlPmParams *p = parse(w, &err);
    assert_non_null(p);
    g_string_truncate(what, 0);
    double b = wl_pixelmerge_ops.mem_bytes(p, what);
    wl_pixelmerge_ops.free_params(p);
    return b;
}

static void test_mem_bytes(void **state)
{
    (void)state;
    GString *what = g_string_new("");
    double px = sizeof(WlPmPixel);
    /* processors 0 (the machine's count) counts as 1 */
    assert_true(mem("resolution: 10", what) ==
                100 * (3 * px + 3) + 1 * 11 * 4.0 + 1 * 1 * 8.0);
    assert_string_equal(what->str, "0 processors, 10 x 10 pixels");
    assert_true(mem("resolution: 10, processors: 4, check_image: false",
                    what) == 100 * (2 * px + 3) + 4 * 11 * 4.0 + 16 * 8.0);
    assert_string_equal(what->str, "4 processors, 10 x 10 pixels");
    g_string_free(what, TRUE);
}

/* Without `processors` the run takes every node of the machine. */
static void test_machine_count_by_default(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "machine: {model: ipsc2}\n"
        "workload: {type: pixelmerge, resolution: 16, scheme: aapc}\n"
        "scene: {generator: teapots, count: 1, polygons_per_teapot: 300}\n",
        "pm.yaml", &err);
    assert_non_null(root);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    assert_non_null(m);
    double nodes = mach_kind(m, "node")->count;
    mach_free(m);
    sim_engine_free(eng);
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    SimResult *r = support_run_tree(root, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    double v = 0;
    assert_true(sim_result_get_metric(r, "processors", &v));
    assert_true(v == nodes && nodes == 16);
    /* the peak is the sum of its parts */
    double sum = 0, part = 0;
    const char *parts[] = {"memory_base", "memory_polygons", "memory_spans",
                           "memory_zbuffer", "memory_buffers"};
    for (guint i = 0; i < G_N_ELEMENTS(parts); i++) {
        assert_true(sim_result_get_metric(r, parts[i], &part) && part >= 0);
        sum += part;
    }
    assert_true(sim_result_get_metric(r, "peak_memory", &v));
    assert_true(v == sum && sum > 0);
    sim_result_free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_local_phases_follow_costs),
        cmocka_unit_test(test_machine_busy_matches_cost_model),
        cmocka_unit_test(test_replay_overflow_bound),
        cmocka_unit_test(test_processor_counts),
        cmocka_unit_test(test_mem_bytes),
        cmocka_unit_test(test_machine_count_by_default),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
