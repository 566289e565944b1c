/* pm_images.c — the block images of a frame and their serial references
 * (pm_images.h): blocks' footprints (pm_blocks.c), the volume ray-cast
 * or its isosurface drawn by block (pm_volume.c).
 */
#include "sim/workload/pixelmerge/pm_images.h"
#include <string.h>

const char *const wl_pm_image_names[] = {"scene", "blocks", "volume", NULL};

/* The volume's box: the isosurface fields' domain. */
static const Vec3 box_lo = {-1, -1, -1}, box_hi = {1, 1, 1};

/* A key that needs another setting, refused where it stands. */
static gboolean refuse(const CfgNode *at, const char *found,
                       const char *expected, GError **err)
{
    cfg_error(err, at, found, expected);
    return FALSE;
}

gboolean wl_pm_images_parse(const CfgNode *sec, gboolean compose,
                            gboolean has_order, WlPmImages *im, GError **err)
{
    int kind = WL_PM_IMAGES_SCENE;
    *im = (WlPmImages){.kind = WL_PM_IMAGES_SCENE,
                       .density = 1.5,
                       .vol = wl_pm_volume_defaults()};
    const CfgNode *vol = NULL;
    if (!cfg_get_enum(sec, "images", FALSE, wl_pm_image_names, &kind, err) ||
        !cfg_get_map(sec, "volume", FALSE,
                     "a map of volume settings {density, field, grid, ...}",
                     &vol, err))
        return FALSE;
    im->kind = (WlPmImageKind)kind;
    if (kind == WL_PM_IMAGES_SCENE)
        return !vol || refuse(cfg_get(sec, "volume"),
                              "'volume' with images "
                              "'scene'",
                              "images: blocks or volume for a "
                              "volume section",
                              err);
    if (!compose)
        return refuse(cfg_get(sec, "images"),
                      "block images with one of "
                      "Kurç's schemes",
                      "a compositing scheme (binary_swap, "
                      "direct_send, radix_k, two_three_swap)",
                      err);
    if (has_order)
        return refuse(cfg_get(sec, "visibility"),
                      "'visibility' with block "
                      "images",
                      "no visibility list (the blocks' order "
                      "comes from the view)",
                      err);
    if (kind == WL_PM_IMAGES_BLOCKS)
        return cfg_get_double(vol, "density", FALSE, 1e-9, 1e6, &im->density,
                              err);
    return wl_pm_volume_parse(vol, &im->vol, err);
}

double wl_pm_images_mem_bytes(const WlPmImages *im, guint n, guint N)
{
    if (im->kind == WL_PM_IMAGES_SCENE)
        return 0;
    guint layers = 1;
    while ((uint64_t)layers * layers * layers < n)
        layers++;
    double lattice = 0;
    if (im->kind == WL_PM_IMAGES_VOLUME) {
        double g = im->vol.iso.grid + 1.0;
        lattice = g * g * g * sizeof(double);
    }
    return (double)N * N * layers * (sizeof(WlPmPixel) + 4 * sizeof(double)) +
           lattice;
}

/* The isosurface's polygons of each block: ids[p] (k[p] of them). */
static void surface(WlPmImageSet *s, const RastView *v, const WlPmVolume *vol)
{
    s->mesh = scene_iso_mesh(&vol->iso);
    guint np = scene_mesh_n_polys(s->mesh);
    guint *own = wl_pm_volume_owners(s->mesh, &s->grid);
    guint *at = g_new0(guint, s->n + 1);
    for (guint i = 0; i < np; i++)
        at[own[i] + 1]++;
    for (guint p = 0; p < s->n; p++)
        at[p + 1] += at[p];
    uint32_t *ids = g_new(uint32_t, MAX(np, 1u));
    guint *fill = g_memdup2(at, (s->n + 1) * sizeof *at);
    for (guint i = 0; i < np; i++)
        ids[fill[own[i]]++] = i;
    for (guint p = 0; p < s->n; p++)
        s->local[p] = wl_pm_render_ids(v, s->mesh, ids + at[p],
                                       at[p + 1] - at[p], &s->counts[p]);
    g_free(fill);
    g_free(ids);
    g_free(at);
    g_free(own);
}

WlPmImageSet *wl_pm_images_make(const WlPmImages *im, const SceneCamera *cam,
                                const RastView *v, guint n, WlPmOperator op)
{
    g_assert(im->kind != WL_PM_IMAGES_SCENE);
    WlPmImageSet *s = g_new0(WlPmImageSet, 1);
    s->n = n;
    s->local = g_new0(WlPmWpa *, n);
    s->counts = g_new0(WlPmCounts, n);
    s->order = g_new(guint, n);
    wl_pm_grid_init(&s->grid, n, box_lo, box_hi);
    wl_pm_grid_order(&s->grid, cam, s->order);
    WlPmRays r;
    wl_pm_rays_init(&r, cam, (guint)v->width, (guint)v->height);
    if (im->kind == WL_PM_IMAGES_VOLUME && op == WL_PM_OP_Z) {
        surface(s, v, &im->vol);
        return s;
    }
    WlPmField *f =
        im->kind == WL_PM_IMAGES_VOLUME ? wl_pm_field_new(&im->vol.iso) : NULL;
    for (guint p = 0; p < n; p++)
        s->local[p] =
            f ? wl_pm_volume_image(f, &im->vol, &s->grid, &r, p, &s->counts[p])
              : wl_pm_block_image(&s->grid, &r, p, im->density, &s->counts[p]);
    wl_pm_field_free(f);
    return s;
}

void wl_pm_images_free(WlPmImageSet *set)
{
    if (!set)
        return;
    for (guint p = 0; p < set->n; p++)
        wl_pm_wpa_free(set->local[p]);
    g_free(set->local);
    g_free(set->counts);
    g_free(set->order);
    if (set->mesh)
        scene_mesh_free(set->mesh);
    g_free(set);
}

/* The whole volume cast by one process against the composite. */
static gboolean over_matches(const WlPmImages *im, const SceneCamera *cam,
                             const RastView *v, const WlPmComposite *comp)
{
    WlPmImages one = *im;
    WlPmImageSet *s = wl_pm_images_make(&one, cam, v, 1, WL_PM_OP_OVER);
    gsize n = (gsize)v->width * v->height * 4;
    double *ref = wl_pm_over_serial(s->local, 1, NULL, 1.0);
    gboolean ok = wl_pm_over_diff(ref, comp->rgba, n) < 0;
    g_free(ref);
    wl_pm_images_free(s);
    return ok;
}

gboolean wl_pm_images_match(const WlPmImages *im, const WlPmImageSet *set,
                            const SceneCamera *cam, const RastView *v,
                            WlPmOperator op, const WlPmComposite *comp)
{
    if (op == WL_PM_OP_OVER)
        return im->kind != WL_PM_IMAGES_VOLUME ||
               over_matches(im, cam, v, comp);
    WlPmFrame *f = wl_pm_frame_new((guint)v->width, (guint)v->height);
    if (set->mesh) {
        WlPmCounts k;
        WlPmWpa *w =
            wl_pm_render_local(v, set->mesh, 0, 1, WL_PM_SPLIT_BLOCK, &k);
        wl_pm_frame_put_wpa(f, w);
        wl_pm_wpa_free(w);
    } else {
        for (guint p = 0; p < set->n; p++)
            wl_pm_frame_put_wpa(f, set->local[p]);
    }
    gboolean ok = wl_pm_frame_diff(f, comp->merge->image) < 0;
    wl_pm_frame_free(f);
    return ok;
}
