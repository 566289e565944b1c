/* test_sf_bv.c — bounding-volume kinds of sort-first chunks (sf_bv.h):
 *   - a sphere's screen rectangle is exact: a unit sphere seen from
 *     distance D through a perspective of focal f spans 2 f / sqrt(D²-1)
 *     in NDC, and one wholly behind the eye or off one side is culled;
 *   - every kind holds its chunk: on the small vehicle, over 8 frames,
 *     each instance's volume rectangle contains the rectangle of its
 *     projected vertices (and is on whenever they are);
 *   - the slab set lies inside the box (its axis slabs are the box), so
 *     its area ratio is at most the box's, and both are >= 1;
 *   - runs with each kind render the serial image, and price one test
 *     as documented (box and oriented box 8 transform_vertex, sphere 1
 *     plus sphere_bound, slabs more than 8);
 *   - a bad kind is located.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/scene_cfg.h"
#include "tests/workload/sortfirst/sf_testutil.h"

static const char *const small = SF_TEST_SMALL;

/* Two triangles whose vertices are the unit circle's 4 axis points in
 * z = 0 (box centre the origin, farthest vertex 1), one chunk. */
static WlSfDb *circle_db(SceneDb **src)
{
    Vec3 a[3] = {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0)};
    Vec3 b[3] = {vec3(1, 0, 0), vec3(0, -1, 0), vec3(-1, 0, 0)};
    *src = scene_db_new();
    guint r = scene_db_add_struct(*src, "r");
    SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, a, 3);
    assert_true(scene_db_append(*src, r, &e, NULL));
    e = scene_elem_prim(SCENE_EL_TRIANGLE, b, 3);
    assert_true(scene_db_append(*src, r, &e, NULL));
    scene_db_post(*src, r);
    WlSfDb *db = wl_sf_db_new(*src, 1, 2, WL_SF_CHUNK_SORTED, NULL);
    assert_non_null(db);
    wl_sf_bv_set(db, *src, WL_SF_BV_SPHERE);
    return db;
}

/* Perspective of focal f (aspect 1, near 0.1, far 100) of the camera at
 * (tx, 0, d) looking down -z. */
static Mat4 camera(double f, double tx, double d)
{
    Mat4 p = {{{f, 0, 0, 0},
               {0, f, 0, 0},
               {0, 0, -100.1 / 99.9, -2 * 100 * 0.1 / 99.9},
               {0, 0, -1, 0}}};
    return mat4_mul(p, mat4_translate(-tx, 0, -d));
}

static void test_sphere_exact(void **st)
{
    (void)st;
    SceneDb *src;
    WlSfDb *db = circle_db(&src);
    WlSfRegions r;
    wl_sf_regions_init(&r, 1, 100, 100);
    double f = 2, d = 5;
    WlSfScreen s = wl_sf_bv_screen(db, &r, 0, camera(f, 0, d));
    assert_true(s.on);
    double half = f / sqrt(d * d - 1) * 50; /* pixels */
    assert_true(fabs(s.x0 - (50 - half)) < 1e-6);
    assert_true(fabs(s.x1 - (50 + half)) < 1e-6);
    assert_true(fabs(s.y0 - (50 - half)) < 1e-6);
    assert_true(fabs(s.y1 - (50 + half)) < 1e-6);
    /* the box's rectangle is looser: its near face is closer */
    WlSfScreen bx = wl_sf_screen_of(&r, wl_sf_chunk(db, 0)->box,
                                    camera(f, 0, d));
    assert_true(bx.x1 - bx.x0 < s.x1 - s.x0); /* flat box: a square */
    /* behind the eye, and far off to the side: culled */
    assert_false(wl_sf_bv_screen(db, &r, 0, camera(f, 0, -5)).on);
    assert_false(wl_sf_bv_screen(db, &r, 0, camera(f, 50, d)).on);
    /* around the eye: the whole plane */
    WlSfScreen in = wl_sf_bv_screen(db, &r, 0, camera(f, 0, 0.5));
    assert_true(in.on && isinf(in.x0) && isinf(in.x1));
    wl_sf_db_free(db);
    scene_db_free(src);
}

/* The rectangle of chunk c's vertices under m (each a point box). */
static WlSfScreen vertex_rect(const WlSfDb *d, const SceneDb *db,
                              const WlSfRegions *r, guint c, Mat4 m)
{
    const WlSfChunk *ch = wl_sf_chunk(d, c);
    WlSfScreen s = {INFINITY, INFINITY, -INFINITY, -INFINITY, FALSE};
    unsigned all = 0x3f;
    gboolean behind = FALSE;
    for (guint k = 0; k < ch->n_prims; k++) {
        guint pos = g_array_index(d->prims, guint, ch->prim_first + k);
        const SceneElem *e = scene_db_elem(db, ch->sid, pos);
        for (guint v = 0; v < e->nverts; v++)
            all &= wl_sf_screen_point(r, mat4_apply_point(m, e->verts[v]), &s,
                                      &behind);
    }
    s.on = !all;
    if (behind) {
        s.x0 = s.y0 = -INFINITY;
        s.x1 = s.y1 = INFINITY;
    }
    return s;
}

static void test_holds_chunks(void **st)
{
    (void)st;
    GError *e = NULL;
    CfgNode *root = cfg_load_string(small, "sf.yaml", &e);
    Scene *scene = scene_from_cfg(cfg_get(root, "scene"), &e);
    assert_non_null(scene);
    WlSfRegions r;
    wl_sf_regions_init(&r, 4, 64, 64);
    for (int kind = WL_SF_BV_SPHERE; kind <= WL_SF_BV_SLABS; kind++) {
        WlSfDb *d = wl_sf_db_new(scene->db, 4, 5, WL_SF_CHUNK_SORTED, &e);
        wl_sf_bv_set(d, scene->db, (WlSfBvKind)kind);
        uint64_t on = 0;
        for (int f = 0; f < 8; f++) {
            SceneCamera cam = scene_camera_at(scene, f);
            Mat4 vp = rast_view_for_camera(&cam, 64, 64).view_proj;
            for (guint i = 0; i < wl_sf_n_insts(d); i++) {
                const WlSfInst *in = wl_sf_inst(d, i);
                Mat4 m = mat4_mul(vp, in->matrix);
                WlSfScreen ex = vertex_rect(d, scene->db, &r, in->chunk, m);
                WlSfScreen bv = wl_sf_bv_screen(d, &r, in->chunk, m);
                if (!ex.on)
                    continue;
                on++;
                assert_true(bv.on);
                double eps = 1e-6 * 64;
                assert_true(bv.x0 <= ex.x0 + eps && bv.x1 >= ex.x1 - eps);
                assert_true(bv.y0 <= ex.y0 + eps && bv.y1 >= ex.y1 - eps);
            }
        }
        assert_true(on > 100);
        wl_sf_db_free(d);
    }
    scene_free(scene);
    cfg_free(root);
}

static SimResult *run_bv(const char *kind)
{
    return sf_test_run_checked(small, 4, "workload.bounding_volume", kind,
                               "workload.traversal", "culled");
}

static void test_runs(void **st)
{
    (void)st;
    SimResult *r[4];
    double ratio[4], tests[4];
    for (int k = 0; k < 4; k++) {
        r[k] = run_bv(wl_sf_bv_names[k]);
        ratio[k] = sf_test_metric(r[k], "bv_area_ratio");
        tests[k] = sf_test_metric(r[k], "bv_test_ns");
        assert_true(ratio[k] >= 1);
        assert_true(sf_test_metric(r[k], "bv_false_regions_per_polygon") >= 0);
    }
    assert_true(ratio[WL_SF_BV_SLABS] < ratio[WL_SF_BV_AABB]);
    SfEditFixture f;
    const WlSfEditSpec none = {{0}, 0};
    sf_test_edit_init(&f, WL_SF_MAXSET, &none);
    double tv = (double)f.c.transform_vertex / 1e3; /* ns */
    double sb = (double)f.c.sphere_bound / 1e3;
    sf_test_edit_clear(&f);
    assert_true(fabs(tests[WL_SF_BV_AABB] - 8 * tv) < 1e-9);
    assert_true(fabs(tests[WL_SF_BV_OBB] - 8 * tv) < 1e-9);
    assert_true(fabs(tests[WL_SF_BV_SPHERE] - (tv + sb)) < 1e-9);
    assert_true(tests[WL_SF_BV_SLABS] > 8 * tv);
    /* the box run's frame is the default's: the metric costs nothing */
    SimResult *plain = sf_test_run_checked(small, 4, "workload.traversal",
                                           "culled", "workload.granularity",
                                           "5");
    assert_true(sf_test_metric(plain, "frame_ms") ==
                sf_test_metric(r[WL_SF_BV_AABB], "frame_ms"));
    sim_result_free(plain);
    for (int k = 0; k < 4; k++)
        sim_result_free(r[k]);
}

static void test_bad_kind(void **st)
{
    (void)st;
    const char *const o[] = {"workload.bounding_volume=cone", NULL};
    GError *e = NULL;
    SimResult *r = sf_test_run(small, o, 1, NULL, FALSE, &e);
    assert_null(r);
    assert_non_null(strstr(e->message, "cone"));
    assert_non_null(strstr(e->message, "aabb"));
    g_error_free(e);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_exact),
        cmocka_unit_test(test_holds_chunks),
        cmocka_unit_test(test_runs),
        cmocka_unit_test(test_bad_kind),
    };
    return cmocka_run_group_tests_name("sf_bv", tests, NULL, NULL);
}
