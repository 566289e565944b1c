/* sf_render.c — a sort-first processor's region (sf_frame.h, the
 * `render` step): the chunk instances overlapping its region drawn
 * through sim/raster with the frame's camera, spans clipped to the
 * region and z-buffered pixel by pixel into the frame's z-buffer, or,
 * when no image is wanted and setup `pre` is given, the same counts
 * from the frame rasterised once (prerender.h).  Also the serial render
 * a frame is checked against.  Cost: O(polygons of the region's
 * instances + pixels inside the region).
 */
#include "sim/workload/sortfirst/sf_frame_internal.h"

typedef struct {
    RastZBuffer *zb;
    WlSfRect r;
    uint64_t spans, pixels;
} RegionSink;

/* Z-buffers the part of a span inside the region with
 * rast_zbuffer_span_part(), so the pixels equal the serial ones. */
static void region_span(void *ctx, const RastSpan *s, RastCounters *c)
{
    RegionSink *k = ctx;
    if (s->y < k->r.y0 || s->y >= k->r.y1)
        return;
    int x0 = MAX(s->x0, k->r.x0), x1 = MIN(s->x1, k->r.x1);
    if (x0 >= x1)
        return;
    k->spans++;
    k->pixels += (uint64_t)(x1 - x0);
    rast_zbuffer_span_part(k->zb, s, x0, x1, c);
}

RastView wl_sf_frame_view(const Scene *scene, const WlSfSetup *s, guint frame)
{
    SceneCamera cam = scene_camera_at(scene, frame);
    RastView v = rast_view_for_camera(&cam, s->resolution, s->resolution);
    v.cull_back = s->cull_back;
    return v;
}

void wl_sf_render_serial(const Scene *scene, const WlSfDb *db,
                         const WlSfSetup *s, guint frame, RastZBuffer *zb)
{
    RastView v = wl_sf_frame_view(scene, s, frame);
    RastCounters c = {0};
    rast_zbuffer_clear(zb);
    rast_draw_mesh(&v, db->flat, mat4_identity(), (SceneColor){1, 1, 1}, 0,
                   NULL, rast_zbuffer_sink(zb), &c);
}

/* Counts from the frame rendered once (setup `pre`) when no image is
 * wanted: the same spans and pixels, no z-buffer (prerender.h). */
gboolean wl_sf_prerendered(const WlSfRun *r)
{
    return r->s.pre && !r->s.check_image && !r->hook;
}

/* The region's counts from the frame rendered once, instance by
 * instance (no subset gathered). */
static void count_region(WlSfRun *r, WlSfProc *pr)
{
    const RastPrerender *pre = rast_prerender_set_get(r->s.pre, (guint)r->frame,
                                                      &r->view, r->db->flat);
    WlSfRect q = wl_sf_region_rect(&r->regions, pr->p);
    RastRect rect = {q.x0, q.y0, q.x1, q.y1};
    pr->polys = pr->spans = pr->pixels = 0;
    for (guint k = 0; k < r->render->len; k++) {
        guint i = g_array_index(r->render, guint, k);
        guint n = wl_sf_chunk(r->db, wl_sf_inst(r->db, i)->chunk)->polys;
        rast_prerender_count(pre, r->db->flat, wl_sf_inst_polys(r->db, i), n,
                             rect, &pr->rc, &pr->spans, &pr->pixels);
        pr->polys += n;
    }
}

void wl_sf_render_region(WlSfRun *r, WlSfProc *pr)
{
    if (wl_sf_prerendered(r)) {
        count_region(r, pr);
        return;
    }
    g_array_set_size(r->subset, 0);
    for (guint k = 0; k < r->render->len; k++) {
        guint i = g_array_index(r->render, guint, k);
        const uint32_t *polys = wl_sf_inst_polys(r->db, i);
        guint n = wl_sf_chunk(r->db, wl_sf_inst(r->db, i)->chunk)->polys;
        g_array_append_vals(r->subset, polys, n);
    }
    RegionSink k = {r->zb, wl_sf_region_rect(&r->regions, pr->p), 0, 0};
    RastSpanSink sink = {region_span, &k};
    pr->polys = r->subset->len;
    if (r->subset->len)
        rast_draw_mesh(&r->view, r->db->flat, mat4_identity(),
                       (SceneColor){1, 1, 1}, 0,
                       &(RastSubset){(const uint32_t *)(void *)r->subset->data,
                                     r->subset->len},
                       sink, &pr->rc);
    pr->spans = k.spans;
    pr->pixels = k.pixels;
}
