/* test_performer.c — IRIS Performer's frame pipeline and scene graph
 * (seed 002, slides "libpf"), each check beside the case where its cause
 * is removed:
 *   - DRAW locked and extending past a boundary halves the frame rate;
 *     floating, the same DRAW does not;
 *   - an APP that extends drops the frame rate although CULL and DRAW
 *     keep up; a short APP does not;
 *   - pipelining trades latency for throughput (three processes keep
 *     the rate that one process loses, at a longer latency);
 *   - stress-feedback LOD reacts one frame late (one process) or later
 *     (pipelined), and with a high gain oscillates where a low gain
 *     settles;
 *   - culling removes exactly the triangles it counted, pfFlatten the
 *     matrix operations it counted, lazy pfGeoState the state changes it
 *     counted, and DRAW's CPU time drops by those counts times the
 *     model's costs.
 * Run from the repository root (models/sgi-onyx.yaml).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/performer/pf_stages.h"
#include "sim/workload/performer/pf_workload.h"
#include "tests/support.h"

/* ---- the pipeline with synthetic stage costs --------------------------- */

#define T_US 33333 /* about one frame at 30 Hz; V = T / 2 */

typedef struct {
    double app, cull, draw; /* in frames (T) */
    guint step_frame;       /* from this frame on, DRAW load x step */
    double step;
    gboolean stress_divides; /* DRAW load / stress (LOD lowers it) */
} Synth;

#define SY(a, c, d)                                                            \
    {                                                                          \
        .app = (a), .cull = (c), .draw = (d)                                   \
    }

static SimTime in_t(double frames)
{
    return (SimTime)(frames * 2 * T_US / 2) * SIM_US;
}

static SimTime s_app(void *ctx, guint n)
{
    (void)n;
    return in_t(((Synth *)ctx)->app);
}
static double last_stress;
static SimTime s_cull(void *ctx, guint n, double stress)
{
    (void)ctx;
    (void)n;
    last_stress = stress;
    return in_t(((Synth *)ctx)->cull);
}
static SimTime s_draw(void *ctx, guint n)
{
    Synth *s = ctx;
    double d = s->draw * (s->step_frame && n >= s->step_frame ? s->step : 1);
    if (s->stress_divides)
        d /= last_stress;
    return in_t(d);
}

static WlPfPipeParams params(WlPfMpMode mode, gboolean locked, guint frames)
{
    return (WlPfPipeParams){.mode = mode,
                            .video = (SimTime)T_US / 2 * SIM_US,
                            .per_frame = 2,
                            .locked = locked,
                            .low = 0.7,
                            .high = 0.9,
                            .gain = 0.5,
                            .max_stress = 8,
                            .frames = frames};
}

/* Runs the synthetic pipeline; returns the records (g_array_free). */
static GArray *run_synth(const WlPfPipeParams *p, Synth *s)
{
    SimEngine *eng = sim_engine_new(1);
    GError *err = NULL;
    MachMachine *m = mach_new_from_model(eng, "sgi-onyx", "analytic", &err);
    if (!m)
        fail_msg("%s", err->message);
    MachProc *procs[4];
    for (guint i = 0; i < 4; i++)
        procs[i] = mach_proc(m, "cpu", i);
    WlPfStageFns f = {.app = s_app, .cull = s_cull, .draw = s_draw};
    GArray *recs = g_array_new(FALSE, TRUE, sizeof(WlPfFrameRec));
    last_stress = 1;
    assert_true(wl_pf_pipe_run(eng, procs, p, &f, s, recs, SIM_TIME_MAX, &err));
    mach_free(m);
    sim_engine_free(eng);
    return recs;
}

/* Frames per frame boundary actually shown (1 = the target rate). */
static double rate_ratio(const WlPfPipeParams *p, Synth *s)
{
    GArray *r = run_synth(p, s);
    double iv = wl_pf_mean_interval_s(r, 4);
    g_array_free(r, TRUE);
    return sim_time_to_s(p->video * p->per_frame) / iv;
}

static void test_locked_draw_halves_rate(void **st)
{
    (void)st;
    Synth ok = SY(0.1, 0.1, 0.9), longer = SY(0.1, 0.1, 1.1);
    WlPfPipeParams lk = params(WL_PF_MP_APP_CULL_DRAW, TRUE, 40);
    WlPfPipeParams fl = params(WL_PF_MP_APP_CULL_DRAW, FALSE, 40);
    assert_float_equal(rate_ratio(&lk, &ok), 1.0, 1e-9);
    assert_float_equal(rate_ratio(&lk, &longer), 0.5, 1e-9);
    /* floating: swaps at the next retrace, 1.5 T per frame, not 2 T */
    assert_float_equal(rate_ratio(&fl, &longer), 2.0 / 3.0, 1e-9);
}

static void test_app_extends_drops_rate(void **st)
{
    (void)st;
    Synth keep = SY(0.8, 0.3, 0.5), extend = SY(1.2, 0.3, 0.5);
    WlPfPipeParams p = params(WL_PF_MP_APP_CULL_DRAW, TRUE, 40);
    assert_float_equal(rate_ratio(&p, &keep), 1.0, 1e-9);
    assert_float_equal(rate_ratio(&p, &extend), 0.5, 1e-9);
    /* CULL and DRAW kept up: each took under half a frame */
    GArray *r = run_synth(&p, &extend);
    const WlPfFrameRec *f = &g_array_index(r, WlPfFrameRec, 10);
    assert_true(f->draw_end - f->draw_start < in_t(0.6));
    g_array_free(r, TRUE);
}

static void test_latency_vs_throughput(void **st)
{
    (void)st;
    Synth s = SY(0.4, 0.4, 0.4);
    WlPfPipeParams one = params(WL_PF_MP_APPCULLDRAW, FALSE, 40);
    WlPfPipeParams three = params(WL_PF_MP_APP_CULL_DRAW, FALSE, 40);
    GArray *a = run_synth(&one, &s), *b = run_synth(&three, &s);
    double T = sim_time_to_s(one.video * one.per_frame);
    /* one process: 1.2 T of work per frame -> every other boundary */
    assert_float_equal(wl_pf_mean_interval_s(a, 4), 2 * T, 1e-9);
    /* three processes keep every boundary ... */
    assert_float_equal(wl_pf_mean_interval_s(b, 4), T, 1e-9);
    /* ... and each frame takes longer from APP to the screen */
    assert_true(wl_pf_mean_latency_s(b, 4) > 1.4 * T);
    assert_true(wl_pf_mean_latency_s(b, 4) > wl_pf_mean_latency_s(a, 4) - T);
    g_array_free(a, TRUE);
    g_array_free(b, TRUE);
}

/* First frame whose CULL used a stress above 1. */
static guint first_stressed(const GArray *r)
{
    for (guint i = 0; i < r->len; i++)
        if (g_array_index(r, WlPfFrameRec, i).stress > 1)
            return i;
    return G_MAXUINT;
}

static void test_stress_one_frame_late(void **st)
{
    (void)st;
    Synth s = {0.1, 0.1, 0.5, 10, 2.0, TRUE}; /* load 0.5 -> 1.0 at 10 */
    WlPfPipeParams one = params(WL_PF_MP_APPCULLDRAW, FALSE, 30);
    WlPfPipeParams three = params(WL_PF_MP_APP_CULL_DRAW, FALSE, 30);
    one.stress = three.stress = TRUE;
    GArray *a = run_synth(&one, &s);
    assert_int_equal(first_stressed(a), 11); /* overload at 10, react 11 */
    g_array_free(a, TRUE);
    GArray *b = run_synth(&three, &s);
    assert_true(first_stressed(b) >= 12); /* pipelined: later still */
    assert_true(first_stressed(b) != G_MAXUINT);
    g_array_free(b, TRUE);
    /* without stress feedback nothing reacts */
    one.stress = FALSE;
    a = run_synth(&one, &s);
    assert_int_equal(first_stressed(a), G_MAXUINT);
    g_array_free(a, TRUE);
}

/* Direction changes of the stress over frames [from, to). */
static guint reversals(const GArray *r, guint from)
{
    guint c = 0;
    int last = 0;
    for (guint i = from + 1; i < r->len; i++) {
        double d = g_array_index(r, WlPfFrameRec, i).stress -
                   g_array_index(r, WlPfFrameRec, i - 1).stress;
        int sgn = d > 1e-12 ? 1 : d < -1e-12 ? -1 : 0;
        if (sgn && last && sgn != last)
            c++;
        if (sgn)
            last = sgn;
    }
    return c;
}

static void test_stress_high_gain_oscillates(void **st)
{
    (void)st;
    Synth s = {0.1, 0.1, 1.6, 0, 1, TRUE}; /* DRAW needs stress 2 */
    WlPfPipeParams p = params(WL_PF_MP_APPCULLDRAW, FALSE, 80);
    p.stress = TRUE;
    p.gain = 0.3;
    GArray *low = run_synth(&p, &s);
    p.gain = 6;
    GArray *high = run_synth(&p, &s);
    assert_true(reversals(low, 40) <= 1);
    assert_true(reversals(high, 40) >= 10);
    g_array_free(low, TRUE);
    g_array_free(high, TRUE);
}

/* ---- the scene graph on the town --------------------------------------- */

static WlPfCosts onyx_costs(void)
{
    SimEngine *eng = sim_engine_new(1);
    GError *err = NULL;
    MachMachine *m = mach_new_from_model(eng, "sgi-onyx", "analytic", &err);
    assert_non_null(m);
    WlPfCosts c;
    assert_true(wl_pf_costs_read(m, 32, &c, &err));
    mach_free(m);
    sim_engine_free(eng);
    return c;
}

static WlPfTown *small_town(void)
{
    WlPfTownParams p = wl_pf_town_defaults();
    p.blocks = 5;
    return wl_pf_town_new(&p);
}

static void cull_draw(WlPfTown *t, guint frame, gboolean cull,
                      WlPfCullStats *cs, WlPfDrawStats *ds)
{
    SceneCamera cam = wl_pf_town_camera(t, frame, 0);
    WlPfView v = wl_pf_view(&cam, 1.0, cull);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    memset(cs, 0, sizeof *cs);
    memset(ds, 0, sizeof *ds);
    wl_pf_cull(t->g, &v, dl, cs);
    wl_pf_draw(t->g, dl, ds);
    g_array_free(dl, TRUE);
}

static void test_culling_saves_what_it_counts(void **st)
{
    (void)st;
    WlPfCosts c = onyx_costs();
    WlPfTown *t = small_town();
    for (guint f = 0; f < 200; f += 50) {
        WlPfCullStats on_c, off_c;
        WlPfDrawStats on_d, off_d;
        cull_draw(t, f, TRUE, &on_c, &on_d);
        cull_draw(t, f, FALSE, &off_c, &off_d);
        assert_true(on_c.tris_culled > 0);
        assert_int_equal(off_d.tris - on_d.tris, on_c.tris_culled);
        assert_int_equal(off_c.tris_culled, 0);
        SimTime saved =
            wl_pf_draw_cpu(&c, &off_d, TRUE) - wl_pf_draw_cpu(&c, &on_d, TRUE);
        assert_true(saved >= 3 * on_c.tris_culled * c.draw_vertex);
    }
    wl_pf_town_free(t);
}

static void test_flatten_saves_what_it_counts(void **st)
{
    (void)st;
    WlPfCosts c = onyx_costs();
    WlPfTown *a = small_town(), *b = small_town();
    guint scs = wl_pf_count_kind(b->g, WL_PF_SCS);
    assert_int_equal(wl_pf_flatten(b->g), scs); /* houses are static */
    assert_int_equal(wl_pf_count_kind(b->g, WL_PF_SCS), 0);
    assert_int_equal(wl_pf_count_kind(b->g, WL_PF_DCS), a->cars->len);
    for (guint f = 0; f < 200; f += 50) {
        WlPfCullStats ca, cb;
        WlPfDrawStats da, db;
        cull_draw(a, f, TRUE, &ca, &da);
        cull_draw(b, f, TRUE, &cb, &db);
        assert_true(cb.matrix_saved > 0);
        assert_int_equal(ca.matrix_saved, 0);
        assert_int_equal(da.matrix_ops - db.matrix_ops, cb.matrix_saved);
        assert_int_equal(da.tris, db.tris); /* same picture */
        assert_int_equal(da.state_changes, db.state_changes);
        assert_int_equal(wl_pf_draw_cpu(&c, &da, TRUE) -
                             wl_pf_draw_cpu(&c, &db, TRUE),
                         cb.matrix_saved * c.draw_matrix);
    }
    wl_pf_town_free(a);
    wl_pf_town_free(b);
}

static void test_lazy_state_saves_what_it_counts(void **st)
{
    (void)st;
    WlPfCosts c = onyx_costs();
    WlPfTown *t = small_town();
    WlPfCullStats cs;
    WlPfDrawStats ds;
    cull_draw(t, 0, TRUE, &cs, &ds);
    assert_true(ds.state_changes < ds.state_naive);
    assert_int_equal(ds.state_naive, 3 * ds.geosets);
    assert_int_equal(wl_pf_draw_cpu(&c, &ds, FALSE) -
                         wl_pf_draw_cpu(&c, &ds, TRUE),
                     (ds.state_naive - ds.state_changes) * c.draw_state);
    wl_pf_town_free(t);
}

/* Masks and switches: a node without the CULL bit vanishes from DRAW;
 * switching lamps off removes their triangles. */
static void test_masks_and_switches(void **st)
{
    (void)st;
    WlPfTown *t = small_town();
    WlPfCullStats cs;
    WlPfDrawStats before, after;
    cull_draw(t, 0, FALSE, &cs, &before);
    guint off = 0;
    for (guint i = 0; i < t->g->nodes->len; i++) {
        WlPfNode *n = wl_pf_node(t->g, i);
        if (n->kind == WL_PF_BILLBOARD)
            n->mask &= ~(guint32)WL_PF_MASK_CULL;
        if (n->kind == WL_PF_SWITCH && n->which == WL_PF_SWITCH_ALL) {
            n->which = WL_PF_SWITCH_NONE;
            off++;
        }
    }
    cull_draw(t, 0, FALSE, &cs, &after);
    guint trees = t->p.trees * t->p.blocks * t->p.blocks * 2;
    guint lamps = off * 4 * 12;
    assert_int_equal(before.tris - after.tris, trees + lamps);
    assert_int_equal(cs.billboards, 0);
    wl_pf_town_free(t);
}

/* ISECT finds the terrain under the eye. */
static void test_isect_finds_ground(void **st)
{
    (void)st;
    WlPfTown *t = small_town();
    for (guint f = 0; f < 150; f += 37) {
        SceneCamera c = wl_pf_town_camera(t, f, 0);
        WlPfIsectStats is = {0};
        wl_pf_isect(t->g, c.eye.x + 0.37, c.eye.z + 0.11, -100, 100, &is);
        assert_true(is.hit);
        assert_true(is.tris_tested < 2000); /* spheres pruned the rest */
        assert_true(fabs(is.height - wl_pf_town_height(c.eye.x + 0.37,
                                                       c.eye.z + 0.11)) < 0.3);
    }
    wl_pf_town_free(t);
}

/* ---- PN triangles as geometry compression ------------------------------ */

/* Runs the performer workload's pn: mode on the Onyx model (pipe costs
 * per triangle and per PN point optionally overridden); returns a metric. */
static double pn_metric(const char *send, guint level, const char *tri,
                        const char *pt, const char *metric)
{
    char *yaml = g_strdup_printf(
        "schema_version: 1\n"
        "machine:\n  model: sgi-onyx\n"
        "  nodes: {pipe: {costs: {triangle: {value: %s, assumption: t},\n"
        "          pn_vertex: {value: %s, assumption: t}}}}\n"
        "scene: {generator: teapots, count: 1, polygons_per_teapot: 400}\n"
        "workload: {type: performer, pn: {level: %u, send: %s}}\n",
        tri, pt, level, send);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(yaml, "pn.yaml", &err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = 3};
    SimResult *r = support_run_tree(root, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    double v = -1;
    assert_true(sim_result_get_metric(r, metric, &v));
    sim_result_free(r);
    g_free(yaml);
    return v;
}

static void test_pn_compresses_the_bus(void **st)
{
    (void)st;
    for (guint L = 1; L <= 4; L++) {
        double c =
            pn_metric("coarse", L, "1 us", "0.3 us", "link_bytes_per_frame");
        double f =
            pn_metric("fine", L, "1 us", "0.3 us", "link_bytes_per_frame");
        assert_float_equal(f / c, (L + 1) * (L + 1), 1e-9);
    }
}

/* The slides' claim: with the bus busy and the graphics processor fast
 * enough, curved PN triangles (coarse over the bus, tessellated by the
 * pipe) render at the speed of the flat mesh; with a RealityEngine2-
 * class pipe (not fast enough) they do not. */
static void test_pn_at_flat_speed_only_with_fast_pipe(void **st)
{
    (void)st;
    const char *fast = "0.01 us", *fast_pt = "0.002 us";
    double flat = pn_metric("fine", 0, fast, fast_pt, "frame_ms");
    double pn = pn_metric("coarse", 3, fast, fast_pt, "frame_ms");
    double sent_fine = pn_metric("fine", 3, fast, fast_pt, "frame_ms");
    /* bus-bound either way: equal but for the FIFO's drain of the last
     * chunk, which the pipe tessellates (pf_gpipe.h) */
    assert_true(pn >= flat && pn < 1.05 * flat);
    assert_true(sent_fine > 10 * flat); /* the fine mesh fills the bus */
    double re_flat = pn_metric("fine", 0, "1 us", "0.3 us", "frame_ms");
    double re_pn = pn_metric("coarse", 3, "1 us", "0.3 us", "frame_ms");
    assert_true(re_pn > 10 * re_flat); /* pipe-bound: 16x the triangles */
}

/* ---- bad input: located errors ---------------------------------------- */

static const struct {
    const char *yaml, *message;
} bad[] = {
    {"workload: {type: performer, frame_rate: 25}\n",
     "b.yaml:1:41: found a frame rate that does not divide the video rate"},
    {"workload: {type: performer, mode: four}\n",
     "b.yaml:1:35: found 'four', expected one of: appculldraw"},
    {"workload: {type: performer, stress: {low: 0.9, high: 0.5}}\n",
     "b.yaml:1:37: found high < low"},
    {"workload: {type: performer, town: {lod_ranges: [10, 5, 20]}}\n",
     "b.yaml:1:53: found a non-increasing range"},
    {"workload: {type: performer, pn: 3}\n",
     "b.yaml:1:33: found a non-map, expected pn: {level"},
    {"workload: {type: performer, pn: {send: both}}\n",
     "b.yaml:1:40: found 'both', expected one of: coarse, fine"},
};

static void test_bad_config(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        GError *err = NULL;
        CfgNode *root = cfg_load_string(bad[i].yaml, "b.yaml", &err);
        assert_non_null(root);
        void *p = wl_pf_ops.parse(cfg_get(root, "workload"), &err);
        assert_null(p);
        if (!g_str_has_prefix(err->message, bad[i].message))
            fail_msg("case %u: got %s", i, err->message);
        g_error_free(err);
        cfg_free(root);
    }
}

/* A machine without the kinds a run needs is named in the error. */
static void test_bad_machine(void **st)
{
    (void)st;
    const char *yaml = "schema_version: 1\nmachine: {model: pixel-planes-5}\n"
                       "workload: {type: performer}\n";
    GError *err = NULL;
    CfgNode *root = cfg_load_string(yaml, "m.yaml", &err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = 3};
    assert_null(support_run_tree(root, &o, &err));
    if (!strstr(err->message, "found no node kind 'cpu'"))
        fail_msg("got %s", err->message);
    g_error_free(err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_locked_draw_halves_rate),
        cmocka_unit_test(test_app_extends_drops_rate),
        cmocka_unit_test(test_latency_vs_throughput),
        cmocka_unit_test(test_stress_one_frame_late),
        cmocka_unit_test(test_stress_high_gain_oscillates),
        cmocka_unit_test(test_culling_saves_what_it_counts),
        cmocka_unit_test(test_flatten_saves_what_it_counts),
        cmocka_unit_test(test_lazy_state_saves_what_it_counts),
        cmocka_unit_test(test_masks_and_switches),
        cmocka_unit_test(test_isect_finds_ground),
        cmocka_unit_test(test_pn_compresses_the_bus),
        cmocka_unit_test(test_pn_at_flat_speed_only_with_fast_pipe),
        cmocka_unit_test(test_bad_config),
        cmocka_unit_test(test_bad_machine),
    };
    return cmocka_run_group_tests_name("performer", tests, NULL, NULL);
}
