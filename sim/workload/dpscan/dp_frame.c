/* dp_frame.c — one frame of data-parallel polygon rendering (seed 004).
 *
 * The polygons are ordered by scan-line count (descending) once, so the
 * polygons alive in scan-line iteration i are a prefix of that order.
 * The segment buffer is a histogram of segment lengths: a flush needs
 * only the longest length M and, for each pixel iteration j < M, the
 * number of segments longer than j (the live pixels of that iteration).
 * Utilisation weighs each step's useful elements by its operation count
 * against the virtual-processor slots it occupies.
 *
 * Complexity: O(V log V) for the order (V visible polygons), O(segments)
 * for the scan loop, O(M) per flush; memory O(V + longest segment).
 */
#include "sim/workload/dpscan/dp_frame.h"
#include <string.h>

static const char *const phase_names[WL_DP_N_PHASES] = {
    "transform", "scan", "pixel", "router", "display",
};

const char *wl_dp_phase_name(WlDpPhase ph)
{
    g_assert(ph < WL_DP_N_PHASES);
    return phase_names[ph];
}

/* Operation counts: see docs/validation.md, section "ortega93". */
WlDpAlgo wl_dp_algo_defaults(void)
{
    return (WlDpAlgo){
        .transform_ops = 210, .transform_steps = 12,
        .scan_ops = 40, .scan_steps = 10,
        .pixel_ops = 12, .pixel_steps = 5,
        .display_ops = 3, .display_steps = 3,
        .buffer_factor = 1.0,
        .segment_bytes = 32, .pixel_bytes = 8,
    };
}

typedef struct {
    const WlDpGeom *g;
    const WlDpMachine *m;
    const WlDpAlgo *a;
    WlDpFrame *f;
    uint32_t *hist;       /* buffered segments per length */
    uint64_t buffered;    /* segments in the buffer */
    uint32_t longest;     /* longest buffered segment */
    uint64_t capacity;    /* declared buffer size */
    double useful, slots; /* utilisation sums */
} DpRun;

static void charge(DpRun *r, WlDpPhase ph, SimTime t)
{
    SimTime *p = &r->f->phase[ph];
    gboolean ok = sim_time_add(*p, t, p);
    g_assert(ok);
}

/* One compute step over n elements of which `live` do useful work. */
static void step(DpRun *r, WlDpPhase ph, uint64_t n, uint64_t live,
                 uint32_t ops)
{
    charge(r, ph, wl_dp_step_cost(r->m, n, ops, &r->f->coef));
    uint64_t v = wl_dp_vp_ratio(n, r->m->procs);
    r->useful += (double)live * ops;
    r->slots += (double)v * (double)r->m->procs * ops;
}

/* Issues a loop body's steps: ops spread over `steps` steps. */
static void body(DpRun *r, WlDpPhase ph, uint64_t n, uint64_t live,
                 uint32_t ops, uint32_t steps)
{
    g_assert(steps > 0);
    for (uint32_t s = 0; s < steps; s++) {
        uint32_t share = ops / steps + (s < ops % steps);
        step(r, ph, n, live, share);
    }
}

static void send(DpRun *r, uint64_t active, uint32_t bytes)
{
    charge(r, WL_DP_PH_ROUTER, wl_dp_send_cost(r->m, active, &r->f->coef));
    r->f->messages += active;
    r->f->bytes += active * bytes;
}

static void flush(DpRun *r)
{
    if (r->buffered == 0)
        return;
    uint64_t n = r->buffered, live = r->buffered;
    r->f->flushes++;
    for (uint32_t j = 0; j < r->longest; j++) {
        live -= r->hist[j];
        body(r, WL_DP_PH_PIXEL, n, live, r->a->pixel_ops, r->a->pixel_steps);
        send(r, live, r->a->pixel_bytes);
        r->f->pixel_iters++;
    }
    memset(r->hist, 0, sizeof(uint32_t) * ((size_t)r->longest + 1));
    r->buffered = 0;
    r->longest = 0;
}

static int rows_desc(const void *x, const void *y, void *ctx)
{
    const WlDpGeom *g = ctx;
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    uint32_t ra = wl_dp_geom_rows(g, a), rb = wl_dp_geom_rows(g, b);
    if (ra != rb)
        return ra > rb ? -1 : 1;
    return (a > b) - (a < b);
}

/* Visible polygons by scan-line count, tallest first. */
static uint32_t *order_by_rows(const WlDpGeom *g)
{
    uint32_t *ord = g_new(uint32_t, MAX(g->n_visible, 1));
    for (uint64_t p = 0; p < g->n_visible; p++)
        ord[p] = (uint32_t)p;
    g_qsort_with_data(ord, (gint)g->n_visible, sizeof(uint32_t), rows_desc,
                      (gpointer)g);
    return ord;
}

static void scan_loop(DpRun *r)
{
    const WlDpGeom *g = r->g;
    uint32_t *ord = order_by_rows(g);
    uint64_t live = g->n_visible;
    for (uint32_t i = 0; i < g->max_rows; i++) {
        while (live > 0 && wl_dp_geom_rows(g, ord[live - 1]) <= i)
            live--;
        body(r, WL_DP_PH_SCAN, g->n_polys, live, r->a->scan_ops,
             r->a->scan_steps);
        if (r->buffered > 0 && r->buffered + live > r->capacity)
            flush(r);
        send(r, live, r->a->segment_bytes);
        for (uint64_t k = 0; k < live; k++) {
            uint32_t len = wl_dp_geom_len(g, ord[k], i);
            r->hist[len]++;
            r->longest = MAX(r->longest, len);
        }
        r->buffered += live;
        r->f->segments += live;
        r->f->scan_iters++;
    }
    flush(r);
    g_free(ord);
}

void wl_dp_frame_run(const WlDpGeom *g, const WlDpMachine *m,
                     const WlDpAlgo *a, WlDpFrame *out)
{
    g_assert(a->buffer_factor > 0.0);
    memset(out, 0, sizeof(*out));
    DpRun r = {.g = g, .m = m, .a = a, .f = out};
    r.hist = g_new0(uint32_t, (size_t)g->max_len + 1);
    r.capacity = (uint64_t)ceil(a->buffer_factor * (double)g->n_polys);
    r.capacity = MAX(r.capacity, 1);
    uint64_t screen = (uint64_t)g->width * (uint64_t)g->height;
    body(&r, WL_DP_PH_DISPLAY, screen, screen, 1, 1); /* clear z-buffer */
    body(&r, WL_DP_PH_TRANSFORM, g->n_polys, g->n_polys, a->transform_ops,
         a->transform_steps);
    scan_loop(&r);
    body(&r, WL_DP_PH_DISPLAY, screen, screen, a->display_ops,
         a->display_steps);
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++) {
        gboolean ok = sim_time_add(out->total, out->phase[ph], &out->total);
        g_assert(ok);
    }
    out->util = r.slots > 0.0 ? r.useful / r.slots : 0.0;
    g_free(r.hist);
}
