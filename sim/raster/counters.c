/* counters.c — operation counters of the rendering pipeline.
 *
 * Field-wise addition and a one-line text form for logs and benchmarks.
 * O(1).  See counters.h for what each counter means (seed 003 names).
 */
#include "sim/raster/counters.h"

void rast_counters_add(RastCounters *dst, const RastCounters *src)
{
    dst->verts += src->verts;
    dst->prims += src->prims;
    dst->culled += src->culled;
    dst->clipped += src->clipped;
    dst->rejected += src->rejected;
    dst->degenerate += src->degenerate;
    dst->spans += src->spans;
    dst->pixels += src->pixels;
    dst->winners += src->winners;
    dst->zcompares += src->zcompares;
    dst->zwrites += src->zwrites;
}

char *rast_counters_format(const RastCounters *c)
{
    return g_strdup_printf(
        "verts=%" G_GUINT64_FORMAT " prims=%" G_GUINT64_FORMAT
        " culled=%" G_GUINT64_FORMAT " clipped=%" G_GUINT64_FORMAT
        " rejected=%" G_GUINT64_FORMAT " degenerate=%" G_GUINT64_FORMAT
        " spans=%" G_GUINT64_FORMAT " TPG=%" G_GUINT64_FORMAT
        " TPF=%" G_GUINT64_FORMAT " zcmp=%" G_GUINT64_FORMAT
        " zwrites=%" G_GUINT64_FORMAT,
        c->verts, c->prims, c->culled, c->clipped, c->rejected, c->degenerate,
        c->spans, c->pixels, c->winners, c->zcompares, c->zwrites);
}
