/* dp_sched.c — the data-parallel steps of one frame (dp_sched.h).
 *
 * A state machine over the paper's loops.  The polygons are ordered by
 * scan-line count (descending) once, so the polygons alive in scan-line
 * iteration i are a prefix of that order.  The segment buffer holds
 * (x0, y, length, slot) per segment; a flush sorts it by length
 * (descending, counting sort) so that the live pixels of pixel iteration
 * j are a prefix too.  Invariant: buffered <= capacity except when one
 * scan line alone brings more segments than the buffer holds (then the
 * buffer is flushed first and takes that scan line whole, as a CM Fortran
 * program with a larger buffer would).
 *
 * Complexity: O(V log V) once; O(1) per step except the scan send
 * (O(live polygons)) and a flush's sort (O(buffered + longest)).
 */
#include "sim/workload/dpscan/dp_sched.h"
#include <math.h>
#include <string.h>

typedef WlDpSeg DpSeg;

typedef enum {
    ST_CLEAR,
    ST_TRANSFORM,
    ST_SCAN_COMPUTE,
    ST_SCAN_ENUM,
    ST_SCAN_CHECK,
    ST_SCAN_SEND,
    ST_FLUSH_MAX,
    ST_PIX_COMPUTE,
    ST_PIX_SEND,
    ST_EXTRACT,
    ST_DONE
} DpState;

struct WlDpSched {
    const WlDpGeom *g;
    WlDpAlgo a;
    WlDpCounts c;
    uint32_t *ord;       /* visible polygons, tallest first */
    uint64_t live_polys; /* alive in the current scan line */
    GArray *buf;         /* DpSeg, slot order */
    DpSeg *fl;           /* the buffer being flushed, longest first */
    uint64_t fl_n, fl_live;
    uint32_t longest, fl_longest;
    uint64_t capacity;
    uint64_t sent_first; /* first slot of the last segment send */
    DpState st;
    gboolean final_flush;
    uint32_t i, j, k;
};

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
        .clear_ops = 2,
        .transform_ops = 240,
        .transform_steps = 12,
        .scan_ops = 60,
        .scan_steps = 6,
        .scan_scans = 1,
        .pixel_ops = 14,
        .pixel_steps = 3,
        .extract_ops = 3,
        .segment_words = 7,
        .pixel_words = 2,
        .buffer_factor = 1.0,
    };
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

WlDpSched *wl_dp_sched_new(const WlDpGeom *g, const WlDpAlgo *a)
{
    g_assert(a->buffer_factor > 0.0 && a->transform_steps > 0 &&
             a->scan_steps > 0 && a->pixel_steps > 0);
    WlDpSched *s = g_new0(WlDpSched, 1);
    s->g = g;
    s->a = *a;
    s->ord = g_new(uint32_t, MAX(g->n_visible, 1));
    for (uint64_t p = 0; p < g->n_visible; p++)
        s->ord[p] = (uint32_t)p;
    g_qsort_with_data(s->ord, (gint)g->n_visible, sizeof(uint32_t), rows_desc,
                      (gpointer)g);
    s->live_polys = g->n_visible;
    s->buf = g_array_new(FALSE, FALSE, sizeof(DpSeg));
    s->capacity = (uint64_t)ceil(a->buffer_factor * (double)g->n_polys);
    s->capacity = MAX(s->capacity, 1);
    s->st = ST_CLEAR;
    return s;
}

void wl_dp_sched_free(WlDpSched *s)
{
    if (!s)
        return;
    g_free(s->ord);
    g_free(s->fl);
    g_array_free(s->buf, TRUE);
    g_free(s);
}

const WlDpCounts *wl_dp_sched_counts(const WlDpSched *s)
{
    return &s->c;
}

const WlDpGeom *wl_dp_sched_geom(const WlDpSched *s)
{
    return s->g;
}

const WlDpSeg *wl_dp_sched_sent(const WlDpSched *s)
{
    return (const WlDpSeg *)s->buf->data + s->sent_first;
}

const WlDpSeg *wl_dp_sched_live(const WlDpSched *s, uint32_t *j)
{
    g_assert(s->st == ST_PIX_SEND);
    *j = s->j;
    return s->fl;
}

static void compute(WlDpStep *o, WlDpPhase ph, uint64_t n, uint32_t ops)
{
    *o = (WlDpStep){.kind = WL_DP_COMPUTE, .phase = ph, .n = n, .ops = ops};
}

/* Share s of `ops` spread over `steps` steps. */
static uint32_t share(uint32_t ops, uint32_t steps, uint32_t s)
{
    return ops / steps + (s < ops % steps);
}

/* Moves the buffer into fl, longest first (counting sort). */
static void start_flush(WlDpSched *s)
{
    uint64_t n = s->buf->len;
    uint32_t L = s->longest;
    uint64_t *first = g_new0(uint64_t, (size_t)L + 2);
    const DpSeg *b = (const DpSeg *)s->buf->data;
    for (uint64_t q = 0; q < n; q++)
        first[L - b[q].len + 1]++;
    for (uint32_t l = 1; l <= L + 1; l++)
        first[l] += first[l - 1];
    g_free(s->fl);
    s->fl = g_new(DpSeg, MAX(n, 1));
    for (uint64_t q = 0; q < n; q++)
        s->fl[first[L - b[q].len]++] = b[q];
    g_free(first);
    s->fl_n = n;
    s->fl_live = n;
    s->fl_longest = L;
    g_array_set_size(s->buf, 0);
    s->longest = 0;
    s->c.flushes++;
    s->j = 0;
    s->k = 0;
}

/* Appends the segments of scan line i of every live polygon. */
static void add_segments(WlDpSched *s)
{
    const WlDpGeom *g = s->g;
    s->sent_first = s->buf->len;
    for (uint64_t q = 0; q < s->live_polys; q++) {
        uint32_t p = s->ord[q];
        DpSeg d = {.x0 = wl_dp_geom_x0(g, p, s->i),
                   .y = wl_dp_geom_y0(g, p) + s->i,
                   .len = wl_dp_geom_len(g, p, s->i),
                   .slot = (uint32_t)s->buf->len,
                   .poly = p};
        g_array_append_val(s->buf, d);
        s->longest = MAX(s->longest, d.len);
    }
    s->c.segments += s->live_polys;
}

/* Steps of the pixel loop; FALSE when the flush is over. */
static gboolean pixel_step(WlDpSched *s, WlDpStep *o)
{
    while (s->fl_live > 0 && s->fl[s->fl_live - 1].len <= s->j)
        s->fl_live--;
    if (s->j >= s->fl_longest || s->fl_live == 0)
        return FALSE;
    if (s->k < s->a.pixel_steps) {
        compute(o, WL_DP_PH_PIXEL, s->capacity,
                share(s->a.pixel_ops, s->a.pixel_steps, s->k));
        s->k++;
        return TRUE;
    }
    *o = (WlDpStep){.kind = WL_DP_SEND,
                    .phase = WL_DP_PH_ROUTER,
                    .n = s->capacity,
                    .words = s->a.pixel_words,
                    .active = s->fl_live,
                    .zbuf = TRUE};
    s->c.messages += s->fl_live * s->a.pixel_words;
    s->c.words += s->fl_live * s->a.pixel_words;
    s->c.pixel_iters++;
    s->k = 0;
    s->st = ST_PIX_SEND;
    return TRUE;
}

static void next_scan_line(WlDpSched *s)
{
    s->i++;
    s->k = 0;
    s->c.scan_iters++;
    const WlDpGeom *g = s->g;
    while (s->live_polys > 0 &&
           wl_dp_geom_rows(g, s->ord[s->live_polys - 1]) <= s->i)
        s->live_polys--;
    if (s->i >= g->max_rows) {
        s->final_flush = TRUE;
        s->st = s->buf->len > 0 ? ST_FLUSH_MAX : ST_EXTRACT;
    } else {
        s->st = ST_SCAN_COMPUTE;
    }
}

static gboolean scan_step(WlDpSched *s, WlDpStep *o)
{
    uint64_t n = s->g->n_polys;
    switch (s->st) {
    case ST_SCAN_COMPUTE:
        compute(o, WL_DP_PH_SCAN, n,
                share(s->a.scan_ops, s->a.scan_steps, s->k));
        if (++s->k == s->a.scan_steps) {
            s->k = 0;
            s->st = s->a.scan_scans > 0 ? ST_SCAN_ENUM : ST_SCAN_CHECK;
        }
        return TRUE;
    case ST_SCAN_ENUM:
        *o = (WlDpStep){.kind = WL_DP_SCAN, .phase = WL_DP_PH_SCAN, .n = n};
        if (++s->k >= s->a.scan_scans)
            s->st = ST_SCAN_CHECK;
        return TRUE;
    default:
        break;
    }
    g_assert(s->st == ST_SCAN_SEND);
    *o = (WlDpStep){.kind = WL_DP_SEND,
                    .phase = WL_DP_PH_ROUTER,
                    .n = n,
                    .words = s->a.segment_words,
                    .active = s->live_polys};
    s->c.messages += s->live_polys * s->a.segment_words;
    s->c.words += s->live_polys * s->a.segment_words;
    add_segments(s);
    next_scan_line(s);
    return TRUE;
}

static gboolean flush_step(WlDpSched *s, WlDpStep *o)
{
    if (s->st == ST_FLUSH_MAX) {
        start_flush(s);
        *o = (WlDpStep){
            .kind = WL_DP_SCAN, .phase = WL_DP_PH_PIXEL, .n = s->capacity};
        s->st = ST_PIX_COMPUTE;
        return TRUE;
    }
    if (s->st == ST_PIX_SEND) {
        s->j++;
        s->st = ST_PIX_COMPUTE;
    }
    if (pixel_step(s, o))
        return TRUE;
    s->st = s->final_flush ? ST_EXTRACT : ST_SCAN_SEND;
    return FALSE;
}

gboolean wl_dp_sched_next(WlDpSched *s, WlDpStep *o)
{
    const WlDpGeom *g = s->g;
    uint64_t screen = (uint64_t)g->width * (uint64_t)g->height;
    for (;;) {
        switch (s->st) {
        case ST_CLEAR:
            compute(o, WL_DP_PH_DISPLAY, screen, s->a.clear_ops);
            s->st = ST_TRANSFORM;
            return TRUE;
        case ST_TRANSFORM:
            compute(o, WL_DP_PH_TRANSFORM, g->n_polys,
                    share(s->a.transform_ops, s->a.transform_steps, s->k));
            if (++s->k == s->a.transform_steps) {
                s->k = 0;
                s->st = g->max_rows > 0 ? ST_SCAN_COMPUTE : ST_EXTRACT;
            }
            return TRUE;
        case ST_SCAN_CHECK:
            s->st = s->buf->len > 0 && s->buf->len + s->live_polys > s->capacity
                        ? ST_FLUSH_MAX
                        : ST_SCAN_SEND;
            continue;
        case ST_SCAN_COMPUTE:
        case ST_SCAN_ENUM:
        case ST_SCAN_SEND:
            return scan_step(s, o);
        case ST_FLUSH_MAX:
        case ST_PIX_COMPUTE:
        case ST_PIX_SEND:
            if (flush_step(s, o))
                return TRUE;
            continue;
        case ST_EXTRACT:
            compute(o, WL_DP_PH_DISPLAY, screen, s->a.extract_ops);
            s->st = ST_DONE;
            return TRUE;
        default:
            return FALSE;
        }
    }
}
