/* test_pphigs_frame_exact.c — one PPHIGS frame (seed 001 §1.1) on a
 * 300 x 200 screen of 128-pixel regions (3 x 2, the right and bottom ones
 * partial), three triangles on GP 0 of 2, every count worked out by
 * hand: commands per region touched, batches (a full batch goes at once,
 * the rest at the end), end markers, region stores and their bytes
 * (partial regions send only their pixels), expressions, and each
 * processor kind's busy time from the machine's costs.  The frame's
 * image is the serial render's; a second frame counts afresh.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pphigs/pphigs_frame.h"
#include "sim/workload/pphigs/pphigs_pixels.h"

static const char *const PP5 =
    "model: pixel-planes-5\n"
    "nodes:\n"
    "  gp: {count: 2, costs: {polygon: 600 ns, vertex: 100 ns,\n"
    "       reject_vertex: 75 ns, send_primitive: 1 us}}\n"
    "  renderer: {count: 4, costs: {expression: 100 ns, compare: 1 us,\n"
    "             region_begin: 50 us, region_shade: 200 us}}\n"
    "  frame_buffer: {costs: {store_region: 10 us}}\n";

/* a: the whole screen (6 regions); b, c: inside region 0; d: off. */
static SceneDb *three_db(void)
{
    static const double xy[4][6] = {{-3, -3, 3, -3, 0, 3},
                                    {-0.9, 0.9, -0.8, 0.9, -0.9, 0.8},
                                    {-0.7, 0.9, -0.6, 0.9, -0.7, 0.8},
                                    {5, 0, 6, 0, 5, 1}};
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "three");
    for (guint k = 0; k < 4; k++) {
        Vec3 v[3];
        for (guint i = 0; i < 3; i++)
            v[i] = vec3(xy[k][2 * i], xy[k][2 * i + 1], 0);
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(scene_db_append(db, s, &e, NULL));
    }
    scene_db_post(db, s);
    return db;
}

static SimTime cost(const MachMachine *m, const char *kind, const char *op)
{
    SimTime t = 0;
    assert_true(mach_cost_lookup(m, kind, op, &t, NULL));
    return t;
}

static SimTime busy_of(MachMachine *m, const char *kind, guint n)
{
    SimTime t = 0;
    for (guint i = 0; i < n; i++)
        t += mach_proc_busy(mach_proc(m, kind, i));
    return t;
}

static void test_frame_counts(void **st)
{
    (void)st;
    SimEngine *eng = sim_engine_new(1);
    CfgNode *sec = cfg_load_string(PP5, "pp5.yaml", NULL);
    assert_non_null(sec);
    MachMachine *m = mach_new_from_cfg(eng, sec, "analytic", NULL);
    assert_non_null(m);
    WlPphigsFrameSpec s = {.cmd_bytes = 100, .end_bytes = 16, .batch = 2,
                           .pixel_bytes = 4, .width = 300, .height = 200,
                           .region = 128, .element_bytes = 80};
    WlPphigsFrame *f = wl_pphigs_frame_new(m, &s, NULL);
    assert_non_null(f);
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(wl_pphigs_frame_costs(f), 100, &w);
    SceneDb *db = three_db();
    WlPphigsDist *d = wl_pphigs_dist_new(db, 2, WL_PPHIGS_COMPLEX, &w);
    assert_int_equal(scene_db_len(wl_pphigs_dist_gp(d, 0), 0), 4);
    SimTime rend0 = 0;
    for (int k = 0; k < 2; k++) {
        WlPphigsFrameStats fs;
        assert_true(wl_pphigs_frame_run(f, d, mat4_identity(), NULL, &fs, NULL));
        /* a in 6 regions, b and c in region 0 */
        assert_int_equal(fs.commands, 8);
        assert_int_equal(fs.primitives, 4);
        assert_int_equal(fs.offscreen, 1);
        assert_int_equal(fs.host_elements, 0);
        assert_int_equal(fs.expressions, 8 * (3 + 1 + 3));
        /* GP 0: 3 triangles of 0.9 us and a rejected one of 0.225 us */
        assert_true(fs.gp_time_us[0] == sim_time_to_us(3 * 900 * SIM_NS +
                                                       225 * SIM_NS));
        assert_true(fs.gp_time_us[1] == 0);
        /* batches: region 0 a b (full), then c; regions 1-5 one each:
         * 7; end markers 2 GPs x 4 renderers; 6 regions stored */
        NetNet *net = mach_net(m);
        assert_int_equal(net_total_messages(net), (uint64_t)(k + 1) * 21);
        assert_int_equal(net_total_bytes(net),
                         (uint64_t)(k + 1) * (8 * 100 + 8 * 16 + 300 * 200 * 4));
        /* renderers: 6 regions begun and shaded, 56 expressions, 8
         * compares; the frame buffer: 6 stores; GP 0 sends 8 */
        SimTime rend = 6 * (cost(m, "renderer", "region_begin") +
                            cost(m, "renderer", "region_shade")) +
                       56 * cost(m, "renderer", "expression") +
                       8 * cost(m, "renderer", "compare");
        assert_int_equal(rend, 6 * 250 * SIM_US + 56 * 100 * SIM_NS + 8 * SIM_US);
        assert_int_equal(busy_of(m, "renderer", 4) - rend0, rend);
        rend0 += rend;
        assert_int_equal(busy_of(m, "frame_buffer", 1),
                         (SimTime)(k + 1) * 6 * 10 * SIM_US);
        assert_int_equal(mach_proc_busy(mach_proc(m, "gp", 0)),
                         (SimTime)(k + 1) * (8 * SIM_US + 2925 * SIM_NS));
        assert_int_equal(mach_proc_busy(mach_proc(m, "gp", 1)), 0);
        if (!k)
            assert_int_equal(fs.time, sim_now(eng));
        RastImage *ref = wl_pphigs_render_serial(wl_pphigs_dist_host(d),
                                                 mat4_identity(), 300, 200);
        assert_true(rast_image_equal(wl_pphigs_frame_image(f), ref));
        rast_image_free(ref);
    }
    double gu, ru;
    SimTime now = sim_now(eng);
    wl_pphigs_frame_util(f, now, &gu, &ru);
    assert_true(fabs(gu - (double)(2 * (8 * SIM_US + 2925 * SIM_NS)) / now / 2) < 1e-12);
    assert_true(fabs(ru - (double)rend0 / now / 4) < 1e-12);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
    wl_pphigs_frame_free(f);
    mach_free(m);
    cfg_free(sec);
    sim_engine_free(eng);
}

/* The ends of the processor counts a frame takes: 64 GPs (one bit each
 * in the distribution's masks) and a single renderer are accepted. */
static void test_count_ends(void **st)
{
    (void)st;
    static const char *const over[] = {"nodes.gp.count=64",
                                       "nodes.renderer.count=1"};
    for (guint i = 0; i < G_N_ELEMENTS(over); i++) {
        SimEngine *eng = sim_engine_new(1);
        CfgNode *sec = cfg_load_string(PP5, "pp5.yaml", NULL);
        assert_true(cfg_set_override(sec, over[i], NULL));
        MachMachine *m = mach_new_from_cfg(eng, sec, "analytic", NULL);
        assert_non_null(m);
        WlPphigsFrameSpec s = {.cmd_bytes = 1, .end_bytes = 1, .batch = 1,
                               .pixel_bytes = 1, .width = 8, .height = 8,
                               .region = 8, .element_bytes = 1};
        GError *err = NULL;
        WlPphigsFrame *f = wl_pphigs_frame_new(m, &s, &err);
        if (!f)
            fail_msg("%s: %s", over[i], err->message);
        assert_int_equal(wl_pphigs_frame_gps(f), i ? 2 : 64);
        wl_pphigs_frame_free(f);
        mach_free(m);
        cfg_free(sec);
        sim_engine_free(eng);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frame_counts),
        cmocka_unit_test(test_count_ends),
    };
    return cmocka_run_group_tests_name("pphigs_frame_exact", tests, NULL, NULL);
}
