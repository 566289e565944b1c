/* pm_runs.c — the runs and counts rungs' image elements (pm_runs.h) and
 * images (pm_rung.h).
 *
 * A runs list is sorted, disjoint and coalesced (no two runs adjacent),
 * so a fragment's runs in linear order are its elements; in a bounding
 * box's row order a run ending on the box's right edge joins one
 * starting on its left edge on the next row, as the pixel rung counts
 * them (pm_composite.c).  A run over two rows or more spans the width.
 */
#include "sim/workload/pixelmerge/pm_runs.h"
#include <math.h>

static size_t elem_size(WlPmRung rung)
{
    return rung == WL_PM_RUNG_RUNS ? sizeof(WlPmRun) : sizeof(WlPmCover);
}

/* ---- runs ---------------------------------------------------------------- */

/* First run of el ending after a. */
static guint run_lower(const GArray *el, uint64_t a)
{
    guint lo = 0, hi = el->len;
    while (lo < hi) {
        guint mid = lo + (hi - lo) / 2;
        if (g_array_index(el, WlPmRun, mid).e <= a)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

static GArray *runs_slice(const GArray *el, uint64_t a, uint64_t b)
{
    GArray *o = g_array_new(FALSE, FALSE, sizeof(WlPmRun));
    for (guint i = el ? run_lower(el, a) : 0; el && i < el->len; i++) {
        WlPmRun r = g_array_index(el, WlPmRun, i);
        if (r.s >= b)
            break;
        r.s = MAX(r.s, a), r.e = MIN(r.e, b);
        g_array_append_val(o, r);
    }
    return o;
}

/* Appends r to o, coalescing with o's last run when they touch. */
static void run_put(GArray *o, WlPmRun r)
{
    WlPmRun *last = o->len ? &g_array_index(o, WlPmRun, o->len - 1) : NULL;
    if (last && r.s <= last->e)
        last->e = MAX(last->e, r.e);
    else
        g_array_append_val(o, r);
}

static GArray *runs_union(GArray *f, GArray *b)
{
    GArray *o =
        g_array_sized_new(FALSE, FALSE, sizeof(WlPmRun), f->len + b->len);
    guint i = 0, j = 0;
    while (i < f->len || j < b->len) {
        const WlPmRun *x = i < f->len ? &g_array_index(f, WlPmRun, i) : NULL;
        const WlPmRun *y = j < b->len ? &g_array_index(b, WlPmRun, j) : NULL;
        if (x && (!y || x->s <= y->s))
            run_put(o, *x), i++;
        else
            run_put(o, *y), j++;
    }
    g_array_free(f, TRUE);
    g_array_free(b, TRUE);
    return o;
}

static void box_add(WlPmMeasure *m, guint x0, guint x1, guint y0, guint y1)
{
    if (!m->any) {
        m->box[0] = x0, m->box[1] = x1, m->box[2] = y0, m->box[3] = y1;
        m->any = TRUE;
        return;
    }
    m->box[0] = MIN(m->box[0], x0), m->box[1] = MAX(m->box[1], x1);
    m->box[2] = MIN(m->box[2], y0), m->box[3] = MAX(m->box[3], y1);
}

static void runs_measure(const GArray *el, guint w, gboolean box_mode,
                         WlPmMeasure *m)
{
    for (guint i = 0; i < el->len; i++) {
        const WlPmRun *r = &g_array_index(el, WlPmRun, i);
        uint64_t ys = r->s / w, ye = (r->e - 1) / w;
        m->active += r->e - r->s;
        if (ys == ye)
            box_add(m, r->s % w, (r->e - 1) % w, ys, ys);
        else
            box_add(m, 0, w - 1, ys, ye);
    }
    m->runs = el->len;
    for (guint i = 1; box_mode && i < el->len; i++) {
        const WlPmRun *p = &g_array_index(el, WlPmRun, i - 1);
        const WlPmRun *q = p + 1;
        m->runs -= (p->e - 1) % w == m->box[1] && q->s % w == m->box[0] &&
                   q->s / w == (p->e - 1) / w + 1;
    }
}

/* ---- counts -------------------------------------------------------------- */

static double rect_area(const WlPmCover *r)
{
    return (double)(r->x1 - r->x0 + 1) * (double)(r->y1 - r->y0 + 1);
}

/* Appends the part of r inside rows y0..y1, columns x0..x1 (if any),
 * holding its share of r's pixels. */
static void rect_part(GArray *o, const WlPmCover *r, guint x0, guint x1,
                      uint64_t y0, uint64_t y1)
{
    WlPmCover p = {MAX(r->x0, x0), (guint)MAX((uint64_t)r->y0, y0),
                   MIN(r->x1, x1), (guint)MIN((uint64_t)r->y1, y1), 0};
    if (p.x0 > p.x1 || y0 > r->y1 || y1 < r->y0 || p.y0 > p.y1)
        return;
    p.active = r->active * rect_area(&p) / rect_area(r);
    g_array_append_val(o, p);
}

static GArray *rects_slice(const GArray *el, guint w, uint64_t a, uint64_t b)
{
    GArray *o = g_array_new(FALSE, FALSE, sizeof(WlPmCover));
    uint64_t ya = a / w, yb = (b - 1) / w;
    guint xa = a % w, xb = (b - 1) % w;
    for (guint i = 0; el && a < b && i < el->len; i++) {
        const WlPmCover *r = &g_array_index(el, WlPmCover, i);
        uint64_t first = (uint64_t)r->y0 * w + r->x0;
        uint64_t last = (uint64_t)r->y1 * w + r->x1;
        if (first >= a && last < b) {
            g_array_append_vals(o, r, 1);
        } else if (ya == yb) {
            rect_part(o, r, xa, xb, ya, ya);
        } else {
            rect_part(o, r, xa, w - 1, ya, ya);
            if (yb > ya + 1)
                rect_part(o, r, 0, w - 1, ya + 1, yb - 1);
            rect_part(o, r, 0, xb, yb, yb);
        }
    }
    return o;
}

/* Merges q into p when they intersect: their bounding box, the overlap
 * counted once at the product of the coverages. */
static gboolean rect_merge(WlPmCover *p, const WlPmCover *q)
{
    guint x0 = MAX(p->x0, q->x0), x1 = MIN(p->x1, q->x1);
    guint y0 = MAX(p->y0, q->y0), y1 = MIN(p->y1, q->y1);
    if (x0 > x1 || y0 > y1)
        return FALSE;
    double inter = (double)(x1 - x0 + 1) * (double)(y1 - y0 + 1);
    double a = p->active + q->active -
               inter * (p->active / rect_area(p)) * (q->active / rect_area(q));
    p->x0 = MIN(p->x0, q->x0), p->x1 = MAX(p->x1, q->x1);
    p->y0 = MIN(p->y0, q->y0), p->y1 = MAX(p->y1, q->y1);
    p->active = MIN(a, rect_area(p));
    return TRUE;
}

static GArray *rects_over(GArray *f, GArray *b)
{
    g_array_append_vals(f, b->data, b->len);
    g_array_free(b, TRUE);
    for (gboolean changed = TRUE; changed;) {
        changed = FALSE;
        for (guint i = 0; i < f->len; i++)
            for (guint j = i + 1; j < f->len; j++)
                if (rect_merge(&g_array_index(f, WlPmCover, i),
                               &g_array_index(f, WlPmCover, j))) {
                    g_array_remove_index(f, j--);
                    changed = TRUE;
                }
    }
    return f;
}

static int row_cmp(gconstpointer a, gconstpointer b)
{
    const WlPmRun *x = a, *y = b;
    return x->s < y->s ? -1 : x->s > y->s;
}

/* Rows [s, e) of the rectangles of `el` that touch column x, shifted by
 * `shift`, as a sorted coalesced list. */
static GArray *edge_rows(const GArray *el, guint x, int shift)
{
    GArray *o = g_array_new(FALSE, FALSE, sizeof(WlPmRun));
    for (guint i = 0; i < el->len; i++) {
        const WlPmCover *r = &g_array_index(el, WlPmCover, i);
        if (r->active > 0 && r->x0 <= x && x <= r->x1 &&
            (int64_t)r->y1 + shift >= 0) {
            WlPmRun v = {(uint64_t)MAX((int64_t)r->y0 + shift, 0),
                         (uint64_t)((int64_t)r->y1 + shift + 1)};
            g_array_append_val(o, v);
        }
    }
    g_array_sort(o, row_cmp);
    GArray *c = runs_slice(NULL, 0, 0);
    for (guint i = 0; i < o->len; i++)
        run_put(c, g_array_index(o, WlPmRun, i));
    g_array_free(o, TRUE);
    return c;
}

/* Rows both lists hold. */
static uint64_t rows_common(const GArray *a, const GArray *b)
{
    uint64_t n = 0;
    for (guint i = 0, j = 0; i < a->len && j < b->len;) {
        const WlPmRun *x = &g_array_index(a, WlPmRun, i);
        const WlPmRun *y = &g_array_index(b, WlPmRun, j);
        if (MIN(x->e, y->e) > MAX(x->s, y->s))
            n += MIN(x->e, y->e) - MAX(x->s, y->s);
        if (x->e < y->e)
            i++;
        else
            j++;
    }
    return n;
}

/* Runs: one a rectangle row, less the joins of a row ending on the
 * walk's right edge (the screen's, or the box's in box_mode) with the
 * next starting on its left edge. */
static void rects_measure(const GArray *el, guint w, gboolean box_mode,
                          WlPmMeasure *m)
{
    double active = 0;
    for (guint i = 0; i < el->len; i++) {
        const WlPmCover *r = &g_array_index(el, WlPmCover, i);
        if (r->active > 0) {
            active += r->active;
            box_add(m, r->x0, r->x1, r->y0, r->y1);
            m->runs += r->y1 - r->y0 + 1;
        }
    }
    guint x0 = box_mode ? m->box[0] : 0, x1 = box_mode ? m->box[1] : w - 1;
    if (m->any) {
        GArray *right = edge_rows(el, x1, 0), *left = edge_rows(el, x0, -1);
        m->runs -= MIN(m->runs, rows_common(right, left));
        g_array_free(right, TRUE);
        g_array_free(left, TRUE);
    }
    m->active = (uint64_t)llround(active);
    m->runs = MIN(m->runs, m->active);
}

/* ---- dispatch ------------------------------------------------------------ */

static GArray *rep_slice(const void *ctx, const GArray *el, uint64_t a,
                         uint64_t b)
{
    const WlPmRunsCtx *k = ctx;
    if (k->rung == WL_PM_RUNG_RUNS)
        return runs_slice(el, a, b);
    return rects_slice(el, k->width, a, b);
}

static GArray *rep_over(const void *ctx, GArray *front, GArray *back)
{
    const WlPmRunsCtx *k = ctx;
    if (k->rung == WL_PM_RUNG_RUNS)
        return runs_union(front, back);
    return rects_over(front, back);
}

void wl_pm_runs_measure(const void *ctx, const GArray *el, gboolean box_mode,
                        WlPmMeasure *m)
{
    const WlPmRunsCtx *k = ctx;
    *m = (WlPmMeasure){0};
    if (k->rung == WL_PM_RUNG_RUNS)
        runs_measure(el, k->width, box_mode, m);
    else
        rects_measure(el, k->width, box_mode, m);
}

WlPmRep wl_pm_runs_rep(const WlPmRunsCtx *ctx)
{
    g_assert(ctx->rung != WL_PM_RUNG_PIXELS);
    return (WlPmRep){rep_slice, rep_over, wl_pm_runs_measure, ctx};
}

/* ---- images -------------------------------------------------------------- */

WlPmRungImage *wl_pm_rung_image_new(WlPmRung rung, guint width, guint height)
{
    g_assert(rung != WL_PM_RUNG_PIXELS);
    WlPmRungImage *im = g_new0(WlPmRungImage, 1);
    *im = (WlPmRungImage){rung, width, height,
                          g_array_new(FALSE, FALSE, elem_size(rung))};
    return im;
}

void wl_pm_rung_image_free(WlPmRungImage *im)
{
    if (!im)
        return;
    g_array_free(im->el, TRUE);
    g_free(im);
}

void wl_pm_rung_add_span(WlPmRungImage *im, guint y, guint x0, guint x1)
{
    g_assert(im->rung == WL_PM_RUNG_RUNS && x0 <= x1 && x1 < im->width);
    uint64_t s = (uint64_t)y * im->width + x0;
    if (im->el->len)
        g_assert(g_array_index(im->el, WlPmRun, im->el->len - 1).e <= s);
    run_put(im->el, (WlPmRun){s, s + (x1 - x0) + 1});
}

void wl_pm_rung_add_rect(WlPmRungImage *im, const WlPmCover *r)
{
    g_assert(im->rung == WL_PM_RUNG_COUNTS && r->x1 < im->width &&
             r->y1 < im->height);
    g_array_append_vals(im->el, r, 1);
}

WlPmRungImage *wl_pm_rung_from_wpa(WlPmRung rung, const WlPmWpa *w)
{
    WlPmRungImage *im = wl_pm_rung_image_new(rung, w->width, w->height);
    WlPmCover box = {w->width, w->height, 0, 0, 0};
    for (guint i = 0; i < w->px->len; i++) {
        const WlPmPixel *p = &g_array_index(w->px, WlPmPixel, i);
        if (rung == WL_PM_RUNG_RUNS) {
            wl_pm_rung_add_span(im, p->y, p->x, p->x);
            continue;
        }
        box.x0 = MIN(box.x0, p->x), box.x1 = MAX(box.x1, p->x);
        box.y0 = MIN(box.y0, p->y), box.y1 = MAX(box.y1, p->y);
        box.active++;
    }
    if (rung == WL_PM_RUNG_COUNTS && box.active > 0)
        wl_pm_rung_add_rect(im, &box);
    return im;
}

uint64_t wl_pm_rung_image_active(const WlPmRungImage *im)
{
    WlPmRunsCtx k = {im->rung, im->width};
    WlPmMeasure m;
    wl_pm_runs_measure(&k, im->el, FALSE, &m);
    return m.active;
}
