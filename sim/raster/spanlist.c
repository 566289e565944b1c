/* spanlist.c — scanline span lists sorted by x_min (seed 003, §2).
 *
 * Spans accumulate unsorted in `raw`; sorting moves them, grouped by row,
 * into `rows` with a counting sort (offsets in `start`, H + 1 entries)
 * and then sorts each row.  Invariant: `sorted` is TRUE exactly when
 * `rows`/`start` describe every span in `raw`.  Memory O(S + H).
 */
#include "sim/raster/spanlist.h"
#include <stdlib.h>
#include <string.h>

struct RastSpanList {
    int width, height;
    GArray *raw;  /* RastSpan, insertion order */
    GArray *rows; /* RastSpan, grouped by row, each row sorted */
    size_t *start;
    gboolean sorted;
};

RastSpanList *rast_spanlist_new(int width, int height)
{
    g_assert(width > 0 && height > 0);
    RastSpanList *sl = g_new0(RastSpanList, 1);
    sl->width = width;
    sl->height = height;
    sl->raw = g_array_new(FALSE, FALSE, sizeof(RastSpan));
    sl->rows = g_array_new(FALSE, FALSE, sizeof(RastSpan));
    sl->start = g_new0(size_t, (size_t)height + 1);
    sl->sorted = TRUE;
    return sl;
}

void rast_spanlist_free(RastSpanList *sl)
{
    if (!sl)
        return;
    g_array_free(sl->raw, TRUE);
    g_array_free(sl->rows, TRUE);
    g_free(sl->start);
    g_free(sl);
}

void rast_spanlist_clear(RastSpanList *sl)
{
    g_array_set_size(sl->raw, 0);
    g_array_set_size(sl->rows, 0);
    memset(sl->start, 0, sizeof(size_t) * ((size_t)sl->height + 1));
    sl->sorted = TRUE;
}

int rast_spanlist_width(const RastSpanList *sl)
{
    return sl->width;
}

int rast_spanlist_height(const RastSpanList *sl)
{
    return sl->height;
}

void rast_spanlist_add(RastSpanList *sl, const RastSpan *s)
{
    g_assert(s->y >= 0 && s->y < sl->height);
    g_assert(s->x0 >= 0 && s->x0 < s->x1 && s->x1 <= sl->width);
    g_array_append_val(sl->raw, *s);
    sl->sorted = FALSE;
}

static void sink_fn(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    rast_spanlist_add(ctx, s);
}

RastSpanSink rast_spanlist_sink(RastSpanList *sl)
{
    return (RastSpanSink){sink_fn, sl};
}

static int cmp_span(const void *pa, const void *pb)
{
    const RastSpan *a = pa, *b = pb;
    if (a->x0 != b->x0)
        return a->x0 < b->x0 ? -1 : 1;
    if (a->prim != b->prim)
        return a->prim < b->prim ? -1 : 1;
    if (a->x1 != b->x1)
        return a->x1 < b->x1 ? -1 : 1;
    if (a->z0 != b->z0)
        return a->z0 < b->z0 ? -1 : 1;
    return 0;
}

/* Rows are mostly short: insertion sort below 16 spans, qsort above. */
static void sort_row(RastSpan *r, size_t k)
{
    if (k > 16) {
        qsort(r, k, sizeof(RastSpan), cmp_span);
        return;
    }
    for (size_t i = 1; i < k; i++) {
        RastSpan t = r[i];
        size_t j = i;
        for (; j > 0 && cmp_span(&r[j - 1], &t) > 0; j--)
            r[j] = r[j - 1];
        r[j] = t;
    }
}

void rast_spanlist_sort(RastSpanList *sl)
{
    if (sl->sorted)
        return;
    size_t n = sl->raw->len, h = (size_t)sl->height;
    const RastSpan *raw = (const RastSpan *)sl->raw->data;
    memset(sl->start, 0, sizeof(size_t) * (h + 1));
    for (size_t i = 0; i < n; i++)
        sl->start[raw[i].y + 1]++;
    for (size_t y = 0; y < h; y++)
        sl->start[y + 1] += sl->start[y];
    g_array_set_size(sl->rows, n);
    RastSpan *rows = (RastSpan *)sl->rows->data;
    size_t *next = g_memdup2(sl->start, sizeof(size_t) * h);
    for (size_t i = 0; i < n; i++)
        rows[next[raw[i].y]++] = raw[i];
    g_free(next);
    for (size_t y = 0; y < h; y++) {
        size_t k = sl->start[y + 1] - sl->start[y];
        if (k > 1)
            sort_row(rows + sl->start[y], k);
    }
    sl->sorted = TRUE;
}

gboolean rast_spanlist_sorted(const RastSpanList *sl)
{
    return sl->sorted;
}

const RastSpan *rast_spanlist_row(const RastSpanList *sl, int y, size_t *n)
{
    g_assert(sl->sorted);
    g_assert(y >= 0 && y < sl->height);
    *n = sl->start[y + 1] - sl->start[y];
    return (const RastSpan *)sl->rows->data + sl->start[y];
}

size_t rast_spanlist_len(const RastSpanList *sl)
{
    return sl->raw->len;
}
