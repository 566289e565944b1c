/* test_dp_iters.c — the data-parallel renderer's loop counts against the
 * geometry, computed here from dp_poly.h (issue 21): scan conversion
 * iterates over the rows of the tallest polygon, lines and points over
 * the pixels of the longest edge, once each. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/scene.h"
#include "sim/workload/dpscan/dp_color.h"
#include "sim/workload/dpscan/dp_render.h"
#include "sim/workload/workload.h"
#include "tests/support.h"

/* Three triangles of different sizes, seen from the front. */
static Scene *triangles(void)
{
    SceneMesh *m = scene_mesh_new();
    const double t[3][3][2] = {{{-0.9, -0.9}, {0.1, -0.8}, {-0.5, 0.7}},
                               {{0.2, 0.1}, {0.8, 0.3}, {0.5, 0.5}},
                               {{0.3, -0.6}, {0.6, -0.7}, {0.4, -0.2}}};
    for (int k = 0; k < 3; k++) {
        uint32_t v[3];
        for (int j = 0; j < 3; j++)
            v[j] = scene_mesh_add_vertex(m, vec3(t[k][j][0], t[k][j][1], 0));
        scene_mesh_add_poly(m, v, 3, scene_color(1, 0.5f, 0), 0);
    }
    Scene *s = scene_new("tris");
    scene_add_instance(s, scene_add_mesh(s, m), mat4_identity(),
                       scene_color(1, 1, 1), 0);
    s->camera.proj = SCENE_ORTHOGRAPHIC;
    s->camera.eye = vec3(0, 0, 2);
    s->camera.height = 2;
    return s;
}

static void check_mode(const Scene *s, WlDpMode mode)
{
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 48, 48, mode, pal);
    uint32_t rows = 0, len = 0;
    for (uint64_t i = 0; i < p->n; i++) {
        int32_t y0;
        rows = MAX(rows, wl_dp_poly_rows(p, i, &y0));
        for (uint32_t e = 0; e < wl_dp_poly_len(p, i); e++)
            len = MAX(len, mode == WL_DP_MODE_POINTS
                               ? 1u
                               : wl_dp_edge_pixels(p, i, e));
    }
    WlDpRenderOpts o = {.mode = mode, .buffer_factor = 1,
                        .ops = wl_dp_ops_defaults()};
    WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 16};
    WlDpVm *vm = wl_dp_vm_new(&mc, 1, 48, 48);
    WlDpImage *img = wl_dp_render(vm, p, 48, 48, &o);
    if (wl_dp_mode_fills(mode)) {
        assert_true(rows > 10);
        assert_int_equal(img->max_rows, rows);
        assert_int_equal(img->scan_iters, rows);
    } else {
        assert_true(mode == WL_DP_MODE_POINTS || len > 10);
        assert_int_equal(img->max_len, len);
        assert_int_equal(img->pixel_iters, len);
    }
    wl_dp_image_free(img);
    wl_dp_vm_free(vm);
    wl_dp_polys_free(p);
}

static void test_loop_counts(void **state)
{
    (void)state;
    Scene *s = triangles();
    check_mode(s, WL_DP_MODE_FLAT);
    check_mode(s, WL_DP_MODE_GOURAUD);
    check_mode(s, WL_DP_MODE_WIREFRAME);
    check_mode(s, WL_DP_MODE_LINES);
    check_mode(s, WL_DP_MODE_POINTS);
    scene_free(s);
}

static SimResult *run(const char *wire)
{
    char *yml = g_strdup_printf("workload: {type: dpscan, model: cm5, "
                                "processors: 16, width: 48, height: 32, "
                                "wire: %s}\n"
                                "scene: {generator: isosurface, grid: 6}\n",
                                wire);
    GError *err = NULL;
    SupportRun o = {.fidelity = "analytic", .frames = 1};
    SimResult *r = support_run_text(yml, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    g_free(yml);
    return r;
}

/* Priced by formula, SPMD sends put nothing on a network: no bytes and
 * no messages are reported; over the network they are. */
static void test_formula_wire_reports_no_traffic(void **state)
{
    (void)state;
    SimResult *f = run("formula"), *n = run("network");
    assert_int_equal(f->comm_bytes, 0);
    assert_int_equal(f->comm_messages, 0);
    assert_true(n->comm_bytes > 0 && n->comm_messages > 0);
    sim_result_free(f);
    sim_result_free(n);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_loop_counts),
        cmocka_unit_test(test_formula_wire_reports_no_traffic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
