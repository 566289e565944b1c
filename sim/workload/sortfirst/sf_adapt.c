/* sf_adapt.c — adaptive screen regions: the grid estimate and the k-d
 * median-of-weight split (sf_adapt.h; seed 000 §1.2, [12]).
 */
#include "sim/workload/sortfirst/sf_adapt.h"
#include <math.h>
#include <string.h>

WlSfAdapt *wl_sf_adapt_new(guint grid, guint procs)
{
    g_assert(grid >= 1 && grid <= 1024 && wl_sf_adapt_fits(grid, procs));
    WlSfAdapt *a = g_new0(WlSfAdapt, 1);
    a->grid = grid;
    a->procs = procs;
    a->weight = g_new0(uint64_t, (gsize)grid * grid);
    a->added = g_new0(uint64_t, procs);
    a->nz = g_new0(uint64_t, procs);
    a->mark = g_new0(guint8, ((gsize)grid * grid * procs + 7) / 8);
    a->factor = g_new(double, (gsize)grid * grid);
    for (guint i = 0; i < grid * grid; i++)
        a->factor[i] = 1;
    return a;
}

void wl_sf_adapt_free(WlSfAdapt *a)
{
    if (!a)
        return;
    g_free(a->weight);
    g_free(a->added);
    g_free(a->nz);
    g_free(a->mark);
    g_free(a->factor);
    g_free(a->last_x);
    g_free(a->last_y);
    g_free(a->last_ok);
    g_free(a);
}

/* The cell (0 .. G-1) of pixel coordinate v on an axis of `size` pixels. */
static guint cell_of(const WlSfAdapt *a, double v, int size)
{
    if (!(v > 0)) /* also NaN */
        return 0;
    double c = floor(v * a->grid / size);
    return c >= a->grid ? a->grid - 1 : (guint)c;
}

void wl_sf_adapt_predict(WlSfAdapt *a, guint n_insts)
{
    g_assert(!a->last_x);
    a->n_insts = n_insts;
    a->last_x = g_new0(float, MAX(n_insts, 1));
    a->last_y = g_new0(float, MAX(n_insts, 1));
    a->last_ok = g_new0(guint8, MAX(n_insts, 1));
}

void wl_sf_adapt_remap(WlSfAdapt *a, const gint64 *map, guint n)
{
    g_assert(a->last_x);
    float *x = g_new0(float, MAX(n, 1)), *y = g_new0(float, MAX(n, 1));
    guint8 *ok = g_new0(guint8, MAX(n, 1));
    for (guint i = 0; i < n; i++)
        if (map[i] >= 0) {
            x[i] = a->last_x[map[i]];
            y[i] = a->last_y[map[i]];
            ok[i] = a->last_ok[map[i]];
        }
    g_free(a->last_x);
    g_free(a->last_y);
    g_free(a->last_ok);
    a->last_x = x, a->last_y = y, a->last_ok = ok;
    a->n_insts = n;
}

/* With prediction: remembers instance i's centre (cx, cy) and moves it
 * to 2 c - c_last when it had one, clamped to [0, size). */
static void extrapolate(WlSfAdapt *a, const WlSfRegions *r, guint i,
                        double *cx, double *cy)
{
    if (!a->last_x)
        return;
    double lx = a->last_x[i], ly = a->last_y[i];
    gboolean had = a->last_ok[i];
    a->last_x[i] = (float)*cx;
    a->last_y[i] = (float)*cy;
    a->last_ok[i] = 1;
    if (!had)
        return;
    *cx = CLAMP(2 * *cx - lx, 0, r->width - 1e-9);
    *cy = CLAMP(2 * *cy - ly, 0, r->height - 1e-9);
    a->predicted++;
}

/* Processor p's master added to cell: counts it once in nz[p]. */
static void count_cell(WlSfAdapt *a, guint p, gsize cell)
{
    gsize bit = (gsize)p * a->grid * a->grid + cell;
    guint8 m = (guint8)(1u << (bit & 7));
    a->added[p]++;
    if (!(a->mark[bit >> 3] & m)) {
        a->mark[bit >> 3] |= m;
        a->nz[p]++;
    }
}

void wl_sf_adapt_estimate(WlSfAdapt *a, const WlSfDb *db,
                          const WlSfRegions *r, Mat4 view_proj)
{
    memset(a->weight, 0, sizeof(uint64_t) * a->grid * a->grid);
    memset(a->added, 0, sizeof(uint64_t) * a->procs);
    memset(a->nz, 0, sizeof(uint64_t) * a->procs);
    memset(a->mark, 0, ((gsize)a->grid * a->grid * a->procs + 7) / 8);
    g_assert(!a->last_x || a->n_insts == wl_sf_n_insts(db));
    a->predicted = 0;
    for (guint i = 0; i < wl_sf_n_insts(db); i++) {
        const WlSfInst *in = wl_sf_inst(db, i);
        const WlSfChunk *ch = wl_sf_chunk(db, in->chunk);
        double x0, y0, x1, y1;
        if (scene_box_is_empty(ch->box) ||
            !wl_sf_box_screen(r, ch->box, mat4_mul(view_proj, in->matrix), &x0,
                              &y0, &x1, &y1)) {
            if (a->last_x)
                a->last_ok[i] = 0;
            continue;
        }
        double cx = isfinite(x0) ? (MAX(x0, 0) + MIN(x1, r->width)) / 2
                                 : r->width / 2.0;
        double cy = isfinite(y0) ? (MAX(y0, 0) + MIN(y1, r->height)) / 2
                                 : r->height / 2.0;
        extrapolate(a, r, i, &cx, &cy);
        guint gx = cell_of(a, cx, r->width), gy = cell_of(a, cy, r->height);
        gsize cell = (gsize)gy * a->grid + gx;
        a->weight[cell] += ch->polys;
        guint m = a->master ? a->master[in->chunk] : ch->master;
        count_cell(a, m % a->procs, cell);
    }
}

/* ---- which nodes can be split to the end ------------------------------
 * A node of a x b cells holds k processors when k = 1 or when some cut
 * across either axis leaves both halves (k/2 and k - k/2 processors)
 * able to hold theirs: cells >= k is not enough (3 x 3 cells cannot
 * hold 9: each half of 4 or 5 needs 2 of the 3 lines).  A larger node
 * holds whatever a smaller one does (widen its last slab), so a node
 * of `other` lines across holds k exactly when it is at least
 * need(other, k) lines long; need(other, k) <= k (a strip of k lines).
 * Memoised per (other, k): O(G P) entries, each O(P) to fill. */

typedef struct {
    guint grid, procs;
    guint8 *memo; /* (grid + 1) x (procs + 1); 0: not yet known */
} Need;

static guint need(Need *n, guint other, guint k);

static gboolean holds(Need *n, guint a, guint b, guint k)
{
    guint k1 = k / 2, k2 = k - k1;
    return k == 1 || a >= need(n, b, k1) + need(n, b, k2) ||
           b >= need(n, a, k1) + need(n, a, k2);
}

static guint need(Need *n, guint other, guint k)
{
    guint8 *m = &n->memo[(gsize)other * (n->procs + 1) + k];
    guint a = 1;
    if (*m)
        return *m;
    while (!holds(n, a, other, k))
        a++;
    return *m = (guint8)a;
}

static Need need_new(guint grid, guint procs)
{
    gsize cells = ((gsize)MAX(grid, procs) + 1) * (procs + 1);
    return (Need){MAX(grid, procs), procs, g_new0(guint8, cells)};
}

gboolean wl_sf_adapt_fits(guint grid, guint procs)
{
    Need n = need_new(grid, procs);
    gboolean ok = holds(&n, grid, grid, procs);
    g_free(n.memo);
    return ok;
}

/* ---- the k-d split --------------------------------------------------------
 */

typedef struct {
    guint x0, y0, x1, y1; /* cells */
} Cells;

typedef struct {
    const WlSfAdapt *a;
    WlSfRegions *r;
    uint64_t visited;
    uint64_t *marg; /* scratch, G */
    uint64_t *sat;  /* (G+1)^2 summed-area table of weight x factor */
    Need need;      /* lines each side of a cut keeps */
} Split;

/* Σ of the weights of cells [x0, x1) x [y0, y1). */
static uint64_t sat_sum(const Split *s, guint x0, guint y0, guint x1, guint y1)
{
    gsize g1 = s->a->grid + 1;
    const uint64_t *t = s->sat;
    return t[y1 * g1 + x1] - t[y0 * g1 + x1] - t[y1 * g1 + x0] +
           t[y0 * g1 + x0];
}

/* Weight per line across the node along `axis` (0: columns, 1: rows). */
static uint64_t marginal(Split *s, Cells c, int axis)
{
    guint lo = axis ? c.y0 : c.x0, hi = axis ? c.y1 : c.x1;
    for (guint i = lo; i < hi; i++)
        s->marg[i] = axis ? sat_sum(s, c.x0, i, c.x1, i + 1)
                          : sat_sum(s, i, c.y0, i + 1, c.y1);
    s->visited += 2 * (uint64_t)(hi - lo);
    return sat_sum(s, c.x0, c.y0, c.x1, c.y1);
}

/* The summed-area table of weight x factor: G^2 cells visited. */
static void build_sat(Split *s)
{
    guint g = s->a->grid;
    gsize g1 = g + 1;
    for (guint y = 0; y < g; y++) {
        uint64_t row = 0;
        for (guint x = 0; x < g; x++) {
            gsize i = (gsize)y * g + x;
            row += (uint64_t)llround((double)s->a->weight[i] * s->a->factor[i]);
            s->sat[(y + 1) * g1 + x + 1] = s->sat[y * g1 + x + 1] + row;
        }
    }
    s->visited += (uint64_t)g * g;
}

typedef struct {
    guint at;   /* the cut: a cell boundary */
    uint64_t v; /* max(left k2, right k1): the larger side's load x k1 k2 */
} Cut;

/* The cut for k1 of k processors on [lo, hi), each side keeping at least
 * need1 / need2 lines. */
static Cut best_cut(const Split *s, guint lo, guint hi, guint need1,
                    guint need2, guint k1, guint k, uint64_t total)
{
    guint k2 = k - k1;
    Cut best = {lo + need1, UINT64_MAX};
    double prop = lo + (double)(hi - lo) * k1 / k, best_d = INFINITY;
    uint64_t left = 0;
    for (guint i = lo; i < lo + need1; i++)
        left += s->marg[i];
    for (guint c = lo + need1; c + need2 <= hi; left += s->marg[c++]) {
        uint64_t v = MAX(left * k2, (total - left) * k1);
        double d = fabs(c - prop);
        if (v < best.v || (v == best.v && d < best_d)) {
            best = (Cut){c, v};
            best_d = d;
        }
    }
    return best;
}

static void leaf(Split *s, Cells c, guint p)
{
    const WlSfRegions *r = s->r;
    guint g = s->a->grid;
    s->r->rect[p] = (WlSfRect){
        (int)((int64_t)c.x0 * r->width / g), (int)((int64_t)c.y0 * r->height / g),
        (int)((int64_t)c.x1 * r->width / g), (int)((int64_t)c.y1 * r->height / g)};
}

/* The best cut across axis (0: a vertical cut, 1: horizontal); v is
 * UINT64_MAX when the node cannot be cut that way. */
static Cut axis_cut(Split *s, Cells c, int axis, guint k1, guint k)
{
    guint w = c.x1 - c.x0, h = c.y1 - c.y0, other = axis ? w : h;
    guint n1 = need(&s->need, other, k1), n2 = need(&s->need, other, k - k1);
    guint lo = axis ? c.y0 : c.x0, hi = axis ? c.y1 : c.x1;
    if (n1 + n2 > hi - lo)
        return (Cut){0, UINT64_MAX};
    uint64_t total = marginal(s, c, axis);
    return best_cut(s, lo, hi, n1, n2, k1, k, total);
}

/* Cut across the node's longer side (the other when the longer cannot
 * hold both halves' processors).  Trying both axes and keeping the
 * better cut balanced a test grid better but moved the regions more
 * from frame to frame: on the vehicle (P = 16) it migrated 4.1 MB a
 * frame instead of 2.5 MB and the frame took 0.68 ms instead of 0.61. */
static void split(Split *s, Cells c, guint first, guint k)
{
    if (k == 1) {
        leaf(s, c, first);
        return;
    }
    guint k1 = k / 2;
    gboolean wide = c.x1 - c.x0 >= c.y1 - c.y0;
    Cut x = {0, UINT64_MAX}, y = {0, UINT64_MAX};
    if (wide)
        x = axis_cut(s, c, 0, k1, k);
    if (!wide || x.v == UINT64_MAX)
        y = axis_cut(s, c, 1, k1, k);
    if (!wide && y.v == UINT64_MAX)
        x = axis_cut(s, c, 0, k1, k);
    g_assert(x.v != UINT64_MAX || y.v != UINT64_MAX);
    gboolean use_x = wide ? x.v != UINT64_MAX : y.v == UINT64_MAX;
    Cells a = c, b = c;
    if (use_x)
        a.x1 = b.x0 = x.at;
    else
        a.y1 = b.y0 = y.at;
    split(s, a, first, k1);
    split(s, b, first + k1, k - k1);
}

uint64_t wl_sf_adapt_split(const WlSfAdapt *a, WlSfRegions *r)
{
    g_assert(r->procs == a->procs);
    gsize g1 = (gsize)a->grid + 1;
    Split s = {a, r, 0, g_new0(uint64_t, a->grid), g_new0(uint64_t, g1 * g1),
               need_new(a->grid, a->procs)};
    build_sat(&s);
    split(&s, (Cells){0, 0, a->grid, a->grid}, 0, r->procs);
    g_free(s.marg);
    g_free(s.sat);
    g_free(s.need.memo);
    return s.visited;
}

void wl_sf_adapt_calibrate(WlSfAdapt *a, const WlSfRegions *r,
                           const double *work)
{
    double k[WL_SF_MAX_PROCS], mean = 0;
    guint n = 0;
    for (guint p = 0; p < r->procs; p++) {
        uint64_t w = wl_sf_adapt_weight_in(a, r, r->rect[p]);
        k[p] = w ? work[p] / (double)w : -1;
        if (w) {
            mean += k[p];
            n++;
        }
    }
    mean = n ? mean / n : 1;
    guint g = a->grid;
    for (guint y = 0; y < g; y++)
        for (guint x = 0; x < g; x++) {
            int px = (int)((int64_t)x * r->width / g);
            int py = (int)((int64_t)y * r->height / g);
            for (guint p = 0; p < r->procs; p++) {
                WlSfRect q = r->rect[p];
                if (px >= q.x0 && px < q.x1 && py >= q.y0 && py < q.y1)
                    a->factor[(gsize)y * g + x] = k[p] >= 0 ? k[p] : mean;
            }
        }
    a->calibrated = TRUE;
}

uint64_t wl_sf_adapt_weight_in(const WlSfAdapt *a, const WlSfRegions *r,
                               WlSfRect q)
{
    uint64_t sum = 0;
    guint g = a->grid;
    for (guint y = 0; y < g; y++)
        for (guint x = 0; x < g; x++) {
            int px = (int)((int64_t)x * r->width / g);
            int py = (int)((int64_t)y * r->height / g);
            if (px >= q.x0 && px < q.x1 && py >= q.y0 && py < q.y1)
                sum += a->weight[(gsize)y * g + x];
        }
    return sum;
}
