/* test_pm_mutants.c — claims of the pixel-merging frame (pm_frame.h) that
 * mutation testing (make mutate, docs/testing.md) found unchecked: the
 * merged image keeps empty pixels black and shows the teapot elsewhere. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/teapot.h"
#include "sim/workload/pixelmerge/pm_frame.h"

static void test_merged_image_background(void **state)
{
    (void)state;
    SceneTeapotTess tess;
    assert_true(scene_teapot_tess_for(300, "test", &tess, NULL));
    Scene *sc = scene_new("pot");
    guint m = scene_add_mesh(sc, scene_teapot_mesh(tess, scene_color(1, 1, 1)));
    scene_add_instance(sc, m, mat4_identity(), scene_color(1, 1, 1), 0);
    sc->camera = scene_camera_default();
    scene_camera_fit(&sc->camera, scene_bbox(sc), 0.5); /* corners empty */
    WlPmSetup s = {.scheme = WL_PM_PAIR, .balance = WL_PM_BAL_RS, .procs = 4,
                   .resolution = 32, .split = WL_PM_SPLIT_CYCLIC,
                   .fmt = {8, 4, 2}, .span_rule = RAST_SPAN_EXACT,
                   .keep_image = TRUE};
    WlPmCosts c = {.polygon = SIM_US, .span = SIM_US, .pixel = SIM_US,
                   .merge = {.compare = SIM_US, .count_bytes = 4}};
    NetParams np = {.bandwidth = 1e6, .channels = 1, .startup = SIM_US,
                    .switching = NET_SW_CIRCUIT};
    SimEngine *eng = sim_engine_new(1);
    NetTopo *topo = net_hypercube_new(2);
    NetNet *net = net_new(eng, topo, &np, NET_FLOW);
    WlPmFrameOut out;
    GError *err = NULL;
    assert_true(wl_pm_frame_run(net, sc, &s, &c, &out, &err));
    const RastImage *img = out.image;
    assert_non_null(img);
    guint lit = 0;
    for (int i = 0; i < img->width * img->height; i++)
        lit += img->rgb[3 * i] || img->rgb[3 * i + 1] || img->rgb[3 * i + 2];
    assert_true(lit > 20 && lit < (guint)(img->width * img->height) / 2);
    for (int k = 0; k < 3; k++) /* the top-left corner is empty: black */
        assert_int_equal(img->rgb[k], 0);
    wl_pm_frame_out_clear(&out, s.procs);
    net_free(net);
    net_topo_free(topo);
    sim_engine_free(eng);
    scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_merged_image_background),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
