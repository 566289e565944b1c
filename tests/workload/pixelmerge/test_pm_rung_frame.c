/* test_pm_rung_frame.c — workload.image_fidelity (pm_rung_frame.h): a
 * block-image frame at the runs rung gives the pixel rung's merge bytes,
 * messages and compositing time exactly, at the counts rung within 30 %
 * (and not exactly, so the comparison can fail); the parser takes
 * counts with block images up to 65,536 processors and 16384^2 and
 * refuses runs or counts with Kurç's schemes, counts without block
 * images and more than 1,024 processors or 4096^2 below counts, each
 * located; the own-memory estimate at counts grows with P (P^2 for
 * direct send); a counts frame runs on machine processors whose model
 * prices only pack and compare. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/machine/partition.h"
#include "sim/workload/pixelmerge/pm_workload.h"

static const WlPmFormat fmt = {8, 4, 2, 4, 8};

/* One frame on a 64-node hypercube at the analytic fidelity. */
static void run_on(const Scene *sc, const WlPmSetup *s, WlPmFrameOut *out)
{
    NetParams np = {.bandwidth = 2.8e6,
                    .channels = 1,
                    .startup = 350 * SIM_US,
                    .per_hop = 10 * SIM_US,
                    .switching = NET_SW_CIRCUIT};
    static const WlPmCosts costs = {
        .merge = {.pack = SIM_US, .compare = SIM_US, .count_bytes = 4}};
    SimEngine *eng = sim_engine_new(1);
    NetTopo *topo = net_hypercube_new(6);
    NetNet *net = net_new(eng, topo, &np, NET_ANALYTIC);
    GError *err = NULL;
    if (!wl_pm_frame_run(net, sc, s, &costs, out, &err))
        fail_msg("%s", err->message);
    net_free(net);
    net_topo_free(topo);
    sim_engine_free(eng);
}

static void test_rungs_in_frames(void **st)
{
    (void)st;
    Scene *sc = scene_new("camera only");
    sc->camera = scene_camera_default();
    sc->camera.eye = vec3(2.6, 1.9, 3.4);
    scene_camera_fit(&sc->camera, (SceneBox){{-1, -1, -1}, {1, 1, 1}}, 1.0);
    const WlPmScheme sch[] = {WL_PM_BINARY_SWAP, WL_PM_RADIX_K,
                              WL_PM_DIRECT_SEND};
    for (guint i = 0; i < G_N_ELEMENTS(sch); i++) {
        WlPmSetup s = {
            .scheme = sch[i],
            .procs = 64,
            .resolution = 192,
            .fmt = fmt,
            .comp = {.bounding_rect = TRUE, .rle = TRUE, .opacity = 1},
            .images = {.kind = WL_PM_IMAGES_BLOCKS, .density = 1.5}};
        WlPmFrameOut o[3];
        for (int r = 0; r < 3; r++) {
            s.rung = (WlPmRung)r;
            run_on(sc, &s, &o[r]);
        }
        assert_int_equal(o[1].merge_bytes, o[0].merge_bytes);
        assert_int_equal(o[1].merge_msgs, o[0].merge_msgs);
        assert_int_equal(o[1].merge_records, o[0].merge_records);
        assert_true(o[1].merge_ms == o[0].merge_ms);
        double e = (double)o[2].merge_bytes / o[0].merge_bytes - 1;
        double t = o[2].merge_ms / o[0].merge_ms - 1;
        if (!(fabs(e) < 0.3 && fabs(t) < 0.3 && e != 0))
            fail_msg("%s: counts off by %.3f in bytes, %.3f in time",
                     wl_pm_scheme_names[sch[i]], e, t);
        assert_int_equal(o[2].merge_msgs, o[0].merge_msgs);
        for (int r = 0; r < 3; r++)
            wl_pm_frame_out_clear(&o[r], 64);
    }
    scene_free(sc);
}

/* A frame at the counts rung on machine processors of a model with only
 * the two costs compositing spends (ring-8 has no pixel-merging table
 * and no processor description to derive one from; cluster-ib now
 * derives it): it runs, and its processors are busy merging. */
static void test_counts_on_machine_with_two_costs(void **st)
{
    (void)st;
    const char *sets[] = {"machine.nodes.node.costs.pack=5 ns",
                          "machine.nodes.node.costs.compare=7 ns", NULL};
    GError *err = NULL;
    CfgNode *root =
        mach_partition_root("test", "ring-8", sets, 64, NULL, &err);
    assert_non_null(root);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    assert_non_null(m);
    WlPmCosts c;
    assert_false(wl_pm_costs_from_machine(m, 4, &c, &err));
    g_clear_error(&err);
    assert_true(wl_pm_composite_costs_from_machine(m, 4, &c, &err));
    MachProc *procs[64];
    for (guint q = 0; q < 64; q++)
        procs[q] = mach_proc(m, "node", q);
    Scene *sc = scene_new("camera only");
    sc->camera = scene_camera_default();
    scene_camera_fit(&sc->camera, (SceneBox){{-1, -1, -1}, {1, 1, 1}}, 1.0);
    WlPmSetup s = {.scheme = WL_PM_RADIX_K,
                   .procs = 64,
                   .resolution = 512,
                   .fmt = fmt,
                   .comp = {.bounding_rect = TRUE, .rle = TRUE, .opacity = 1},
                   .images = {.kind = WL_PM_IMAGES_BLOCKS, .density = 1.5},
                   .rung = WL_PM_RUNG_COUNTS};
    WlPmFrameOut o;
    if (!wl_pm_frame_run_procs(mach_net(m), procs, 0, sc, &s, &c, &o, &err))
        fail_msg("%s", err->message);
    assert_true(o.merge_ms > 0 && o.merge_bytes > 0);
    assert_true(o.busy[0].total > 0);
    wl_pm_frame_out_clear(&o, 64);
    scene_free(sc);
    mach_free(m);
    sim_engine_free(eng);
    cfg_free(root);
}

static WlPmParams *parse(const char *extra, GError **err)
{
    char *text = g_strdup_printf("workload: {type: pixelmerge%s}\n", extra);
    CfgNode *root = cfg_load_string(text, "pm.yaml", err);
    assert_non_null(root);
    WlPmParams *p = wl_pixelmerge_ops.parse(cfg_get(root, "workload"), err);
    cfg_free(root);
    g_free(text);
    return p;
}

/* Refused, the message located and holding `want`. */
static void refused(const char *extra, const char *want)
{
    GError *e = NULL;
    WlPmParams *p = parse(extra, &e);
    if (p || !strstr(e->message, "pm.yaml:1:") || !strstr(e->message, want))
        fail_msg("%s: %s", extra, p ? "accepted" : e->message);
    g_clear_error(&e);
}

static void test_parse(void **st)
{
    (void)st;
    GError *e = NULL;
    WlPmParams *p = parse(", scheme: radix_k, images: blocks, image_fidelity: "
                          "counts, processors: 65536, resolution: 16384",
                          &e);
    assert_non_null(p);
    assert_int_equal(p->setup.rung, WL_PM_RUNG_COUNTS);
    GString *what = g_string_new("");
    double radix = wl_pixelmerge_ops.mem_bytes(p, what);
    wl_pixelmerge_ops.free_params(p);
    p = parse(", images: blocks, image_fidelity: counts, processors: 4096, "
              "scheme: direct_send",
              &e);
    assert_non_null(p);
    double direct = wl_pixelmerge_ops.mem_bytes(p, what);
    assert_true(radix < 65536 * 8192.0 && direct > 4096.0 * 4096 * 100);
    wl_pixelmerge_ops.free_params(p);
    g_string_free(what, TRUE);
    p = parse(", scheme: radix_k, image_fidelity: runs, processors: 1024", &e);
    assert_non_null(p);
    assert_int_equal(p->setup.rung, WL_PM_RUNG_RUNS);
    wl_pixelmerge_ops.free_params(p);
    refused(", scheme: radix_k, image_fidelity: counts", "images: blocks");
    refused(", scheme: pair, image_fidelity: runs", "compositing scheme");
    refused(", scheme: radix_k, image_fidelity: runs, processors: 2048",
            "at most 1024");
    refused(", scheme: radix_k, processors: 2048", "at most 1024");
    refused(", scheme: radix_k, resolution: 8192", "at most 4096");
    refused(", scheme: radix_k, image_fidelity: lines", "pixels");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rungs_in_frames),
        cmocka_unit_test(test_parse),
        cmocka_unit_test(test_counts_on_machine_with_two_costs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
