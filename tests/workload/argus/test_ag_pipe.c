/* test_ag_pipe.c — the parallel API's synchronisation in the Argus
 * pipeline (sim/workload/argus/ag_pipe.c): glpBarrier and glpWaitContext
 * make a context's later commands wait at every tile, so a blended
 * (order-dependent) frame equals the serial render with them and
 * differs from it when the same streams are issued without them; the
 * application barrier holds application threads; the streams of every
 * order carry Figure 2's loop (clear, appBarrier, glpWaitContext,
 * glpBarrier, swap).
 *
 * The hand-built streams: context 0 or 1 issues a slow block A (40
 * full-screen triangles), the other a fast block Y (one full-screen
 * triangle) ordered after A by the command under test; mesh order is
 * A then Y, so the serial render is "A then Y" at every pixel.  Without
 * the command, Y's geometry finishes first and the tiles draw it first.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/core/record.h"
#include "sim/scene/march.h"
#include "sim/workload/argus/ag_pipe.h"

#define SIDE 64
#define A_TRIS 40

static gboolean pool; /* workers: pool instead of split */

typedef struct {
    SimEngine *eng;
    CfgNode *root;
    MachMachine *m;
    SceneMesh *mesh;
    AgFrame *f;
    RastView view;
    AgStreams *st;
} Rig;

/* Two triangles covering the screen (identity view: clip = world). */
static void add_quad(SceneMesh *m, SceneColor c)
{
    uint32_t b = scene_mesh_n_vertices(m);
    const double v[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int i = 0; i < 4; i++)
        scene_mesh_add_vertex(m, vec3(v[i][0], v[i][1], 0));
    scene_mesh_add_tri(m, b, b + 1, b + 2, c, 0);
    scene_mesh_add_tri(m, b, b + 2, b + 3, c, 0);
}

static void rig_init(Rig *r)
{
    memset(r, 0, sizeof *r);
    GError *e = NULL;
    r->eng = sim_engine_new(1);
    r->root = cfg_load_string("machine: {model: origin2000}\n", "t.yaml", &e);
    assert_non_null(r->root);
    r->m = mach_new_from_cfg(r->eng, cfg_get(r->root, "machine"), "analytic",
                             &e);
    assert_non_null(r->m);
    r->mesh = scene_mesh_new();
    for (int q = 0; q < A_TRIS / 2; q++)
        add_quad(r->mesh, scene_color(0.9, 0.1 + 0.02 * q, 0.1));
    add_quad(r->mesh, scene_color(0.1, 0.2, 0.9)); /* Y: 2 triangles */
    r->f = wl_ag_frame_new(SIDE, SIDE, 16, WL_AG_BLEND, 0.5f,
                           (RastColor){0, 0, 0});
    r->view = rast_view_make(mat4_identity(), SIDE, SIDE);
    r->view.cull_back = FALSE;
    r->st = g_new0(AgStreams, 1);
    r->st->contexts = 2;
    r->st->batches = g_array_new(FALSE, TRUE, sizeof(AgBatch));
    r->st->ctx = g_ptr_array_new_with_free_func((GDestroyNotify)g_array_unref);
    for (int c = 0; c < 2; c++)
        g_ptr_array_add(r->st->ctx, g_array_new(FALSE, TRUE, sizeof(AgBlock)));
    r->st->barriers = 1;
    r->st->barrier_parties = 2;
}

static void rig_free(Rig *r)
{
    wl_ag_streams_free(r->st);
    wl_ag_frame_free(r->f);
    scene_mesh_free(r->mesh);
    mach_free(r->m);
    cfg_free(r->root);
    sim_engine_free(r->eng);
}

/* Appends a block of triangles [first, first + n) to context c. */
static AgBlock *block(Rig *r, guint c, guint first, guint n)
{
    GArray *a = wl_ag_ctx_blocks(r->st, c);
    AgBlock x = {.ctx = c, .batch = G_MAXUINT,
                 .first = first, .n = n, .verts = 3 * (uint64_t)n};
    g_array_append_val(a, x);
    return &g_array_index(a, AgBlock, a->len - 1);
}

static void pre(AgBlock *b, AgSyncKind k, guint id)
{
    b->pre[b->n_pre++] = (AgSync){k, id};
}

static void post(AgBlock *b, AgSyncKind k, guint id)
{
    b->post[b->n_post++] = (AgSync){k, id};
}

/* Busy time of processors [from, to). */
static SimTime busy_of(Rig *r, guint from, guint to)
{
    SimTime t = 0;
    for (guint k = from; k < to; k++)
        t += mach_proc_busy(mach_proc(r->m, "cpu", k));
    return t;
}

/* With a processor per thread (ag_pipe.h: app 0..C-1, geometry, then
 * raster; a pool's workers after the applications), each group's
 * processors are busy exactly its threads' summed time, the others not
 * at all. */
static void threads_on_their_processors(Rig *r, const AgSetup *s,
                                        const AgFrameStats *fs)
{
    guint C = s->contexts, G = s->geometry, R = s->rasterisers;
    assert_true(fs->app_busy > 0 && fs->geom_busy > 0 && fs->rast_busy > 0);
    assert_true(busy_of(r, 0, C) == fs->app_busy);
    if (s->pool) {
        assert_true(busy_of(r, C, C + G + R) ==
                    fs->geom_busy + fs->rast_busy);
    } else {
        assert_true(busy_of(r, C, C + G) == fs->geom_busy);
        assert_true(busy_of(r, C + G, C + G + R) == fs->rast_busy);
    }
    assert_true(busy_of(r, C + G + R, s->procs) == 0);
}

/* Runs one frame; returns the pixels differing from the serial render
 * (mesh order) and the frame time in *ms. */
static uint64_t run_frame(Rig *r, double *ms)
{
    GError *e = NULL;
    AgSetup s = {.procs = 24, .contexts = 2, .geometry = 4,
                 .rasterisers = 4, .pool = pool, .app = WL_AG_APP_NONE,
                 .vertex_bytes = 32, .triangle_bytes = 64};
    AgPipe *p = wl_ag_pipe_new(r->m, &s, r->st, r->f, r->mesh, &r->view);
    AgFrameStats fs;
    gboolean ok = wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e);
    if (!ok)
        fail_msg("%s", e->message);
    threads_on_their_processors(r, &s, &fs);
    *ms = sim_time_to_ms(fs.end - fs.start);
    AgFrame *ref = wl_ag_frame_new(SIDE, SIDE, 16, WL_AG_BLEND, 0.5f,
                                   (RastColor){0, 0, 0});
    guint n = scene_mesh_n_polys(r->mesh);
    uint32_t all[A_TRIS + 4]; /* A, Y and at most one more quad */
    assert_true(n <= G_N_ELEMENTS(all));
    for (guint i = 0; i < n; i++)
        all[i] = i;
    wl_ag_draw(ref, G_MAXUINT, &r->view, r->mesh, all, n);
    RastImage *a = wl_ag_frame_image(ref), *b = wl_ag_frame_image(r->f);
    uint64_t d = rast_image_diff(a, b);
    rast_image_free(a);
    rast_image_free(b);
    wl_ag_frame_free(ref);
    wl_ag_pipe_free(p);
    return d;
}

/* Context 1 draws A, then arrives; context 0 arrives at once (an empty
 * block), then draws Y after glpBarrier(0). */
static uint64_t barrier_frame(gboolean with_barrier, double *ms)
{
    Rig r;
    rig_init(&r);
    post(block(&r, 0, 0, 0), WL_AG_SYNC_BARRIER, 0);
    AgBlock *y = block(&r, 0, A_TRIS, 2);
    post(block(&r, 1, 0, A_TRIS), WL_AG_SYNC_BARRIER, 0);
    pre(y, WL_AG_SYNC_BARRIER_WAIT, 0);
    if (!with_barrier)
        wl_ag_streams_drop(r.st, WL_AG_SYNC_BARRIER_WAIT);
    uint64_t d = run_frame(&r, ms);
    rig_free(&r);
    return d;
}

static void test_barrier_blocks(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        pool = k == 1;
        double with_ms, without_ms;
        assert_int_equal(barrier_frame(TRUE, &with_ms), 0);
        /* the same streams without the wait: Y overtakes A at the tiles */
        assert_true(barrier_frame(FALSE, &without_ms) > 0);
        assert_true(with_ms >= without_ms);
    }
    pool = FALSE;
}

/* Context 0 issues A and meets context 1 at the application barrier;
 * context 1 then issues glpWaitContext(0) and Y. */
static uint64_t wait_frame(gboolean with_wait, gboolean with_app, double *ms)
{
    Rig r;
    rig_init(&r);
    block(&r, 0, 0, A_TRIS);
    pre(block(&r, 0, 0, 0), WL_AG_SYNC_APP_BARRIER, 0);
    AgBlock *y = block(&r, 1, A_TRIS, 2);
    pre(y, WL_AG_SYNC_APP_BARRIER, 0);
    pre(y, WL_AG_SYNC_WAIT_CONTEXT, 0);
    if (!with_wait)
        wl_ag_streams_drop(r.st, WL_AG_SYNC_WAIT_CONTEXT);
    if (!with_app)
        wl_ag_streams_drop(r.st, WL_AG_SYNC_APP_BARRIER);
    uint64_t d = run_frame(&r, ms);
    rig_free(&r);
    return d;
}

static void test_wait_context_orders(void **state)
{
    (void)state;
    double ms;
    assert_int_equal(wait_frame(TRUE, TRUE, &ms), 0);
    assert_true(wait_frame(FALSE, TRUE, &ms) > 0);
    /* glpWaitContext covers what context 0 had issued at the call: with
     * no application barrier, context 1 calls it before A is issued and
     * it orders nothing (the reason for appBarrier in Figure 2) */
    assert_true(wait_frame(TRUE, FALSE, &ms) > 0);
}

/* glpWaitContext(0) waits for what context 0 had issued when it was
 * called, not for the block context 0 issues next: context 1 (Y) parks
 * at the application barrier at once; context 0 issues A, arrives last
 * (waking context 1) and issues B (a green quad) after the barrier,
 * while context 1 calls glpWaitContext(0) and issues Y.  At every tile
 * A is drawn first and then the turn goes to context 1: A, Y, B, the
 * mesh order.  Waiting for B as well would draw A, B, Y. */
static void test_wait_context_excludes_next_block(void **state)
{
    (void)state;
    Rig r;
    rig_init(&r);
    add_quad(r.mesh, scene_color(0.1, 0.9, 0.2)); /* B: triangles 42, 43 */
    block(&r, 0, 0, A_TRIS);
    pre(block(&r, 0, A_TRIS + 2, 2), WL_AG_SYNC_APP_BARRIER, 0);
    AgBlock *y = block(&r, 1, A_TRIS, 2);
    pre(y, WL_AG_SYNC_WAIT_CONTEXT, 0); /* the commands in either order */
    pre(y, WL_AG_SYNC_APP_BARRIER, 0);
    double ms;
    assert_int_equal(run_frame(&r, &ms), 0);
    rig_free(&r);
}

/* The wait is looked up on the block that carries it, also when that is
 * not its context's first: context 1 issues an empty block E, then Y
 * with glpWaitContext(0) after the application barrier.  Y still waits
 * for A at every tile (the serial picture); reading the wait of another
 * block (E's or one of context 0's, which wait for nothing) lets Y
 * overtake A, as dropping the wait does. */
static uint64_t later_wait_frame(gboolean with_wait)
{
    Rig r;
    rig_init(&r);
    block(&r, 0, 0, A_TRIS);
    pre(block(&r, 0, 0, 0), WL_AG_SYNC_APP_BARRIER, 0);
    block(&r, 1, 0, 0);
    AgBlock *y = block(&r, 1, A_TRIS, 2);
    pre(y, WL_AG_SYNC_APP_BARRIER, 0);
    pre(y, WL_AG_SYNC_WAIT_CONTEXT, 0);
    if (!with_wait)
        wl_ag_streams_drop(r.st, WL_AG_SYNC_WAIT_CONTEXT);
    double ms;
    uint64_t d = run_frame(&r, &ms);
    rig_free(&r);
    return d;
}

static void test_wait_context_on_later_block(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        pool = k == 1;
        assert_int_equal(later_wait_frame(TRUE), 0);
        assert_true(later_wait_frame(FALSE) > 0);
    }
    pool = FALSE;
}

/* The last thread to reach the application barrier wakes every other
 * one, context 0 included: context 0 reaches it at once (Y's block) and
 * parks, context 1 issues A first and arrives last.  glpWaitContext(1)
 * in Y then orders Y after A: the serial picture.  A wake-up that
 * skipped context 0 would leave Y never issued (the frame fails). */
static void test_app_barrier_wakes_context_0(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        pool = k == 1;
        Rig r;
        rig_init(&r);
        AgBlock *y = block(&r, 0, A_TRIS, 2);
        pre(y, WL_AG_SYNC_APP_BARRIER, 0);
        pre(y, WL_AG_SYNC_WAIT_CONTEXT, 1);
        block(&r, 1, 0, A_TRIS);
        pre(block(&r, 1, 0, 0), WL_AG_SYNC_APP_BARRIER, 0);
        double ms;
        assert_int_equal(run_frame(&r, &ms), 0);
        rig_free(&r);
    }
    pool = FALSE;
}

static guint kind_count(const AgStreams *s, AgSyncKind k)
{
    return (guint)wl_ag_count_syncs(s, k);
}

/* Figure 2 around every order's drawing (ag_stream.h). */
static void test_streams_carry_the_frame_loop(void **state)
{
    (void)state;
    SceneMarchParams mp = scene_march_defaults();
    mp.iso.grid = 16;
    mp.cell = 4;
    SceneMesh *m = scene_iso_mesh_cells(&mp.iso, mp.cell);
    for (AgOrder o = WL_AG_ORDER_FRAME; o <= WL_AG_ORDER_NONE; o++) {
        GError *e = NULL;
        AgStreams *s =
            wl_ag_streams_new(m, 3, o, WL_AG_PRIM_TRIANGLES, 8, 4, &e);
        assert_non_null(s);
        assert_int_equal(kind_count(s, WL_AG_SYNC_APP_BARRIER), 3);
        assert_int_equal(kind_count(s, WL_AG_SYNC_WAIT_CONTEXT), 2);
        assert_int_equal(kind_count(s, WL_AG_SYNC_BARRIER), 3);
        assert_int_equal(kind_count(s, WL_AG_SYNC_BARRIER_WAIT), 1);
        GArray *b0 = wl_ag_ctx_blocks(s, 0);
        assert_true(g_array_index(b0, AgBlock, 0).clear);
        assert_true(g_array_index(b0, AgBlock, b0->len - 1).swap);
        wl_ag_streams_free(s);
        /* one context: clear, drawing, swap, nothing to synchronise */
        s = wl_ag_streams_new(m, 1, o, WL_AG_PRIM_TRIANGLES, 8, 4, &e);
        assert_non_null(s);
        assert_int_equal(s->syncs, 0);
        wl_ag_streams_free(s);
    }
    scene_mesh_free(m);
}

static void event_chain(gboolean pooled)
{
    Rig r;
    rig_init(&r);
    r.st->contexts = 1;
    r.st->barrier_parties = 1;
    wl_ag_frame_free(r.f);
    r.f = wl_ag_frame_new(SIDE, SIDE, SIDE, WL_AG_OPAQUE, 1.0f,
                          (RastColor){0, 0, 0});
    block(&r, 0, 0, 2);
    block(&r, 0, 2, 2);
    GError *e = NULL;
    AgCosts c;
    assert_true(wl_ag_costs_from_machine(r.m, &c, &e));
    AgSetup s = {.procs = 3, .contexts = 1, .geometry = 1, .rasterisers = 1,
                 .pool = pooled, .fill_infinite = TRUE,
                 .app = WL_AG_APP_NONE, .vertex_bytes = 32,
                 .triangle_bytes = 64, .mem_bandwidth = 1e8,
                 .mem_latency = SIM_US};
    AgPipe *p = wl_ag_pipe_new(r.m, &s, r.st, r.f, r.mesh, &r.view);
    AgFrameStats fs;
    if (!wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e))
        fail_msg("%s", e->message);
    SimTime a = 6 * c.issue_vertex + c.lock;
    SimTime g = c.lock + 6 * c.geom_vertex + 2 * c.geom_triangle +
                2 * c.geom_tile;
    SimTime rt = 2 * c.rast_triangle, L = SIM_US;
    SimTime dv = sim_time_for_bytes(192, 1e8), dt = sim_time_for_bytes(128, 1e8);
    assert_true(dv < a && dt < g); /* the memory is never the queue */
    assert_true(a < g); /* block 1 reaches geometry while block 0 is there */
    SimTime e0 = a + dv + L, e1 = 2 * a + dv + L;   /* at geometry */
    /* split: one geometry thread takes them in turn; pool: the idle
     * worker takes block 1 at once */
    SimTime g0 = e0 + g, g1 = (pooled ? e1 : MAX(e1, g0)) + g;
    SimTime r0 = g0 + dt + L, r1 = g1 + dt + L;       /* at the tile */
    SimTime end = MAX(r1, r0 + rt) + rt;
    assert_int_equal(fs.start, 0);
    assert_int_equal(fs.end, end);
    assert_int_equal(fs.app_busy, 2 * a);
    assert_int_equal(fs.geom_busy, 2 * g);
    assert_int_equal(fs.rast_busy, 2 * rt);
    assert_int_equal(fs.shmem_bytes, 2 * (192 + 128));
    assert_int_equal(fs.triangles, 4);
    assert_int_equal(fs.verts_issued, 12);
    assert_int_equal(fs.bucketed, 4);
    assert_int_equal(fs.blocks, 2);
    assert_int_equal(fs.syncs, 0);
    assert_int_equal(fs.pixels, 2 * SIDE * SIDE);
    /* the threads' processors: app 0, then geometry 1 and raster 2
     * (split) or the two pool workers 1 and 2 */
    MachProc *q[3];
    for (int i = 0; i < 3; i++)
        q[i] = mach_proc(r.m, "cpu", i);
    assert_int_equal(mach_proc_busy(q[0]), 2 * a);
    if (!pooled) {
        assert_int_equal(mach_proc_busy(q[1]), 2 * g);
        assert_int_equal(mach_proc_busy(q[2]), 2 * rt);
    } else {
        assert_int_equal(mach_proc_busy(q[1]) + mach_proc_busy(q[2]),
                         2 * g + 2 * rt);
        assert_true(mach_proc_busy(q[2]) >= g); /* worker 1 did geometry */
    }
    wl_ag_pipe_free(p);
    rig_free(&r);
}

/* The pipeline's event chain timed by hand: one context issues two
 * blocks of one quad (2 triangles, 6 vertices) to geometry and
 * rasterisation over a single tile, each thread on its own processor;
 * shared memory at 100 MB/s with 1 us latency.  Per block: the
 * application pays 6 issue_vertex + a lock, its vertices (6 x 32 B)
 * cross the memory, geometry pays a lock, 6 geom_vertex, 2
 * geom_triangle and 2 geom_tile, the bucketed triangles (2 x 64 B)
 * cross the memory, the rasteriser pays 2 rast_triangle (infinite fill
 * rate).  With one geometry thread and one rasteriser (split), or a
 * pool of two workers. */
static void test_event_chain_timing(void **state)
{
    (void)state;
    event_chain(FALSE);
    event_chain(TRUE);
}

/* Replaces the rig's mesh by n quads of the colours col[0 .. n-1], and
 * its frame by a blending one (alpha 0.5 over black). */
static void rig_quads(Rig *r, const float (*col)[3], int n)
{
    scene_mesh_free(r->mesh);
    r->mesh = scene_mesh_new();
    for (int q = 0; q < n; q++)
        add_quad(r->mesh, scene_color(col[q][0], col[q][1], col[q][2]));
    wl_ag_frame_free(r->f);
    r->f = wl_ag_frame_new(SIDE, SIDE, SIDE, WL_AG_BLEND, 0.5f,
                           (RastColor){0, 0, 0});
}

/* One frame of the rig's streams through a pipe of `contexts`
 * application threads, one geometry and one rasteriser thread; the pipe
 * is the caller's to free. */
static AgPipe *run_blend_frame(Rig *r, guint contexts)
{
    GError *e = NULL;
    AgSetup s = {.procs = 8, .contexts = contexts, .geometry = 1,
                 .rasterisers = 1, .app = WL_AG_APP_NONE,
                 .vertex_bytes = 32, .triangle_bytes = 64};
    AgPipe *p = wl_ag_pipe_new(r->m, &s, r->st, r->f, r->mesh, &r->view);
    AgFrameStats fs;
    if (!wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e))
        fail_msg("%s", e->message);
    return p;
}

/* A tile takes the contexts' ready blocks in turn (round robin from the
 * context after the one it drew last).  Two contexts of two full-screen
 * quads each (red, green; blue, white), blended at alpha 0.5 over black
 * on one tile; drawing is slow (finite fill rate, one rasteriser), so
 * once the first block is drawn every other block is ready: the tile
 * draws red, blue, green, white, leaving (0.5625, 0.75, 0.625); taking
 * a context's blocks back to back (red, green, blue, white) would leave
 * (0.5625, 0.625, 0.75). */
static void test_tile_round_robin(void **state)
{
    (void)state;
    Rig r;
    rig_init(&r);
    const float col[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    rig_quads(&r, col, 4);
    block(&r, 0, 0, 2);
    block(&r, 0, 2, 2);
    block(&r, 1, 4, 2);
    block(&r, 1, 6, 2);
    AgPipe *p = run_blend_frame(&r, 2);
    const float want[3] = {0.5625f, 0.75f, 0.625f};
    for (int i = 0; i < SIDE * SIDE; i += 97)
        for (int k = 0; k < 3; k++)
            if (fabsf(r.f->rgb[3 * i + k] - want[k]) > 1e-6f)
                fail_msg("pixel %d channel %d: %f, expected %f", i, k,
                         r.f->rgb[3 * i + k], want[k]);
    wl_ag_pipe_free(p);
    rig_free(&r);
}

/* Adds two triangles covering tile 0 (the top-left quadrant of a 2 x 2
 * tiling: every pixel centre in it) and no other tile in colour c. */
static void add_tile0_quad(SceneMesh *m, SceneColor c)
{
    uint32_t b = scene_mesh_n_vertices(m);
    const double v[4][2] = {
        {-0.99, 0.01}, {-0.01, 0.01}, {-0.01, 0.99}, {-0.99, 0.99}};
    for (int i = 0; i < 4; i++)
        scene_mesh_add_vertex(m, vec3(v[i][0], v[i][1], 0));
    scene_mesh_add_tri(m, b, b + 1, b + 2, c, 0);
    scene_mesh_add_tri(m, b, b + 2, b + 3, c, 0);
}

/* Blends the layers col[order[0]], col[order[1]], ... (n of them) over
 * *c at alpha 0.5. */
static void blend_layers(float c[3], const float (*col)[3], const int *order,
                         int n)
{
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            c[k] = 0.5f * col[order[i]][k] + 0.5f * c[k];
}

/* Every tile starts each frame's round robin at context 0.  One
 * rasteriser owns the 2 x 2 tiles.  Context 0 issues block a (grey over
 * tile 0 only, 2048 blended fragments: slow to draw) then b (a red
 * full-screen quad); context 1 issues c (four blue full-screen quads,
 * slower to issue than a).  The rasteriser draws a at tile 0 while b
 * and c finish their geometry, so at tiles 1, 2 and 3 both contexts'
 * blocks are ready at the first pick: from context 0, red then blue;
 * at tile 0 from context 1 (after a): blue then red.  Twice with the
 * same pipe (the second frame over the first's picture): each frame
 * starts the tiles afresh. */
static void test_round_robin_starts_at_context_0(void **state)
{
    (void)state;
    Rig r;
    rig_init(&r);
    scene_mesh_free(r.mesh);
    r.mesh = scene_mesh_new();
    add_tile0_quad(r.mesh, scene_color(0.5, 0.5, 0.5));
    add_quad(r.mesh, scene_color(1, 0, 0));
    for (int l = 0; l < 4; l++)
        add_quad(r.mesh, scene_color(0, 0, 1));
    wl_ag_frame_free(r.f);
    r.f = wl_ag_frame_new(SIDE, SIDE, SIDE / 2, WL_AG_BLEND, 0.5f,
                          (RastColor){0, 0, 0});
    block(&r, 0, 0, 2);
    block(&r, 0, 2, 2);
    block(&r, 1, 4, 8);
    AgPipe *p = run_blend_frame(&r, 2);
    const float col[3][3] = {{0.5f, 0.5f, 0.5f}, {1, 0, 0}, {0, 0, 1}};
    const int at0[6] = {0, 2, 2, 2, 2, 1}, at1[5] = {1, 2, 2, 2, 2};
    float want[2][3] = {{0}}; /* [0]: tile 0, [1]: tiles 1 to 3 */
    for (int frame = 1; frame <= 2; frame++) {
        GError *e = NULL;
        AgFrameStats fs;
        if (frame == 2 && !wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e))
            fail_msg("%s", e->message);
        blend_layers(want[0], col, at0, 6);
        blend_layers(want[1], col, at1, 5);
        for (int y = 0; y < SIDE; y += 7)
            for (int x = 0; x < SIDE; x += 7) {
                int other = x >= SIDE / 2 || y >= SIDE / 2; /* not tile 0 */
                const float *px = &r.f->rgb[3 * (y * SIDE + x)];
                for (int k = 0; k < 3; k++)
                    if (fabsf(px[k] - want[other][k]) > 1e-5f)
                        fail_msg("frame %d pixel (%d, %d) channel %d: %f, "
                                 "expected %f", frame, x, y, k, px[k],
                                 want[other][k]);
            }
    }
    wl_ag_pipe_free(p);
    rig_free(&r);
}

/* Three contexts of 2, 1 and 2 blocks (red, green; blue; white,
 * yellow): the turn passes over a context with nothing left, so the
 * tile draws red, blue, white, green, yellow. */
static void test_tile_round_robin_skips(void **state)
{
    (void)state;
    Rig r;
    rig_init(&r);
    g_ptr_array_add(r.st->ctx, g_array_new(FALSE, TRUE, sizeof(AgBlock)));
    r.st->contexts = 3;
    r.st->barrier_parties = 3;
    const float col[5][3] = {
        {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {1, 1, 0}};
    rig_quads(&r, col, 5);
    block(&r, 0, 0, 2);
    block(&r, 0, 2, 2);
    block(&r, 1, 4, 2);
    block(&r, 2, 6, 2);
    block(&r, 2, 8, 2);
    AgPipe *p = run_blend_frame(&r, 3);
    const int order[5] = {0, 2, 3, 1, 4};
    float want[3] = {0, 0, 0};
    for (int i = 0; i < 5; i++)
        for (int k = 0; k < 3; k++)
            want[k] = 0.5f * col[order[i]][k] + 0.5f * want[k];
    for (int i = 0; i < SIDE * SIDE; i += 97)
        for (int k = 0; k < 3; k++)
            if (fabsf(r.f->rgb[3 * i + k] - want[k]) > 1e-6f)
                fail_msg("pixel %d channel %d: %f, expected %f", i, k,
                         r.f->rgb[3 * i + k], want[k]);
    wl_ag_pipe_free(p);
    rig_free(&r);
}

/* A rig of one context and one barrier party whose one white quad is
 * drawn on a blended frame of `tile`-pixel tiles: the pool tests' start. */
static void rig_pool_init(Rig *r, int tile)
{
    rig_init(r);
    r->st->contexts = 1;
    r->st->barrier_parties = 1;
    const float white[1][3] = {{1, 1, 1}};
    rig_quads(r, white, 1);
    wl_ag_frame_free(r->f);
    r->f = wl_ag_frame_new(SIDE, SIDE, tile, WL_AG_BLEND, 0.5f,
                           (RastColor){0, 0, 0});
}

/* A pool takes ready tiles round robin, from tile 0 at each frame and
 * then from the tile after the one taken.  One block: a full-screen quad
 * (2 triangles in each of the 4 x 4 tiles) and 19 small triangles in
 * tile 1, infinite fill rate, a pool of two workers (processors 1 and
 * 2).  Worker 0 does the geometry; then the block is ready everywhere:
 * worker 0 takes tile 0 (2 rast_triangle), worker 1 tile 1 (21); worker
 * 0 goes on alone with tiles 2 to 11 (done at 22), worker 1 is free at
 * 21 and takes 12 and 14, worker 0 13 and 15: worker 0 is busy the
 * geometry plus 26 triangles, worker 1 25, every frame. */
static void test_pool_round_robin(void **state)
{
    (void)state;
    Rig r;
    rig_pool_init(&r, 16);
    for (int k = 0; k < 19; k++) {
        uint32_t b = scene_mesh_n_vertices(r.mesh);
        scene_mesh_add_vertex(r.mesh, vec3(-0.4, 0.7, 0));
        scene_mesh_add_vertex(r.mesh, vec3(-0.2, 0.7, 0));
        scene_mesh_add_vertex(r.mesh, vec3(-0.3, 0.9, 0));
        scene_mesh_add_tri(r.mesh, b, b + 1, b + 2, scene_color(1, 0, 0), 0);
    }
    block(&r, 0, 0, 21);
    GError *e = NULL;
    AgSetup s = {.procs = 3, .contexts = 1, .geometry = 1, .rasterisers = 1,
                 .pool = TRUE, .fill_infinite = TRUE, .app = WL_AG_APP_NONE,
                 .vertex_bytes = 32, .triangle_bytes = 64};
    AgPipe *p = wl_ag_pipe_new(r.m, &s, r.st, r.f, r.mesh, &r.view);
    SimTime geom = 0, rt = mach_cost(r.m, "cpu", "rast_triangle");
    for (int frame = 1; frame <= 2; frame++) {
        AgFrameStats fs;
        if (!wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e))
            fail_msg("%s", e->message);
        assert_int_equal(fs.bucketed, 16 * 2 + 19);
        /* this frame's bytes: 63 vertices of 32 B, 51 triangles of 64 B */
        assert_int_equal(fs.shmem_bytes, 63 * 32 + 51 * 64);
        assert_int_equal(fs.rast_busy, 51 * rt);
        geom += fs.geom_busy;
        assert_int_equal(busy_of(&r, 1, 2), geom + frame * 26 * rt);
        assert_int_equal(busy_of(&r, 2, 3), frame * 25 * rt);
    }
    wl_ag_pipe_free(p);
    rig_free(&r);
}

/* A recorder that writes down, for one processor, the rast_triangle
 * count of each piece of work it is given (and, with geom, its
 * geom_vertex count). */
typedef struct {
    uint32_t node;
    GString *seq;
    gboolean geom; /* also "g<vertices>" for each geom_vertex count */
} RastRec;

static uint64_t rr_compute(SimRecorder *r, SimTime now, uint32_t node,
                           unsigned phase, SimTime cost, SimTime end,
                           const SimWork *w, gboolean handled)
{
    const SimOp *ops = w->ops;
    unsigned n_ops = w->n_ops;
    const SimOpTerm *terms = w->terms;
    unsigned n_terms = w->n_terms;
    (void)now, (void)phase, (void)cost, (void)end, (void)terms;
    (void)n_terms, (void)handled;
    RastRec *k = r->state;
    for (unsigned i = 0; node == k->node && i < n_ops; i++) {
        if (!strcmp(ops[i].name, "rast_triangle"))
            g_string_append_printf(k->seq, "%" G_GUINT64_FORMAT " ",
                                   (guint64)ops[i].count);
        if (k->geom && !strcmp(ops[i].name, "geom_vertex"))
            g_string_append_printf(k->seq, "g%" G_GUINT64_FORMAT " ",
                                   (guint64)ops[i].count);
    }
    return 1;
}

static void rr_begin(SimRecorder *r, uint64_t id, SimTime t)
{
    (void)r, (void)id, (void)t;
}

static void rr_end(SimRecorder *r, uint64_t id)
{
    (void)r, (void)id;
}

/* A rasteriser serves its tiles round robin, from the tile after the
 * one it drew last: one rasteriser owns the 2 x 2 tiles; block 1 (a
 * full-screen quad: 2 triangles a tile) and block 2 (two, and a small
 * triangle in tile 1: 4 a tile, 5 in tile 1) are both ready once its
 * first tile is drawn (finite fill rate), so it draws block 1 at tiles
 * 0, 1, 2, 3, then block 2 at each, not block 2 at tile 0 right after
 * block 1 there, nor the tiles in another order. */
static void test_rasteriser_round_robin(void **state)
{
    (void)state;
    Rig r;
    rig_init(&r);
    r.st->contexts = 1;
    r.st->barrier_parties = 1;
    const float col[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    rig_quads(&r, col, 3);
    wl_ag_frame_free(r.f);
    r.f = wl_ag_frame_new(SIDE, SIDE, SIDE / 2, WL_AG_BLEND, 0.5f,
                          (RastColor){0, 0, 0});
    uint32_t b = scene_mesh_n_vertices(r.mesh); /* a small one in tile 1 */
    scene_mesh_add_vertex(r.mesh, vec3(0.2, 0.7, 0));
    scene_mesh_add_vertex(r.mesh, vec3(0.4, 0.7, 0));
    scene_mesh_add_vertex(r.mesh, vec3(0.3, 0.9, 0));
    scene_mesh_add_tri(r.mesh, b, b + 1, b + 2, scene_color(1, 1, 1), 0);
    block(&r, 0, 0, 2);
    block(&r, 0, 2, 5);
    static const SimRecorderOps ops = {
        .compute = rr_compute, .begin = rr_begin, .end = rr_end};
    RastRec k = {mach_proc_id(mach_proc(r.m, "cpu", 2)), g_string_new(""),
                 FALSE};
    SimRecorder rec = {&ops, &k};
    sim_engine_set_recorder(r.eng, &rec);
    GError *e = NULL;
    AgSetup s = {.procs = 3, .contexts = 1, .geometry = 1, .rasterisers = 1,
                 .app = WL_AG_APP_NONE, .vertex_bytes = 32,
                 .triangle_bytes = 64};
    AgPipe *p = wl_ag_pipe_new(r.m, &s, r.st, r.f, r.mesh, &r.view);
    AgFrameStats fs;
    if (!wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e))
        fail_msg("%s", e->message);
    assert_string_equal(k.seq->str, "2 2 2 2 4 5 4 4 ");
    sim_engine_set_recorder(r.eng, NULL);
    g_string_free(k.seq, TRUE);
    wl_ag_pipe_free(p);
    rig_free(&r);
}

/* Adds n small triangles inside tile `tile` of a 2 x 2 tiling. */
static void add_small_tris(SceneMesh *m, int n, int tile)
{
    double x = tile % 2 ? 0.3 : -0.7, y = tile < 2 ? 0.6 : -0.4;
    for (int k = 0; k < n; k++) {
        uint32_t b = scene_mesh_n_vertices(m);
        scene_mesh_add_vertex(m, vec3(x, y, 0));
        scene_mesh_add_vertex(m, vec3(x + 0.2, y, 0));
        scene_mesh_add_vertex(m, vec3(x + 0.1, y + 0.2, 0));
        scene_mesh_add_tri(m, b, b + 1, b + 2, scene_color(1, 1, 1), 0);
    }
}

/* A pool worker takes geometry only when it is idle: one context issues
 * block 0 (a full-screen quad and 10 small triangles in tile 0: 36
 * vertices) and block 1 (100 small triangles in tile 3: 300 vertices,
 * slow to issue); a pool of two workers (processors 1 and 2), blended
 * at a finite fill rate on 2 x 2 tiles.  Worker 0 does block 0's
 * geometry; then worker 0 draws it at tile 0 and worker 1 at tile 1
 * (over 1000 pixels each), and block 1 reaches the queue meanwhile.
 * Worker 1, with fewer pixels, is idle first and takes block 1's
 * geometry: processor 2 draws 2 triangles (tile 1), then transforms 300
 * vertices; worker 0, busy, is not given it. */
static void test_pool_geometry_to_idle_worker(void **state)
{
    (void)state;
    Rig r;
    rig_pool_init(&r, SIDE / 2);
    add_small_tris(r.mesh, 10, 0);
    add_small_tris(r.mesh, 100, 3);
    block(&r, 0, 0, 12);
    block(&r, 0, 12, 100);
    static const SimRecorderOps ops = {
        .compute = rr_compute, .begin = rr_begin, .end = rr_end};
    RastRec k[2] = {{mach_proc_id(mach_proc(r.m, "cpu", 1)),
                     g_string_new(""), TRUE},
                    {mach_proc_id(mach_proc(r.m, "cpu", 2)),
                     g_string_new(""), TRUE}};
    SimRecorder rec[2] = {{&ops, &k[0]}, {&ops, &k[1]}};
    GError *e = NULL;
    AgSetup s = {.procs = 3, .contexts = 1, .geometry = 1, .rasterisers = 1,
                 .pool = TRUE, .app = WL_AG_APP_NONE, .vertex_bytes = 32,
                 .triangle_bytes = 64};
    AgPipe *p = wl_ag_pipe_new(r.m, &s, r.st, r.f, r.mesh, &r.view);
    for (int w = 0; w < 2; w++) {
        sim_engine_set_recorder(r.eng, &rec[w]);
        AgFrameStats fs;
        if (!wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e))
            fail_msg("%s", e->message);
        if (!g_str_has_prefix(k[w].seq->str, w ? "2 g300 " : "g36 12 "))
            fail_msg("worker %d: %s", w, k[w].seq->str);
        g_string_free(k[w].seq, TRUE);
    }
    sim_engine_set_recorder(r.eng, NULL);
    wl_ag_pipe_free(p);
    rig_free(&r);
}

/* A block's (tile, triangle) pairs are sorted by tile: two triangles,
 * the first in tile 1 and the second in tile 0 (two pairs out of tile
 * order), are each drawn at their tile: the picture is the serial one. */
static void test_two_pairs_sorted(void **state)
{
    (void)state;
    Rig r;
    rig_init(&r);
    scene_mesh_free(r.mesh);
    r.mesh = scene_mesh_new();
    const double x0[2] = {-0.4, -0.9}; /* tile 1, then tile 0 */
    for (int k = 0; k < 2; k++) {
        uint32_t b = scene_mesh_n_vertices(r.mesh);
        scene_mesh_add_vertex(r.mesh, vec3(x0[k], 0.7, 0));
        scene_mesh_add_vertex(r.mesh, vec3(x0[k] + 0.2, 0.7, 0));
        scene_mesh_add_vertex(r.mesh, vec3(x0[k] + 0.1, 0.9, 0));
        scene_mesh_add_tri(r.mesh, b, b + 1, b + 2, scene_color(1, k, 0), 0);
    }
    block(&r, 0, 0, 2);
    double ms;
    assert_int_equal(run_frame(&r, &ms), 0);
    rig_free(&r);
}

/* Streams without a block: every tile is finished at once (none has
 * anything to draw), so the frame ends where it starts, having drawn,
 * moved and synchronised nothing. */
static void test_empty_frame(void **state)
{
    (void)state;
    Rig r;
    rig_init(&r);
    GError *e = NULL;
    AgSetup s = {.procs = 4, .contexts = 2, .geometry = 1, .rasterisers = 1,
                 .vertex_bytes = 32, .triangle_bytes = 64};
    AgPipe *p = wl_ag_pipe_new(r.m, &s, r.st, r.f, r.mesh, &r.view);
    AgFrameStats fs;
    if (!wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e))
        fail_msg("%s", e->message);
    assert_int_equal(fs.start, 0);
    assert_int_equal(fs.end, 0);
    assert_int_equal(fs.blocks, 0);
    assert_int_equal(fs.pixels + fs.triangles + fs.shmem_bytes + fs.syncs, 0);
    wl_ag_pipe_free(p);
    rig_free(&r);
}

/* An engine error ends the frame with that error: a dry run (the engine
 * stops before the first event) fails the frame with the engine's
 * message, even for streams without a block (nothing left undrawn). */
static void test_engine_error_ends_frame(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        Rig r;
        rig_init(&r);
        if (k == 1)
            block(&r, 0, 0, 2);
        sim_engine_set_dry_run(r.eng, TRUE);
        GError *e = NULL;
        AgSetup s = {.procs = 4, .contexts = 2, .geometry = 1,
                     .rasterisers = 1, .vertex_bytes = 32,
                     .triangle_bytes = 64};
        AgPipe *p = wl_ag_pipe_new(r.m, &s, r.st, r.f, r.mesh, &r.view);
        AgFrameStats fs;
        assert_false(wl_ag_pipe_frame(p, SIM_TIME_MAX, &fs, &e));
        assert_non_null(e);
        assert_string_equal(e->message, "stopped before the first simulated "
                                        "event (dry run)");
        g_error_free(e);
        wl_ag_pipe_free(p);
        rig_free(&r);
    }
}

/* A glpPSema no glpVSema answers deadlocks every tile: the frame fails
 * saying how many tiles are left, also when the other context's block
 * signals a glpBarrier arrival (barriers count apart from semaphores);
 * an `until` short of the frame does the same unless it is the run's
 * horizon (run.until: the runner's graceful cut, test_run_until). */
static void test_deadlock_reported(void **state)
{
    (void)state;
    for (int k = 0; k < 3; k++) {
        Rig r;
        rig_init(&r);
        AgBlock *b = block(&r, 0, 0, 2);
        if (k != 1) {
            pre(b, WL_AG_SYNC_P, 0);
            r.st->sems = 1;
        }
        AgBlock *o = block(&r, 1, 2, 2);
        if (k == 2)
            post(o, WL_AG_SYNC_BARRIER, 0);
        GError *e = NULL;
        AgSetup s = {.procs = 24, .contexts = 2, .geometry = 4,
                     .rasterisers = 4, .app = WL_AG_APP_NONE,
                     .vertex_bytes = 32, .triangle_bytes = 64};
        AgPipe *p =
            wl_ag_pipe_new(r.m, &s, r.st, r.f, r.mesh, &r.view);
        AgFrameStats fs;
        assert_false(
            wl_ag_pipe_frame(p, k == 1 ? SIM_US : SIM_TIME_MAX, &fs, &e));
        assert_non_null(e);
        if (!g_str_has_prefix(e->message,
                              "argus: 16 of 16 tiles left undrawn at ") ||
            !strstr(e->message, "expected every block drawn"))
            fail_msg("%s", e->message);
        g_error_free(e);
        wl_ag_pipe_free(p);
        rig_free(&r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_barrier_blocks),
        cmocka_unit_test(test_wait_context_orders),
        cmocka_unit_test(test_app_barrier_wakes_context_0),
        cmocka_unit_test(test_wait_context_excludes_next_block),
        cmocka_unit_test(test_wait_context_on_later_block),
        cmocka_unit_test(test_streams_carry_the_frame_loop),
        cmocka_unit_test(test_event_chain_timing),
        cmocka_unit_test(test_tile_round_robin),
        cmocka_unit_test(test_tile_round_robin_skips),
        cmocka_unit_test(test_round_robin_starts_at_context_0),
        cmocka_unit_test(test_deadlock_reported),
        cmocka_unit_test(test_empty_frame),
        cmocka_unit_test(test_engine_error_ends_frame),
        cmocka_unit_test(test_pool_round_robin),
        cmocka_unit_test(test_rasteriser_round_robin),
        cmocka_unit_test(test_pool_geometry_to_idle_worker),
        cmocka_unit_test(test_two_pairs_sorted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
