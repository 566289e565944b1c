/* test_pphigs_pixels.c — Pixel-Planes 5 renderers that draw: the frame
 * the renderers evaluate region by region and the frame buffer assembles
 * equals a serial render of the whole list, for every database at 1, 3,
 * 4 and 16 GPs and both algorithms; a missing primitive makes the images
 * differ (the comparison has teeth); two triangles sharing an edge draw
 * each pixel once; the visibility key makes the result independent of
 * drawing order; ODPs win over 3D primitives and later priorities over
 * earlier ones; renderer time is the counted expressions.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/pphigs_frame.h"
#include "sim/workload/pphigs/pphigs_pixels.h"
#include <string.h>

static const char *const MACHINE =
    "model: pixel-planes-5\n"
    "nodes:\n"
    "  gp: {count: %u}\n"
    "  renderer: {count: %u, costs: {expression: 1 us, compare: 3 us}}\n";

static ScenePphigsDb make_db(ScenePphigsKind k)
{
    ScenePphigsSpec s = {.kind = k,
                         .seed = 3,
                         .polygons = 400,
                         .attributes = 40,
                         .verts = 4,
                         .size = 100,
                         .fov_deg = 51,
                         .boids = 20,
                         .boid_polygons = 5,
                         .boid_colors = 4,
                         .well_structs = 6,
                         .well_polygons = 40,
                         .well_attributes = 4,
                         .figures = 2,
                         .structures = 20,
                         .levels = 5};
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    return db;
}

static WlPphigsFrameSpec spec(void)
{
    return (WlPphigsFrameSpec){.cmd_bytes = 100,
                               .end_bytes = 16,
                               .batch = 8,
                               .pixel_bytes = 4,
                               .width = 320,
                               .height = 256,
                               .region = 64,
                               .element_bytes = 80};
}

typedef struct {
    RastImage *img;
    uint64_t exprs, commands;
    SimTime rast_busy;
} Frame;

/* One frame of db on ngp GPs and nrend renderers. */
static Frame run_frame(const ScenePphigsDb *db, guint ngp, guint nrend,
                       WlPphigsAlgo a)
{
    SimEngine *eng = sim_engine_new(1);
    char *text = g_strdup_printf(MACHINE, ngp, nrend);
    CfgNode *sec = cfg_load_string(text, "test-machine.yaml", NULL);
    MachMachine *m = mach_new_from_cfg(eng, sec, "analytic", NULL);
    assert_non_null(m);
    WlPphigsFrameSpec s = spec();
    WlPphigsFrame *f = wl_pphigs_frame_new(m, &s, NULL);
    assert_non_null(f);
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(wl_pphigs_frame_costs(f), 4, &w);
    WlPphigsDist *d = wl_pphigs_dist_new(db->db, ngp, a, &w);
    WlPphigsFrameStats st;
    assert_true(wl_pphigs_frame_run(f, d, scene_camera_view_proj(&db->camera),
                                    NULL, &st, NULL));
    const RastImage *img = wl_pphigs_frame_image(f);
    Frame out = {rast_image_new(img->width, img->height), st.expressions,
                 st.commands, 0};
    memcpy(out.img->rgb, img->rgb, (gsize)3 * img->width * img->height);
    for (guint r = 0; r < nrend; r++)
        out.rast_busy += mach_proc_busy_phase(
            mach_proc(m, "renderer", r), sim_engine_phase(eng, "rasterise"));
    wl_pphigs_dist_free(d);
    wl_pphigs_frame_free(f);
    mach_free(m);
    cfg_free(sec);
    g_free(text);
    sim_engine_free(eng);
    return out;
}

static uint64_t lit_pixels(const RastImage *img)
{
    uint64_t n = 0;
    for (int i = 0; i < img->width * img->height; i++)
        n += img->rgb[3 * i] || img->rgb[3 * i + 1] || img->rgb[3 * i + 2];
    return n;
}

static void test_frame_equals_serial(void **st)
{
    (void)st;
    static const guint gps[] = {1, 3, 4, 16}, rends[] = {1, 5, 4, 16};
    for (int k = SCENE_PPHIGS_STATION; k <= SCENE_PPHIGS_HUMANS; k++) {
        ScenePphigsDb db = make_db((ScenePphigsKind)k);
        WlPphigsFrameSpec s = spec();
        RastImage *ref = wl_pphigs_render_serial(
            db.db, scene_camera_view_proj(&db.camera), s.width, s.height);
        if (lit_pixels(ref) < 200)
            fail_msg("db %d: %llu lit pixels", k,
                     (unsigned long long)lit_pixels(ref));
        for (guint i = 0; i < G_N_ELEMENTS(gps); i++)
            for (int a = WL_PPHIGS_SIMPLE; a <= WL_PPHIGS_COMPLEX; a++) {
                Frame fr = run_frame(&db, gps[i], rends[i], (WlPphigsAlgo)a);
                if (!rast_image_equal(fr.img, ref))
                    fail_msg("db %d, %u GPs, algo %d: %llu pixels differ", k,
                             gps[i], a,
                             (unsigned long long)rast_image_diff(fr.img, ref));
                rast_image_free(fr.img);
            }
        rast_image_free(ref);
        scene_pphigs_db_clear(&db);
    }
}

/* Deleting one on-screen primitive changes the serial image: equality
 * above is not the comparison of two empty pictures. */
static void test_missing_primitive_differs(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db(SCENE_PPHIGS_STATION);
    WlPphigsFrameSpec s = spec();
    Mat4 vp = scene_camera_view_proj(&db.camera);
    RastImage *ref = wl_pphigs_render_serial(db.db, vp, s.width, s.height);
    guint sid = scene_db_posted_at(db.db, 0), changed = 0;
    for (guint pos = 0; pos < scene_db_len(db.db, sid) && !changed; pos++) {
        if (scene_db_elem(db.db, sid, pos)->kind != SCENE_EL_POLYGON)
            continue;
        SceneDb *cut = scene_db_copy(db.db);
        scene_db_delete(cut, sid, pos);
        RastImage *img = wl_pphigs_render_serial(cut, vp, s.width, s.height);
        changed = rast_image_diff(img, ref) > 0;
        rast_image_free(img);
        scene_db_free(cut);
    }
    assert_true(changed);
    rast_image_free(ref);
    scene_pphigs_db_clear(&db);
}

static ScenePrimInst tri(SceneElem *e, Vec3 a, Vec3 b, Vec3 c, uint64_t tag)
{
    Vec3 v[3] = {a, b, c};
    *e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    e->verts = g_memdup2(v, sizeof v);
    e->tag = tag;
    return (ScenePrimInst){.el = e, .matrix = mat4_identity(),
                           .color = vec3(1, 1, 1)};
}

static WlPphigsCmd one_cmd(const ScenePrimInst *pi, guint w, guint h)
{
    GArray *a = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    assert_int_equal(wl_pphigs_cmds(pi, mat4_identity(), w, h, a), 1);
    WlPphigsCmd c = g_array_index(a, WlPphigsCmd, 0);
    g_array_unref(a);
    return c;
}

/* A square split along its diagonal: every pixel inside is drawn by
 * exactly one of the two triangles (no gap, no double draw). */
static void test_shared_edge_once(void **st)
{
    (void)st;
    SceneElem e1, e2;
    Vec3 p0 = vec3(-0.7, -0.6, 0), p1 = vec3(0.5, -0.65, 0),
         p2 = vec3(0.55, 0.7, 0), p3 = vec3(-0.6, 0.6, 0);
    ScenePrimInst a = tri(&e1, p0, p1, p2, 1), b = tri(&e2, p0, p2, p3, 2);
    WlPphigsCmd ca = one_cmd(&a, 97, 83), cb = one_cmd(&b, 97, 83);
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, 97, 83, 0);
    uint64_t na = wl_pphigs_region_draw(r, &ca);
    WlPphigsRegion *q = wl_pphigs_region_new(0, 0, 97, 83, 0);
    uint64_t nb = wl_pphigs_region_draw(q, &cb);
    uint64_t both = 0, either = 0;
    for (int i = 0; i < 97 * 83; i++) {
        both += r->key[i] && q->key[i];
        either += r->key[i] || q->key[i];
    }
    assert_true(na > 500 && nb > 500);
    assert_int_equal(both, 0);
    assert_int_equal(either, na + nb);
    wl_pphigs_region_free(r);
    wl_pphigs_region_free(q);
    g_free(e1.verts);
    g_free(e2.verts);
}

/* Overlapping triangles at different depths, an ODP over them: any
 * drawing order gives the same pixels; the nearer triangle and the ODP
 * win where they cover. */
static void test_order_independent(void **st)
{
    (void)st;
    SceneElem e[3];
    ScenePrimInst far = tri(&e[0], vec3(-0.9, -0.9, 0.5), vec3(0.9, -0.9, 0.5),
                            vec3(0, 0.9, 0.5), 1);
    ScenePrimInst near = tri(&e[1], vec3(-0.5, 0.8, -0.2),
                             vec3(0.8, 0.8, -0.2), vec3(0, -0.8, -0.2), 2);
    ScenePrimInst odp = tri(&e[2], vec3(-0.2, -0.2, 0.9), vec3(0.2, -0.2, 0.9),
                            vec3(0, 0.2, 0.9), 3);
    e[2].kind = SCENE_EL_POLYGON2D;
    far.color = vec3(1, 0, 0), near.color = vec3(0, 1, 0),
    odp.color = vec3(0, 0, 1);
    odp.priority = 1;
    WlPphigsCmd c[3] = {one_cmd(&far, 64, 64), one_cmd(&near, 64, 64),
                        one_cmd(&odp, 64, 64)};
    WlPphigsRegion *fwd = wl_pphigs_region_new(0, 0, 64, 64, 0);
    WlPphigsRegion *rev = wl_pphigs_region_new(0, 0, 64, 64, 0);
    for (int i = 0; i < 3; i++) {
        wl_pphigs_region_draw(fwd, &c[i]);
        wl_pphigs_region_draw(rev, &c[2 - i]);
    }
    assert_memory_equal(fwd->rgba, rev->rgba, 64 * 64 * sizeof(uint32_t));
    uint32_t centre = fwd->rgba[32 * 64 + 32];
    assert_true((centre & 0xff0000u) && !(centre & 0x00ffffu)); /* ODP */
    uint32_t mid = fwd->rgba[16 * 64 + 32]; /* near over far */
    assert_true((mid & 0x00ff00u) && !(mid & 0xff00ffu));
    wl_pphigs_region_free(fwd);
    wl_pphigs_region_free(rev);
    for (int i = 0; i < 3; i++)
        g_free(e[i].verts);
}

/* Renderer rasterise time = expressions x 1 us + commands x 3 us, with
 * every command counted once per region it reaches. */
static void test_renderer_time_counted(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db(SCENE_PPHIGS_LOBBY);
    Frame fr = run_frame(&db, 4, 4, WL_PPHIGS_COMPLEX);
    assert_true(fr.exprs >= 7 * fr.commands);
    WlPphigsFrameSpec s = spec();
    guint regions = (s.width / s.region) * (s.height / s.region);
    SimTime begin = regions * 50 * SIM_US; /* the model's region_begin */
    assert_int_equal(fr.rast_busy,
                     begin + fr.exprs * SIM_US + fr.commands * 3 * SIM_US);
    rast_image_free(fr.img);
    scene_pphigs_db_clear(&db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frame_equals_serial),
        cmocka_unit_test(test_missing_primitive_differs),
        cmocka_unit_test(test_shared_edge_once),
        cmocka_unit_test(test_order_independent),
        cmocka_unit_test(test_renderer_time_counted),
    };
    return cmocka_run_group_tests_name("pphigs_pixels", tests, NULL, NULL);
}
