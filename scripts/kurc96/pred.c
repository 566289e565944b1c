#include "sim/scene/teapots.h"
#include "sim/workload/pixelmerge/pm_frame.h"
#include <stdio.h>
static const char *names[] = {"1POT","2POT","4POT_1","4POT_2","8POT_1","8POT_2"};
static Scene *mk(int i) {
    guint cnt[] = {1,2,4,4,8,8}; int lay[] = {0,0,0,1,0,1};
    SceneTeapotsParams p = scene_teapots_defaults();
    p.polygons_per_teapot = 3751; p.count = cnt[i]; p.layout = lay[i];
    Scene *s = scene_teapots_new(&p, "x", NULL);
    SceneView v = scene_view_default(); v.azimuth_deg = 30; v.elevation_deg = 20; v.fill = 1.0;
    scene_apply_view(s, &v); return s;
}
static WlPmCosts C;
static WlPmFrameOut run(Scene *s, WlPmScheme sch, WlPmBalance bal, guint P, guint N) {
    NetParams np = {.bandwidth = 2.8e6, .channels = 1, .startup = 350 * SIM_US, .per_hop = 10 * SIM_US, .switching = NET_SW_CIRCUIT};
    SimEngine *eng = sim_engine_new(1); NetTopo *topo = net_hypercube_new(4);
    NetNet *net = net_new(eng, topo, &np, NET_ANALYTIC);
    WlPmSetup st = {sch, bal, P, N, WL_PM_SPLIT_CYCLIC, {8, 4, 2}, FALSE, FALSE};
    WlPmFrameOut o; wl_pm_frame_run(net, s, &st, &C, &o, NULL);
    if (sch == WL_PM_AAPC && bal == WL_PM_BAL_HBP && N == 640 && P == 16 && s->instances->len == 2)
        printf("text P16/2POT/640 aapc_hbp_speedup %.3f\n", wl_pm_serial_ms(s, &st, &C) / o.frame_ms);
    wl_pm_frame_out_clear(&o, P);
    net_free(net); net_topo_free(topo); sim_engine_free(eng); return o;
}
int main(void) {
    C = (WlPmCosts){.polygon = 1100 * SIM_US, .span = 7359 * SIM_NS, .insert_step = 6021 * SIM_NS,
        .pixel = 186300 * SIM_NS, .zcompare = 0, .scanline = 12 * SIM_US, .zbuf_init = 1639 * SIM_NS,
        .merge = {.pack = 42400 * SIM_NS, .scatter = 42400 * SIM_NS, .compare = 11720 * SIM_NS, .gather = 42400 * SIM_NS,
                  .sum_elem = 2 * SIM_US, .sort_elem = 10 * SIM_US, .count_bytes = 4}};
    for (int i = 0; i < 6; i++) {
        Scene *s = mk(i);
        WlPmFrameOut a = run(s, WL_PM_AAPC, WL_PM_BAL_HBP, 16, 400), b = run(s, WL_PM_AAPC, WL_PM_BAL_HBP, 16, 640);
        printf("1 %s polygons %lu\n1 %s tpg_400 %lu\n1 %s tpf_400 %lu\n1 %s tpg_640 %lu\n1 %s tpf_640 %lu\n", names[i], a.polygons, names[i], a.tpg, names[i], a.tpf, names[i], b.tpg, names[i], b.tpf);
        for (guint P = 16; P >= 8; P /= 2) {
            WlPmFrameOut pr = run(s, WL_PM_PAIR, WL_PM_BAL_RS, P, 400), zx = run(s, WL_PM_ZBUF_EXC, WL_PM_BAL_STRIPS, P, 400);
            printf("2 P%u/%s pair_rs_span_ms %.1f\n2 P%u/%s pair_rs_zbuf_ms %.1f\n2 P%u/%s pair_rs_merge_ms %.1f\n", P, names[i], pr.span_ms, P, names[i], pr.zbuf_ms, P, names[i], pr.merge_ms);
            printf("2 P%u/%s zbuf_exc_span_ms %.1f\n2 P%u/%s zbuf_exc_zbuf_ms %.1f\n2 P%u/%s zbuf_exc_merge_ms %.1f\n", P, names[i], zx.span_ms, P, names[i], zx.zbuf_ms, P, names[i], zx.merge_ms);
        }
        if (i == 1) run(s, WL_PM_AAPC, WL_PM_BAL_HBP, 16, 640);
        scene_free(s);
    }
}
