/* dp_render.c — the data-parallel renderer (dp_render.h).
 *
 * The machine computes every element of an array in lock step; here the
 * active elements are found cheaply instead of scanning masks: polygons
 * are ordered by scan-line count once (the ones alive in iteration i are
 * a prefix of that order) and a flush orders the buffered segments by
 * length (the ones alive in pixel iteration j are a prefix).  The costs
 * are charged for the whole arrays, masked elements included.
 * Invariants: buffered segments <= capacity, except when one scan line
 * alone brings more (the buffer then takes it whole, as a larger CM
 * Fortran buffer would); the z-buffer holds the maximum key of every
 * pixel sent to it so far.
 */
#include "sim/workload/dpscan/dp_render.h"
#include <math.h>
#include <string.h>

WlDpOps wl_dp_ops_defaults(void)
{
    return (WlDpOps){.transform = 35,
                     .shade = 21,
                     .cross = 12,
                     .swap = 6,
                     .pair = 6,
                     .pixel = 20,
                     .line = 16,
                     .clear = 2,
                     .extract = 2,
                     .edge = 6};
}

typedef struct {
    WlDpVm *vm;
    const WlDpPolys *p;
    const WlDpRenderOpts *o;
    WlDpImage *img;
    uint64_t n, cap, nbuf, screen;
    WlDpSpan *buf;
    uint64_t bufsz; /* entries allocated in buf */
    uint64_t *src, *dst, *val; /* one send's messages */
    uint64_t room;             /* entries of src, dst, val */
} Rd;

WlDpImage *wl_dp_image_new(int width, int height)
{
    g_assert(width > 0 && height > 0);
    WlDpImage *img = g_new0(WlDpImage, 1);
    img->width = width;
    img->height = height;
    img->zbuf = g_new0(uint64_t, (gsize)width * height);
    img->index = g_new0(uint8_t, (gsize)width * height);
    return img;
}

void wl_dp_image_free(WlDpImage *img)
{
    if (!img)
        return;
    g_free(img->zbuf);
    g_free(img->index);
    g_free(img);
}

void wl_dp_image_extract(WlDpImage *img)
{
    uint64_t n = (uint64_t)img->width * img->height;
    for (uint64_t k = 0; k < n; k++)
        img->index[k] = img->zbuf[k] ? wl_dp_key_index(img->zbuf[k]) : 0;
}

static void ensure_room(Rd *r, uint64_t need)
{
    if (need <= r->room)
        return;
    r->room = MAX(need, 2 * r->room);
    r->src = g_renew(uint64_t, r->src, r->room);
    r->dst = g_renew(uint64_t, r->dst, r->room);
    r->val = g_renew(uint64_t, r->val, r->room);
}

/* Adds message (src, x, y, key) unless the pixel is off the viewport. */
static void add_pixel(Rd *r, uint64_t *cnt, uint64_t src, int64_t x, int64_t y,
                      uint64_t key)
{
    if (x < 0 || y < 0 || x >= r->img->width || y >= r->img->height) {
        r->img->clipped++;
        return;
    }
    r->src[*cnt] = src;
    r->dst[*cnt] = (uint64_t)y * r->img->width + (uint64_t)x;
    r->val[*cnt] = key;
    (*cnt)++;
}

/* Send-with-max of the collected pixels into the z-buffer. */
static void send_pixels(Rd *r, uint64_t n_src, uint64_t cnt)
{
    WlDpSend s = {.phase = WL_DP_PH_ROUTER,
                  .n_src = n_src,
                  .n_dst = r->screen,
                  .lay = WL_DP_LAYOUT_SCREEN,
                  .src = r->src,
                  .dst = r->dst,
                  .val = r->val,
                  .count = cnt,
                  .dest = r->img->zbuf,
                  .words = 2,
                  .comb = WL_DP_COMBINE_MAX};
    wl_dp_send(r->vm, &s);
    r->img->pixels += cnt;
}

/* Indices 0..n-1 ordered by len[] descending (stable counting sort). */
static uint32_t *order_desc(const uint32_t *len, uint64_t n, uint32_t longest)
{
    uint64_t *first = g_new0(uint64_t, (gsize)longest + 2);
    for (uint64_t k = 0; k < n; k++)
        first[longest - len[k] + 1]++;
    for (uint32_t l = 1; l <= longest + 1; l++)
        first[l] += first[l - 1];
    uint32_t *ord = g_new(uint32_t, MAX(n, 1));
    for (uint64_t k = 0; k < n; k++)
        ord[first[longest - len[k]]++] = (uint32_t)k;
    g_free(first);
    return ord;
}

/* The pixel loop over the buffered segments, then an empty buffer. */
static void flush(Rd *r)
{
    uint64_t n = r->nbuf, nb = MAX(r->cap, n);
    uint32_t *len = g_new(uint32_t, MAX(n, 1));
    for (uint64_t k = 0; k < n; k++)
        len[k] = r->buf[k].len;
    uint32_t longest = wl_dp_reduce_max(r->vm, WL_DP_PH_PIXEL, nb, len, n);
    uint32_t *ord = order_desc(len, n, longest);
    uint64_t live = n;
    ensure_room(r, n);
    for (uint32_t j = 0; j < longest; j++) {
        while (live > 0 && len[ord[live - 1]] <= j)
            live--;
        wl_dp_ew(r->vm, WL_DP_PH_PIXEL, nb, live, r->o->ops.pixel);
        uint64_t cnt = 0;
        for (uint64_t q = 0; q < live; q++) {
            const WlDpSpan *s = &r->buf[ord[q]];
            add_pixel(r, &cnt, ord[q], (int64_t)s->x0 + j, s->y,
                      wl_dp_span_key(r->p, s, j));
        }
        send_pixels(r, nb, cnt);
        r->img->pixel_iters++;
    }
    r->img->max_len = MAX(r->img->max_len, longest);
    r->img->flushes++;
    r->nbuf = 0;
    g_free(ord);
    g_free(len);
}

/* Router send of `tot` new segments (7 words each) into the buffer. */
static void send_segments(Rd *r, const WlDpSpan *tmp, uint64_t tot)
{
    if (r->nbuf > 0 && r->nbuf + tot > r->cap)
        flush(r);
    if (r->nbuf + tot > r->bufsz) {
        r->bufsz = r->nbuf + tot;
        r->buf = g_renew(WlDpSpan, r->buf, r->bufsz);
    }
    ensure_room(r, tot);
    for (uint64_t k = 0; k < tot; k++) {
        r->src[k] = tmp[k].poly;
        r->dst[k] = r->nbuf + k;
        r->buf[r->nbuf + k] = tmp[k];
    }
    WlDpSend s = {.phase = WL_DP_PH_ROUTER,
                  .n_src = r->n,
                  .n_dst = MAX(r->cap, r->nbuf + tot),
                  .lay = WL_DP_LAYOUT_LINEAR,
                  .src = r->src,
                  .dst = r->dst,
                  .count = tot,
                  .words = 7,
                  .comb = WL_DP_COMBINE_OVERWRITE};
    wl_dp_send(r->vm, &s);
    r->nbuf += tot;
    r->img->segments += tot;
}

/* Statement cost of one scan line per polygon element. */
static uint32_t scan_ops(const Rd *r)
{
    uint32_t k = r->p->kmax;
    return k * r->o->ops.cross + k * (k - 1) / 2 * r->o->ops.swap +
           (k / 2) * r->o->ops.pair;
}

/* Scan line i of the `live` polygons ord[0..live). */
static void scan_line(Rd *r, const uint32_t *ord, uint64_t live,
                      const int32_t *y0, uint32_t i, uint32_t *cnt,
                      uint32_t *slot, WlDpSpan *tmp)
{
    wl_dp_ew(r->vm, WL_DP_PH_SCAN, r->n, live, scan_ops(r));
    uint64_t tot = 0;
    for (uint64_t q = 0; q < live; q++) {
        cnt[q] = wl_dp_poly_spans(r->p, ord[q], y0[ord[q]] + (int32_t)i,
                                  tmp + tot);
        tot += cnt[q];
    }
    uint64_t sum = wl_dp_scan_add(r->vm, WL_DP_PH_SCAN, r->n, cnt, slot, live);
    g_assert(sum == tot);
    send_segments(r, tmp, tot);
    r->img->scan_iters++;
}

static void scan_convert(Rd *r)
{
    uint64_t n = r->n;
    uint32_t *rows = g_new(uint32_t, MAX(n, 1));
    int32_t *y0 = g_new(int32_t, MAX(n, 1));
    for (uint64_t k = 0; k < n; k++)
        rows[k] = wl_dp_poly_rows(r->p, k, &y0[k]);
    wl_dp_ew(r->vm, WL_DP_PH_SCAN, n, r->p->n_ok, 2 * r->p->kmax + 4);
    uint32_t tallest = wl_dp_reduce_max(r->vm, WL_DP_PH_SCAN, n, rows, n);
    uint32_t *ord = order_desc(rows, n, tallest);
    uint64_t live = n;
    uint32_t *cnt = g_new(uint32_t, MAX(n, 1)), *slot = g_new(uint32_t, MAX(n, 1));
    WlDpSpan *tmp = g_new(WlDpSpan, MAX(n, 1) * (WL_DP_MAX_VERTS / 2));
    for (uint32_t i = 0; i < tallest; i++) {
        while (live > 0 && rows[ord[live - 1]] <= i)
            live--;
        scan_line(r, ord, live, y0, i, cnt, slot, tmp);
    }
    if (r->nbuf > 0)
        flush(r);
    r->img->max_rows = tallest;
    g_free(tmp);
    g_free(slot);
    g_free(cnt);
    g_free(ord);
    g_free(y0);
    g_free(rows);
}

/* Edges (or, for points, vertices) of every polygon, padded to kmax:
 * pixel counts per element of the n * kmax array. */
static uint32_t *edge_lengths(const Rd *r, uint64_t *active)
{
    const WlDpPolys *p = r->p;
    uint64_t ne = r->n * p->kmax;
    uint32_t *len = g_new0(uint32_t, MAX(ne, 1));
    *active = 0;
    for (uint64_t i = 0; i < r->n; i++)
        for (uint32_t e = 0; e < wl_dp_poly_len(p, i); e++) {
            uint32_t l = p->mode == WL_DP_MODE_POINTS
                             ? (p->ok[i] ? 1u : 0u)
                             : wl_dp_edge_pixels(p, i, e);
            len[i * p->kmax + e] = l;
            *active += l > 0;
        }
    return len;
}

/* Lines and points: pixel k of every edge, a send-with-max each. */
static void draw_lines(Rd *r)
{
    uint64_t ne = r->n * r->p->kmax, active;
    uint32_t *len = edge_lengths(r, &active);
    wl_dp_ew(r->vm, WL_DP_PH_SCAN, ne, active, r->o->ops.line);
    uint32_t longest = wl_dp_reduce_max(r->vm, WL_DP_PH_PIXEL, ne, len, ne);
    uint32_t *ord = order_desc(len, ne, longest);
    uint64_t live = ne;
    ensure_room(r, ne);
    for (uint32_t k = 0; k < longest; k++) {
        while (live > 0 && len[ord[live - 1]] <= k)
            live--;
        wl_dp_ew(r->vm, WL_DP_PH_PIXEL, ne, live, r->o->ops.line);
        uint64_t cnt = 0;
        for (uint64_t q = 0; q < live; q++) {
            uint64_t i = ord[q] / r->p->kmax, key;
            uint32_t e = ord[q] % r->p->kmax;
            int64_t x, y;
            if (r->p->mode == WL_DP_MODE_POINTS)
                wl_dp_point_pixel(r->p, i, e, &x, &y, &key);
            else
                wl_dp_edge_pixel(r->p, i, e, k, &x, &y, &key);
            add_pixel(r, &cnt, ord[q], x, y, key);
        }
        send_pixels(r, ne, cnt);
        r->img->pixel_iters++;
    }
    r->img->max_len = longest;
    g_free(ord);
    g_free(len);
}

/* Hidden-line pass: NEWS moves find the border pixels (dp_poly.h). */
static void hidden_lines(Rd *r)
{
    uint64_t *nb = g_new(uint64_t, r->screen);
    uint8_t *edge = g_new0(uint8_t, r->screen);
    const int dx[4] = {0, 0, 1, -1}, dy[4] = {1, -1, 0, 0};
    const uint64_t *z = r->img->zbuf;
    for (int d = 0; d < 4; d++) {
        wl_dp_news(r->vm, WL_DP_PH_DISPLAY, z, nb, dx[d], dy[d], 0);
        wl_dp_ew(r->vm, WL_DP_PH_DISPLAY, r->screen, r->screen,
                 r->o->ops.edge);
        for (uint64_t k = 0; k < r->screen; k++)
            edge[k] |= z[k] && (nb[k] == 0 ||
                                wl_dp_key_id(nb[k]) != wl_dp_key_id(z[k]));
    }
    for (uint64_t k = 0; k < r->screen; k++)
        r->img->index[k] = edge[k] ? wl_dp_key_index(z[k]) : 0;
    g_free(edge);
    g_free(nb);
}

/* Steps 1-3: the per-vertex arithmetic of dp_poly.c, charged. */
static void transform_and_shade(Rd *r)
{
    const WlDpPolys *p = r->p;
    WlDpMode m = p->mode;
    uint32_t per = m == WL_DP_MODE_GOURAUD || m == WL_DP_MODE_CONTOUR
                       ? p->kmax * r->o->ops.shade
                       : r->o->ops.shade;
    wl_dp_ew(r->vm, WL_DP_PH_TRANSFORM, r->n, r->n, p->kmax * r->o->ops.transform);
    if (m != WL_DP_MODE_WIREFRAME && m != WL_DP_MODE_POINTS &&
        m != WL_DP_MODE_LINES)
        wl_dp_ew(r->vm, WL_DP_PH_TRANSFORM, r->n, r->n, per);
}

WlDpImage *wl_dp_render(WlDpVm *vm, const WlDpPolys *p, int width, int height,
                        const WlDpRenderOpts *o)
{
    g_assert(o->buffer_factor > 0.0);
    g_assert(wl_dp_vm_screen_elems(vm) == (uint64_t)width * height);
    Rd r = {.vm = vm, .p = p, .o = o, .n = p->n};
    r.img = wl_dp_image_new(width, height);
    r.screen = (uint64_t)width * height;
    r.cap = MAX((uint64_t)ceil(o->buffer_factor * (double)p->n), 1);
    r.bufsz = r.cap;
    r.buf = g_new(WlDpSpan, r.bufsz);
    wl_dp_ew(vm, WL_DP_PH_DISPLAY, r.screen, r.screen, o->ops.clear);
    transform_and_shade(&r);
    if (wl_dp_mode_fills(p->mode))
        scan_convert(&r);
    else
        draw_lines(&r);
    wl_dp_ew(vm, WL_DP_PH_DISPLAY, r.screen, r.screen, o->ops.extract);
    if (p->mode == WL_DP_MODE_HIDDEN_LINE)
        hidden_lines(&r);
    else
        wl_dp_image_extract(r.img);
    g_free(r.buf);
    g_free(r.src);
    g_free(r.dst);
    g_free(r.val);
    return r.img;
}
