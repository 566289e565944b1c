/* ag_tile.c — tiled frame buffer, cropping span sink, bucketing
 * (ag_tile.h).  O(pixels) per draw, O(W H) per clear.
 */
#include "sim/workload/argus/ag_tile.h"
#include <math.h>
#include <string.h>

const char *const wl_ag_pixel_names[] = {"opaque", "blend", NULL};

AgFrame *wl_ag_frame_new(int width, int height, int tile, AgPixelMode mode,
                         float alpha, RastColor bg)
{
    g_assert(width > 0 && height > 0 && tile > 0);
    AgFrame *f = g_new0(AgFrame, 1);
    f->width = width;
    f->height = height;
    f->tile = tile;
    f->tiles_x = (guint)((width + tile - 1) / tile);
    f->tiles_y = (guint)((height + tile - 1) / tile);
    f->mode = mode;
    f->alpha = alpha;
    f->bg = bg;
    gsize n = (gsize)width * height;
    f->rgb = g_new(float, 3 * n);
    f->depth = g_new(double, n);
    f->prim = g_new(uint32_t, n);
    f->front = g_new(float, 3 * n);
    wl_ag_frame_clear(f);
    memcpy(f->front, f->rgb, 3 * n * sizeof(float));
    return f;
}

void wl_ag_frame_free(AgFrame *f)
{
    if (!f)
        return;
    g_free(f->rgb);
    g_free(f->depth);
    g_free(f->prim);
    g_free(f->front);
    g_free(f);
}

static void clear_pixel(AgFrame *f, gsize i)
{
    f->rgb[3 * i] = f->bg.r;
    f->rgb[3 * i + 1] = f->bg.g;
    f->rgb[3 * i + 2] = f->bg.b;
    f->depth[i] = INFINITY;
    f->prim[i] = RAST_NO_PRIM;
}

void wl_ag_frame_clear(AgFrame *f)
{
    gsize n = (gsize)f->width * f->height;
    for (gsize i = 0; i < n; i++)
        clear_pixel(f, i);
}

/* The pixel rectangle [x0, x1) x [y0, y1) of tile t (the whole frame for
 * G_MAXUINT). */
static void tile_rect(const AgFrame *f, guint t, int r[4])
{
    r[0] = r[1] = 0;
    r[2] = f->width;
    r[3] = f->height;
    if (t == G_MAXUINT)
        return;
    r[0] = (int)(t % f->tiles_x) * f->tile;
    r[1] = (int)(t / f->tiles_x) * f->tile;
    r[2] = MIN(r[0] + f->tile, f->width);
    r[3] = MIN(r[1] + f->tile, f->height);
}

uint64_t wl_ag_frame_clear_tile(AgFrame *f, guint t)
{
    int r[4];
    tile_rect(f, t, r);
    for (int y = r[1]; y < r[3]; y++)
        for (int x = r[0]; x < r[2]; x++)
            clear_pixel(f, (gsize)y * f->width + x);
    return (uint64_t)(r[2] - r[0]) * (uint64_t)(r[3] - r[1]);
}

void wl_ag_frame_present_tile(AgFrame *f, guint t)
{
    int r[4];
    tile_rect(f, t, r);
    for (int y = r[1]; y < r[3]; y++) {
        gsize i = 3 * ((gsize)y * f->width + r[0]);
        memcpy(&f->front[i], &f->rgb[i],
               3 * sizeof(float) * (gsize)(r[2] - r[0]));
    }
}

typedef struct {
    AgFrame *f;
    int x0, y0, x1, y1; /* the tile's pixels */
    uint64_t pixels;
} Crop;

static void put_pixel(AgFrame *f, const RastSpan *s, int x, gsize i)
{
    float t = (float)(x - s->x0);
    float c[3];
    for (int k = 0; k < 3; k++) {
        c[k] = s->c0[k] + s->dcdx[k] * t;
        c[k] = c[k] < 0 ? 0 : (c[k] > 1 ? 1 : c[k]);
    }
    if (f->mode == WL_AG_OPAQUE) {
        double z = rast_span_z(s, x);
        if (!rast_depth_wins(z, s->prim, f->depth[i], f->prim[i]))
            return;
        f->depth[i] = z;
        f->prim[i] = s->prim;
        memcpy(&f->rgb[3 * i], c, sizeof c);
        return;
    }
    for (int k = 0; k < 3; k++)
        f->rgb[3 * i + k] =
            f->alpha * c[k] + (1 - f->alpha) * f->rgb[3 * i + k];
}

static void crop_span(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    Crop *k = ctx;
    if (s->y < k->y0 || s->y >= k->y1)
        return;
    int a = MAX(s->x0, k->x0), b = MIN(s->x1, k->x1);
    for (int x = a; x < b; x++)
        put_pixel(k->f, s, x, (gsize)s->y * k->f->width + x);
    if (b > a)
        k->pixels += (uint64_t)(b - a);
}

uint64_t wl_ag_draw(AgFrame *f, guint t, const RastView *v, const SceneMesh *m,
                    const uint32_t *tris, guint n)
{
    int r[4];
    tile_rect(f, t, r);
    Crop k = {f, r[0], r[1], r[2], r[3], 0};
    RastCounters c = {0};
    RastSpanSink sink = {crop_span, &k};
    if (n)
        rast_draw_mesh(v, m, mat4_identity(), scene_color(1, 1, 1), 0,
                       &(RastSubset){tris, n}, sink, &c);
    return k.pixels;
}

guint wl_ag_bucket(const AgFrame *f, const Mat4 *vp, const SceneMesh *m,
                   guint i, void (*fn)(guint tile, void *ctx), void *ctx)
{
    const uint32_t *idx = scene_mesh_poly(m, i);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    gboolean behind = FALSE;
    for (int k = 0; k < 3; k++) {
        Vec4 p = mat4_apply_point(*vp, scene_mesh_vertex(m, idx[k]));
        if (p.w <= 1e-9) {
            behind = TRUE;
            break;
        }
        double sx = (p.x / p.w + 1) * 0.5 * f->width;
        double sy = (1 - p.y / p.w) * 0.5 * f->height;
        lo[0] = MIN(lo[0], sx), hi[0] = MAX(hi[0], sx);
        lo[1] = MIN(lo[1], sy), hi[1] = MAX(hi[1], sy);
    }
    int tx0 = 0, ty0 = 0, tx1 = (int)f->tiles_x - 1, ty1 = (int)f->tiles_y - 1;
    if (!behind) {
        if (hi[0] < 0 || hi[1] < 0 || lo[0] >= f->width || lo[1] >= f->height)
            return 0;
        tx0 = MAX(0, (int)floor(lo[0]) / f->tile);
        ty0 = MAX(0, (int)floor(lo[1]) / f->tile);
        tx1 = MIN(tx1, (int)floor(hi[0]) / f->tile);
        ty1 = MIN(ty1, (int)floor(hi[1]) / f->tile);
    }
    guint n = 0;
    for (int y = ty0; y <= ty1; y++)
        for (int x = tx0; x <= tx1; x++, n++)
            fn((guint)(y * (int)f->tiles_x + x), ctx);
    return n;
}

static RastImage *image_of(const AgFrame *f, const float *rgb)
{
    RastImage *img = rast_image_new(f->width, f->height);
    for (int y = 0; y < f->height; y++)
        for (int x = 0; x < f->width; x++) {
            const float *c = &rgb[3 * ((gsize)y * f->width + x)];
            uint32_t rgba = rast_channel(c[0]) | rast_channel(c[1]) << 8 |
                            rast_channel(c[2]) << 16 | 0xff000000u;
            rast_image_set(img, x, y, rgba);
        }
    return img;
}

RastImage *wl_ag_frame_image(const AgFrame *f)
{
    return image_of(f, f->rgb);
}

RastImage *wl_ag_frame_front_image(const AgFrame *f)
{
    return image_of(f, f->front);
}
