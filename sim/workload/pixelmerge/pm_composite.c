/* pm_composite.c — compositing on real pixels (pm_composite.h): the
 * pixel rung's representation (depth, colour, the operator's blend) for
 * the plan runner of pm_rung.c, which records the messages and work.
 * A process's pixels are sorted by linear index.
 */
#include "sim/workload/pixelmerge/pm_composite.h"
#include "sim/workload/pixelmerge/pm_rung.h"
#include <math.h>
#include <string.h>

const char *const wl_pm_operator_names[] = {"z", "over", NULL};

typedef struct {
    uint32_t idx, poly, color;
    double z;
    double c[4]; /* over: premultiplied r, g, b, a */
} CPx;

static CPx to_cpx(const WlPmPixel *p, guint w, double a)
{
    CPx q = {(uint32_t)p->y * w + p->x, p->poly, p->color, p->z, {0}};
    q.c[0] = (double)((p->color >> 16) & 255) / 255.0 * a;
    q.c[1] = (double)((p->color >> 8) & 255) / 255.0 * a;
    q.c[2] = (double)(p->color & 255) / 255.0 * a;
    q.c[3] = a;
    return q;
}

/* Pixel i of l at opacity a, or at its own colour when l has one. */
static CPx local_cpx(const WlPmWpa *l, guint i, guint w, double a)
{
    CPx q = to_cpx(&g_array_index(l->px, WlPmPixel, i), w, a);
    if (l->rgba)
        memcpy(q.c, &g_array_index(l->rgba, double, 4 * (gsize)i), sizeof q.c);
    return q;
}

/* f composited over (in front of) b at the same location. */
static CPx blend(const CPx *f, const CPx *b, WlPmOperator op)
{
    if (op == WL_PM_OP_Z)
        return f->z < b->z || (f->z == b->z && f->poly < b->poly) ? *f : *b;
    CPx o = *f;
    for (int i = 0; i < 4; i++)
        o.c[i] = f->c[i] + (1.0 - f->c[3]) * b->c[i];
    return o;
}

/* The front list f composited over the back list b: a new list. */
static GArray *composite(const GArray *f, const GArray *b, WlPmOperator op)
{
    GArray *o = g_array_sized_new(FALSE, FALSE, sizeof(CPx), f->len + b->len);
    guint i = 0, j = 0;
    while (i < f->len || j < b->len) {
        const CPx *x = i < f->len ? &g_array_index(f, CPx, i) : NULL;
        const CPx *y = j < b->len ? &g_array_index(b, CPx, j) : NULL;
        if (x && y && x->idx == y->idx) {
            CPx v = blend(x, y, op);
            g_array_append_val(o, v);
            i++, j++;
        } else if (x && (!y || x->idx < y->idx)) {
            g_array_append_vals(o, x, 1), i++;
        } else {
            g_array_append_vals(o, y, 1), j++;
        }
    }
    return o;
}

/* First pixel of `px` at index >= at. */
static guint lower(const GArray *px, uint64_t at)
{
    guint lo = 0, hi = px->len;
    while (lo < hi) {
        guint mid = lo + (hi - lo) / 2;
        if (g_array_index(px, CPx, mid).idx < at)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The pixel representation's context. */
typedef struct {
    guint w, h;
    WlPmOperator op;
} PxCtx;

/* TRUE when q follows p directly in the order the encoding walks: the
 * linear order, or the box's rows (box NULL: linear). */
static gboolean adjacent(guint w, const CPx *p, const CPx *q, const guint *box)
{
    if (!box)
        return q->idx == p->idx + 1;
    guint px = p->idx % w, py = p->idx / w;
    guint qx = q->idx % w, qy = q->idx / w;
    return (qy == py && qx == px + 1) ||
           (qy == py + 1 && px == box[1] && qx == box[0]);
}

static GArray *px_slice(const void *ctx, const GArray *el, uint64_t a,
                        uint64_t b)
{
    (void)ctx;
    GArray *o = g_array_new(FALSE, FALSE, sizeof(CPx));
    if (el) {
        guint i = lower(el, a), j = lower(el, b);
        g_array_append_vals(o, &g_array_index(el, CPx, i), j - i);
    }
    return o;
}

static GArray *px_over(const void *ctx, GArray *front, GArray *back)
{
    GArray *o = composite(front, back, ((const PxCtx *)ctx)->op);
    g_array_free(front, TRUE);
    g_array_free(back, TRUE);
    return o;
}

static void px_measure(const void *ctx, const GArray *el, gboolean box_mode,
                       WlPmMeasure *m)
{
    guint w = ((const PxCtx *)ctx)->w, n = el->len;
    const CPx *px = (const CPx *)(const void *)el->data;
    *m = (WlPmMeasure){.active = n, .any = n > 0,
                       .box = {w, 0, ((const PxCtx *)ctx)->h, 0}};
    for (guint i = 0; i < n; i++) {
        guint x = px[i].idx % w, y = px[i].idx / w;
        m->box[0] = MIN(m->box[0], x), m->box[1] = MAX(m->box[1], x);
        m->box[2] = MIN(m->box[2], y), m->box[3] = MAX(m->box[3], y);
    }
    const guint *bx = box_mode && n ? m->box : NULL;
    for (guint i = 0; i < n; i++)
        m->runs += i == 0 || !adjacent(w, &px[i - 1], &px[i], bx);
}

static guint8 to_byte(double v)
{
    return (guint8)CLAMP(v * 255.0 + 0.5, 0.0, 255.0);
}

/* A final piece (px, by idx) as an active pixel array (over: the blend
 * as 8-bit colour); over also fills rgba. */
static WlPmWpa *held_wpa(const GArray *px, guint w, guint h, double *rgba)
{
    WlPmWpa *o = wl_pm_wpa_new(w, h);
    for (guint i = 0; i < px->len; i++) {
        const CPx *q = &g_array_index(px, CPx, i);
        WlPmPixel p = {(uint16_t)(q->idx % w), (uint16_t)(q->idx / w), q->z,
                       q->poly, q->color};
        if (rgba) {
            memcpy(&rgba[(gsize)q->idx * 4], q->c, sizeof q->c);
            p.z = 0;
            p.poly = 0;
            p.color = (uint32_t)to_byte(q->c[0]) << 16 |
                      (uint32_t)to_byte(q->c[1]) << 8 | to_byte(q->c[2]);
        }
        wl_pm_wpa_push(o, &p);
    }
    wl_pm_wpa_finish(o);
    return o;
}

/* Processor p's local image as the representation's elements. */
static GArray *local_pixels(const WlPmWpa *l, double opacity)
{
    GArray *px = g_array_sized_new(FALSE, FALSE, sizeof(CPx), l->px->len);
    for (guint i = 0; i < l->px->len; i++) {
        CPx q = local_cpx(l, i, l->width, opacity);
        g_array_append_val(px, q);
    }
    return px;
}

WlPmComposite *wl_pm_composite_run(WlPmScheme scheme, const WlPmCompose *c,
                                   WlPmWpa *const *local, guint n_procs,
                                   const WlPmFormat *fmt)
{
    PxCtx ctx = {local[0]->width, local[0]->height, c->op};
    WlPmRep rep = {px_slice, px_over, px_measure, &ctx};
    uint64_t npix = (uint64_t)ctx.w * ctx.h;
    GArray **el = g_new(GArray *, n_procs);
    for (guint p = 0; p < n_procs; p++)
        el[p] = local_pixels(local[p], c->opacity);
    WlPmComposite *out = g_new0(WlPmComposite, 1);
    out->merge = wl_pm_merge_new(scheme, n_procs, ctx.w, ctx.h);
    out->stages = wl_pm_plan_run(&rep, scheme, c, el, n_procs, ctx.w, npix,
                                 fmt, out->merge->steps);
    if (c->op == WL_PM_OP_OVER)
        out->rgba = g_new0(double, npix * 4);
    for (guint p = 0; p < n_procs; p++) {
        out->merge->held[p] = held_wpa(el[p], ctx.w, ctx.h, out->rgba);
        g_array_free(el[p], TRUE);
    }
    g_free(el);
    wl_pm_merge_summarise(out->merge);
    return out;
}

void wl_pm_composite_free(WlPmComposite *c)
{
    if (!c)
        return;
    wl_pm_merge_free(c->merge);
    g_free(c->rgba);
    g_free(c);
}

gboolean wl_pm_order_ok(const guint *order, guint n)
{
    guint8 *seen = g_new0(guint8, n);
    gboolean ok = TRUE;
    for (guint r = 0; ok && r < n; r++) {
        ok = order[r] < n && !seen[order[r]];
        if (ok)
            seen[order[r]] = 1;
    }
    g_free(seen);
    return ok;
}

double *wl_pm_over_serial(WlPmWpa *const *local, guint n_procs,
                          const guint *order, double opacity)
{
    guint w = local[0]->width;
    double *acc = g_new0(double, (gsize)w * local[0]->height * 4);
    for (guint r = 0; r < n_procs; r++) {
        const WlPmWpa *l = local[order ? order[r] : r];
        for (guint i = 0; i < l->px->len; i++) {
            CPx q = local_cpx(l, i, w, opacity);
            double *a = &acc[(gsize)q.idx * 4], t = 1.0 - a[3];
            for (int j = 0; j < 4; j++)
                a[j] += t * q.c[j];
        }
    }
    return acc;
}

int64_t wl_pm_over_diff(const double *a, const double *b, gsize n)
{
    for (gsize i = 0; i < n; i++)
        if (!(fabs(a[i] - b[i]) <= 1e-9))
            return (int64_t)i;
    return -1;
}
