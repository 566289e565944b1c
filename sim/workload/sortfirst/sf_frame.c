/* sf_frame.c — sort-first frames on the machine (sf_frame.h; seed 000
 * §3.3.2 push communication, §4.1 the two passes: a sorting pass over
 * the chunks' bounding boxes, then the rendering pass): the node costs
 * the run declares, each frame's events on the processors (traversal,
 * sort, pack, the exchange or pull requests, the current-frame estimate
 * and split, edits, unpack and render) and the run's lifetime.  A
 * region's rendering is sf_render.c, the frame's figures and checks
 * sf_figures.c; the three share sf_frame_internal.h.
 */
#include "sim/workload/sortfirst/sf_frame_internal.h"
#include <string.h>

const char *const wl_sf_cost_ops[] = {"transform_vertex", "span_create",
                                      "pixel_zbuffer",    "chunk_pack",
                                      "grid_cell",        "node_visit",
                                      "pointer_update",   "sphere_bound",
                                      "request_interrupt", "pixel_readout",
                                      "pixel_assemble",
                                      NULL};
/* Each op's portable work (sim/machine/work.h; the estimates in
 * models/cluster-ib.yaml's notes): a cost the model lacks is derived
 * from it on the node's processor description. */
static const MachWork sf_work[] = {
    {"transform_vertex", {[MACH_W_VERTEX] = 1}},
    {"span_create", {[MACH_W_FLOP] = 4, [MACH_W_INSTR] = 20}},
    {"pixel_zbuffer", {[MACH_W_PIXEL] = 1}},
    /* copy a 36-byte triangle: read and write it, and a list insert */
    {"chunk_pack", {[MACH_W_INSTR] = 10, [MACH_W_MEMBYTE] = 72}},
    {"grid_cell", {[MACH_W_INSTR] = 3}},
    /* a 4x4 matrix product (64 multiply-adds) and 3 list misses */
    {"node_visit", {[MACH_W_FLOP] = 128, [MACH_W_INSTR] = 20,
                    [MACH_W_MISS] = 3}},
    {"pointer_update", {[MACH_W_INSTR] = 6}},
    /* a bounding sphere against the clip matrix's rows and planes and
     * its two tangent quadratics: ~150 flops */
    {"sphere_bound", {[MACH_W_FLOP] = 150, [MACH_W_INSTR] = 20}},
    /* an interrupt, the kernel's handler and two context switches: a few
     * thousand instructions and the cache lines they touch */
    {"request_interrupt", {[MACH_W_INSTR] = 3000, [MACH_W_MISS] = 20}},
    /* copy one 4-byte pixel (read it, write it) */
    {"pixel_readout", {[MACH_W_INSTR] = 1, [MACH_W_MEMBYTE] = 8}},
    {"pixel_assemble", {[MACH_W_INSTR] = 1, [MACH_W_MEMBYTE] = 8}},
    {NULL, {0}}};
const MachNeed wl_sf_needs[] = {{"node", wl_sf_cost_ops, sf_work},
                                {NULL, NULL, NULL}};

gboolean wl_sf_costs_from_machine(const MachMachine *m, WlSfCosts *c,
                                  GError **err)
{
    MachCosts *set = mach_costs_new(m, wl_sf_needs, err);
    if (!set)
        return FALSE;
    SimTime *const dst[] = {&c->transform_vertex, &c->span_create,
                            &c->pixel_zbuffer,    &c->chunk_pack,
                            &c->grid_cell,        &c->node_visit,
                            &c->pointer_update,   &c->sphere_bound,
                            &c->request_interrupt, &c->pixel_readout,
                            &c->pixel_assemble};
    G_STATIC_ASSERT(G_N_ELEMENTS(dst) == G_N_ELEMENTS(wl_sf_cost_ops) - 1);
    mach_costs_fill(set, "node", wl_sf_cost_ops, dst);
    mach_costs_free(set);
    return TRUE;
}

/* ---- the frame's events ---------------------------------------------------
 */

static void start_frame(SimEngine *eng, void *ctx, void *arg);

/* The work is given to the machine as named counts of the node's
 * costs (wl_sf_cost_ops), so a recording writes counts: one op, one
 * count (a bounding box test: 8 transformed vertices). */
static MachOps ops1(const char *op, uint64_t n)
{
    MachOps o = {.op = {{op, n}}, .n = 1};
    return o;
}

/* `boxes` bounding-volume tests of the database's kind (sf_bv.h; an
 * axis-aligned box: 8 transformed vertices). */
static void add_boxes(const WlSfRun *r, MachOps *o, uint64_t boxes)
{
    WlSfBvCost c = wl_sf_bv_cost(r->db);
    mach_ops_add(o, "transform_vertex", c.verts * boxes);
    if (c.spheres)
        mach_ops_add(o, "sphere_bound", c.spheres * boxes);
}

static void charge(WlSfRun *r, WlSfProc *pr, const MachOps *o, unsigned ph,
                   SimHandler done, guint arg)
{
    mach_proc_compute_list(pr->proc, o, ph, done, r, GUINT_TO_POINTER(arg));
}

/* Processor p's traversal of the hierarchy, the first thing its first
 * pass does (sf_trav.h): charged in phase `traverse`. */
static void traverse(WlSfRun *r, WlSfProc *pr)
{
    const WlSfTravProc *tp = &r->tp[pr->p];
    MachOps o = ops1("node_visit", tp->nodes);
    add_boxes(r, &o, tp->tests);
    charge(r, pr, &o, r->ph_traverse, NULL, 0);
}

static void render_done(SimEngine *eng, void *ctx, void *arg);

/* Processor q's grid as sent: dense (G^2 counts) unless the sparse
 * list of its non-zero cells, (index, count) pairs of bytes.cell each,
 * is smaller; *entries: the cells a receiver adds. */
static uint64_t grid_bytes(const WlSfRun *r, guint q, uint64_t *entries)
{
    uint64_t g2 = (uint64_t)r->adapt->grid * r->adapt->grid;
    uint64_t nz = r->adapt->nz[q];
    gboolean sparse = 2 * nz < g2;
    if (entries)
        *entries = sparse ? nz : g2;
    return (sparse ? 2 * nz : g2) * r->s.sizes.cell;
}

/* Grid cells processor p handles after the exchange: its own grid, the
 * P - 1 received ones added in, then the split. */
uint64_t wl_sf_partition_cells(const WlSfRun *r, guint p)
{
    uint64_t n = (uint64_t)r->adapt->grid * r->adapt->grid, e;
    for (guint q = 0; q < r->s.procs; q++)
        if (q != p) {
            grid_bytes(r, q, &e);
            n += e;
        }
    return n + r->split_cells;
}

/* Bytes processor p's grid and region work (feedback, 8 B) add to each
 * message it sends. */
uint64_t wl_sf_estimate_bytes(const WlSfRun *r, guint p)
{
    return grid_bytes(r, p, NULL) + (r->s.feedback ? 8 : 0);
}

/* Bytes riding on p's exchange messages (previous-frame estimate). */
static uint64_t ride_bytes(const WlSfRun *r, guint p)
{
    return !r->adapt || r->s.current ? 0 : wl_sf_estimate_bytes(r, p);
}

static void render(WlSfRun *r, WlSfProc *pr)
{
    g_array_set_size(r->render, 0);
    wl_sf_book_render_set(r->book, pr->p, pr->fresh, r->render, &pr->w);
    wl_sf_render_region(r, pr);
    MachOps unpack = ops1("chunk_pack", pr->w.recv_polys);
    add_boxes(r, &unpack, pr->w.new_boxes);
    MachOps draw = ops1("transform_vertex", pr->rc.verts);
    mach_ops_add(&draw, "span_create", pr->spans);
    mach_ops_add(&draw, "pixel_zbuffer", pr->pixels);
    pr->region_work = sim_time_add_sat(mach_proc_ops_cost(pr->proc, &unpack),
                                       mach_proc_ops_cost(pr->proc, &draw));
    charge(r, pr, &unpack, r->ph_unpack, NULL, 0);
    if (!r->adapt || r->s.current) {
        charge(r, pr, &draw, r->ph_render, render_done, pr->p);
        return;
    }
    charge(r, pr, &draw, r->ph_render, NULL, 0);
    MachOps part = ops1("grid_cell", wl_sf_partition_cells(r, pr->p));
    charge(r, pr, &part, r->ph_partition, render_done, pr->p);
}

static void maybe_render(WlSfRun *r, WlSfProc *pr)
{
    guint want = r->s.mig == WL_SF_PULL ? pr->expect : r->s.procs - 1;
    if (pr->sorted && pr->received == want)
        render(r, pr);
}

static void arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    WlSfRun *r = ctx;
    const WlSfBatch *bt = d->payload;
    WlSfProc *pr = &r->procs[bt->dst];
    wl_sf_book_receive(r->book, bt, &pr->w);
    g_array_append_vals(pr->fresh, bt->chunks->data, bt->chunks->len);
    pr->received++;
    maybe_render(r, pr);
}

/* ---- pull: requests and answers (sf_book.h) ------------------------------ */

static void serve_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    WlSfRun *r = ctx;
    WlSfBatch *reply = arg;
    net_send(r->net, mach_proc_id(r->procs[reply->src].proc),
             mach_proc_id(r->procs[reply->dst].proc), reply->bytes, reply,
             arrive, r);
}

/* A request reaches its master, which packs the answer when free. */
static void request_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    WlSfRun *r = ctx;
    const WlSfBatch *req = d->payload;
    WlSfProc *m = &r->procs[req->dst];
    WlSfBatch *reply = &m->reply[req->src];
    wl_sf_book_serve(r->book, req, reply, &m->w);
    m->w.served++;
    MachOps irq = ops1("request_interrupt", 1);
    charge(r, m, &irq, r->ph_interrupt, NULL, 0);
    MachOps o = ops1("chunk_pack", reply->polys);
    mach_proc_compute_list(m->proc, &o, r->ph_pack, serve_done, r, reply);
}

static void pull_requests(WlSfRun *r, WlSfProc *pr)
{
    for (guint q = 0; q < r->s.procs; q++) {
        WlSfBatch *bt = &pr->out[q];
        if (q == pr->p || !bt->chunks->len)
            continue;
        pr->expect++;
        net_send(r->net, mach_proc_id(pr->proc), mach_proc_id(r->procs[q].proc),
                 bt->bytes, bt, request_arrive, r);
    }
}

static void sort_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    WlSfRun *r = ctx;
    WlSfProc *pr = &r->procs[GPOINTER_TO_UINT(arg)];
    if (r->s.mig == WL_SF_PULL) {
        pull_requests(r, pr);
        pr->sorted = TRUE;
        maybe_render(r, pr);
        return;
    }
    for (guint q = 0; q < r->s.procs; q++) {
        if (q == pr->p)
            continue;
        WlSfBatch *bt = &pr->out[q];
        net_send(r->net, mach_proc_id(pr->proc), mach_proc_id(r->procs[q].proc),
                 bt->bytes + ride_bytes(r, pr->p), bt, arrive, r);
    }
    pr->sorted = TRUE;
    maybe_render(r, pr);
}

/* p's sort pass on the book: state changes at the frame's start. */
static void sort_book(WlSfRun *r, WlSfProc *pr)
{
    memset(&pr->w, 0, sizeof pr->w);
    memset(&pr->rc, 0, sizeof pr->rc);
    g_array_set_size(pr->fresh, 0);
    pr->received = pr->expect = 0;
    pr->sorted = FALSE;
    if (r->s.mig == WL_SF_PULL)
        wl_sf_book_pull_sort(r->book, pr->p, pr->out, &pr->w);
    else
        wl_sf_book_sort(r->book, pr->p, pr->out, &pr->w);
}

/* The sort's time: traversal, box transforms, packing. */
static void sort_charge(WlSfRun *r, WlSfProc *pr)
{
    const WlSfTravProc *tp = &r->tp[pr->p];
    g_assert(tp->master_culled <= pr->w.master_boxes &&
             tp->slave_culled <= pr->w.slave_boxes);
    MachOps t = {0};
    add_boxes(r, &t, pr->w.master_boxes + pr->w.slave_boxes +
                      pr->w.probe_boxes - tp->master_culled -
                      tp->slave_culled);
    if (!(r->adapt && r->s.current)) /* else the estimate traversed */
        traverse(r, pr);
    if (r->adapt && r->s.current) { /* master boxes done by the estimate */
        t.n = 0;
        add_boxes(r, &t, pr->w.slave_boxes - tp->slave_culled);
    } else if (r->adapt) /* an extrapolation: one more cell's work */
        mach_ops_add(&t, "grid_cell",
                     r->adapt->added[pr->p] * (r->s.predict ? 2 : 1));
    charge(r, pr, &t, r->ph_sort, NULL, 0);
    MachOps pack = ops1("chunk_pack", pr->w.sent_polys);
    charge(r, pr, &pack, r->ph_pack, sort_done, pr->p);
}

static void sort(WlSfRun *r, WlSfProc *pr)
{
    sort_book(r, pr);
    sort_charge(r, pr);
}

/* ---- the current-frame estimate (estimate: current) ---------------------
 * Each processor transforms its master boxes and fills its grid, sends
 * the grid to every other, and when it holds all P grids sums them,
 * splits, and sorts into the regions just made. */

static void split_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    WlSfRun *r = ctx;
    sort(r, &r->procs[GPOINTER_TO_UINT(arg)]);
}

static void maybe_split(WlSfRun *r, WlSfProc *pr)
{
    if (!pr->estimated || pr->grids + 1 < r->s.procs)
        return;
    MachOps o = ops1("grid_cell", wl_sf_partition_cells(r, pr->p));
    charge(r, pr, &o, r->ph_partition, split_done, pr->p);
}

static void grid_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    WlSfProc *pr = d->payload;
    pr->grids++;
    maybe_split(ctx, pr);
}

static void estimate_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    WlSfRun *r = ctx;
    WlSfProc *pr = &r->procs[GPOINTER_TO_UINT(arg)];
    for (guint q = 0; q < r->s.procs; q++)
        if (q != pr->p)
            net_send(r->net, mach_proc_id(pr->proc),
                     mach_proc_id(r->procs[q].proc),
                     wl_sf_estimate_bytes(r, pr->p), &r->procs[q],
                     grid_arrive, r);
    pr->estimated = TRUE;
    maybe_split(r, pr);
}

/* Instances of the chunks p masters now. */
static uint64_t own_boxes(const WlSfRun *r, guint p)
{
    uint64_t n = 0;
    for (guint c = 0; c < wl_sf_n_chunks(r->db); c++)
        if (wl_sf_book_master(r->book, c) == p)
            n += wl_sf_chunk(r->db, c)->n_inst;
    return n;
}

static void estimate(WlSfRun *r, WlSfProc *pr)
{
    pr->grids = 0;
    pr->estimated = FALSE;
    traverse(r, pr);
    MachOps o = {0};
    add_boxes(r, &o, own_boxes(r, pr->p) - r->tp[pr->p].master_culled);
    mach_ops_add(&o, "grid_cell", r->adapt->added[pr->p]);
    charge(r, pr, &o, r->ph_estimate, estimate_done, pr->p);
}

/* The regions of this frame and the next (the split of this frame's
 * estimate: this frame's own with estimate: current, else the next's). */
static void plan_regions(WlSfRun *r)
{
    wl_sf_adapt_estimate(r->adapt, r->db, &r->regions, r->view.view_proj);
    r->next = r->regions;
    r->split_cells = wl_sf_adapt_split(r->adapt, &r->next);
    double total = 0, max = 0;
    for (guint p = 0; p < r->s.procs; p++) {
        double w = (double)wl_sf_adapt_weight_in(r->adapt, &r->next,
                                                 r->next.rect[p]);
        total += w;
        max = MAX(max, w);
    }
    r->split_imbalance = wl_sf_max_over_mean(max, total, r->s.procs);
    if (r->s.current)
        r->regions = r->next;
}

/* ---- edits (sf_edit.h) ----------------------------------------------------
 * The application on processor 0 edits the database between frames; it
 * sends the frame's commands to every other processor, each of which
 * applies them (and maintains its max-set skeleton) before its first
 * pass: node_visit per command and per max-set node created or
 * collected, pointer_update per pointer created or collected. */

static void edit_apply(WlSfRun *r)
{
    memset(&r->ef, 0, sizeof r->ef);
    memset(r->ew, 0, r->s.procs * sizeof *r->ew);
    if (!r->edit || r->frame == 0)
        return;
    gint64 *map = wl_sf_edit_frame(r->edit, r->book, &r->ef, r->ew);
    if (map && r->adapt && r->adapt->last_x)
        wl_sf_adapt_remap(r->adapt, map, wl_sf_n_insts(r->db));
    g_free(map);
}

uint64_t wl_sf_edit_message(const WlSfRun *r)
{
    return r->s.sizes.message + r->ef.commands * r->s.sizes.edit;
}

/* p's edit work as named counts of the node's costs. */
MachOps wl_sf_edit_ops(const WlSfRun *r, guint p)
{
    uint64_t nodes = r->ef.commands;
    if (r->s.bk == WL_SF_MAXSET)
        nodes += r->ef.nodes_created + r->ef.nodes_collected;
    MachOps o = ops1("node_visit", nodes);
    mach_ops_add(&o, "pointer_update",
                 r->ew[p].ptr_created + r->ew[p].ptr_collected);
    return o;
}

/* p's frame work after the edits: its first pass. */
static void begin(WlSfRun *r, WlSfProc *pr)
{
    MachOps o = wl_sf_edit_ops(r, pr->p);
    if (r->ef.commands)
        charge(r, pr, &o, r->ph_edit, NULL, 0);
    if (r->adapt && r->s.current)
        estimate(r, pr);
    else
        sort_charge(r, pr);
}

static void edit_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    begin(ctx, d->payload);
}

static void edit_send(WlSfRun *r)
{
    for (guint q = 1; r->ef.commands && q < r->s.procs; q++)
        net_send(r->net, mach_proc_id(r->procs[0].proc),
                 mach_proc_id(r->procs[q].proc), wl_sf_edit_message(r),
                 &r->procs[q], edit_arrive, r);
}

/* The instances' screen rectangles of this frame: made once per frame
 * (kept in setup `screens` when given), read by the bucket sort and by
 * the overlap figures.  Edits change the instances, so the own store
 * follows their number. */
static const WlSfScreen *frame_screens(WlSfRun *r)
{
    gboolean fresh = TRUE;
    guint n = wl_sf_n_insts(r->db);
    WlSfScreen *s;
    if (r->s.screens) {
        s = wl_sf_screen_set_get(r->s.screens, (guint)r->frame, n,
                                 r->view.view_proj, &fresh);
    } else {
        r->scr_own = g_renew(WlSfScreen, r->scr_own, n + 1);
        s = r->scr_own;
    }
    if (fresh)
        wl_sf_book_screens(r->book, r->view.view_proj, s);
    return s;
}

/* Dynamic mastership with `offscreen: spread`: the off-screen masters
 * made even once every processor has sorted (sf_mastership.c). */
static void spread(WlSfRun *r)
{
    WlSfBatch *out[WL_SF_MAX_PROCS];
    WlSfBookWork *w[WL_SF_MAX_PROCS];
    if (r->s.ms != WL_SF_DYNAMIC || r->s.off != WL_SF_OFF_SPREAD ||
        (r->adapt && r->s.current)) /* the sorts come one at a time */
        return;
    for (guint p = 0; p < r->s.procs; p++) {
        out[p] = r->procs[p].out;
        w[p] = &r->procs[p].w;
    }
    wl_sf_book_spread(r->book, out, w);
}

static void start_frame(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    WlSfRun *r = ctx;
    r->start = sim_now(eng);
    r->done = 0;
    r->fb_bytes = 0;
    if (r->s.fb == WL_SF_FB_NODE)
        r->fb_busy0 = mach_proc_busy_phase(r->fb, r->ph_assemble);
    r->view = wl_sf_frame_view(r->scene, &r->s, (guint)r->frame);
    rast_zbuffer_clear(r->zb);
    edit_apply(r);
    if (r->adapt)
        plan_regions(r);
    r->book->regions = r->regions; /* the bucket sorts use this frame's */
    r->scr = frame_screens(r);
    wl_sf_book_need_from(r->book, r->scr);
    memset(&r->trav, 0, sizeof r->trav);
    wl_sf_trav_count(r->book, r->s.trav, &r->trav, r->tp);
    for (guint p = 0; p < r->s.procs; p++) {
        r->procs[p].busy0 = mach_proc_busy(r->procs[p].proc);
        if (!(r->adapt && r->s.current))
            sort_book(r, &r->procs[p]);
    }
    spread(r);
    edit_send(r);
    for (guint p = 0; p < r->s.procs; p++)
        if (!r->ef.commands || p == 0) /* others: when the edits arrive */
            begin(r, &r->procs[p]);
}

/* Cost feedback: this frame's region work (unpack + render) per
 * estimated polygon of each region weights the cells of the splits to
 * come.  Each processor's figure (8 B) rides on its next frame's grid
 * messages (the exchange's with the previous-frame estimate, the
 * estimate's own with current), so it reaches the next split made. */
static void calibrate(WlSfRun *r)
{
    double work[WL_SF_MAX_PROCS];
    for (guint p = 0; p < r->s.procs; p++)
        work[p] = (double)r->procs[p].region_work;
    wl_sf_adapt_calibrate(r->adapt, &r->regions, work);
}

static void render_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    WlSfRun *r = ctx;
    wl_sf_fbuf_region(r, &r->procs[GPOINTER_TO_UINT(arg)]);
}

void wl_sf_frame_end(WlSfRun *r, SimEngine *eng)
{
    WlSfFrameStats st = {.start = r->start, .end = sim_now(eng),
                         .trav = r->trav};
    wl_sf_frame_sum(r, &st);
    GError *e = NULL;
    gboolean ok = wl_sf_frame_check(r, &st, &e) &&
                  (!r->hook || r->hook(r->hook_ctx, r->frame, r->zb, &e));
    g_array_append_val(r->stats, st);
    if (!ok) {
        sim_engine_fail(eng, e);
        return;
    }
    if (r->adapt) {
        if (r->s.feedback)
            calibrate(r);
        r->regions = r->next;
    }
    if (++r->frame < r->frames)
        sim_schedule_in(eng, 0, start_frame, r, NULL);
}

/* ---- lifetime -------------------------------------------------------------
 */

WlSfRun *wl_sf_run_new(MachMachine *m, const Scene *scene, const WlSfDb *db,
                       const WlSfSetup *s, const WlSfCosts *c)
{
    WlSfRun *r = g_new0(WlSfRun, 1);
    r->m = m;
    r->net = mach_net(m);
    r->eng = mach_engine(m);
    r->scene = scene;
    r->db = db;
    r->s = *s;
    r->c = *c;
    wl_sf_regions_init(&r->regions, s->procs, s->resolution, s->resolution);
    r->book = wl_sf_book_new(db, &r->regions, s->bk, &s->sizes);
    wl_sf_book_set_policy(r->book, s->mig, s->ms);
    g_assert(!s->adaptive || s->mig == WL_SF_PUSH);
    g_assert(s->mig == WL_SF_PUSH || s->trav == WL_SF_TRAV_PLAIN);
    g_assert(!(s->edits && s->pre)); /* edits change the frames' mesh */
    g_assert(!(s->edits && s->screens)); /* and the instances */
    if (s->adaptive) {
        r->adapt = wl_sf_adapt_new(s->grid, s->procs);
        r->adapt->master = r->book->master;
    }
    if (s->adaptive && s->predict && !s->current)
        wl_sf_adapt_predict(r->adapt, wl_sf_n_insts(db));
    r->procs = g_new0(WlSfProc, s->procs);
    r->tp = g_new0(WlSfTravProc, s->procs);
    r->ew = g_new0(WlSfRemapWork, s->procs);
    for (guint p = 0; p < s->procs; p++) {
        WlSfProc *pr = &r->procs[p];
        pr->run = r;
        pr->p = p;
        pr->proc = mach_proc(m, "node", p);
        pr->out = g_new0(WlSfBatch, s->procs);
        for (guint q = 0; q < s->procs; q++)
            wl_sf_batch_init(&pr->out[q]);
        pr->fresh = g_array_new(FALSE, FALSE, sizeof(guint));
        pr->reply = g_new0(WlSfBatch, s->procs);
        for (guint q = 0; q < s->procs; q++)
            wl_sf_batch_init(&pr->reply[q]);
    }
    r->zb = rast_zbuffer_new(s->resolution, s->resolution);
    r->serial = rast_zbuffer_new(s->resolution, s->resolution);
    r->stats = g_array_new(FALSE, TRUE, sizeof(WlSfFrameStats));
    r->render = g_array_new(FALSE, FALSE, sizeof(guint));
    r->subset = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    r->ph_traverse = sim_engine_phase(r->eng, "traverse");
    if (r->s.edits)
        r->ph_edit = sim_engine_phase(r->eng, "edit");
    r->ph_sort = sim_engine_phase(r->eng, "sort");
    r->ph_pack = sim_engine_phase(r->eng, "pack");
    r->ph_unpack = sim_engine_phase(r->eng, "unpack");
    r->ph_render = sim_engine_phase(r->eng, "render");
    if (s->adaptive && s->current)
        r->ph_estimate = sim_engine_phase(r->eng, "estimate");
    if (s->adaptive)
        r->ph_partition = sim_engine_phase(r->eng, "partition");
    if (s->mig == WL_SF_PULL)
        r->ph_interrupt = sim_engine_phase(r->eng, "interrupt");
    if (s->fb == WL_SF_FB_NODE) {
        r->ph_readout = sim_engine_phase(r->eng, "readout");
        r->ph_assemble = sim_engine_phase(r->eng, "assemble");
    }
    r->fb = wl_sf_fbuf_proc(m, s->procs);
    return r;
}

void wl_sf_run_free(WlSfRun *r)
{
    if (!r)
        return;
    for (guint p = 0; p < r->s.procs; p++) {
        for (guint q = 0; q < r->s.procs; q++) {
            wl_sf_batch_clear(&r->procs[p].out[q]);
            wl_sf_batch_clear(&r->procs[p].reply[q]);
        }
        g_free(r->procs[p].out);
        g_free(r->procs[p].reply);
        g_array_unref(r->procs[p].fresh);
    }
    g_free(r->procs);
    g_free(r->scr_own);
    g_free(r->tp);
    g_free(r->ew);
    wl_sf_book_free(r->book);
    wl_sf_adapt_free(r->adapt);
    rast_zbuffer_free(r->zb);
    rast_zbuffer_free(r->serial);
    g_array_unref(r->stats);
    g_array_unref(r->render);
    g_array_unref(r->subset);
    g_free(r);
}

gboolean wl_sf_run_frames(WlSfRun *r, int frames, SimTime until, GError **err)
{
    g_assert(frames >= 1);
    r->frames = r->frame + frames;
    sim_schedule_in(r->eng, 0, start_frame, r, NULL); /* failure: in run */
    return sim_engine_run(r->eng, until, err);
}

void wl_sf_run_set_edit(WlSfRun *r, WlSfEdit *e)
{
    g_assert(r->s.edits && r->frame == 0);
    r->edit = e;
}

void wl_sf_run_set_hook(WlSfRun *r, WlSfFrameHook hook, void *ctx)
{
    r->hook = hook;
    r->hook_ctx = ctx;
}

const GArray *wl_sf_run_stats(const WlSfRun *r)
{
    return r->stats;
}

const WlSfBook *wl_sf_run_book(const WlSfRun *r)
{
    return r->book;
}

const WlSfRegions *wl_sf_run_regions(const WlSfRun *r)
{
    return &r->regions;
}

const RastZBuffer *wl_sf_run_zbuffer(const WlSfRun *r)
{
    return r->stats->len && !wl_sf_prerendered(r) ? r->zb : NULL;
}
