/* pf_pipeline.c — the multiprocessed frame pipeline (see pf_pipeline.h).
 *
 * A small state machine: each pipe's CULL and DRAW have a "next frame"
 * counter and a busy flag; try_cull() / try_draw() start a stage when its
 * input is ready, its buffer is free and its process is free; a process
 * that serves several stages (APP with CULL and DRAW, CULL with DRAW)
 * runs them in order, the APP process by a cursor (`at`) over its
 * frame's stages.  The process that owns APP re-enters pfSync after the
 * last stage it runs.  Stage work goes through mach_proc_compute(), so
 * busy time is charged per phase; waiting is idle time.  Deterministic:
 * no randomness.
 */
#include "sim/workload/performer/pf_pipeline.h"

#include "sim/core/error.h"

#include <string.h>

const char *const wl_pf_mp_mode_names[] = {
    "appculldraw", "appcull_draw", "app_cull_draw", "app_culldraw", NULL};

enum { ST_APP, ST_CULL, ST_DRAW, ST_ISECT, ST_UPDATE, ST_N };
#define NP WL_PF_MAX_PIPES
/* the APP process's cursor: APP, then CULL / DRAW of pipe i */
#define AT_APP (-1)
#define AT_CULL(i) (2 * (int)(i))
#define AT_DRAW(i) (2 * (int)(i) + 1)

typedef struct Pipe Pipe;
typedef struct {
    Pipe *s;
    guint i;
} Chan;

struct Pipe {
    SimEngine *eng;
    MachProc *app, *isect, *cull[NP], *draw[NP];
    unsigned phase[ST_N];
    const WlPfPipeParams *p;
    const WlPfStageFns *f;
    void *ctx;
    GArray *recs;
    guint np;
    int at;
    gboolean cull_in_app, draw_in_app, draw_with_cull;
    double stress[NP];
    SimTime last_swap[NP];
    guint app_done, cull_next[NP], cull_done[NP], draw_next[NP], draw_done[NP];
    gboolean cull_busy[NP], draw_busy[NP], isect_busy, app_blocked;
    guint *ncull, *ndraw, *nswap; /* per frame: pipes started / swapped */
    SimTime *dstart;              /* per frame and pipe: DRAW's start */
    SimTime cstart[NP];           /* each pipe's CULL start */
    WlPfGpipe *gp[NP];
    Chan chan[NP];
};

guint wl_pf_mp_procs(WlPfMpMode mode, guint pipes)
{
    pipes = MAX(pipes, 1);
    switch (mode) {
    case WL_PF_MP_APPCULLDRAW:
        return 1;
    case WL_PF_MP_APP_CULL_DRAW:
        return 1 + 2 * pipes;
    default:
        return 1 + pipes;
    }
}

guint wl_pf_mp_proc(WlPfMpMode mode, guint i, gboolean draw)
{
    switch (mode) {
    case WL_PF_MP_APPCULLDRAW:
        return 0;
    case WL_PF_MP_APPCULL_DRAW:
        return draw ? 1 + i : 0;
    case WL_PF_MP_APP_CULLDRAW:
        return 1 + i;
    default:
        return 1 + 2 * i + (draw ? 1 : 0);
    }
}

static WlPfFrameRec *rec(Pipe *s, guint n)
{
    return &g_array_index(s->recs, WlPfFrameRec, n);
}

/* An event argument: frame n of pipe i. */
static void *arg_of(guint n, guint i)
{
    return GUINT_TO_POINTER(n * NP + i);
}

static guint arg_frame(void *a)
{
    return GPOINTER_TO_UINT(a) / NP;
}

static guint arg_pipe(void *a)
{
    return GPOINTER_TO_UINT(a) % NP;
}

/* First multiple of `step` at or after t. */
static SimTime ceil_to(SimTime t, SimTime step)
{
    return (t + step - 1) / step * step;
}

static SimTime frame_period(const Pipe *s)
{
    return s->p->video * s->p->per_frame;
}

static void app_start(SimEngine *eng, void *ctx, void *arg);
static void try_cull(Pipe *s, guint i);
static void try_draw(Pipe *s, guint i);

/* A pipe's stage starts a frame's now: the frame's start is the first
 * pipe's (*count pipes started it before). */
static void first_start(guint *count, SimTime *start, SimTime now)
{
    if ((*count)++ == 0 || now < *start)
        *start = now;
}

static void channel(Pipe *s, guint i)
{
    if (s->f->channel)
        s->f->channel(s->ctx, i);
}

/* Stage st's work c on p (the stage function's named counts, if it gave
 * them: a recording writes those). */
static void stage_compute(Pipe *s, MachProc *p, int st, SimTime c,
                          SimHandler done, void *arg)
{
    const MachOverlap *o =
        s->f->ops && st != ST_UPDATE ? s->f->ops(s->ctx) : NULL;
    if (s->p->arena && s->f->arena_bytes) { /* pieces, each after its bytes */
        gboolean own = o && o->own.n && !o->n;
        wl_pf_arena_run(s->p->arena, p, s->phase[st], c, own ? &o->own : NULL,
                        s->f->arena_bytes(s->ctx), done, s, arg);
        return;
    }
    if (!o || !o->own.n) {
        mach_proc_compute(p, c, s->phase[st], done, s, arg);
        return;
    }
    g_assert(mach_overlap_cost(p, o) == c);
    mach_proc_compute_overlap(p, o, s->phase[st], done, s, arg);
}

/* Runs h(arg) at t on processor p's behalf: a wait for the display
 * refresh when t is the next multiple of `period` (or now: a period of
 * 1 ps), so a recording writes the wait (`v`), else a timer. */
static void wait_until(Pipe *s, MachProc *p, SimTime t, SimTime period,
                       SimHandler h, void *arg)
{
    SimTime now = sim_now(s->eng);
    if (t == now && t != sim_refresh_at(now, period))
        period = 1;
    if (t == sim_refresh_at(now, period))
        sim_wait_refresh(s->eng, mach_proc_id(p), period, h, s, arg);
    else
        sim_schedule_at(s->eng, t, h, s, arg);
}

/* The first frame boundary at or after now and a period after frame n's
 * APP start. */
static SimTime next_boundary(Pipe *s, guint n)
{
    SimTime T = frame_period(s), now = sim_now(s->eng);
    return MAX(ceil_to(now, T), rec(s, n)->app_start + T);
}

/* pfSync: the APP process waits for the next frame boundary. */
static void app_sync(Pipe *s, guint n)
{
    if (n + 1 >= s->p->frames)
        return;
    s->at = AT_APP;
    wait_until(s, s->app, next_boundary(s, n), frame_period(s), app_start,
               arg_of(n + 1, 0));
}

static void isect_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    ((Pipe *)ctx)->isect_busy = FALSE;
}

static void start_isect(Pipe *s, guint n)
{
    if (!s->f->isect || s->isect_busy || s->p->isect_in_app)
        return;
    SimTime c = s->f->isect(s->ctx, n);
    rec(s, n)->isect = c;
    s->isect_busy = TRUE;
    stage_compute(s, s->isect, ST_ISECT, c, isect_done, NULL);
}

static void try_cull_all(Pipe *s)
{
    for (guint i = 0; i < s->np; i++)
        try_cull(s, i);
}

/* pfFrame with an update list: at the boundary, frame n reaches the
 * CULL processes. */
static void handoff(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Pipe *s = ctx;
    s->app_done = arg_frame(arg) + 1;
    s->app_blocked = TRUE; /* pfFrame: until every CULL takes frame n */
    try_cull_all(s);
}

/* APP's part of frame n (with ISECT in the APP process: and ISECT) is
 * done: CULL in this process, or the hand-off to the CULL processes. */
static void app_work_done(Pipe *s, guint n)
{
    rec(s, n)->app_end = sim_now(s->eng);
    if (s->cull_in_app) {
        s->app_done = n + 1;
        s->at = AT_CULL(0);
        try_cull(s, 0);
    } else if (s->p->update_list) {
        wait_until(s, s->app, next_boundary(s, n), frame_period(s), handoff,
                   arg_of(n, 0));
    } else {
        s->app_done = n + 1;
        s->app_blocked = TRUE; /* pfFrame: until CULL takes frame n */
        try_cull_all(s);
    }
}

static void app_isect_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    app_work_done(ctx, arg_frame(arg));
}

static void app_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Pipe *s = ctx;
    guint n = arg_frame(arg);
    if (!s->f->isect || !s->p->isect_in_app) {
        app_work_done(s, n);
        return;
    }
    SimTime c = s->f->isect(s->ctx, n);
    rec(s, n)->isect = c;
    stage_compute(s, s->app, ST_ISECT, c, app_isect_done, arg);
}

static void app_start(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = arg_frame(arg);
    rec(s, n)->app_start = sim_now(eng);
    s->at = AT_APP;
    start_isect(s, n);
    stage_compute(s, s->app, ST_APP, s->f->app(s->ctx, n), app_done,
                  arg_of(n, 0));
}

/* The APP process finished its stage for pipe i (CULL, or DRAW when it
 * runs DRAW): the next pipe's CULL, or pfSync after the last. */
static void app_next(Pipe *s, guint i, guint n)
{
    if (i + 1 < s->np) {
        s->at = AT_CULL(i + 1);
        try_cull(s, i + 1);
    } else {
        app_sync(s, n);
    }
}

/* ---- CULL -------------------------------------------------------------- */

static void cull_done(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = arg_frame(arg), i = arg_pipe(arg);
    WlPfFrameRec *r = rec(s, n);
    r->cull_end = MAX(r->cull_end, sim_now(eng));
    r->cull_ms += (sim_now(eng) - s->cstart[i]) / s->np;
    s->cull_done[i] = n + 1;
    s->cull_busy[i] = FALSE;
    if (s->draw_in_app) {
        s->at = AT_DRAW(i);
    } else if (s->cull_in_app) {
        app_next(s, i, n);
    }
    try_draw(s, i);
    try_cull(s, i);
}

static void cull_start(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Pipe *s = ctx;
    guint n = arg_frame(arg), i = arg_pipe(arg);
    channel(s, i);
    SimTime c = s->f->cull(s->ctx, n, s->stress[i]);
    stage_compute(s, s->cull[i], ST_CULL, c, cull_done, arg);
}

/* Is pipe i's CULL process free for its next frame? */
static gboolean cull_proc_free(const Pipe *s, guint i)
{
    if (s->cull_in_app)
        return s->at == AT_CULL(i);
    if (s->draw_with_cull) /* CULL+DRAW: after DRAW of the last frame */
        return !s->draw_busy[i] && s->draw_next[i] == s->cull_next[i];
    return TRUE;
}

/* The CULLs of frame n took it from APP: pfFrame returns. */
static void app_released(Pipe *s, guint n)
{
    for (guint i = 0; i < s->np; i++)
        if (s->cull_next[i] <= n)
            return;
    s->app_blocked = FALSE;
    if (!s->p->update_list) {
        app_sync(s, n); /* APP process: pfSync after pfFrame returns */
    } else if (n + 1 < s->p->frames) { /* pfSync was before pfFrame */
        s->at = AT_APP;
        wait_until(s, s->app, sim_now(s->eng), frame_period(s), app_start,
                   arg_of(n + 1, 0));
    }
}

/* Pipe i's CULL begins frame n: the update list, then the traversal. */
static void cull_begin(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = arg_frame(arg), i = arg_pipe(arg);
    WlPfFrameRec *r = rec(s, n);
    first_start(&s->ncull[n], &r->cull_start, sim_now(eng));
    s->cstart[i] = sim_now(eng);
    if (i == 0)
        r->stress = s->stress[0];
    gboolean upd = s->p->update_list && !s->cull_in_app && s->f->update;
    if (upd) /* apply the update list, then cull */
        stage_compute(s, s->cull[i], ST_UPDATE, s->f->update(s->ctx, n),
                      cull_start, arg);
    else
        cull_start(eng, s, arg);
    if (s->app_blocked && !s->cull_in_app)
        app_released(s, n);
}

static void try_cull(Pipe *s, guint i)
{
    guint n = s->cull_next[i];
    /* n < app_done <= frames: app_sync starts no APP past the last frame */
    if (s->cull_busy[i] || n >= s->app_done ||
        (n >= 2 && s->draw_done[i] < n - 1) || !cull_proc_free(s, i))
        return;
    s->cull_busy[i] = TRUE;
    s->cull_next[i]++;
    SimTime now = sim_now(s->eng), T = frame_period(s);
    /* a CULL+DRAW process is the DRAW process: locked, on a boundary */
    if (s->draw_with_cull && s->p->locked && now != ceil_to(now, T))
        wait_until(s, s->cull[i], ceil_to(now, T), T, cull_begin,
                   arg_of(n, i));
    else
        cull_begin(s->eng, s, arg_of(n, i));
}

/* ---- DRAW -------------------------------------------------------------- */

static void update_stress(Pipe *s, guint i, SimTime start, SimTime end)
{
    const WlPfPipeParams *p = s->p;
    if (!p->stress)
        return;
    double load = (double)(end - start) / (double)frame_period(s);
    if (load > p->high || load < p->low)
        s->stress[i] += p->gain * (load - (p->low + p->high) / 2);
    s->stress[i] = CLAMP(s->stress[i], 1.0, p->max_stress);
}

/* DRAW of frame n on pipe i released its process (its CPU's part). */
static void draw_released(Pipe *s, guint i, guint n)
{
    WlPfFrameRec *r = rec(s, n);
    r->draw_end = MAX(r->draw_end, sim_now(s->eng));
    r->draw_ms += (sim_now(s->eng) - s->dstart[n * s->np + i]) / s->np;
    s->draw_done[i] = n + 1;
    s->draw_busy[i] = FALSE;
    if (s->draw_in_app)
        app_next(s, i, n); /* one process: pfSync after the whole frame */
    try_cull(s, i);
    try_draw(s, i);
}

/* Pipe i swapped frame n in at `t`. */
static void swapped_at(Pipe *s, guint i, guint n, SimTime t)
{
    s->last_swap[i] = t;
    if (++s->nswap[n] == s->np)
        rec(s, n)->swap = t;
}

static void draw_done(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = arg_frame(arg), i = arg_pipe(arg);
    SimTime step = s->p->locked ? frame_period(s) : s->p->video;
    SimTime now = sim_now(eng);
    update_stress(s, i, s->dstart[n * s->np + i], now);
    swapped_at(s, i, n, ceil_to(now, step));
    draw_released(s, i, n);
    /* the swap waits for the refresh: a recording ends the frame there */
    sim_wait_refresh(eng, mach_proc_id(s->draw[i]), step, NULL, NULL, NULL);
}

/* With a graphics pipe: DRAW's CPU wrote frame n's last command. */
static void piped_cpu_done(void *ctx, guint n)
{
    Chan *c = ctx;
    draw_released(c->s, c->i, n);
}

/* With a graphics pipe: frame n swapped in now; the load of the stress
 * filter is DRAW's start to the pipe's last command. */
static void piped_swapped(void *ctx, guint n)
{
    Chan *c = ctx;
    Pipe *s = c->s;
    update_stress(s, c->i, s->dstart[n * s->np + c->i],
                  wl_pf_gpipe_frame_end(s->gp[c->i], n));
    swapped_at(s, c->i, n, sim_now(s->eng));
}

static void draw_start(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = arg_frame(arg), i = arg_pipe(arg);
    SimTime now = sim_now(eng);
    first_start(&s->ndraw[n], &rec(s, n)->draw_start, now);
    s->dstart[n * s->np + i] = now; /* the stress filter's load */
    channel(s, i);
    SimTime c = s->f->draw(s->ctx, n);
    if (!s->gp[i]) {
        stage_compute(s, s->draw[i], ST_DRAW, c, draw_done, arg);
        return;
    }
    WlPfDrawWork w;
    s->f->draw_work(s->ctx, n, &w);
    wl_pf_gpipe_frame(s->gp[i], n, &w);
}

static void try_draw(Pipe *s, guint i)
{
    guint n = s->draw_next[i];
    if (s->draw_busy[i] || n >= s->cull_done[i] ||
        (s->draw_in_app && s->at != AT_DRAW(i)))
        return;
    s->draw_busy[i] = TRUE;
    s->draw_next[i]++;
    SimTime t = sim_now(s->eng);
    if (n > 0 && !s->gp[i])
        t = MAX(t, s->last_swap[i]); /* double-buffered frame buffer */
    gboolean own = !s->draw_in_app && !s->draw_with_cull;
    if (s->p->locked && own) /* a DRAW process in phase locked */
        t = ceil_to(t, frame_period(s));
    wait_until(s, s->draw[i], t,
               s->p->locked && own ? frame_period(s) : s->p->video,
               draw_start, arg_of(n, i));
}

/* ---- run --------------------------------------------------------------- */

static void map_procs(Pipe *s, MachProc *const *procs)
{
    WlPfMpMode m = s->p->mode;
    s->app = procs[0];
    for (guint i = 0; i < s->np; i++) {
        s->cull[i] = procs[wl_pf_mp_proc(m, i, FALSE)];
        s->draw[i] = procs[wl_pf_mp_proc(m, i, TRUE)];
    }
    s->cull_in_app = m == WL_PF_MP_APPCULLDRAW || m == WL_PF_MP_APPCULL_DRAW;
    s->draw_in_app = m == WL_PF_MP_APPCULLDRAW;
    s->draw_with_cull = m == WL_PF_MP_APP_CULLDRAW;
    s->isect = s->f->isect && !s->p->isect_in_app
                   ? procs[wl_pf_mp_procs(m, s->np)]
                   : NULL;
}

static void set_pipes(Pipe *s)
{
    const WlPfPipeParams *p = s->p;
    for (guint i = 0; i < s->np; i++) {
        s->stress[i] = 1.0;
        s->gp[i] = p->gpipes ? p->gpipes[i] : i == 0 ? p->gpipe : NULL;
        s->chan[i] = (Chan){s, i};
        if (!s->gp[i])
            continue;
        g_assert(s->f->draw_work);
        wl_pf_gpipe_set_swap(s->gp[i],
                             p->locked ? p->video * p->per_frame : p->video,
                             piped_cpu_done, piped_swapped, &s->chan[i]);
    }
}

gboolean wl_pf_pipe_run(SimEngine *eng, MachProc *const *procs,
                        const WlPfPipeParams *p, const WlPfStageFns *f,
                        void *ctx, GArray *recs, SimTime until, GError **err)
{
    g_assert(p->frames > 0 && p->per_frame > 0 && p->video > 0);
    g_assert(p->pipes <= NP && (p->pipes <= 1 || !p->gpipe || p->gpipes));
    Pipe s = {.eng = eng,
              .p = p,
              .f = f,
              .ctx = ctx,
              .recs = recs,
              .np = MAX(p->pipes, 1)};
    static const char *const names[ST_N] = {"app", "cull", "draw", "isect",
                                            "update"};
    for (int i = 0; i < ST_N; i++)
        s.phase[i] = i == ST_UPDATE && !p->update_list
                         ? 0
                         : sim_engine_phase(eng, names[i]);
    map_procs(&s, procs);
    set_pipes(&s);
    s.ncull = g_new0(guint, p->frames);
    s.ndraw = g_new0(guint, p->frames);
    s.nswap = g_new0(guint, p->frames);
    s.dstart = g_new0(SimTime, (gsize)p->frames * s.np);
    g_array_set_size(recs, p->frames);
    memset(recs->data, 0, sizeof(WlPfFrameRec) * p->frames);
    sim_schedule_at(eng, 0, app_start, &s, arg_of(0, 0));
    gboolean ok = sim_engine_run(eng, until, err);
    guint done = 0; /* frames swap in order; `until` may cut the rest */
    while (done < recs->len && s.nswap[done] == s.np)
        done++;
    g_array_set_size(recs, done);
    g_free(s.ncull);
    g_free(s.ndraw);
    g_free(s.nswap);
    g_free(s.dstart);
    return ok;
}

double wl_pf_mean_interval_s(const GArray *recs, guint skip)
{
    guint n = recs->len;
    if (n < skip + 2)
        return 0;
    const WlPfFrameRec *a = &g_array_index(recs, WlPfFrameRec, skip);
    const WlPfFrameRec *b = &g_array_index(recs, WlPfFrameRec, n - 1);
    return sim_time_to_s(b->swap - a->swap) / (n - 1 - skip);
}

double wl_pf_mean_latency_s(const GArray *recs, guint skip)
{
    double sum = 0;
    guint c = 0;
    for (guint i = skip; i < recs->len; i++, c++) {
        const WlPfFrameRec *r = &g_array_index(recs, WlPfFrameRec, i);
        sum += sim_time_to_s(r->swap - r->app_start);
    }
    return c ? sum / c : 0;
}
