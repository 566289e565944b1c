/* frame.c — one PPHIGS frame on the Pixel-Planes 5 model (see frame.h).
 *
 * Each GP's frame is first planned (a list of steps: traverse cost, send
 * cost, then one ring message) by walking its portion; the steps then run
 * as events on a FIFO processor.  Renderers and the frame buffer react to
 * arrivals.  Invariant: every region is stored exactly once per frame, so
 * the frame ends when the frame buffer has stored them all.
 * Seed 001 §1.1 (the pipeline), §5.2 (off-screen primitives are cheaper),
 * §6 (processor time).  Cost: see frame.h.
 */
#include "sim/workload/pphigs/frame.h"
#include "sim/scene/pphigs_db.h"
#include <string.h>

#define NONE G_MAXUINT

typedef struct {
    SimTime free_at;
    SimBusy busy;
} Proc;

typedef struct {
    SimTime trav, send; /* work before the message */
    guint region;       /* NONE: no batch */
    guint count;        /* commands in the batch */
} Step;

typedef struct {
    guint gp, region, count;
    gboolean end;
    guint msgs; /* end marker: batches this GP sent to the renderer */
} Msg;

typedef struct WlPphigsFrame WlPphigsFrame;

typedef struct {
    WlPphigsFrame *f;
    guint id;
    Proc p;
    GArray *steps; /* Step */
    guint next;
    guint *buf;    /* per region: commands buffered */
    guint *sent;   /* per renderer: batches sent */
} Gp;

typedef struct {
    WlPphigsFrame *f;
    guint id;
    Proc p;
    guint nreg;      /* its regions: id, id + R, id + 2R ... */
    guint cur;       /* local index of the region being rasterised */
    guint *pending;  /* per local region: commands not yet rasterised */
    gboolean *begun;
    guint *got, *expect; /* per GP: batches received / announced */
    guint gps_done;
} Rend;

struct WlPphigsFrame {
    SimEngine *eng;
    NetNet *net;
    WlPphigsFrameSpec s;
    guint ngp, nx, ny, nregions;
    Gp *gp;
    Rend *rend;
    Proc fb;
    guint stored;
    SimTime start, end;
    unsigned ph_trav, ph_send, ph_rast, ph_shade, ph_store;
    double *trav_us;
    uint64_t commands, offscreen, prims;
    Mat4 vp;
};

/* ---- processors ------------------------------------------------------- */

static void proc_compute(WlPphigsFrame *f, Proc *p, SimTime cost,
                         unsigned phase, SimHandler done, void *ctx,
                         void *arg)
{
    SimTime start = MAX(sim_now(f->eng), p->free_at);
    p->free_at = start + cost;
    sim_busy_add(&p->busy, phase, cost);
    if (done)
        sim_schedule_at(f->eng, p->free_at, done, ctx, arg);
}

static SimTime us_to_ps(double us)
{
    SimTime t = 0;
    sim_time_from_s(us * 1e-6, &t);
    return t;
}

static guint station_gp(const WlPphigsFrame *f, guint g)
{
    (void)f;
    return 1 + g;
}

static guint station_rend(const WlPphigsFrame *f, guint r)
{
    return 1 + f->ngp + r;
}

static guint station_fb(const WlPphigsFrame *f)
{
    return 1 + f->ngp + f->s.renderers;
}

guint wl_pphigs_frame_stations(guint ngp, guint renderers)
{
    return ngp + renderers + 2;
}

/* ---- planning a GP's frame -------------------------------------------- */

typedef struct {
    WlPphigsFrame *f;
    Gp *g;
    SimTime trav, send; /* accumulated since the last step */
} Plan;

static void plan_step(Plan *pl, guint region, guint count)
{
    Step st = {pl->trav, pl->send, region, count};
    g_array_append_val(pl->g->steps, st);
    pl->trav = pl->send = 0;
    if (region != NONE)
        pl->g->sent[region % pl->f->s.renderers]++;
}

static guint clampi(double v, guint hi)
{
    return v <= 0 ? 0 : v >= hi ? hi - 1 : (guint)v;
}

/* Screen box of a primitive that is not trivially rejected, in regions.
 * A vertex behind the eye makes the box the whole screen (conservative).*/
static void prim_regions(const WlPphigsFrame *f, Mat4 m, const SceneElem *e,
                         guint r[4])
{
    double x0 = 1, x1 = -1, y0 = 1, y1 = -1;
    for (guint v = 0; v < e->nverts; v++) {
        Vec4 q = mat4_apply_point(m, e->verts[v]);
        if (q.w <= 0) {
            x0 = y0 = -1;
            x1 = y1 = 1;
            break;
        }
        x0 = MIN(x0, q.x / q.w);
        x1 = MAX(x1, q.x / q.w);
        y0 = MIN(y0, q.y / q.w);
        y1 = MAX(y1, q.y / q.w);
    }
    guint W = f->s.width, H = f->s.height, R = f->s.region;
    r[0] = clampi((x0 + 1) / 2 * W, W) / R;
    r[1] = clampi((x1 + 1) / 2 * W, W) / R;
    r[2] = clampi((1 - y1) / 2 * H, H) / R;
    r[3] = clampi((1 - y0) / 2 * H, H) / R;
}

static void plan_command(Plan *pl, guint region)
{
    WlPphigsFrame *f = pl->f;
    pl->send += f->s.gp_send;
    f->commands++;
    if (++pl->g->buf[region] >= f->s.batch) {
        plan_step(pl, region, pl->g->buf[region]);
        pl->g->buf[region] = 0;
    }
}

static void plan_prim(const ScenePrimInst *pi, void *ud)
{
    Plan *pl = ud;
    WlPphigsFrame *f = pl->f;
    const WlPphigsCosts *c = &f->s.gp;
    Mat4 m = mat4_mul(f->vp, pi->matrix);
    double us = wl_pphigs_elem_us(c, pi->el);
    f->prims++;
    if (scene_pphigs_prim_offscreen(m, pi->el)) {
        pl->trav += us_to_ps(us * c->offscreen);
        f->trav_us[pl->g->id] += us * c->offscreen;
        f->offscreen++;
        return;
    }
    pl->trav += us_to_ps(us);
    f->trav_us[pl->g->id] += us;
    guint r[4];
    prim_regions(f, m, pi->el, r);
    for (guint y = r[2]; y <= r[3]; y++)
        for (guint x = r[0]; x <= r[1]; x++)
            plan_command(pl, y * f->nx + x);
}

/* Attributes and executes of every structure instance (max-set). */
static double nonprim_us(const SceneDb *db, const WlPphigsCosts *c)
{
    double us = 0;
    GArray *mx = scene_db_maxset(db);
    for (guint k = 0; k < mx->len; k++) {
        guint sid = g_array_index(mx, SceneMaxNode, k).sid;
        for (guint i = 0; i < scene_db_len(db, sid); i++) {
            const SceneElem *e = scene_db_elem(db, sid, i);
            if (!scene_elem_is_prim(e->kind))
                us += wl_pphigs_elem_us(c, e);
        }
    }
    g_array_unref(mx);
    return us;
}

static void plan_gp(WlPphigsFrame *f, Gp *g, const SceneDb *db)
{
    g_array_set_size(g->steps, 0);
    g->next = 0;
    memset(g->sent, 0, f->s.renderers * sizeof *g->sent);
    Plan pl = {f, g, 0, 0};
    double attr = nonprim_us(db, &f->s.gp);
    f->trav_us[g->id] = attr;
    pl.trav = us_to_ps(attr);
    plan_step(&pl, NONE, 0);
    scene_db_traverse(db, plan_prim, &pl);
    for (guint k = 0; k < f->nregions; k++)
        if (g->buf[k]) {
            plan_step(&pl, k, g->buf[k]);
            g->buf[k] = 0;
        }
    if (pl.trav || pl.send)
        plan_step(&pl, NONE, 0);
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
    (void)d;
    WlPphigsFrame *f = ctx;
    proc_compute(f, &f->fb, f->s.fb_store, f->ph_store, fb_done, f, NULL);
}

/* ---- renderers -------------------------------------------------------- */

static guint region_bytes(const WlPphigsFrame *f, guint k)
{
    guint R = f->s.region, x = k % f->nx, y = k / f->nx;
    guint w = MIN(R, f->s.width - x * R), h = MIN(R, f->s.height - y * R);
    return w * h * f->s.pixel_bytes;
}

static void rend_region_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Rend *r = ctx;
    WlPphigsFrame *f = r->f;
    guint k = GPOINTER_TO_UINT(arg) * f->s.renderers + r->id;
    net_send(f->net, station_rend(f, r->id), station_fb(f),
             region_bytes(f, k), NULL, fb_arrive, f);
}

static void rend_raster(Rend *r, guint j)
{
    WlPphigsFrame *f = r->f;
    if (!r->begun[j]) {
        r->begun[j] = TRUE;
        proc_compute(f, &r->p, f->s.rend_begin, f->ph_rast, NULL, NULL,
                     NULL);
    }
    if (r->pending[j])
        proc_compute(f, &r->p, r->pending[j] * f->s.rend_prim, f->ph_rast,
                     NULL, NULL, NULL);
    r->pending[j] = 0;
}

/* Every GP is done with this renderer: complete its regions in order. */
static void rend_finish(Rend *r)
{
    WlPphigsFrame *f = r->f;
    for (; r->cur < r->nreg; r->cur++) {
        rend_raster(r, r->cur);
        proc_compute(f, &r->p, f->s.rend_shade, f->ph_shade,
                     rend_region_done, r, GUINT_TO_POINTER(r->cur));
    }
}

static void rend_check_gp(Rend *r, guint g)
{
    if (r->got[g] == r->expect[g] && ++r->gps_done == r->f->ngp)
        rend_finish(r);
}

static void rend_arrive(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    WlPphigsFrame *f = ctx;
    Msg *m = d->payload;
    Rend *r = &f->rend[d->dst - station_rend(f, 0)];
    if (m->end) {
        r->expect[m->gp] = m->msgs;
    } else {
        guint j = m->region / f->s.renderers;
        r->pending[j] += m->count;
        r->got[m->gp]++;
        if (j == r->cur)
            rend_raster(r, j);
    }
    rend_check_gp(r, m->gp);
    g_free(m);
}

/* ---- GPs -------------------------------------------------------------- */

static void gp_send_ends(WlPphigsFrame *f, Gp *g)
{
    for (guint r = 0; r < f->s.renderers; r++) {
        Msg *m = g_new0(Msg, 1);
        m->gp = g->id;
        m->end = TRUE;
        m->msgs = g->sent[r];
        net_send(f->net, station_gp(f, g->id), station_rend(f, r),
                 f->s.end_bytes, m, rend_arrive, f);
    }
}

static void gp_next(Gp *g);

static void gp_step_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    Gp *g = ctx;
    WlPphigsFrame *f = g->f;
    const Step *st = &g_array_index(g->steps, Step, g->next);
    if (st->region != NONE) {
        Msg *m = g_new0(Msg, 1);
        m->gp = g->id;
        m->region = st->region;
        m->count = st->count;
        net_send(f->net, station_gp(f, g->id),
                 station_rend(f, st->region % f->s.renderers),
                 (uint64_t)st->count * f->s.cmd_bytes, m, rend_arrive, f);
    }
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
    proc_compute(f, &g->p, st->trav, f->ph_trav, NULL, NULL, NULL);
    proc_compute(f, &g->p, st->send, f->ph_send, gp_step_done, g, NULL);
}

static void gp_start(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    gp_next(ctx);
}

/* ---- lifetime --------------------------------------------------------- */

static void rend_init(WlPphigsFrame *f, Rend *r, guint id)
{
    r->f = f;
    r->id = id;
    sim_busy_init(&r->p.busy);
    r->nreg = f->nregions > id
                  ? (f->nregions - id + f->s.renderers - 1) / f->s.renderers
                  : 0;
    r->pending = g_new0(guint, MAX(r->nreg, 1));
    r->begun = g_new0(gboolean, MAX(r->nreg, 1));
    r->got = g_new0(guint, f->ngp);
    r->expect = g_new0(guint, f->ngp);
}

WlPphigsFrame *wl_pphigs_frame_new(SimEngine *eng, NetNet *net, guint ngp,
                                   const WlPphigsFrameSpec *spec)
{
    g_assert(ngp >= 1 && spec->renderers >= 1 && spec->region >= 1);
    g_assert(spec->batch >= 1 && spec->width >= 1 && spec->height >= 1);
    g_assert(net_nodes(net) >= wl_pphigs_frame_stations(ngp,
                                                        spec->renderers));
    WlPphigsFrame *f = g_new0(WlPphigsFrame, 1);
    f->eng = eng;
    f->net = net;
    f->s = *spec;
    f->ngp = ngp;
    f->nx = (spec->width + spec->region - 1) / spec->region;
    f->ny = (spec->height + spec->region - 1) / spec->region;
    f->nregions = f->nx * f->ny;
    f->ph_trav = sim_engine_phase(eng, "traverse");
    f->ph_send = sim_engine_phase(eng, "send");
    f->ph_rast = sim_engine_phase(eng, "rasterise");
    f->ph_shade = sim_engine_phase(eng, "shade");
    f->ph_store = sim_engine_phase(eng, "store");
    f->trav_us = g_new0(double, ngp);
    sim_busy_init(&f->fb.busy);
    f->gp = g_new0(Gp, ngp);
    for (guint g = 0; g < ngp; g++) {
        f->gp[g].f = f;
        f->gp[g].id = g;
        sim_busy_init(&f->gp[g].p.busy);
        f->gp[g].steps = g_array_new(FALSE, FALSE, sizeof(Step));
        f->gp[g].buf = g_new0(guint, f->nregions);
        f->gp[g].sent = g_new0(guint, spec->renderers);
    }
    f->rend = g_new0(Rend, spec->renderers);
    for (guint r = 0; r < spec->renderers; r++)
        rend_init(f, &f->rend[r], r);
    return f;
}

void wl_pphigs_frame_free(WlPphigsFrame *f)
{
    if (!f)
        return;
    for (guint g = 0; g < f->ngp; g++) {
        sim_busy_clear(&f->gp[g].p.busy);
        g_array_unref(f->gp[g].steps);
        g_free(f->gp[g].buf);
        g_free(f->gp[g].sent);
    }
    for (guint r = 0; r < f->s.renderers; r++) {
        Rend *x = &f->rend[r];
        sim_busy_clear(&x->p.busy);
        g_free(x->pending);
        g_free(x->begun);
        g_free(x->got);
        g_free(x->expect);
    }
    sim_busy_clear(&f->fb.busy);
    g_free(f->gp);
    g_free(f->rend);
    g_free(f->trav_us);
    g_free(f);
}

static void frame_reset(WlPphigsFrame *f)
{
    for (guint r = 0; r < f->s.renderers; r++) {
        Rend *x = &f->rend[r];
        x->cur = 0;
        x->gps_done = 0;
        memset(x->pending, 0, MAX(x->nreg, 1) * sizeof *x->pending);
        memset(x->begun, 0, MAX(x->nreg, 1) * sizeof *x->begun);
        memset(x->got, 0, f->ngp * sizeof *x->got);
        for (guint g = 0; g < f->ngp; g++)
            x->expect[g] = NONE;
    }
    f->stored = 0;
    f->commands = f->offscreen = f->prims = 0;
    f->start = f->end = sim_now(f->eng);
}

gboolean wl_pphigs_frame_run(WlPphigsFrame *f, const WlPphigsDist *d,
                             Mat4 vp, WlPphigsFrameStats *out, GError **err)
{
    g_assert(wl_pphigs_dist_ngp(d) == f->ngp);
    frame_reset(f);
    f->vp = vp;
    for (guint g = 0; g < f->ngp; g++) {
        plan_gp(f, &f->gp[g], wl_pphigs_dist_gp(d, g));
        sim_schedule_in(f->eng, 0, gp_start, &f->gp[g], NULL);
    }
    if (!sim_engine_run(f->eng, SIM_TIME_MAX, err))
        return FALSE;
    g_assert(f->stored == f->nregions);
    out->time = f->end - f->start;
    out->gp_traverse_us = f->trav_us;
    out->commands = f->commands;
    out->offscreen = f->offscreen;
    out->primitives = f->prims;
    return TRUE;
}

/* ---- results ---------------------------------------------------------- */

static void add_node(SimResult *r, const char *name, const char *kind,
                     const Proc *p)
{
    SimNodeResult *n = sim_result_add_node(r, name, kind);
    for (guint i = 0; p->busy.per_phase && i < p->busy.per_phase->len; i++)
        sim_busy_add(&n->busy, i, sim_busy_phase(&p->busy, i));
}

void wl_pphigs_frame_fill_result(const WlPphigsFrame *f, SimResult *r)
{
    sim_result_set_phases(r, f->eng);
    char name[32];
    for (guint g = 0; g < f->ngp; g++) {
        g_snprintf(name, sizeof name, "gp%u", g);
        add_node(r, name, "gp", &f->gp[g].p);
    }
    for (guint i = 0; i < f->s.renderers; i++) {
        g_snprintf(name, sizeof name, "renderer%u", i);
        add_node(r, name, "renderer", &f->rend[i].p);
    }
    add_node(r, "fb", "frame_buffer", &f->fb);
}

void wl_pphigs_frame_util(const WlPphigsFrame *f, SimTime elapsed,
                          double *gp_util, double *rend_util)
{
    double e = (double)MAX(elapsed, 1), gs = 0, rs = 0;
    for (guint g = 0; g < f->ngp; g++)
        gs += (double)f->gp[g].p.busy.total / e;
    for (guint i = 0; i < f->s.renderers; i++)
        rs += (double)f->rend[i].p.busy.total / e;
    *gp_util = gs / f->ngp;
    *rend_util = rs / f->s.renderers;
}
