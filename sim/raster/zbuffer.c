/* zbuffer.c — the full z-buffer (see zbuffer.h).
 *
 * Invariant: prim[i] == RAST_NO_PRIM exactly when depth[i] == +inf and
 * rgba[i] == 0.  Per span pixel: one depth comparison, at most one write.
 */
#include "sim/raster/zbuffer.h"
#include <math.h>

RastZBuffer *rast_zbuffer_new(int width, int height)
{
    g_assert(width > 0 && height > 0);
    RastZBuffer *zb = g_new0(RastZBuffer, 1);
    size_t n = (size_t)width * (size_t)height;
    zb->width = width;
    zb->height = height;
    zb->depth = g_new(double, n);
    zb->prim = g_new(uint32_t, n);
    zb->rgba = g_new(uint32_t, n);
    rast_zbuffer_clear(zb);
    return zb;
}

void rast_zbuffer_free(RastZBuffer *zb)
{
    if (!zb)
        return;
    g_free(zb->depth);
    g_free(zb->prim);
    g_free(zb->rgba);
    g_free(zb);
}

void rast_zbuffer_clear(RastZBuffer *zb)
{
    size_t n = (size_t)zb->width * (size_t)zb->height;
    for (size_t i = 0; i < n; i++) {
        zb->depth[i] = INFINITY;
        zb->prim[i] = RAST_NO_PRIM;
        zb->rgba[i] = 0;
    }
}

void rast_zbuffer_span(RastZBuffer *zb, const RastSpan *s, RastCounters *c)
{
    rast_zbuffer_span_part(zb, s, s->x0, s->x1, c);
}

void rast_zbuffer_span_part(RastZBuffer *zb, const RastSpan *s, int x0,
                            int x1, RastCounters *c)
{
    g_assert(s->y >= 0 && s->y < zb->height);
    g_assert(x0 >= 0 && x1 <= zb->width);
    size_t row = (size_t)s->y * (size_t)zb->width;
    for (int x = x0; x < x1; x++) {
        size_t i = row + (size_t)x;
        double z = rast_span_z(s, x);
        c->zcompares++;
        if (rast_depth_wins(z, s->prim, zb->depth[i], zb->prim[i])) {
            zb->depth[i] = z;
            zb->prim[i] = s->prim;
            zb->rgba[i] = rast_span_rgba(s, x);
            c->zwrites++;
        }
    }
}

static void sink_fn(void *ctx, const RastSpan *s, RastCounters *c)
{
    rast_zbuffer_span(ctx, s, c);
}

RastSpanSink rast_zbuffer_sink(RastZBuffer *zb)
{
    return (RastSpanSink){sink_fn, zb};
}

void rast_zbuffer_spans(RastZBuffer *zb, const RastSpanList *sl,
                        RastCounters *c)
{
    g_assert(rast_spanlist_width(sl) == zb->width);
    g_assert(rast_spanlist_height(sl) == zb->height);
    for (int y = 0; y < zb->height; y++) {
        size_t n;
        const RastSpan *row = rast_spanlist_row(sl, y, &n);
        for (size_t i = 0; i < n; i++)
            rast_zbuffer_span(zb, &row[i], c);
    }
}

uint64_t rast_zbuffer_covered(const RastZBuffer *zb)
{
    size_t n = (size_t)zb->width * (size_t)zb->height;
    uint64_t k = 0;
    for (size_t i = 0; i < n; i++)
        k += zb->prim[i] != RAST_NO_PRIM;
    return k;
}

void rast_zbuffer_merge(RastZBuffer *dst, const RastZBuffer *src,
                        RastCounters *c)
{
    g_assert(dst->width == src->width && dst->height == src->height);
    size_t n = (size_t)dst->width * (size_t)dst->height;
    for (size_t i = 0; i < n; i++) {
        if (src->prim[i] == RAST_NO_PRIM)
            continue;
        c->zcompares++;
        if (rast_depth_wins(src->depth[i], src->prim[i], dst->depth[i],
                            dst->prim[i])) {
            dst->depth[i] = src->depth[i];
            dst->prim[i] = src->prim[i];
            dst->rgba[i] = src->rgba[i];
            c->zwrites++;
        }
    }
}
