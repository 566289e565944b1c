/* sf_regions.c — screen regions and bounding-box bucket sort
 * (sf_regions.h; seed 000 §4.1). */
#include "sim/workload/sortfirst/sf_regions.h"
#include <math.h>
#include <string.h>

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

/* Corner k of b under m (axis j at its max when bit j of k is set),
 * from t: the products m[i][j] x bound, each formed once per box (24,
 * not 96), summed in mat4_apply_point()'s order, so every corner is bit
 * for bit what mat4_apply_point() gives. */
static inline Vec4 corner(const double t[4][3][2], const Mat4 *m, int k)
{
    int a = k & 1, e = (k >> 1) & 1, f = (k >> 2) & 1;
    return (Vec4){t[0][0][a] + t[0][1][e] + t[0][2][f] + m->m[0][3],
                  t[1][0][a] + t[1][1][e] + t[1][2][f] + m->m[1][3],
                  t[2][0][a] + t[2][1][e] + t[2][2][f] + m->m[2][3],
                  t[3][0][a] + t[3][1][e] + t[3][2][f] + m->m[3][3]};
}

static void products(SceneBox b, const Mat4 *m, double t[4][3][2])
{
    for (int i = 0; i < 4; i++) {
        t[i][0][0] = m->m[i][0] * b.min.x;
        t[i][0][1] = m->m[i][0] * b.max.x;
        t[i][1][0] = m->m[i][1] * b.min.y;
        t[i][1][1] = m->m[i][1] * b.max.y;
        t[i][2][0] = m->m[i][2] * b.min.z;
        t[i][2][1] = m->m[i][2] * b.max.z;
    }
}

gboolean wl_sf_box_screen(const WlSfRegions *r, SceneBox b, Mat4 m,
                          double *x0, double *y0, double *x1, double *y1)
{
    unsigned all = 0x3f;
    gboolean behind = FALSE;
    WlSfScreen s = {INFINITY, INFINITY, -INFINITY, -INFINITY, FALSE};
    double t[4][3][2];
    products(b, &m, t);
    for (int k = 0; k < 8; k++)
        all &= wl_sf_screen_point(r, corner(t, &m, k), &s, &behind);
    if (behind) {
        s.x0 = s.y0 = -INFINITY;
        s.x1 = s.y1 = INFINITY;
    }
    *x0 = s.x0;
    *y0 = s.y0;
    *x1 = s.x1;
    *y1 = s.y1;
    return !all;
}

WlSfScreen wl_sf_screen_of(const WlSfRegions *r, SceneBox box,
                           Mat4 clip_from_obj)
{
    WlSfScreen s = {0};
    s.on = !scene_box_is_empty(box) &&
           wl_sf_box_screen(r, box, clip_from_obj, &s.x0, &s.y0, &s.x1,
                            &s.y1);
    return s;
}

uint64_t wl_sf_box_regions(const WlSfRegions *r, SceneBox box,
                           Mat4 clip_from_obj)
{
    WlSfScreen s = wl_sf_screen_of(r, box, clip_from_obj);
    return wl_sf_screen_regions(r, &s);
}

uint64_t wl_sf_screen_regions(const WlSfRegions *r, const WlSfScreen *s)
{
    if (!s->on)
        return 0;
    double x0 = s->x0 - 1, y0 = s->y0 - 1, x1 = s->x1 + 1, y1 = s->y1 + 1;
    uint64_t mask = 0;
    for (guint p = 0; p < r->procs; p++) {
        WlSfRect q = wl_sf_region_rect(r, p);
        if (q.x1 - 0.5 >= x0 && q.x0 + 0.5 <= x1 && q.y1 - 0.5 >= y0 &&
            q.y0 + 0.5 <= y1)
            mask |= wl_sf_bit(p);
    }
    return mask;
}

/* ---- screen rectangles kept by frame ------------------------------------ */

typedef struct {
    Mat4 view_proj;
    guint n;
    WlSfScreen *v;
} ScreenFrame;

struct WlSfScreenSet {
    GArray *by_key; /* ScreenFrame; v NULL: not made */
};

static void screen_frame_clear(gpointer p)
{
    ScreenFrame *f = p;
    g_free(f->v);
    f->v = NULL;
}

WlSfScreenSet *wl_sf_screen_set_new(void)
{
    WlSfScreenSet *s = g_new0(WlSfScreenSet, 1);
    s->by_key = g_array_new(FALSE, TRUE, sizeof(ScreenFrame));
    g_array_set_clear_func(s->by_key, screen_frame_clear);
    return s;
}

void wl_sf_screen_set_clear(WlSfScreenSet *s)
{
    g_array_set_size(s->by_key, 0);
}

void wl_sf_screen_set_free(WlSfScreenSet *s)
{
    if (!s)
        return;
    g_array_unref(s->by_key);
    g_free(s);
}

WlSfScreen *wl_sf_screen_set_get(WlSfScreenSet *s, guint key, guint n,
                                 Mat4 view_proj, gboolean *fresh)
{
    if (key >= s->by_key->len)
        g_array_set_size(s->by_key, key + 1);
    ScreenFrame *f = &g_array_index(s->by_key, ScreenFrame, key);
    *fresh = f->v == NULL;
    if (*fresh) {
        f->view_proj = view_proj;
        f->n = n;
        f->v = g_new(WlSfScreen, MAX(n, 1));
    }
    g_assert(f->n == n &&
             memcmp(&f->view_proj, &view_proj, sizeof view_proj) == 0);
    return f->v;
}
