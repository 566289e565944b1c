/* pm_foot.c — block-decomposition footprints as compositing images at
 * every rung (pm_foot.h).  All three rungs read the ellipse's rows from
 * wl_pm_foot_span, so the pixel and runs rungs hold the same pixels.
 */
#include "sim/workload/pixelmerge/pm_foot.h"
#include <math.h>

/* The largest divisor of n that is at most lim (at least 1). */
static guint divisor_below(guint n, double lim)
{
    guint best = 1;
    for (guint d = 1; d <= n && d <= lim + 1e-9; d++)
        if (n % d == 0)
            best = d;
    return best;
}

/* Screen coordinate of unit-cube coordinate u seen with depth shift t of
 * depth z, over `size` pixels. */
static double screen(double u, double z, double t, guint size)
{
    return ((u + t * z) / (1.0 + t) * 0.9 + 0.05) * size;
}

void wl_pm_foot_box(guint p, guint n, guint width, guint height, WlPmCover *r)
{
    guint bz = divisor_below(n, cbrt((double)n));
    guint by = divisor_below(n / bz, sqrt((double)(n / bz)));
    guint bx = n / bz / by;
    guint i = p % bx, j = p / bx % by, k = p / bx / by;
    double x0 = screen((double)i / bx, (double)k / bz, 0.35, width);
    double x1 = screen((double)(i + 1) / bx, (double)(k + 1) / bz, 0.35, width);
    double y0 = screen((double)j / by, (double)k / bz, 0.25, height);
    double y1 =
        screen((double)(j + 1) / by, (double)(k + 1) / bz, 0.25, height);
    r->x0 = (guint)floor(x0), r->x1 = MAX(r->x0, (guint)ceil(x1) - 1);
    r->y0 = (guint)floor(y0), r->y1 = MAX(r->y0, (guint)ceil(y1) - 1);
    r->x1 = MIN(r->x1, width - 1), r->y1 = MIN(r->y1, height - 1);
    r->active = 0;
}

gboolean wl_pm_foot_span(const WlPmCover *r, guint y, guint *x0, guint *x1)
{
    if (y < r->y0 || y > r->y1)
        return FALSE;
    double rx = (r->x1 - r->x0 + 1) / 2.0, ry = (r->y1 - r->y0 + 1) / 2.0;
    double cx = r->x0 + rx, dy = (y + 0.5 - (r->y0 + ry)) / ry;
    double h = 1.0 - dy * dy;
    if (h < 0)
        return FALSE;
    h = rx * sqrt(h);
    double a = ceil(cx - h - 0.5), b = floor(cx + h - 0.5);
    a = MAX(a, (double)r->x0), b = MIN(b, (double)r->x1);
    if (a > b)
        return FALSE;
    *x0 = (guint)a, *x1 = (guint)b;
    return TRUE;
}

WlPmWpa *wl_pm_foot_pixels(guint p, guint n, guint width, guint height)
{
    WlPmCover r;
    wl_pm_foot_box(p, n, width, height, &r);
    guint bxy = n / divisor_below(n, cbrt((double)n));
    WlPmWpa *w = wl_pm_wpa_new(width, height);
    for (guint y = r.y0, a, b; y <= r.y1; y++) {
        if (!wl_pm_foot_span(&r, y, &a, &b))
            continue;
        for (guint x = a; x <= b; x++) {
            WlPmPixel px = {(uint16_t)x, (uint16_t)y, (double)(p / bxy), p,
                            0x102030u * (p % 7 + 1) & 0xffffffu};
            wl_pm_wpa_push(w, &px);
        }
    }
    wl_pm_wpa_finish(w);
    return w;
}

WlPmRungImage *wl_pm_foot_image(WlPmRung rung, guint p, guint n, guint width,
                                guint height)
{
    WlPmCover r;
    wl_pm_foot_box(p, n, width, height, &r);
    WlPmRungImage *im = wl_pm_rung_image_new(rung, width, height);
    if (rung == WL_PM_RUNG_COUNTS) {
        r.active = G_PI / 4 * (r.x1 - r.x0 + 1) * (double)(r.y1 - r.y0 + 1);
        wl_pm_rung_add_rect(im, &r);
        return im;
    }
    for (guint y = r.y0, a, b; y <= r.y1; y++)
        if (wl_pm_foot_span(&r, y, &a, &b))
            wl_pm_rung_add_span(im, y, a, b);
    return im;
}
