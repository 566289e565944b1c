/* test_ag_mutants.c — claims of the Argus workload that mutation testing
 * (make mutate, docs/testing.md) found unchecked: every triangle of the
 * scene is issued exactly once, batches of a single triangle included
 * (ag_stream.h); per-frame metrics are means over the frames, so a static
 * scene reports the same pixels a frame over one frame or three. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/workload/argus/ag_stream.h"
#include "sim/workload/argus/ag_tile.h"
#include "sim/workload/argus/ag_workload.h"
#include "tests/support.h"
#include "sim/raster/zbuffer.h"

/* n separate triangles, triangle i tagged tags[i]. */
static SceneMesh *tagged_mesh(const guint *tags, guint n)
{
    SceneMesh *m = scene_mesh_new();
    for (guint i = 0; i < n; i++) {
        uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(i, 0, 0)),
                         scene_mesh_add_vertex(m, vec3(i + 1, 0, 0)),
                         scene_mesh_add_vertex(m, vec3(i, 1, 0))};
        scene_mesh_add_poly(m, v, 3, scene_color(1, 1, 1), tags[i]);
    }
    return m;
}

static void check_each_once(const guint *tags, guint n, guint contexts,
                            guint block)
{
    SceneMesh *m = tagged_mesh(tags, n);
    GError *err = NULL;
    AgStreams *s = wl_ag_streams_new(m, contexts, WL_AG_ORDER_FRAME,
                                     WL_AG_PRIM_TRIANGLES, block, 0, &err);
    assert_non_null(s);
    assert_int_equal(s->ctx->len, contexts); /* one stream a context */
    guint seen[16] = {0};
    for (guint c = 0; c < contexts; c++) {
        GArray *b = wl_ag_ctx_blocks(s, c);
        for (guint k = 0; k < b->len; k++) {
            const AgBlock *x = &g_array_index(b, AgBlock, k);
            for (guint t = x->first; t < x->first + x->n; t++)
                seen[t]++;
        }
    }
    for (guint t = 0; t < n; t++)
        if (seen[t] != 1)
            fail_msg("%u contexts: triangle %u issued %u times", contexts, t,
                     seen[t]);
    wl_ag_streams_free(s);
    scene_mesh_free(m);
}

static void test_every_triangle_once(void **state)
{
    (void)state;
    const guint singles[5] = {0, 1, 2, 3, 4};
    const guint mixed[7] = {0, 0, 0, 1, 2, 2, 3};
    check_each_once(singles, 5, 1, 4);
    check_each_once(singles, 5, 2, 4);
    check_each_once(mixed, 7, 1, 2);
    check_each_once(mixed, 7, 3, 2);
}

/* Cell order: one batch per cell of the 2^3 grid, empty cells included,
 * each starting where the previous one ends (the stream walks the mesh
 * in order), the first cell empty. */
static void test_cell_batches_contiguous(void **state)
{
    (void)state;
    const guint tags[4] = {1, 1, 3, 5};
    const guint first[8] = {0, 0, 2, 2, 3, 3, 4, 4};
    const guint n[8] = {0, 2, 0, 1, 0, 1, 0, 0};
    SceneMesh *m = tagged_mesh(tags, 4);
    GError *err = NULL;
    AgStreams *s = wl_ag_streams_new(m, 2, WL_AG_ORDER_CELLS,
                                     WL_AG_PRIM_TRIANGLES, 4, 2, &err);
    assert_non_null(s);
    assert_int_equal(s->batches->len, 8);
    assert_int_equal(s->sems, 8);
    for (guint i = 0; i < 8; i++) {
        const AgBatch *b = &g_array_index(s->batches, AgBatch, i);
        if (b->first != first[i] || b->n != n[i] || b->tag != i ||
            b->verts != 3 * n[i] || b->distinct != 3 * n[i])
            fail_msg("cell %u: first %u n %u tag %u, expected %u %u %u", i,
                     b->first, b->n, b->tag, first[i], n[i], i);
    }
    for (guint c = 0; c < 2; c++) {
        GArray *a = wl_ag_ctx_blocks(s, c);
        for (guint k = 0; k < a->len; k++) {
            const AgBlock *x = &g_array_index(a, AgBlock, k);
            if (x->batch == G_MAXUINT)
                continue;
            assert_int_equal(x->first, first[x->batch]);
            assert_int_equal(x->n, n[x->batch]);
            assert_int_equal(x->verts, 3 * n[x->batch]);
        }
    }
    wl_ag_streams_free(s);
    scene_mesh_free(m);
}

/* Fragment colours are clamped to [0, 1] before they are blended (or
 * stored): a triangle of colour (1.5, -0.5, 0.5) over a (0.2, 0.4, 0.6)
 * background at alpha 0.5 gives (0.6, 0.2, 0.55); drawn opaque, the
 * frame holds (1, 0, 0.5). */
static void test_fragment_colour_clamped(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(-3, -3, 0)),
                     scene_mesh_add_vertex(m, vec3(3, -3, 0)),
                     scene_mesh_add_vertex(m, vec3(0, 3, 0))};
    scene_mesh_add_poly(m, v, 3, scene_color(1.5f, -0.5f, 0.5f), 0);
    RastView view = rast_view_make(mat4_identity(), 16, 16);
    view.cull_back = FALSE;
    const RastColor bg = {0.2f, 0.4f, 0.6f};
    const float blend[3] = {0.6f, 0.2f, 0.55f}, opaque[3] = {1, 0, 0.5f};
    for (int mode = 0; mode < 2; mode++) {
        AgFrame *f = wl_ag_frame_new(16, 16, 8, mode ? WL_AG_BLEND : WL_AG_OPAQUE,
                                     0.5f, bg);
        uint32_t tri = 0;
        assert_true(wl_ag_draw(f, G_MAXUINT, &view, m, &tri, 1) > 0);
        const float *px = &f->rgb[3 * (8 * 16 + 8)]; /* the centre */
        const float *want = mode ? blend : opaque;
        for (int k = 0; k < 3; k++)
            if (fabsf(px[k] - want[k]) > 1e-6f)
                fail_msg("mode %d channel %d: %f, expected %f", mode, k,
                         px[k], want[k]);
        wl_ag_frame_free(f);
    }
    scene_mesh_free(m);
}

/* Bucketing on a 64 x 48 frame of 16-pixel tiles (4 x 3; identity view:
 * screen x = (x + 1) 32, y = (1 - y) 24): a triangle lands in the tiles
 * its screen box overlaps, clamped to the frame; one wholly off any side
 * lands nowhere; one with a vertex behind the eye (w <= 0) in every
 * tile.  Tiles are numbered row by row. */
static void add_tri(SceneMesh *m, double x0, double y0, double x1, double y1,
                    double z)
{
    uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(x0, y0, z)),
                     scene_mesh_add_vertex(m, vec3(x1, y0, 1)),
                     scene_mesh_add_vertex(m, vec3(x0, y1, 1))};
    scene_mesh_add_poly(m, v, 3, scene_color(1, 1, 1), 0);
}

static void tile_list(guint tile, void *ctx)
{
    g_array_append_val((GArray *)ctx, tile);
}

static void test_bucket_boxes(void **state)
{
    (void)state;
    AgFrame *f = wl_ag_frame_new(64, 48, 16, WL_AG_OPAQUE, 1,
                                 (RastColor){0, 0, 0});
    assert_int_equal(f->tiles_x, 4);
    assert_int_equal(f->tiles_y, 3);
    assert_int_equal(wl_ag_n_tiles(f), 12);
    /* a pixel past a whole number of tiles makes one more (65 x 33) */
    AgFrame *odd = wl_ag_frame_new(65, 33, 16, WL_AG_OPAQUE, 1,
                                   (RastColor){0, 0, 0});
    assert_int_equal(odd->tiles_x, 5);
    assert_int_equal(odd->tiles_y, 3);
    wl_ag_frame_free(odd);
    SceneMesh *m = scene_mesh_new();
    add_tri(m, -0.45, 0.3, 0.05, 0.6, 1);  /* x 17.6..33.6, y 9.6..16.8 */
    add_tri(m, -1.5, 1.4, -0.8, 0.9, 1);   /* off the top left corner */
    add_tri(m, 1.1, 0, 1.5, 0.5, 1);       /* off the right */
    add_tri(m, 0, -1.1, 0.5, -1.5, 1);     /* off the bottom */
    add_tri(m, -1.9, 0, -1.2, 0.5, 1);     /* off the left */
    add_tri(m, 0, 1.2, 0.5, 1.5, 1);       /* off the top */
    add_tri(m, 0.9, -0.9, 1.3, -1.3, 1);   /* the bottom right corner */
    add_tri(m, -0.2, 0.1, 0.2, 0.2, -1);   /* a vertex behind the eye */
    add_tri(m, -1.5, 0.3, -1, 0.6, 1);     /* its right edge at x = 0 */
    add_tri(m, 0.1, 1.5, 0.2, 1, 1);       /* its bottom edge at y = 0 */
    /* clip w = z: the first vertex of the last triangle has w = -1 */
    Mat4 vp = mat4_identity();
    vp.m[3][2] = 1, vp.m[3][3] = 0;
    const guint want[10][5] = {{4, 1, 2, 5, 6}, {1, 0}, {0}, {0}, {0}, {0},
                               {1, 11}, {12}, {2, 0, 4}, {1, 2}};
    for (guint t = 0; t < 10; t++) {
        GArray *a = g_array_new(FALSE, FALSE, sizeof(guint));
        guint n = wl_ag_bucket(f, &vp, m, t, tile_list, a);
        assert_int_equal(n, a->len);
        if (n != want[t][0])
            fail_msg("triangle %u: %u tiles, expected %u", t, n, want[t][0]);
        for (guint k = 0; t != 7 && k < n; k++)
            assert_int_equal(g_array_index(a, guint, k), want[t][1 + k]);
        for (guint k = 0; t == 7 && k < n; k++)
            assert_int_equal(g_array_index(a, guint, k), k);
        g_array_free(a, TRUE);
    }
    /* 70 x 50 pixels (5 x 4 tiles, the last ones partial): a triangle
     * starting exactly at the right or bottom edge is off the frame */
    AgFrame *g = wl_ag_frame_new(70, 50, 16, WL_AG_OPAQUE, 1,
                                 (RastColor){0, 0, 0});
    SceneMesh *e = scene_mesh_new();
    add_tri(e, 1, 0, 1.5, 0.5, 1);    /* x from 70 */
    add_tri(e, 0, -1, 0.5, -1.5, 1);  /* y from 50 */
    add_tri(e, 0.95, -0.95, 1.5, -1.5, 1); /* the partial corner tile */
    Mat4 id = mat4_identity();
    for (guint t = 0; t < 3; t++) {
        GArray *a = g_array_new(FALSE, FALSE, sizeof(guint));
        assert_int_equal(wl_ag_bucket(g, &id, e, t, tile_list, a),
                         t < 2 ? 0 : 1);
        if (t == 2)
            assert_int_equal(g_array_index(a, guint, 0), 19);
        g_array_free(a, TRUE);
    }
    scene_mesh_free(e);
    wl_ag_frame_free(g);
    /* tiles go to rasterisers along rows and columns: (tx + ty) mod R */
    assert_int_equal(wl_ag_tile_owner(f, 0, 3), 0);
    assert_int_equal(wl_ag_tile_owner(f, 5, 3), 2);
    assert_int_equal(wl_ag_tile_owner(f, 7, 3), 1);
    assert_int_equal(wl_ag_tile_owner(f, 11, 5), 0);
    scene_mesh_free(m);
    wl_ag_frame_free(f);
}

/* One expected block: triangles [first, first + n), its cell (or -1:
 * none), clear / swap, and its waits and signals as "kind:id" words
 * (P, V, A = appBarrier, W = glpWaitContext, B = glpBarrier, BW = the
 * barrier wait). */
typedef struct {
    guint first, n;
    int cell;
    gboolean opens, clear, swap;
    const char *pre, *post;
} Want;

static const char *kind_name(AgSyncKind k)
{
    switch (k) {
    case WL_AG_SYNC_P:
        return "P";
    case WL_AG_SYNC_V:
        return "V";
    case WL_AG_SYNC_APP_BARRIER:
        return "A";
    case WL_AG_SYNC_WAIT_CONTEXT:
        return "W";
    case WL_AG_SYNC_BARRIER:
        return "B";
    default:
        return "BW";
    }
}

static char *syncs_text(const AgSync *s, guint n)
{
    GString *t = g_string_new("");
    for (guint i = 0; i < n; i++)
        g_string_append_printf(t, "%s%s:%u", i ? " " : "",
                               kind_name(s[i].kind), s[i].id);
    return g_string_free(t, FALSE);
}

static void blocks_are(const AgStreams *s, guint c, const Want *w, guint n)
{
    GArray *a = wl_ag_ctx_blocks(s, c);
    assert_int_equal(a->len, n);
    for (guint i = 0; i < n; i++) {
        const AgBlock *k = &g_array_index(a, AgBlock, i);
        char *pre = syncs_text(k->pre, k->n_pre);
        char *post = syncs_text(k->post, k->n_post);
        int cell = k->batch == G_MAXUINT
                       ? -1
                       : (int)g_array_index(s->batches, AgBatch, k->batch).tag;
        if (k->ctx != c || cell != w[i].cell ||
            (cell >= 0 && (k->first != w[i].first || k->n != w[i].n)) ||
            k->opens != w[i].opens || k->clear != w[i].clear ||
            k->swap != w[i].swap || strcmp(pre, w[i].pre) ||
            strcmp(post, w[i].post) || k->verts != 3 * (uint64_t)k->n)
            fail_msg("context %u block %u: cell %d [%u, +%u) opens %d "
                     "clear %d swap %d pre '%s' post '%s'; expected cell %d "
                     "[%u, +%u) opens %d pre '%s' post '%s'",
                     c, i, cell, k->first, k->n, k->opens, k->clear, k->swap,
                     pre, post, w[i].cell, w[i].first, w[i].n, w[i].opens,
                     w[i].pre, w[i].post);
        g_free(pre);
        g_free(post);
    }
}

/* Cell order on a 2 x 2 x 2 grid, 2 contexts, blocks of 2 triangles:
 * cell 0 holds 5 triangles (3 blocks, its waits on the first, its
 * signals on the last), cell 3 none (one empty block, its semaphores
 * kept).  Cell (x, y, z) waits on each lower neighbour (z, then y, then
 * x) and signals once per upper neighbour; context c draws, in each
 * layer z, the cells j = (c + z) mod 2, + 2, ...; Figure 2's loop: the
 * appBarrier on each context's first block, glpWaitContext(0) after it
 * in context 1, glpBarrier after each one's last, context 0's clear
 * first and swap (after the barrier wait) last. */
static void test_cell_streams_exactly(void **state)
{
    (void)state;
    const guint tags[11] = {0, 0, 0, 0, 0, 1, 2, 4, 5, 6, 7};
    SceneMesh *m = tagged_mesh(tags, 11);
    GError *err = NULL;
    AgStreams *s = wl_ag_streams_new(m, 2, WL_AG_ORDER_CELLS,
                                     WL_AG_PRIM_TRIANGLES, 2, 2, &err);
    assert_non_null(s);
    const Want c0[8] = {
        {0, 0, -1, FALSE, TRUE, FALSE, "", ""},
        {0, 2, 0, TRUE, FALSE, FALSE, "A:0", ""},
        {2, 2, 0, FALSE, FALSE, FALSE, "", ""},
        {4, 1, 0, FALSE, FALSE, FALSE, "", "V:0 V:0 V:0"},
        {6, 1, 2, TRUE, FALSE, FALSE, "P:0", "V:2 V:2"},
        {8, 1, 5, TRUE, FALSE, FALSE, "P:1 P:4", "V:5"},
        {10, 1, 7, TRUE, FALSE, FALSE, "P:3 P:5 P:6", "B:0"},
        {0, 0, -1, FALSE, FALSE, TRUE, "BW:0", ""}};
    const Want c1[4] = {
        {5, 1, 1, TRUE, FALSE, FALSE, "P:0 A:0 W:0", "V:1 V:1"},
        {7, 0, 3, TRUE, FALSE, FALSE, "P:1 P:2", "V:3"},
        {7, 1, 4, TRUE, FALSE, FALSE, "P:0", "V:4 V:4"},
        {9, 1, 6, TRUE, FALSE, FALSE, "P:2 P:4", "V:6 B:0"}};
    blocks_are(s, 0, c0, 8);
    blocks_are(s, 1, c1, 4);
    assert_int_equal(s->sems, 8);
    assert_int_equal(s->barriers, 1);
    assert_int_equal(s->barrier_parties, 2);
    assert_int_equal(s->syncs, 30);
    assert_int_equal(wl_ag_n_blocks(s), 12);
    wl_ag_streams_free(s);
    /* frame order: batches dealt round robin, no semaphores */
    s = wl_ag_streams_new(m, 2, WL_AG_ORDER_FRAME, WL_AG_PRIM_TRIANGLES, 2, 0,
                          &err);
    const Want f0[8] = {{0, 0, -1, FALSE, TRUE, FALSE, "", ""},
                        {0, 2, 0, TRUE, FALSE, FALSE, "A:0", ""},
                        {2, 2, 0, FALSE, FALSE, FALSE, "", ""},
                        {4, 1, 0, FALSE, FALSE, FALSE, "", ""},
                        {6, 1, 2, TRUE, FALSE, FALSE, "", ""},
                        {8, 1, 5, TRUE, FALSE, FALSE, "", ""},
                        {10, 1, 7, TRUE, FALSE, FALSE, "", "B:0"},
                        {0, 0, -1, FALSE, FALSE, TRUE, "BW:0", ""}};
    const Want f1[3] = {{5, 1, 1, TRUE, FALSE, FALSE, "A:0 W:0", ""},
                        {7, 1, 4, TRUE, FALSE, FALSE, "", ""},
                        {9, 1, 6, TRUE, FALSE, FALSE, "", "B:0"}};
    blocks_are(s, 0, f0, 8);
    blocks_are(s, 1, f1, 3);
    assert_int_equal(s->sems, 0);
    wl_ag_streams_free(s);
    scene_mesh_free(m);
}

static double metric_at(int frames, const char *name)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "machine: {model: origin2000}\n"
        "workload: {type: argus, processors: 8, contexts: 2,\n"
        "  application: march, cells: 2, order: cells, tile: 32, block: 8,\n"
        "  width: 96, height: 80}\n"
        "scene: {generator: march, grid: 8, cell: 4, iso: 1.67}\n",
        "a.yaml", &err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic", .frames = frames};
    SimResult *r = support_run_tree(root, &o, &err);
    if (!r)
        fail_msg("%s", err->message);
    double px = -1;
    assert_true(sim_result_get_metric(r, name, &px));
    sim_result_free(r);
    return px;
}

static void test_pixels_mean_over_frames(void **state)
{
    (void)state;
    double one = metric_at(1, "pixels");
    assert_true(one > 100);
    assert_true(metric_at(3, "pixels") == one);
    /* frames last about as long: a frame's time is its end - its start */
    double ms1 = metric_at(1, "frame_ms"), ms3 = metric_at(3, "frame_ms");
    assert_true(ms1 > 0 && fabs(ms3 - ms1) < 0.2 * ms1);
}

/* Opaque pixels are z-buffered: two full-screen quads, the nearer
 * (z = -0.5, red) drawn before the farther (z = 0.5, blue), leave the
 * frame (colour, depth, primitive) the nearer alone leaves; drawn the
 * other way round, the same. */
static void test_opaque_depth_test(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    const double z[2] = {-0.5, 0.5};
    for (int q = 0; q < 2; q++) {
        uint32_t v[4];
        const double c[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (int i = 0; i < 4; i++)
            v[i] = scene_mesh_add_vertex(m, vec3(c[i][0], c[i][1], z[q]));
        SceneColor col = scene_color(q ? 0 : 1, 0, q ? 1 : 0);
        scene_mesh_add_tri(m, v[0], v[1], v[2], col, 0);
        scene_mesh_add_tri(m, v[0], v[2], v[3], col, 0);
    }
    RastView view = rast_view_make(mat4_identity(), 16, 16);
    view.cull_back = FALSE;
    const uint32_t near[2] = {0, 1}, both[2][4] = {{0, 1, 2, 3}, {2, 3, 0, 1}};
    AgFrame *want = wl_ag_frame_new(16, 16, 8, WL_AG_OPAQUE, 1,
                                    (RastColor){0, 0, 0});
    wl_ag_draw(want, G_MAXUINT, &view, m, near, 2);
    for (int k = 0; k < 2; k++) {
        AgFrame *f = wl_ag_frame_new(16, 16, 8, WL_AG_OPAQUE, 1,
                                     (RastColor){0, 0, 0});
        assert_int_equal(wl_ag_draw(f, G_MAXUINT, &view, m, both[k], 4),
                         2 * 16 * 16); /* both quads, all drawn */
        assert_memory_equal(f->rgb, want->rgb, 3 * 16 * 16 * sizeof(float));
        assert_memory_equal(f->depth, want->depth, 16 * 16 * sizeof(double));
        assert_memory_equal(f->prim, want->prim, 16 * 16 * sizeof(uint32_t));
        wl_ag_frame_free(f);
    }
    assert_true(want->rgb[0] > 0 && want->rgb[2] == 0); /* red */
    wl_ag_frame_free(want);
    scene_mesh_free(m);
}

/* A Gouraud triangle (red, green and blue corners, no lighting) drawn
 * opaque into the tiled frame, tile by tile, gives the picture the
 * raster module's own z-buffer gives: colours interpolated along each
 * span from its left end, background elsewhere; alpha plays no part. */
static void test_gouraud_as_zbuffer(void **state)
{
    (void)state;
    SceneMesh *m = scene_mesh_new();
    const SceneColor col[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    uint32_t v[3] = {scene_mesh_add_vertex(m, vec3(-0.9, -0.8, 0)),
                     scene_mesh_add_vertex(m, vec3(0.9, -0.6, 0)),
                     scene_mesh_add_vertex(m, vec3(-0.2, 0.9, 0))};
    for (int k = 0; k < 3; k++)
        g_array_append_val(m->colors, col[k]);
    scene_mesh_add_poly(m, v, 3, scene_color(1, 1, 1), 0);
    RastView view = rast_view_make(mat4_identity(), 24, 20);
    view.cull_back = FALSE;
    view.lighting = FALSE;
    view.shading = RAST_SHADE_GOURAUD;
    AgFrame *f = wl_ag_frame_new(24, 20, 8, WL_AG_OPAQUE, 1,
                                 (RastColor){0, 0, 0});
    uint32_t tri = 0;
    uint64_t px = 0;
    for (guint t = 0; t < wl_ag_n_tiles(f); t++)
        px += wl_ag_draw(f, t, &view, m, &tri, 1);
    RastZBuffer *zb = rast_zbuffer_new(24, 20);
    RastCounters c = {0};
    rast_draw_mesh(&view, m, mat4_identity(), scene_color(1, 1, 1), 0,
                   &(RastSubset){&tri, 1},
                   rast_zbuffer_sink(zb), &c);
    assert_int_equal(px, rast_zbuffer_covered(zb));
    assert_true(px > 100);
    RastImage *img = wl_ag_frame_image(f);
    for (int y = 0; y < 20; y++)
        for (int x = 0; x < 24; x++) {
            uint32_t want = zb->rgba[y * 24 + x] ? zb->rgba[y * 24 + x]
                                                 : 0xff000000u;
            if (rast_image_get(img, x, y) != want)
                fail_msg("pixel (%d, %d): %08x, expected %08x", x, y,
                         rast_image_get(img, x, y), want);
        }
    rast_image_free(img);
    /* opaque pixels take the fragment's colour whatever the alpha: the
     * same floats with alpha 0.3 as with 1 */
    AgFrame *g = wl_ag_frame_new(24, 20, 8, WL_AG_OPAQUE, 0.3f,
                                 (RastColor){0, 0, 0});
    for (guint t = 0; t < wl_ag_n_tiles(g); t++)
        wl_ag_draw(g, t, &view, m, &tri, 1);
    assert_memory_equal(g->rgb, f->rgb, 3 * 24 * 20 * sizeof(float));
    wl_ag_frame_free(g);
    rast_zbuffer_free(zb);
    wl_ag_frame_free(f);
    scene_mesh_free(m);
}

/* wl_ag_costs_from_machine fills every field with the machine's cost of
 * the op of the same name (wl_ag_cost_ops order), the first included;
 * a machine without them is refused. */
static void test_costs_from_machine(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    GError *err = NULL;
    MachMachine *m = mach_new_from_model(eng, "origin2000", "analytic", &err);
    assert_non_null(m);
    AgCosts c;
    memset(&c, 0xff, sizeof c);
    assert_true(wl_ag_costs_from_machine(m, &c, &err));
    const SimTime *got = (const SimTime *)&c;
    guint n = 0;
    for (; wl_ag_cost_ops[n]; n++)
        if (got[n] != mach_cost(m, "cpu", wl_ag_cost_ops[n]))
            fail_msg("%s: %" G_GUINT64_FORMAT ", expected %" G_GUINT64_FORMAT,
                     wl_ag_cost_ops[n], (guint64)got[n],
                     (guint64)mach_cost(m, "cpu", wl_ag_cost_ops[n]));
    assert_int_equal(n * sizeof(SimTime), sizeof c);
    mach_free(m);
    /* a machine without Argus's costs (nor a processor description to
     * derive them from): FALSE, naming the first missing */
    CfgNode *bare = cfg_load_string(
        "name: bare\nprovenance: assumption\nnodes: {cpu: {count: 4}}\n"
        "network: {topology: bus, bandwidth: 1 GB/s, startup: 1 us}\n",
        "bare.yaml", &err);
    assert_non_null(bare);
    m = mach_new_from_cfg(eng, bare, "analytic", &err);
    cfg_free(bare);
    if (!m)
        fail_msg("%s", err->message);
    assert_false(wl_ag_costs_from_machine(m, &c, &err));
    assert_non_null(err);
    if (!strstr(err->message, "found no cost for 'nurbs_vertex' on 'cpu'"))
        fail_msg("%s", err->message);
    g_error_free(err);
    mach_free(m);
    sim_engine_free(eng);
}

/* The free functions take NULL (GLib's convention), which the run's
 * clean-up after a failed build relies on. */
static void test_free_null(void **state)
{
    (void)state;
    wl_ag_frame_free(NULL);
    wl_ag_streams_free(NULL);
    wl_ag_pipe_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_triangle_once),
        cmocka_unit_test(test_pixels_mean_over_frames),
        cmocka_unit_test(test_cell_batches_contiguous),
        cmocka_unit_test(test_fragment_colour_clamped),
        cmocka_unit_test(test_bucket_boxes),
        cmocka_unit_test(test_cell_streams_exactly),
        cmocka_unit_test(test_free_null),
        cmocka_unit_test(test_costs_from_machine),
        cmocka_unit_test(test_gouraud_as_zbuffer),
        cmocka_unit_test(test_opaque_depth_test),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
