/* test_pphigs_frame.c — the event-driven PPHIGS frame on a Pixel-Planes 5
 * machine built by the machine layer (test costs over the model): GP
 * processor time (traverse + transform busy) equals the analytic
 * traversal cost of each portion to the picosecond; every processor kind
 * is busy in its phases; every region reaches the frame buffer; the same
 * inputs give the same results twice; ring-slot packets are never faster than
 * the contention-free analytic transport; off-screen work sends nothing; the
 * host's edit traffic delays the GP it goes to (and a frame with nothing
 * to scan gives the host no request); a machine the frame cannot use (no
 * frame buffer or two included) is a located error.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/pphigs_frame.h"
#include <string.h>

/* Test costs (not the model's): a 4-vertex polygon 1 us on-screen,
 * 0.3 us rejected. */
static const char *const MACHINE =
    "model: pixel-planes-5\n"
    "nodes:\n"
    "  gp: {count: %u, costs: {polygon: 600 ns, vertex: 100 ns,\n"
    "       reject_vertex: 75 ns, color: 100 ns, matrix_replace: 300 ns,\n"
    "       matrix_concat: 1 us, execute: 500 ns, send_primitive: 1 us,\n"
    "       line: 400 ns, sphere: 500 ns}}\n"
    "  renderer: {count: 4, costs: {primitive: 8 us, region_begin: 50 us,\n"
    "             region_shade: 200 us}}\n"
    "  frame_buffer: {costs: {store_region: 10 us}}\n"
    "  host: {costs: {send_element: 20 us, scan_element: 2 us}}\n";

static const WlPphigsCosts C = {.poly = 600 * SIM_NS,
                                .vertex = 100 * SIM_NS,
                                .reject_vertex = 75 * SIM_NS,
                                .color = 100 * SIM_NS,
                                .matrix = 300 * SIM_NS,
                                .concat = SIM_US,
                                .execute = 500 * SIM_NS,
                                .line = 400 * SIM_NS,
                                .sphere = 500 * SIM_NS};

#define RENDERERS 4

static WlPphigsFrameSpec spec(void)
{
    WlPphigsFrameSpec s = {.cmd_bytes = 100,
                           .end_bytes = 16,
                           .batch = 16,
                           .pixel_bytes = 4,
                           .width = 640,
                           .height = 512,
                           .region = 128,
                           .element_bytes = 80};
    return s;
}

static MachMachine *machine(SimEngine *eng, guint ngp, const char *fid,
                            GError **err)
{
    char *text = g_strdup_printf(MACHINE, ngp);
    CfgNode *sec = cfg_load_string(text, "test-machine.yaml", NULL);
    assert_non_null(sec);
    MachMachine *m = mach_new_from_cfg(eng, sec, fid, err);
    cfg_free(sec);
    g_free(text);
    return m;
}

typedef struct {
    SimTime frame[2];
    double trav[16];
    uint64_t commands, bytes, messages, offscreen;
    double gp_util, rend_util;
} Run;

/* Per-phase busy of every processor kind, from mach_fill_result. */
static void check_result(MachMachine *m, guint ngp)
{
    SimResult *r = sim_result_new("pphigs", "test");
    mach_fill_result(m, r);
    assert_int_equal(r->nodes->len + sim_result_n_idle(r),
                     1 + ngp + RENDERERS + 1);
    static const char *const want[][3] = {{"gp", "transform", "send"},
                                          {"renderer", "rasterise", "shade"},
                                          {"frame_buffer", "store", "store"}};
    for (guint i = 0; i < r->nodes->len; i++) {
        SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        for (guint k = 0; k < G_N_ELEMENTS(want); k++) {
            if (strcmp(n->kind, want[k][0]) != 0)
                continue;
            for (guint ph = 0; ph < r->phases->len; ph++) {
                const char *name = g_ptr_array_index(r->phases, ph);
                if (!strcmp(name, want[k][1]) || !strcmp(name, want[k][2]))
                    assert_true(sim_busy_phase(&n->busy, ph) > 0);
            }
        }
    }
    sim_result_free(r);
}

static void run(const ScenePphigsDb *db, guint ngp, WlPphigsAlgo a,
                const char *fid, const WlPphigsFrameSpec *s, Run *out)
{
    SimEngine *eng = sim_engine_new(7);
    MachMachine *m = machine(eng, ngp, fid, NULL);
    assert_non_null(m);
    WlPphigsFrame *f = wl_pphigs_frame_new(m, s, NULL);
    assert_non_null(f);
    assert_int_equal(wl_pphigs_frame_gps(f), ngp);
    assert_memory_equal(wl_pphigs_frame_costs(f), &C, sizeof C);
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(&C, 8, &w);
    WlPphigsDist *d = wl_pphigs_dist_new(db->db, ngp, a, &w);
    Mat4 vp = scene_camera_view_proj(&db->camera);
    for (int k = 0; k < 2; k++) {
        WlPphigsFrameStats st;
        assert_true(wl_pphigs_frame_run(f, d, vp, NULL, &st, NULL));
        out->frame[k] = st.time;
        out->commands = st.commands;
        out->offscreen = st.offscreen;
        for (guint g = 0; g < ngp; g++)
            out->trav[g] = st.gp_time_us[g];
    }
    NetNet *net = mach_net(m);
    out->bytes = net_total_bytes(net);
    out->messages = net_total_messages(net);
    wl_pphigs_frame_util(f, sim_now(eng), &out->gp_util, &out->rend_util);
    if (out->commands) /* else no GP sends, no renderer rasterises */
        check_result(m, ngp);
    wl_pphigs_frame_free(f);
    mach_free(m);
    sim_engine_free(eng);
    wl_pphigs_dist_free(d);
}

static ScenePphigsDb make_db(ScenePphigsKind k)
{
    ScenePphigsSpec s = {.kind = k,
                         .seed = 2,
                         .polygons = 600,
                         .attributes = 60,
                         .verts = 4,
                         .size = 100,
                         .fov_deg = 51,
                         .boids = 30,
                         .boid_polygons = 5,
                         .boid_colors = 4,
                         .well_structs = 10,
                         .well_polygons = 60,
                         .well_attributes = 5};
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
        run(&db, 4, WL_PPHIGS_COMPLEX, "packet", &s, &r);
        WlPphigsWeights w;
        wl_pphigs_weights_from_costs(&C, 8, &w);
        WlPphigsDist *d = wl_pphigs_dist_new(db.db, 4, WL_PPHIGS_COMPLEX, &w);
        Mat4 vp = scene_camera_view_proj(&db.camera);
        for (guint g = 0; g < 4; g++) {
            double a = sim_time_to_us(
                wl_pphigs_traversal_cost(wl_pphigs_dist_gp(d, g), vp, &C));
            assert_true(a > 0);
            assert_true(r.trav[g] == a); /* exact: integer picoseconds */
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
    run(&db, 4, WL_PPHIGS_SIMPLE, "packet", &s, &a);
    run(&db, 4, WL_PPHIGS_SIMPLE, "packet", &s, &b);
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
    run(&db, 4, WL_PPHIGS_COMPLEX, "packet", &s, &pk);
    run(&db, 4, WL_PPHIGS_COMPLEX, "analytic", &s, &an);
    assert_true(pk.frame[0] >= an.frame[0]);
    assert_int_equal(pk.bytes, an.bytes);
    /* 2 frames: commands, 20 regions of 128x128x4 bytes, end markers */
    guint regions = 5 * 4;
    uint64_t want =
        2 * (pk.commands * s.cmd_bytes + (uint64_t)regions * 128 * 128 * 4 +
             4 * RENDERERS * s.end_bytes);
    assert_int_equal(pk.bytes, want);
    /* fewer, larger batches: fewer messages, same bytes */
    WlPphigsFrameSpec big = s;
    big.batch = 1000;
    Run bb = {0};
    run(&db, 4, WL_PPHIGS_COMPLEX, "packet", &big, &bb);
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
    run(&db, 4, WL_PPHIGS_COMPLEX, "analytic", &s, &r);
    assert_true(r.offscreen > 0);
    /* look away: every primitive is off-screen, no command is sent */
    db.camera.target =
        vec3_scale(vec3_sub(db.camera.eye, db.camera.target), 1.0);
    db.camera.target = vec3_add(db.camera.eye, db.camera.target);
    Run away = {0};
    run(&db, 4, WL_PPHIGS_COMPLEX, "analytic", &s, &away);
    assert_int_equal(away.commands, 0);
    assert_true(away.offscreen > r.offscreen);
    scene_pphigs_db_clear(&db);
}

/* Elements the host sends before a frame: packed on the host (phase
 * "edit") after its step back over the elements it examined, carried by
 * the ring, and the GP that gets them starts late. */
static void test_host_edits(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db(SCENE_PPHIGS_STATION);
    WlPphigsFrameSpec s = spec();
    SimTime t[2];
    uint64_t bytes[2];
    for (int k = 0; k < 2; k++) {
        SimEngine *eng = sim_engine_new(7);
        MachMachine *m = machine(eng, 4, "analytic", NULL);
        WlPphigsFrame *f = wl_pphigs_frame_new(m, &s, NULL);
        WlPphigsWeights w;
        wl_pphigs_weights_from_costs(&C, 8, &w);
        WlPphigsDist *d = wl_pphigs_dist_new(db.db, 4, WL_PPHIGS_COMPLEX, &w);
        uint64_t elems[4] = {0, 500, 0, 0};
        WlPphigsFrameStats fs;
        if (k)
            wl_pphigs_frame_host_scan(f, 300);
        assert_true(wl_pphigs_frame_run(f, d,
                                        scene_camera_view_proj(&db.camera),
                                        k ? elems : NULL, &fs, NULL));
        t[k] = fs.time;
        bytes[k] = net_total_bytes(mach_net(m));
        assert_int_equal(fs.host_elements, k ? 500 : 0);
        MachProc *host = mach_proc(m, "host", 0);
        unsigned edit = sim_engine_phase(eng, "edit");
        assert_int_equal(mach_proc_busy_phase(host, edit),
                         k ? (500 * 20 + 300 * 2) * SIM_US : 0);
        /* one scan and one packing with edits; nothing to scan or send
         * submits no host work at all (not even a zero-time request) */
        assert_int_equal(mach_proc_requests(host), k ? 2 : 0);
        wl_pphigs_dist_free(d);
        wl_pphigs_frame_free(f);
        mach_free(m);
        sim_engine_free(eng);
    }
    assert_int_equal(bytes[1] - bytes[0], 500 * s.element_bytes);
    assert_true(t[1] >= t[0] + (500 * 20 + 300 * 2) * SIM_US); /* gp1 waited */
    scene_pphigs_db_clear(&db);
}

/* A machine the frame cannot use is a located error, not a crash. */
static void expect_bad_machine(const char *over, const char *needle)
{
    SimEngine *eng = sim_engine_new(1);
    char *text = g_strdup_printf(MACHINE, 4u);
    CfgNode *sec = cfg_load_string(text, "test-machine.yaml", NULL);
    assert_true(cfg_set_override(sec, over, NULL));
    MachMachine *m = mach_new_from_cfg(eng, sec, "analytic", NULL);
    assert_non_null(m);
    GError *err = NULL;
    WlPphigsFrameSpec s = spec();
    assert_null(wl_pphigs_frame_new(m, &s, &err));
    assert_non_null(err);
    assert_non_null(strstr(err->message, needle));
    assert_non_null(strstr(err->message, ":"));
    g_error_free(err);
    mach_free(m);
    cfg_free(sec);
    g_free(text);
    sim_engine_free(eng);
}

static void test_bad_machine(void **st)
{
    (void)st;
    expect_bad_machine("nodes.gp.count=65", "65 gp processors");
    /* exactly one frame buffer: none is as wrong as two */
    expect_bad_machine("nodes.frame_buffer.count=2",
                       "2 frame_buffer processors");
    expect_bad_machine("nodes.frame_buffer.count=0",
                       "0 frame_buffer processors");
    expect_bad_machine("nodes.frame_buffer.count=0",
                       "1 .. 1 frame_buffer processors");
    expect_bad_machine("nodes.renderer.count=0", "0 renderer processors");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_traverse_equals_analytic),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_traffic_and_fidelity),
        cmocka_unit_test(test_offscreen_sends_nothing),
        cmocka_unit_test(test_host_edits),
        cmocka_unit_test(test_bad_machine),
    };
    return cmocka_run_group_tests_name("pphigs_frame", tests, NULL, NULL);
}
