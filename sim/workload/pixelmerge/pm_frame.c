/* pm_frame.c — one frame: local rendering, merge, timing (seed 003 §2–5).
 *
 * Counted operations become time by the linear cost model of pm_frame.h;
 * every product saturates instead of wrapping (a saturated time makes the
 * replay report an overflow).  The merged image is compared with the
 * serial render (P = 1, same polygons and ids) when check_image is set.
 */
#include "sim/workload/pixelmerge/pm_frame.h"
#include <string.h>

static SimTime add(SimTime a, SimTime b)
{
    return sim_time_add_sat(a, b);
}

static SimTime span_time(const WlPmCounts *k, const WlPmCosts *c,
                         gboolean sorted)
{
    SimTime t = add(sim_time_mul_sat(c->polygon, k->polygons),
                    sim_time_mul_sat(c->span, k->rc.spans));
    return sorted ? add(t, sim_time_mul_sat(c->insert_step, k->insert_steps))
                  : t;
}

static SimTime zbuf_time(const WlPmCounts *k, const WlPmCosts *c, guint n,
                         gboolean full)
{
    SimTime t = add(sim_time_mul_sat(c->pixel, k->rc.pixels),
                    sim_time_mul_sat(c->scanline, n));
    if (full)
        return add(t, add(sim_time_mul_sat(c->zbuf_init, (uint64_t)n * n),
                          sim_time_mul_sat(c->zcompare, k->rc.pixels)));
    return add(t, sim_time_mul_sat(c->zcompare, k->rc.zcompares));
}

double wl_pm_serial_ms(const Scene *scene, const WlPmSetup *s,
                       const WlPmCosts *c, double *insert_ms)
{
    guint resolution = s->resolution;
    SceneMesh *flat = scene_flatten(scene);
    SceneCamera cam = scene_camera_at(scene, 0);
    RastView v = rast_view_for_camera(&cam, resolution, resolution);
    v.cull_back = s->cull_back;
    v.span_rule = s->span_rule;
    WlPmCounts k;
    WlPmWpa *w = wl_pm_render_local(&v, flat, 0, 1, WL_PM_SPLIT_BLOCK, &k);
    SimTime t =
        add(span_time(&k, c, TRUE), zbuf_time(&k, c, resolution, FALSE));
    if (insert_ms)
        *insert_ms =
            sim_time_to_ms(sim_time_mul_sat(c->insert_step, k.insert_steps));
    wl_pm_wpa_free(w);
    scene_mesh_free(flat);
    return sim_time_to_ms(t);
}

typedef struct {
    WlPmWpa **local;
    WlPmCounts *counts;
    uint64_t *rows; /* global active pixels per scanline */
    SceneMesh *flat;
    RastView view;
} Local;

static void render_all(Local *l, const Scene *scene, guint frame,
                       const WlPmSetup *s)
{
    guint n = s->procs, N = s->resolution;
    l->flat = scene_flatten(scene);
    SceneCamera cam = scene_camera_at(scene, frame);
    l->view = rast_view_for_camera(&cam, N, N);
    l->view.cull_back = s->cull_back;
    l->view.span_rule = s->span_rule;
    l->local = g_new0(WlPmWpa *, n);
    l->counts = g_new0(WlPmCounts, n);
    l->rows = g_new0(uint64_t, N);
    for (guint p = 0; p < n; p++) {
        l->local[p] = wl_pm_render_local(&l->view, l->flat, p, n, s->split,
                                         &l->counts[p]);
        wl_pm_wpa_add_row_counts(l->local[p], l->rows);
    }
}

static void local_clear(Local *l, guint n)
{
    for (guint p = 0; p < n; p++)
        wl_pm_wpa_free(l->local[p]);
    g_free(l->local);
    g_free(l->counts);
    g_free(l->rows);
    scene_mesh_free(l->flat);
}

/* The merged frame as an RGB image (empty pixels black), row 0 on top. */
static RastImage *frame_image(const WlPmFrame *f)
{
    RastImage *img = rast_image_new((int)f->width, (int)f->height);
    for (guint i = 0; i < f->width * f->height; i++) {
        uint32_t c = f->px[i].poly == WL_PM_EMPTY ? 0 : f->px[i].color;
        img->rgb[3 * i] = (uint8_t)(c >> 16);
        img->rgb[3 * i + 1] = (uint8_t)(c >> 8);
        img->rgb[3 * i + 2] = (uint8_t)c;
    }
    return img;
}

static gboolean image_matches(const Local *l, const WlPmFrame *img)
{
    WlPmCounts k;
    WlPmWpa *w =
        wl_pm_render_local(&l->view, l->flat, 0, 1, WL_PM_SPLIT_BLOCK, &k);
    WlPmFrame *f = wl_pm_frame_new(img->width, img->height);
    wl_pm_frame_put_wpa(f, w);
    gboolean ok = wl_pm_frame_diff(f, img) < 0;
    wl_pm_frame_free(f);
    wl_pm_wpa_free(w);
    return ok;
}

/* The counts of span_time() / zbuf_time(), named as wl_pm_cost_ops. */
static guint span_ops(const WlPmCounts *k, gboolean sorted, MachOp *o)
{
    o[0] = (MachOp){"polygon", k->polygons};
    o[1] = (MachOp){"span", k->rc.spans};
    o[2] = (MachOp){"insert_step", k->insert_steps};
    return sorted ? 3 : 2;
}

static guint zbuf_ops(const WlPmCounts *k, guint n, gboolean full, MachOp *o)
{
    o[0] = (MachOp){"pixel", k->rc.pixels};
    o[1] = (MachOp){"scanline", n};
    o[2] = (MachOp){"zcompare", full ? k->rc.pixels : k->rc.zcompares};
    o[3] = (MachOp){"zbuf_init", (uint64_t)n * n};
    return full ? 4 : 3;
}

/* Gives processor p its local phases as named counts (the same times). */
static void local_compute(MachProc *proc, const WlPmCounts *k, guint n,
                          gboolean full, unsigned ph_span, unsigned ph_zbuf)
{
    MachOp o[4];
    mach_proc_compute_ops(proc, o, span_ops(k, !full, o), ph_span, NULL, NULL,
                          NULL);
    mach_proc_compute_ops(proc, o, zbuf_ops(k, n, full, o), ph_zbuf, NULL, NULL,
                          NULL);
}

/* Local phases into busy[]; returns the barrier time (slowest node). */
static SimTime local_phases(const Local *l, const WlPmSetup *s,
                            const WlPmCosts *c, SimEngine *eng,
                            MachProc *const *procs, WlPmFrameOut *out)
{
    gboolean full = s->scheme == WL_PM_ZBUF_EXC;
    unsigned ph_span = sim_engine_phase(eng, "span");
    unsigned ph_zbuf = sim_engine_phase(eng, "zbuf");
    SimTime barrier = 0, span_max = 0, zbuf_max = 0;
    for (guint p = 0; p < s->procs; p++) {
        SimTime ts = span_time(&l->counts[p], c, !full);
        SimTime tz = zbuf_time(&l->counts[p], c, s->resolution, full);
        sim_busy_add(&out->busy[p], ph_span, ts);
        sim_busy_add(&out->busy[p], ph_zbuf, tz);
        if (procs)
            local_compute(procs[p], &l->counts[p], s->resolution, full, ph_span,
                          ph_zbuf);
        span_max = MAX(span_max, ts);
        zbuf_max = MAX(zbuf_max, tz);
        barrier = MAX(barrier, add(ts, tz));
    }
    out->span_ms = sim_time_to_ms(span_max);
    out->zbuf_ms = sim_time_to_ms(zbuf_max);
    return barrier;
}

static void merge_metrics(const Local *l, const WlPmSetup *s,
                          const WlPmMerge *m, const WlPmPartition *part,
                          WlPmFrameOut *out)
{
    guint n = s->procs;
    out->polygons = scene_mesh_n_polys(l->flat);
    out->counts = g_memdup2(l->counts, n * sizeof *l->counts);
    out->active = g_new(uint64_t, n);
    for (guint p = 0; p < n; p++) {
        out->tpg += l->counts[p].rc.pixels;
        out->active[p] = wl_pm_wpa_len(l->local[p]);
    }
    out->tpf = wl_pm_frame_count(m->image);
    out->concurrent_volume = m->concurrent_volume;
    out->merge_bytes = m->total_bytes;
    out->load_imbalance = wl_pm_load_imbalance(m->merge_ops, n);
    uint64_t *load = g_new(uint64_t, n);
    wl_pm_partition_loads(part, l->rows, load);
    out->partition_imbalance = wl_pm_load_imbalance(load, n);
    g_free(load);
}

gboolean wl_pm_frame_run(NetNet *net, const Scene *scene, const WlPmSetup *s,
                         const WlPmCosts *c, WlPmFrameOut *out, GError **err)
{
    return wl_pm_frame_run_procs(net, NULL, 0, scene, s, c, out, err);
}

gboolean wl_pm_frame_run_procs(NetNet *net, MachProc *const *procs, guint frame,
                               const Scene *scene, const WlPmSetup *s,
                               const WlPmCosts *c, WlPmFrameOut *out,
                               GError **err)
{
    guint n = s->procs;
    SimEngine *eng = net_engine(net);
    memset(out, 0, sizeof *out);
    out->busy = g_new0(SimBusy, n);
    for (guint p = 0; p < n; p++)
        sim_busy_init(&out->busy[p]);
    Local l;
    render_all(&l, scene, frame, s);
    WlPmPartition *part =
        wl_pm_partition_new(s->balance, n, l.rows, s->resolution);
    WlPmMerge *m = wl_pm_merge_run(s->scheme, l.local, n, part, &s->fmt);
    merge_metrics(&l, s, m, part, out);
    if (s->check_image) {
        out->image_checked = TRUE;
        out->image_ok = image_matches(&l, m->image);
    }
    if (s->keep_image)
        out->image = frame_image(m->image);
    SimTime base = sim_now(eng);
    SimTime barrier = add(base, local_phases(&l, s, c, eng, procs, out));
    SimTime *ready = g_new(SimTime, n);
    for (guint p = 0; p < n; p++)
        ready[p] = barrier;
    WlPmReplayOut ro = {0};
    WlPmBalance bal =
        s->scheme == WL_PM_ZBUF_EXC ? WL_PM_BAL_STRIPS : s->balance;
    gboolean ok =
        wl_pm_replay_procs(net, procs, m, bal, s->resolution, &c->merge, ready,
                           out->busy, sim_engine_phase(eng, "merge"), &ro, err);
    if (ok && !sim_engine_cut(eng)) { /* a frame run.until cut: no times */
        out->merge_ms = sim_time_to_ms(ro.end - barrier);
        out->frame_ms = sim_time_to_ms(ro.end - base);
    }
    wl_pm_replay_out_clear(&ro);
    g_free(ready);
    wl_pm_merge_free(m);
    wl_pm_partition_free(part);
    local_clear(&l, n);
    return ok;
}

void wl_pm_frame_out_clear(WlPmFrameOut *out, guint procs)
{
    for (guint p = 0; out->busy && p < procs; p++)
        sim_busy_clear(&out->busy[p]);
    g_free(out->busy);
    out->busy = NULL;
    g_free(out->counts);
    out->counts = NULL;
    g_free(out->active);
    out->active = NULL;
    rast_image_free(out->image);
    out->image = NULL;
}
