/* dp_serial.c — the serial reference renderer (dp_serial.h).
 *
 * Written independently of dp_render.c's loops (no buffer, no sort by
 * height or length, no router): only the per-polygon pixel rule of
 * dp_poly.h is shared.  O(pixels) plus set-up per polygon row.
 */
#include "sim/workload/dpscan/dp_serial.h"

static void plot(WlDpImage *img, int64_t x, int64_t y, uint64_t key)
{
    if (x < 0 || y < 0 || x >= img->width || y >= img->height)
        return;
    uint64_t *z = &img->zbuf[y * img->width + x];
    if (key > *z)
        *z = key;
    img->pixels++;
}

static void fill_polygon(WlDpImage *img, const WlDpPolys *p, uint64_t i)
{
    int32_t y0;
    uint32_t rows = wl_dp_poly_rows(p, i, &y0);
    WlDpSpan sp[WL_DP_MAX_VERTS / 2];
    for (uint32_t r = 0; r < rows; r++) {
        guint n = wl_dp_poly_spans(p, i, y0 + (int32_t)r, sp);
        for (guint k = 0; k < n; k++)
            for (uint32_t j = 0; j < sp[k].len; j++)
                plot(img, (int64_t)sp[k].x0 + j, sp[k].y,
                     wl_dp_span_key(p, &sp[k], j));
    }
}

static void line_polygon(WlDpImage *img, const WlDpPolys *p, uint64_t i)
{
    for (uint32_t e = 0; e < wl_dp_poly_len(p, i); e++) {
        int64_t x, y;
        uint64_t key;
        if (p->mode == WL_DP_MODE_POINTS) {
            if (p->ok[i]) {
                wl_dp_point_pixel(p, i, e, &x, &y, &key);
                plot(img, x, y, key);
            }
            continue;
        }
        uint32_t n = wl_dp_edge_pixels(p, i, e);
        for (uint32_t k = 0; k < n; k++) {
            wl_dp_edge_pixel(p, i, e, k, &x, &y, &key);
            plot(img, x, y, key);
        }
    }
}

static uint64_t at(const WlDpImage *img, int64_t x, int64_t y)
{
    if (x < 0 || y < 0 || x >= img->width || y >= img->height)
        return 0;
    return img->zbuf[y * img->width + x];
}

static void hidden_lines(WlDpImage *img)
{
    for (int64_t y = 0; y < img->height; y++)
        for (int64_t x = 0; x < img->width; x++) {
            uint64_t nb[4] = {at(img, x, y - 1), at(img, x, y + 1),
                              at(img, x - 1, y), at(img, x + 1, y)};
            img->index[y * img->width + x] =
                wl_dp_edge_index(at(img, x, y), nb);
        }
}

WlDpImage *wl_dp_serial_render(const WlDpPolys *p, int width, int height)
{
    WlDpImage *img = wl_dp_image_new(width, height);
    for (uint64_t i = 0; i < p->n; i++) {
        if (wl_dp_mode_fills(p->mode))
            fill_polygon(img, p, i);
        else
            line_polygon(img, p, i);
    }
    if (p->mode == WL_DP_MODE_HIDDEN_LINE)
        hidden_lines(img);
    else
        wl_dp_image_extract(img);
    return img;
}
