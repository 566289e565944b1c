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
    return scene_new_app("march", scene_iso_mesh_cells(&p->iso, p->cell), 45,
                         atan(1 / sqrt(2.0)) * 180 / G_PI, p->fill);
}
