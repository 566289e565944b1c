/* pf_pipeline.c — the multiprocessed frame pipeline (see pf_pipeline.h).
 *
 * A small state machine: each stage has a "next frame" counter and a
 * busy flag; try_cull() / try_draw() start a stage when its input is
 * ready and its buffer is free; completions hand frames on.  The process
 * that owns APP re-enters pfSync after the last stage it runs.  Stage
 * work goes through mach_proc_compute(), so busy time is charged per
 * phase; waiting is idle time.  Deterministic: no randomness.
 */
#include "sim/workload/performer/pf_pipeline.h"

#include "sim/core/error.h"

#include <string.h>

const char *const wl_pf_mp_mode_names[] = {"appculldraw", "appcull_draw",
                                           "app_cull_draw", NULL};

enum { ST_APP, ST_CULL, ST_DRAW, ST_ISECT, ST_N };

typedef struct {
    SimEngine *eng;
    MachProc *proc[ST_N];
    unsigned phase[ST_N];
    const WlPfPipeParams *p;
    const WlPfStageFns *f;
    void *ctx;
    GArray *recs;
    double stress;
    guint app_done, cull_next, cull_done, draw_next, draw_done;
    gboolean cull_busy, draw_busy, isect_busy, app_blocked;
} Pipe;

guint wl_pf_mp_procs(WlPfMpMode mode)
{
    return (guint)mode + 1;
}

static WlPfFrameRec *rec(Pipe *s, guint n)
{
    return &g_array_index(s->recs, WlPfFrameRec, n);
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
static void try_cull(Pipe *s);
static void try_draw(Pipe *s);

/* Stage st's work c (the stage function's named counts, if it gave
 * them: a recording writes those). */
static void stage_compute(Pipe *s, int st, SimTime c, SimHandler done,
                          void *arg)
{
    const MachOverlap *o = s->f->ops ? s->f->ops(s->ctx) : NULL;
    if (!o || !o->own.n) {
        mach_proc_compute(s->proc[st], c, s->phase[st], done, s, arg);
        return;
    }
    g_assert(mach_overlap_cost(s->proc[st], o) == c);
    mach_proc_compute_overlap(s->proc[st], o, s->phase[st], done, s, arg);
}

/* Runs h(frame n) at t on processor p's behalf: a wait for the display
 * refresh when t is the next multiple of `period` (or now: a period of
 * 1 ps), so a recording writes the wait (`v`), else a timer. */
static void wait_until(Pipe *s, MachProc *p, SimTime t, SimTime period,
                       SimHandler h, guint n)
{
    SimTime now = sim_now(s->eng);
    if (t == now && t != sim_refresh_at(now, period))
        period = 1;
    if (t == sim_refresh_at(now, period))
        sim_wait_refresh(s->eng, mach_proc_id(p), period, h, s,
                         GUINT_TO_POINTER(n));
    else
        sim_schedule_at(s->eng, t, h, s, GUINT_TO_POINTER(n));
}

/* pfSync: the APP process waits for the next frame boundary. */
static void app_sync(Pipe *s, guint n)
{
    if (n + 1 >= s->p->frames)
        return;
    SimTime T = frame_period(s), now = sim_now(s->eng);
    SimTime t = MAX(ceil_to(now, T), rec(s, n)->app_start + T);
    wait_until(s, s->proc[ST_APP], t, T, app_start, n + 1);
}

static void isect_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    ((Pipe *)ctx)->isect_busy = FALSE;
}

static void start_isect(Pipe *s, guint n)
{
    if (!s->f->isect || s->isect_busy)
        return;
    SimTime c = s->f->isect(s->ctx, n);
    rec(s, n)->isect = c;
    s->isect_busy = TRUE;
    stage_compute(s, ST_ISECT, c, isect_done, NULL);
}

static void app_done(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = GPOINTER_TO_UINT(arg);
    rec(s, n)->app_end = sim_now(eng);
    s->app_done = n + 1;
    s->app_blocked = TRUE; /* pfFrame: until CULL takes frame n */
    try_cull(s);
}

static void app_start(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = GPOINTER_TO_UINT(arg);
    rec(s, n)->app_start = sim_now(eng);
    start_isect(s, n);
    stage_compute(s, ST_APP, s->f->app(s->ctx, n), app_done, arg);
}

/* ---- CULL -------------------------------------------------------------- */

static void cull_done(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = GPOINTER_TO_UINT(arg);
    rec(s, n)->cull_end = sim_now(eng);
    s->cull_done = n + 1;
    s->cull_busy = FALSE;
    if (s->proc[ST_CULL] == s->proc[ST_APP] &&
        s->proc[ST_DRAW] != s->proc[ST_APP])
        app_sync(s, n); /* APP+CULL process: pfSync after CULL */
    try_draw(s);
    try_cull(s);
}

static void try_cull(Pipe *s)
{
    guint n = s->cull_next;
    /* n < app_done <= frames: app_sync starts no APP past the last frame */
    if (s->cull_busy || n >= s->app_done || (n >= 2 && s->draw_done < n - 1))
        return;
    s->cull_busy = TRUE;
    s->cull_next++;
    rec(s, n)->cull_start = sim_now(s->eng);
    rec(s, n)->stress = s->stress;
    SimTime c = s->f->cull(s->ctx, n, s->stress);
    stage_compute(s, ST_CULL, c, cull_done, GUINT_TO_POINTER(n));
    if (s->app_blocked && s->proc[ST_CULL] != s->proc[ST_APP]) {
        s->app_blocked = FALSE;
        app_sync(s, n); /* APP process: pfSync after pfFrame returns */
    }
}

/* ---- DRAW -------------------------------------------------------------- */

static void update_stress(Pipe *s, const WlPfFrameRec *r)
{
    const WlPfPipeParams *p = s->p;
    if (!p->stress)
        return;
    double load =
        (double)(r->draw_end - r->draw_start) / (double)frame_period(s);
    if (load > p->high || load < p->low)
        s->stress += p->gain * (load - (p->low + p->high) / 2);
    s->stress = CLAMP(s->stress, 1.0, p->max_stress);
}

static void draw_done(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = GPOINTER_TO_UINT(arg);
    WlPfFrameRec *r = rec(s, n);
    r->draw_end = sim_now(eng);
    SimTime step = s->p->locked ? frame_period(s) : s->p->video;
    r->swap = ceil_to(r->draw_end, step);
    s->draw_done = n + 1;
    s->draw_busy = FALSE;
    update_stress(s, r);
    if (s->proc[ST_DRAW] == s->proc[ST_APP])
        app_sync(s, n); /* one process: pfSync after the whole frame */
    try_cull(s);
    try_draw(s);
    /* the swap waits for the refresh: a recording ends the frame there */
    sim_wait_refresh(eng, mach_proc_id(s->proc[ST_DRAW]), step, NULL, NULL,
                     NULL);
}

/* With a graphics pipe: DRAW's CPU wrote frame n's last command. */
static void piped_cpu_done(void *ctx, guint n)
{
    Pipe *s = ctx;
    rec(s, n)->draw_end = sim_now(s->eng);
    s->draw_done = n + 1;
    s->draw_busy = FALSE;
    if (s->proc[ST_DRAW] == s->proc[ST_APP])
        app_sync(s, n); /* one process: pfSync after the whole frame */
    try_cull(s);
    try_draw(s);
}

/* With a graphics pipe: frame n swapped in now; the load of the stress
 * filter is DRAW's start to the pipe's last command. */
static void piped_swapped(void *ctx, guint n)
{
    Pipe *s = ctx;
    WlPfFrameRec *r = rec(s, n), load = *r;
    r->swap = sim_now(s->eng);
    load.draw_end = wl_pf_gpipe_frame_end(s->p->gpipe, n);
    update_stress(s, &load);
}

static void draw_start(SimEngine *eng, void *ctx, void *arg)
{
    Pipe *s = ctx;
    guint n = GPOINTER_TO_UINT(arg);
    rec(s, n)->draw_start = sim_now(eng);
    SimTime c = s->f->draw(s->ctx, n);
    if (!s->p->gpipe) {
        stage_compute(s, ST_DRAW, c, draw_done, arg);
        return;
    }
    WlPfDrawWork w;
    s->f->draw_work(s->ctx, n, &w);
    wl_pf_gpipe_frame(s->p->gpipe, n, &w);
}

static void try_draw(Pipe *s)
{
    guint n = s->draw_next;
    if (s->draw_busy || n >= s->cull_done)
        return;
    s->draw_busy = TRUE;
    s->draw_next++;
    SimTime t = sim_now(s->eng);
    if (n > 0 && !s->p->gpipe)
        t = MAX(t, rec(s, n - 1)->swap); /* double-buffered frame buffer */
    if (s->p->locked)
        t = ceil_to(t, frame_period(s));
    wait_until(s, s->proc[ST_DRAW], t,
               s->p->locked ? frame_period(s) : s->p->video, draw_start, n);
}

/* ---- run --------------------------------------------------------------- */

static void map_procs(Pipe *s, MachProc *const *procs)
{
    guint np = wl_pf_mp_procs(s->p->mode);
    s->proc[ST_APP] = procs[0];
    s->proc[ST_CULL] =
        s->p->mode == WL_PF_MP_APP_CULL_DRAW ? procs[1] : procs[0];
    s->proc[ST_DRAW] = procs[np - 1];
    s->proc[ST_ISECT] = s->f->isect ? procs[np] : NULL;
}

gboolean wl_pf_pipe_run(SimEngine *eng, MachProc *const *procs,
                        const WlPfPipeParams *p, const WlPfStageFns *f,
                        void *ctx, GArray *recs, SimTime until, GError **err)
{
    g_assert(p->frames > 0 && p->per_frame > 0 && p->video > 0);
    Pipe s = {
        .eng = eng, .p = p, .f = f, .ctx = ctx, .recs = recs, .stress = 1.0};
    static const char *const names[ST_N] = {"app", "cull", "draw", "isect"};
    for (int i = 0; i < ST_N; i++)
        s.phase[i] = sim_engine_phase(eng, names[i]);
    map_procs(&s, procs);
    if (p->gpipe) {
        g_assert(f->draw_work);
        wl_pf_gpipe_set_swap(p->gpipe,
                             p->locked ? p->video * p->per_frame : p->video,
                             piped_cpu_done, piped_swapped, &s);
    }
    g_array_set_size(recs, p->frames);
    memset(recs->data, 0, sizeof(WlPfFrameRec) * p->frames);
    sim_schedule_at(eng, 0, app_start, &s, GUINT_TO_POINTER(0));
    if (!sim_engine_run(eng, until, err))
        return FALSE;
    guint done = 0; /* frames swap in order; `until` may cut the rest */
    while (done < recs->len &&
           g_array_index(recs, WlPfFrameRec, done).swap > 0)
        done++;
    g_array_set_size(recs, done);
    return TRUE;
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
