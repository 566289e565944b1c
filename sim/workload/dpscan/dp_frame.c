/* dp_frame.c — one frame in closed form (dp_frame.h).
 *
 * Utilisation weighs each compute step's live elements (the polygons
 * still scanning, the segments still producing pixels) by its operation
 * count against the virtual-processor slots the step occupies; it is
 * approximate for scan lines (every polygon of the array counts live).
 * O(steps + pixels).
 */
#include "sim/workload/dpscan/dp_frame.h"
#include <string.h>

static void charge(WlDpFrame *f, WlDpPhase ph, SimTime t)
{
    gboolean ok = sim_time_add(f->phase[ph], t, &f->phase[ph]) &&
                  sim_time_add(f->total, t, &f->total);
    g_assert(ok);
}

void wl_dp_frame_run(const WlDpGeom *g, const WlDpMachine *m, const WlDpAlgo *a,
                     WlDpFrame *out)
{
    memset(out, 0, sizeof(*out));
    WlDpSched *s = wl_dp_sched_new(g, a);
    WlDpLayout *l =
        wl_dp_layout_new(m->procs, (uint32_t)g->width, (uint32_t)g->height);
    double useful = 0.0, slots = 0.0;
    WlDpStep st;
    while (wl_dp_sched_next(s, &st)) {
        charge(out, st.phase, wl_dp_step_time(m, l, s, &st, &out->coef));
        out->steps++;
        if (st.kind == WL_DP_COMPUTE) {
            double v = (double)wl_dp_vp_ratio(m, st.n);
            useful += (double)st.n * st.ops;
            slots += v * (double)m->procs * st.ops;
        }
    }
    out->counts = *wl_dp_sched_counts(s);
    out->util = slots > 0.0 ? useful / slots : 0.0;
    wl_dp_layout_free(l);
    wl_dp_sched_free(s);
}
