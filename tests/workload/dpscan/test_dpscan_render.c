/* test_dpscan_render.c — seed 004's data-parallel renderer against the
 * serial reference: equal images for every mode on convex, non-convex
 * and self-overlapping polygons (many flushes, collisions, clipping),
 * the even-odd rule itself, the colour table, and equal costs on
 * repeated runs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/core/rng.h"
#include "sim/workload/dpscan/dp_color.h"
#include "sim/workload/dpscan/dp_serial.h"
#include <math.h>
#include <string.h>

enum { W = 97, H = 61 };

static void add_poly(SceneMesh *m, const double (*xy)[2], guint n, double z,
                     SceneColor c)
{
    uint32_t v[16];
    for (guint k = 0; k < n; k++)
        v[k] = scene_mesh_add_vertex(m, vec3(xy[k][0], xy[k][1], z));
    scene_mesh_add_poly(m, v, n, c, 0);
}

/* A regular star {n/2} (self-overlapping) or a concave arrow. */
static void star(SceneMesh *m, SimRng *r, guint n, double rad, gboolean self)
{
    double cx = 2.4 * sim_rng_uniform(r) - 1.2, cy = 2.4 * sim_rng_uniform(r) - 1.2;
    double xy[16][2];
    for (guint k = 0; k < n; k++) {
        guint j = self ? (2 * k) % n : k;
        double a = 2 * G_PI * j / n + sim_rng_uniform(r) * 0.1;
        double rr = self || k % 2 == 0 ? rad : rad * 0.35;
        xy[k][0] = cx + rr * cos(a);
        xy[k][1] = cy + rr * sin(a);
    }
    SceneColor c = {(float)sim_rng_uniform(r), (float)sim_rng_uniform(r),
                    (float)sim_rng_uniform(r)};
    add_poly(m, (const double(*)[2])xy, n, 2 * sim_rng_uniform(r) - 1, c);
}

/* 60 polygons: convex triangles and quads, concave stars, pentagrams
 * and bow-ties; some reach past the window (clipping). */
static Scene *mixed_scene(void)
{
    SimRng r;
    sim_rng_init(&r, 7, 0);
    SceneMesh *m = scene_mesh_new();
    for (guint i = 0; i < 60; i++) {
        double rad = 0.05 + 0.5 * sim_rng_uniform(&r);
        switch (i % 4) {
        case 0: star(m, &r, 3 + i % 2, rad, FALSE); break; /* convex */
        case 1: star(m, &r, 10, rad, FALSE); break;        /* concave */
        case 2: star(m, &r, 5, rad, TRUE); break;          /* pentagram */
        default: {
            double xy[4][2] = {{-rad, -rad}, {rad, rad}, {rad, -rad}, {-rad, rad}};
            double cx = 2 * sim_rng_uniform(&r) - 1, cy = 2 * sim_rng_uniform(&r) - 1;
            for (int k = 0; k < 4; k++)
                xy[k][0] += cx, xy[k][1] += cy;
            add_poly(m, (const double(*)[2])xy, 4, 2 * sim_rng_uniform(&r) - 1,
                     scene_color(0.2f, 0.9f, 0.3f)); /* bow-tie */
        }
        }
    }
    /* and one across the left edge of the screen (column 0) */
    const double left[4][2] = {{-3, -0.3}, {-1, -0.3}, {-1, 0.3}, {-3, 0.3}};
    add_poly(m, left, 4, 0.5, scene_color(0.9f, 0.2f, 0.2f));
    scene_mesh_compute_normals(m);
    Scene *s = scene_new("mixed");
    scene_add_instance(s, scene_add_mesh(s, m), mat4_identity(),
                       scene_color(1, 1, 1), 0);
    SceneCamera c = scene_camera_default();
    c.proj = SCENE_PERSPECTIVE;
    c.eye = vec3(0.3, 0.2, 4);
    c.target = vec3(0, 0, 0);
    s->camera = c;
    return s;
}

static WlDpVm *three_targets(void)
{
    WlDpMachine ms[3] = {
        {.arch = WL_DP_SIMD, .procs = 16, .vp_pow2 = TRUE, .op = 1, .step = 1,
         .scan_slice = 1, .send_slice = 1, .news_slice = 1},
        {.arch = WL_DP_SIMD, .procs = 64, .op = 1, .step = 1, .scan_slice = 1,
         .send_slice = 1, .news_slice = 1},
        {.arch = WL_DP_SPMD, .procs = 8, .op = 1, .step = 1, .scan_slice = 1,
         .msg_overhead = 1, .msg_bytes = 20, .arity = 4, .levels = 1,
         .level_bw = {20e6}},
    };
    return wl_dp_vm_new(ms, 3, W, H);
}

static void test_every_mode_equals_serial(void **state)
{
    (void)state;
    Scene *s = mixed_scene();
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    for (int mode = 0; mode < WL_DP_N_MODES; mode++) {
        WlDpPolys *p = wl_dp_polys_new(s, 0, W, H, (WlDpMode)mode, pal);
        WlDpRenderOpts o = {.mode = (WlDpMode)mode, .buffer_factor = 0.3,
                            .ops = wl_dp_ops_defaults()};
        WlDpVm *vm = three_targets();
        WlDpImage *dp = wl_dp_render(vm, p, W, H, &o);
        WlDpImage *ref = wl_dp_serial_render(p, W, H);
        assert_memory_equal(dp->index, ref->index, W * H);
        uint64_t drawn = 0;
        for (int k = 0; k < W * H; k++)
            drawn += dp->index[k] != 0;
        assert_true(drawn > 100);
        if (wl_dp_mode_fills((WlDpMode)mode)) {
            assert_true(dp->flushes > 1);   /* a small buffer */
            assert_true(dp->clipped > 0);   /* polygons past the edge */
            assert_true(wl_dp_vm_counts(vm)->collisions > 0);
        }
        wl_dp_image_free(ref);
        wl_dp_image_free(dp);
        wl_dp_vm_free(vm);
        wl_dp_polys_free(p);
    }
    scene_free(s);
}

/* A pentagram's centre is outside by the even-odd rule (a fan of
 * triangles would fill it); its tips are inside. */
static void test_even_odd_rule(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    double xy[5][2];
    for (int k = 0; k < 5; k++) {
        double a = G_PI / 2 + 2 * G_PI * ((2 * k) % 5) / 5;
        xy[k][0] = 0.9 * cos(a);
        xy[k][1] = 0.9 * sin(a);
    }
    add_poly(m, (const double(*)[2])xy, 5, 0, scene_color(1, 0, 0));
    Scene *s = scene_new("star");
    scene_add_instance(s, scene_add_mesh(s, m), mat4_identity(),
                       scene_color(1, 1, 1), 0);
    s->camera.proj = SCENE_ORTHOGRAPHIC;
    s->camera.eye = vec3(0, 0, 2);
    s->camera.height = 2;
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    WlDpPolys *p = wl_dp_polys_new(s, 0, 64, 64, WL_DP_MODE_FLAT, pal);
    WlDpRenderOpts o = {.mode = WL_DP_MODE_FLAT, .buffer_factor = 1,
                        .ops = wl_dp_ops_defaults()};
    WlDpMachine mc = {.arch = WL_DP_SIMD, .procs = 16};
    WlDpVm *vm = wl_dp_vm_new(&mc, 1, 64, 64);
    WlDpImage *img = wl_dp_render(vm, p, 64, 64, &o);
    assert_int_equal(img->index[32 * 64 + 32], 0);  /* centre: hole */
    assert_int_not_equal(img->index[6 * 64 + 32], 0); /* top tip */
    /* Five pairs' worth of segments: rows through the hole have two. */
    assert_true(img->segments > img->scan_iters);
    wl_dp_image_free(img);
    wl_dp_vm_free(vm);
    wl_dp_polys_free(p);
    scene_free(s);
}

static void test_color_table(void **state)
{
    (void)state;
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    pal[2][0] = 1, pal[2][1] = 0.5f, pal[2][2] = 0;
    WlDpColorTable t;
    wl_dp_color_table(pal, &t);
    uint8_t full = wl_dp_color_index(2, 1.0), dark = wl_dp_color_index(2, 0.0);
    assert_int_equal(full, 30 + 2 * 15 + 14);
    assert_int_equal(dark, 30 + 2 * 15);
    assert_int_equal(t.rgb[full][0], 255);
    assert_int_equal(t.rgb[full][1], 128);
    assert_int_equal(t.rgb[dark][0], 17); /* 1/15 of full */
    assert_int_equal(wl_dp_color_index(14, 1.0), 254);
    assert_int_equal(wl_dp_contour_index(1.0), 254);
    assert_int_equal(wl_dp_contour_index(0.0), 44);
    GError *err = NULL;
    CfgNode *bad = cfg_load_string("p: [[1, 0, 0]]\n", "pal.yaml", &err);
    assert_false(wl_dp_palette_from_cfg(cfg_get(bad, "p"), pal, &err));
    assert_non_null(strstr(err->message, "pal.yaml:1:"));
    g_clear_error(&err);
    cfg_free(bad);
}

static void test_costs_deterministic(void **state)
{
    (void)state;
    Scene *s = mixed_scene();
    float pal[WL_DP_COLORS][3];
    wl_dp_palette_default(pal);
    SimTime t[2];
    for (int k = 0; k < 2; k++) {
        WlDpPolys *p = wl_dp_polys_new(s, 0, W, H, WL_DP_MODE_GOURAUD, pal);
        WlDpRenderOpts o = {.mode = WL_DP_MODE_GOURAUD, .buffer_factor = 1,
                            .ops = wl_dp_ops_defaults()};
        WlDpVm *vm = three_targets();
        wl_dp_image_free(wl_dp_render(vm, p, W, H, &o));
        t[k] = wl_dp_vm_target(vm, 2)->total;
        /* More processors, less time (same program). */
        assert_true(wl_dp_vm_target(vm, 1)->total <
                    wl_dp_vm_target(vm, 0)->total);
        wl_dp_vm_free(vm);
        wl_dp_polys_free(p);
    }
    assert_int_equal(t[0], t[1]);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_mode_equals_serial),
        cmocka_unit_test(test_even_odd_rule),
        cmocka_unit_test(test_color_table),
        cmocka_unit_test(test_costs_deterministic),
    };
    return cmocka_run_group_tests_name("dpscan_render", tests, NULL, NULL);
}
