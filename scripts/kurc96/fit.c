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
static double merge_ms(Scene *s, WlPmScheme sch, WlPmBalance bal, guint P, const WlPmCosts *c) {
    NetParams np = {.bandwidth = 2.8e6, .channels = 1, .startup = 350 * SIM_US, .per_hop = 10 * SIM_US, .switching = NET_SW_CIRCUIT};
    SimEngine *eng = sim_engine_new(1); NetTopo *topo = net_hypercube_new(4);
    NetNet *net = net_new(eng, topo, &np, NET_ANALYTIC);
    WlPmSetup st = {sch, bal, P, 400, WL_PM_SPLIT_CYCLIC, {8, 4, 2}, FALSE, FALSE};
    WlPmFrameOut o; wl_pm_frame_run(net, s, &st, c, &o, NULL);
    double r = o.merge_ms; wl_pm_frame_out_clear(&o, P);
    net_free(net); net_topo_free(topo); sim_engine_free(eng); return r;
}
int main(void) {
    for (int i = 0; i < 6; i++) {
        Scene *s = mk(i);
        SceneMesh *flat = scene_flatten(s); SceneCamera cam = scene_camera_at(s, 0);
        RastView rv = rast_view_for_camera(&cam, 400, 400); rv.cull_back = FALSE;
        uint64_t mx[5] = {0};
        for (guint q = 0; q < 16; q++) {
            WlPmCounts c; WlPmWpa *w = wl_pm_render_local(&rv, flat, q, 16, WL_PM_SPLIT_CYCLIC, &c);
            uint64_t v[5] = {c.polygons, c.rc.spans, c.insert_steps, c.rc.pixels, c.rc.zcompares};
            for (int k = 0; k < 5; k++) if (v[k] > mx[k]) mx[k] = v[k];
            wl_pm_wpa_free(w);
        }
        WlPmCosts z = {0}; z.merge.count_bytes = 4;
        double pr0 = merge_ms(s, WL_PM_PAIR, WL_PM_BAL_RS, 16, &z);
        double zx0 = merge_ms(s, WL_PM_ZBUF_EXC, WL_PM_BAL_STRIPS, 16, &z);
        WlPmCosts a = z; a.merge.compare = SIM_US;
        double prc = merge_ms(s, WL_PM_PAIR, WL_PM_BAL_RS, 16, &a) - pr0;
        double zxc = merge_ms(s, WL_PM_ZBUF_EXC, WL_PM_BAL_STRIPS, 16, &a) - zx0;
        WlPmCosts b = z; b.merge.scatter = b.merge.gather = b.merge.pack = SIM_US;
        double prs = merge_ms(s, WL_PM_PAIR, WL_PM_BAL_RS, 16, &b) - pr0;
        printf("%s %lu %lu %lu %lu %lu %.3f %.3f %.3f %.3f %.3f\n", names[i], mx[0], mx[1], mx[2], mx[3], mx[4], pr0, prc, prs, zx0, zxc);
        scene_mesh_free(flat); scene_free(s);
    }
}
