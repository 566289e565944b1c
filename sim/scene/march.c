/* march.c — the March scene of Argus: a procedural volume polygonised
 * cell by cell, viewed so that cell order is back-to-front (march.h).
 * O(grid^3) time, O(triangles) memory.
 */
#include "sim/scene/march.h"
#include <math.h>

SceneMarchParams scene_march_defaults(void)
{
    SceneMarchParams p;
    p.iso = scene_iso_defaults();
    p.iso.field = SCENE_FIELD_METABALLS;
    p.iso.grid = 64;
    p.iso.balls = 10;
    p.iso.seed = 2;
    p.iso.iso = 1.67;
    p.iso.color = scene_color(0.95f, 0.90f, 0.80f);
    p.cell = 16;
    p.fill = 0.95;
    return p;
}

guint scene_march_cells(const SceneMarchParams *p)
{
    return p->iso.grid / p->cell;
}

Scene *scene_march_new(const SceneMarchParams *p)
{
    Scene *s = scene_new("march");
    SceneMesh *m = scene_iso_mesh_cells(&p->iso, p->cell);
    guint id = scene_add_mesh(s, m);
    scene_add_instance(s, id, mat4_identity(), scene_color(1, 1, 1), 0);
    s->width = 1200;
    s->height = 1000;
    s->two_sided = TRUE;
    SceneView v = scene_view_default();
    v.azimuth_deg = 45;
    v.elevation_deg = atan(1 / sqrt(2.0)) * 180 / G_PI;
    v.aspect = 1.2;
    v.fill = p->fill;
    v.fit_vertices = TRUE;
    scene_apply_view(s, &v);
    return s;
}
