/* test_pphigs_frame.c — the event-driven PPHIGS frame on a Pixel-Planes 5
 * ring: GP traverse time equals the analytic traversal cost of each
 * portion; every region reaches the frame buffer; the same inputs give
 * the same results twice; ring-slot packets are never faster than the
 * contention-free analytic transport; off-screen work sends nothing.
 * Parameters here are test values, not the model's.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/frame.h"

static const WlPphigsCosts C = {.poly = 0.6, .vertex = 0.1,
                                .offscreen = 0.3, .color = 0.1,
                                .matrix = 0.3, .concat = 1, .execute = 0.5};

static WlPphigsFrameSpec spec(void)
{
    WlPphigsFrameSpec s = {
        .gp = C, .gp_send = SIM_US, .rend_prim = 8 * SIM_US,
        .rend_begin = 50 * SIM_US, .rend_shade = 200 * SIM_US,
        .fb_store = 10 * SIM_US, .cmd_bytes = 100, .end_bytes = 16,
        .batch = 16, .pixel_bytes = 4, .width = 640, .height = 512,
        .region = 128, .renderers = 4};
    return s;
}

static NetParams ring_params(void)
{
    NetParams p = {0};
    p.bandwidth = 80e6;
    p.channels = 8;
    p.startup = 5 * SIM_US;
    p.per_hop = 50 * SIM_NS;
    p.packet_bytes = 1024;
    p.switching = NET_SW_RING_SLOTS;
    return p;
}

typedef struct {
    SimTime frame[2];
    double trav[16];
    uint64_t commands, bytes, messages, offscreen;
    double gp_util, rend_util;
} Run;

static void run(const ScenePphigsDb *db, guint ngp, WlPphigsAlgo a,
                NetFidelity fid, const WlPphigsFrameSpec *s, Run *out)
{
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(&C, 8, &w);
    WlPphigsDist *d = wl_pphigs_dist_new(db->db, ngp, a, &w);
    SimEngine *eng = sim_engine_new(7);
    NetTopo *t = net_ring_new(wl_pphigs_frame_stations(ngp, s->renderers));
    NetParams p = ring_params();
    NetNet *net = net_new(eng, t, &p, fid);
    WlPphigsFrame *f = wl_pphigs_frame_new(eng, net, ngp, s);
    Mat4 vp = scene_camera_view_proj(&db->camera);
    for (int k = 0; k < 2; k++) {
        WlPphigsFrameStats st;
        assert_true(wl_pphigs_frame_run(f, d, vp, &st, NULL));
        out->frame[k] = st.time;
        out->commands = st.commands;
        out->offscreen = st.offscreen;
        for (guint g = 0; g < ngp; g++)
            out->trav[g] = st.gp_traverse_us[g];
    }
    out->bytes = net_total_bytes(net);
    out->messages = net_total_messages(net);
    wl_pphigs_frame_util(f, sim_now(eng), &out->gp_util, &out->rend_util);
    SimResult *r = sim_result_new("pphigs", "test");
    wl_pphigs_frame_fill_result(f, r);
    assert_int_equal(r->nodes->len, ngp + s->renderers + 1);
    sim_result_free(r);
    wl_pphigs_frame_free(f);
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
    wl_pphigs_dist_free(d);
}

static ScenePphigsDb make_db(ScenePphigsKind k)
{
    ScenePphigsSpec s = {.kind = k, .seed = 2, .polygons = 600,
                         .attributes = 60, .verts = 4, .size = 100,
                         .fov_deg = 51, .boids = 30, .boid_polygons = 5,
                         .boid_colors = 4, .well_structs = 10,
                         .well_polygons = 60, .well_attributes = 5};
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    return db;
}

static void test_traverse_equals_analytic(void **st)
{
    (void)st;
    for (int k = SCENE_PPHIGS_STATION; k <= SCENE_PPHIGS_FLOCK; k++) {
        ScenePphigsDb db = make_db((ScenePphigsKind)k);
        WlPphigsFrameSpec s = spec();
        Run r;
        run(&db, 4, WL_PPHIGS_COMPLEX, NET_PACKET, &s, &r);
        WlPphigsWeights w;
        wl_pphigs_weights_from_costs(&C, 8, &w);
        WlPphigsDist *d = wl_pphigs_dist_new(db.db, 4, WL_PPHIGS_COMPLEX, &w);
        Mat4 vp = scene_camera_view_proj(&db.camera);
        for (guint g = 0; g < 4; g++) {
            double a = wl_pphigs_traversal_us(wl_pphigs_dist_gp(d, g), vp, &C);
            assert_true(a > 0);
            assert_true(fabs(r.trav[g] - a) < 1e-9 * a);
        }
        assert_true(r.commands > 0);
        /* the frame is at least the slowest GP's traversal */
        double max = 0;
        for (guint g = 0; g < 4; g++)
            max = MAX(max, r.trav[g]);
        assert_true(sim_time_to_us(r.frame[0]) > max);
        assert_true(r.gp_util > 0 && r.gp_util <= 1);
        assert_true(r.rend_util > 0 && r.rend_util <= 1);
        wl_pphigs_dist_free(d);
        scene_pphigs_db_clear(&db);
    }
}

static void test_deterministic(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db(SCENE_PPHIGS_FLOCK);
    WlPphigsFrameSpec s = spec();
    Run a = {0}, b = {0};
    run(&db, 4, WL_PPHIGS_SIMPLE, NET_PACKET, &s, &a);
    run(&db, 4, WL_PPHIGS_SIMPLE, NET_PACKET, &s, &b);
    assert_memory_equal(&a, &b, sizeof a);
    /* the same portions twice: the second frame is as long as the first */
    assert_true(a.frame[0] == a.frame[1]);
    scene_pphigs_db_clear(&db);
}

static void test_traffic_and_fidelity(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db(SCENE_PPHIGS_STATION);
    WlPphigsFrameSpec s = spec();
    Run pk = {0}, an = {0};
    run(&db, 4, WL_PPHIGS_COMPLEX, NET_PACKET, &s, &pk);
    run(&db, 4, WL_PPHIGS_COMPLEX, NET_ANALYTIC, &s, &an);
    assert_true(pk.frame[0] >= an.frame[0]);
    assert_int_equal(pk.bytes, an.bytes);
    /* 2 frames: commands, 20 regions of 128x128x4 bytes, end markers */
    guint regions = 5 * 4;
    uint64_t want = 2 * (pk.commands * s.cmd_bytes +
                         (uint64_t)regions * 128 * 128 * 4 +
                         4 * s.renderers * s.end_bytes);
    assert_int_equal(pk.bytes, want);
    /* fewer, larger batches: fewer messages, same bytes */
    WlPphigsFrameSpec big = s;
    big.batch = 1000;
    Run bb = {0};
    run(&db, 4, WL_PPHIGS_COMPLEX, NET_PACKET, &big, &bb);
    assert_int_equal(bb.bytes, pk.bytes);
    assert_true(bb.messages < pk.messages);
    scene_pphigs_db_clear(&db);
}

static void test_offscreen_sends_nothing(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db(SCENE_PPHIGS_LOBBY);
    WlPphigsFrameSpec s = spec();
    Run r = {0};
    run(&db, 4, WL_PPHIGS_COMPLEX, NET_ANALYTIC, &s, &r);
    assert_true(r.offscreen > 0);
    /* look away: every primitive is off-screen, no command is sent */
    db.camera.target = vec3_scale(vec3_sub(db.camera.eye, db.camera.target),
                                  1.0);
    db.camera.target = vec3_add(db.camera.eye, db.camera.target);
    Run away = {0};
    run(&db, 4, WL_PPHIGS_COMPLEX, NET_ANALYTIC, &s, &away);
    assert_int_equal(away.commands, 0);
    assert_true(away.offscreen > r.offscreen);
    scene_pphigs_db_clear(&db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_traverse_equals_analytic),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_traffic_and_fidelity),
        cmocka_unit_test(test_offscreen_sends_nothing),
    };
    return cmocka_run_group_tests_name("pphigs_frame", tests, NULL, NULL);
}
