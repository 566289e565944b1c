/* pm_scene.c — teapot scenes from a config section (pm_scene.h). */
#include "sim/workload/pixelmerge/pm_scene.h"
#include "sim/scene/teapots.h"

static const char *const generators[] = {"teapots", NULL};
static const char *const layouts[] = {"spread", "depth", NULL};

static gboolean get_view(const CfgNode *sec, const CfgNode *dflt,
                         SceneView *v, GError **err)
{
    *v = scene_view_default();
    const CfgNode *n = cfg_get(sec, "view");
    if (!n)
        n = dflt;
    if (!n)
        return TRUE;
    if (cfg_kind(n) != CFG_MAP) {
        cfg_error(err, n, "a non-map", "a map of azimuth, elevation, fov, "
                  "fill");
        return FALSE;
    }
    return cfg_get_double(n, "azimuth", FALSE, -360, 360, &v->azimuth_deg,
                          err) &&
           cfg_get_double(n, "elevation", FALSE, -90, 90, &v->elevation_deg,
                          err) &&
           cfg_get_double(n, "fov", FALSE, 1, 170, &v->fov_deg, err) &&
           cfg_get_double(n, "fill", FALSE, 0.01, 1, &v->fill, err);
}

static gboolean get_teapots(const CfgNode *sec, SceneTeapotsParams *p,
                            GError **err)
{
    uint64_t count = 1, polys = p->polygons_per_teapot;
    int layout = p->layout;
    if (!cfg_get_count(sec, "teapots", TRUE, 1, 4096, &count, err) ||
        !cfg_get_count(sec, "polygons_per_teapot", FALSE, 1, 1u << 26,
                       &polys, err) ||
        !cfg_get_enum(sec, "layout", FALSE, layouts, &layout, err) ||
        !cfg_get_double(sec, "spacing", FALSE, 0, 100, &p->spacing, err) ||
        !cfg_get_double(sec, "shift", FALSE, 0, 100, &p->shift, err) ||
        !cfg_get_double(sec, "yaw_step", FALSE, -360, 360, &p->yaw_step,
                        err))
        return FALSE;
    p->count = (guint)count;
    p->polygons_per_teapot = polys;
    p->layout = layout;
    return TRUE;
}

Scene *wl_pm_scene_from_cfg(const CfgNode *sec, const CfgNode *view,
                            GError **err)
{
    int gen = 0;
    if (!sec || cfg_kind(sec) != CFG_MAP) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "pixelmerge: found no 'scene' map, expected a scene "
                    "section with generator: teapots");
        return NULL;
    }
    SceneTeapotsParams p = scene_teapots_defaults();
    SceneView v;
    if (!cfg_get_enum(sec, "generator", TRUE, generators, &gen, err) ||
        !get_teapots(sec, &p, err) || !get_view(sec, view, &v, err))
        return NULL;
    Scene *s = scene_teapots_new(&p, cfg_file(sec), err);
    if (s)
        scene_apply_view(s, &v);
    return s;
}
