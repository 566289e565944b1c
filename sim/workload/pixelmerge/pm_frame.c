/* pm_frame.c — one frame: local rendering, merge, timing (seed 003 §2–5).
 *
 * Every piece of work is described once, as named operation counts
 * (span_ops, zbuf_ops; the merge's in pm_replay.c), and charged once: on
 * a machine to its processors, which price it by their kind's cost table
 * and are the frame's clock (the barrier is when the last one is free,
 * the phase times are their busy time per phase); without a machine
 * (tests of the algorithm alone) it is priced by the linear cost model
 * of pm_frame.h.  Every product saturates instead of wrapping.  The
 * merged image is compared with the serial render (P = 1, same polygons
 * and ids) when check_image is set.
 */
#include "sim/workload/pixelmerge/pm_frame.h"
#include "sim/workload/pixelmerge/pm_rung_frame.h"
#include <string.h>

static SimTime add(SimTime a, SimTime b)
{
    return sim_time_add_sat(a, b);
}

/* The counts of a processor's local phases, named as wl_pm_cost_ops:
 * the one description of the work, priced by the processor's kind on a
 * machine or by a WlPmCosts (local_price) without one. */
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

static const WlPmUnit local_units[] = {
    {"polygon", G_STRUCT_OFFSET(WlPmCosts, polygon)},
    {"span", G_STRUCT_OFFSET(WlPmCosts, span)},
    {"insert_step", G_STRUCT_OFFSET(WlPmCosts, insert_step)},
    {"pixel", G_STRUCT_OFFSET(WlPmCosts, pixel)},
    {"zcompare", G_STRUCT_OFFSET(WlPmCosts, zcompare)},
    {"scanline", G_STRUCT_OFFSET(WlPmCosts, scanline)},
    {"zbuf_init", G_STRUCT_OFFSET(WlPmCosts, zbuf_init)},
    {NULL, 0}};

/* The named counts o[0 .. n-1] at c's prices, saturating. */
static SimTime local_price(const WlPmCosts *c, const MachOp *o, guint n)
{
    return wl_pm_price(c, local_units, o, n);
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
    WlPmWpa *w = NULL;
    if (s->images.kind != WL_PM_IMAGES_SCENE) {
        WlPmImageSet *one = wl_pm_images_make(&s->images, &cam, &v, 1,
                                              s->comp.op);
        k = one->counts[0];
        wl_pm_images_free(one);
    } else {
        w = wl_pm_render_local(&v, flat, 0, 1, WL_PM_SPLIT_BLOCK, &k);
    }
    MachOp so[3], zo[4];
    SimTime t = add(local_price(c, so, span_ops(&k, TRUE, so)),
                    local_price(c, zo, zbuf_ops(&k, resolution, FALSE, zo)));
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
    SceneCamera cam;
    WlPmImageSet *set; /* block images (local, counts borrowed), or NULL */
} Local;

static void render_all(Local *l, const Scene *scene, guint frame,
                       const WlPmSetup *s)
{
    guint n = s->procs, N = s->resolution;
    l->flat = scene_flatten(scene);
    l->cam = scene_camera_at(scene, frame);
    l->view = rast_view_for_camera(&l->cam, N, N);
    l->view.cull_back = s->cull_back;
    l->view.span_rule = s->span_rule;
    l->rows = g_new0(uint64_t, N);
    l->set = NULL;
    if (s->images.kind != WL_PM_IMAGES_SCENE) {
        l->set = wl_pm_images_make(&s->images, &l->cam, &l->view, n,
                                   s->comp.op);
        l->local = l->set->local;
        l->counts = l->set->counts;
    } else {
        l->local = g_new0(WlPmWpa *, n);
        l->counts = g_new0(WlPmCounts, n);
    }
    for (guint p = 0; p < n; p++) {
        if (!l->set)
            l->local[p] = wl_pm_render_local(&l->view, l->flat, p, n,
                                             s->split, &l->counts[p]);
        wl_pm_wpa_add_row_counts(l->local[p], l->rows);
    }
}

static void local_clear(Local *l, guint n)
{
    for (guint p = 0; !l->set && p < n; p++)
        wl_pm_wpa_free(l->local[p]);
    if (l->set) {
        wl_pm_images_free(l->set);
    } else {
        g_free(l->local);
        g_free(l->counts);
    }
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

/* The engine phases of a frame: span, zbuf, merge. */
enum { PH_SPAN, PH_ZBUF, PH_MERGE, N_PH };

/* Processor p's local phases, charged once: to machine processor
 * procs[p] when there are processors (its busy time per phase is the
 * record), else priced at c into out->busy[p].  *end gets when p's
 * local work ends; the two phase times go into t[2]. */
static void local_proc(const Local *l, guint p, const WlPmSetup *s,
                       const WlPmCosts *c, MachProc *const *procs,
                       const unsigned *ph, SimTime *t, WlPmFrameOut *out)
{
    gboolean full = s->scheme == WL_PM_ZBUF_EXC;
    MachOp o[2][4];
    guint n[2] = {span_ops(&l->counts[p], !full, o[0]),
                  zbuf_ops(&l->counts[p], s->resolution, full, o[1])};
    for (int i = 0; i < 2; i++) {
        if (procs) {
            SimTime before = mach_proc_busy_phase(procs[p], ph[i]);
            mach_proc_compute_ops(procs[p], o[i], n[i], ph[i], NULL, NULL,
                                  NULL);
            t[i] = mach_proc_busy_phase(procs[p], ph[i]) - before;
        } else {
            t[i] = local_price(c, o[i], n[i]);
            sim_busy_add(&out->busy[p], ph[i], t[i]);
        }
    }
}

/* The local phases of every processor from `base`; returns the barrier:
 * when the last processor is free (its machine processor's free time,
 * or base + its priced work without processors).  span_ms and zbuf_ms
 * are the largest processor's time in the phase. */
static SimTime local_phases(const Local *l, const WlPmSetup *s,
                            const WlPmCosts *c, MachProc *const *procs,
                            const unsigned *ph, SimTime base, WlPmFrameOut *out)
{
    SimTime barrier = base, span_max = 0, zbuf_max = 0;
    for (guint p = 0; p < s->procs; p++) {
        SimTime t[2];
        local_proc(l, p, s, c, procs, ph, t, out);
        span_max = MAX(span_max, t[0]);
        zbuf_max = MAX(zbuf_max, t[1]);
        barrier = MAX(barrier, procs ? mach_proc_free_at(procs[p])
                                     : add(base, add(t[0], t[1])));
    }
    out->span_ms = sim_time_to_ms(span_max);
    out->zbuf_ms = sim_time_to_ms(zbuf_max);
    return barrier;
}

/* With processors: their busy time per phase (N_PH per processor), read
 * before the frame (start[]) or added to out->busy after it. */
static void procs_busy(MachProc *const *procs, guint n, const unsigned *ph,
                       SimTime *start, WlPmFrameOut *out)
{
    for (guint p = 0; procs && p < n; p++)
        for (int i = 0; i < N_PH; i++) {
            SimTime b = mach_proc_busy_phase(procs[p], ph[i]);
            if (out)
                sim_busy_add(&out->busy[p], ph[i], b - start[p * N_PH + i]);
            else
                start[p * N_PH + i] = b;
        }
}

/* Pixels z-buffered per owner: the partition's, or without one (the
 * compositing schemes) the pixels each process holds at the end. */
static double owner_imbalance(const Local *l, const WlPmMerge *m,
                              const WlPmPartition *part)
{
    guint n = m->n_procs;
    uint64_t *load = g_new(uint64_t, n);
    if (part)
        wl_pm_partition_loads(part, l->rows, load);
    for (guint p = 0; !part && p < n; p++)
        load[p] = wl_pm_wpa_len(m->held[p]);
    double v = wl_pm_load_imbalance(load, n);
    g_free(load);
    return v;
}

static void merge_metrics(const Local *l, const WlPmSetup *s,
                          const WlPmMerge *m, const WlPmPartition *part,
                          WlPmFrameOut *out)
{
    guint n = s->procs;
    out->polygons = l->set ? 0 : scene_mesh_n_polys(l->flat);
    out->counts = g_memdup2(l->counts, n * sizeof *l->counts);
    out->active = g_new(uint64_t, n);
    for (guint p = 0; p < n; p++) {
        if (l->set) /* a block's polygons: its own, or the block itself */
            out->polygons += l->counts[p].polygons;
        out->tpg += l->counts[p].rc.pixels;
        out->active[p] = wl_pm_wpa_len(l->local[p]);
    }
    out->tpf = wl_pm_frame_count(m->image);
    out->concurrent_volume = m->concurrent_volume;
    out->merge_bytes = m->total_bytes;
    out->merge_msgs = m->total_msgs;
    for (guint i = 0; i < m->steps->len; i++) {
        const WlPmStep *st = g_ptr_array_index(m->steps, i);
        for (guint j = 0; st->exchange && j < st->n_msgs; j++)
            out->merge_records += st->msg[j].pixels;
    }
    out->load_imbalance = wl_pm_load_imbalance(m->merge_ops, n);
    out->partition_imbalance = owner_imbalance(l, m, part);
}

/* The merge of the frame's local images: Kurç's scheme on a scanline
 * partition (*part), or a compositing scheme (*comp, *part NULL); the
 * image checked as check_image says. */
static WlPmMerge *merge_frame(const Local *l, const WlPmSetup *s,
                              WlPmPartition **part, WlPmComposite **comp,
                              WlPmFrameOut *out)
{
    guint n = s->procs;
    WlPmMerge *m;
    *part = NULL;
    *comp = NULL;
    if (wl_pm_scheme_composites(s->scheme)) {
        *comp = wl_pm_composite_run(s->scheme, &s->comp, l->local, n, &s->fmt);
        m = (*comp)->merge;
        out->stages = (*comp)->stages;
    } else {
        *part = wl_pm_partition_new(s->balance, n, l->rows, s->resolution);
        m = wl_pm_merge_run(s->scheme, l->local, n, *part, &s->fmt);
    }
    if (!s->check_image)
        return m;
    out->image_checked = TRUE;
    if (*comp && s->comp.op == WL_PM_OP_OVER) {
        double *ref =
            wl_pm_over_serial(l->local, n, s->comp.order, s->comp.opacity);
        gsize len = (gsize)s->resolution * s->resolution * 4;
        out->image_ok = wl_pm_over_diff(ref, (*comp)->rgba, len) < 0;
        g_free(ref);
    } else if (!l->set) {
        out->image_ok = image_matches(l, m->image);
    }
    if (l->set && (out->image_ok || s->comp.op == WL_PM_OP_Z))
        out->image_ok = wl_pm_images_match(&s->images, l->set, &l->cam,
                                           &l->view, s->comp.op, *comp);
    return m;
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
    if (s->rung != WL_PM_RUNG_PIXELS)
        return wl_pm_rung_frame_run(net, procs, frame, scene, s, c, out, err);
    guint n = s->procs;
    SimEngine *eng = net_engine(net);
    memset(out, 0, sizeof *out);
    out->busy = g_new0(SimBusy, n);
    for (guint p = 0; p < n; p++)
        sim_busy_init(&out->busy[p]);
    Local l;
    render_all(&l, scene, frame, s);
    WlPmSetup fs = *s; /* block images: their order from the view */
    if (l.set)
        fs.comp.order = l.set->order;
    s = &fs;
    WlPmPartition *part;
    WlPmComposite *comp;
    WlPmMerge *m = merge_frame(&l, s, &part, &comp, out);
    merge_metrics(&l, s, m, part, out);
    if (s->keep_image)
        out->image = frame_image(m->image);
    const unsigned ph[N_PH] = {sim_engine_phase(eng, "span"),
                               sim_engine_phase(eng, "zbuf"),
                               sim_engine_phase(eng, "merge")};
    SimTime *start = g_new(SimTime, (gsize)n * N_PH);
    procs_busy(procs, n, ph, start, NULL);
    SimTime base = sim_now(eng);
    SimTime barrier = local_phases(&l, s, c, procs, ph, base, out);
    SimTime *ready = g_new(SimTime, n);
    for (guint p = 0; p < n; p++)
        ready[p] = barrier;
    WlPmReplayOut ro = {0};
    WlPmReplayRig rig = {.net = net,
                         .procs = procs,
                         .costs = &c->merge,
                         .ready = ready,
                         .busy = procs ? NULL : out->busy,
                         .phase = ph[PH_MERGE],
                         .bal = part && s->scheme != WL_PM_ZBUF_EXC
                                    ? s->balance
                                    : WL_PM_BAL_STRIPS,
                         .height = s->resolution};
    gboolean ok = wl_pm_replay(&rig, m, &ro, err);
    procs_busy(procs, n, ph, start, out);
    if (ok && !sim_engine_cut(eng)) { /* a frame run.until cut: no times */
        out->merge_ms = sim_time_to_ms(ro.end - barrier);
        out->frame_ms = sim_time_to_ms(ro.end - base);
    }
    g_free(start);
    wl_pm_replay_out_clear(&ro);
    g_free(ready);
    if (comp)
        wl_pm_composite_free(comp);
    else
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
