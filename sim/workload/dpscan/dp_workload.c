/* dp_workload.c — workload `dpscan` (dp_workload.h): parses its section,
 * plans its machine (workload.model and workload.processors as
 * shorthands for the machine: section), reads the costs from the dpscan:
 * section of the machine the runner built (dp_model.h), renders each
 * frame with the data-parallel renderer on the array layer
 * (dp_render.h), writes the image under --out, and plays the frame's
 * counted phase times on the machine (one piece of work per phase on the
 * SIMD array, or on every SPMD node) so the result has its busy times.
 * O(render) per frame.
 */
#include "sim/workload/dpscan/dp_workload.h"
#include "sim/scene/scene_cfg.h"
#include "sim/machine/machine.h"
#include "sim/workload/dpscan/dp_color.h"
#include "sim/workload/dpscan/dp_model.h"
#include "sim/workload/dpscan/dp_render.h"
#include "sim/raster/scan.h"

/* The partition when neither workload.processors nor a machine: section
 * gives one (seed 004's smallest CM-200). */
#define DP_DEFAULT_PROCS 16384

typedef struct {
    const char *model;
    const CfgNode *model_at; /* workload.model, borrowed while the runner
                                loads; NULL when not given */
    uint64_t procs;          /* workload.processors; 0 when not given */
    const CfgNode *parts_at; /* workload.partitions, as model_at; NULL */
    GArray *parts;           /* uint64_t: workload.partitions (may be
                                empty), each costed too */
    int64_t width, height;
    WlDpRenderOpts ro;
    float pal[WL_DP_COLORS][3];
    gboolean formula; /* wire: formula (SPMD sends priced by dp_cost.h) */
} DpParams;

static gboolean parse_mode(const CfgNode *sec, DpParams *p, GError **err)
{
    static const char *names[WL_DP_N_MODES + 1];
    for (int m = 0; m < WL_DP_N_MODES; m++)
        names[m] = wl_dp_mode_name((WlDpMode)m);
    int mode = WL_DP_MODE_GOURAUD;
    if (!cfg_get_enum(sec, "mode", FALSE, names, &mode, err))
        return FALSE;
    p->ro.mode = (WlDpMode)mode;
    static const char *const wires[] = {"network", "formula", NULL};
    int wire = 0;
    if (!cfg_get_enum(sec, "wire", FALSE, wires, &wire, err))
        return FALSE;
    p->formula = wire == 1;
    const CfgNode *pal = cfg_get(sec, "palette");
    wl_dp_palette_default(p->pal);
    return !pal || wl_dp_palette_from_cfg(pal, p->pal, err);
}

/* workload.partitions: a list of processor counts in [1, 2^32 - 1]. */
static gboolean parse_parts(const CfgNode *sec, DpParams *p, GError **err)
{
    const CfgNode *l = p->parts_at = cfg_get(sec, "partitions");
    if (!l)
        return TRUE;
    if (cfg_kind(l) != CFG_SEQ || cfg_seq_len(l) == 0) {
        cfg_error(err, l, "no list of partitions", "partitions: [n, ...]");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(l); i++) {
        uint64_t n = 0;
        GError *e = NULL;
        const char *v = cfg_scalar(cfg_seq_at(l, i));
        if (!v || !cfg_parse_count(v, "partition", &n, &e) || n == 0 ||
            n > G_MAXUINT32) {
            g_clear_error(&e);
            cfg_error(err, cfg_seq_at(l, i), v ? v : "a non-scalar",
                      "a processor count in [1, 4294967295]");
            return FALSE;
        }
        g_array_append_val(p->parts, n);
    }
    return TRUE;
}

static void dp_free_params(void *params)
{
    DpParams *p = params;
    g_array_free(p->parts, TRUE);
    g_free(p);
}

static void *dp_parse(const CfgNode *sec, GError **err)
{
    DpParams *p = g_new0(DpParams, 1);
    p->parts = g_array_new(FALSE, FALSE, sizeof(uint64_t));
    p->model = "cm200";
    p->model_at = cfg_get(sec, "model");
    p->width = 1280;
    p->height = 1024;
    p->ro.buffer_factor = 0.25; /* configs/papers/ortega93/setup.yaml */
    p->ro.ops = wl_dp_ops_defaults();
    if (!cfg_get_str(sec, "model", FALSE, &p->model, err) ||
        !cfg_get_count(sec, "processors", FALSE, 1, G_MAXUINT32, &p->procs,
                       err) ||
        !cfg_get_int(sec, "width", FALSE, 1, RAST_MAX_SIDE, &p->width, err) ||
        !cfg_get_int(sec, "height", FALSE, 1, RAST_MAX_SIDE, &p->height, err) ||
        !cfg_get_double(sec, "buffer_factor", FALSE, 1e-6, 1e6,
                        &p->ro.buffer_factor, err) ||
        !parse_mode(sec, p, err) || !parse_parts(sec, p, err)) {
        dp_free_params(p);
        return NULL;
    }
    return p;
}

/* Own memory (WlOps.mem_bytes): the z-buffer and colour index (9 B a
 * pixel), the output image (3 B), and per virtual processor a span
 * count and the router's injection and receive counters (12 B). */
static double dp_mem_bytes(const void *params, GString *what)
{
    const DpParams *p = params;
    uint64_t procs = p->procs ? p->procs : DP_DEFAULT_PROCS;
    g_string_append_printf(what, "%" G_GUINT64_FORMAT " processors, %"
                           G_GINT64_FORMAT " x %" G_GINT64_FORMAT " pixels",
                           procs, p->width, p->height);
    for (guint i = 0; i < p->parts->len; i++)
        procs += g_array_index(p->parts, uint64_t, i);
    return (double)p->width * (double)p->height * 12.0 + (double)procs * 12.0;
}

static void add_metrics(SimResult *out, const WlDpTarget *t,
                        const WlDpImage *img, const WlDpVmCounts *c,
                        uint64_t n_polys)
{
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++) {
        char *name = g_strdup_printf("%s_s", wl_dp_phase_name(ph));
        sim_result_set_metric(out, name, sim_time_to_s(t->phase[ph]), "s");
        g_free(name);
    }
    double s = sim_time_to_s(t->total);
    sim_result_set_metric(out, "polygons", (double)n_polys, "");
    sim_result_set_metric(out, "polygons_per_s", (double)n_polys / s, "1/s");
    sim_result_set_metric(out, "steps", (double)c->steps, "");
    sim_result_set_metric(out, "scan_iters", (double)img->scan_iters, "");
    sim_result_set_metric(out, "pixel_iters", (double)img->pixel_iters, "");
    sim_result_set_metric(out, "flushes", (double)img->flushes, "");
    sim_result_set_metric(out, "segments", (double)img->segments, "");
    sim_result_set_metric(out, "pixels", (double)img->pixels, "");
    sim_result_set_metric(out, "collisions", (double)c->collisions, "");
    sim_result_set_metric(out, "messages", (double)c->messages, "");
    sim_result_set_metric(out, "max_load", (double)t->max_load, "");
    if (t->m.arch == WL_DP_SPMD) {
        sim_result_set_metric(out, "router_wire_s",
                              sim_time_to_s(t->wire_total), "s");
        sim_result_set_metric(out, "router_soft_s",
                              sim_time_to_s(t->soft_total), "s");
    }
}

/* Per workload.partitions entry P (target[i]: the machine's own, 0, when
 * P is its partition): time_s@P and, per
 * model constant KEY, KEY_count@P (dp_cost.h: the frame time is the sum
 * of count x constant, plus the SPMD wire time). */
static void add_partition_metrics(SimResult *out, const WlDpVm *vm,
                                  const GArray *parts, const guint *target)
{
    for (guint i = 0; i < parts->len; i++) {
        const WlDpTarget *t = wl_dp_vm_target(vm, target[i]);
        uint64_t P = g_array_index(parts, uint64_t, i);
        char *name = g_strdup_printf("time_s@%" G_GUINT64_FORMAT, P);
        sim_result_set_metric(out, name, sim_time_to_s(t->total), "s");
        g_free(name);
        for (int c = 0; c < WL_DP_N_COSTS; c++) {
            uint64_t n = 0;
            for (int ph = 0; ph < WL_DP_N_PHASES; ph++)
                n += t->count[ph].n[c];
            name = g_strdup_printf("%s_count@%" G_GUINT64_FORMAT,
                                   wl_dp_cost_name((WlDpCost)c), P);
            sim_result_set_metric(out, name, (double)n, "");
            g_free(name);
        }
    }
}

/* The machine's data network at the run's fidelity, on a private engine:
 * each send's node pairs are injected at once (one message per pair of
 * msgs x msg_bytes) and the time to the last delivery, less the network's
 * message start-up (already in the model's net_latency), is the send's
 * wire time (dp_array.h WlDpWireFn).  The frame's
 * clock is not moved by it: the workload plays the counted phase times on
 * the machine afterwards. */
typedef struct {
    SimEngine *eng;
    NetNet *net;
    uint32_t first;     /* endpoint of node 0 */
    uint32_t msg_bytes; /* bytes of one message on the wire */
    GError *err;        /* the first failure, if any */
} DpWire;

static SimTime dp_wire(void *ctx, const WlDpTraffic *t)
{
    DpWire *w = ctx;
    if (w->err)
        return 0;
    SimTime t0 = sim_now(w->eng);
    for (size_t k = 0; k < t->n; k++)
        net_send(w->net, w->first + t->src[k], w->first + t->dst[k],
                 t->msgs[k] * w->msg_bytes, NULL, NULL, NULL);
    if (!sim_engine_run(w->eng, SIM_TIME_MAX, &w->err))
        return 0;
    /* The message start-up is the model's net_latency, charged apart. */
    SimTime d = sim_now(w->eng) - t0, st = net_params(w->net)->startup;
    return d > st ? d - st : 0;
}

/* A DpWire over mach's network, or NULL (SIMD: the router is the fitted
 * send_slice of the model, docs/validation.md; or no network built). */
static DpWire *dp_wire_new(MachMachine *mach, const WlDpMachine *m)
{
    NetNet *net = mach_net(mach);
    const MachKindInfo *k = mach_kind(mach, "node");
    if (m->arch != WL_DP_SPMD || !net || !k)
        return NULL;
    DpWire *w = g_new0(DpWire, 1);
    w->eng = sim_engine_new(1);
    w->net = net_new(w->eng, net_topo(net), net_params(net),
                     net_fidelity(net));
    w->first = k->first;
    w->msg_bytes = m->msg_bytes;
    return w;
}

static void dp_wire_free(DpWire *w)
{
    if (!w)
        return;
    net_free(w->net);
    sim_engine_free(w->eng);
    g_clear_error(&w->err);
    g_free(w);
}

static void frame_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng, (void)ctx, (void)arg;
}

/* Phase ph's work on processor q: its named counts (the names are the
 * model keys they multiply, dp_cost.h), priced here as the array layer
 * charged them, then the data network's time of the sends it bounded
 * (SPMD; a time).  `done` goes with the last piece. */
static void play_phase(MachProc *q, const WlDpTarget *t, int ph, unsigned id,
                       SimHandler done)
{
    const WlDpCounts *k = &t->count[ph];
    MachOp ops[WL_DP_N_COSTS];
    guint n = 0;
    for (int c = 0; c < WL_DP_N_COSTS; c++)
        if (k->n[c])
            ops[n++] = (MachOp){wl_dp_cost_path((WlDpCost)c), k->n[c]};
    SimTime cost = wl_dp_counts_price(&t->m, k) - k->wire;
    g_assert(cost + k->wire == t->phase[ph]); /* the counts are the charge */
    if (n)
        mach_proc_compute_priced(q, cost, ops, n, id, k->wire ? NULL : done,
                                 NULL, NULL);
    if (k->wire || !n)
        mach_proc_compute(q, k->wire, id, done, NULL, NULL);
}

/* Busy time per phase on the array, or on every node; the last piece
 * of work ends the frame (an event, so the clock reaches its end). */
static gboolean play(SimEngine *eng, MachMachine *mach, const WlDpTarget *t,
                     GError **err)
{
    const char *kind = t->m.arch == WL_DP_SIMD ? "array" : "node";
    const MachKindInfo *k = mach_kind(mach, kind);
    guint n = t->m.arch == WL_DP_SIMD ? 1 : (guint)t->m.procs;
    if (!k || k->count < n) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "machine %s: found %u '%s' processors, expected %u for "
                    "the dpscan model",
                    mach_name(mach), k ? k->count : 0, kind, n);
        return FALSE;
    }
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++) {
        unsigned id = sim_engine_phase(eng, wl_dp_phase_name(ph));
        for (guint i = 0; i < n; i++)
            play_phase(mach_proc_at(mach, k->first + i), t, ph, id,
                       ph == WL_DP_N_PHASES - 1 ? frame_done : NULL);
    }
    return sim_engine_run(eng, SIM_TIME_MAX, err);
}

/* The frame's image through the generic hook (DIR/frame.png, or
 * DIR/frame-NNNN.png with --frames all); nothing is built without --out. */
static gboolean write_image(const WlContext *ctx, const DpParams *p,
                            const WlDpImage *img, int frame, GError **err)
{
    if (!wl_wants_frame(ctx, frame))
        return TRUE;
    WlDpColorTable t;
    wl_dp_color_table(p->pal, &t);
    RastImage *rgb = wl_dp_color_image(img->index, img->width, img->height, &t);
    gboolean ok = wl_emit_frame(ctx, frame, rgb, err);
    rast_image_free(rgb);
    return ok;
}

/* One run's fixed parts: the machine, its dpscan costs at the machine's
 * partition and at each of workload.partitions (ms, targets in order),
 * the network pricing the sends (or NULL). */
typedef struct {
    const WlContext *ctx;
    const DpParams *p;
    MachMachine *mach;
    GArray *ms;    /* WlDpMachine */
    guint *target; /* per workload.partitions entry, its index in ms */
    DpWire *wire;
} DpRun;

static gboolean one_frame(const DpRun *r, int fr, SimResult *out,
                          GError **err)
{
    const WlContext *ctx = r->ctx;
    const DpParams *p = r->p;
    DpWire *wire = r->wire;
    int w = (int)p->width, h = (int)p->height;
    WlDpPolys *poly = wl_dp_polys_new(ctx->scene, fr, w, h, p->ro.mode, p->pal);
    WlDpVm *vm = wl_dp_vm_new((const WlDpMachine *)r->ms->data, r->ms->len,
                              (uint32_t)w, (uint32_t)h);
    if (wire)
        wl_dp_vm_set_wire(vm, 0, dp_wire, wire);
    WlDpImage *img = wl_dp_render(vm, poly, w, h, &p->ro);
    const WlDpTarget *t = wl_dp_vm_target(vm, 0);
    gboolean ok = TRUE;
    if (wire && wire->err) {
        g_propagate_error(err, wire->err);
        wire->err = NULL;
        ok = FALSE;
    }
    SimTime start = sim_now(ctx->eng);
    ok = ok && play(ctx->eng, r->mach, t, err);
    gboolean cut = sim_engine_cut(ctx->eng); /* run.until ended it */
    ok = ok && (cut || write_image(ctx, p, img, fr, err));
    if (ok && !cut) { /* the frame is the engine's: played, not summed */
        sim_result_add_frame(out, sim_now(ctx->eng) - start);
        wl_mark_frame(ctx->eng, (guint)fr, sim_now(ctx->eng));
        add_metrics(out, t, img, wl_dp_vm_counts(vm), poly->n);
        add_partition_metrics(out, vm, p->parts, r->target);
    }
    wl_dp_image_free(img);
    wl_dp_vm_free(vm);
    wl_dp_polys_free(poly);
    return ok;
}

static gboolean dp_run(const WlContext *ctx, void *params, SimResult *out,
                       GError **err)
{
    DpParams *p = params;
    WlDpMachine m = {0};
    MachMachine *mach = ctx->machine;
    if (!wl_dp_machine_from_mach(mach, &m, err))
        return FALSE;
    DpRun r = {.ctx = ctx, .p = p, .mach = mach,
               .ms = g_array_new(FALSE, FALSE, sizeof(WlDpMachine))};
    g_array_append_val(r.ms, m);
    r.target = g_new0(guint, p->parts->len + 1);
    for (guint i = 0; i < p->parts->len; i++) {
        WlDpMachine mp = m;
        mp.procs = g_array_index(p->parts, uint64_t, i);
        if (mp.procs != m.procs) {
            r.target[i] = r.ms->len;
            g_array_append_val(r.ms, mp);
        }
    }
    DpWire *wire = r.wire = !p->formula ? dp_wire_new(mach, &m) : NULL;
    gboolean ok = TRUE;
    for (int fr = 0; ok && fr < ctx->frames && !sim_engine_cut(ctx->eng); fr++)
        ok = one_frame(&r, fr, out, err);
    if (ok) {
        mach_fill_result(mach, out);
        out->elapsed = sim_now(ctx->eng);
        out->comm_bytes = 0;
        out->comm_messages = 0;
        if (wire)
            net_fill_result(wire->net, out);
    }
    dp_wire_free(wire);
    g_array_free(r.ms, TRUE);
    g_free(r.target);
    return ok;
}

/* Every metric dp_run sets (add_metrics), in order; the first five are
 * "<phase>_s" for the phases of dp_array.h, checked by the runner. */
static const WlMetric dp_metrics[] = {
    {"transform_s", "s", "phase transform: the frame's counted time"},
    {"scan_s", "s", "phase scan: the frame's counted time"},
    {"pixel_s", "s", "phase pixel: the frame's counted time"},
    {"router_s", "s", "phase router: the frame's counted time"},
    {"display_s", "s", "phase display: the frame's counted time"},
    {"polygons", "", "polygons in the frame"},
    {"polygons_per_s", "1/s", "polygons / the frame's counted time"},
    {"steps", "", "data-parallel operations issued"},
    {"scan_iters", "", "scan-line iterations (one per scan line)"},
    {"pixel_iters", "", "pixel-loop iterations (longest buffered span, per flush)"},
    {"flushes", "", "flushes of the segment buffer"},
    {"segments", "", "span segments sent into the buffer"},
    {"pixels", "", "pixel messages into the z-buffer"},
    {"collisions", "", "router messages combined with an earlier one"},
    {"messages", "", "router messages sent"},
    {"max_load", "", "largest load of any router send"},
    {"router_wire_s", "s", "SPMD: the data network's time of all sends"},
    {"router_soft_s", "s", "SPMD: per-message software time of all sends"},
    /* with workload.partitions, per partition P (metrics.h: "@P") */
    {"time_s@P", "s", "the frame's counted time at P processors"},
    {"step_count@P", "", "at P: steps issued (x dpscan.step)"},
    {"op_count@P", "", "at P: VP slices x ops (x dpscan.op)"},
    {"scan_slice_count@P", "", "at P: VP slices of scans (x dpscan.scan_slice)"},
    {"news_slice_count@P", "", "at P: VP slices of NEWS moves (x dpscan.news_slice)"},
    {"send_setup_count@P", "", "at P, SIMD: arrays sent (x dpscan.send_setup)"},
    {"send_vp_count@P", "", "at P, SIMD: VP slices of arrays sent (x dpscan.send_vp)"},
    {"send_msg_count@P", "", "at P, SIMD: mean router loads (x dpscan.send_msg)"},
    {"send_slice_count@P", "", "at P, SIMD: router loads (x dpscan.send_slice)"},
    {"net_latency_count@P", "", "at P, SPMD: arrays sent (x dpscan.net_latency)"},
    {"msg_overhead_count@P", "", "at P, SPMD: loads the software bounds (x dpscan.msg_overhead)"},
    {NULL, NULL, NULL},
};

/* The machine is the config's machine: section, or workload.model
 * (default cm200) when it has none; workload.processors sets its
 * partition (dp_plan_machine). */
static void dp_plan(const void *params, WlPlan *plan)
{
    const DpParams *p = params;
    plan->reads = WL_READS_MACHINE | WL_READS_SCENE;
    plan->default_model = p->model;
}

/* workload.model beside a machine: section naming another model (or an
 * inline machine): one of them would be ignored. */
static gboolean model_conflict(const DpParams *p, const CfgNode *given,
                               GError **err)
{
    const CfgNode *mm = cfg_get(given, "model");
    const char *name = cfg_scalar(mm);
    if (!p->model_at || (name && !g_strcmp0(name, p->model)))
        return FALSE;
    char *found = mm ? g_strdup_printf("workload.model '%s' beside "
                                       "machine.model '%s' (%s:%d:%d)",
                                       p->model, name ? name : "?",
                                       cfg_file(mm), cfg_line(mm), cfg_col(mm))
                     : g_strdup_printf("workload.model '%s' beside an inline "
                                       "machine: section",
                                       p->model);
    cfg_error(err, p->model_at, found,
              "one of them (workload.model is a shorthand for machine.model)");
    g_free(found);
    return TRUE;
}

/* workload.processors as the machine's partition (DP_DEFAULT_PROCS on the
 * default machine): the SIMD array's lanes and router nodes (16
 * processors each, when the model counts them), or the SPMD nodes.  The
 * model's dpscan: section is read here too, so a machine dpscan cannot
 * run on is refused before anything is built. */
static gboolean dp_plan_machine(const void *params, const CfgNode *given,
                                const CfgNode *model, GPtrArray *set,
                                GError **err)
{
    const DpParams *p = params;
    if (given && model_conflict(p, given, err))
        return FALSE;
    const CfgNode *at = cfg_get(given, "model") ? cfg_get(given, "model")
                        : given                 ? given
                                                : p->model_at;
    WlDpMachine m = {0};
    if (!wl_dp_machine_from_model(model, at, &m, err))
        return FALSE;
    if (m.arch == WL_DP_SPMD && p->parts->len && !p->formula) {
        cfg_error(err, p->parts_at,
                  "partitions with SPMD sends on the machine's network",
                  "wire: formula (the network is the machine's, at its own "
                  "node count)");
        return FALSE;
    }
    uint64_t procs = p->procs ? p->procs : given ? 0 : DP_DEFAULT_PROCS;
    if (!procs)
        return TRUE;
    if (m.arch == WL_DP_SPMD) {
        g_ptr_array_add(set, g_strdup_printf("nodes.node.count=%" G_GUINT64_FORMAT,
                                             procs));
        return TRUE;
    }
    g_ptr_array_add(set, g_strdup_printf("nodes.array.lanes=%" G_GUINT64_FORMAT,
                                         procs));
    if (cfg_path(model, "network.router_nodes"))
        g_ptr_array_add(set, g_strdup_printf("network.router_nodes=%" G_GUINT64_FORMAT,
                                             MAX(procs / 16, 1)));
    return TRUE;
}

const WlOps wl_dpscan_ops = {
    .name = "dpscan",
    .summary = "ortega93: data-parallel scan conversion on SIMD/SPMD "
               "machines (CM-200, CM-5)",
    .parse = dp_parse,
    .free_params = dp_free_params,
    .plan = dp_plan,
    .plan_machine = dp_plan_machine,
    .run = dp_run,
    .needs_alt = wl_dp_model_needs,
    .mem_bytes = dp_mem_bytes,
    .metrics = dp_metrics,
};
