/* scanzbuf.c — the modified scanline z-buffer (seed 003, §2).
 *
 * WPA indices in the MSA are 1-based, so the all-zero MSA set up once
 * per frame means "nothing"; the range of the first scanline is 1.
 * Invariants while processing row y: every WPA entry at index >= range-1
 * belongs to row y; `covered` is the largest x_max of the spans of row y
 * done so far; because spans come in x_min order, the columns
 * [x_min, covered) of the next span all have current-row entries and
 * the columns >= covered have none.  So the range test of the paper is
 * needed only as an assertion: the split decides everything.  Stores
 * start at max(x_min, covered), so a row's WPA entries are in x order.
 * Per generated pixel: O(1); no per-scanline clearing.
 */
#include "sim/raster/scanzbuf.h"
#include <string.h>

struct RastActive {
    int width, height;
    GArray *wpa;     /* RastActivePixel */
    uint32_t *msa;   /* width entries, 1-based WPA indices */
    size_t *offsets; /* height + 1 */
};

RastActive *rast_active_new(int width, int height)
{
    g_assert(width > 0 && height > 0);
    RastActive *a = g_new0(RastActive, 1);
    a->width = width;
    a->height = height;
    a->wpa = g_array_new(FALSE, FALSE, sizeof(RastActivePixel));
    a->msa = g_new0(uint32_t, (size_t)width);
    a->offsets = g_new0(size_t, (size_t)height + 1);
    return a;
}

void rast_active_free(RastActive *a)
{
    if (!a)
        return;
    g_array_free(a->wpa, TRUE);
    g_free(a->msa);
    g_free(a->offsets);
    g_free(a);
}

int rast_active_width(const RastActive *a)
{
    return a->width;
}

int rast_active_height(const RastActive *a)
{
    return a->height;
}

static void append(RastActive *a, const RastSpan *s, int x, double z,
                   RastCounters *c)
{
    RastActivePixel p = {x, s->prim, z, rast_span_rgba(s, x)};
    g_array_append_val(a->wpa, p);
    g_assert(a->wpa->len < UINT32_MAX);
    a->msa[x] = a->wpa->len;
    c->zwrites++;
}

/* The first segment: columns that earlier spans of this row own.  The
 * span that set `covered` starts at or before this one (x_min order), so
 * it covers the whole segment: every MSA entry here is current. */
static void segment_test(RastActive *a, const RastSpan *s, int from, int to,
                         uint32_t range, RastCounters *c)
{
    for (int x = from; x < to; x++) {
        double z = rast_span_z(s, x);
        uint32_t idx = a->msa[x];
        g_assert(idx >= range);
        RastActivePixel *w = &g_array_index(a->wpa, RastActivePixel, idx - 1);
        c->zcompares++;
        if (rast_depth_wins(z, s->prim, w->z, w->prim)) {
            w->z = z;
            w->prim = s->prim;
            w->rgba = rast_span_rgba(s, x);
            c->zwrites++;
        }
    }
}

/* The second segment: columns no earlier span of this row reached. */
static void segment_store(RastActive *a, const RastSpan *s, int from, int to,
                          RastCounters *c)
{
    for (int x = from; x < to; x++)
        append(a, s, x, rast_span_z(s, x), c);
}

static void scan_row(RastActive *a, const RastSpan *row, size_t n,
                     RastCounters *c)
{
    uint32_t range = a->wpa->len + 1;
    int covered = 0;
    for (size_t i = 0; i < n; i++) {
        const RastSpan *s = &row[i];
        int split = s->x1 < covered ? s->x1 : covered;
        if (split > s->x0)
            segment_test(a, s, s->x0, split, range, c);
        else
            split = s->x0;
        segment_store(a, s, split, s->x1, c);
        if (s->x1 > covered)
            covered = s->x1;
    }
}

void rast_scanline_zbuffer(RastActive *a, const RastSpanList *sl,
                           RastCounters *c)
{
    g_assert(rast_spanlist_width(sl) == a->width);
    g_assert(rast_spanlist_height(sl) == a->height);
    g_array_set_size(a->wpa, 0);
    memset(a->msa, 0, sizeof(uint32_t) * (size_t)a->width);
    a->offsets[0] = 0;
    for (int y = 0; y < a->height; y++) {
        size_t n;
        const RastSpan *row = rast_spanlist_row(sl, y, &n);
        scan_row(a, row, n, c);
        a->offsets[y + 1] = a->wpa->len;
    }
    c->winners += a->wpa->len;
}

const RastActivePixel *rast_active_pixels(const RastActive *a, size_t *n)
{
    *n = a->wpa->len;
    return (const RastActivePixel *)a->wpa->data;
}

const RastActivePixel *rast_active_row(const RastActive *a, int y, size_t *n)
{
    g_assert(y >= 0 && y < a->height);
    *n = a->offsets[y + 1] - a->offsets[y];
    return (const RastActivePixel *)a->wpa->data + a->offsets[y];
}

const size_t *rast_active_offsets(const RastActive *a)
{
    return a->offsets;
}

size_t rast_active_count(const RastActive *a)
{
    return a->wpa->len;
}
