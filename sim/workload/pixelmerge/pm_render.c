/* pm_render.c — span-list creation and the modified scanline z-buffer on
 * one processor's polygons (seed 003 §2), through sim/raster.
 *
 * The local pixels are converted from the raster library's WPA
 * (RastActivePixel, rows consecutive) to WlPmWpa keeping scanline order
 * and the generation order inside a row; depths and primitive ids are
 * kept exactly, so the depth-tie rule is the raster library's.  Colours
 * are repacked from the raster's 0xAABBGGRR to WlPmPixel's 0xRRGGBB.
 */
#include "sim/workload/pixelmerge/pm_render.h"
#include "sim/raster/scanzbuf.h"
#include <string.h>

const char *const wl_pm_split_names[] = {"cyclic", "block", NULL};

/* The polygon indices of processor p of n. */
static uint32_t *share(guint n_polys, guint p, guint n, WlPmSplit split,
                       guint *count)
{
    uint32_t *ids = g_new(uint32_t, n_polys / n + 1);
    guint k = 0;
    if (split == WL_PM_SPLIT_CYCLIC) {
        for (guint i = p; i < n_polys; i += n)
            ids[k++] = i;
    } else {
        guint lo = (guint)((uint64_t)n_polys * p / n);
        guint hi = (guint)((uint64_t)n_polys * (p + 1) / n);
        for (guint i = lo; i < hi; i++)
            ids[k++] = i;
    }
    *count = k;
    return ids;
}

static void count_rows(const RastSpanList *sl, WlPmCounts *c)
{
    for (int y = 0; y < rast_spanlist_height(sl); y++) {
        size_t s;
        rast_spanlist_row(sl, y, &s);
        c->span_rows += s > 0;
        c->insert_steps += (uint64_t)s * (s - 1) / 4; /* s = 0: 0 (unsigned) */
    }
}

/* The raster library's 0xAABBGGRR (scan.h) as WlPmPixel's 0xRRGGBB. */
static uint32_t rgb_of(uint32_t rgba)
{
    return (rgba & 0xffu) << 16 | (rgba & 0xff00u) | (rgba >> 16 & 0xffu);
}

static WlPmWpa *to_wpa(const RastActive *a)
{
    int w = rast_active_width(a), h = rast_active_height(a);
    WlPmWpa *out = wl_pm_wpa_new((guint)w, (guint)h);
    for (int y = 0; y < h; y++) {
        size_t n;
        const RastActivePixel *r = rast_active_row(a, y, &n);
        for (size_t i = 0; i < n; i++) {
            WlPmPixel px = {(uint16_t)r[i].x, (uint16_t)y, r[i].z, r[i].prim,
                            rgb_of(r[i].rgba)};
            wl_pm_wpa_push(out, &px);
        }
    }
    wl_pm_wpa_finish(out);
    return out;
}

WlPmWpa *wl_pm_render_local(const RastView *v, const SceneMesh *flat, guint p,
                            guint n, WlPmSplit split, WlPmCounts *c)
{
    guint k;
    uint32_t *ids = share(scene_mesh_n_polys(flat), p, n, split, &k);
    WlPmWpa *w = wl_pm_render_ids(v, flat, ids, k, c);
    g_free(ids);
    return w;
}

WlPmWpa *wl_pm_render_ids(const RastView *v, const SceneMesh *flat,
                          const uint32_t *ids, guint k, WlPmCounts *c)
{
    memset(c, 0, sizeof *c);
    c->polygons = k;
    RastSpanList *sl = rast_spanlist_new(v->width, v->height);
    if (k > 0)
        rast_draw_mesh(v, flat, mat4_identity(), scene_color(1, 1, 1), 0,
                       &(RastSubset){ids, k}, rast_spanlist_sink(sl), &c->rc);
    rast_spanlist_sort(sl);
    count_rows(sl, c);
    RastActive *a = rast_active_new(v->width, v->height);
    rast_scanline_zbuffer(a, sl, &c->rc);
    WlPmWpa *w = to_wpa(a);
    rast_active_free(a);
    rast_spanlist_free(sl);
    return w;
}
