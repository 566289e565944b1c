/* teapots.c — the teapot scenes of the active-pixel-merging paper.
 *
 * Implements teapots.h: one shared teapot mesh (teapot.h), instanced
 * `count` times by a layout rule or explicit placements.  O(T + count).
 */
#include "sim/scene/teapots.h"
#include "sim/core/memlimit.h"
#include "sim/scene/scene_limits.h"

#include "sim/scene/teapot.h"

/* Hues for vary_color: distinct, fully saturated-ish, no paper data. */
static const SceneColor palette[8] = {
    {0.90f, 0.30f, 0.25f}, {0.30f, 0.70f, 0.90f}, {0.95f, 0.80f, 0.30f},
    {0.45f, 0.85f, 0.40f}, {0.80f, 0.45f, 0.85f}, {0.95f, 0.60f, 0.30f},
    {0.40f, 0.50f, 0.95f}, {0.85f, 0.85f, 0.85f},
};

SceneTeapotsParams scene_teapots_defaults(void)
{
    SceneTeapotsParams p = {.polygons_per_teapot = 3200,
                            .count = 1,
                            .layout = SCENE_TEAPOTS_SPREAD,
                            .spacing = 1.1,
                            .shift = 0.5,
                            .color = {1, 1, 1},
                            .vary_color = TRUE,
                            .columns = 1,
                            .across = 1.1};
    return p;
}

static SceneTeapotPlacement layout_at(const SceneTeapotsParams *p, guint i,
                                      Vec3 size)
{
    SceneTeapotPlacement pl = {{0, 0, 0}, p->yaw + i * p->yaw_step, 1.0};
    if (p->layout == SCENE_TEAPOTS_SPREAD) {
        guint cols = (guint)ceil(sqrt((double)p->count));
        guint rows = (p->count + cols - 1) / cols;
        guint r = i / cols, c = i % cols;
        /* the last row may be short: centre it */
        guint in_row = r + 1 < rows ? cols : p->count - r * cols;
        pl.at.x = (c - (in_row - 1) / 2.0) * p->spacing * size.x;
        pl.at.y = ((rows - 1) / 2.0 - r) * p->spacing * size.y;
    } else {
        guint cols = MIN(MAX(p->columns, 1u), p->count);
        guint rows = (p->count + cols - 1) / cols;
        double mid = (rows - 1) / 2.0, r = i / cols, c = i % cols;
        pl.at.x = (c - (cols - 1) / 2.0) * p->across * size.x +
                  (r - mid) * p->shift * size.x;
        pl.at.z = -(r - mid) * p->spacing * size.z;
    }
    return pl;
}

static Mat4 place(const SceneTeapotPlacement *pl, Vec3 centre)
{
    Mat4 m = mat4_translate(-centre.x, -centre.y, -centre.z);
    m = mat4_mul(mat4_scale(pl->scale, pl->scale, pl->scale), m);
    m = mat4_mul(mat4_rotate(vec3(0, 1, 0), pl->yaw_deg * G_PI / 180), m);
    return mat4_mul(mat4_translate(pl->at.x, pl->at.y, pl->at.z), m);
}

gboolean scene_teapots_check(const SceneTeapotsParams *p, const char *what,
                             GError **err)
{
    if (p->count < 1 || p->count > SCENE_TEAPOTS_MAX) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found %u teapots, expected 1 to %d", what, p->count,
                    SCENE_TEAPOTS_MAX);
        return FALSE;
    }
    char *size = g_strdup_printf("%u teapots x %" G_GUINT64_FORMAT
                                 " polygons",
                                 p->count, (guint64)p->polygons_per_teapot);
    gboolean ok = sim_mem_check((double)p->count *
                                    (double)p->polygons_per_teapot *
                                    SCENE_POLY_BYTES,
                                what, size, err);
    g_free(size);
    return ok;
}

Scene *scene_teapots_new(const SceneTeapotsParams *p, const char *what,
                         GError **err)
{
    SceneTeapotTess t;
    g_assert(!p->placements || p->n_placements == p->count);
    if (!scene_teapots_check(p, what, err) ||
        !scene_teapot_tess_for(p->polygons_per_teapot, what, &t, err))
        return NULL;
    Scene *s = scene_new("teapots");
    SceneMesh *m = scene_teapot_mesh(t, scene_color(1, 1, 1));
    SceneBox box = scene_mesh_bbox(m);
    Vec3 size = scene_box_size(box), centre = scene_box_center(box);
    guint id = scene_add_mesh(s, m);
    for (guint i = 0; i < p->count; i++) {
        SceneTeapotPlacement pl =
            p->placements ? p->placements[i] : layout_at(p, i, size);
        SceneColor c = p->vary_color ? palette[i % 8] : p->color;
        scene_add_instance(s, id, place(&pl, centre), c, i);
    }
    SceneView v = scene_view_default();
    scene_apply_view(s, &v);
    return s;
}
