/* test_pm_volume.c — the volume workload (pm_volume.h, pm_images.h):
 * the lattice field is the isosurface's field at its points and
 * trilinear between them; the ray-cast samples split among the blocks
 * without loss or overlap; at 1, 2, 8, 12 and 64 processes, perspective
 * and orthographic, the blocks' partial images composited with over by
 * binary swap, radix-k and direct send in view order equal the whole
 * volume cast by one process to 1e-9, and the isosurface drawn by block and
 * composited with z equals it drawn whole, exactly (both checks shown failing:
 * the reversed order, a block left out); whole frames with block and volume
 * images on a 64-node hypercube pass their image check and send their
 * merge bytes over the network; the shipped configs
 * (configs/composite-blocks.yaml, composite-volume.yaml) run, made
 * small, with both operators and their images checked.  The config
 * keys: test_pm_parse.c. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/run/run.h"
#include "sim/workload/pixelmerge/pm_workload.h"

enum { N = 40 };

static const guint counts[] = {1, 2, 8, 12, 64};
static const WlPmFormat fmt = {8, 4, 2, 4, 8};
static const WlPmScheme schemes[] = {WL_PM_BINARY_SWAP, WL_PM_RADIX_K,
                                     WL_PM_DIRECT_SEND};

static SceneCamera camera_of(SceneProjection proj)
{
    SceneCamera c = scene_camera_default();
    c.proj = proj;
    c.eye = vec3(2.6, 1.9, 3.4);
    scene_camera_fit(&c, (SceneBox){{-1, -1, -1}, {1, 1, 1}}, 1.0);
    return c;
}

static SceneCamera camera(void)
{
    return camera_of(SCENE_PERSPECTIVE);
}

static WlPmImages volume(void)
{
    WlPmImages im = {.kind = WL_PM_IMAGES_VOLUME,
                     .vol = wl_pm_volume_defaults()};
    im.vol.iso.grid = 12;
    im.vol.step = 0.05;
    return im;
}

static void test_field(void **st)
{
    (void)st;
    for (int kind = 0; kind < 2; kind++) {
        SceneIsoParams iso = scene_iso_defaults();
        iso.field = (SceneFieldKind)kind;
        iso.grid = 8;
        WlPmField *f = wl_pm_field_new(&iso);
        Vec3 *ctr = scene_iso_centres(&iso);
        Vec3 a = vec3(-0.5, 0.25, 0.75), b = vec3(-0.25, 0.25, 0.75);
        double fa = scene_iso_field(&iso, ctr, a);
        double fb = scene_iso_field(&iso, ctr, b);
        assert_true(wl_pm_field_at(f, a) == fa);
        assert_true(fabs(wl_pm_field_at(f, vec3(-0.375, 0.25, 0.75)) -
                         (fa + fb) / 2) < 1e-12);
        assert_true(fabs(wl_pm_field_at(f, vec3(1, 1, 1)) -
                         scene_iso_field(&iso, ctr, vec3(1, 1, 1))) < 1e-12);
        g_free(ctr);
        wl_pm_field_free(f);
    }
}

static RastView view_of(const SceneCamera *c)
{
    return rast_view_for_camera(c, N, N);
}

/* The samples every block takes add up to the serial render's. */
static void test_samples_partition(void **st)
{
    (void)st;
    SceneCamera c = camera();
    RastView v = view_of(&c);
    WlPmImages im = volume();
    WlPmImageSet *one = wl_pm_images_make(&im, &c, &v, 1, WL_PM_OP_OVER);
    uint64_t serial = one->counts[0].rc.pixels;
    assert_true(serial > 10000);
    assert_true(wl_pm_wpa_len(one->local[0]) > 500);
    for (guint i = 1; i < G_N_ELEMENTS(counts); i++) {
        WlPmImageSet *s =
            wl_pm_images_make(&im, &c, &v, counts[i], WL_PM_OP_OVER);
        uint64_t sum = 0;
        for (guint p = 0; p < counts[i]; p++)
            sum += s->counts[p].rc.pixels;
        assert_int_equal(sum, serial);
        wl_pm_images_free(s);
    }
    wl_pm_images_free(one);
}

static void check_volume(WlPmOperator op, SceneProjection proj)
{
    SceneCamera c = camera_of(proj);
    RastView v = view_of(&c);
    WlPmImages im = volume();
    for (guint i = 0; i < G_N_ELEMENTS(counts); i++) {
        guint n = counts[i];
        WlPmImageSet *s = wl_pm_images_make(&im, &c, &v, n, op);
        for (guint k = 0; k < G_N_ELEMENTS(schemes); k++)
            for (int opt = 0; opt < 4; opt += 3) {
                WlPmCompose cp = {.bounding_rect = opt & 1,
                                  .rle = (opt & 2) != 0,
                                  .op = op,
                                  .opacity = 0.5,
                                  .order = s->order};
                WlPmComposite *r =
                    wl_pm_composite_run(schemes[k], &cp, s->local, n, &fmt);
                if (!wl_pm_images_match(&im, s, &c, &v, op, r))
                    fail_msg("%s P=%u op=%d opt=%d: not the serial render",
                             wl_pm_scheme_names[schemes[k]], n, op, opt);
                wl_pm_composite_free(r);
            }
        if (n == 8) { /* can fail: over in reverse, z without a block */
            guint rev[8];
            for (guint k = 0; k < 8; k++)
                rev[k] = s->order[7 - k];
            WlPmWpa *kept = s->local[s->order[0]];
            if (op == WL_PM_OP_Z)
                s->local[s->order[0]] = wl_pm_wpa_new(N, N);
            wl_pm_wpa_finish(s->local[s->order[0]]);
            WlPmCompose cp = {.op = op, .order = rev, .opacity = 0.5};
            WlPmComposite *r =
                wl_pm_composite_run(WL_PM_RADIX_K, &cp, s->local, n, &fmt);
            assert_false(wl_pm_images_match(&im, s, &c, &v, op, r));
            wl_pm_composite_free(r);
            if (op == WL_PM_OP_Z) {
                wl_pm_wpa_free(s->local[s->order[0]]);
                s->local[s->order[0]] = kept;
            }
        }
        wl_pm_images_free(s);
    }
}

static void test_volume_over(void **st)
{
    (void)st;
    check_volume(WL_PM_OP_OVER, SCENE_PERSPECTIVE);
    check_volume(WL_PM_OP_OVER, SCENE_ORTHOGRAPHIC);
}

static void test_volume_z(void **st)
{
    (void)st;
    check_volume(WL_PM_OP_Z, SCENE_PERSPECTIVE);
    check_volume(WL_PM_OP_Z, SCENE_ORTHOGRAPHIC);
}

/* One frame on a 64-node hypercube. */
static void run_on(const Scene *sc, const WlPmSetup *s, WlPmFrameOut *out,
                   uint64_t *net_bytes)
{
    NetParams np = {.bandwidth = 2.8e6,
                    .channels = 1,
                    .startup = 350 * SIM_US,
                    .per_hop = 10 * SIM_US,
                    .switching = NET_SW_CIRCUIT};
    static const WlPmCosts costs = {
        .pixel = SIM_US,
        .scanline = SIM_US,
        .polygon = SIM_US,
        .span = SIM_US,
        .merge = {.pack = SIM_US, .compare = SIM_US, .count_bytes = 4}};
    SimEngine *eng = sim_engine_new(1);
    NetTopo *topo = net_hypercube_new(6);
    NetNet *net = net_new(eng, topo, &np, NET_FLOW);
    GError *err = NULL;
    assert_true(wl_pm_frame_run(net, sc, s, &costs, out, &err));
    *net_bytes = net_total_bytes(net);
    net_free(net);
    net_topo_free(topo);
    sim_engine_free(eng);
}

static void test_frames(void **st)
{
    (void)st;
    Scene *sc = scene_new("camera only");
    sc->camera = camera();
    for (int kind = WL_PM_IMAGES_BLOCKS; kind <= WL_PM_IMAGES_VOLUME; kind++)
        for (int op = 0; op < 2; op++) {
            WlPmSetup s = {.scheme = WL_PM_RADIX_K,
                           .procs = 12,
                           .resolution = N,
                           .fmt = fmt,
                           .check_image = TRUE,
                           .comp = {.op = (WlPmOperator)op, .opacity = 0.5},
                           .images = volume()};
            s.images.kind = (WlPmImageKind)kind;
            s.images.density = 1.5;
            WlPmFrameOut out;
            uint64_t bytes;
            run_on(sc, &s, &out, &bytes);
            if (!out.image_checked || !out.image_ok)
                fail_msg("images %d op %d: not the serial render", kind, op);
            assert_int_equal(bytes, out.merge_bytes);
            assert_true(out.merge_ms > 0 && out.tpf > 0);
            wl_pm_frame_out_clear(&out, 12);
        }
    scene_free(sc);
}

/* The shipped configs at 48 x 48, 8 processes, z and over. */
static void test_shipped_configs(void **st)
{
    (void)st;
    const char *files[] = {"configs/composite-blocks.yaml",
                           "configs/composite-volume.yaml"};
    const char *ops[] = {"workload.operator=z", "workload.operator=over"};
    for (guint i = 0; i < G_N_ELEMENTS(files); i++)
        for (guint k = 0; k < G_N_ELEMENTS(ops); k++) {
            const char *set[] = {"workload.resolution=48",
                                 "workload.processors=8", ops[k], NULL};
            GError *err = NULL;
            CfgRun *r = cfg_run_load(files[i], set, &err);
            if (!r)
                fail_msg("%s: %s", files[i], err->message);
            CfgRunOpts o = {.quiet = TRUE};
            SimResult *res = cfg_run_exec(r, &o, &err);
            if (!res)
                fail_msg("%s: %s", files[i], err->message);
            assert_true(sim_result_metric(res, "image_matches_serial") == 1);
            assert_true(sim_result_metric(res, "merge_bytes") > 0);
            assert_true(sim_result_metric(res, "composite_stages") == 1);
            sim_result_free(res);
            cfg_run_free(r);
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_field),
        cmocka_unit_test(test_samples_partition),
        cmocka_unit_test(test_volume_over),
        cmocka_unit_test(test_volume_z),
        cmocka_unit_test(test_frames),
        cmocka_unit_test(test_shipped_configs),
    };
    return cmocka_run_group_tests_name("pm_volume", tests, NULL, NULL);
}
