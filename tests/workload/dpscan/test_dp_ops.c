/* test_dp_ops.c — what the data-parallel renderer (dp_render.c) charges
 * each phase, statement by statement, on a machine where only the
 * elementwise operation costs (1 ps) and every array fits one virtual
 * processor slice (v = 1): a phase's time is then the sum of the ops
 * per element of its statements, worked out here from dp_render.h:
 *   transform  kmax x transform, then shade (x kmax for Gouraud and
 *              contour; none for wireframe, points and lines)
 *   scan       (fills) 2 kmax + 4 once, then per scan line of the
 *              tallest polygon k cross + k (k - 1) / 2 swap + k / 2 pair;
 *              (lines) line once
 *   pixel      pixel (fills) or line (lines) per pixel iteration
 *   display    clear + extract, and 4 x edge for hidden lines
 *   router     nothing (sends cost nothing on this machine)
 * Distinct op values make a statement counted with the wrong one show.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/scene.h"
#include "sim/workload/dpscan/dp_color.h"
#include "sim/workload/dpscan/dp_render.h"

/* Two triangles and a quad, seen from the front (kmax 4). */
static Scene *shapes(void)
{
    SceneMesh *m = scene_mesh_new();
    const double t[2][3][2] = {{{-0.9, -0.9}, {0.1, -0.8}, {-0.5, 0.7}},
                               {{0.2, 0.1}, {0.8, 0.3}, {0.5, 0.5}}};
    for (int k = 0; k < 2; k++) {
        uint32_t v[3];
        for (int j = 0; j < 3; j++)
            v[j] = scene_mesh_add_vertex(m, vec3(t[k][j][0], t[k][j][1], 0));
        scene_mesh_add_poly(m, v, 3, scene_color(1, 0.5f, 0), 0);
    }
    const double q[4][2] = {{0.3, -0.7}, {0.7, -0.7}, {0.7, -0.2}, {0.3, -0.2}};
    uint32_t v[4];
    for (int j = 0; j < 4; j++)
        v[j] = scene_mesh_add_vertex(m, vec3(q[j][0], q[j][1], 0));
    scene_mesh_add_poly(m, v, 4, scene_color(0, 0.5f, 1), 0);
    Scene *s = scene_new("shapes");
    scene_add_instance(s, scene_add_mesh(s, m), mat4_identity(),
                       scene_color(1, 1, 1), 0);
    s->camera.proj = SCENE_ORTHOGRAPHIC;
    s->camera.eye = vec3(0, 0, 2);
    s->camera.height = 2;
    return s;
}

static const WlDpOps ops = {.transform = 3,
                            .shade = 5,
                            .cross = 7,
                            .swap = 11,
                            .pair = 13,
                            .pixel = 17,
                            .line = 19,
                            .clear = 23,
                            .extract = 29,
                            .edge = 31};

static void check_mode(const Scene *s, WlDpMode mode)
{
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 48, 40, mode, pal);
    assert_int_equal(p->kmax, 4);
    assert_int_equal(p->n, 3);
    WlDpRenderOpts o = {.mode = mode, .buffer_factor = 0.5, .ops = ops};
    WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 1 << 20, .op = 1};
    WlDpVm *vm = wl_dp_vm_new(&mc, 1, 48, 40);
    WlDpImage *img = wl_dp_render(vm, p, 48, 40, &o);
    const WlDpTarget *t = wl_dp_vm_target(vm, 0);
    gboolean fills = wl_dp_mode_fills(mode);
    gboolean per_vertex =
        mode == WL_DP_MODE_GOURAUD || mode == WL_DP_MODE_CONTOUR;
    gboolean lines = !fills;
    SimTime tr = 4 * 3 + (lines ? 0 : per_vertex ? 4 * 5 : 5);
    SimTime scan =
        fills ? 2 * 4 + 4 + img->scan_iters * (4 * 7 + 6 * 11 + 2 * 13) : 19;
    SimTime pixel = img->pixel_iters * (fills ? 17 : 19);
    SimTime disp = 23 + 29 + (mode == WL_DP_MODE_HIDDEN_LINE ? 4 * 31 : 0);
    assert_true(img->pixel_iters > 0);
    assert_true(!fills || img->scan_iters > 10);
    const SimTime want[WL_DP_N_PHASES] = {tr, scan, pixel, 0, disp};
    for (int ph = 0; ph < WL_DP_N_PHASES; ph++)
        if (t->phase[ph] != want[ph])
            fail_msg("mode %s, phase %s: %lu ps, expected %lu",
                     wl_dp_mode_name(mode), wl_dp_phase_name(ph),
                     (unsigned long)t->phase[ph], (unsigned long)want[ph]);
    wl_dp_image_free(img);
    wl_dp_vm_free(vm);
    wl_dp_polys_free(p);
}

static void test_phase_ops(void **state)
{
    (void)state;
    Scene *s = shapes();
    for (int m = 0; m < WL_DP_N_MODES; m++)
        check_mode(s, (WlDpMode)m);
    scene_free(s);
}

/* The segment buffer holds ceil(buffer_factor x polygons) segments (at
 * least one): a flush happens before a scan line would overflow it, so
 * a smaller buffer flushes more often, never less. */
static void test_buffer_capacity(void **state)
{
    (void)state;
    Scene *s = shapes();
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 48, 40, WL_DP_MODE_FLAT, pal);
    uint64_t last = 0;
    const double f[] = {100, 1, 0.5, 0.01};
    for (guint i = 0; i < G_N_ELEMENTS(f); i++) {
        WlDpRenderOpts o = {
            .mode = WL_DP_MODE_FLAT, .buffer_factor = f[i], .ops = ops};
        WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 1 << 20, .op = 1};
        WlDpVm *vm = wl_dp_vm_new(&mc, 1, 48, 40);
        WlDpImage *img = wl_dp_render(vm, p, 48, 40, &o);
        assert_true(img->flushes >= last);
        if (i == 0)
            assert_int_equal(img->flushes, 1); /* it all fits: one flush */
        last = img->flushes;
        wl_dp_image_free(img);
        wl_dp_vm_free(vm);
    }
    assert_true(last > 3);
    wl_dp_polys_free(p);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_phase_ops),
        cmocka_unit_test(test_buffer_capacity),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
