/* pm_rung.c — running a compositing plan (pm_stages.h) on images of
 * any rung (pm_rung.h, WlPmRep): who sends what to whom, the messages'
 * sizes and the work; what an element is and how it is cut, composited
 * and measured is the representation's (pixels: pm_composite.c; runs and
 * counts: pm_runs.c).
 *
 * Invariants: every process's elements are sorted by linear index and
 * lie in its piece [lo, hi); the active processes of a block have
 * disjoint pieces covering the image, each holding the composite of the
 * block's ranks over its piece; an inactive process holds nothing.
 * Blocks are runs of consecutive ranks (blk[b] .. blk[b + 1]); act[b]
 * lists block b's active ranks by piece, so a block's slice finds its
 * pieces by binary search (binary swap at 32,768 processes would
 * otherwise walk half the block for every share).
 */
#include "sim/workload/pixelmerge/pm_rung.h"
#include "sim/workload/pixelmerge/pm_runs.h"
#include <stdlib.h>

const char *const wl_pm_rung_names[] = {"pixels", "runs", "counts", NULL};

typedef struct {
    GArray *el;
    uint64_t lo, hi;
    gboolean active;
} RProc;

typedef struct {
    const WlPmRep *rep;
    const WlPmCompose *c;
    const WlPmFormat *fmt;
    guint n, w;
    uint64_t npix;
    RProc *pr;
    guint *blk, n_blk; /* block starts, blk[n_blk] == n */
    GArray **act;      /* per block: guint active ranks by lo */
} Rung;

typedef struct {
    uint64_t lo;
    guint blk, rank;
} Owner;

static guint proc_of(const Rung *k, guint r)
{
    return k->c->order ? k->c->order[r] : r;
}

/* Row y's part of [a, b) inside the box's columns. */
static uint64_t row_part(guint w, uint64_t y, uint64_t a, uint64_t b,
                         const guint *box)
{
    uint64_t s = y * w + box[0], e = y * w + box[1] + 1;
    return MIN(e, b) > MAX(s, a) ? MIN(e, b) - MAX(s, a) : 0;
}

uint64_t wl_pm_box_locations(guint w, uint64_t a, uint64_t b, const guint *box)
{
    if (a >= b)
        return 0;
    uint64_t ya = a / w, yb = (b - 1) / w, n = 0;
    if (ya >= box[2] && ya <= box[3])
        n += row_part(w, ya, a, b, box);
    if (yb != ya && yb >= box[2] && yb <= box[3])
        n += row_part(w, yb, a, b, box);
    uint64_t f0 = MAX(ya + 1, (uint64_t)box[2]);
    uint64_t f1 = MIN(yb, (uint64_t)box[3] + 1); /* exclusive */
    if (f1 > f0)
        n += (f1 - f0) * (box[1] - box[0] + 1);
    return n;
}

/* A fragment's records and bytes: the overlap [a, b) holding `el`. */
static void fragment_cost(const Rung *k, const GArray *el, uint64_t a,
                          uint64_t b, WlPmMsg *m)
{
    const WlPmFormat *f = k->fmt;
    WlPmMeasure ms;
    k->rep->measure(k->rep->ctx, el, k->c->bounding_rect, &ms);
    uint64_t rect = k->c->bounding_rect ? f->bytes_per_rect : 0;
    if (k->c->rle) {
        m->pixels = ms.active;
        m->bytes = ms.active * f->bytes_per_location +
                   (ms.runs + 1) * f->bytes_per_run + rect;
    } else {
        m->pixels = !k->c->bounding_rect ? b - a
                    : ms.any ? wl_pm_box_locations(k->w, a, b, ms.box)
                             : 0;
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

/* The group's active processes in share order; returns how many. */
static guint owners(const Rung *k, guint b0, guint nb, Owner *own)
{
    guint n = 0;
    for (guint b = b0; b < b0 + nb; b++)
        for (guint i = 0; i < k->act[b]->len; i++) {
            guint r = g_array_index(k->act[b], guint, i);
            own[n++] = (Owner){k->pr[r].lo, b, r};
        }
    qsort(own, n, sizeof *own, owner_cmp);
    return n;
}

/* First index of block b's active list whose piece ends after `at`. */
static guint piece_at(const Rung *k, guint b, uint64_t at)
{
    const GArray *a = k->act[b];
    guint lo = 0, hi = a->len;
    while (lo < hi) {
        guint mid = lo + (hi - lo) / 2;
        if (k->pr[g_array_index(a, guint, mid)].hi <= at)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* Block b's composite over [a, e): its active processes' slices. */
static GArray *block_slice(const Rung *k, guint b, uint64_t a, uint64_t e)
{
    GArray *o = NULL;
    for (guint i = piece_at(k, b, a); i < k->act[b]->len; i++) {
        const RProc *p = &k->pr[g_array_index(k->act[b], guint, i)];
        if (p->lo >= e)
            break;
        GArray *s =
            k->rep->slice(k->rep->ctx, p->el, MAX(a, p->lo), MIN(e, p->hi));
        if (o) {
            g_array_append_vals(o, s->data, s->len);
            g_array_free(s, TRUE);
        } else {
            o = s;
        }
    }
    return o ? o : k->rep->slice(k->rep->ctx, NULL, a, e);
}

/* Messages of process q to the owners of share[0 .. no], into msgs and
 * work: only the shares its piece overlaps. */
static void send_fragments(const Rung *k, guint q, const Owner *own, guint no,
                           const uint64_t *share, GArray *msgs, WlPmWork *work)
{
    const RProc *p = &k->pr[q];
    guint i = (guint)(p->lo * no / k->npix);
    while (i > 0 && share[i] > p->lo)
        i--;
    for (; i < no && share[i] < p->hi; i++) {
        guint r = own[i].rank;
        uint64_t a = MAX(p->lo, share[i]), b = MIN(p->hi, share[i + 1]);
        if (r == q || a >= b)
            continue;
        WlPmMsg m = {.src = proc_of(k, q), .dst = proc_of(k, r)};
        GArray *frag = k->rep->slice(k->rep->ctx, p->el, a, b);
        fragment_cost(k, frag, a, b, &m);
        g_array_free(frag, TRUE);
        g_array_append_val(msgs, m);
        work[m.src].pack += m.pixels;
        work[m.dst].compare += m.pixels;
    }
}

/* One group of nb blocks from block b0: messages, then new pieces; the
 * group's new active list goes to act[b0]. */
static void run_group(Rung *k, guint b0, guint nb, gboolean fold, GArray *msgs,
                      WlPmWork *work)
{
    guint r0 = k->blk[b0], r1 = k->blk[b0 + nb];
    Owner *own = g_new(Owner, r1 - r0);
    guint na = owners(k, b0, nb, own), no = fold ? MIN(na, 1u) : na;
    uint64_t *share = g_new(uint64_t, no + 1);
    for (guint i = 0; i <= no; i++)
        share[i] = k->npix * i / no;
    for (guint i = 0; i < na; i++)
        send_fragments(k, own[i].rank, own, no, share, msgs, work);
    GArray **next = g_new0(GArray *, no);
    for (guint i = 0; i < no; i++) {
        next[i] = block_slice(k, b0, share[i], share[i + 1]);
        for (guint b = b0 + 1; b < b0 + nb; b++)
            next[i] = k->rep->over(
                k->rep->ctx, next[i],
                block_slice(k, b, share[i], share[i + 1]));
    }
    for (guint i = 0; i < na; i++) {
        RProc *p = &k->pr[own[i].rank];
        g_array_set_size(p->el, 0);
        p->active = FALSE;
    }
    for (guint b = b0; b < b0 + nb; b++)
        g_array_set_size(k->act[b], 0);
    for (guint i = 0; i < no; i++) {
        RProc *p = &k->pr[own[i].rank];
        g_array_free(p->el, TRUE);
        *p = (RProc){next[i], share[i], share[i + 1], TRUE};
        g_array_append_val(k->act[b0], own[i].rank);
    }
    g_free(next);
    g_free(share);
    g_free(own);
}

/* One stage: its groups, one exchange step, the merged block list. */
static WlPmStep *run_stage(Rung *k, const WlPmStage *st)
{
    WlPmStep *step = wl_pm_step_new(k->n, TRUE);
    GArray *msgs = g_array_new(FALSE, FALSE, sizeof(WlPmMsg));
    guint b = 0;
    for (guint g = 0; g < st->n_groups; g++) {
        if (st->size[g] > 1)
            run_group(k, b, st->size[g], st->fold, msgs, step->work);
        k->blk[g] = k->blk[b];
        GArray *keep = k->act[b];
        for (guint j = b + 1; j < b + st->size[g]; j++)
            g_array_free(k->act[j], TRUE);
        k->act[g] = keep;
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

static void rung_init(Rung *k, GArray **el)
{
    k->pr = g_new0(RProc, k->n);
    k->blk = g_new(guint, k->n + 1);
    k->act = g_new(GArray *, k->n);
    k->n_blk = k->n;
    for (guint p = 0; p <= k->n; p++)
        k->blk[p] = p;
    for (guint r = 0; r < k->n; r++) {
        k->pr[r] = (RProc){el[proc_of(k, r)], 0, k->npix, TRUE};
        k->act[r] = g_array_new(FALSE, FALSE, sizeof(guint));
        g_array_append_val(k->act[r], r);
    }
}

guint wl_pm_plan_run(const WlPmRep *rep, WlPmScheme scheme,
                     const WlPmCompose *c, GArray **el, guint n_procs,
                     guint width, uint64_t npix, const WlPmFormat *fmt,
                     GPtrArray *steps)
{
    g_assert(!c->order || wl_pm_order_ok(c->order, n_procs));
    Rung k = {.rep = rep, .c = c, .fmt = fmt, .n = n_procs, .w = width,
              .npix = npix};
    rung_init(&k, el);
    WlPmPlan *plan = wl_pm_plan_new(scheme, n_procs, c->radices, c->n_radices);
    for (guint s = 0; s < plan->n_stages; s++)
        g_ptr_array_add(steps, run_stage(&k, &plan->stage[s]));
    guint stages = plan->n_stages;
    g_assert(k.n_blk == 1);
    for (guint r = 0; r < n_procs; r++)
        el[proc_of(&k, r)] = k.pr[r].el;
    g_array_free(k.act[0], TRUE);
    wl_pm_plan_free(plan);
    g_free(k.act);
    g_free(k.pr);
    g_free(k.blk);
    return stages;
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

WlPmMerge *wl_pm_rung_run(WlPmScheme scheme, const WlPmCompose *c,
                          WlPmRungImage *const *images, guint n_procs,
                          const WlPmFormat *fmt, guint *stages)
{
    WlPmRunsCtx ctx = {images[0]->rung, images[0]->width};
    WlPmRep rep = wl_pm_runs_rep(&ctx);
    uint64_t npix = (uint64_t)ctx.width * images[0]->height;
    GArray **el = g_new(GArray *, n_procs);
    for (guint p = 0; p < n_procs; p++) {
        g_assert(images[p]->rung == ctx.rung && images[p]->width == ctx.width);
        el[p] = rep.slice(&ctx, images[p]->el, 0, npix);
    }
    WlPmMerge *m = g_new0(WlPmMerge, 1);
    m->scheme = scheme;
    m->n_procs = n_procs;
    m->steps = g_ptr_array_new();
    m->merge_ops = g_new0(uint64_t, n_procs);
    guint ns =
        wl_pm_plan_run(&rep, scheme, c, el, n_procs, ctx.width, npix, fmt,
                       m->steps);
    if (stages)
        *stages = ns;
    for (guint s = 0; s < m->steps->len; s++) {
        const WlPmStep *st = g_ptr_array_index(m->steps, s);
        for (guint p = 0; p < n_procs; p++)
            m->merge_ops[p] += st->work[p].compare;
        for (guint i = 0; i < st->n_msgs; i++)
            m->total_bytes += st->msg[i].bytes;
        m->total_msgs += st->n_msgs;
    }
    m->concurrent_volume = wl_pm_concurrent_volume(m->steps, n_procs);
    for (guint p = 0; p < n_procs; p++)
        g_array_free(el[p], TRUE);
    g_free(el);
    return m;
}

void wl_pm_rung_merge_free(WlPmMerge *m)
{
    if (!m)
        return;
    for (guint s = 0; s < m->steps->len; s++) {
        WlPmStep *st = g_ptr_array_index(m->steps, s);
        g_free(st->msg);
        g_free(st->work);
        g_free(st);
    }
    g_ptr_array_free(m->steps, TRUE);
    g_free(m->merge_ops);
    g_free(m);
}
