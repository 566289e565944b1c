/* test_pm_frame.c — whole frames on real teapots at a small resolution:
 * the merged image equals the serial render for every scheme, balancing
 * and P; phase times follow the cost model.  The compositing schemes
 * (binary swap, direct send, radix-k, 2-3 swap) at 1, 2, 3, 5, 8, 12,
 * 16 and 64 processes with the z and the over operator, timed on a
 * 64-node hypercube through the merge replay: the image check passes,
 * every merge message crosses the network (bytes and count equal the
 * net's), bounding rectangles and RLE shrink the bytes, the same frame
 * twice gives the same times. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/teapot.h"
#include "sim/workload/pixelmerge/pm_frame.h"

enum { N = 48 };

static Scene *two_teapots(void)
{
    SceneTeapotTess t;
    assert_true(scene_teapot_tess_for(300, "test", &t, NULL));
    Scene *s = scene_new("2pot-small");
    guint m = scene_add_mesh(s, scene_teapot_mesh(t, scene_color(1, 1, 1)));
    scene_add_instance(s, m, mat4_identity(), scene_color(1, 0.5f, 0.5f), 0);
    scene_add_instance(s, m, mat4_translate(2.0, 0.8, -1.5),
                       scene_color(0.5f, 0.5f, 1), 1);
    s->camera = scene_camera_default();
    s->camera.eye = vec3(1.0, 4.0, 9.0);
    scene_camera_fit(&s->camera, scene_bbox(s), 0.9);
    return s;
}

static const WlPmCosts costs = {.polygon = 1000 * SIM_US,
                                .span = 20 * SIM_US,
                                .insert_step = SIM_US,
                                .pixel = 100 * SIM_US,
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

typedef struct {
    SimEngine *eng;
    NetTopo *topo;
    NetNet *net;
} Rig;

/* One frame on a fresh hypercube of 2^dim nodes; *net_bytes and
 * *net_msgs (may be NULL) get the network's totals. */
static void run_on(const Scene *sc, const WlPmSetup *s, guint dim,
                   WlPmFrameOut *out, uint64_t *net_bytes, uint64_t *net_msgs)
{
    NetParams np = {.bandwidth = 2.8e6,
                    .channels = 1,
                    .startup = 350 * SIM_US,
                    .per_hop = 10 * SIM_US,
                    .switching = NET_SW_CIRCUIT};
    SimEngine *eng = sim_engine_new(1);
    NetTopo *topo = net_hypercube_new(dim);
    NetNet *net = net_new(eng, topo, &np, NET_FLOW);
    GError *err = NULL;
    assert_true(wl_pm_frame_run(net, sc, s, &costs, out, &err));
    if (net_bytes)
        *net_bytes = net_total_bytes(net);
    if (net_msgs)
        *net_msgs = net_total_messages(net);
    net_free(net);
    net_topo_free(topo);
    sim_engine_free(eng);
}

static void run(const Scene *sc, const WlPmSetup *s, WlPmFrameOut *out)
{
    run_on(sc, s, 3, out, NULL, NULL);
}

static void test_images_match_serial(void **state)
{
    (void)state;
    Scene *sc = two_teapots();
    uint64_t tpf[2] = {0, 0}; /* without, with back-face culling */
    for (guint n = 1; n <= 8; n *= 2)
        for (int sch = 0; sch < 3; sch++)
            for (int bal = 0; bal < 3; bal++) {
                WlPmSetup s = {sch,
                               bal,
                               n,
                               N,
                               (n & 2) ? WL_PM_SPLIT_BLOCK : WL_PM_SPLIT_CYCLIC,
                               {8, 4, 2, 0, 0},
                               TRUE,
                               n == 4,
                               RAST_SPAN_EXACT,
                               FALSE,
                               {{0}, 0, FALSE, FALSE, 0, 0, NULL}, {0},
                               WL_PM_RUNG_PIXELS};
                WlPmFrameOut out;
                run(sc, &s, &out);
                assert_true(out.image_checked);
                assert_true(out.image_ok);
                assert_true(out.tpf > 100);
                if (!tpf[s.cull_back])
                    tpf[s.cull_back] = out.tpf;
                assert_int_equal(out.tpf, tpf[s.cull_back]);
                assert_int_equal(out.polygons, 600);
                assert_true(out.frame_ms >= out.merge_ms);
                wl_pm_frame_out_clear(&out, n);
            }
    scene_free(sc);
}

/* Full z-buffer merging pays N^2 initialisation and moves every location;
 * active pixel merging moves less on the same frame. */
static void test_zbuf_exc_costs_more(void **state)
{
    (void)state;
    Scene *sc = two_teapots();
    WlPmSetup s = {WL_PM_PAIR,         WL_PM_BAL_RS, 8,     N,
                   WL_PM_SPLIT_CYCLIC, {8, 4, 2, 0, 0},    FALSE, TRUE,
                   RAST_SPAN_EXACT,    FALSE,
                   {{0}, 0, FALSE, FALSE, 0, 0, NULL}, {0},
                   WL_PM_RUNG_PIXELS};
    WlPmFrameOut pair, full;
    run(sc, &s, &pair);
    s.scheme = WL_PM_ZBUF_EXC;
    run(sc, &s, &full);
    assert_false(pair.image_checked);
    assert_true(full.zbuf_ms > pair.zbuf_ms);
    assert_true(full.span_ms < pair.span_ms); /* no sorted insertion */
    assert_true(full.concurrent_volume > pair.concurrent_volume);
    assert_true(full.merge_ms > pair.merge_ms);
    /* ZBUF-EXC: (N/2 + N/4 + N/8) rows x N x 4 B. */
    assert_int_equal(full.concurrent_volume, (24 + 12 + 6) * N * 4);
    wl_pm_frame_out_clear(&pair, 8);
    wl_pm_frame_out_clear(&full, 8);
    scene_free(sc);
}

/* The serial time is the counted work of one processor holding every
 * polygon, priced one cost a count: polygons, spans, sorted-insertion
 * steps, pixels, the scanline loop (N of them) and depth comparisons;
 * insert_ms is the insertion part alone.  A cost so large the product
 * would wrap saturates. */
static void test_serial_ms(void **state)
{
    (void)state;
    Scene *sc = two_teapots();
    WlPmSetup s = {.procs = 1, .resolution = N, .cull_back = TRUE};
    SceneMesh *flat = scene_flatten(sc);
    SceneCamera cam = scene_camera_at(sc, 0);
    RastView v = rast_view_for_camera(&cam, N, N);
    v.cull_back = TRUE;
    WlPmCounts k;
    WlPmWpa *w = wl_pm_render_local(&v, flat, 0, 1, WL_PM_SPLIT_BLOCK, &k);
    assert_true(k.polygons > 0 && k.rc.spans > 0 && k.insert_steps > 0 &&
                k.rc.pixels > 0 && k.rc.zcompares > 0);
    double want = sim_time_to_ms(
        k.polygons * costs.polygon + k.rc.spans * costs.span +
        k.insert_steps * costs.insert_step + k.rc.pixels * costs.pixel +
        N * costs.scanline + k.rc.zcompares * costs.zcompare);
    double ins = -1;
    assert_true(wl_pm_serial_ms(sc, &s, &costs, &ins) == want);
    assert_true(ins == sim_time_to_ms(k.insert_steps * costs.insert_step));
    assert_true(wl_pm_serial_ms(sc, &s, &costs, NULL) == want);
    WlPmCosts huge = costs;
    huge.pixel = SIM_TIME_MAX / 2;
    assert_true(wl_pm_serial_ms(sc, &s, &huge, NULL) ==
                sim_time_to_ms(SIM_TIME_MAX));
    wl_pm_wpa_free(w);
    scene_mesh_free(flat);
    scene_free(sc);
}

/* The compositing schemes (pm_composite.h) on a 64-node hypercube. */
static WlPmSetup comp_setup(WlPmScheme scheme, guint n, WlPmOperator op)
{
    WlPmSetup s = {.scheme = scheme,
                   .procs = n,
                   .resolution = 40,
                   .split = WL_PM_SPLIT_CYCLIC,
                   .fmt = {8, 4, 2, 4, 8},
                   .check_image = TRUE,
                   .comp = {.op = op, .opacity = 0.5}};
    return s;
}

static void test_images_on_the_machine(void **state)
{
    (void)state;
    static const guint counts[] = {1, 2, 3, 5, 8, 12, 16, 64};
    Scene *sc = two_teapots();
    for (guint i = 0; i < G_N_ELEMENTS(counts); i++)
        for (guint sch = WL_PM_BINARY_SWAP; sch <= WL_PM_TWO_THREE_SWAP; sch++)
            for (int op = 0; op < 2; op++) {
                guint n = counts[i];
                WlPmSetup s = comp_setup((WlPmScheme)sch, n, (WlPmOperator)op);
                s.comp.rle = (i % 2) == 1;
                s.comp.bounding_rect = (i % 4) >= 2;
                guint order[64]; /* the far half first, then the near */
                for (guint r = 0; r < n; r++)
                    order[r] = (r + n / 2) % n;
                s.comp.order = op ? order : NULL;
                WlPmFrameOut out;
                uint64_t bytes, msgs;
                run_on(sc, &s, 6, &out, &bytes, &msgs);
                if (!out.image_checked || !out.image_ok)
                    fail_msg("%s P=%u op=%d: image differs",
                             wl_pm_scheme_names[sch], n, op);
                assert_int_equal(bytes, out.merge_bytes);
                assert_int_equal(msgs, out.merge_msgs);
                assert_true(n == 1 || out.merge_ms > 0);
                assert_true(out.frame_ms >= out.merge_ms);
                wl_pm_frame_out_clear(&out, n);
            }
    scene_free(sc);
}

/* Bounding rectangles and RLE send less than whole pieces; RLE alone
 * less than rectangles alone on sparse teapots; the same frame twice has
 * the same merge time. */
static void test_options_shrink_bytes(void **state)
{
    (void)state;
    Scene *sc = two_teapots();
    uint64_t b[4], bytes, msgs;
    double ms[4];
    for (int opt = 0; opt < 4; opt++) {
        WlPmSetup s = comp_setup(WL_PM_RADIX_K, 12, WL_PM_OP_Z);
        s.comp.bounding_rect = opt & 1;
        s.comp.rle = (opt & 2) != 0;
        WlPmFrameOut out, again;
        run_on(sc, &s, 6, &out, &bytes, &msgs);
        run_on(sc, &s, 6, &again, &bytes, &msgs);
        assert_true(out.merge_ms == again.merge_ms);
        b[opt] = out.merge_bytes;
        ms[opt] = out.merge_ms;
        wl_pm_frame_out_clear(&out, 12);
        wl_pm_frame_out_clear(&again, 12);
    }
    assert_true(b[1] < b[0] && b[2] < b[1] && b[3] <= b[2] + 12 * 12 * 8);
    assert_true(ms[2] < ms[0]);
    scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_serial_ms),
        cmocka_unit_test(test_images_match_serial),
        cmocka_unit_test(test_zbuf_exc_costs_more),
        cmocka_unit_test(test_images_on_the_machine),
        cmocka_unit_test(test_options_shrink_bytes),
    };
    return cmocka_run_group_tests_name("pm_frame", tests, NULL, NULL);
}
