/* pm_rung_frame.c — a compositing frame at the runs or counts rung
 * (pm_rung_frame.h): the rung's images, the plan run on them
 * (pm_rung.c), the replay (pm_replay.c).
 */
#include "sim/workload/pixelmerge/pm_rung_frame.h"
#include "sim/workload/pixelmerge/pm_images.h"
#include <string.h>

/* The volume's box (pm_images.c's). */
static const Vec3 box_lo = {-1, -1, -1}, box_hi = {1, 1, 1};

enum { SAMPLES = 8 }; /* sample rays a side of a footprint */

/* Block p's counts image: its footprint holding the sampled fraction. */
static WlPmRungImage *block_counts(const WlPmGrid *g, const WlPmRays *r,
                                   guint p)
{
    WlPmRungImage *im =
        wl_pm_rung_image_new(WL_PM_RUNG_COUNTS, r->width, r->height);
    WlPmRect f;
    if (!wl_pm_block_rect(g, r, p, &f))
        return im;
    Vec3 lo, hi, o, d;
    wl_pm_grid_block(g, p, &lo, &hi);
    guint hit = 0, w = f.x1 - f.x0, h = f.y1 - f.y0;
    for (guint i = 0; i < SAMPLES; i++)
        for (guint j = 0; j < SAMPLES; j++) {
            double t0, t1;
            wl_pm_ray(r, f.x0 + (2 * i + 1) * w / (2 * SAMPLES),
                      f.y0 + (2 * j + 1) * h / (2 * SAMPLES), &o, &d);
            hit += wl_pm_ray_box(o, d, lo, hi, &t0, &t1);
        }
    WlPmCover c = {f.x0, f.y0, f.x1 - 1, f.y1 - 1,
                   (double)w * h * hit / (SAMPLES * SAMPLES)};
    if (hit)
        wl_pm_rung_add_rect(im, &c);
    return im;
}

/* The frame's images at the rung into im[n]; *order (g_free, NULL:
 * processor order) the visibility order of block images. */
static void make_images(const Scene *scene, guint frame, const WlPmSetup *s,
                        WlPmRungImage **im, guint **order)
{
    guint n = s->procs, N = s->resolution;
    SceneCamera cam = scene_camera_at(scene, frame);
    RastView v = rast_view_for_camera(&cam, N, N);
    v.cull_back = s->cull_back;
    v.span_rule = s->span_rule;
    *order = NULL;
    if (s->rung == WL_PM_RUNG_COUNTS) {
        WlPmGrid g;
        WlPmRays r;
        wl_pm_grid_init(&g, n, box_lo, box_hi);
        wl_pm_rays_init(&r, &cam, N, N);
        *order = g_new(guint, n);
        wl_pm_grid_order(&g, &cam, *order);
        for (guint p = 0; p < n; p++)
            im[p] = block_counts(&g, &r, p);
        return;
    }
    if (s->images.kind != WL_PM_IMAGES_SCENE) {
        WlPmImageSet *set =
            wl_pm_images_make(&s->images, &cam, &v, n, s->comp.op);
        *order = g_memdup2(set->order, n * sizeof *set->order);
        for (guint p = 0; p < n; p++)
            im[p] = wl_pm_rung_from_wpa(s->rung, set->local[p]);
        wl_pm_images_free(set);
        return;
    }
    SceneMesh *flat = scene_flatten(scene);
    for (guint p = 0; p < n; p++) {
        WlPmCounts k;
        WlPmWpa *w = wl_pm_render_local(&v, flat, p, n, s->split, &k);
        im[p] = wl_pm_rung_from_wpa(s->rung, w);
        wl_pm_wpa_free(w);
    }
    scene_mesh_free(flat);
}

static void fill_metrics(const WlPmMerge *m, WlPmRungImage *const *im, guint n,
                         WlPmFrameOut *out)
{
    out->counts = g_new0(WlPmCounts, n);
    out->active = g_new(uint64_t, n);
    for (guint p = 0; p < n; p++) {
        out->active[p] = wl_pm_rung_image_active(im[p]);
        out->tpg += out->active[p];
    }
    out->concurrent_volume = m->concurrent_volume;
    out->merge_bytes = m->total_bytes;
    out->merge_msgs = m->total_msgs;
    for (guint i = 0; i < m->steps->len; i++) {
        const WlPmStep *st = g_ptr_array_index(m->steps, i);
        for (guint j = 0; j < st->n_msgs; j++)
            out->merge_records += st->msg[j].pixels;
    }
    out->load_imbalance = wl_pm_load_imbalance(m->merge_ops, n);
}

/* Replays m from now on net: procs' busy time in `phase` (or engine
 * events priced at c) into out->busy; the merge's time into out. */
static gboolean replay(NetNet *net, MachProc *const *procs, const WlPmSetup *s,
                       const WlPmCosts *c, const WlPmMerge *m,
                       WlPmFrameOut *out, GError **err)
{
    guint n = s->procs;
    SimEngine *eng = net_engine(net);
    unsigned ph = sim_engine_phase(eng, "merge");
    SimTime base = sim_now(eng), *before = g_new0(SimTime, n);
    SimTime *ready = g_new(SimTime, n);
    for (guint p = 0; p < n; p++) {
        ready[p] = base;
        before[p] = procs ? mach_proc_busy_phase(procs[p], ph) : 0;
    }
    WlPmReplayOut ro = {0};
    WlPmReplayRig rig = {.net = net,
                         .procs = procs,
                         .costs = &c->merge,
                         .ready = ready,
                         .busy = procs ? NULL : out->busy,
                         .phase = ph,
                         .bal = WL_PM_BAL_STRIPS,
                         .height = s->resolution};
    gboolean ok = wl_pm_replay(&rig, m, &ro, err);
    for (guint p = 0; procs && p < n; p++)
        sim_busy_add(&out->busy[p], ph,
                     mach_proc_busy_phase(procs[p], ph) - before[p]);
    if (ok && !sim_engine_cut(eng)) {
        out->merge_ms = sim_time_to_ms(ro.end - base);
        out->frame_ms = out->merge_ms;
    }
    wl_pm_replay_out_clear(&ro);
    g_free(ready);
    g_free(before);
    return ok;
}

gboolean wl_pm_rung_frame_run(NetNet *net, MachProc *const *procs, guint frame,
                              const Scene *scene, const WlPmSetup *s,
                              const WlPmCosts *c, WlPmFrameOut *out,
                              GError **err)
{
    guint n = s->procs;
    memset(out, 0, sizeof *out);
    out->busy = g_new0(SimBusy, n);
    for (guint p = 0; p < n; p++)
        sim_busy_init(&out->busy[p]);
    WlPmRungImage **im = g_new(WlPmRungImage *, n);
    guint *order;
    make_images(scene, frame, s, im, &order);
    WlPmCompose comp = s->comp;
    if (order)
        comp.order = order;
    WlPmMerge *m =
        wl_pm_rung_run(s->scheme, &comp, im, n, &s->fmt, &out->stages);
    fill_metrics(m, im, n, out);
    for (guint p = 0; p < n; p++)
        wl_pm_rung_image_free(im[p]);
    g_free(im);
    gboolean ok = replay(net, procs, s, c, m, out, err);
    wl_pm_rung_merge_free(m);
    g_free(order);
    return ok;
}
