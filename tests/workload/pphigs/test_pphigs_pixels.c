/* test_pphigs_pixels.c — Pixel-Planes 5 renderers that draw: the frame
 * the renderers evaluate region by region and the frame buffer assembles
 * equals a serial render of the whole list, for every database at 1, 3,
 * 4 and 16 GPs and all three algorithms; a missing primitive makes the images
 * differ (the comparison has teeth); two triangles sharing an edge draw
 * each pixel once; the visibility key makes the result independent of
 * drawing order; ODPs win over 3D primitives and later priorities over
 * earlier ones; renderer time is the counted expressions.  Order-
 * dependent primitives (seed 001 §4): a station with a panel and labels
 * spread over the GPs draws as the serial painter's order, also after
 * ODP inserts, deletes and modifies; reordering two overlapping labels
 * changes the picture (the order is visible, so the test can fail).
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

static ScenePphigsDb make_db_overlays(ScenePphigsKind k, guint overlays)
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
                         .levels = 5,
                         .overlays = overlays};
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    return db;
}

static ScenePphigsDb make_db(ScenePphigsKind k)
{
    return make_db_overlays(k, 0);
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

typedef void (*EditFn)(WlPphigsDist *d);

/* One frame of db on ngp GPs and nrend renderers, after `edit` (NULL:
 * none) changed the distributed list; the serial reference is then the
 * host's list, returned in *host_img when host_img is not NULL. */
static Frame run_edited(const ScenePphigsDb *db, guint ngp, guint nrend,
                        WlPphigsAlgo a, EditFn edit, RastImage **host_img)
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
    if (edit)
        edit(d);
    if (host_img)
        *host_img = wl_pphigs_render_serial(
            wl_pphigs_dist_host(d), scene_camera_view_proj(&db->camera),
            s.width, s.height);
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

static Frame run_frame(const ScenePphigsDb *db, guint ngp, guint nrend,
                       WlPphigsAlgo a)
{
    return run_edited(db, ngp, nrend, a, NULL, NULL);
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
            for (int a = WL_PPHIGS_SIMPLE; a <= WL_PPHIGS_BY_STRUCTURE; a++) {
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


/* The overlay structure of a generated database and its ODP positions. */
static guint overlay_sid(const SceneDb *db)
{
    guint sid;
    assert_true(scene_db_find(db, "overlay", &sid));
    return sid;
}

static void test_odp_frame_equals_serial(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db_overlays(SCENE_PPHIGS_STATION, 10);
    WlPphigsFrameSpec s = spec();
    RastImage *ref = wl_pphigs_render_serial(
        db.db, scene_camera_view_proj(&db.camera), s.width, s.height);
    static const guint gps[] = {1, 3, 4, 16};
    for (guint i = 0; i < G_N_ELEMENTS(gps); i++)
        for (int a = WL_PPHIGS_SIMPLE; a <= WL_PPHIGS_COMPLEX; a++) {
            Frame fr = run_frame(&db, gps[i], 4, (WlPphigsAlgo)a);
            assert_int_equal(rast_image_diff(fr.img, ref), 0);
            rast_image_free(fr.img);
        }
    rast_image_free(ref);
    scene_pphigs_db_clear(&db);
}

/* Moving the last label to just after the panel (drawn before the other
 * labels) changes the picture: labels overlap, so priorities show. */
static void test_odp_order_visible(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db_overlays(SCENE_PPHIGS_STATION, 10);
    WlPphigsFrameSpec s = spec();
    Mat4 vp = scene_camera_view_proj(&db.camera);
    RastImage *ref = wl_pphigs_render_serial(db.db, vp, s.width, s.height);
    guint sid = overlay_sid(db.db), n = scene_db_len(db.db, sid);
    SceneDb *moved = scene_db_copy(db.db);
    SceneElem e = *scene_db_elem(moved, sid, n - 1);
    e.verts = g_memdup2(e.verts, e.nverts * sizeof *e.verts);
    scene_db_delete(moved, sid, n - 1);
    assert_true(scene_db_insert(moved, sid, 2, &e, NULL));
    g_free(e.verts);
    RastImage *img = wl_pphigs_render_serial(moved, vp, s.width, s.height);
    assert_true(rast_image_diff(img, ref) > 0);
    rast_image_free(img);
    rast_image_free(ref);
    scene_db_free(moved);
    scene_pphigs_db_clear(&db);
}

/* ODP edits on the distributed list: insert a label between the panel
 * and the first label, delete one, recolour one (modify a colour), and
 * move the last label to the front (delete + insert). */
static void odp_edits(WlPphigsDist *d)
{
    const SceneDb *h = wl_pphigs_dist_host(d);
    guint sid = overlay_sid(h), n = scene_db_len(h, sid);
    SceneElem big = *scene_db_elem(h, sid, 1); /* the panel */
    Vec3 v[4];
    for (int i = 0; i < 4; i++)
        v[i] = vec3_scale(vec3_add(big.verts[i], big.verts[(i + 2) % 4]), 0.5),
        v[i] = vec3_add(vec3_scale(big.verts[i], 0.3), vec3_scale(v[i], 0.7));
    SceneElem label = scene_elem_prim(SCENE_EL_POLYGON2D, v, 4);
    assert_true(wl_pphigs_dist_insert(d, sid, 2, &label, NULL));
    wl_pphigs_dist_delete(d, sid, 5);
    SceneElem col = scene_elem_color(vec3(1, 0.1, 0.1));
    assert_true(wl_pphigs_dist_modify(d, sid, 0, &col, NULL));
    n = scene_db_len(h, sid);
    SceneElem last = *scene_db_elem(h, sid, n - 1);
    last.verts = g_memdup2(last.verts, last.nverts * sizeof *last.verts);
    wl_pphigs_dist_delete(d, sid, n - 1);
    assert_true(wl_pphigs_dist_insert(d, sid, 3, &last, NULL));
    g_free(last.verts);
    wl_pphigs_dist_finish(d);
}

static void test_odp_edits_equal_serial(void **st)
{
    (void)st;
    ScenePphigsDb db = make_db_overlays(SCENE_PPHIGS_STATION, 10);
    static const guint gps[] = {1, 4, 16};
    for (guint i = 0; i < G_N_ELEMENTS(gps); i++)
        for (int a = WL_PPHIGS_SIMPLE; a <= WL_PPHIGS_COMPLEX; a++) {
            RastImage *ref = NULL;
            Frame fr =
                run_edited(&db, gps[i], 4, (WlPphigsAlgo)a, odp_edits, &ref);
            if (rast_image_diff(fr.img, ref))
                fail_msg("%u GPs, algo %d: %llu pixels differ after edits",
                         gps[i], a,
                         (unsigned long long)rast_image_diff(fr.img, ref));
            rast_image_free(fr.img);
            rast_image_free(ref);
        }
    scene_pphigs_db_clear(&db);
}

/* The frame and region free functions take NULL. */
static void test_free_null(void **st)
{
    (void)st;
    wl_pphigs_frame_free(NULL);
    wl_pphigs_region_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_null),
        cmocka_unit_test(test_frame_equals_serial),
        cmocka_unit_test(test_missing_primitive_differs),
        cmocka_unit_test(test_shared_edge_once),
        cmocka_unit_test(test_order_independent),
        cmocka_unit_test(test_renderer_time_counted),
        cmocka_unit_test(test_odp_frame_equals_serial),
        cmocka_unit_test(test_odp_order_visible),
        cmocka_unit_test(test_odp_edits_equal_serial),
    };
    return cmocka_run_group_tests_name("pphigs_pixels", tests, NULL, NULL);
}
