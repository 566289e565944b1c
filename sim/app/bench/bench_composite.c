/* bench_composite.c — `pgsim bench composite`: the image fidelity ladder
 * of sort-last compositing (pm_rung.h), speed against error.
 *
 * P processes composite the footprints of a block decomposition
 * (pm_foot.h) on an R x R image with one scheme and one optimisation
 * (none, bounding rectangles, bounding rectangles + RLE), at each rung
 * (pixels first: the reference), and the merge is replayed on the
 * machine model's network at P nodes (sim/machine/partition.h) with the
 * model's pixel-merging costs of node kind "node" (engine events, no
 * processors).  Per rung it prints the simulated compositing time, bytes
 * and messages, their relative error against the pixel rung, the wall
 * seconds (images, compositing and replay) and the speed-up over pixels;
 * last, the peak resident memory of the process.  --set
 * machine.KEY=VALUE overrides the model as in `pgsim run`.
 * Output is deterministic except for the wall and memory figures.
 */
#include "sim/app/bench/bench.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include "sim/core/units.h"
#include "sim/machine/partition.h"
#include "sim/workload/pixelmerge/pm_foot.h"
#include "sim/workload/pixelmerge/pm_workload.h"
#include <stdio.h>
#include <string.h>

typedef struct {
    char *machine, *scheme_s, *opt_s, *rung_s, *fidelity;
    char **sets;
    int procs, size, repeat;
    WlPmScheme scheme;
    WlPmCompose comp;
} Opts;

typedef struct {
    double comp_ms, wall_s;
    uint64_t bytes, msgs, elements;
    guint stages;
} Row;

static const char *const opt_words[] = {"none", "rect", "rect_rle", NULL};

static double now_s(void)
{
    return (double)g_get_monotonic_time() / 1e6;
}

/* Peak resident set of this process in MB (0 where unknown). */
static double peak_rss_mb(void)
{
    char *text = NULL;
    double mb = 0;
    if (g_file_get_contents("/proc/self/status", &text, NULL, NULL)) {
        const char *at = strstr(text, "VmHWM:");
        if (at)
            mb = g_ascii_strtod(at + 6, NULL) / 1024.0;
    }
    g_free(text);
    return mb;
}

static int word_index(const char *const *words, const char *s)
{
    for (int i = 0; words[i]; i++)
        if (!strcmp(words[i], s))
            return i;
    return -1;
}

/* The merge of the rung's images: records steps only. */
static WlPmMerge *composite(const Opts *o, WlPmRung rung, Row *row,
                            WlPmComposite **pc)
{
    guint n = (guint)o->procs, r = (guint)o->size;
    const WlPmFormat fmt = {8, 4, 2, 4, 8};
    *pc = NULL;
    if (rung == WL_PM_RUNG_PIXELS) {
        WlPmWpa **l = g_new(WlPmWpa *, n);
        for (guint p = 0; p < n; p++) {
            l[p] = wl_pm_foot_pixels(p, n, r, r);
            row->elements += wl_pm_wpa_len(l[p]);
        }
        *pc = wl_pm_composite_run(o->scheme, &o->comp, l, n, &fmt);
        row->stages = (*pc)->stages;
        for (guint p = 0; p < n; p++)
            wl_pm_wpa_free(l[p]);
        g_free(l);
        return (*pc)->merge;
    }
    WlPmRungImage **im = g_new(WlPmRungImage *, n);
    for (guint p = 0; p < n; p++) {
        im[p] = wl_pm_foot_image(rung, p, n, r, r);
        row->elements += im[p]->el->len;
    }
    WlPmMerge *m =
        wl_pm_rung_run(o->scheme, &o->comp, im, n, &fmt, &row->stages);
    for (guint p = 0; p < n; p++)
        wl_pm_rung_image_free(im[p]);
    g_free(im);
    return m;
}

/* The machine on eng with its network and pixel-merging costs *c, or
 * NULL with *err. */
static MachMachine *build(const Opts *o, const CfgNode *root, SimEngine *eng,
                          WlPmCosts *c, GError **err)
{
    MachMachine *mach =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), o->fidelity, err);
    if (mach && (!mach_require_net(mach, err) ||
                 !wl_pm_composite_costs_from_machine(mach, 4, c, err))) {
        mach_free(mach);
        return NULL;
    }
    return mach;
}

/* Builds the machine once, before any rung runs. */
static gboolean probe(const Opts *o, const CfgNode *root, GError **err)
{
    SimEngine *eng = sim_engine_new(1);
    WlPmCosts c;
    MachMachine *mach = build(o, root, eng, &c, err);
    gboolean ok = mach != NULL;
    mach_free(mach);
    sim_engine_free(eng);
    return ok;
}

/* Replays m on a fresh machine: the compositing time in ms. */
static gboolean replay(const Opts *o, const CfgNode *root, const WlPmMerge *m,
                       double *ms, GError **err)
{
    SimEngine *eng = sim_engine_new(1);
    WlPmCosts c;
    MachMachine *mach = build(o, root, eng, &c, err);
    gboolean ok = mach != NULL;
    guint n = (guint)o->procs;
    SimBusy *busy = g_new(SimBusy, n);
    SimTime *ready = g_new0(SimTime, n);
    for (guint p = 0; p < n; p++)
        sim_busy_init(&busy[p]);
    WlPmReplayOut ro = {0};
    if (ok) {
        WlPmReplayRig rig = {.net = mach_net(mach),
                             .costs = &c.merge,
                             .ready = ready,
                             .busy = busy,
                             .phase = sim_engine_phase(eng, "merge"),
                             .bal = WL_PM_BAL_STRIPS,
                             .height = (guint)o->size};
        ok = wl_pm_replay(&rig, m, &ro, err);
        *ms = sim_time_to_ms(ro.end);
    }
    wl_pm_replay_out_clear(&ro);
    for (guint p = 0; p < n; p++)
        sim_busy_clear(&busy[p]);
    g_free(busy);
    g_free(ready);
    mach_free(mach);
    sim_engine_free(eng);
    return ok;
}

static gboolean run_rung(const Opts *o, const CfgNode *root, WlPmRung rung,
                         Row *best, GError **err)
{
    for (int i = 0; i < o->repeat; i++) {
        Row row = {0};
        double t0 = now_s();
        WlPmComposite *pc;
        WlPmMerge *m = composite(o, rung, &row, &pc);
        gboolean ok = replay(o, root, m, &row.comp_ms, err);
        row.bytes = m->total_bytes;
        row.msgs = m->total_msgs;
        if (pc)
            wl_pm_composite_free(pc);
        else
            wl_pm_rung_merge_free(m);
        row.wall_s = now_s() - t0;
        if (!ok)
            return FALSE;
        if (i == 0 || row.wall_s < best->wall_s)
            *best = row;
    }
    return TRUE;
}

static double rel(double v, double ref)
{
    return ref > 0 ? v / ref - 1.0 : 0.0;
}

static void print_row(WlPmRung rung, const Row *r, const Row *ref)
{
    printf("%-7s %12.4f %14" G_GUINT64_FORMAT " %10" G_GUINT64_FORMAT
           " %12" G_GUINT64_FORMAT,
           wl_pm_rung_names[rung], r->comp_ms, r->bytes, r->msgs, r->elements);
    if (ref)
        printf(" %+9.4f %+9.4f %9.3f %8.2f\n", rel(r->comp_ms, ref->comp_ms),
               rel((double)r->bytes, (double)ref->bytes), r->wall_s,
               ref->wall_s / MAX(r->wall_s, 1e-9));
    else
        printf(" %9s %9s %9.3f %8s\n", "ref", "ref", r->wall_s, "1");
}

/* The pixel rung's memory before it is spent: frames and pixels. */
static gboolean pixels_fit(const Opts *o, GError **err)
{
    double px = (double)o->size * o->size;
    return sim_mem_check(24.0 * px + 4 * 80.0 * px,
                         "bench composite: --size, --rung pixels",
                         "the pixel rung's frame and pixels", err);
}

/* Every rung's per-process state: processes, blocks, a step's work
 * and message slots per stage (at most 33), the replay's state. */
static gboolean procs_fit(const Opts *o, GError **err)
{
    return sim_mem_check((double)o->procs * (256.0 + 33 * 64.0),
                         "bench composite: --procs",
                         "per-process compositing and replay state", err);
}

static int run_all(const Opts *o, const CfgNode *root, const char *part)
{
    int only = word_index(wl_pm_rung_names, o->rung_s);
    GError *err = NULL;
    if (!procs_fit(o, &err) || !probe(o, root, &err))
        return bench_fail(err);
    printf("machine %s: %d nodes (%s), network fidelity %s\n", o->machine,
           o->procs, part ? part : "model size", o->fidelity);
    printf("image %d x %d, %d processes (block footprints), %s, %s\n", o->size,
           o->size, o->procs, o->scheme_s, o->opt_s);
    printf("%-7s %12s %14s %10s %12s %9s %9s %9s %8s\n", "rung", "comp_ms",
           "bytes", "msgs", "elements", "err_time", "err_bytes", "wall_s",
           "speedup");
    Row ref = {0}, r = {0};
    for (int g = 0; g < 3; g++) {
        if (only >= 0 && g != only)
            continue;
        if (g == WL_PM_RUNG_PIXELS && !pixels_fit(o, &err))
            return bench_fail(err);
        if (!run_rung(o, root, (WlPmRung)g, &r, &err))
            return bench_fail(err);
        print_row((WlPmRung)g, &r, only < 0 && g > 0 ? &ref : NULL);
        if (g == 0)
            ref = r;
    }
    printf("stages: %u\n", r.stages);
    printf("wall_s: %.3f\n", r.wall_s);
    printf("peak_rss_mb: %.1f\n", peak_rss_mb());
    return 0;
}

static gboolean check_opts(Opts *o, GError **err)
{
    int s = word_index(wl_pm_scheme_names, o->scheme_s);
    int opt = word_index(opt_words, o->opt_s);
    gboolean rung_ok = !strcmp(o->rung_s, "all") ||
                       word_index(wl_pm_rung_names, o->rung_s) >= 0;
    if (s < 0 || !wl_pm_scheme_composites((WlPmScheme)s) || opt < 0 ||
        !rung_ok || o->procs < 1 || o->size < 2 || o->size > 65535 ||
        o->repeat < 1) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "bench composite: found a bad option value, expected "
                    "--scheme binary_swap|direct_send|radix_k|two_three_swap, "
                    "--opt none|rect|rect_rle, --rung all|pixels|runs|counts, "
                    "--procs >= 1, --size 2..65535, --repeat >= 1");
        return FALSE;
    }
    o->scheme = (WlPmScheme)s;
    o->comp =
        (WlPmCompose){.bounding_rect = opt >= 1, .rle = opt == 2, .opacity = 1};
    return TRUE;
}

int bench_composite_main(int argc, char **argv)
{
    Opts o = {.procs = 256, .size = 1024, .repeat = 1};
    GOptionEntry entries[] = {
        {"machine", 0, 0, G_OPTION_ARG_STRING, &o.machine,
         "machine model (ipsc2)", "M"},
        {"set", 0, 0, G_OPTION_ARG_STRING_ARRAY, &o.sets,
         "override a model value (repeatable)", "machine.KEY=VALUE"},
        {"procs", 0, 0, G_OPTION_ARG_INT, &o.procs, "processes (256)", "P"},
        {"size", 0, 0, G_OPTION_ARG_INT, &o.size, "image side (1024)", "R"},
        {"scheme", 0, 0, G_OPTION_ARG_STRING, &o.scheme_s,
         "binary_swap, direct_send, radix_k, two_three_swap (binary_swap)",
         "S"},
        {"opt", 0, 0, G_OPTION_ARG_STRING, &o.opt_s,
         "none, rect or rect_rle (rect_rle)", "O"},
        {"rung", 0, 0, G_OPTION_ARG_STRING, &o.rung_s,
         "all, pixels, runs or counts (all)", "R"},
        {"fidelity", 0, 0, G_OPTION_ARG_STRING, &o.fidelity,
         "network fidelity: analytic, flow, packet, faithful (analytic)", "F"},
        {"repeat", 0, 0, G_OPTION_ARG_INT, &o.repeat,
         "runs a rung, the least wall time shown (1)", "K"},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    GError *err = NULL;
    CfgNode *root = NULL;
    char *part = NULL;
    gboolean ok = bench_parse_options("composite",
                                      "- compositing image rungs: speed "
                                      "against error",
                                      entries, &argc, &argv, &err);
    if (ok) {
        o.machine = o.machine ? o.machine : g_strdup("ipsc2");
        o.scheme_s = o.scheme_s ? o.scheme_s : g_strdup("binary_swap");
        o.opt_s = o.opt_s ? o.opt_s : g_strdup("rect_rle");
        o.rung_s = o.rung_s ? o.rung_s : g_strdup("all");
        o.fidelity = o.fidelity ? o.fidelity : g_strdup("analytic");
        ok = check_opts(&o, &err);
    }
    if (ok)
        root = mach_partition_root("bench composite", o.machine,
                                   (const char *const *)o.sets, (guint)o.procs,
                                   &part, &err);
    int status = root ? run_all(&o, root, part) : bench_fail(err);
    cfg_free(root);
    g_free(part);
    g_free(o.machine);
    g_free(o.scheme_s);
    g_free(o.opt_s);
    g_free(o.rung_s);
    g_free(o.fidelity);
    g_strfreev(o.sets);
    return status;
}
