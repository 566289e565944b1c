/* test_pm_render.c — the local rendering of pixel merging (pm_render.h)
 * checked against the raster library itself (issue 21): on one processor
 * wl_pm_render_local's pixels (x, y, depth, id, colour) and raster counts
 * equal rast_draw_mesh's of the flattened scene into a span list and the
 * modified scanline z-buffer, span_rows and insert_steps are recomputed from
 * that span list (s (s - 1) / 4 per row of s spans), each processor's share is
 * the ids worked out by hand for both splits (and draws as rast_draw_mesh of
 * those ids), and the merged frame image equals the raster library's
 * image, channel order included. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/raster/image.h"
#include "sim/scene/teapot.h"
#include "sim/workload/pixelmerge/pm_frame.h"

enum { N = 32, POLYS = 600 };

/* Two teapots of distinct colours; fill 3 overflows the top and bottom edges,
 * so rows 0 and N - 1 have spans. */
static Scene *pots(void)
{
    SceneTeapotTess t;
    assert_true(scene_teapot_tess_for(300, "test", &t, NULL));
    Scene *s = scene_new("pots");
    guint m = scene_add_mesh(s, scene_teapot_mesh(t, scene_color(1, 1, 1)));
    scene_add_instance(s, m, mat4_identity(), scene_color(0.9f, 0.3f, 0.1f),
                       0);
    scene_add_instance(s, m, mat4_translate(2.0, 0.8, -1.5),
                       scene_color(0.2f, 0.5f, 0.8f), 1);
    s->camera = scene_camera_default();
    s->camera.eye = vec3(1.0, 4.0, 9.0);
    scene_camera_fit(&s->camera, scene_bbox(s), 3.0);
    return s;
}

static RastView view(const Scene *sc)
{
    SceneCamera cam = scene_camera_at(sc, 0);
    RastView v = rast_view_for_camera(&cam, N, N);
    v.cull_back = TRUE;
    return v;
}

/* The raster library's render of a span list: sorted, z-buffered. */
typedef struct {
    RastSpanList *sl;
    RastActive *a;
    RastCounters rc;
} Ref;

static void ref_finish(Ref *r)
{
    rast_spanlist_sort(r->sl);
    r->a = rast_active_new(N, N);
    rast_scanline_zbuffer(r->a, r->sl, &r->rc);
}

/* Every polygon of the flattened scene, untinted, ids 0 .. POLYS - 1. */
static Ref whole(const RastView *v, const SceneMesh *flat)
{
    Ref r = {rast_spanlist_new(N, N), NULL, {0}};
    rast_draw_mesh(v, flat, mat4_identity(), scene_color(1, 1, 1), 0, NULL,
                   rast_spanlist_sink(r.sl), &r.rc);
    ref_finish(&r);
    return r;
}

static void ref_clear(Ref *r)
{
    rast_active_free(r->a);
    rast_spanlist_free(r->sl);
}

/* 0xAABBGGRR (raster) as WlPmPixel's 0xRRGGBB. */
static uint32_t rgb_of(uint32_t rgba)
{
    return (rgba & 0xffu) << 16 | (rgba & 0xff00u) | (rgba >> 16 & 0xffu);
}

/* w and k equal the reference, pixel for pixel and count for count. */
static void check_local(const WlPmWpa *w, const WlPmCounts *k, const Ref *r)
{
    assert_memory_equal(&k->rc, &r->rc, sizeof k->rc);
    uint64_t rows = 0, steps = 0;
    for (int y = 0; y < N; y++) {
        size_t s, n;
        rast_spanlist_row(r->sl, y, &s);
        rows += s > 0;
        steps += s ? (uint64_t)s * (s - 1) / 4 : 0;
        const RastActivePixel *a = rast_active_row(r->a, y, &n);
        assert_int_equal(wl_pm_wpa_row_len(w, (guint)y), n);
        const WlPmPixel *p = wl_pm_wpa_row(w, (guint)y);
        for (size_t i = 0; i < n; i++) {
            assert_int_equal(p[i].x, a[i].x);
            assert_int_equal(p[i].y, y);
            assert_true(p[i].z == a[i].z);
            assert_int_equal(p[i].poly, a[i].prim);
            assert_int_equal(p[i].color, rgb_of(a[i].rgba));
        }
    }
    assert_int_equal(k->span_rows, rows);
    assert_int_equal(k->insert_steps, steps);
}

static void test_one_processor_is_the_raster_render(void **state)
{
    (void)state;
    Scene *sc = pots();
    RastView v = view(sc);
    SceneMesh *flat = scene_flatten(sc);
    Ref r = whole(&v, flat);
    size_t s0, s1;
    rast_spanlist_row(r.sl, 0, &s0);
    rast_spanlist_row(r.sl, N - 1, &s1);
    assert_true(s0 > 2 && s1 > 0); /* both edge rows drawn */
    for (int split = 0; split < 2; split++) {
        WlPmCounts k;
        WlPmWpa *w = wl_pm_render_local(&v, flat, 0, 1, (WlPmSplit)split, &k);
        assert_int_equal(k.polygons, POLYS);
        check_local(w, &k, &r);
        assert_true(k.span_rows == N && k.insert_steps > 0);
        wl_pm_wpa_free(w);
    }
    scene_mesh_free(flat);
    ref_clear(&r);
    scene_free(sc);
}

/* Processor p's ids by hand: cyclic p, p + P, ...; block the p-th run
 * [POLYS p / P, POLYS (p + 1) / P) (POLYS = 600 does not divide by 7). */
static guint share_ids(WlPmSplit split, guint p, guint P, uint32_t *ids)
{
    guint k = 0;
    for (guint i = 0; i < POLYS; i++)
        if (split == WL_PM_SPLIT_CYCLIC ? i % P == p
                                        : i >= POLYS * p / P &&
                                              i < POLYS * (p + 1) / P)
            ids[k++] = i;
    return k;
}

static void check_shares(const Scene *sc, WlPmSplit split, guint P)
{
    RastView v = view(sc);
    SceneMesh *flat = scene_flatten(sc);
    uint32_t ids[POLYS];
    guint total = 0;
    for (guint p = 0; p < P; p++) {
        guint n = share_ids(split, p, P, ids);
        Ref r = {rast_spanlist_new(N, N), NULL, {0}};
        rast_draw_mesh(&v, flat, mat4_identity(), scene_color(1, 1, 1), 0,
                       &(RastSubset){ids, n}, rast_spanlist_sink(r.sl), &r.rc);
        ref_finish(&r);
        WlPmCounts k;
        WlPmWpa *w = wl_pm_render_local(&v, flat, p, P, split, &k);
        assert_int_equal(k.polygons, n);
        check_local(w, &k, &r);
        total += n;
        wl_pm_wpa_free(w);
        ref_clear(&r);
    }
    assert_int_equal(total, POLYS);
    scene_mesh_free(flat);
}

static void test_shares(void **state)
{
    (void)state;
    Scene *sc = pots();
    const guint P[] = {2, 7, 8};
    for (guint i = 0; i < G_N_ELEMENTS(P); i++) {
        check_shares(sc, WL_PM_SPLIT_CYCLIC, P[i]);
        check_shares(sc, WL_PM_SPLIT_BLOCK, P[i]);
    }
    assert_int_equal(share_ids(WL_PM_SPLIT_BLOCK, 0, 7, (uint32_t[POLYS]){0}),
                     85); /* 600 / 7 = 85.7: the first run is 85 ids */
    scene_free(sc);
}

/* More processors than polygons: the extra processors draw nothing and
 * return an empty array with zero counts. */
static void test_empty_share(void **state)
{
    (void)state;
    Scene *sc = pots();
    RastView v = view(sc);
    SceneMesh *flat = scene_flatten(sc);
    for (int split = 0; split < 2; split++) {
        WlPmCounts k;
        memset(&k, 0xff, sizeof k);
        WlPmWpa *w =
            wl_pm_render_local(&v, flat, 700, 1024, (WlPmSplit)split, &k);
        WlPmCounts zero = {0};
        assert_memory_equal(&k, &zero, sizeof k);
        assert_int_equal(wl_pm_wpa_len(w), 0);
        assert_int_equal(w->row_start[N], 0);
        wl_pm_wpa_free(w);
    }
    scene_mesh_free(flat);
    scene_free(sc);
}

/* The merged frame's image (keep_image) is the raster library's image of
 * the whole scene on a black background, every channel in its place. */
static void test_frame_image_is_the_raster_image(void **state)
{
    (void)state;
    Scene *sc = pots();
    RastView v = view(sc);
    SceneMesh *flat = scene_flatten(sc);
    Ref r = whole(&v, flat);
    RastImage *want = rast_image_new(N, N);
    rast_image_from_active(want, r.a, (RastColor){0, 0, 0});
    WlPmSetup s = {.scheme = WL_PM_AAPC, .balance = WL_PM_BAL_RS, .procs = 4,
                   .resolution = N, .split = WL_PM_SPLIT_CYCLIC,
                   .fmt = {8, 4, 2}, .cull_back = TRUE,
                   .span_rule = RAST_SPAN_EXACT, .keep_image = TRUE};
    WlPmCosts c = {.polygon = SIM_US, .merge = {.count_bytes = 4}};
    NetParams np = {.bandwidth = 1e6, .channels = 1, .startup = SIM_US,
                    .switching = NET_SW_CIRCUIT};
    SimEngine *eng = sim_engine_new(1);
    NetTopo *topo = net_hypercube_new(2);
    NetNet *net = net_new(eng, topo, &np, NET_ANALYTIC);
    WlPmFrameOut out;
    GError *err = NULL;
    assert_true(wl_pm_frame_run(net, sc, &s, &c, &out, &err));
    assert_non_null(out.image);
    assert_int_equal(rast_image_diff(out.image, want), 0);
    /* the first teapot is mostly red: some pixel has red above blue */
    guint reddish = 0;
    for (int i = 0; i < N * N; i++)
        reddish += want->rgb[3 * i] > want->rgb[3 * i + 2] + 40;
    assert_true(reddish > 10);
    wl_pm_frame_out_clear(&out, s.procs);
    net_free(net);
    net_topo_free(topo);
    sim_engine_free(eng);
    rast_image_free(want);
    ref_clear(&r);
    scene_mesh_free(flat);
    scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_processor_is_the_raster_render),
        cmocka_unit_test(test_shares),
        cmocka_unit_test(test_empty_share),
        cmocka_unit_test(test_frame_image_is_the_raster_image),
    };
    return cmocka_run_group_tests_name("pm_render", tests, NULL, NULL);
}
