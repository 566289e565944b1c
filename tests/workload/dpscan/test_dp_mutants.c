/* test_dp_mutants.c — claims of the data-parallel scan workload that
 * mutation testing (make mutate, docs/testing.md) found unchecked:
 * "#rrggbb" palette colours read channel by channel, and a NEWS move's
 * time is its coefficients times the machine's unit costs (dp_cost.h:
 * "tests can check sums"), points mode draws no vertex of a polygon
 * behind the eye, and hidden-line mode keeps a filled square's border
 * pixels, the screen's edge included. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/workload/dpscan/dp_color.h"
#include "sim/workload/dpscan/dp_cost.h"
#include "tests/workload/dpscan/dp_test_model.h"
#include "sim/workload/dpscan/dp_render.h"
#include "sim/scene/teapots.h"

static void test_hex_palette(void **state)
{
    (void)state;
    GString *y = g_string_new("[");
    for (int i = 0; i < WL_DP_COLORS; i++)
        g_string_append_printf(y, "%s\"#%02x8040\"", i ? ", " : "", i * 16);
    g_string_append(y, "]\n");
    GError *err = NULL;
    CfgNode *seq = cfg_load_string(y->str, "p.yaml", &err);
    assert_non_null(seq);
    float pal[WL_DP_COLORS][3];
    assert_true(wl_dp_palette_from_cfg(seq, pal, &err));
    for (int i = 0; i < WL_DP_COLORS; i++) {
        assert_true(fabsf(pal[i][0] - i * 16 / 255.0f) < 1e-6);
        assert_true(fabsf(pal[i][1] - 0x80 / 255.0f) < 1e-6);
        assert_true(fabsf(pal[i][2] - 0x40 / 255.0f) < 1e-6);
    }
    cfg_free(seq);
    g_string_free(y, TRUE);
}

static void test_news_cost_sum(void **state)
{
    (void)state;
    WlDpMachine m = {0};
    m.arch = WL_DP_SIMD;
    m.procs = 1024;
    m.step = 3 * SIM_US;
    m.news_slice = 5 * SIM_US;
    for (uint64_t n = 1; n <= 5000; n += 1337) {
        WlDpCoef k = {0};
        SimTime t = wl_dp_news_cost(&m, n, &k);
        assert_true(k.steps == 1);
        assert_true(k.news_slices == (double)wl_dp_vp_ratio(&m, n));
        assert_true((double)t == (double)m.step * k.steps +
                                     (double)m.news_slice * k.news_slices);
    }
}

/* The segment buffer's size changes when it is flushed, not what is
 * drawn: every segment reaches the z-buffer once, so a buffer a hundredth
 * of the polygons (several flushes) sends as many pixels as one that holds
 * them all, and the z-buffers agree. */
static WlDpImage *render(const Scene *s, double factor)
{
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 64, 64, WL_DP_MODE_FLAT, pal);
    WlDpRenderOpts o = {.mode = WL_DP_MODE_FLAT, .buffer_factor = factor,
                        .ops = wl_dp_ops_defaults()};
    WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 16};
    WlDpVm *vm = wl_dp_vm_new(&mc, 1, 64, 64);
    WlDpImage *img = wl_dp_render(vm, p, 64, 64, &o);
    wl_dp_vm_free(vm);
    wl_dp_polys_free(p);
    return img;
}

static void test_flushes_send_each_segment_once(void **state)
{
    (void)state;
    SceneTeapotsParams tp = scene_teapots_defaults();
    tp.count = 2;
    tp.polygons_per_teapot = 300;
    GError *err = NULL;
    Scene *s = scene_teapots_new(&tp, "t", &err);
    assert_non_null(s);
    WlDpImage *many = render(s, 0.01), *one = render(s, 100);
    assert_true(many->flushes > 2 && one->flushes < many->flushes);
    assert_int_equal(many->segments, one->segments);
    assert_int_equal(many->pixels, one->pixels);
    assert_memory_equal(many->zbuf, one->zbuf, 64 * 64 * sizeof(uint64_t));
    wl_dp_image_free(many);
    wl_dp_image_free(one);
    scene_free(s);
}

/* router_procs is optional, default 1 (dp_model.c): the CM-5 model has
 * none, the CM-200's sets its own. */
static void test_router_procs_default(void **state)
{
    (void)state;
    GError *err = NULL;
    WlDpMachine m = {0};
    if (!dp_test_model("cm5", &m, &err))
        fail_msg("%s", err->message);
    assert_int_equal(m.router_procs, 1);
    WlDpMachine c = {0};
    assert_true(dp_test_model("cm200", &c, &err));
    assert_true(c.router_procs > 1);
}

/* Points mode draws the vertices of the polygons in front of the eye
 * only: by hand, polygon 0 (ok) has two vertices on a 16 x 16 screen and
 * one left of it (clipped), polygon 1 (not ok: a vertex behind the eye)
 * has three on screen, none drawn.  The z-buffer holds exactly polygon
 * 0's two keys at the floors of its vertices. */
static void test_points_skip_polygons_behind_eye(void **state)
{
    (void)state;
    double x[6] = {2.5, 10.2, -1.5, 12, 13.5, 9.9};
    double y[6] = {3.5, 4.9, 12, 12, 13, 14.2};
    double z[6] = {0.5, 0.25, 0.75, 0.5, 0.5, 0.5}, v[6] = {0};
    uint32_t start[3] = {0, 3, 6};
    uint8_t color[2] = {3, 5}, ok[2] = {1, 0};
    WlDpPolys p = {.n = 2, .n_ok = 1, .kmax = 3, .start = start,
                   .x = x, .y = y, .z = z, .val = v, .color = color,
                   .ok = ok, .n_verts = 6, .mode = WL_DP_MODE_POINTS};
    WlDpRenderOpts o = {.mode = WL_DP_MODE_POINTS, .buffer_factor = 1,
                        .ops = wl_dp_ops_defaults()};
    WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 16};
    WlDpVm *vm = wl_dp_vm_new(&mc, 1, 16, 16);
    WlDpImage *img = wl_dp_render(vm, &p, 16, 16, &o);
    assert_int_equal(img->pixels, 2);
    assert_int_equal(img->clipped, 1);
    assert_int_equal(img->max_len, 1);
    uint8_t idx = wl_dp_color_index(3, 1.0);
    for (int k = 0; k < 16 * 16; k++) {
        uint64_t want = k == 3 * 16 + 2    ? wl_dp_key(0.5, 0, idx)
                        : k == 4 * 16 + 10 ? wl_dp_key(0.25, 0, idx)
                                           : 0;
        if (img->zbuf[k] != want)
            fail_msg("pixel %d: key %#llx, expected %#llx", k,
                     (unsigned long long)img->zbuf[k],
                     (unsigned long long)want);
    }
    wl_dp_image_free(img);
    wl_dp_vm_free(vm);
}

/* Hidden-line mode keeps the border pixels of what the fill drew: a
 * square over pixels 0..3 of rows 0..3 of an 8 x 8 screen (its corner
 * at pixel 0, the screen's edge counting as "nothing" beside it) shows
 * its 12 border pixels with the fill's colour index, its 4 inner pixels
 * and everything else background (0). */
static void test_hidden_line_border(void **state)
{
    (void)state;
    double x[4] = {0.2, 3.8, 3.8, 0.2}, y[4] = {0.2, 0.2, 3.8, 3.8};
    double z[4] = {0.5, 0.5, 0.5, 0.5}, v[4] = {1, 1, 1, 1};
    uint32_t start[2] = {0, 4};
    uint8_t color[1] = {3}, ok[1] = {1};
    WlDpPolys p = {.n = 1, .n_ok = 1, .kmax = 4, .start = start,
                   .x = x, .y = y, .z = z, .val = v, .color = color,
                   .ok = ok, .n_verts = 4, .mode = WL_DP_MODE_HIDDEN_LINE};
    WlDpRenderOpts o = {.mode = WL_DP_MODE_HIDDEN_LINE, .buffer_factor = 1,
                        .ops = wl_dp_ops_defaults()};
    WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 16};
    WlDpVm *vm = wl_dp_vm_new(&mc, 1, 8, 8);
    WlDpImage *img = wl_dp_render(vm, &p, 8, 8, &o);
    uint8_t fill = wl_dp_key_index(img->zbuf[0]);
    assert_true(fill != 0);
    for (int k = 0; k < 64; k++) {
        int px = k % 8, py = k / 8;
        gboolean in = px < 4 && py < 4;
        gboolean border = in && (px == 0 || px == 3 || py == 0 || py == 3);
        assert_int_equal(img->zbuf[k] != 0, in);
        if (img->index[k] != (border ? fill : 0))
            fail_msg("pixel (%d, %d): index %u, expected %u", px, py,
                     img->index[k], border ? fill : 0);
    }
    wl_dp_image_free(img);
    wl_dp_vm_free(vm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hex_palette),
        cmocka_unit_test(test_news_cost_sum),
        cmocka_unit_test(test_flushes_send_each_segment_once),
        cmocka_unit_test(test_router_procs_default),
        cmocka_unit_test(test_points_skip_polygons_behind_eye),
        cmocka_unit_test(test_hidden_line_border),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
