/* pm_pixels.h — active (local foremost) pixels and reference frames for
 * the active pixel merging workload (Kurç, Aykanat, Özgüç, seed 003).
 *
 * A WlPmWpa is a processor's Winning Pixel Array (seed 003 §2): its local
 * foremost pixels stored consecutively in scanline order, so that the
 * pixels of any band of scanlines form one contiguous run (no message
 * fragmentation).  `row_start[y] .. row_start[y + 1]` indexes scanline y.
 *
 * Depth order: a pixel a is in front of b when (a.z, a.poly) <
 * (b.z, b.poly) lexicographically.  The polygon id breaks depth ties, so
 * the merged image does not depend on how polygons were partitioned and
 * equals the serial render pixel for pixel (a serial z-buffer that keeps
 * the first of equal depths, polygons in id order, obeys the same rule).
 *
 * A WlPmFrame is a plain N x N z-buffer of pixels (empty locations have
 * poly == WL_PM_EMPTY), used as the merge reference and the final image.
 * All operations are O(pixels touched); frames are O(N^2).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_PIXELS_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_PIXELS_H

#include <glib.h>
#include <stdint.h>

#define WL_PM_EMPTY UINT32_MAX

typedef struct {
    uint16_t x, y;
    double z;       /* depth: smaller is nearer */
    uint32_t poly;  /* global polygon id (tie-break); WL_PM_EMPTY: none */
    uint32_t color; /* packed 0xRRGGBB */
} WlPmPixel;

/* TRUE when a is in front of b (an empty pixel is behind everything). */
static inline gboolean wl_pm_pixel_front(const WlPmPixel *a, const WlPmPixel *b)
{
    if (a->poly == WL_PM_EMPTY)
        return FALSE;
    if (b->poly == WL_PM_EMPTY)
        return TRUE;
    return a->z < b->z || (a->z == b->z && a->poly < b->poly);
}

typedef struct {
    guint width, height;
    GArray *px;          /* WlPmPixel, scanline order */
    uint32_t *row_start; /* height + 1 offsets into px */
    guint next_row;      /* first row whose start is not yet fixed */
    GArray *rgba; /* NULL, or per pixel its premultiplied r, g, b, a (4
                   * doubles): the over operator's value in place of the
                   * colour at the compose opacity (wl_pm_wpa_push_rgba) */
} WlPmWpa;

/* Returns a new empty array for a width x height screen; free with
 * wl_pm_wpa_free(). */
WlPmWpa *wl_pm_wpa_new(guint width, guint height);
void wl_pm_wpa_free(WlPmWpa *w);
/* Appends a pixel; scanlines must come in nondecreasing y (asserted). */
void wl_pm_wpa_push(WlPmWpa *w, const WlPmPixel *p);
/* Appends a pixel with its own premultiplied colour rgba[4] (an array
 * takes either pushes or these, from its first pixel on; asserted). */
void wl_pm_wpa_push_rgba(WlPmWpa *w, const WlPmPixel *p, const double *rgba);
/* Closes the array after the last push (fixes the remaining rows). */
void wl_pm_wpa_finish(WlPmWpa *w);
static inline guint wl_pm_wpa_len(const WlPmWpa *w)
{
    return w->px->len;
}
static inline const WlPmPixel *wl_pm_wpa_row(const WlPmWpa *w, guint y)
{
    return &g_array_index(w->px, WlPmPixel, w->row_start[y]);
}
static inline guint wl_pm_wpa_row_len(const WlPmWpa *w, guint y)
{
    return w->row_start[y + 1] - w->row_start[y];
}
/* Adds this array's pixel count per scanline into counts[height]. */
void wl_pm_wpa_add_row_counts(const WlPmWpa *w, uint64_t *counts);

typedef struct {
    guint width, height;
    WlPmPixel *px; /* width * height, row-major */
} WlPmFrame;

/* Returns a new all-empty frame; free with wl_pm_frame_free(). */
WlPmFrame *wl_pm_frame_new(guint width, guint height);
void wl_pm_frame_free(WlPmFrame *f);
/* Z-buffers p into the frame; returns TRUE if it became the visible one. */
gboolean wl_pm_frame_put(WlPmFrame *f, const WlPmPixel *p);
/* Z-buffers every pixel of w. */
void wl_pm_frame_put_wpa(WlPmFrame *f, const WlPmWpa *w);
/* Number of non-empty locations. */
uint64_t wl_pm_frame_count(const WlPmFrame *f);
/* Index of the first location where a and b differ (poly, z or colour);
 * -1 when identical.  Frames must have the same size. */
int64_t wl_pm_frame_diff(const WlPmFrame *a, const WlPmFrame *b);
/* The frame's non-empty locations as an active pixel array. */
WlPmWpa *wl_pm_frame_to_wpa(const WlPmFrame *f);

#endif
