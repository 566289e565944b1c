/* pm_composite.c — running a compositing plan (pm_stages.h) on real
 * pixels, recording its messages and work (pm_composite.h).
 *
 * Invariants: every process's pixels are sorted by linear index and lie
 * in its piece [lo, hi); the active processes of a block have disjoint
 * pieces that cover the image, each holding the composite of the
 * block's ranks over its piece; an inactive process holds nothing.
 * Blocks are runs of consecutive ranks (blk[b] .. blk[b + 1]).
 */
#include "sim/workload/pixelmerge/pm_composite.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *const wl_pm_operator_names[] = {"z", "over", NULL};

typedef struct {
    uint32_t idx, poly, color;
    double z;
    double c[4]; /* over: premultiplied r, g, b, a */
} CPx;

typedef struct {
    GArray *px; /* CPx, by idx */
    uint64_t lo, hi;
    gboolean active;
} CProc;

typedef struct {
    const WlPmCompose *c;
    const WlPmFormat *fmt;
    guint n, w, h;
    uint64_t npix;
    CProc *pr;
    guint *blk, n_blk; /* block starts, blk[n_blk] == n */
} Comp;

/* The processor of rank r. */
static guint proc_of(const Comp *k, guint r)
{
    return k->c->order ? k->c->order[r] : r;
}

/* One active process of a group, as its new share is chosen. */
typedef struct {
    uint64_t lo;
    guint blk, rank;
} Owner;

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

/* Locations of [a, b) inside the box x0..x1, y0..y1 (inclusive). */
static uint64_t box_locations(const Comp *k, uint64_t a, uint64_t b,
                              const guint *box)
{
    uint64_t n = 0;
    for (guint y = box[2]; y <= box[3]; y++) {
        uint64_t s = (uint64_t)y * k->w + box[0], e = s + box[1] - box[0] + 1;
        if (MIN(e, b) > MAX(s, a))
            n += MIN(e, b) - MAX(s, a);
    }
    return n;
}

/* TRUE when q follows p directly in the order the encoding walks: the
 * linear order, or the box's rows (box NULL: linear). */
static gboolean adjacent(const Comp *k, const CPx *p, const CPx *q,
                         const guint *box)
{
    if (!box)
        return q->idx == p->idx + 1;
    guint px = p->idx % k->w, py = p->idx / k->w;
    guint qx = q->idx % k->w, qy = q->idx / k->w;
    return (qy == py && qx == px + 1) ||
           (qy == py + 1 && px == box[1] && qx == box[0]);
}

/* A fragment's records and bytes: the overlap [a, b) holding px[n]. */
static void fragment_cost(const Comp *k, const CPx *px, guint n, uint64_t a,
                          uint64_t b, WlPmMsg *m)
{
    const WlPmFormat *f = k->fmt;
    guint box[4] = {k->w, 0, k->h, 0}; /* x0, x1, y0, y1 */
    for (guint i = 0; i < n; i++) {
        guint x = px[i].idx % k->w, y = px[i].idx / k->w;
        box[0] = MIN(box[0], x), box[1] = MAX(box[1], x);
        box[2] = MIN(box[2], y), box[3] = MAX(box[3], y);
    }
    const guint *bx = k->c->bounding_rect && n ? box : NULL;
    uint64_t runs = 0;
    for (guint i = 0; i < n; i++)
        runs += i == 0 || !adjacent(k, &px[i - 1], &px[i], bx);
    uint64_t rect = k->c->bounding_rect ? f->bytes_per_rect : 0;
    if (k->c->rle) {
        m->pixels = n;
        m->bytes = (uint64_t)n * f->bytes_per_location +
                   (runs + 1) * f->bytes_per_run + rect;
    } else {
        m->pixels = k->c->bounding_rect ? (bx ? box_locations(k, a, b, bx) : 0)
                                        : b - a;
        m->bytes = m->pixels * f->bytes_per_location + rect;
    }
}

static int owner_cmp(const void *a, const void *b)
{
    const Owner *x = a, *y = b;
    if (x->lo != y->lo)
        return x->lo < y->lo ? -1 : 1;
    return x->blk < y->blk ? -1 : x->blk > y->blk;
}

/* The group's active processes in share order; returns how many own a
 * share (one for a fold). */
static guint owners(const Comp *k, guint b0, guint nb, gboolean fold,
                    Owner *own)
{
    guint n = 0;
    for (guint b = b0; b < b0 + nb; b++)
        for (guint r = k->blk[b]; r < k->blk[b + 1]; r++)
            if (k->pr[r].active)
                own[n++] = (Owner){k->pr[r].lo, b, r};
    qsort(own, n, sizeof *own, owner_cmp);
    return fold ? MIN(n, 1u) : n;
}

/* Block b's composite over [a, e): its active processes' slices. */
static GArray *block_slice(const Comp *k, guint b, uint64_t a, uint64_t e)
{
    GArray *o = g_array_new(FALSE, FALSE, sizeof(CPx));
    for (uint64_t at = a; at < e;) { /* pieces of a block tile the image */
        guint r = k->blk[b];
        while (!k->pr[r].active || k->pr[r].lo > at || k->pr[r].hi <= at)
            g_assert(++r < k->blk[b + 1]);
        const GArray *px = k->pr[r].px;
        uint64_t end = MIN(e, k->pr[r].hi);
        guint i = lower(px, at), j = lower(px, end);
        g_array_append_vals(o, &g_array_index(px, CPx, i), j - i);
        at = end;
    }
    return o;
}

/* Messages of process q to the group's new owners, into msgs and work. */
static void send_fragments(const Comp *k, guint q, const Owner *own,
                           guint n_own, const uint64_t *share, GArray *msgs,
                           WlPmWork *work)
{
    const CProc *p = &k->pr[q];
    for (guint i = 0; i < n_own; i++) {
        guint r = own[i].rank;
        uint64_t a = MAX(p->lo, share[i]), b = MIN(p->hi, share[i + 1]);
        if (r == q || a >= b)
            continue;
        guint s = lower(p->px, a), e = lower(p->px, b);
        WlPmMsg m = {.src = proc_of(k, q), .dst = proc_of(k, r)};
        fragment_cost(k, &g_array_index(p->px, CPx, s), e - s, a, b, &m);
        g_array_append_val(msgs, m);
        work[m.src].pack += m.pixels;
        work[m.dst].compare += m.pixels;
    }
}

/* One group of nb blocks from block b0: messages, then new pieces. */
static void run_group(Comp *k, guint b0, guint nb, gboolean fold, GArray *msgs,
                      WlPmWork *work)
{
    guint r0 = k->blk[b0], r1 = k->blk[b0 + nb];
    Owner *own = g_new(Owner, r1 - r0);
    guint no = owners(k, b0, nb, fold, own);
    uint64_t *share = g_new(uint64_t, no + 1);
    for (guint i = 0; i <= no; i++)
        share[i] = k->npix * i / no;
    for (guint q = r0; q < r1; q++)
        if (k->pr[q].active)
            send_fragments(k, q, own, no, share, msgs, work);
    GArray **next = g_new0(GArray *, no);
    for (guint i = 0; i < no; i++) {
        next[i] = block_slice(k, b0, share[i], share[i + 1]);
        for (guint b = b0 + 1; b < b0 + nb; b++) {
            GArray *back = block_slice(k, b, share[i], share[i + 1]);
            GArray *t = composite(next[i], back, k->c->op);
            g_array_free(back, TRUE);
            g_array_free(next[i], TRUE);
            next[i] = t;
        }
    }
    for (guint q = r0; q < r1; q++) {
        g_array_set_size(k->pr[q].px, 0);
        k->pr[q].active = FALSE;
    }
    for (guint i = 0; i < no; i++) {
        CProc *p = &k->pr[own[i].rank];
        g_array_free(p->px, TRUE);
        *p = (CProc){next[i], share[i], share[i + 1], TRUE};
    }
    g_free(next);
    g_free(share);
    g_free(own);
}

WlPmMsg *wl_pm_msgs_by_sender(GArray *msgs, guint n)
{
    guint *at = g_new0(guint, n + 1);
    for (guint i = 0; i < msgs->len; i++)
        at[g_array_index(msgs, WlPmMsg, i).src + 1]++;
    for (guint p = 0; p < n; p++)
        at[p + 1] += at[p];
    WlPmMsg *out = g_new(WlPmMsg, MAX(msgs->len, 1u));
    for (guint i = 0; i < msgs->len; i++) {
        const WlPmMsg *m = &g_array_index(msgs, WlPmMsg, i);
        out[at[m->src]++] = *m;
    }
    g_array_free(msgs, TRUE);
    g_free(at);
    return out;
}

/* One stage: its groups, one exchange step, the merged block list. */
static WlPmStep *run_stage(Comp *k, const WlPmStage *st)
{
    WlPmStep *step = wl_pm_step_new(k->n, TRUE);
    GArray *msgs = g_array_new(FALSE, FALSE, sizeof(WlPmMsg));
    guint b = 0;
    for (guint g = 0; g < st->n_groups; g++) {
        if (st->size[g] > 1)
            run_group(k, b, st->size[g], st->fold, msgs, step->work);
        k->blk[g] = k->blk[b];
        b += st->size[g];
    }
    g_assert(b == k->n_blk);
    k->n_blk = st->n_groups;
    k->blk[k->n_blk] = k->n;
    g_free(step->msg);
    step->n_msgs = msgs->len;
    step->msg = wl_pm_msgs_by_sender(msgs, k->n);
    return step;
}

static guint8 to_byte(double v)
{
    return (guint8)CLAMP(v * 255.0 + 0.5, 0.0, 255.0);
}

/* p's final piece as an active pixel array (over: the blend as 8-bit
 * colour); over also fills rgba. */
static WlPmWpa *held_wpa(const Comp *k, const CProc *p, double *rgba)
{
    WlPmWpa *w = wl_pm_wpa_new(k->w, k->h);
    for (guint i = 0; p->active && i < p->px->len; i++) {
        const CPx *q = &g_array_index(p->px, CPx, i);
        WlPmPixel o = {(uint16_t)(q->idx % k->w), (uint16_t)(q->idx / k->w),
                       q->z, q->poly, q->color};
        if (rgba) {
            memcpy(&rgba[(gsize)q->idx * 4], q->c, sizeof q->c);
            o.z = 0;
            o.poly = 0;
            o.color = (uint32_t)to_byte(q->c[0]) << 16 |
                      (uint32_t)to_byte(q->c[1]) << 8 | to_byte(q->c[2]);
        }
        wl_pm_wpa_push(w, &o);
    }
    wl_pm_wpa_finish(w);
    return w;
}

static void comp_init(Comp *k, WlPmWpa *const *local)
{
    k->w = local[0]->width;
    k->h = local[0]->height;
    k->npix = (uint64_t)k->w * k->h;
    k->pr = g_new0(CProc, k->n);
    k->blk = g_new(guint, k->n + 1);
    k->n_blk = k->n;
    for (guint p = 0; p <= k->n; p++)
        k->blk[p] = p;
    for (guint p = 0; p < k->n; p++) {
        const WlPmWpa *l = local[proc_of(k, p)];
        GArray *px = g_array_sized_new(FALSE, FALSE, sizeof(CPx), l->px->len);
        for (guint i = 0; i < l->px->len; i++) {
            CPx q = local_cpx(l, i, k->w, k->c->opacity);
            g_array_append_val(px, q);
        }
        k->pr[p] = (CProc){px, 0, k->npix, TRUE};
    }
}

WlPmComposite *wl_pm_composite_run(WlPmScheme scheme, const WlPmCompose *c,
                                   WlPmWpa *const *local, guint n_procs,
                                   const WlPmFormat *fmt)
{
    g_assert(!c->order || wl_pm_order_ok(c->order, n_procs));
    Comp k = {.c = c, .fmt = fmt, .n = n_procs};
    comp_init(&k, local);
    WlPmComposite *out = g_new0(WlPmComposite, 1);
    out->merge = wl_pm_merge_new(scheme, n_procs, k.w, k.h);
    WlPmPlan *plan =
        wl_pm_plan_new(scheme, n_procs, c->radices, c->n_radices);
    for (guint s = 0; s < plan->n_stages; s++)
        g_ptr_array_add(out->merge->steps, run_stage(&k, &plan->stage[s]));
    out->stages = plan->n_stages;
    g_assert(k.n_blk == 1);
    if (c->op == WL_PM_OP_OVER)
        out->rgba = g_new0(double, k.npix * 4);
    for (guint r = 0; r < n_procs; r++) {
        out->merge->held[proc_of(&k, r)] = held_wpa(&k, &k.pr[r], out->rgba);
        g_array_free(k.pr[r].px, TRUE);
    }
    wl_pm_merge_summarise(out->merge);
    wl_pm_plan_free(plan);
    g_free(k.pr);
    g_free(k.blk);
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
