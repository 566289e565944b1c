/* prerender.c — a mesh rasterised once for a view (prerender.h).
 *
 * Invariant: the spans of polygon i are spans[first[i] .. first[i + 1]),
 * in the order the scan converter emitted them; a polygon drawn as
 * several fan triangles keeps all their spans.  Spans are stored as
 * 16-bit coordinates (RAST_MAX_SIDE fits).  Counting a subset is one pass
 * over its polygons' spans.
 */
#include "sim/raster/prerender.h"
#include <string.h>

G_STATIC_ASSERT(RAST_MAX_SIDE <= G_MAXINT16);

typedef struct {
    int16_t y, x0, x1;
} PreSpan;

struct RastPrerender {
    RastView view;
    guint n_polys;
    uint32_t *first; /* n_polys + 1 span offsets */
    GArray *spans;   /* PreSpan */
};

typedef struct {
    RastPrerender *p;
    guint next; /* polygons whose offsets are set */
} Builder;

/* Spans arrive polygon by polygon (ids = polygon indices, ascending);
 * polygons that made no span get empty ranges. */
static void keep_span(void *ctx, const RastSpan *s, RastCounters *c)
{
    (void)c;
    Builder *b = ctx;
    g_assert(s->prim < b->p->n_polys && s->prim + 1 >= b->next);
    for (; b->next <= s->prim; b->next++)
        b->p->first[b->next] = b->p->spans->len;
    PreSpan k = {(int16_t)s->y, (int16_t)s->x0, (int16_t)s->x1};
    g_array_append_val(b->p->spans, k);
}

RastPrerender *rast_prerender_new(const RastView *v, const SceneMesh *m)
{
    RastPrerender *p = g_new0(RastPrerender, 1);
    p->view = *v;
    p->n_polys = scene_mesh_n_polys(m);
    p->first = g_new(uint32_t, p->n_polys + 1);
    p->spans = g_array_new(FALSE, FALSE, sizeof(PreSpan));
    Builder b = {p, 0};
    RastCounters c = {0};
    rast_draw_mesh(v, m, mat4_identity(), (SceneColor){1, 1, 1}, 0, NULL,
                   (RastSpanSink){keep_span, &b}, &c);
    g_assert(c.spans == p->spans->len && c.spans <= G_MAXUINT32);
    for (; b.next <= p->n_polys; b.next++)
        p->first[b.next] = p->spans->len;
    return p;
}

void rast_prerender_free(RastPrerender *p)
{
    if (!p)
        return;
    g_free(p->first);
    g_array_unref(p->spans);
    g_free(p);
}

guint64 rast_prerender_n_spans(const RastPrerender *p)
{
    return p->spans->len;
}

/* What draw_poly() counts before scanning: an n-gon of up to
 * RAST_POLY_MAX vertices is one primitive of n vertices, a larger one
 * n - 2 fan triangles of 3. */
static void count_poly(guint n, RastCounters *c)
{
    gboolean whole = n <= RAST_POLY_MAX;
    c->verts += whole ? n : 3 * (uint64_t)(n - 2);
    c->prims += whole ? 1 : n - 2;
}

void rast_prerender_count(const RastPrerender *p, const SceneMesh *m,
                          const uint32_t *subset, guint n, RastRect r,
                          RastCounters *c, uint64_t *spans, uint64_t *pixels)
{
    g_assert(scene_mesh_n_polys(m) == p->n_polys);
    const PreSpan *sp = (const PreSpan *)(void *)p->spans->data;
    uint64_t in_spans = 0, in_pixels = 0, all_spans = 0, all_pixels = 0;
    for (guint k = 0; k < n; k++) {
        uint32_t poly = subset[k];
        g_assert(poly < p->n_polys);
        count_poly(scene_mesh_poly_len(m, poly), c);
        all_spans += p->first[poly + 1] - p->first[poly];
        for (uint32_t i = p->first[poly]; i < p->first[poly + 1]; i++) {
            all_pixels += (uint64_t)(sp[i].x1 - sp[i].x0);
            int x0 = MAX(sp[i].x0, r.x0), x1 = MIN(sp[i].x1, r.x1);
            gboolean in = sp[i].y >= r.y0 && sp[i].y < r.y1 && x0 < x1;
            in_spans += in;
            in_pixels += in ? (uint64_t)(x1 - x0) : 0;
        }
    }
    c->spans += all_spans;
    c->pixels += all_pixels;
    c->zcompares += in_pixels;
    *spans += in_spans;
    *pixels += in_pixels;
}

/* ---- the set, by key ----------------------------------------------------- */

struct RastPrerenderSet {
    GPtrArray *by_key; /* RastPrerender or NULL, indexed by key */
};

RastPrerenderSet *rast_prerender_set_new(void)
{
    RastPrerenderSet *s = g_new0(RastPrerenderSet, 1);
    s->by_key =
        g_ptr_array_new_with_free_func((GDestroyNotify)rast_prerender_free);
    return s;
}

void rast_prerender_set_free(RastPrerenderSet *s)
{
    if (!s)
        return;
    g_ptr_array_free(s->by_key, TRUE);
    g_free(s);
}

/* The fields that decide which spans a polygon makes. */
static gboolean same_geometry(const RastView *a, const RastView *b)
{
    return memcmp(&a->view_proj, &b->view_proj, sizeof a->view_proj) == 0 &&
           a->width == b->width && a->height == b->height &&
           a->cull_back == b->cull_back && a->span_rule == b->span_rule;
}

const RastPrerender *rast_prerender_set_get(RastPrerenderSet *s, guint key,
                                            const RastView *v,
                                            const SceneMesh *m)
{
    if (key >= s->by_key->len)
        g_ptr_array_set_size(s->by_key, (gint)key + 1);
    RastPrerender *p = g_ptr_array_index(s->by_key, key);
    if (!p) {
        p = rast_prerender_new(v, m);
        g_ptr_array_index(s->by_key, key) = p;
    }
    g_assert(same_geometry(&p->view, v));
    g_assert(p->n_polys == scene_mesh_n_polys(m));
    return p;
}
