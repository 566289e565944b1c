/* pm_merge.c — ZBUF-EXC, PAIR and AAPC pixel merging (seed 003 §1, §3).
 *
 * Invariants: before PAIR/ZBUF-EXC stage i, held[p] contains only pixels
 * of scanlines whose owner agrees with p on address bits 0 .. i-1 (p's
 * current region); after the last stage, only scanlines p owns.  Merging
 * two scanline-ordered arrays uses an MSA-like index of width N (§2) that
 * is reset by walking the row's output, never by clearing N entries, so a
 * merge costs O(pixels + scanlines).
 */
#include "sim/workload/pixelmerge/pm_merge.h"
#include <string.h>

const char *const wl_pm_scheme_names[] = {
    "zbuf-exc",    "pair",    "aapc",           "binary_swap",
    "direct_send", "radix_k", "two_three_swap", NULL};

WlPmStep *wl_pm_step_new(guint n, gboolean exchange)
{
    WlPmStep *s = g_new0(WlPmStep, 1);
    s->exchange = exchange;
    s->msg = g_new0(WlPmMsg, n);
    s->n_msgs = n;
    for (guint p = 0; p < n; p++)
        s->msg[p].src = p;
    s->work = g_new0(WlPmWork, n);
    return s;
}

static void step_free(gpointer p)
{
    WlPmStep *s = p;
    g_free(s->msg);
    g_free(s->work);
    g_free(s);
}

/* The pixels of src in scanlines with take[y] set (all if take NULL). */
static WlPmWpa *extract_rows(const WlPmWpa *src, const guint8 *take)
{
    WlPmWpa *out = wl_pm_wpa_new(src->width, src->height);
    for (guint y = 0; y < src->height; y++) {
        if (take && !take[y])
            continue;
        const WlPmPixel *r = wl_pm_wpa_row(src, y);
        guint n = wl_pm_wpa_row_len(src, y);
        for (guint i = 0; i < n; i++)
            wl_pm_wpa_push(out, &r[i]);
    }
    wl_pm_wpa_finish(out);
    return out;
}

/* Puts one pixel into the row being built (msa: location -> index). */
static void merge_put(WlPmWpa *out, int32_t *msa, const WlPmPixel *p)
{
    int32_t at = msa[p->x];
    if (at < 0) {
        msa[p->x] = (int32_t)out->px->len;
        wl_pm_wpa_push(out, p);
        return;
    }
    WlPmPixel *held = &g_array_index(out->px, WlPmPixel, at);
    if (wl_pm_pixel_front(p, held))
        *held = *p;
}

static void merge_row(WlPmWpa *out, int32_t *msa, const WlPmWpa *w, guint y)
{
    const WlPmPixel *r = wl_pm_wpa_row(w, y);
    guint n = wl_pm_wpa_row_len(w, y);
    for (guint i = 0; i < n; i++)
        merge_put(out, msa, &r[i]);
}

/* Z-buffers a and b (same size) into a new array: a's pixels first, then
 * b's compared; one pixel per location in the result. */
static WlPmWpa *merge_arrays(const WlPmWpa *a, const WlPmWpa *b, int32_t *msa)
{
    WlPmWpa *out = wl_pm_wpa_new(a->width, a->height);
    for (guint y = 0; y < a->height; y++) {
        guint first = out->px->len;
        merge_row(out, msa, a, y);
        merge_row(out, msa, b, y);
        for (guint i = first; i < out->px->len; i++)
            msa[g_array_index(out->px, WlPmPixel, i).x] = -1;
    }
    wl_pm_wpa_finish(out);
    return out;
}

/* A full z-buffer: every location, empty ones with poly WL_PM_EMPTY. */
static WlPmWpa *expand_full(const WlPmWpa *w)
{
    WlPmFrame *f = wl_pm_frame_new(w->width, w->height);
    wl_pm_frame_put_wpa(f, w);
    WlPmWpa *out = wl_pm_wpa_new(w->width, w->height);
    for (gsize i = 0; i < (gsize)w->width * w->height; i++)
        wl_pm_wpa_push(out, &f->px[i]);
    wl_pm_wpa_finish(out);
    wl_pm_frame_free(f);
    return out;
}

typedef struct {
    const WlPmPartition *part;
    const WlPmFormat *fmt;
    gboolean full; /* ZBUF-EXC */
} PairCfg;

/* Marks p's send rows at stage i; returns how many there are. */
static guint pair_send_rows(const WlPmPartition *part, guint p, guint i,
                            guint8 *send, guint8 *keep)
{
    guint lower = (1u << i) - 1, bit = 1u << i, n = 0;
    for (guint y = 0; y < part->height; y++) {
        guint diff = part->owner[y] ^ p;
        gboolean mine = (diff & lower) == 0;
        send[y] = mine && (diff & bit);
        keep[y] = mine && !(diff & bit);
        n += send[y];
    }
    return n;
}

static void pair_account(WlPmStep *st, guint p, guint partner,
                         const WlPmWpa *out, const WlPmWpa *keep, guint rows,
                         const PairCfg *c)
{
    WlPmMsg *m = &st->msg[p];
    WlPmWork *w = &st->work[p];
    m->dst = partner;
    m->pixels = wl_pm_wpa_len(out);
    if (c->full) {
        m->bytes = m->pixels * c->fmt->bytes_per_location;
    } else {
        m->bytes = m->pixels * c->fmt->bytes_per_pixel +
                   (uint64_t)rows * c->fmt->bytes_per_scanline;
        w->pack = c->part->banded ? 0 : m->pixels;
        w->scatter = wl_pm_wpa_len(keep);
    }
}

static void pair_stage(WlPmMerge *m, WlPmWpa **held, guint i, const PairCfg *c,
                       int32_t *msa)
{
    guint n = m->n_procs, h = c->part->height;
    WlPmStep *st = wl_pm_step_new(n, TRUE);
    WlPmWpa **out = g_new0(WlPmWpa *, n), **keep = g_new0(WlPmWpa *, n);
    guint8 *send = g_new(guint8, h), *kept = g_new(guint8, h);
    for (guint p = 0; p < n; p++) {
        guint rows = pair_send_rows(c->part, p, i, send, kept);
        out[p] = extract_rows(held[p], send);
        keep[p] = extract_rows(held[p], kept);
        pair_account(st, p, p ^ (1u << i), out[p], keep[p], rows, c);
    }
    for (guint p = 0; p < n; p++) {
        const WlPmWpa *recv = out[p ^ (1u << i)];
        wl_pm_wpa_free(held[p]);
        held[p] = merge_arrays(keep[p], recv, msa);
        st->work[p].compare = wl_pm_wpa_len(recv);
        st->work[p].gather = c->full ? 0 : wl_pm_wpa_len(held[p]);
    }
    for (guint p = 0; p < n; p++) {
        wl_pm_wpa_free(out[p]);
        wl_pm_wpa_free(keep[p]);
    }
    g_ptr_array_add(m->steps, st);
    g_free(out);
    g_free(keep);
    g_free(send);
    g_free(kept);
}

static guint log2u(guint n)
{
    guint d = 0;
    while ((1u << d) < n)
        d++;
    return d;
}

static void run_pair(WlPmMerge *m, WlPmWpa *const *local, const PairCfg *c,
                     int32_t *msa)
{
    for (guint p = 0; p < m->n_procs; p++)
        m->held[p] =
            c->full ? expand_full(local[p]) : extract_rows(local[p], NULL);
    for (guint i = 0; i < log2u(m->n_procs); i++)
        pair_stage(m, m->held, i, c, msa);
}

/* Per (sender, owner): pixels the sender holds in the owner's rows. */
static uint64_t *aapc_counts(WlPmWpa *const *local, guint n,
                             const WlPmPartition *part)
{
    uint64_t *cnt = g_new0(uint64_t, (gsize)n * n);
    for (guint p = 0; p < n; p++)
        for (guint y = 0; y < part->height; y++)
            cnt[p * n + part->owner[y]] += wl_pm_wpa_row_len(local[p], y);
    return cnt;
}

static void aapc_messages(WlPmMerge *m, const uint64_t *cnt,
                          const WlPmPartition *part, const WlPmFormat *fmt)
{
    guint n = m->n_procs;
    guint *rows = g_new0(guint, n);
    for (guint y = 0; y < part->height; y++)
        rows[part->owner[y]]++;
    for (guint j = 1; j < n; j++) {
        WlPmStep *st = wl_pm_step_new(n, TRUE);
        for (guint p = 0; p < n; p++) {
            guint k = p ^ j;
            WlPmMsg *msg = &st->msg[p];
            msg->dst = k;
            msg->pixels = cnt[p * n + k];
            msg->bytes = msg->pixels * fmt->bytes_per_pixel +
                         (uint64_t)rows[k] * fmt->bytes_per_scanline;
            st->work[p].pack = part->banded ? 0 : msg->pixels;
        }
        g_ptr_array_add(m->steps, st);
    }
    g_free(rows);
}

/* The owner's z-buffering: its own pixels first, then each received
 * array in schedule order. */
static void aapc_zbuffer(WlPmMerge *m, WlPmWpa *const *local,
                         const uint64_t *cnt, const WlPmPartition *part,
                         int32_t *msa)
{
    guint n = m->n_procs;
    WlPmStep *st = wl_pm_step_new(n, FALSE);
    guint8 *mine = g_new(guint8, part->height);
    for (guint p = 0; p < n; p++) {
        for (guint y = 0; y < part->height; y++)
            mine[y] = part->owner[y] == p;
        m->held[p] = extract_rows(local[p], mine);
        for (guint j = 1; j < n; j++) {
            WlPmWpa *r = extract_rows(local[p ^ j], mine);
            WlPmWpa *t = merge_arrays(m->held[p], r, msa);
            wl_pm_wpa_free(m->held[p]);
            wl_pm_wpa_free(r);
            m->held[p] = t;
            st->work[p].compare += cnt[(p ^ j) * n + p];
        }
        st->work[p].scatter = cnt[p * n + p];
    }
    g_ptr_array_add(m->steps, st);
    g_free(mine);
}

static void run_aapc(WlPmMerge *m, WlPmWpa *const *local,
                     const WlPmPartition *part, const WlPmFormat *fmt,
                     int32_t *msa)
{
    uint64_t *cnt = aapc_counts(local, m->n_procs, part);
    aapc_messages(m, cnt, part, fmt);
    aapc_zbuffer(m, local, cnt, part, msa);
    g_free(cnt);
}

void wl_pm_merge_summarise(WlPmMerge *m)
{
    guint n = m->n_procs;
    for (guint s = 0; s < m->steps->len; s++) {
        const WlPmStep *st = g_ptr_array_index(m->steps, s);
        for (guint p = 0; p < n; p++)
            m->merge_ops[p] += st->work[p].scatter + st->work[p].compare;
        for (guint i = 0; st->exchange && i < st->n_msgs; i++) {
            m->total_bytes += st->msg[i].bytes;
            m->total_msgs++;
        }
    }
    m->concurrent_volume = wl_pm_concurrent_volume(m->steps, n);
    for (guint p = 0; p < n; p++)
        wl_pm_frame_put_wpa(m->image, m->held[p]);
}

WlPmMerge *wl_pm_merge_new(WlPmScheme scheme, guint n_procs, guint width,
                           guint height)
{
    WlPmMerge *m = g_new0(WlPmMerge, 1);
    m->scheme = scheme;
    m->n_procs = n_procs;
    m->steps = g_ptr_array_new_with_free_func(step_free);
    m->image = wl_pm_frame_new(width, height);
    m->held = g_new0(WlPmWpa *, n_procs);
    m->merge_ops = g_new0(uint64_t, n_procs);
    return m;
}

WlPmMerge *wl_pm_merge_run(WlPmScheme scheme, WlPmWpa *const *local,
                           guint n_procs, const WlPmPartition *part,
                           const WlPmFormat *fmt)
{
    g_assert(n_procs > 0 && (n_procs & (n_procs - 1)) == 0);
    g_assert(scheme == WL_PM_ZBUF_EXC || part->n_procs == n_procs);
    guint w = local[0]->width, h = local[0]->height;
    WlPmMerge *m = wl_pm_merge_new(scheme, n_procs, w, h);
    int32_t *msa = g_new(int32_t, w);
    memset(msa, 0xff, w * sizeof *msa); /* all -1 */
    WlPmPartition *strips = NULL;
    if (scheme == WL_PM_ZBUF_EXC)
        part = strips = wl_pm_partition_new(WL_PM_BAL_STRIPS, n_procs, NULL, h);
    PairCfg c = {part, fmt, scheme == WL_PM_ZBUF_EXC};
    if (scheme == WL_PM_AAPC)
        run_aapc(m, local, part, fmt, msa);
    else
        run_pair(m, local, &c, msa);
    wl_pm_merge_summarise(m);
    wl_pm_partition_free(strips);
    g_free(msa);
    return m;
}

void wl_pm_merge_free(WlPmMerge *m)
{
    if (!m)
        return;
    g_ptr_array_free(m->steps, TRUE);
    wl_pm_frame_free(m->image);
    for (guint p = 0; p < m->n_procs; p++)
        wl_pm_wpa_free(m->held[p]);
    g_free(m->held);
    g_free(m->merge_ops);
    g_free(m);
}

uint64_t wl_pm_concurrent_volume(const GPtrArray *steps, guint n_procs)
{
    (void)n_procs;
    uint64_t vol = 0;
    for (guint s = 0; s < steps->len; s++) {
        const WlPmStep *st = g_ptr_array_index(steps, s);
        if (!st->exchange)
            continue;
        uint64_t mx = 0;
        for (guint i = 0; i < st->n_msgs; i++)
            mx = MAX(mx, st->msg[i].bytes);
        vol += mx;
    }
    return vol;
}
