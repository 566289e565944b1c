/* test_sf_frame_values.c — the figures of sort-first frames (sf_frame.c)
 * on a scene worked out by hand: five triangles, one chunk each
 * (granularity 1, unsorted), seen by an orthographic camera whose view
 * square [-1, 1]^2 fills a 16 x 16 screen, four processors in 8 x 8
 * tiles.  Triangle 0 lies in tile 0 (screen box [2, 6]^2), triangle 1 in
 * tile 1 ([10, 14] x [2, 6]), triangle 2 across all four ([6, 10]^2),
 * triangles 3 and 4 off the screen.  Chunk c is mastered by c mod 4.
 * Every figure of WlSfFrameStats that does not depend on the machine's
 * costs is checked against its hand count; those that do (busy time,
 * utilisation, traversal time) against the machine's own busy times. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "tests/workload/sortfirst/sf_testutil.h"

#define P 4

typedef struct {
    Scene *scene;
    SimEngine *eng;
    MachMachine *m;
    WlSfDb *db;
    WlSfRun *run;
    WlSfSetup s;
    WlSfCosts c;
} Rig;

static Scene *hand_scene(void)
{
    Scene *s = scene_new("hand");
    s->camera = (SceneCamera){.proj = SCENE_ORTHOGRAPHIC,
                              .eye = vec3(0, 0, 5),
                              .target = vec3(0, 0, 0),
                              .up = vec3(0, 1, 0),
                              .fov_deg = 45,
                              .height = 2,
                              .near = 1,
                              .far = 10,
                              .aspect = 1};
    scene_set_db(s, sf_test_hand_db());
    return s;
}

/* adapt (may be NULL): its grid (0: static regions), current,
 * feedback, pre and screens (pre: no image check) replace the rig's. */
static void rig_init_setup(Rig *r, WlSfBookkeeping bk, WlSfMigration mig,
                           WlSfMastership ms, const WlSfSetup *adapt)
{
    GError *e = NULL;
    r->scene = hand_scene();
    r->eng = sim_engine_new(1);
    r->m = mach_new_from_model(r->eng, "cluster-ib", "analytic", &e);
    assert_non_null(r->m);
    assert_true(wl_sf_costs_from_machine(r->m, &r->c, &e));
    r->db = wl_sf_db_new(r->scene->db, P, 1, WL_SF_CHUNK_UNSORTED, &e);
    assert_non_null(r->db);
    assert_int_equal(wl_sf_n_chunks(r->db), 5);
    assert_int_equal(wl_sf_n_insts(r->db), 5);
    r->s = (WlSfSetup){.procs = P,
                       .resolution = 16,
                       .bk = bk,
                       .mig = mig,
                       .ms = ms,
                       .sizes = {64, 40, 36, 8, 4, 8, 16, 96},
                       .check_image = TRUE};
    if (adapt) {
        r->s.adaptive = adapt->grid > 0;
        r->s.grid = adapt->grid;
        r->s.current = adapt->current;
        r->s.feedback = adapt->feedback;
        r->s.pre = adapt->pre;
        r->s.screens = adapt->screens;
        r->s.check_image = !adapt->pre;
    }
    r->run = wl_sf_run_new(r->m, r->scene, r->db, &r->s, &r->c);
}

static void rig_init(Rig *r, WlSfBookkeeping bk, WlSfMigration mig,
                     WlSfMastership ms)
{
    rig_init_setup(r, bk, mig, ms, NULL);
}

static void rig_clear(Rig *r)
{
    wl_sf_run_free(r->run);
    wl_sf_db_free(r->db);
    mach_free(r->m);
    sim_engine_free(r->eng);
    scene_free(r->scene);
}

static const WlSfFrameStats *frame(const Rig *r, guint f)
{
    const GArray *st = wl_sf_run_stats(r->run);
    assert_true(f < st->len);
    return &g_array_index(st, WlSfFrameStats, f);
}

static void run(Rig *r, int frames)
{
    GError *e = NULL;
    if (!wl_sf_run_frames(r->run, frames, SIM_TIME_MAX, &e))
        fail_msg("%s", e->message);
}

static void expect_near(double got, double want, const char *what)
{
    if (!(fabs(got - want) <= 1e-12 * fabs(want)))
        fail_msg("%s: %.15g, expected %.15g", what, got, want);
}

/* Pixels the serial render covers: the triangles do not overlap, so
 * every covered pixel is z-buffered once, in one region. */
static uint64_t covered(const Rig *r)
{
    RastZBuffer *zb = rast_zbuffer_new(16, 16);
    wl_sf_render_serial(r->scene, r->db, &r->s, 0, zb);
    uint64_t n = 0;
    for (guint i = 0; i < 256; i++)
        n += zb->prim[i] != RAST_NO_PRIM;
    rast_zbuffer_free(zb);
    return n;
}

/* The frame's busy figures from the machine: each processor's busy
 * time in [busy0[p], now), max / mean, and busy / (P x frame time). */
static void expect_busy(const Rig *r, const WlSfFrameStats *st,
                        const SimTime *busy0)
{
    double total = 0, max = 0;
    for (guint p = 0; p < P; p++) {
        double b =
            (double)(mach_proc_busy(mach_proc(r->m, "node", p)) - busy0[p]);
        assert_true(b > 0);
        total += b;
        max = MAX(max, b);
    }
    expect_near(st->imbalance, max * P / total, "imbalance");
    expect_near(st->utilisation, total / ((double)(st->end - st->start) * P),
                "utilisation");
    assert_true(st->end > st->start);
    /* traversal: node visits and 8 vertices a volume test */
    SimTime t = r->c.node_visit * st->trav.plain +
                r->c.transform_vertex * 8 * st->trav.tests;
    assert_true(st->trav.plain > 0);
    assert_true(st->traverse_busy == t);
}

/* Frame 0, max-set push: processor 2 sends triangle 2's chunk and
 * pointer to 0, 1 and 3 (3 chunks, 3 polygons, 3 pointers); every
 * processor sends every other a message: 12 x 64 B + 3 x (40 + 36 + 8)
 * B.  Renders: 0 and 1 two triangles each, 2 and 3 one: 6, max 2, min
 * 1.  Masters: processor 0 holds 2 master polygons (triangles 0 and 4),
 * the others 1: max / mean = 2 / 1.25; triangle 4 (processor 0's) and 3
 * (processor 3's) are off-screen.  Copies held after the frame: 0 has 3
 * (0, 4, 2), 1 has 2 (1, 2), 2 has 1, 3 has 2 (3, 2).  Three instances
 * on screen, over 1 + 1 + 4 regions, each box 4 x 4 pixels.  Peak
 * memory: processor 0, three chunks with their pointer (3 x (40 + 36 +
 * 8)) and two 2-byte master vectors.  Frame 1 (same view): nothing moves; each
 * slave pointer is tested (3 slave boxes), 12 header-only messages. */
static void test_maxset_push(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED);
    SimTime busy0[P] = {0};
    assert_null(wl_sf_run_zbuffer(r.run)); /* no frame yet */
    run(&r, 1);
    assert_non_null(wl_sf_run_zbuffer(r.run));
    const WlSfFrameStats *f = frame(&r, 0);
    assert_int_equal(f->messages, 12);
    assert_int_equal(f->migrated_chunks, 3);
    assert_int_equal(f->migrated_polys, 3);
    assert_int_equal(f->migrated_insts, 3);
    assert_int_equal(f->migrated_bytes, 12 * 64 + 3 * 84);
    assert_int_equal(f->master_boxes, 5);
    assert_int_equal(f->slave_boxes, 0);
    assert_int_equal(f->new_boxes, 3);
    assert_int_equal(f->deleted_chunks, 0);
    assert_int_equal(f->probe_boxes, 0);
    assert_int_equal(f->requests, 0);
    assert_int_equal(f->handovers, 0);
    assert_int_equal(f->polys_rendered, 6);
    assert_int_equal(f->load_max, 2);
    assert_int_equal(f->load_min, 1);
    expect_near(f->poly_imbalance, 2.0 * 4 / 6, "poly_imbalance");
    expect_near(f->master_imbalance, 2 / 1.25, "master_imbalance");
    assert_int_equal(f->offscreen_max, 1);
    assert_int_equal(f->offscreen_total, 2);
    assert_int_equal(f->held_polys, 8);
    assert_int_equal(f->onscreen_insts, 3);
    assert_int_equal(f->region_insts, 6);
    expect_near(f->box_side, 12, "box_side");
    assert_int_equal(f->peak_memory, 3 * 84 + 2 * 2);
    uint64_t px = covered(&r);
    assert_true(px > 0);
    assert_int_equal(f->pixels, px);
    assert_true(f->image_checked && f->image_ok);
    assert_int_equal(f->estimate_bytes, 0);
    assert_int_equal(f->estimate_cells, 0);
    assert_int_equal(f->edits, 0);
    assert_int_equal(f->edit_bytes, 0);
    assert_true(f->edit_busy == 0);
    expect_busy(&r, f, busy0);
    for (guint p = 0; p < P; p++)
        busy0[p] = mach_proc_busy(mach_proc(r.m, "node", p));
    run(&r, 1);
    f = frame(&r, 1);
    assert_int_equal(f->messages, 12);
    assert_int_equal(f->migrated_chunks, 0);
    assert_int_equal(f->migrated_insts, 0);
    assert_int_equal(f->migrated_bytes, 12 * 64);
    assert_int_equal(f->master_boxes, 5);
    assert_int_equal(f->slave_boxes, 3);
    assert_int_equal(f->new_boxes, 0);
    assert_int_equal(f->polys_rendered, 6);
    assert_int_equal(f->offscreen_total, 2);
    assert_int_equal(f->held_polys, 8);
    assert_int_equal(f->pixels, px);
    assert_true(f->start >= frame(&r, 0)->end);
    expect_busy(&r, f, busy0);
    rig_clear(&r);
}

/* Pull (min-set, fixed): processors 0, 1 and 3 each ask 2 for triangle
 * 2 (a request and an answer each: 6 messages); each tests the box of
 * every chunk it does not hold (probe boxes: 0 holds 2 of 5, 1, 2 and 3
 * one each: 3 + 4 + 4 + 4). */
static void test_pull(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MINSET, WL_SF_PULL, WL_SF_FIXED);
    SimTime busy0[P] = {0};
    run(&r, 1);
    const WlSfFrameStats *f = frame(&r, 0);
    assert_int_equal(f->messages, 6);
    assert_int_equal(f->requests, 3);
    assert_int_equal(f->probe_boxes, 15);
    assert_int_equal(f->master_boxes, 5);
    assert_int_equal(f->migrated_chunks, 3);
    assert_int_equal(f->migrated_polys, 3);
    assert_int_equal(f->migrated_insts, 0);
    assert_int_equal(f->migrated_bytes, 3 * (64 + 8) + 3 * (64 + 76));
    assert_int_equal(f->new_boxes, 3);
    assert_int_equal(f->polys_rendered, 6);
    assert_int_equal(f->offscreen_total, 2);
    assert_int_equal(f->offscreen_max, 1);
    assert_true(f->image_ok);
    expect_busy(&r, f, busy0);
    rig_clear(&r);
}

static void expect_rect(const WlSfRegions *g, guint p, int x0, int y0, int x1,
                        int y1)
{
    WlSfRect q = g->rect[p];
    if (q.x0 != x0 || q.y0 != y0 || q.x1 != x1 || q.y1 != y1)
        fail_msg("region %u: [%d, %d) x [%d, %d), expected [%d, %d) x "
                 "[%d, %d)",
                 p, q.x0, q.x1, q.y0, q.y1, x0, x1, y0, y1);
}

/* Adaptive regions on a 4 x 4 grid of 4 x 4-pixel cells.  The estimate
 * puts each on-screen instance's polygon in the cell of its box's
 * centre: triangle 0 in cell (1, 1), 1 in (3, 1), 2 in (2, 2); each
 * processor's grid has one non-zero cell (0, 1, 2: their masters) or
 * none (3), sent sparse: 2 x 4 B.  The k-d split cuts columns at 2 (left
 * 1 polygon, right 2: max(1 x 2, 2 x 2) = 4, the least, and nearest the
 * proportional cut), then each half's rows at 2 (the tie of cuts 1 and 2
 * goes to the one nearest the middle): processor 0 top left, 1 bottom
 * left, 2 top right, 3 bottom right; estimated weights 1, 0, 1, 1: split
 * imbalance 1 x 4 / 3.  The split visits the 16 cells of the summed-area
 * table and 2 x 4 marginals in each of its 3 cuts: 40.  Each processor
 * adds the others' non-zero cells to its own 16 and the split's 40: 58,
 * 58, 58, 59, and the estimate added 3 cells.  With the previous-frame
 * estimate frame 0 runs in the static tiles and frame 1 in the split
 * ones, where triangle 1 (processor 1's) lies in processor 2's region:
 * one more chunk and pointer migrate. */
static void test_adaptive_previous(void **st)
{
    (void)st;
    Rig r;
    WlSfSetup a = {.grid = 4};
    rig_init_setup(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED, &a);
    SimTime busy0[P] = {0};
    run(&r, 1);
    const WlSfFrameStats *f = frame(&r, 0);
    assert_int_equal(f->estimate_bytes, 3 * (8 + 8 + 8 + 0));
    assert_int_equal(f->estimate_cells, 3 * 58 + 59 + 3);
    expect_near(f->split_imbalance, 4.0 / 3, "split_imbalance");
    assert_int_equal(f->migrated_chunks, 3);
    assert_int_equal(f->migrated_bytes, 12 * 64 + 3 * 84);
    assert_int_equal(f->polys_rendered, 6);
    expect_busy(&r, f, busy0);
    /* phase `sort`: 8 vertices per master box (2, 1, 1, 1; no slave
     * yet) and, without prediction, one grid cell per instance added */
    unsigned ph = sim_engine_phase(r.eng, "sort");
    static const SimTime boxes[P] = {2, 1, 1, 1}, added[P] = {1, 1, 1, 0};
    for (guint p = 0; p < P; p++)
        assert_true(mach_proc_busy_phase(mach_proc(r.m, "node", p), ph) ==
                    8 * boxes[p] * r.c.transform_vertex +
                        added[p] * r.c.grid_cell);
    const WlSfRegions *g = wl_sf_run_regions(r.run);
    expect_rect(g, 0, 0, 0, 8, 8);
    expect_rect(g, 1, 0, 8, 8, 16);
    expect_rect(g, 2, 8, 0, 16, 8);
    expect_rect(g, 3, 8, 8, 16, 16);
    run(&r, 1);
    f = frame(&r, 1);
    assert_int_equal(f->migrated_chunks, 1);
    assert_int_equal(f->migrated_insts, 1);
    assert_int_equal(f->migrated_bytes, 12 * 64 + 84);
    assert_int_equal(f->slave_boxes, 3);
    assert_int_equal(f->new_boxes, 1);
    assert_int_equal(f->estimate_cells, 3 * 58 + 59 + 3);
    assert_true(f->image_ok);
    rig_clear(&r);
}

/* The current-frame estimate: frame 0 already runs in the split
 * regions (4 chunks migrate); with cost feedback each grid message
 * carries 8 B more. */
static void test_adaptive_current(void **st)
{
    (void)st;
    Rig r;
    WlSfSetup a = {.grid = 4, .current = TRUE, .feedback = TRUE};
    rig_init_setup(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED, &a);
    SimTime busy0[P] = {0};
    run(&r, 1);
    const WlSfFrameStats *f = frame(&r, 0);
    assert_int_equal(f->estimate_bytes, 3 * (16 + 16 + 16 + 8));
    assert_int_equal(f->estimate_cells, 3 * 58 + 59 + 3);
    expect_near(f->split_imbalance, 4.0 / 3, "split_imbalance");
    assert_int_equal(f->migrated_chunks, 4);
    assert_int_equal(f->migrated_bytes, 12 * 64 + 4 * 84);
    assert_int_equal(f->master_boxes, 5);
    assert_int_equal(f->polys_rendered, 6);
    assert_true(f->image_ok);
    expect_busy(&r, f, busy0);
    expect_rect(wl_sf_run_regions(r.run), 1, 0, 8, 8, 16);
    /* phase `estimate`: 8 vertices per master box (chunk c's master is
     * c mod 4: 2, 1, 1, 1 boxes) and a grid cell per on-screen instance
     * added (triangles 0, 1, 2: processors 0, 1, 2) */
    unsigned ph = sim_engine_phase(r.eng, "estimate");
    static const SimTime boxes[P] = {2, 1, 1, 1}, added[P] = {1, 1, 1, 0};
    for (guint p = 0; p < P; p++)
        assert_true(mach_proc_busy_phase(mach_proc(r.m, "node", p), ph) ==
                    8 * boxes[p] * r.c.transform_vertex +
                        added[p] * r.c.grid_cell);
    rig_clear(&r);
}

/* Counted from the frames rasterised once (setup `pre`) and the screen
 * rectangles kept by frame (`screens`): the same figures as frame by
 * frame rasterising, for a first run that fills both stores and a
 * second that finds them filled; no image is kept. */
static void test_prerendered(void **st)
{
    (void)st;
    RastPrerenderSet *pre = rast_prerender_set_new();
    WlSfScreenSet *screens = wl_sf_screen_set_new();
    WlSfSetup x = {.pre = pre, .screens = screens};
    for (int pass = 0; pass < 2; pass++) {
        Rig r;
        rig_init_setup(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED, &x);
        run(&r, 2);
        uint64_t px = covered(&r);
        for (guint k = 0; k < 2; k++) {
            const WlSfFrameStats *f = frame(&r, k);
            assert_int_equal(f->polys_rendered, 6);
            assert_int_equal(f->load_max, 2);
            assert_int_equal(f->load_min, 1);
            assert_int_equal(f->pixels, px);
            assert_int_equal(f->region_insts, 6);
            assert_int_equal(f->onscreen_insts, 3);
            expect_near(f->box_side, 12, "box_side");
            assert_int_equal(f->offscreen_total, 2);
            assert_false(f->image_checked);
        }
        assert_int_equal(frame(&r, 0)->migrated_chunks, 3);
        assert_int_equal(frame(&r, 1)->slave_boxes, 3);
        assert_null(wl_sf_run_zbuffer(r.run));
        rig_clear(&r);
    }
    rast_prerender_set_free(pre);
    wl_sf_screen_set_free(screens);
}

/* The camera moved to look at (10, 10): no triangle on screen.  The
 * max / mean ratios of an empty frame are 0 (nothing rendered, no
 * estimated weight), every master polygon is off-screen (processor 0:
 * 2), nothing migrates, and the grids sent are empty. */
static void test_nothing_on_screen(void **st)
{
    (void)st;
    for (int adaptive = 0; adaptive < 2; adaptive++) {
        Rig r;
        WlSfSetup a = {.grid = adaptive ? 4 : 0};
        rig_init_setup(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED, &a);
        r.scene->camera.eye = vec3(10, 10, 5);
        r.scene->camera.target = vec3(10, 10, 0);
        run(&r, 2);
        for (guint k = 0; k < 2; k++) {
            const WlSfFrameStats *f = frame(&r, k);
            assert_int_equal(f->polys_rendered, 0);
            assert_int_equal(f->load_max, 0);
            assert_int_equal(f->load_min, 0);
            assert_true(f->poly_imbalance == 0);
            assert_true(f->split_imbalance == 0);
            expect_near(f->master_imbalance, 2 / 1.25, "master_imbalance");
            assert_int_equal(f->offscreen_max, 2);
            assert_int_equal(f->offscreen_total, 5);
            assert_int_equal(f->onscreen_insts, 0);
            assert_true(f->box_side == 0);
            assert_int_equal(f->pixels, 0);
            assert_int_equal(f->migrated_chunks, 0);
            assert_int_equal(f->migrated_bytes, 12 * 64);
            assert_int_equal(f->estimate_bytes, 0);
            assert_true(f->image_ok);
        }
        rig_clear(&r);
    }
}

/* The camera moved to look at (3.75, 1): only triangle 3 is on screen,
 * at [2, 6] x [12, 16], in region 2 alone.  One polygon rendered (by
 * processor 2, sent by its master 3): max / mean = 1 x 4 / 1; the
 * estimate weighs 1 in all: split imbalance 4 too.  Off-screen master
 * polygons: 2 of processor 0, 1 each of 1 and 2. */
static void test_one_polygon(void **st)
{
    (void)st;
    for (int adaptive = 0; adaptive < 2; adaptive++) {
        Rig r;
        WlSfSetup a = {.grid = adaptive ? 4 : 0};
        rig_init_setup(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED, &a);
        r.scene->camera.eye = vec3(3.75, 1, 5);
        r.scene->camera.target = vec3(3.75, 1, 0);
        run(&r, 1);
        const WlSfFrameStats *f = frame(&r, 0);
        assert_int_equal(f->polys_rendered, 1);
        assert_int_equal(f->load_max, 1);
        assert_int_equal(f->load_min, 0);
        expect_near(f->poly_imbalance, 4, "poly_imbalance");
        assert_true(f->split_imbalance == (adaptive ? 4 : 0));
        assert_int_equal(f->region_insts, 1);
        assert_int_equal(f->migrated_chunks, 1);
        assert_int_equal(f->offscreen_max, 2);
        assert_int_equal(f->offscreen_total, 4);
        assert_true(f->image_ok);
        rig_clear(&r);
    }
}

/* The camera moved to look at (4.0625, -0.5625): triangle 3's box
 * spans screen [-0.5, 3.5] x [-0.5, 3.5], triangle 4's [-0.5, 3.5] x
 * [7.5, 11.5]; clipped to the screen they are 3.5 x 3.5 and 3.5 x 4:
 * box sides 3.5 and sqrt(14). */
static void test_box_side_clipped(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED);
    r.scene->camera.eye = vec3(4.0625, -0.5625, 5);
    r.scene->camera.target = vec3(4.0625, -0.5625, 0);
    run(&r, 1);
    const WlSfFrameStats *f = frame(&r, 0);
    assert_int_equal(f->onscreen_insts, 2);
    expect_near(f->box_side, 3.5 + sqrt(14), "box_side");
    rig_clear(&r);
}

/* A frame that takes no time: one processor (no message: no frame
 * buffer either) on a machine whose eleven sort-first costs are 0.  Its utilisation is 0 (nothing
 * busy over no time), not busy / 0. */
static void test_zero_time_frame(void **st)
{
    (void)st;
    static const char *cfg =
        "schema_version: 1\n"
        "machine: {model: cluster-ib}\n"
        "workload: {type: sortfirst, processors: 1, granularity: 5,\n"
        "           resolution: 32, bookkeeping: maxset,\n"
        "           framebuffer: none}\n"
        "scene: {generator: vehicle, structures: 10, triangles: 200,\n"
        "        instances: 2, circle_radius: 6, camera_radius: 15,\n"
        "        camera_height: 5, fov: 30, degrees_per_frame: 12}\n";
    const char *o[16] = {NULL};
    guint n = 0;
    for (; wl_sf_cost_ops[n] && n + 1 < G_N_ELEMENTS(o); n++)
        o[n] = g_strdup_printf("machine.nodes.node.costs.%s.value=0 ns",
                               wl_sf_cost_ops[n]);
    GError *e = NULL;
    SimResult *r = sf_test_run(cfg, o, 2, NULL, FALSE, &e);
    if (!r)
        fail_msg("%s", e->message);
    assert_int_equal(n, 11);
    assert_true(sf_test_metric(r, "frame_ms") == 0);
    assert_true(sf_test_metric(r, "polygons_rendered_per_frame") > 0);
    assert_true(sf_test_metric(r, "utilisation") == 0);
    sim_result_free(r);
    for (guint k = 0; k < n; k++)
        g_free((char *)o[k]);
}

/* A grid sent dense when its non-zero cells are half of it or more
 * (sf_frame.c grid_bytes: the sparse list's pairs cost as much then).
 * The camera widened to [-2.5, 5.5] x [-4, 4] shows all five triangles;
 * on a 2 x 2 grid of 8-pixel cells processor 0's triangles 0 (centre
 * (-0.5, 0.5)) and 4 ((3.25, -0.75)) fall in cells 0 and 3: 2 of 4
 * cells, dense (4 entries to add); processors 1, 2, 3 have one
 * triangle each, sparse (1 entry).  Each processor's partition work is
 * its own grid, the others' entries and the split: processor 1 adds
 * processor 0's 4 entries where processor 0 adds 1, so 3 cells more. */
static void test_dense_grid_at_half(void **st)
{
    (void)st;
    Rig r;
    WlSfSetup a = {.grid = 2};
    rig_init_setup(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED, &a);
    r.scene->camera.height = 8;
    r.scene->camera.eye = vec3(1.5, 0, 5);
    r.scene->camera.target = vec3(1.5, 0, 0);
    run(&r, 1);
    const WlSfFrameStats *f = frame(&r, 0);
    assert_int_equal(f->onscreen_insts, 5);
    unsigned ph = sim_engine_phase(r.eng, "partition");
    SimTime b[P];
    for (guint p = 0; p < P; p++)
        b[p] = mach_proc_busy_phase(mach_proc(r.m, "node", p), ph);
    assert_true(b[1] == b[0] + 3 * r.c.grid_cell);
    assert_true(b[2] == b[1] && b[3] == b[1]);
    /* bytes: dense 4 cells, sparse 2 per non-zero cell, to 3 others */
    uint64_t cell = r.s.sizes.cell;
    assert_int_equal(f->estimate_bytes, 3 * (4 * cell + 3 * 2 * cell));
    assert_true(f->image_ok);
    rig_clear(&r);
}

/* Culled boxes cost no transform in the sort (sort_charge): with
 * `traversal: culled` and, after a first frame, the camera turned to
 * (10, 10), every master and slave box is in a culled subtree, so the
 * second frame adds nothing to any processor's `sort` phase; with the
 * current-frame estimate (masters done by the estimate) likewise for
 * the slave boxes.  Frame 1 has slave boxes to cull: the pointers
 * frame 0 sent (3; 4 in the split regions of the current estimate). */
static void test_culled_boxes_free(void **st)
{
    (void)st;
    for (int current = 0; current < 2; current++) {
        Rig r;
        WlSfSetup a = {.grid = current ? 4 : 0, .current = current};
        rig_init_setup(&r, WL_SF_MAXSET, WL_SF_PUSH, WL_SF_FIXED, &a);
        wl_sf_run_free(r.run);
        r.s.trav = WL_SF_TRAV_CULLED;
        r.run = wl_sf_run_new(r.m, r.scene, r.db, &r.s, &r.c);
        run(&r, 1);
        unsigned ph = sim_engine_phase(r.eng, "sort");
        SimTime b0[P];
        for (guint p = 0; p < P; p++)
            b0[p] = mach_proc_busy_phase(mach_proc(r.m, "node", p), ph);
        r.scene->camera.eye = vec3(10, 10, 5);
        r.scene->camera.target = vec3(10, 10, 0);
        run(&r, 1);
        const WlSfFrameStats *f = frame(&r, 1);
        assert_int_equal(f->slave_boxes, current ? 4 : 3);
        assert_int_equal(f->onscreen_insts, 0);
        for (guint p = 0; p < P; p++)
            assert_true(mach_proc_busy_phase(mach_proc(r.m, "node", p),
                                             ph) == b0[p]);
        rig_clear(&r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_maxset_push),
        cmocka_unit_test(test_pull),
        cmocka_unit_test(test_adaptive_previous),
        cmocka_unit_test(test_adaptive_current),
        cmocka_unit_test(test_prerendered),
        cmocka_unit_test(test_nothing_on_screen),
        cmocka_unit_test(test_one_polygon),
        cmocka_unit_test(test_box_side_clipped),
        cmocka_unit_test(test_zero_time_frame),
        cmocka_unit_test(test_dense_grid_at_half),
        cmocka_unit_test(test_culled_boxes_free),
    };
    return cmocka_run_group_tests_name("sf_frame_values", tests, NULL, NULL);
}
