/* pphigs_frame.c — one PPHIGS frame on the Pixel-Planes 5 machine (pphigs_frame.h).
 *
 * Each GP's frame is first planned (a list of steps: traverse, transform
 * and send costs, then one ring message) by walking its portion; the
 * steps then run on the GP's MachProc (FIFO, busy time per phase).
 * Renderers and the frame buffer react to ring arrivals.  Invariant:
 * every region is stored exactly once per frame, so the frame ends when
 * the frame buffer has stored them all.  Hardware costs, processor
 * counts and the ring come from the machine, never from this file.
 * Seed 001 §1.1 (the pipeline), §5.2 (off-screen primitives are cheaper),
 * §6 (processor time).  Cost: see frame.h.
 */
#include "sim/workload/pphigs/pphigs_frame.h"
#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/pphigs_pixels.h"
#include <string.h>

#define NONE G_MAXUINT
#define MAX_GPS 64 /* one bit per GP in the distribution's masks */

typedef struct {
    MachOps trav, xform; /* work before the message, as named counts */
    uint64_t send;       /* commands sent (send_primitive each) */
    guint region;        /* NONE: no batch */
    GArray *cmds;        /* the batch (WlPphigsCmd), owned */
} Step;

typedef struct {
    guint gp, region;
    GArray *cmds; /* the batch's commands, owned */
    gboolean end;
    guint msgs; /* end marker: batches this GP sent to the renderer */
} Msg;

/* A renderer's request for a GP's bin of a region (dynamic regions). */
typedef struct {
    guint gp, region;
} Req;

typedef struct WlPphigsFrame WlPphigsFrame;

typedef struct {
    WlPphigsFrame *f;
    guint id;
    MachProc *p;
    GArray *steps; /* Step */
    guint next;
    GArray **buf;   /* per region: commands buffered (NULL: none) */
    GArray **held;  /* per region: batches kept until it is handed out */
    guint *sent;    /* per renderer: batches sent */
    uint64_t edits; /* elements the host sends before this frame */
} Gp;

typedef struct {
    WlPphigsFrame *f;
    guint id;
    MachProc *p;
    guint cur;      /* the region being rasterised (NONE: none) */
    guint *got, *expect; /* per GP: batches received / announced */
    guint gps_done;
} Rend;

struct WlPphigsFrame {
    MachMachine *m;
    SimEngine *eng;
    NetNet *net;
    WlPphigsFrameSpec s;
    WlPphigsCosts c;
    SimTime gp_send; /* per command sent (0: sends are free) */
    guint ngp, nrend, nx, ny, nregions;
    Gp *gp;
    Rend *rend;
    GArray **pending;     /* per region: commands not yet rasterised */
    WlPphigsRegion **reg; /* per region: its pixels once begun */
    guint *owner;         /* per region: its renderer (NONE: not yet) */
    guint next_region;    /* dynamic: the next region to hand out */
    MachProc *fb, *host;
    guint stored;
    SimTime start, end;
    unsigned ph_trav, ph_xform, ph_send, ph_rast, ph_shade, ph_store, ph_edit;
    double *gp_us;  /* processor time of the frame just run */
    SimTime *busy0; /* traverse + transform busy at the frame's start */
    uint64_t commands, offscreen, prims, host_elems, exprs;
    uint64_t scan_pending; /* host elements examined for the next frame */
    Mat4 vp;
    RastImage *image; /* the frame buffer's pixels */
    GArray *scratch;  /* one primitive's commands while planning */
};

/* Every cost of wl_pphigs_needs, all missing ones in one error. */
static gboolean hw_costs(WlPphigsFrame *f, GError **err)
{
    MachCosts *set = mach_costs_new(f->m, wl_pphigs_needs, err);
    if (set)
        wl_pphigs_costs_fill(set, &f->c, &f->gp_send);
    mach_costs_free(set);
    return set != NULL;
}

/* The kind's processor count, checked against [lo, hi]. */
static gboolean kind_count(const MachMachine *m, const char *kind, guint lo,
                           guint hi, guint *out, GError **err)
{
    const MachKindInfo *k = mach_kind(m, kind);
    *out = k ? k->count : 0;
    if (k && k->count >= lo && k->count <= hi)
        return TRUE;
    char *path = g_strdup_printf("nodes.%s.count", kind);
    const CfgNode *at = cfg_path(mach_model_cfg(m), path);
    char *found = k ? g_strdup_printf("%u %s processors", k->count, kind)
                    : g_strdup_printf("no '%s' processors", kind);
    char *exp = g_strdup_printf("%u .. %u %s processors for a PPHIGS frame", lo,
                                hi, kind);
    cfg_error(err, at ? at : mach_model_cfg(m), found, exp);
    g_free(path);
    g_free(found);
    g_free(exp);
    return FALSE;
}

/* ---- planning a GP's frame -------------------------------------------- */

typedef struct {
    WlPphigsFrame *f;
    Gp *g;
    MachOps trav, xform; /* accumulated since the last step */
    uint64_t send;
} Plan;

static void plan_step(Plan *pl, guint region, GArray *cmds)
{
    Step st = {pl->trav, pl->xform, pl->send, region, cmds};
    g_array_append_val(pl->g->steps, st);
    pl->trav.n = pl->xform.n = 0;
    pl->send = 0;
}

static void plan_command(Plan *pl, guint region, const WlPphigsCmd *c)
{
    WlPphigsFrame *f = pl->f;
    GArray **b = &pl->g->buf[region];
    pl->send++;
    f->commands++;
    if (!*b)
        *b = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    g_array_append_val(*b, *c);
    if ((*b)->len >= f->s.batch) {
        plan_step(pl, region, *b);
        *b = NULL;
    }
}

/* Every region a command's pixel box touches gets the command. */
static void plan_regions(Plan *pl, const WlPphigsCmd *c)
{
    WlPphigsFrame *f = pl->f;
    guint R = f->s.region;
    for (guint y = (guint)c->y0 / R; y <= (guint)c->y1 / R; y++)
        for (guint x = (guint)c->x0 / R; x <= (guint)c->x1 / R; x++)
            plan_command(pl, y * f->nx + x, c);
}

static void plan_prim(const ScenePrimInst *pi, void *ud)
{
    Plan *pl = ud;
    WlPphigsFrame *f = pl->f;
    Mat4 m = mat4_mul(f->vp, pi->matrix);
    gboolean off = scene_pphigs_prim_offscreen(m, pi->el);
    f->prims++;
    wl_pphigs_prim_ops(pi->el, off, &pl->xform);
    if (off) {
        f->offscreen++;
        return;
    }
    g_array_set_size(f->scratch, 0);
    wl_pphigs_cmds(pi, f->vp, f->s.width, f->s.height, f->scratch);
    for (guint i = 0; i < f->scratch->len; i++)
        plan_regions(pl, &g_array_index(f->scratch, WlPphigsCmd, i));
}

static void plan_gp(WlPphigsFrame *f, Gp *g, const SceneDb *db)
{
    g_array_set_size(g->steps, 0);
    g->next = 0;
    memset(g->sent, 0, f->nrend * sizeof *g->sent);
    Plan pl = {.f = f, .g = g};
    wl_pphigs_nonprim_ops(db, &pl.trav);
    plan_step(&pl, NONE, NULL);
    scene_db_traverse(db, plan_prim, &pl);
    for (guint k = 0; k < f->nregions; k++)
        if (g->buf[k]) {
            plan_step(&pl, k, g->buf[k]);
            g->buf[k] = NULL;
        }
    if (mach_proc_ops_cost(g->p, &pl.trav) ||
        mach_proc_ops_cost(g->p, &pl.xform) || (pl.send && f->gp_send))
        plan_step(&pl, NONE, NULL);
}

/* ---- frame buffer ----------------------------------------------------- */

static void fb_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    WlPphigsFrame *f = ctx;
    if (++f->stored == f->nregions)
        f->end = sim_now(eng);
}

static void fb_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    WlPphigsFrame *f = ctx;
    wl_pphigs_region_store(d->payload, f->image);
    wl_pphigs_region_free(d->payload);
    static const MachOp store = {"store_region", 1};
    mach_proc_compute_ops(f->fb, &store, 1, f->ph_store, fb_done, f, NULL);
}

/* ---- renderers -------------------------------------------------------- */

static guint region_bytes(const WlPphigsFrame *f, guint k)
{
    guint R = f->s.region, x = k % f->nx, y = k / f->nx;
    guint w = MIN(R, f->s.width - x * R), h = MIN(R, f->s.height - y * R);
    return w * h * f->s.pixel_bytes;
}

static void rend_take(Rend *r);

static void rend_region_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Rend *r = ctx;
    WlPphigsFrame *f = r->f;
    guint k = GPOINTER_TO_UINT(arg);
    WlPphigsRegion *pixels = f->reg[k];
    f->reg[k] = NULL;
    net_send(f->net, mach_proc_id(r->p), mach_proc_id(f->fb),
             region_bytes(f, k), pixels, fb_arrive, f);
}

static WlPphigsRegion *region_pixels(const WlPphigsFrame *f, guint k)
{
    guint R = f->s.region, x = k % f->nx * R, y = k / f->nx * R;
    return wl_pphigs_region_new((int)x, (int)y, (int)MIN(R, f->s.width - x),
                                (int)MIN(R, f->s.height - y), 0xff000000u);
}

/* Every pixel of region k evaluates each pending command's
 * expressions: the renderer's time is the linear and quadratic
 * expressions it evaluated and one compare-and-store per command. */
static void rend_raster(Rend *r, guint k)
{
    WlPphigsFrame *f = r->f;
    if (!f->reg[k]) {
        f->reg[k] = region_pixels(f, k);
        static const MachOp begin = {"region_begin", 1};
        mach_proc_compute_ops(r->p, &begin, 1, f->ph_rast, NULL, NULL, NULL);
    }
    GArray *cmds = f->pending[k];
    if (!cmds || !cmds->len)
        return;
    uint64_t exprs = 0, quads = 0;
    for (guint i = 0; i < cmds->len; i++) {
        const WlPphigsCmd *c = &g_array_index(cmds, WlPphigsCmd, i);
        wl_pphigs_region_draw(f->reg[k], c);
        exprs += wl_pphigs_cmd_exprs(c);
        quads += wl_pphigs_cmd_quads(c);
    }
    f->exprs += exprs;
    MachOp o[] = {{"expression", exprs}, {"compare", cmds->len},
                  {"quadratic", quads}};
    mach_proc_compute_ops(r->p, o, 3, f->ph_rast, NULL, NULL, NULL);
    g_array_set_size(cmds, 0);
}

static void rend_shade(Rend *r, guint k)
{
    static const MachOp shade = {"region_shade", 1};
    mach_proc_compute_ops(r->p, &shade, 1, r->f->ph_shade, rend_region_done,
                          r, GUINT_TO_POINTER(k));
}

/* Dynamic: region k is rasterised; the renderer asks for its next
 * region, whose commands travel while it shades this one. */
static void rend_rasterised(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Rend *r = ctx;
    rend_shade(r, GPOINTER_TO_UINT(arg));
    rend_take(r);
}

static void rend_complete(Rend *r, guint k)
{
    rend_raster(r, k);
    if (r->f->s.dynamic_regions)
        mach_proc_compute(r->p, 0, r->f->ph_shade, rend_rasterised, r,
                          GUINT_TO_POINTER(k));
    else
        rend_shade(r, k);
}

/* Every GP is done with this renderer's region(s): static, complete its
 * regions in order (id, id + R ...); dynamic, complete the one it holds
 * (rend_region_done then takes the next), or take one if it has none. */
static void rend_finish(Rend *r)
{
    WlPphigsFrame *f = r->f;
    guint k = r->cur;
    r->cur = NONE;
    if (f->s.dynamic_regions) {
        if (k == NONE)
            rend_take(r);
        else
            rend_complete(r, k);
        return;
    }
    for (; k < f->nregions; k += f->nrend)
        rend_complete(r, k);
}

static void rend_check_gp(Rend *r, guint g)
{
    if (r->got[g] == r->expect[g] && ++r->gps_done == r->f->ngp)
        rend_finish(r);
}

/* A batch, a GP's end marker, or (dynamic) a GP's bin of a region. */
static void rend_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    WlPphigsFrame *f = ctx;
    Msg *m = d->payload;
    Rend *r = &f->rend[d->dst - mach_proc_id(f->rend[0].p)];
    if (m->cmds) {
        guint k = m->region;
        if (!f->pending[k])
            f->pending[k] = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
        g_array_append_vals(f->pending[k], m->cmds->data, m->cmds->len);
        g_array_unref(m->cmds);
        r->got[m->gp]++;
        if (k == r->cur)
            rend_raster(r, k);
    }
    if (m->end)
        r->expect[m->gp] = m->msgs;
    rend_check_gp(r, m->gp);
    g_free(m);
}

/* ---- dynamic regions (Fuchs 89: renderers "can be independently
 * reassigned to any part of the screen") ---------------------------------
 *
 * At the frame's start renderer r holds region r; the GPs send batches
 * of held regions as they fill and keep the others' in bins.  Regions
 * are handed out only once every GP has finished (a renderer's first
 * region completes after every GP's end marker), so a renderer that has
 * shaded its region takes the next one in row-major order and asks each
 * GP for its bin (a ring message of end_bytes); each GP answers with one
 * message: its bin's commands (end_bytes when empty). */

static void gp_bin_request(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    WlPphigsFrame *f = ctx;
    Req *q = d->payload;
    Gp *g = &f->gp[q->gp];
    Msg *m = g_new0(Msg, 1);
    m->gp = q->gp;
    m->region = q->region;
    m->cmds = g->held[q->region];
    g->held[q->region] = NULL;
    m->end = TRUE;
    m->msgs = m->cmds ? 1 : 0;
    uint64_t bytes = m->cmds ? (uint64_t)m->cmds->len * f->s.cmd_bytes
                             : f->s.end_bytes;
    net_send(f->net, mach_proc_id(g->p),
             mach_proc_id(f->rend[f->owner[q->region]].p), bytes, m,
             rend_arrive, f);
    g_free(q);
}

static void rend_take(Rend *r)
{
    WlPphigsFrame *f = r->f;
    if (f->next_region >= f->nregions)
        return;
    guint k = f->next_region++;
    f->owner[k] = r->id;
    r->cur = k;
    r->gps_done = 0;
    memset(r->got, 0, f->ngp * sizeof *r->got);
    for (guint g = 0; g < f->ngp; g++) {
        r->expect[g] = NONE;
        Req *q = g_new(Req, 1);
        *q = (Req){g, k};
        net_send(f->net, mach_proc_id(r->p), mach_proc_id(f->gp[g].p),
                 f->s.end_bytes, q, gp_bin_request, f);
    }
}

/* ---- GPs -------------------------------------------------------------- */

static void gp_send_ends(WlPphigsFrame *f, Gp *g)
{
    for (guint r = 0; r < f->nrend; r++) {
        Msg *m = g_new0(Msg, 1);
        m->gp = g->id;
        m->end = TRUE;
        m->msgs = g->sent[r];
        net_send(f->net, mach_proc_id(g->p), mach_proc_id(f->rend[r].p),
                 f->s.end_bytes, m, rend_arrive, f);
    }
}

/* A full (or last) buffer of region k: to its renderer, or into the
 * region's bin while no renderer holds it (dynamic regions). */
static void gp_batch(WlPphigsFrame *f, Gp *g, guint k, GArray *cmds)
{
    guint to = f->owner[k];
    if (to == NONE) {
        if (!g->held[k])
            g->held[k] = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
        g_array_append_vals(g->held[k], cmds->data, cmds->len);
        g_array_unref(cmds);
        return;
    }
    Msg *m = g_new0(Msg, 1);
    m->gp = g->id;
    m->region = k;
    m->cmds = cmds;
    g->sent[to]++;
    net_send(f->net, mach_proc_id(g->p), mach_proc_id(f->rend[to].p),
             (uint64_t)cmds->len * f->s.cmd_bytes, m, rend_arrive, f);
}

static void gp_next(Gp *g);

static void gp_step_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    Gp *g = ctx;
    const Step *st = &g_array_index(g->steps, Step, g->next);
    if (st->region != NONE)
        gp_batch(g->f, g, st->region, st->cmds);
    g->next++;
    gp_next(g);
}

static void gp_next(Gp *g)
{
    WlPphigsFrame *f = g->f;
    if (g->next == g->steps->len) {
        gp_send_ends(f, g);
        return;
    }
    const Step *st = &g_array_index(g->steps, Step, g->next);
    if (mach_proc_ops_cost(g->p, &st->trav))
        mach_proc_compute_list(g->p, &st->trav, f->ph_trav, NULL, NULL, NULL);
    if (mach_proc_ops_cost(g->p, &st->xform))
        mach_proc_compute_list(g->p, &st->xform, f->ph_xform, NULL, NULL,
                               NULL);
    MachOp send = {"send_primitive", st->send};
    mach_proc_compute_ops(g->p, &send, 1, f->ph_send, gp_step_done, g, NULL);
}

static void gp_start(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    gp_next(ctx);
}

/* ---- the host: edits and moves since the last frame ------------------- */

static void gp_edits_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    (void)d;
    gp_next(ctx);
}

static void host_packed(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    Gp *g = ctx;
    WlPphigsFrame *f = g->f;
    net_send(f->net, mach_proc_id(f->host), mach_proc_id(g->p),
             g->edits * f->s.element_bytes, NULL, gp_edits_arrive, g);
}

void wl_pphigs_frame_host_scan(WlPphigsFrame *f, uint64_t elements)
{
    f->scan_pending += elements;
}

/* The host's step back (§3.4-3.5) before it packs anything. */
static void host_scan(WlPphigsFrame *f)
{
    if (!f->scan_pending)
        return;
    MachOp scan = {"scan_element", f->scan_pending};
    mach_proc_compute_ops(f->host, &scan, 1, f->ph_edit, NULL, NULL, NULL);
    f->scan_pending = 0;
}

/* A GP with edits starts when they arrive; the others at once. */
static void gp_launch(WlPphigsFrame *f, Gp *g)
{
    if (!g->edits) {
        sim_schedule_in(f->eng, 0, gp_start, g, NULL);
        return;
    }
    MachOp send = {"send_element", g->edits};
    mach_proc_compute_ops(f->host, &send, 1, f->ph_edit, host_packed, g, NULL);
    f->host_elems += g->edits;
}

/* ---- lifetime --------------------------------------------------------- */

static void rend_init(WlPphigsFrame *f, Rend *r, guint id)
{
    r->f = f;
    r->id = id;
    r->p = mach_proc(f->m, "renderer", id);
    r->got = g_new0(guint, f->ngp);
    r->expect = g_new0(guint, f->ngp);
}

static void gp_init(WlPphigsFrame *f, Gp *g, guint id)
{
    g->f = f;
    g->id = id;
    g->p = mach_proc(f->m, "gp", id);
    g->steps = g_array_new(FALSE, FALSE, sizeof(Step));
    g->buf = g_new0(GArray *, f->nregions);
    g->held = g_new0(GArray *, f->nregions);
    g->sent = g_new0(guint, f->nrend);
}

static void intern_phases(WlPphigsFrame *f)
{
    f->ph_trav = sim_engine_phase(f->eng, "traverse");
    f->ph_xform = sim_engine_phase(f->eng, "transform");
    f->ph_send = sim_engine_phase(f->eng, "send");
    f->ph_rast = sim_engine_phase(f->eng, "rasterise");
    f->ph_shade = sim_engine_phase(f->eng, "shade");
    f->ph_store = sim_engine_phase(f->eng, "store");
    f->ph_edit = sim_engine_phase(f->eng, "edit");
}

static gboolean check_machine(WlPphigsFrame *f, GError **err)
{
    guint nfb, nhost;
    return kind_count(f->m, "host", 1, G_MAXUINT, &nhost, err) &&
           kind_count(f->m, "gp", 1, MAX_GPS, &f->ngp, err) &&
           kind_count(f->m, "renderer", 1, G_MAXUINT16, &f->nrend, err) &&
           kind_count(f->m, "frame_buffer", 1, 1, &nfb, err) &&
           hw_costs(f, err) && mach_require_net(f->m, err);
}

WlPphigsFrame *wl_pphigs_frame_new(MachMachine *m,
                                   const WlPphigsFrameSpec *spec, GError **err)
{
    g_assert(spec->region >= 1 && spec->batch >= 1);
    g_assert(spec->width >= 1 && spec->height >= 1);
    WlPphigsFrame *f = g_new0(WlPphigsFrame, 1);
    f->m = m;
    f->eng = mach_engine(m);
    f->s = *spec;
    if (!check_machine(f, err)) {
        g_free(f);
        return NULL;
    }
    f->net = mach_net(m);
    f->nx = (spec->width + spec->region - 1) / spec->region;
    f->ny = (spec->height + spec->region - 1) / spec->region;
    f->nregions = f->nx * f->ny;
    intern_phases(f);
    f->fb = mach_proc(m, "frame_buffer", 0);
    f->image = rast_image_new((int)spec->width, (int)spec->height);
    f->scratch = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    f->host = mach_proc(m, "host", 0);
    f->gp_us = g_new0(double, f->ngp);
    f->busy0 = g_new0(SimTime, f->ngp);
    f->pending = g_new0(GArray *, f->nregions);
    f->reg = g_new0(WlPphigsRegion *, f->nregions);
    f->owner = g_new0(guint, f->nregions);
    f->gp = g_new0(Gp, f->ngp);
    for (guint g = 0; g < f->ngp; g++)
        gp_init(f, &f->gp[g], g);
    f->rend = g_new0(Rend, f->nrend);
    for (guint r = 0; r < f->nrend; r++)
        rend_init(f, &f->rend[r], r);
    return f;
}

void wl_pphigs_frame_free(WlPphigsFrame *f)
{
    if (!f)
        return;
    for (guint g = 0; g < f->ngp; g++) {
        g_array_unref(f->gp[g].steps);
        for (guint k = 0; k < f->nregions; k++)
            if (f->gp[g].held[k])
                g_array_unref(f->gp[g].held[k]);
        g_free(f->gp[g].buf);
        g_free(f->gp[g].held);
        g_free(f->gp[g].sent);
    }
    for (guint k = 0; k < f->nregions; k++) {
        if (f->pending[k])
            g_array_unref(f->pending[k]);
        wl_pphigs_region_free(f->reg[k]);
    }
    for (guint r = 0; r < f->nrend; r++) {
        g_free(f->rend[r].got);
        g_free(f->rend[r].expect);
    }
    g_free(f->pending);
    g_free(f->reg);
    g_free(f->owner);
    g_free(f->gp);
    g_free(f->rend);
    g_free(f->gp_us);
    g_free(f->busy0);
    rast_image_free(f->image);
    g_array_unref(f->scratch);
    g_free(f);
}

const RastImage *wl_pphigs_frame_image(const WlPphigsFrame *f)
{
    return f->image;
}

guint wl_pphigs_frame_gps(const WlPphigsFrame *f)
{
    return f->ngp;
}

const WlPphigsCosts *wl_pphigs_frame_costs(const WlPphigsFrame *f)
{
    return &f->c;
}

/* ---- running ---------------------------------------------------------- */

static SimTime gp_busy(const WlPphigsFrame *f, guint g)
{
    const MachProc *p = f->gp[g].p;
    return mach_proc_busy_phase(p, f->ph_trav) +
           mach_proc_busy_phase(p, f->ph_xform);
}

/* Static: region k is renderer k mod R's; dynamic: renderer r holds
 * region r, the rest wait to be handed out (rend_take). */
static void frame_reset(WlPphigsFrame *f)
{
    gboolean dyn = f->s.dynamic_regions;
    for (guint k = 0; k < f->nregions; k++)
        f->owner[k] = dyn && k >= f->nrend ? NONE : k % f->nrend;
    f->next_region = MIN(f->nrend, f->nregions);
    for (guint r = 0; r < f->nrend; r++) {
        Rend *x = &f->rend[r];
        x->cur = r < f->nregions ? r : NONE;
        x->gps_done = 0;
        memset(x->got, 0, f->ngp * sizeof *x->got);
        for (guint g = 0; g < f->ngp; g++)
            x->expect[g] = NONE;
    }
    for (guint g = 0; g < f->ngp; g++)
        f->busy0[g] = gp_busy(f, g);
    f->stored = 0;
    f->commands = f->offscreen = f->prims = f->host_elems = f->exprs = 0;
    rast_image_fill(f->image, (RastColor){0, 0, 0});
    f->start = f->end = sim_now(f->eng);
}

gboolean wl_pphigs_frame_run(WlPphigsFrame *f, const WlPphigsDist *d, Mat4 vp,
                             const uint64_t *host_elems,
                             WlPphigsFrameStats *out, GError **err)
{
    g_assert(wl_pphigs_dist_ngp(d) == f->ngp);
    frame_reset(f);
    f->vp = vp;
    host_scan(f);
    for (guint g = 0; g < f->ngp; g++) {
        plan_gp(f, &f->gp[g], wl_pphigs_dist_gp(d, g));
        f->gp[g].edits = host_elems ? host_elems[g] : 0;
        gp_launch(f, &f->gp[g]);
    }
    if (!sim_engine_run(f->eng, SIM_TIME_MAX, err))
        return FALSE;
    if (sim_engine_cut(f->eng)) /* run.until ended it: no frame figures */
        return TRUE;
    g_assert(f->stored == f->nregions);
    for (guint g = 0; g < f->ngp; g++)
        f->gp_us[g] = sim_time_to_us(gp_busy(f, g) - f->busy0[g]);
    out->time = f->end - f->start;
    out->gp_time_us = f->gp_us;
    out->commands = f->commands;
    out->offscreen = f->offscreen;
    out->primitives = f->prims;
    out->host_elements = f->host_elems;
    out->expressions = f->exprs;
    return TRUE;
}

void wl_pphigs_frame_util(const WlPphigsFrame *f, SimTime elapsed,
                          double *gp_util, double *rend_util)
{
    double e = (double)MAX(elapsed, 1), gs = 0, rs = 0;
    for (guint g = 0; g < f->ngp; g++)
        gs += (double)mach_proc_busy(f->gp[g].p) / e;
    for (guint i = 0; i < f->nrend; i++)
        rs += (double)mach_proc_busy(f->rend[i].p) / e;
    *gp_util = gs / f->ngp;
    *rend_util = rs / f->nrend;
}

void wl_pphigs_frame_rend_range(const WlPphigsFrame *f, SimTime elapsed,
                                double *lo, double *hi)
{
    double e = (double)MAX(elapsed, 1);
    *lo = 1e300, *hi = 0;
    for (guint i = 0; i < f->nrend; i++) {
        double u = (double)mach_proc_busy(f->rend[i].p) / e;
        *lo = MIN(*lo, u), *hi = MAX(*hi, u);
    }
}
