/* pm_pixels.c — Winning Pixel Arrays and reference frames (seed 003 §2).
 *
 * Invariant of WlPmWpa: row_start[0 .. next_row] are fixed and
 * nondecreasing; pushes go to scanline >= next_row - 1.  After
 * wl_pm_wpa_finish() every row_start is fixed and row_start[height] ==
 * px->len.  Push is amortised O(1) plus O(rows skipped).
 */
#include "sim/workload/pixelmerge/pm_pixels.h"
#include <string.h>

WlPmWpa *wl_pm_wpa_new(guint width, guint height)
{
    g_assert(width > 0 && height > 0 && width <= 65535 && height <= 65535);
    WlPmWpa *w = g_new0(WlPmWpa, 1);
    w->width = width;
    w->height = height;
    w->px = g_array_new(FALSE, FALSE, sizeof(WlPmPixel));
    w->row_start = g_new0(uint32_t, height + 1);
    w->next_row = 1; /* row_start[0] == 0 is fixed */
    return w;
}

void wl_pm_wpa_free(WlPmWpa *w)
{
    if (!w)
        return;
    g_array_free(w->px, TRUE);
    if (w->rgba)
        g_array_free(w->rgba, TRUE);
    g_free(w->row_start);
    g_free(w);
}

/* Fixes the starts of rows next_row .. y (all begin at the current end). */
static void close_rows_through(WlPmWpa *w, guint y)
{
    while (w->next_row <= y) {
        w->row_start[w->next_row] = w->px->len;
        w->next_row++;
    }
}

void wl_pm_wpa_push(WlPmWpa *w, const WlPmPixel *p)
{
    g_assert(p->x < w->width && p->y < w->height);
    g_assert(p->y + 1u >= w->next_row);
    g_assert(!w->rgba);
    close_rows_through(w, p->y);
    g_array_append_vals(w->px, p, 1);
}

void wl_pm_wpa_push_rgba(WlPmWpa *w, const WlPmPixel *p, const double *rgba)
{
    if (!w->rgba) {
        g_assert(w->px->len == 0);
        w->rgba = g_array_new(FALSE, FALSE, sizeof(double));
    }
    g_assert(p->x < w->width && p->y < w->height);
    g_assert(p->y + 1u >= w->next_row);
    close_rows_through(w, p->y);
    g_array_append_vals(w->px, p, 1);
    g_array_append_vals(w->rgba, rgba, 4);
}

void wl_pm_wpa_finish(WlPmWpa *w)
{
    close_rows_through(w, w->height);
}

void wl_pm_wpa_add_row_counts(const WlPmWpa *w, uint64_t *counts)
{
    g_assert(w->next_row == w->height + 1);
    for (guint y = 0; y < w->height; y++)
        counts[y] += wl_pm_wpa_row_len(w, y);
}

WlPmFrame *wl_pm_frame_new(guint width, guint height)
{
    WlPmFrame *f = g_new0(WlPmFrame, 1);
    f->width = width;
    f->height = height;
    f->px = g_new(WlPmPixel, (gsize)width * height);
    for (gsize i = 0; i < (gsize)width * height; i++) {
        f->px[i] = (WlPmPixel){.x = (uint16_t)(i % width),
                               .y = (uint16_t)(i / width),
                               .z = 0.0f,
                               .poly = WL_PM_EMPTY,
                               .color = 0};
    }
    return f;
}

void wl_pm_frame_free(WlPmFrame *f)
{
    if (!f)
        return;
    g_free(f->px);
    g_free(f);
}

gboolean wl_pm_frame_put(WlPmFrame *f, const WlPmPixel *p)
{
    g_assert(p->x < f->width && p->y < f->height);
    WlPmPixel *d = &f->px[(gsize)p->y * f->width + p->x];
    if (!wl_pm_pixel_front(p, d))
        return FALSE;
    *d = *p;
    return TRUE;
}

void wl_pm_frame_put_wpa(WlPmFrame *f, const WlPmWpa *w)
{
    for (guint i = 0; i < w->px->len; i++)
        wl_pm_frame_put(f, &g_array_index(w->px, WlPmPixel, i));
}

uint64_t wl_pm_frame_count(const WlPmFrame *f)
{
    uint64_t n = 0;
    for (gsize i = 0; i < (gsize)f->width * f->height; i++)
        n += f->px[i].poly != WL_PM_EMPTY;
    return n;
}

static gboolean pixel_same(const WlPmPixel *a, const WlPmPixel *b)
{
    if (a->poly != b->poly)
        return FALSE;
    if (a->poly == WL_PM_EMPTY)
        return TRUE;
    return a->z == b->z && a->color == b->color && a->x == b->x && a->y == b->y;
}

int64_t wl_pm_frame_diff(const WlPmFrame *a, const WlPmFrame *b)
{
    g_assert(a->width == b->width && a->height == b->height);
    for (gsize i = 0; i < (gsize)a->width * a->height; i++)
        if (!pixel_same(&a->px[i], &b->px[i]))
            return (int64_t)i;
    return -1;
}

WlPmWpa *wl_pm_frame_to_wpa(const WlPmFrame *f)
{
    WlPmWpa *w = wl_pm_wpa_new(f->width, f->height);
    for (gsize i = 0; i < (gsize)f->width * f->height; i++)
        if (f->px[i].poly != WL_PM_EMPTY)
            wl_pm_wpa_push(w, &f->px[i]);
    wl_pm_wpa_finish(w);
    return w;
}
