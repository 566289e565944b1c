/* sf_bv_metrics.c — the bounding volumes' fit and test price as the
 * sortfirst workload's metrics (sf_workload.h, sf_bv.h; seed 000
 * §3.3.1: "increasing complexity and tightness of fit").  Cost: one
 * wl_sf_bv_fit() per frame, O(vertices of the chunk instances).
 */
#include "sim/workload/sortfirst/sf_workload.h"

void wl_sf_bv_metrics(SimResult *out, const Scene *sc, const WlSfDb *db,
                      const SceneDb *sdb, const WlSfSetup *s,
                      const WlSfCosts *c, guint frames)
{
    WlSfBvFit fit = {0};
    WlSfRegions rg;
    wl_sf_regions_init(&rg, s->procs, s->resolution, s->resolution);
    for (guint f = 0; f < frames; f++) {
        SceneCamera cam = scene_camera_at(sc, f);
        RastView v = rast_view_for_camera(&cam, s->resolution, s->resolution);
        wl_sf_bv_fit(db, sdb, &rg, v.view_proj, &fit);
    }
    WlSfBvCost bc = wl_sf_bv_cost(db);
    SimTime t = sim_time_add_sat(sim_time_mul_sat(c->transform_vertex, bc.verts),
                                 sim_time_mul_sat(c->sphere_bound, bc.spheres));
    sim_result_set_metric(out, "bv_area_ratio",
                          fit.exact_area ? fit.bv_area / fit.exact_area : 0,
                          "");
    sim_result_set_metric(out, "bv_false_regions_per_polygon",
                          fit.polys ? fit.false_regions / fit.polys : 0, "");
    sim_result_set_metric(out, "bv_test_ns", sim_time_to_us(t) * 1000, "ns");
}
