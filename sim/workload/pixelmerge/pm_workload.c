/* pm_workload.c — the `pixelmerge` workload: object-space parallel
 * polygon rendering with active pixel merging on a hypercube (Kurç,
 * Aykanat, Özgüç, seed 003), behind the WlOps contract.
 *
 *   workload:
 *     type: pixelmerge
 *     scheme: pair            # zbuf_exc (or zbuf-exc) | pair | aapc
 *                             # | binary_swap | direct_send | radix_k
 *                             # | two_three_swap        (pm_composite.h)
 *     balance: rs             # strips | rs | hbp               (§4)
 *     processors: 16          # P <= machine nodes, a power of two for
 *                             # Kurç's schemes, any for the compositing
 *                             # ones (default: all of the machine's nodes)
 *     radices: [4, 2]         # radix_k: product P (default pm_stages.h)
 *     bounding_rect: false    # compositing: send bounding boxes only
 *     rle: false              # compositing: run-length encode
 *     operator: z             # compositing: z | over
 *     opacity: 0.5            # over: every active pixel's alpha
 *     bytes_per_run: 4        # compositing: a run-length header
 *     bytes_per_rect: 8       # compositing: a bounding rectangle
 *     visibility: [2, 0, 1]   # compositing: processors nearest first
 *                             # (default 0, 1, ..., P-1)
 *     image_fidelity: pixels  # compositing: pixels | runs | counts
 *                             # (pm_rung_frame.h; counts: images blocks,
 *                             # up to 65,536 processors and 16384^2;
 *                             # runs, counts: costs pack, compare only)
 *     images: scene           # compositing: scene | blocks | volume
 *     volume: {...}           # blocks, volume: pm_images.h, pm_volume.h
 *     resolution: 400         # N: an N x N screen
 *     polygon_split: cyclic   # cyclic | block
 *     bytes_per_pixel: 8      # active pixel record in a message
 *     bytes_per_location: 4   # ZBUF-EXC record
 *     bytes_per_scanline: 2   # scanline count header
 *     bytes_per_count: 4      # global-sum element (RS, HBP)
 *     check_image: true       # compare with the serial render
 *     cull_back: false        # back-face culling before scan conversion
 *     span_rule: exact        # exact | endpoints (sim/raster/scan.h)
 *     memory: {base: 1 MB, polygon: 200 B, span: 32 B, location: 8 B,
 *              pixel: 8 B, index: 4 B}
 *
 * The machine and the scene are the runner's (sim/run/run.h), built from
 * the config's `machine` and `scene` sections; node costs are the node
 * kind "node"'s cost table (wl_pm_cost_ops).
 * Processor p of the workload is machine processor node<p>: P < nodes
 * runs on the subcube of nodes 0 .. P-1 (the rest stay idle).
 * Cost per frame: pm_frame.h.
 */
#include "sim/workload/pixelmerge/pm_workload.h"
#include "sim/scene/scene_cfg.h"
#include <string.h>

const char *const wl_pm_cost_ops[] = {
    "polygon",  "span",      "insert_step", "pixel",       "zcompare",
    "scanline", "zbuf_init", "pack",        "scatter",     "compare",
    "gather",   "sum_elem",  "sort_elem",   "assign_step", NULL};
/* Each op's portable work (sim/machine/work.h), from the first
 * instruction-count estimates in models/ipsc2.yaml's notes: a cost the
 * model lacks is derived from it on the node's processor description. */
static const MachWork pm_work[] = {
    {"polygon", {[MACH_W_VERTEX] = 3, [MACH_W_SETUP] = 1}},
    {"span", {[MACH_W_FLOP] = 4, [MACH_W_INSTR] = 20}}, /* 2 edge steps */
    {"insert_step", {[MACH_W_INSTR] = 6}},
    {"pixel", {[MACH_W_PIXEL] = 1}},
    {"zcompare", {[MACH_W_ZCMP] = 1}},
    {"scanline", {[MACH_W_INSTR] = 50}},
    {"zbuf_init", {[MACH_W_INSTR] = 2, [MACH_W_MEMBYTE] = 8}},
    {"pack", {[MACH_W_INSTR] = 2, [MACH_W_MEMBYTE] = 16}}, /* 8 B copied */
    {"scatter", {[MACH_W_INSTR] = 6}},
    {"compare", {[MACH_W_ZCMP] = 1, [MACH_W_INSTR] = 9}},
    {"gather", {[MACH_W_INSTR] = 8}},
    {"sum_elem", {[MACH_W_INSTR] = 3}},
    {"sort_elem", {[MACH_W_INSTR] = 8}},
    {"assign_step", {[MACH_W_INSTR] = 6}},
    {NULL, {0}}};
const MachNeed wl_pm_needs[] = {{"node", wl_pm_cost_ops, pm_work},
                                {NULL, NULL, NULL}};

/* Scheme words: the library's names plus "zbuf_exc" (underscore, last). */
static const char *const scheme_words[] = {
    "zbuf-exc",    "pair",    "aapc",           "binary_swap",
    "direct_send", "radix_k", "two_three_swap", "zbuf_exc",
    NULL};
/* Indexed by RastSpanRule. */
static const char *const span_rules[] = {"exact", "endpoints", NULL};

gboolean wl_pm_costs_from_machine(const MachMachine *m, uint32_t count_bytes,
                                  WlPmCosts *c, GError **err)
{
    MachCosts *set = mach_costs_new(m, wl_pm_needs, err);
    if (!set)
        return FALSE;
    SimTime *const dst[] = {&c->polygon,         &c->span,
                            &c->insert_step,     &c->pixel,
                            &c->zcompare,        &c->scanline,
                            &c->zbuf_init,       &c->merge.pack,
                            &c->merge.scatter,   &c->merge.compare,
                            &c->merge.gather,    &c->merge.sum_elem,
                            &c->merge.sort_elem, &c->merge.assign_step};
    G_STATIC_ASSERT(G_N_ELEMENTS(dst) == G_N_ELEMENTS(wl_pm_cost_ops) - 1);
    mach_costs_fill(set, "node", wl_pm_cost_ops, dst);
    mach_costs_free(set);
    c->merge.count_bytes = count_bytes;
    return TRUE;
}

gboolean wl_pm_composite_costs_from_machine(const MachMachine *m,
                                            uint32_t count_bytes,
                                            WlPmCosts *c, GError **err)
{
    static const char *const ops[] = {"pack", "compare", NULL};
    static const MachNeed needs[] = {{"node", ops, pm_work},
                                     {NULL, NULL, NULL}};
    MachCosts *set = mach_costs_new(m, needs, err);
    if (!set)
        return FALSE;
    *c = (WlPmCosts){.merge = {.count_bytes = count_bytes}};
    SimTime *const dst[] = {&c->merge.pack, &c->merge.compare};
    mach_costs_fill(set, "node", ops, dst);
    mach_costs_free(set);
    return TRUE;
}

WlPmMemUse wl_pm_memory_use(const WlPmMemory *mem, const WlPmSetup *s,
                            uint64_t polygons, uint64_t spans, uint64_t active)
{
    uint64_t n = s->resolution, n2 = n * n;
    WlPmMemUse u = {.base = mem->base,
                    .polygons = polygons * mem->polygon,
                    .spans = spans * mem->span}; /* the rest set below */
    gboolean full = s->scheme == WL_PM_ZBUF_EXC ||
                    (wl_pm_scheme_composites(s->scheme) && !s->comp.rle);
    if (full) {
        u.zbuffer = n2 * mem->location;
        u.buffers = n2 * s->fmt.bytes_per_location;
    } else {
        u.zbuffer = active * mem->pixel + n * mem->index;
        u.buffers = 2 * active * s->fmt.bytes_per_pixel;
    }
    u.total = u.base + u.polygons + u.spans + u.zbuffer + u.buffers;
    return u;
}

static gboolean parse_sizes(const CfgNode *sec, WlPmParams *p, GError **err)
{
    uint64_t bpp = 8, bpl = 4, bps = 2, bpc = 4, bpr = 4, bpb = 8;
    if (!cfg_get_count(sec, "bytes_per_pixel", FALSE, 1, 256, &bpp, err) ||
        !cfg_get_count(sec, "bytes_per_location", FALSE, 1, 256, &bpl, err) ||
        !cfg_get_count(sec, "bytes_per_scanline", FALSE, 0, 256, &bps, err) ||
        !cfg_get_count(sec, "bytes_per_count", FALSE, 1, 16, &bpc, err) ||
        !cfg_get_count(sec, "bytes_per_run", FALSE, 0, 256, &bpr, err) ||
        !cfg_get_count(sec, "bytes_per_rect", FALSE, 0, 256, &bpb, err))
        return FALSE;
    p->setup.fmt = (WlPmFormat){(guint)bpp, (guint)bpl, (guint)bps,
                                (guint)bpr, (guint)bpb};
    p->count_bytes = (uint32_t)bpc;
    return TRUE;
}

static gboolean parse_memory(const CfgNode *sec, WlPmMemory *m, GError **err)
{
    *m = (WlPmMemory){1000000, 200, 32, 8, 8, 4};
    const CfgNode *n;
    if (!cfg_get_map(sec, "memory", FALSE,
                     "a map {base, polygon, span, location, pixel, index} of "
                     "sizes",
                     &n, err))
        return FALSE;
    /* no memory map: n is NULL, and each optional read of a NULL map
     * finds nothing and keeps the default (cfg_get) */
    return cfg_get_size(n, "base", FALSE, &m->base, err) &&
           cfg_get_size(n, "polygon", FALSE, &m->polygon, err) &&
           cfg_get_size(n, "span", FALSE, &m->span, err) &&
           cfg_get_size(n, "location", FALSE, &m->location, err) &&
           cfg_get_size(n, "pixel", FALSE, &m->pixel, err) &&
           cfg_get_size(n, "index", FALSE, &m->index, err);
}

/* Kurç's schemes run on a hypercube's address bits: P a power of two. */
static gboolean check_procs(const CfgNode *sec, const WlPmSetup *s,
                            uint64_t procs, GError **err)
{
    if ((procs & (procs - 1)) == 0 || wl_pm_scheme_composites(s->scheme))
        return TRUE;
    char *found = g_strdup_printf("'%" G_GUINT64_FORMAT "'", procs);
    cfg_error(err, cfg_get(sec, "processors"), found,
              "a power of two (a hypercube of 2^d nodes)");
    g_free(found);
    return FALSE;
}

static gboolean parse_words(const CfgNode *sec, WlPmSetup *s, GError **err)
{
    int scheme = WL_PM_PAIR, bal = WL_PM_BAL_RS, split = WL_PM_SPLIT_CYCLIC;
    int rule = RAST_SPAN_EXACT;
    if (!cfg_get_enum(sec, "scheme", FALSE, scheme_words, &scheme, err) ||
        !cfg_get_enum(sec, "span_rule", FALSE, span_rules, &rule, err) ||
        !cfg_get_enum(sec, "balance", FALSE, wl_pm_balance_names, &bal, err) ||
        !cfg_get_enum(sec, "polygon_split", FALSE, wl_pm_split_names, &split,
                      err))
        return FALSE;
    s->scheme = scheme == 7 ? WL_PM_ZBUF_EXC : (WlPmScheme)scheme;
    s->balance = bal;
    s->split = split;
    s->span_rule = (RastSpanRule)rule;
    return TRUE;
}

/* workload.radices: a list of counts >= 2, with scheme radix_k only. */
static gboolean parse_radices(const CfgNode *sec, WlPmSetup *s, GError **err)
{
    const CfgNode *r = cfg_get(sec, "radices");
    if (!r)
        return TRUE;
    guint n = cfg_kind(r) == CFG_SEQ ? cfg_seq_len(r) : 0;
    if (s->scheme != WL_PM_RADIX_K) {
        char *found = g_strdup_printf("'radices' with scheme '%s'",
                                      wl_pm_scheme_names[s->scheme]);
        cfg_error(err, r, found, "scheme radix_k for radices");
        g_free(found);
        return FALSE;
    }
    if (n == 0 || n > WL_PM_MAX_RADICES) {
        cfg_error(err, r, "'radices'",
                  "a list of 1 to 32 radices, e.g. [4, 2]");
        return FALSE;
    }
    for (guint i = 0; i < n; i++) {
        const CfgNode *v = cfg_seq_at(r, i);
        const char *t = cfg_scalar(v);
        uint64_t k = 0;
        if (!t || !cfg_parse_count(t, "radix", &k, NULL) || k < 2 ||
            k > 1024) {
            char *found = g_strdup_printf("'%s'", t ? t : "a collection");
            cfg_error(err, v, found, "a radix, a count from 2 to 1024");
            g_free(found);
            return FALSE;
        }
        s->comp.radices[i] = (guint)k;
    }
    s->comp.n_radices = n;
    return TRUE;
}

/* workload.visibility: a list of processors, nearest first (checked to
 * be a permutation of P by check_order once P is known). */
static gboolean parse_order(const CfgNode *sec, WlPmParams *p, GError **err)
{
    const CfgNode *v = cfg_get(sec, "visibility");
    if (!v)
        return TRUE;
    guint n = cfg_kind(v) == CFG_SEQ ? cfg_seq_len(v) : 0;
    if (n == 0 || n > 1024) {
        cfg_error(err, v, "'visibility'",
                  "a list of 1 to 1024 processors, nearest first");
        return FALSE;
    }
    p->order = g_new(guint, n);
    p->n_order = n;
    for (guint i = 0; i < n; i++) {
        const char *t = cfg_scalar(cfg_seq_at(v, i));
        uint64_t k = 0;
        if (!t || !cfg_parse_count(t, "processor", &k, NULL) || k >= 1024) {
            char *found = g_strdup_printf("'%s'", t ? t : "a collection");
            cfg_error(err, cfg_seq_at(v, i), found,
                      "a processor number from 0 to 1023");
            g_free(found);
            return FALSE;
        }
        p->order[i] = (guint)k;
    }
    p->setup.comp.order = p->order;
    return TRUE;
}

/* The visibility order is a permutation of the P processors (procs 0:
 * not known yet). */
static gboolean check_order(const WlPmParams *p, guint procs,
                            const CfgNode *at, GError **err)
{
    if (!p->order || procs == 0 ||
        (p->n_order == procs && wl_pm_order_ok(p->order, procs)))
        return TRUE;
    char *found = g_strdup_printf("a visibility order of %u processors%s",
                                  p->n_order,
                                  p->n_order == procs ? " with repeats" : "");
    char *exp = g_strdup_printf("each of the %u processors once", procs);
    cfg_error(err, at, found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

/* The compositing schemes' options (pm_composite.h). */
static gboolean parse_compose(const CfgNode *sec, WlPmSetup *s, GError **err)
{
    int op = WL_PM_OP_Z;
    double opacity = 0.5;
    gboolean rect = FALSE, rle = FALSE;
    if (!parse_radices(sec, s, err) ||
        !cfg_get_bool(sec, "bounding_rect", FALSE, &rect, err) ||
        !cfg_get_bool(sec, "rle", FALSE, &rle, err) ||
        !cfg_get_enum(sec, "operator", FALSE, wl_pm_operator_names, &op,
                      err) ||
        !cfg_get_double(sec, "opacity", FALSE, 1e-6, 1.0, &opacity, err))
        return FALSE;
    const char *const keys[] = {"bounding_rect", "rle", "operator",
                                "opacity", "visibility"};
    for (guint i = 0; i < G_N_ELEMENTS(keys); i++)
        if (!wl_pm_scheme_composites(s->scheme) && cfg_has(sec, keys[i])) {
            char *found = g_strdup_printf("'%s' with scheme '%s'", keys[i],
                                          wl_pm_scheme_names[s->scheme]);
            cfg_error(err, cfg_get(sec, keys[i]), found,
                      "a compositing scheme (binary_swap, direct_send, "
                      "radix_k, two_three_swap) for this key");
            g_free(found);
            return FALSE;
        }
    s->comp.bounding_rect = rect;
    s->comp.rle = rle;
    s->comp.op = (WlPmOperator)op;
    s->comp.opacity = opacity;
    return TRUE;
}

/* Radix-k's radices multiply to P (checked when parsed if processors
 * is given, else once the machine is known; procs 0: not yet). */
static gboolean check_radices(const WlPmCompose *c, guint procs,
                              const CfgNode *at, GError **err)
{
    if (procs == 0 || c->n_radices == 0 ||
        wl_pm_radices_ok(c->radices, c->n_radices, procs))
        return TRUE;
    uint64_t prod = 1;
    for (guint i = 0; i < c->n_radices; i++)
        prod *= c->radices[i];
    char *found = g_strdup_printf("radices of product %" G_GUINT64_FORMAT,
                                  prod);
    char *exp = g_strdup_printf("radices whose product is the %u "
                                "processors",
                                procs);
    cfg_error(err, at, found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

/* A count key above what the pixel rung takes: only at counts. */
static gboolean rung_limit(const CfgNode *sec, const char *key, uint64_t v,
                           uint64_t most, GError **err)
{
    if (v <= most)
        return TRUE;
    char *found = g_strdup_printf("%s %" G_GUINT64_FORMAT " at image "
                                  "fidelity pixels or runs", key, v);
    char *exp = g_strdup_printf("at most %" G_GUINT64_FORMAT " (more with "
                                "image_fidelity: counts)", most);
    cfg_error(err, cfg_get(sec, key), found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

/* workload.image_fidelity (pm_rung_frame.h): pixels, or runs and counts
 * with a compositing scheme; counts with block images only. */
static gboolean parse_rung(const CfgNode *sec, WlPmSetup *s, uint64_t procs,
                           uint64_t res, GError **err)
{
    int rung = WL_PM_RUNG_PIXELS;
    if (!cfg_get_enum(sec, "image_fidelity", FALSE, wl_pm_rung_names, &rung,
                      err))
        return FALSE;
    s->rung = (WlPmRung)rung;
    const CfgNode *at = cfg_get(sec, "image_fidelity");
    if (rung != WL_PM_RUNG_PIXELS && !wl_pm_scheme_composites(s->scheme)) {
        cfg_error(err, at, "image fidelity runs or counts with one of Kurç's "
                  "schemes", "a compositing scheme (binary_swap, "
                  "direct_send, radix_k, two_three_swap)");
        return FALSE;
    }
    if (rung == WL_PM_RUNG_COUNTS && s->images.kind != WL_PM_IMAGES_BLOCKS) {
        cfg_error(err, at, "image fidelity counts without block images",
                  "images: blocks (footprints are what counts model)");
        return FALSE;
    }
    return rung == WL_PM_RUNG_COUNTS ||
           (rung_limit(sec, "processors", procs, 1024, err) &&
            rung_limit(sec, "resolution", res, 4096, err));
}

static void pm_free_params(void *params)
{
    WlPmParams *p = params;
    if (p)
        g_free(p->order);
    g_free(p);
}

static void *pm_parse(const CfgNode *sec, GError **err)
{
    WlPmParams *p = g_new0(WlPmParams, 1);
    uint64_t procs = 0, res = 400;
    gboolean check = TRUE, cull = FALSE;
    gboolean ok =
        parse_words(sec, &p->setup, err) &&
        cfg_get_count(sec, "processors", FALSE, 1, 65536, &procs, err) &&
        check_procs(sec, &p->setup, procs, err) &&
        parse_compose(sec, &p->setup, err) &&
        check_radices(&p->setup.comp, (guint)procs, cfg_get(sec, "radices"),
                      err) &&
        parse_order(sec, p, err) &&
        check_order(p, (guint)procs, cfg_get(sec, "visibility"), err) &&
        wl_pm_images_parse(sec, wl_pm_scheme_composites(p->setup.scheme),
                           p->order != NULL, &p->setup.images, err) &&
        cfg_get_count(sec, "resolution", FALSE, 2, 16384, &res, err) &&
        cfg_get_bool(sec, "check_image", FALSE, &check, err) &&
        cfg_get_bool(sec, "cull_back", FALSE, &cull, err) &&
        parse_sizes(sec, p, err) && parse_memory(sec, &p->mem, err) &&
        parse_rung(sec, &p->setup, procs, res, err);
    if (!ok) {
        pm_free_params(p);
        return NULL;
    }
    p->setup.procs = (guint)procs;
    p->setup.resolution = (guint)res;
    p->setup.check_image = check;
    p->setup.cull_back = cull;
    return p;
}

/* Own memory (WlOps.mem_bytes): a WlPmPixel a screen pixel for the
 * merged frame, one more for the processors' active-pixel arrays
 * together and one for the serial reference (check_image), the output
 * image (3 B), each processor's row offsets and the P x P message counts;
 * the compositing schemes more (below), block images more
 * (wl_pm_images_mem_bytes).
 * Processors 0 (the machine's count) counts as 1: a lower bound.  The
 * quickstart at 1600 x 1600 peaked at 156 MB RSS (estimate 183 MiB). */
static double pm_mem_bytes(const void *params, GString *what)
{
    const WlPmParams *p = params;
    double n = p->setup.resolution, procs = MAX(p->setup.procs, 1u);
    if (p->setup.rung == WL_PM_RUNG_COUNTS) {
        /* per process a few rectangles, its messages and replay state a
         * stage (~4 KB); direct send P (P - 1) messages of ~350 B with
         * their replay (4,096 processes: 5.7 GB peak RSS measured) */
        g_string_append_printf(what, "%u processors at image fidelity "
                               "counts", p->setup.procs);
        return procs * 4096.0 +
               (p->setup.scheme == WL_PM_DIRECT_SEND ? procs * procs * 350.0
                                                     : 0.0);
    }
    g_string_append_printf(what, "%u processors, %.0f x %.0f pixels",
                           p->setup.procs, n, n);
    double copies = p->setup.check_image ? 3 : 2;
    double comp = 0; /* compositing: a stage's pixels, old and new (~48 B
                      * each), the over blend and its serial reference */
    if (wl_pm_scheme_composites(p->setup.scheme))
        comp = 2 * 48.0 + (p->setup.comp.op == WL_PM_OP_OVER ? 64.0 : 0.0);
    return n * n * (copies * sizeof(WlPmPixel) + 3.0 + comp) +
           procs * (n + 1) * 4.0 + procs * procs * 8.0 +
           wl_pm_images_mem_bytes(&p->setup.images, (guint)procs, (guint)n);
}

static WlPmMemUse peak_memory(const WlPmFrameOut *fo, const WlPmParams *p,
                              const WlPmSetup *s)
{
    WlPmMemUse peak;
    memset(&peak, 0, sizeof peak); /* all parts 0 until a node has bytes */
    for (guint q = 0; q < s->procs; q++) {
        WlPmMemUse u = wl_pm_memory_use(&p->mem, s, fo->counts[q].polygons,
                                        fo->counts[q].rc.spans, fo->active[q]);
        if (u.total > peak.total)
            peak = u;
    }
    return peak;
}

static void set(SimResult *out, const char *name, double v, const char *unit)
{
    sim_result_set_metric(out, name, v, unit);
}

static void fill_metrics(SimResult *out, const WlPmFrameOut *fo,
                         double serial_ms, const WlPmSetup *s,
                         const WlPmMemUse *mem)
{
    SimTime busy = 0;
    for (guint p = 0; p < s->procs; p++)
        busy += fo->busy[p].total;
    set(out, "processors", s->procs, "");
    set(out, "resolution", s->resolution, "");
    set(out, "span_ms", fo->span_ms, "ms");
    set(out, "zbuf_ms", fo->zbuf_ms, "ms");
    set(out, "merge_ms", fo->merge_ms, "ms");
    set(out, "frame_ms", fo->frame_ms, "ms");
    set(out, "serial_ms", serial_ms, "ms");
    set(out, "speedup", serial_ms / fo->frame_ms, "");
    set(out, "utilisation", sim_time_to_ms(busy) / (s->procs * fo->frame_ms),
        "");
    set(out, "concurrent_volume", (double)fo->concurrent_volume, "B");
    set(out, "merge_bytes", (double)fo->merge_bytes, "B");
    set(out, "load_imbalance", fo->load_imbalance, "");
    set(out, "partition_imbalance", fo->partition_imbalance, "");
    set(out, "polygons", (double)fo->polygons, "");
    set(out, "tpg", (double)fo->tpg, "");
    set(out, "tpf", (double)fo->tpf, "");
    static const char *const part[] = {"peak_memory",     "memory_base",
                                       "memory_polygons", "memory_spans",
                                       "memory_zbuffer",  "memory_buffers"};
    const uint64_t bytes[] = {mem->total, mem->base,    mem->polygons,
                              mem->spans, mem->zbuffer, mem->buffers};
    for (guint i = 0; i < G_N_ELEMENTS(part); i++)
        set(out, part[i], (double)bytes[i], "B");
    if (fo->image_checked)
        set(out, "image_matches_serial", fo->image_ok, "");
    if (!wl_pm_scheme_composites(s->scheme))
        return; /* Kurç's results keep their columns */
    set(out, "composite_stages", fo->stages, "");
    set(out, "merge_messages", (double)fo->merge_msgs, "");
    set(out, "merge_records", (double)fo->merge_records, "");
    uint64_t held = 0; /* the processes' active pixels, summed */
    for (guint p = 0; p < s->procs; p++)
        held += fo->active[p];
    if (fo->tpf) /* the pixel rung's final picture */
        set(out, "image_overlap", (double)held / (double)fo->tpf, "");
}

/* `at`: the processors key, for a located error (may be NULL). */
static gboolean check_machine(MachMachine *m, const WlPmSetup *s,
                              const CfgNode *at, GError **err)
{
    const MachKindInfo *k = mach_kind(m, "node");
    if (!mach_require_net(m, err))
        return FALSE;
    if (k && k->first == 0 && k->count >= s->procs &&
        net_nodes(mach_net(m)) >= s->procs)
        return TRUE;
    char *found = g_strdup_printf("'%u' processors", s->procs);
    char *exp = g_strdup_printf("at most the %u nodes of kind 'node' of "
                                "machine '%s'",
                                k ? k->count : 0, mach_name(m));
    if (at) {
        cfg_error(err, at, found, exp);
    } else {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "pixelmerge: found %s, expected %s", found, exp);
    }
    g_free(found);
    g_free(exp);
    return FALSE;
}

/* One run: the machine's first P processors of kind "node" over the
 * run's frames. */
typedef struct {
    const WlContext *ctx;
    const WlPmParams *p;
    WlPmSetup s; /* procs resolved against the machine */
    WlPmCosts c; /* the machine's, for the serial reference */
    MachProc **procs;
    WlPmFrameOut fo; /* the last frame's */
} PmRun;

static gboolean run_frame(PmRun *r, int f, SimResult *out, GError **err)
{
    MachMachine *m = r->ctx->machine;
    SimEngine *eng = mach_engine(m);
    wl_pm_frame_out_clear(&r->fo, r->s.procs);
    r->s.keep_image = wl_wants_frame(r->ctx, f);
    if (!wl_pm_frame_run_procs(mach_net(m), r->procs, (guint)f, r->ctx->scene,
                               &r->s, &r->c, &r->fo, err))
        return FALSE;
    if (sim_engine_cut(eng))
        return TRUE; /* run.until ended the run inside this frame */
    if (r->fo.image && !wl_emit_frame(r->ctx, f, r->fo.image, err))
        return FALSE;
    SimTime t;
    if (!sim_time_from_s(r->fo.frame_ms * 1e-3, &t))
        t = SIM_TIME_MAX;
    sim_result_add_frame(out, t);
    wl_mark_frame(eng, (guint)f, sim_now(eng));
    if (r->fo.image_checked && !r->fo.image_ok) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                    "pixelmerge: the merged image of frame %d differs "
                    "from the serial render",
                    f);
        return FALSE;
    }
    return TRUE;
}

/* Why the speed-up is above P, when it is: the serial reference inserts
 * every span into its row's sorted list, s (s - 1) / 4 steps for s spans
 * on a row, and a node with 1/P of the spans pays about 1/P^2 of that. */
static void note_speedup(SimResult *out, double serial_ms, double insert_ms,
                         double frame_ms, guint procs)
{
    double speedup = serial_ms / frame_ms;
    if (!(speedup > procs))
        return;
    char *t = g_strdup_printf(
        "speed-up %.1f is above P = %u because of the serial reference's "
        "cost, not the parallel run's: the one-node render spends %.0f ms "
        "(%.0f %% of its %.0f ms, serial_insert_ms) inserting spans into "
        "sorted row lists, s (s - 1) / 4 steps for s spans on a row, and "
        "each of the %u nodes, with about 1/%u of a row's spans, pays about "
        "1/%u of that.  The rest of the serial time over the frame time, "
        "(serial_ms - serial_insert_ms) / frame_ms, is %.1f "
        "(docs/validation.md, kurc96).",
        speedup, procs, insert_ms, 100.0 * insert_ms / serial_ms, serial_ms,
        procs, procs, procs * procs, (serial_ms - insert_ms) / frame_ms);
    sim_result_add_note(out, t);
    g_free(t);
}

/* The run's figures after its last frame. */
static void run_metrics(const PmRun *r, SimResult *out)
{
    WlPmMemUse mem = peak_memory(&r->fo, r->p, &r->s);
    double insert_ms = 0;
    double serial_ms = r->s.rung != WL_PM_RUNG_PIXELS
                           ? 0 /* not rendered: compositing only */
                           : wl_pm_serial_ms(r->ctx->scene, &r->s, &r->c,
                                             &insert_ms);
    fill_metrics(out, &r->fo, serial_ms, &r->s, &mem);
    set(out, "serial_insert_ms", insert_ms, "ms");
    note_speedup(out, serial_ms, insert_ms, r->fo.frame_ms, r->s.procs);
}

static gboolean pm_run(const WlContext *ctx, void *params, SimResult *out,
                       GError **err)
{
    MachMachine *m = ctx->machine;
    PmRun r = {.ctx = ctx, .p = params, .s = ((WlPmParams *)params)->setup};
    if (r.s.procs == 0) {
        const MachKindInfo *k = mach_kind(m, "node");
        r.s.procs = k ? k->count : 0;
    }
    if (!check_machine(m, &r.s, cfg_path(ctx->root, "workload.processors"),
                       err) ||
        !check_radices(&r.s.comp, r.s.procs,
                       cfg_path(ctx->root, "workload.radices"), err) ||
        !check_order(r.p, r.s.procs, cfg_path(ctx->root, "workload.visibility"),
                     err) ||
        !(r.s.rung == WL_PM_RUNG_PIXELS
              ? wl_pm_costs_from_machine(m, r.p->count_bytes, &r.c, err)
              : wl_pm_composite_costs_from_machine(m, r.p->count_bytes, &r.c,
                                                   err)))
        return FALSE;
    r.procs = g_new(MachProc *, r.s.procs);
    for (guint q = 0; q < r.s.procs; q++)
        r.procs[q] = mach_proc(m, "node", q);
    gboolean ok = TRUE;
    SimEngine *eng = mach_engine(m);
    for (int f = 0; ok && f < ctx->frames && !sim_engine_cut(eng); f++)
        ok = run_frame(&r, f, out, err);
    if (ok) {
        mach_fill_result(m, out);
        if (!sim_engine_cut(eng))
            run_metrics(&r, out);
        out->elapsed = sim_now(eng);
    }
    wl_pm_frame_out_clear(&r.fo, r.s.procs);
    g_free(r.procs);
    return ok;
}

/* Every metric pm_run sets (docs/workloads.md, "pixelmerge"). */
static const WlMetric pm_metrics[] = {
    {"processors", "", "P, the processors run"},
    {"resolution", "", "N, the image side in pixels"},
    {"span_ms", "ms", "span-list creation: the slowest node's time"},
    {"zbuf_ms", "ms", "local z-buffering: the slowest node's time"},
    {"merge_ms", "ms", "pixel merging, from the last local z-buffer's end"},
    {"frame_ms", "ms", "the whole frame (last frame)"},
    {"serial_ms", "ms", "the local phases of the whole scene on one node"},
    {"speedup", "", "serial_ms / frame_ms"},
    {"utilisation", "", "busy time of the P nodes / (P x frame time)"},
    {"concurrent_volume", "B",
     "sum over exchange steps of the step's largest message (Fig. 1)"},
    {"merge_bytes", "B", "all pixel-merge bytes sent"},
    {"load_imbalance", "",
     "(max - min) / mean merge operations per node (Fig. 2)"},
    {"partition_imbalance", "",
     "(max - min) / mean pixels each owner z-buffers"},
    {"polygons", "", "Table 1: polygons in the scene"},
    {"tpg", "", "Table 1: total pixels generated"},
    {"tpf", "", "Table 1: pixels in the final picture"},
    {"peak_memory", "B", "largest per-node footprint (memory model)"},
    {"memory_base", "B", "that node's footprint: fixed part"},
    {"memory_polygons", "B", "that node's footprint: its polygons"},
    {"memory_spans", "B", "that node's footprint: its span lists"},
    {"memory_zbuffer", "B", "that node's footprint: z-buffer (or WPA+MSA)"},
    {"memory_buffers", "B", "that node's footprint: message buffers"},
    {"image_matches_serial", "",
     "1 when the merged image equals the serial render (check_image)"},
    {"serial_insert_ms", "ms",
     "of serial_ms, the span-list insertion steps (docs/validation.md)"},
    {"composite_stages", "",
     "compositing schemes: stages (binary swap's fold counts as one)"},
    {"merge_messages", "", "compositing schemes: messages sent in the merge"},
    {"merge_records", "",
     "compositing schemes: pixel records (or locations) the messages carry"},
    {"image_overlap", "",
     "compositing schemes: the processes' active pixels over the final "
     "picture's (sort-last's overlap: images covering a covered pixel)"},
    {NULL, NULL, NULL},
};

const WlOps wl_pixelmerge_ops = {
    .name = "pixelmerge",
    .summary = "kurc96: object-space parallel rendering with active "
               "pixel merging on a hypercube (iPSC/2)",
    .parse = pm_parse,
    .free_params = pm_free_params,
    .plan = wl_plan_machine_scene,
    .run = pm_run,
    .mem_bytes = pm_mem_bytes,
    .needs = wl_pm_needs,
    .metrics = pm_metrics,
};
