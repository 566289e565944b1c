/* sf_regions.c — screen regions and bounding-box bucket sort
 * (sf_regions.h; seed 000 §4.1). */
#include "sim/workload/sortfirst/sf_regions.h"
#include <math.h>

void wl_sf_regions_init(WlSfRegions *r, guint procs, int width, int height)
{
    g_assert(procs >= 1 && procs <= WL_SF_MAX_PROCS);
    guint cols = procs;
    for (guint c = 1; c <= procs; c++)
        if (procs % c == 0 && (double)c >= sqrt((double)procs)) {
            cols = c;
            break;
        }
    r->procs = procs;
    r->cols = cols;
    r->rows = procs / cols;
    r->width = width;
    r->height = height;
    g_assert(width >= (int)cols && height >= (int)r->rows);
    for (guint p = 0; p < procs; p++) {
        guint row = p / cols, col = p % cols;
        WlSfRect *q = &r->rect[p];
        q->x0 = (int)((int64_t)col * width / cols);
        q->x1 = (int)((int64_t)(col + 1) * width / cols);
        q->y0 = (int)((int64_t)row * height / r->rows);
        q->y1 = (int)((int64_t)(row + 1) * height / r->rows);
    }
}

WlSfRect wl_sf_region_rect(const WlSfRegions *r, guint p)
{
    g_assert(p < r->procs);
    return r->rect[p];
}

/* Outcodes of one clip-space point: bit k for the k-th plane it is out. */
static unsigned outcode(Vec4 c)
{
    return (c.x < -c.w) | (c.x > c.w) << 1 | (c.y < -c.w) << 2 |
           (c.y > c.w) << 3 | (c.z < -c.w) << 4 | (c.z > c.w) << 5;
}

gboolean wl_sf_box_screen(const WlSfRegions *r, SceneBox b, Mat4 m,
                          double *x0, double *y0, double *x1, double *y1)
{
    unsigned all = 0x3f;
    gboolean behind = FALSE;
    *x0 = *y0 = INFINITY;
    *x1 = *y1 = -INFINITY;
    for (int k = 0; k < 8; k++) {
        Vec3 p = vec3(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y,
                      k & 4 ? b.max.z : b.min.z);
        Vec4 c = mat4_apply_point(m, p);
        all &= outcode(c);
        if (c.w <= 0) {
            behind = TRUE;
            continue;
        }
        double sx = (c.x / c.w + 1) * 0.5 * r->width;
        double sy = (1 - c.y / c.w) * 0.5 * r->height;
        *x0 = MIN(*x0, sx);
        *x1 = MAX(*x1, sx);
        *y0 = MIN(*y0, sy);
        *y1 = MAX(*y1, sy);
    }
    if (all)
        return FALSE;
    if (behind) {
        *x0 = *y0 = -INFINITY;
        *x1 = *y1 = INFINITY;
    }
    return TRUE;
}

uint64_t wl_sf_box_regions(const WlSfRegions *r, SceneBox box,
                           Mat4 clip_from_obj)
{
    double x0, y0, x1, y1;
    if (scene_box_is_empty(box) ||
        !wl_sf_box_screen(r, box, clip_from_obj, &x0, &y0, &x1, &y1))
        return 0;
    x0 -= 1;
    y0 -= 1;
    x1 += 1;
    y1 += 1;
    uint64_t mask = 0;
    for (guint p = 0; p < r->procs; p++) {
        WlSfRect q = wl_sf_region_rect(r, p);
        if (q.x1 - 0.5 >= x0 && q.x0 + 0.5 <= x1 && q.y1 - 0.5 >= y0 &&
            q.y0 + 0.5 <= y1)
            mask |= wl_sf_bit(p);
    }
    return mask;
}
