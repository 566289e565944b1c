/* pn_cube.c — test helpers: cubes for the PN-triangle tests (pn_cube.h). */
#include "tests/scene/pn_cube.h"

const uint32_t pn_cube_quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6},
                                      {0, 1, 5, 4}, {2, 6, 7, 3},
                                      {0, 4, 6, 2}, {1, 3, 7, 5}};

Vec3 pn_cube_corner(guint c)
{
    return (Vec3){c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1};
}

SceneMesh *pn_cube_smooth(void)
{
    SceneMesh *m = scene_mesh_new();
    for (guint c = 0; c < 8; c++) {
        Vec3 p = pn_cube_corner(c), n = vec3_norm(p);
        scene_mesh_add_vertex(m, p);
        g_array_append_val(m->normals, n);
    }
    for (int f = 0; f < 6; f++) {
        const uint32_t *q = pn_cube_quads[f];
        scene_mesh_add_quad(m, q[0], q[1], q[2], q[3], scene_color(1, 1, 1),
                            0);
    }
    return m;
}
