/* dp_geom.c — screen-space work of a data-parallel frame (seed 004).
 *
 * A span sink collects the spans of the current polygon (the pipeline
 * emits all triangles of one polygon before the next, with the
 * polygon's index as primitive id); when the id changes, the spans are
 * sorted by row and merged into one segment per row (rows without a
 * pixel inside a polygon, possible for slivers, become segments of
 * length 0: the paper's loop still visits them).  Every span also goes
 * into a per-row difference array of coverage counts, resolved once at
 * the end into covered pixels and the deepest stack.  With `inclusive`
 * (the renderer's own convention, see dp_geom.h) each segment gains its
 * right end pixel and each polygon its bottom scan line.
 *
 * Complexity: O(spans log spans-per-polygon + width * height).
 */
#include "sim/workload/dpscan/dp_geom.h"
#include <string.h>

typedef struct {
    int32_t y, x0, x1;
} DpSpan;

typedef struct {
    WlDpGeom *g;
    uint32_t cur;  /* primitive id being collected */
    GArray *spans; /* DpSpan of the current primitive */
    int32_t *cov;  /* (width + 1) * height difference counts */
} DpCollect;

static int span_cmp(const void *a, const void *b)
{
    const DpSpan *s = a, *t = b;
    if (s->y != t->y)
        return s->y < t->y ? -1 : 1;
    return (s->x0 > t->x0) - (s->x0 < t->x0);
}

static void push_row(WlDpGeom *g, uint32_t len, int32_t x0)
{
    uint32_t x = (uint32_t)MAX(x0, 0);
    len += g->inclusive;
    g->seg_pixels += len;
    g_array_append_val(g->seg_len, len);
    g_array_append_val(g->seg_x0, x);
    if (len > g->max_len)
        g->max_len = len;
}

/* Turns the collected spans of one polygon into its row segments. */
static void flush_poly(DpCollect *c)
{
    WlDpGeom *g = c->g;
    GArray *sp = c->spans;
    if (sp->len == 0)
        return;
    qsort(sp->data, sp->len, sizeof(DpSpan), span_cmp);
    const DpSpan *s = (const DpSpan *)sp->data;
    int32_t y = s[0].y, lo = s[0].x0, hi = s[0].x1;
    for (guint i = 1; i < sp->len; i++) {
        if (s[i].y == y) {
            lo = MIN(lo, s[i].x0);
            hi = MAX(hi, s[i].x1);
            continue;
        }
        push_row(g, (uint32_t)(hi - lo), lo);
        for (int32_t gap = y + 1; gap < s[i].y; gap++)
            push_row(g, 0, lo);
        y = s[i].y, lo = s[i].x0, hi = s[i].x1;
    }
    push_row(g, (uint32_t)(hi - lo), lo);
    if (g->inclusive)
        push_row(g, (uint32_t)(hi - lo), lo);
    uint32_t top = (uint32_t)MAX(s[0].y, 0);
    g_array_append_val(g->poly_y0, top);
    uint32_t end = g->seg_len->len;
    g_array_append_val(g->seg_start, end);
    uint32_t rows =
        end - g_array_index(g->seg_start, uint32_t, g->seg_start->len - 2);
    if (rows > g->max_rows)
        g->max_rows = rows;
    g->n_visible++;
    g_array_set_size(sp, 0);
}

static void collect_span(void *ctx, const RastSpan *s, RastCounters *rc)
{
    (void)rc;
    DpCollect *c = ctx;
    if (s->x1 <= s->x0)
        return;
    if (s->prim != c->cur) {
        g_assert(c->cur == RAST_NO_PRIM || s->prim > c->cur);
        flush_poly(c);
        c->cur = s->prim;
    }
    DpSpan d = {s->y, s->x0, s->x1};
    g_array_append_val(c->spans, d);
    int32_t *row = c->cov + (size_t)s->y * (size_t)(c->g->width + 1);
    row[s->x0]++;
    row[s->x1]--;
    c->g->pixels += (uint64_t)(s->x1 - s->x0);
}

/* Resolves the difference counts into covered pixels and max depth. */
static void resolve_coverage(WlDpGeom *g, const int32_t *cov)
{
    for (int y = 0; y < g->height; y++) {
        const int32_t *row = cov + (size_t)y * (size_t)(g->width + 1);
        int32_t depth = 0;
        for (int x = 0; x < g->width; x++) {
            depth += row[x];
            g_assert(depth >= 0);
            if (depth > 0)
                g->covered++;
            if ((uint32_t)depth > g->max_depth)
                g->max_depth = (uint32_t)depth;
        }
    }
}

static WlDpGeom *geom_alloc(int width, int height, gboolean inclusive)
{
    WlDpGeom *g = g_new0(WlDpGeom, 1);
    g->inclusive = inclusive ? 1 : 0;
    g->width = width;
    g->height = height;
    g->seg_start = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g->seg_len = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g->seg_x0 = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    g->poly_y0 = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    uint32_t zero = 0;
    g_array_append_val(g->seg_start, zero);
    return g;
}

WlDpGeom *wl_dp_geom_new(const Scene *scene, double frame, int width,
                         int height, gboolean inclusive)
{
    g_assert(width > 0 && height > 0);
    g_assert(width <= RAST_MAX_SIDE && height <= RAST_MAX_SIDE);
    WlDpGeom *g = geom_alloc(width, height, inclusive);
    DpCollect c = {.g = g, .cur = RAST_NO_PRIM};
    c.spans = g_array_new(FALSE, FALSE, sizeof(DpSpan));
    c.cov = g_new0(int32_t, (size_t)(width + 1) * (size_t)height);
    SceneCamera cam = scene_camera_at(scene, frame);
    RastView v = rast_view_for_camera(&cam, width, height);
    v.cull_back = FALSE;
    v.lighting = FALSE;
    RastSpanSink sink = {collect_span, &c};
    rast_draw_scene(&v, scene, sink, &g->counters);
    flush_poly(&c);
    resolve_coverage(g, c.cov);
    g->n_polys = scene_n_polys(scene);
    g_array_free(c.spans, TRUE);
    g_free(c.cov);
    return g;
}

void wl_dp_geom_free(WlDpGeom *g)
{
    if (!g)
        return;
    g_array_free(g->seg_start, TRUE);
    g_array_free(g->seg_len, TRUE);
    if (g->seg_x0)
        g_array_free(g->seg_x0, TRUE);
    if (g->poly_y0)
        g_array_free(g->poly_y0, TRUE);
    g_free(g);
}
