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
#include "sim/workload/dpscan/dp_serial.h"

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

/* The segment buffer as dp_render.h describes it, replayed here from
 * the polygons' spans: scan line i brings the spans of every polygon
 * with more than i rows; before a line that would overflow a non-empty
 * buffer of `cap` segments it is flushed, and once more at the end.
 * Returns the flushes; *exact: some line filled the buffer exactly. */
static uint64_t model_flushes(const WlDpPolys *p, uint64_t cap,
                              gboolean *exact, uint32_t *longest)
{
    uint32_t tallest = 0;
    for (uint64_t i = 0; i < p->n; i++) {
        int32_t y0;
        tallest = MAX(tallest, wl_dp_poly_rows(p, i, &y0));
    }
    uint64_t nbuf = 0, flushes = 0;
    *longest = 0;
    for (uint32_t r = 0; r < tallest; r++) {
        uint64_t tot = 0;
        for (uint64_t i = 0; i < p->n; i++) {
            int32_t y0;
            if (wl_dp_poly_rows(p, i, &y0) <= r)
                continue;
            WlDpSpan sp[WL_DP_MAX_VERTS / 2];
            guint n = wl_dp_poly_spans(p, i, y0 + (int32_t)r, sp);
            tot += n;
            for (guint k = 0; k < n; k++)
                *longest = MAX(*longest, sp[k].len);
        }
        if (nbuf > 0 && nbuf + tot > cap)
            flushes++, nbuf = 0;
        *exact |= nbuf + tot == cap;
        nbuf += tot;
    }
    return flushes + (nbuf > 0);
}

static void test_flushes_by_hand(void **state)
{
    (void)state;
    Scene *s = shapes();
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 48, 40, WL_DP_MODE_FLAT, pal);
    gboolean exact = FALSE;
    for (double f = 0.3; f < 4; f += 0.34) {
        WlDpRenderOpts o = {
            .mode = WL_DP_MODE_FLAT, .buffer_factor = f, .ops = ops};
        WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 1 << 20, .op = 1};
        WlDpVm *vm = wl_dp_vm_new(&mc, 1, 48, 40);
        WlDpImage *img = wl_dp_render(vm, p, 48, 40, &o);
        uint32_t longest;
        uint64_t cap = MAX((uint64_t)ceil(f * 3), 1);
        uint64_t want = model_flushes(p, cap, &exact, &longest);
        if (img->flushes != want)
            fail_msg("factor %.2f (%lu segments): %lu flushes, expected %lu",
                     f, (unsigned long)cap, (unsigned long)img->flushes,
                     (unsigned long)want);
        assert_int_equal(img->max_len, longest);
        wl_dp_image_free(img);
        wl_dp_vm_free(vm);
    }
    assert_true(exact); /* a line filled the buffer to the brim */
    wl_dp_polys_free(p);
    scene_free(s);
}

/* Polygons running off the right, bottom, left and top edges: the
 * pixels past an edge are masked off (counted as clipped), the z-buffer equals the
 * serial render's. */
static void test_clipped_at_the_edges(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    const double t[3][3][2] = {{{0.2, 0.3}, {1.6, 0.1}, {0.5, 0.9}},
                               {{-0.5, -0.2}, {0.1, -1.7}, {-0.9, -0.6}},
                               {{-1.6, 0.5}, {-0.7, 0.8}, {-0.8, 1.5}}};
    for (int k = 0; k < 3; k++) {
        uint32_t v[3];
        for (int j = 0; j < 3; j++)
            v[j] = scene_mesh_add_vertex(m, vec3(t[k][j][0], t[k][j][1], 0));
        scene_mesh_add_poly(m, v, 3, scene_color(1, 0.5f, 0), 0);
    }
    Scene *s = scene_new("edges");
    scene_add_instance(s, scene_add_mesh(s, m), mat4_identity(),
                       scene_color(1, 1, 1), 0);
    s->camera.proj = SCENE_ORTHOGRAPHIC;
    s->camera.eye = vec3(0, 0, 2);
    s->camera.height = 2;
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    for (int mode = 0; mode < WL_DP_N_MODES; mode++) {
        WlDpPolys *p = wl_dp_polys_new(s, 0, 40, 32, (WlDpMode)mode, pal);
        WlDpRenderOpts o = {
            .mode = (WlDpMode)mode, .buffer_factor = 1, .ops = ops};
        WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 64, .op = 1};
        WlDpVm *vm = wl_dp_vm_new(&mc, 1, 40, 32);
        WlDpImage *img = wl_dp_render(vm, p, 40, 32, &o);
        WlDpImage *ref = wl_dp_serial_render(p, 40, 32);
        if (mode != WL_DP_MODE_POINTS)
            assert_true(img->clipped > 0);
        assert_memory_equal(img->zbuf, ref->zbuf, 40 * 32 * sizeof(uint64_t));
        assert_int_equal(img->pixels, ref->pixels);
        wl_dp_image_free(ref);
        wl_dp_image_free(img);
        wl_dp_vm_free(vm);
        wl_dp_polys_free(p);
    }
    scene_free(s);
}

/* Router sends by their words: a segment is 7 words, a z-buffer pixel 2
 * (a 64-bit key).  With only the issue step costing (1 ps) every send
 * that carries a message costs its words: 7 a scan line with segments,
 * 2 a pixel iteration; and the words moved are 7 per segment and 2 per
 * pixel. */
static void test_router_words(void **state)
{
    (void)state;
    Scene *s = shapes();
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    for (int m = 0; m < WL_DP_N_MODES; m++) {
        WlDpPolys *p = wl_dp_polys_new(s, 0, 48, 40, (WlDpMode)m, pal);
        WlDpRenderOpts o = {.mode = (WlDpMode)m, .buffer_factor = 100,
                            .ops = ops};
        WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 1 << 20, .step = 1};
        WlDpVm *vm = wl_dp_vm_new(&mc, 1, 48, 40);
        WlDpImage *img = wl_dp_render(vm, p, 48, 40, &o);
        const WlDpVmCounts *c = wl_dp_vm_counts(vm);
        uint64_t want = 7 * img->scan_iters + 2 * img->pixel_iters;
        assert_true(img->pixel_iters > 0);
        assert_int_equal(wl_dp_vm_target(vm, 0)->phase[WL_DP_PH_ROUTER],
                         want);
        assert_int_equal(c->sends, want);
        assert_int_equal(c->words, 7 * img->segments + 2 * img->pixels);
        assert_int_equal(c->messages, img->segments + img->pixels);
        wl_dp_image_free(img);
        wl_dp_vm_free(vm);
        wl_dp_polys_free(p);
    }
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_phase_ops),
        cmocka_unit_test(test_router_words),
        cmocka_unit_test(test_buffer_capacity),
        cmocka_unit_test(test_flushes_by_hand),
        cmocka_unit_test(test_clipped_at_the_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
