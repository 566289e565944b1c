/* test_sortfirst.c — the `sortfirst` workload (seed 000) on a small
 * vehicle (40 structures, 3,000 triangles, 3 instances, 64 x 64 screen,
 * 4 and 6 processors, the camera turning 12 degrees a frame):
 * chunks partition the primitives; after every frame each primitive
 * instance whose own screen box overlaps a region is held by that
 * region's processor (checked polygon by polygon, independently of the
 * chunk boxes); the regions' pixels equal the serial render; min-set and
 * max-set give the same images; the min-set tests more slave boxes
 * (seed 000 §4.2); runs repeat exactly; input errors are located;
 * the adaptive k-d split balances a skewed grid that the static grid
 * does not, and adaptive regions beat static ones on the vehicle with
 * images still equal to the serial render. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <glib/gstdio.h>

#include "sim/scene/scene_cfg.h"
#include "sim/workload/sortfirst/sf_adapt.h"
#include "sim/workload/sortfirst/sf_workload.h"
#include "tests/workload/sortfirst/sf_testutil.h"

static const char *const small = SF_TEST_SMALL;

/* Runs `text` with the NULL-terminated overrides (may be NULL). */
static SimResult *run_cfg_out(const char *text, const char *const *overrides,
                              int frames, const char *out_dir, gboolean all,
                              GError **err);

static SimResult *run_cfg(const char *text, const char *override, int frames,
                          GError **err)
{
    const char *const o[] = {override, NULL};
    return run_cfg_out(text, o, frames, NULL, FALSE, err);
}

/* `small`, 6 frames, with two overrides. */
static SimResult *run_cfg_set2(const char *a, const char *b, GError **err)
{
    const char *const o[] = {a, b, NULL};
    return run_cfg_out(small, o, 6, NULL, FALSE, err);
}

static SimResult *run_cfg_out(const char *text, const char *const *overrides,
                              int frames, const char *out_dir, gboolean all,
                              GError **err)
{
    return sf_test_run(text, overrides, frames, out_dir, all, err);
}

static double metric(const SimResult *r, const char *name)
{
    return sf_test_metric(r, name);
}

/* ---- a run driven directly, to look at the state between frames ------- */

typedef struct {
    CfgNode *root;
    Scene *scene;
    SimEngine *eng;
    MachMachine *m;
    WlSfDb *db;
    WlSfRun *run;
    WlSfSetup s;
} Fixture;

static void fixture_init(Fixture *f, guint procs, WlSfBookkeeping bk,
                         guint granularity)
{
    GError *e = NULL;
    f->root = cfg_load_string(small, "sf.yaml", &e);
    assert_non_null(f->root);
    f->scene = scene_from_cfg(cfg_get(f->root, "scene"), &e);
    assert_non_null(f->scene);
    f->eng = sim_engine_new(1);
    f->m = mach_new_from_model(f->eng, "cluster-ib", "analytic", &e);
    assert_non_null(f->m);
    WlSfCosts c;
    assert_true(wl_sf_costs_from_machine(f->m, &c, &e));
    f->db =
        wl_sf_db_new(f->scene->db, procs, granularity, WL_SF_CHUNK_SORTED, &e);
    assert_non_null(f->db);
    f->s = (WlSfSetup){.procs = procs,
                       .resolution = 64,
                       .bk = bk,
                       .sizes = {64, 40, 36, 8, 4, 8, 16},
                       .cull_back = TRUE};
    f->run = wl_sf_run_new(f->m, f->scene, f->db, &f->s, &c);
}

static void fixture_clear(Fixture *f)
{
    wl_sf_run_free(f->run);
    wl_sf_db_free(f->db);
    mach_free(f->m);
    sim_engine_free(f->eng);
    scene_free(f->scene);
    cfg_free(f->root);
}

static void test_chunks_partition(void **state)
{
    (void)state;
    Fixture f;
    fixture_init(&f, 4, WL_SF_MAXSET, 5);
    const WlSfDb *d = f.db;
    guint n = scene_mesh_n_polys(d->flat);
    assert_int_equal(d->min_prims, 3000);
    assert_int_equal(n, 9000);
    guint *seen = g_new0(guint, n);
    uint64_t per_master[4] = {0};
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        assert_true(ch->n_prims >= 1 && ch->n_prims <= 5);
        assert_int_equal(ch->n_inst, 3);
        per_master[ch->master]++;
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
            const uint32_t *p = wl_sf_inst_polys(d, i);
            for (guint k = 0; k < ch->polys; k++)
                seen[p[k]]++;
        }
    }
    for (guint k = 0; k < n; k++)
        assert_int_equal(seen[k], 1);
    for (int p = 1; p < 4; p++) /* fixed masters dealt evenly */
        assert_true(per_master[p] + 1 >= per_master[0] &&
                    per_master[p] <= per_master[0]);
    g_free(seen);
    fixture_clear(&f);
}

static int cmp_guint(const void *a, const void *b)
{
    guint x = *(const guint *)a, y = *(const guint *)b;
    return x < y ? -1 : x > y;
}

static Vec3 elem_centroid(const SceneElem *e)
{
    Vec3 s = vec3(0, 0, 0);
    for (guint k = 0; k < e->nverts; k++)
        s = vec3_add(s, e->verts[k]);
    return vec3_scale(s, 1.0 / e->nverts);
}

/* Partially sorted (§4.1): each structure's chunks, read in order, hold
 * its primitives in the octree order of their centroids
 * (wl_sf_octree_order; its properties in test_sf_db.c), every primitive
 * once; and the run renders the serial image. */
static void test_partial_chunking(void **state)
{
    (void)state;
    Fixture f;
    fixture_init(&f, 4, WL_SF_MAXSET, 5);
    GError *e = NULL;
    WlSfDb *d =
        wl_sf_db_new(f.scene->db, 4, 5, WL_SF_CHUNK_PARTIAL, &e);
    assert_non_null(d);
    assert_int_equal(d->min_prims, f.db->min_prims);
    assert_int_equal(d->prims->len, f.db->prims->len);
    gboolean moved = FALSE;
    for (guint c = 0, k = 0; c < wl_sf_n_chunks(d);) {
        /* the run of chunks of one structure: primitives k .. k + n */
        guint sid = wl_sf_chunk(d, c)->sid, n = 0;
        for (; c < wl_sf_n_chunks(d) && wl_sf_chunk(d, c)->sid == sid; c++)
            n += wl_sf_chunk(d, c)->n_prims;
        const guint *pos = &g_array_index(d->prims, guint, k);
        guint *file = g_memdup2(pos, n * sizeof *pos), *order = g_new(guint, n);
        qsort(file, n, sizeof *file, cmp_guint);
        Vec3 *cen = g_new(Vec3, n);
        for (guint i = 0; i < n; i++)
            cen[i] = elem_centroid(scene_db_elem(f.scene->db, sid, file[i]));
        wl_sf_octree_order(cen, n, order);
        for (guint i = 0; i < n; i++) {
            assert_int_equal(pos[i], file[order[i]]);
            moved |= order[i] != i;
        }
        g_free(file), g_free(order), g_free(cen);
        k += n;
    }
    assert_true(moved); /* the sort changed the file order somewhere */
    wl_sf_db_free(d);
    fixture_clear(&f);
    SimResult *r = run_cfg(small, "workload.chunking=partially_sorted", 2, &e);
    assert_non_null(r);
    assert_true(metric(r, "image_matches_serial") == 1);
    sim_result_free(r);
}

/* Regions whose pixel centres the screen rectangle of one world-space
 * polygon's projected vertices reaches (no margin): culled when every
 * vertex is outside one clip plane, everywhere when a vertex is at or
 * behind the eye.  Independent of the chunk boxes. */
static uint64_t poly_regions(const Fixture *f, const RastView *v,
                             const WlSfRegions *rg, uint32_t poly)
{
    const SceneMesh *m = f->db->flat;
    uint32_t a = g_array_index(m->start, uint32_t, poly);
    uint32_t b = g_array_index(m->start, uint32_t, poly + 1);
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    unsigned all = 0x3f;
    gboolean behind = FALSE;
    for (uint32_t k = a; k < b; k++) {
        Vec3 p =
            g_array_index(m->pos, Vec3, g_array_index(m->idx, uint32_t, k));
        Vec4 c = mat4_apply_point(v->view_proj, p);
        all &= (c.x < -c.w) | (c.x > c.w) << 1 | (c.y < -c.w) << 2 |
               (c.y > c.w) << 3 | (c.z < -c.w) << 4 | (c.z > c.w) << 5;
        if (c.w <= 0) {
            behind = TRUE;
            continue;
        }
        double sx = (c.x / c.w + 1) * 0.5 * rg->width;
        double sy = (1 - c.y / c.w) * 0.5 * rg->height;
        x0 = MIN(x0, sx), x1 = MAX(x1, sx), y0 = MIN(y0, sy), y1 = MAX(y1, sy);
    }
    if (all)
        return 0;
    uint64_t mask = 0;
    for (guint r = 0; r < rg->procs; r++) {
        WlSfRect q = wl_sf_region_rect(rg, r);
        if (behind || (q.x1 - 0.5 >= x0 && q.x0 + 0.5 <= x1 &&
                       q.y1 - 0.5 >= y0 && q.y0 + 0.5 <= y1))
            mask |= wl_sf_bit(r);
    }
    return mask;
}

static void check_holdings(const Fixture *f, guint frame)
{
    const WlSfBook *b = wl_sf_run_book(f->run);
    const WlSfRegions *rg = wl_sf_run_regions(f->run); /* tile the screen */
    int64_t area = 0;
    for (guint p = 0; p < rg->procs; p++)
        area += (int64_t)(rg->rect[p].x1 - rg->rect[p].x0) *
                (rg->rect[p].y1 - rg->rect[p].y0);
    assert_true(rg->procs >= 1 && area == (int64_t)rg->width * rg->height);
    SceneCamera cam = scene_camera_at(f->scene, frame);
    RastView v = rast_view_for_camera(&cam, 64, 64);
    guint checked = 0;
    for (guint i = 0; i < wl_sf_n_insts(f->db); i++) {
        const WlSfInst *in = wl_sf_inst(f->db, i);
        const WlSfChunk *ch = wl_sf_chunk(f->db, in->chunk);
        const uint32_t *p = wl_sf_inst_polys(f->db, i);
        for (guint k = 0; k < ch->polys; k++) {
            uint64_t need = poly_regions(f, &v, &b->regions, p[k]);
            assert_int_equal(need & ~b->held_data[in->chunk], 0);
            if (b->bk == WL_SF_MAXSET)
                assert_int_equal(need & ~b->held_inst[i], 0);
            checked += need != 0;
        }
    }
    assert_true(checked > 1000); /* the scene is on screen */
}

static void compare_serial(const Fixture *f, guint frame)
{
    RastZBuffer *zb = rast_zbuffer_new(64, 64);
    wl_sf_render_serial(f->scene, f->db, &f->s, frame, zb);
    const RastZBuffer *par = wl_sf_run_zbuffer(f->run);
    assert_memory_equal(zb->rgba, par->rgba, 64 * 64 * 4);
    assert_memory_equal(zb->prim, par->prim, 64 * 64 * 4);
    assert_true(rast_zbuffer_covered(zb) > 100);
    rast_zbuffer_free(zb);
}

static void test_migration_and_image(void **state)
{
    (void)state;
    for (int bk = 0; bk < 2; bk++) {
        Fixture f;
        fixture_init(&f, 6, (WlSfBookkeeping)bk, 5);
        GError *e = NULL;
        for (guint frame = 0; frame < 5; frame++) {
            assert_true(wl_sf_run_frames(f.run, 1, SIM_TIME_MAX, &e));
            check_holdings(&f, frame);
            compare_serial(&f, frame);
        }
        const GArray *st = wl_sf_run_stats(f.run);
        assert_int_equal(st->len, 5);
        /* the camera moved: chunks migrated after the first frame */
        assert_true(g_array_index(st, WlSfFrameStats, 3).migrated_chunks > 0);
        fixture_clear(&f);
    }
}

static void test_check_can_fail(void **state)
{
    (void)state;
    Fixture f;
    fixture_init(&f, 4, WL_SF_MINSET, 5);
    /* before any sort only the masters hold chunks: the invariant fails */
    WlSfRegions rg;
    wl_sf_regions_init(&rg, 4, 64, 64);
    WlSfBook *b = wl_sf_book_new(f.db, &rg, WL_SF_MINSET, &f.s.sizes);
    SceneCamera cam = scene_camera_at(f.scene, 0);
    RastView v = rast_view_for_camera(&cam, 64, 64);
    wl_sf_book_need(b, v.view_proj);
    guint inst = 0, proc = 0;
    assert_false(wl_sf_book_check(b, &inst, &proc));
    assert_true(b->need[inst] & wl_sf_bit(proc));
    wl_sf_book_free(b);
    fixture_clear(&f);
}

static void test_minset_equals_maxset(void **state)
{
    (void)state;
    Fixture a, b;
    fixture_init(&a, 4, WL_SF_MINSET, 12);
    fixture_init(&b, 4, WL_SF_MAXSET, 12);
    GError *e = NULL;
    for (guint frame = 0; frame < 4; frame++) {
        assert_true(wl_sf_run_frames(a.run, 1, SIM_TIME_MAX, &e));
        assert_true(wl_sf_run_frames(b.run, 1, SIM_TIME_MAX, &e));
        const RastZBuffer *za = wl_sf_run_zbuffer(a.run);
        const RastZBuffer *zb = wl_sf_run_zbuffer(b.run);
        assert_memory_equal(za->rgba, zb->rgba, 64 * 64 * 4);
    }
    /* same chunks rendered; the min-set tests every instance of each
     * slave chunk, the max-set only those it holds (seed 000 §4.2) */
    const WlSfFrameStats *sa =
        &g_array_index(wl_sf_run_stats(a.run), WlSfFrameStats, 3);
    const WlSfFrameStats *sb =
        &g_array_index(wl_sf_run_stats(b.run), WlSfFrameStats, 3);
    assert_int_equal(sa->polys_rendered, sb->polys_rendered);
    assert_int_equal(sa->master_boxes, sb->master_boxes);
    assert_true(sa->slave_boxes > sb->slave_boxes);
    assert_true(sa->migrated_chunks <=
                sb->migrated_chunks + sb->migrated_insts);
    fixture_clear(&a);
    fixture_clear(&b);
}

static void test_workload_metrics(void **state)
{
    (void)state;
    GError *e = NULL;
    SimResult *r = run_cfg(small, NULL, 4, &e);
    assert_non_null(r);
    assert_int_equal(r->frame_times->len, 4);
    assert_true(metric(r, "image_matches_serial") == 1);
    assert_true(metric(r, "migrated_bytes_per_frame") > 0);
    assert_true(metric(r, "initial_bytes") >
                metric(r, "migrated_bytes_per_frame"));
    assert_true(metric(r, "chunk_overlap") >= 1);
    double u = metric(r, "utilisation");
    assert_true(u > 0 && u <= 1);
    assert_true(metric(r, "load_imbalance") >= 1);
    assert_true(metric(r, "polygon_imbalance") >= 1);
    /* P(P-1) a frame, and P regions to the frame buffer */
    assert_true(r->comm_messages == 4 * (4 * 3 + 4));
    /* determinism: the same config twice gives the same figures */
    SimResult *r2 = run_cfg(small, NULL, 4, &e);
    assert_non_null(r2);
    assert_int_equal(r->metrics->len, r2->metrics->len);
    for (guint i = 0; i < r->metrics->len; i++) {
        const SimMetric *m1 = g_ptr_array_index(r->metrics, i);
        const SimMetric *m2 = g_ptr_array_index(r2->metrics, i);
        assert_string_equal(m1->name, m2->name);
        assert_true(m1->value == m2->value);
    }
    assert_memory_equal(r->frame_times->data, r2->frame_times->data,
                        4 * sizeof(SimTime));
    assert_int_equal(r->comm_bytes, r2->comm_bytes);
    sim_result_free(r);
    sim_result_free(r2);
    r = run_cfg(small, "workload.bookkeeping=minset", 3, &e);
    assert_non_null(r);
    assert_true(metric(r, "image_matches_serial") == 1);
    sim_result_free(r);
}

/* The frame log's columns (frames 1 and 2 of 3 rows) average to the
 * steady-state metrics; its peak memory column peaks at peak_memory. */
static void expect_log_means(const SimResult *r, char **lines)
{
    static const char *const col[] = {
        NULL, "frame_ms", "migrated_chunks_per_frame",
        "migrated_polygons_per_frame", "migrated_pointers_per_frame",
        "migrated_bytes_per_frame", "master_boxes_per_frame",
        "slave_boxes_per_frame", "new_boxes_per_frame",
        "polygons_rendered_per_frame", NULL, NULL, "load_imbalance",
        "polygon_imbalance", "utilisation", NULL, "estimate_bytes_per_frame"};
    double peak = 0;
    for (guint k = 0; k < G_N_ELEMENTS(col); k++) {
        double sum = 0;
        for (guint f = 1; f <= 3; f++) {
            char **v = g_strsplit(lines[f], ",", -1);
            assert_int_equal(g_strv_length(v), G_N_ELEMENTS(col));
            double x = g_ascii_strtod(v[k], NULL);
            sum += f > 1 ? x : 0;
            peak = k == 15 ? MAX(peak, x) : peak;
            assert_true(k || x == f - 1); /* the frame number */
            g_strfreev(v);
        }
        if (col[k] && !(fabs(sum / 2 - metric(r, col[k])) <=
                        1e-6 * MAX(1, fabs(metric(r, col[k])))))
            fail_msg("column %u: mean %.9g, %s %.9g", k, sum / 2, col[k],
                     metric(r, col[k]));
    }
    assert_true(peak == metric(r, "peak_memory"));
    assert_true(metric(r, "estimate_bytes_per_frame") > 0);
}

static void test_frame_log(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("sf-XXXXXX", NULL);
    assert_non_null(dir);
    char *path = g_build_filename(dir, "frames.csv", NULL);
    char *ov = g_strdup_printf("workload.frame_log=%s", path);
    GError *e = NULL;
    const char *const o[] = {ov, "workload.regions=adaptive", NULL};
    SimResult *r = run_cfg_out(small, o, 3, NULL, FALSE, &e);
    assert_non_null(r);
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    char **lines = g_strsplit(text, "\n", -1);
    assert_int_equal(g_strv_length(lines), 5); /* header, 3 rows, "" */
    assert_true(g_str_has_prefix(lines[0], "frame,frame_ms,"));
    assert_true(g_str_has_prefix(lines[3], "2,"));
    /* the first frame distributes from the masters: most bytes */
    char **f0 = g_strsplit(lines[1], ",", -1),
         **f2 = g_strsplit(lines[3], ",", -1);
    assert_true(g_ascii_strtod(f0[5], NULL) > g_ascii_strtod(f2[5], NULL));
    assert_true(g_ascii_strtod(f0[5], NULL) == metric(r, "initial_bytes"));
    expect_log_means(r, lines);
    g_strfreev(f0);
    g_strfreev(f2);
    g_strfreev(lines);
    g_free(text);
    sim_result_free(r);
    g_unlink(path);
    g_rmdir(dir);
    g_free(ov);
    g_free(path);
    g_free(dir);
}

/* ---- adaptive regions ---------------------------------------------------- */

/* max / mean of the estimated weight over the regions. */
static double weight_imbalance(const WlSfAdapt *a, const WlSfRegions *r)
{
    double total = 0, max = 0;
    for (guint p = 0; p < r->procs; p++) {
        double w = (double)wl_sf_adapt_weight_in(a, r, r->rect[p]);
        total += w;
        max = MAX(max, w);
    }
    return max * r->procs / total;
}

/* The regions tile the screen: non-empty, disjoint, covering it. */
static void assert_tiles(const WlSfRegions *r)
{
    int64_t area = 0;
    for (guint p = 0; p < r->procs; p++) {
        WlSfRect a = r->rect[p];
        assert_true(a.x0 < a.x1 && a.y0 < a.y1);
        area += (int64_t)(a.x1 - a.x0) * (a.y1 - a.y0);
        for (guint q = 0; q < p; q++) {
            WlSfRect b = r->rect[q];
            assert_false(a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 &&
                         b.y0 < a.y1);
        }
    }
    assert_int_equal(area, (int64_t)r->width * r->height);
}

static void test_adaptive_split(void **state)
{
    (void)state;
    for (guint procs = 2; procs <= 17; procs += 3) {
        WlSfAdapt *a = wl_sf_adapt_new(64, procs);
        WlSfRegions st, ad;
        wl_sf_regions_init(&st, procs, 128, 128);
        ad = st;
        /* one dense 16 x 12 cell patch near a corner, a thin floor */
        for (guint y = 0; y < 64; y++)
            for (guint x = 0; x < 64; x++)
                a->weight[y * 64 + x] =
                    (x >= 6 && x < 22 && y >= 40 && y < 52) ? 100 : 1;
        wl_sf_adapt_split(a, &ad);
        assert_tiles(&ad);
        /* the same bound fails the static grid on this weight */
        assert_true(weight_imbalance(a, &ad) < 1.3);
        assert_true(weight_imbalance(a, &st) > 1.3);
        /* no weight: the split falls back to equal areas */
        memset(a->weight, 0, 64 * 64 * sizeof(uint64_t));
        wl_sf_adapt_split(a, &ad);
        assert_tiles(&ad);
        wl_sf_adapt_free(a);
    }
}

/* Σ |a - b| over the cells of two G x G grids. */
static uint64_t grid_distance(const uint64_t *a, const uint64_t *b, guint g)
{
    uint64_t d = 0;
    for (guint i = 0; i < g * g; i++)
        d += a[i] > b[i] ? a[i] - b[i] : b[i] - a[i];
    return d;
}

static Mat4 view_at(const Fixture *f, guint frame)
{
    SceneCamera cam = scene_camera_at(f->scene, frame);
    return rast_view_for_camera(&cam, 64, 64).view_proj;
}

/* An estimate with prediction after frames a then b, against the plain
 * estimate of frame c: the L1 distance of the two grids. */
static uint64_t predicted_error(const Fixture *f, guint a, guint b, guint c,
                                gboolean predict)
{
    WlSfAdapt *p = wl_sf_adapt_new(16, 4), *t = wl_sf_adapt_new(16, 4);
    WlSfRegions r;
    wl_sf_regions_init(&r, 4, 64, 64);
    if (predict)
        wl_sf_adapt_predict(p, wl_sf_n_insts(f->db));
    wl_sf_adapt_estimate(p, f->db, &r, view_at(f, a));
    assert_int_equal(p->predicted, 0); /* nothing to extrapolate from */
    wl_sf_adapt_estimate(p, f->db, &r, view_at(f, b));
    assert_true(!predict || p->predicted > 0);
    wl_sf_adapt_estimate(t, f->db, &r, view_at(f, c));
    uint64_t d = grid_distance(p->weight, t->weight, 16);
    wl_sf_adapt_free(p);
    wl_sf_adapt_free(t);
    return d;
}

/* Motion prediction: frames 3 and 4 extrapolated estimate frame 5
 * better than frame 4's own estimate does; when the camera turns back
 * (the next frame is 3 again) the extrapolation is the worse guess. */
static void test_adaptive_predict(void **state)
{
    (void)state;
    Fixture f;
    fixture_init(&f, 4, WL_SF_MAXSET, 5);
    /* the sparse count: each master's distinct cells, at most its
     * instances, together covering every non-zero cell */
    WlSfAdapt *a = wl_sf_adapt_new(16, 4);
    WlSfRegions r;
    wl_sf_regions_init(&r, 4, 64, 64);
    wl_sf_adapt_estimate(a, f.db, &r, view_at(&f, 3));
    uint64_t nz = 0, cells = 0;
    for (guint p = 0; p < 4; p++) {
        assert_true(a->nz[p] > 0 && a->nz[p] <= a->added[p]);
        nz += a->nz[p];
    }
    for (guint i = 0; i < 16 * 16; i++)
        cells += a->weight[i] > 0;
    assert_true(nz >= cells && cells > 0);
    wl_sf_adapt_free(a);
    uint64_t last = predicted_error(&f, 3, 4, 5, FALSE);
    uint64_t pred = predicted_error(&f, 3, 4, 5, TRUE);
    assert_true(pred < last);
    uint64_t back_last = predicted_error(&f, 3, 4, 3, FALSE);
    uint64_t back_pred = predicted_error(&f, 3, 4, 3, TRUE);
    assert_true(back_pred > back_last);
    fixture_clear(&f);
}

/* The adaptive defaults (issue 15 point 3, docs/validation.md): estimate
 * predicted on a grid of 64 (at most the resolution) -- the same run as
 * asking for them, another run than the old previous / 32. */
static void test_adaptive_defaults(void **state)
{
    (void)state;
    const char *big = "workload.resolution=128";
    SimResult *d = run_cfg_set2("workload.regions=adaptive", big, NULL);
    const char *const explicit_o[] = {"workload.regions=adaptive", big,
                                      "workload.estimate=predicted",
                                      "workload.grid=64", NULL};
    SimResult *e = run_cfg_out(small, explicit_o, 6, NULL, FALSE, NULL);
    const char *const old_o[] = {"workload.regions=adaptive", big,
                                 "workload.estimate=previous",
                                 "workload.grid=32", NULL};
    SimResult *o = run_cfg_out(small, old_o, 6, NULL, FALSE, NULL);
    assert_non_null(d);
    assert_non_null(e);
    assert_non_null(o);
    assert_true(metric(d, "frame_ms") == metric(e, "frame_ms"));
    assert_true(metric(d, "estimate_bytes_per_frame") ==
                metric(e, "estimate_bytes_per_frame"));
    assert_true(metric(d, "estimate_bytes_per_frame") !=
                metric(o, "estimate_bytes_per_frame"));
    sim_result_free(d);
    sim_result_free(e);
    sim_result_free(o);
}

static void test_adaptive_beats_static(void **state)
{
    (void)state;
    GError *e = NULL;
    SimResult *a = run_cfg(small, "workload.regions=adaptive", 6, &e);
    assert_non_null(a);
    SimResult *s = run_cfg(small, NULL, 6, &e);
    assert_non_null(s);
    /* images equal the serial render every frame (check_image) */
    assert_true(metric(a, "image_matches_serial") == 1);
    assert_true(metric(a, "load_imbalance") < metric(s, "load_imbalance"));
    assert_true(metric(a, "polygon_imbalance") <
                metric(s, "polygon_imbalance"));
    assert_true(metric(a, "estimate_bytes_per_frame") > 0);
    /* this frame's estimate with cost feedback: still the serial image */
    SimResult *c = run_cfg(
        small, "workload={type: sortfirst, processors: 4, granularity: 5, "
               "resolution: 64, regions: adaptive, estimate: current, "
               "feedback: true}",
        6, &e);
    assert_non_null(c);
    assert_true(metric(c, "image_matches_serial") == 1);
    assert_true(metric(c, "load_imbalance") < metric(s, "load_imbalance"));
    sim_result_free(c);
    /* the previous frame's estimate, not extrapolated (the default is
     * predicted): the serial image */
    c = run_cfg(small, "workload={type: sortfirst, processors: 4, "
                       "granularity: 5, resolution: 64, regions: adaptive, "
                       "estimate: previous, grid: 32}",
                6, &e);
    assert_non_null(c);
    assert_true(metric(c, "image_matches_serial") == 1);
    assert_true(metric(c, "load_imbalance") < metric(s, "load_imbalance"));
    sim_result_free(c);
    sim_result_free(a);
    sim_result_free(s);
}

/* A 64 x 64 PNG at dir/name (the image's pixels equal the serial render,
 * check_image); removed after. */
static void assert_frame_png(const char *dir, const char *name)
{
    char *png = g_build_filename(dir, name, NULL);
    char *data = NULL;
    gsize len = 0;
    assert_true(g_file_get_contents(png, &data, &len, NULL));
    assert_true(len > 100 && memcmp(data, "\x89PNG", 4) == 0);
    assert_int_equal(((guchar)data[18] << 8) | (guchar)data[19], 64);
    assert_int_equal(((guchar)data[22] << 8) | (guchar)data[23], 64);
    g_free(data);
    assert_int_equal(g_remove(png), 0);
    g_free(png);
}

/* --out DIR: the assembled frame through the generic hook, DIR/frame.png
 * (the last frame) or DIR/frame-NNNN.png (all frames); nothing else. */
static void test_frame_out(void **state)
{
    (void)state;
    for (int all = 0; all <= 1; all++) {
        GError *e = NULL;
        char *dir = g_dir_make_tmp("pgsim-sf-XXXXXX", NULL);
        const char *const o[] = {"workload.frame_log=/dev/null", NULL};
        SimResult *r = run_cfg_out(small, o, 2, dir, all, &e);
        assert_non_null(r);
        if (all) {
            assert_frame_png(dir, "frame-0000.png");
            assert_frame_png(dir, "frame-0001.png");
        } else {
            assert_frame_png(dir, "frame.png");
        }
        assert_int_equal(g_rmdir(dir), 0);
        sim_result_free(r);
        g_free(dir);
    }
    /* an output folder that cannot be made fails the run */
    GError *e = NULL;
    assert_null(run_cfg_out(small, NULL, 1, "/dev/null/x", FALSE, &e));
    assert_non_null(e);
    g_clear_error(&e);
}

/* Pull (min-set) and dynamic mastership keep the image and the
 * migration invariant (check_image every frame); pull transforms every
 * box and asks only the masters it needs; dynamic mastership leaves
 * about one copy and, on a narrow view where chunks leave the screen,
 * piles off-screen masters on fewer processors than fixed masters do
 * when they are kept where they left (offscreen: keep; spread:
 * test_sf_costed.c). */
static void test_pull_and_dynamic(void **state)
{
    (void)state;
    GError *e = NULL;
    const char *base = "workload={type: sortfirst, processors: 4, "
                       "granularity: 5, resolution: 64, bookkeeping: minset";
    char *push = g_strdup_printf("%s}", base);
    char *pull = g_strdup_printf("%s, migration: pull}", base);
    SimResult *a = run_cfg(small, push, 6, &e), *b = run_cfg(small, pull, 6, &e);
    assert_non_null(a);
    assert_non_null(b);
    assert_true(metric(b, "image_matches_serial") == 1);
    assert_true(metric(b, "probe_boxes_per_frame") > 0);
    assert_true(metric(b, "transforms_per_frame") >
                metric(a, "transforms_per_frame"));
    assert_true(metric(b, "requests_per_frame") > 0);
    assert_true(metric(b, "messages_per_frame") <= 2 * 4 * 3);
    assert_true(metric(b, "copies") == metric(a, "copies"));
    sim_result_free(b);
    for (int narrow = 0; narrow <= 1; narrow++) {
        const char *scene =
            narrow ? "scene.fov=8" : "scene.degrees_per_frame=12";
        for (int bk = 0; bk <= 1; bk++) {
            char *dyn = g_strdup_printf(
                "workload={type: sortfirst, processors: 4, granularity: 5, "
                "resolution: 64, bookkeeping: %s, mastership: dynamic, "
                "offscreen: keep}",
                bk ? "maxset" : "minset");
            char *fix = g_strdup_printf(
                "workload={type: sortfirst, processors: 4, granularity: 5, "
                "resolution: 64, bookkeeping: %s}",
                bk ? "maxset" : "minset");
            SimResult *d = run_cfg_set2(dyn, scene, &e);
            SimResult *f = run_cfg_set2(fix, scene, &e);
            assert_non_null(d);
            assert_non_null(f);
            assert_true(metric(d, "image_matches_serial") == 1);
            assert_true(metric(d, "handovers_per_frame") > 0);
            assert_true(metric(d, "copies") < metric(f, "copies"));
            assert_true(metric(d, "master_polygon_imbalance") >
                        metric(f, "master_polygon_imbalance"));
            if (narrow)
                assert_true(metric(d, "offscreen_master_polygons_max") >
                            metric(f, "offscreen_master_polygons_max"));
            sim_result_free(d);
            sim_result_free(f);
            g_free(dyn);
            g_free(fix);
        }
    }
    sim_result_free(a);
    g_free(push);
    g_free(pull);
}

/* The scene's database written (dump_db) and rendered from the file
 * (database) gives the same run; a bad file is refused where it is bad. */
static void test_database_file(void **state)
{
    (void)state;
    GError *e = NULL;
    char *dir = g_dir_make_tmp("pgsim-sfdb-XXXXXX", NULL);
    char *path = g_build_filename(dir, "db.yaml", NULL);
    char *dump = g_strdup_printf("workload.dump_db=%s", path);
    char *use = g_strdup_printf("workload.database=%s", path);
    SimResult *a = run_cfg(small, dump, 3, &e);
    assert_non_null(a);
    SimResult *b = run_cfg(small, use, 3, &e);
    assert_non_null(b);
    assert_true(metric(b, "image_matches_serial") == 1);
    assert_true(metric(a, "frame_ms") == metric(b, "frame_ms"));
    assert_true(metric(a, "chunks") == metric(b, "chunks"));
    assert_true(metric(a, "max_set_polygons") ==
                metric(b, "max_set_polygons"));
    sim_result_free(a);
    sim_result_free(b);
    assert_true(g_file_set_contents(
        path, "structure_database: 1\nstructures:\n  - name: a\n"
              "    elements: [{execute: b}]\n",
        -1, NULL));
    assert_null(run_cfg(small, use, 1, &e));
    assert_non_null(e);
    assert_non_null(strstr(e->message, "db.yaml:4:26: found 'b'"));
    g_clear_error(&e);
    /* a matrix between one structure's primitives: no chunk box */
    assert_true(g_file_set_contents(
        path,
        "structure_database: 1\nstructures:\n  - name: a\n    elements:\n"
        "      - triangle: [[0,0,0], [1,0,0], [0,1,0]]\n"
        "      - {matrix: [1,0,0,2, 0,1,0,0, 0,0,1,0, 0,0,0,1]}\n"
        "      - triangle: [[0,0,0], [1,0,0], [0,1,0]]\n"
        "posted: [a]\n",
        -1, NULL));
    assert_null(run_cfg(small, use, 1, &e));
    assert_non_null(e);
    assert_non_null(strstr(e->message, "matrix element between the "
                                       "primitives of structure 'a'"));
    g_clear_error(&e);
    /* dump_db into a directory that does not exist: refused */
    char *bad = g_strdup_printf("workload.dump_db=%s/no/such/dir/db.yaml", dir);
    assert_null(run_cfg(small, bad, 1, &e));
    assert_non_null(e);
    g_clear_error(&e);
    g_free(bad);
    assert_int_equal(g_remove(path), 0);
    assert_int_equal(g_rmdir(dir), 0);
    g_free(use);
    g_free(dump);
    g_free(path);
    g_free(dir);
}

/* §3.5 counts: empty flags and culling each scan fewer structure
 * instances than the plain traversal, both together fewer than either,
 * and a narrow view culls more than the wide one (test_sf_trav.c
 * prices them). */
static void test_traversal_counts(void **state)
{
    (void)state;
    GError *e = NULL;
    for (int bk = 0; bk <= 1; bk++) {
        /* 26-primitive chunks: ~3 per structure, fewer than the 4
         * processors, so some structures are locally empty (§3.5) */
        const char *b =
            bk ? "workload={type: sortfirst, processors: 4, granularity: 26, "
                 "resolution: 64, bookkeeping: maxset}"
               : "workload={type: sortfirst, processors: 4, granularity: 26, "
                 "resolution: 64, bookkeeping: minset}";
        SimResult *w = run_cfg_set2(b, "scene.fov=30", &e);
        SimResult *n = run_cfg_set2(b, "scene.fov=8", &e);
        assert_non_null(w);
        assert_non_null(n);
        double plain = metric(w, "traversal_nodes_per_frame");
        double flags = metric(w, "traversal_nodes_flags");
        double culled = metric(w, "traversal_nodes_culled");
        double both = metric(w, "traversal_nodes_flags_culled");
        assert_true(flags < plain && culled <= plain);
        assert_true(both <= flags && both <= culled);
        assert_true(plain == metric(n, "traversal_nodes_per_frame"));
        assert_true(metric(n, "traversal_nodes_culled") < culled);
        /* min-set slaves keep a copy a frame past its last use, so a
         * wide view holds more copies of off-screen instances */
        assert_true(!bk || metric(n, "boxes_culled_per_frame") >
                               metric(w, "boxes_culled_per_frame"));
        sim_result_free(w);
        sim_result_free(n);
    }
}

/* Counting from frames rasterised once (setup `pre`, shared by runs)
 * and screen rectangles kept per frame (setup `screens`) gives every run
 * the figures of rasterising each region and transforming each box: the
 * same frame times (vertices, spans and pixels are all charged), pixels
 * and overlap figures; no image is kept.  Two runs share the sets, as a
 * reproduction's cases do. */
static void test_prerender_same_figures(void **state)
{
    (void)state;
    RastPrerenderSet *pre = rast_prerender_set_new();
    WlSfScreenSet *screens = wl_sf_screen_set_new();
    for (int bk = 0; bk < 2; bk++) {
        Fixture a, b;
        fixture_init(&a, 6, (WlSfBookkeeping)bk, 5);
        fixture_init(&b, 6, (WlSfBookkeeping)bk, 5);
        WlSfCosts c;
        assert_true(wl_sf_costs_from_machine(b.m, &c, NULL));
        wl_sf_run_free(b.run);
        b.s.pre = pre;
        b.s.screens = screens; /* kept from bk 0: the same boxes */
        b.run = wl_sf_run_new(b.m, b.scene, b.db, &b.s, &c);
        GError *e = NULL;
        assert_true(wl_sf_run_frames(a.run, 5, SIM_TIME_MAX, &e));
        assert_true(wl_sf_run_frames(b.run, 5, SIM_TIME_MAX, &e));
        assert_null(wl_sf_run_zbuffer(b.run));
        for (guint f = 0; f < 5; f++) {
            const WlSfFrameStats *x =
                &g_array_index(wl_sf_run_stats(a.run), WlSfFrameStats, f);
            const WlSfFrameStats *y =
                &g_array_index(wl_sf_run_stats(b.run), WlSfFrameStats, f);
            assert_int_equal(x->end - x->start, y->end - y->start);
            assert_int_equal(x->pixels, y->pixels);
            assert_int_equal(x->polys_rendered, y->polys_rendered);
            assert_true(x->imbalance == y->imbalance && x->pixels > 100);
            assert_true(x->box_side == y->box_side && x->box_side > 0);
            assert_int_equal(x->region_insts, y->region_insts);
        }
        fixture_clear(&a);
        fixture_clear(&b);
    }
    rast_prerender_set_free(pre);
    wl_sf_screen_set_free(screens);
}

/* wl_sf_box_screen() forms each corner from shared products: the
 * rectangle is bit for bit that of the corners by mat4_apply_point(). */
static void test_box_screen_exact(void **state)
{
    (void)state;
    WlSfRegions rg;
    wl_sf_regions_init(&rg, 12, 256, 256);
    SimRng rng;
    sim_rng_init(&rng, 5, 0);
    guint seen = 0;
    for (int t = 0; t < 20000; t++) {
        Mat4 m;
        for (int i = 0; i < 16; i++)
            m.m[i / 4][i % 4] = sim_rng_uniform(&rng) * 2 - 1 +
                                (i % 5 == 0 ? 2 : 0);
        Vec3 lo = vec3(sim_rng_uniform(&rng) - 0.5,
                       sim_rng_uniform(&rng) - 0.5, sim_rng_uniform(&rng));
        SceneBox b = {lo, vec3_add(lo, vec3(0.3, sim_rng_uniform(&rng), 0.1))};
        double r[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY}, g[4];
        gboolean front = TRUE;
        for (int k = 0; k < 8; k++) {
            Vec4 c = mat4_apply_point(
                m, vec3(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y,
                        k & 4 ? b.max.z : b.min.z));
            front = front && c.w > 0;
            double sx = (c.x / c.w + 1) * 0.5 * 256;
            double sy = (1 - c.y / c.w) * 0.5 * 256;
            r[0] = MIN(r[0], sx), r[1] = MIN(r[1], sy);
            r[2] = MAX(r[2], sx), r[3] = MAX(r[3], sy);
        }
        if (!front || !wl_sf_box_screen(&rg, b, m, &g[0], &g[1], &g[2], &g[3]))
            continue;
        assert_memory_equal(r, g, sizeof r);
        seen++;
    }
    assert_true(seen > 1000);
}

/* Re-dealing the masters of a database built for 4 processors gives
 * the database built for 6 (what reproduce mueller97 relies on to share
 * one database over its processor counts). */
static void test_db_set_procs(void **state)
{
    (void)state;
    Fixture f;
    fixture_init(&f, 4, WL_SF_MAXSET, 5);
    WlSfDb *d6 = wl_sf_db_new(f.scene->db, 6, 5, WL_SF_CHUNK_SORTED, NULL);
    assert_non_null(d6);
    assert_int_equal(wl_sf_n_chunks(f.db), wl_sf_n_chunks(d6));
    guint moved = 0;
    for (guint c = 0; c < wl_sf_n_chunks(d6); c++)
        moved += wl_sf_chunk(f.db, c)->master != wl_sf_chunk(d6, c)->master;
    assert_true(moved > 0);
    wl_sf_db_set_procs(f.db, 6);
    assert_int_equal(f.db->procs, 6);
    for (guint c = 0; c < wl_sf_n_chunks(d6); c++) {
        const WlSfChunk *a = wl_sf_chunk(f.db, c), *b = wl_sf_chunk(d6, c);
        assert_int_equal(a->master, b->master);
        assert_int_equal(a->polys, b->polys);
        assert_int_equal(a->inst_first, b->inst_first);
        assert_memory_equal(&a->box, &b->box, sizeof a->box);
    }
    assert_int_equal(f.db->inst_polys->len, d6->inst_polys->len);
    assert_memory_equal(f.db->inst_polys->data, d6->inst_polys->data,
                        d6->inst_polys->len * sizeof(uint32_t));
    wl_sf_db_free(d6);
    fixture_clear(&f);
}

static void expect_error(const char *override, const char *what)
{
    GError *e = NULL;
    SimResult *r = run_cfg(small, override, 1, &e);
    assert_null(r);
    assert_non_null(e);
    if (!strstr(e->message, what))
        fail_msg("'%s' not in '%s'", what, e->message);
    g_clear_error(&e);
}

static void test_errors(void **state)
{
    (void)state;
    expect_error("workload.bookkeeping=both", "--set workload.bookk");
    expect_error("workload.bookkeeping=both", "maxset");
    expect_error("workload.processors=65", "processors");
    expect_error("machine.nodes.node.count=2", "at most the 2 nodes");
    expect_error("machine.network.topology=dragonfly", /* no network */
                 "topology 'dragonfly' (not yet built");
    expect_error("workload.granularity=0", "granularity");
    expect_error("workload.regions=dynamic", "adaptive");
    expect_error("workload.estimate=next", "current");
    expect_error("workload.grid=128", "at most the resolution");
    expect_error("workload.migration=poll", "pull");
    expect_error("workload.mastership=moving", "dynamic");
    expect_error("workload.migration=pull", "bookkeeping: minset");
    expect_error("workload={type: sortfirst, bookkeeping: minset, "
                 "migration: pull, mastership: dynamic}",
                 "mastership: fixed");
    expect_error("workload={type: sortfirst, bookkeeping: minset, "
                 "migration: pull, regions: adaptive}",
                 "regions: static");
    expect_error("scene={generator: teapots, count: 1}",
                 "without a structure database");
}

/* The processors a machine can take (sf_workload.c check_procs): as
 * many as its nodes of kind `node` (here exactly 4 of 4), and no more
 * than its network has endpoints: a CM router of 2 lanes takes 2 of 3
 * nodes, not 3. */
static void test_procs_limits(void **state)
{
    (void)state;
    GError *e = NULL;
    SimResult *r = run_cfg(small, "machine.nodes.node.count=4", 1, &e);
    if (!r)
        fail_msg("%s", e->message);
    assert_true(metric(r, "processors") == 4);
    sim_result_free(r);
    static const char *const router[] = {
        "topology=cm-router",
        "procs_per_router={value: 1, assumption: test}",
        "router_nodes={value: 2, assumption: test}",
        "aggregate_bandwidth={value: 3 Gbit/s, assumption: test}",
        "router_cycle={value: 500 us, assumption: test}",
        "router_link_bandwidth={value: 1.25 MB/s, assumption: test}",
        "news_bandwidth={value: 1.25 MB/s, assumption: test}"};
    const char *o[G_N_ELEMENTS(router) + 4] = {NULL};
    for (guint k = 0; k < G_N_ELEMENTS(router); k++)
        o[k] = g_strdup_printf("machine.network.%s", router[k]);
    guint n = G_N_ELEMENTS(router);
    o[n] = "machine.nodes.node.count=3";
    o[n + 1] = "machine.nodes.node.lanes=2";
    for (guint procs = 2; procs <= 3; procs++) {
        char *p = g_strdup_printf("workload.processors=%u", procs);
        o[n + 2] = p;
        r = run_cfg_out(small, o, 1, NULL, FALSE, &e);
        if (procs == 2 && !r)
            fail_msg("%s", e->message);
        if (procs == 3) {
            assert_null(r);
            assert_non_null(strstr(e->message, "'3' processors"));
            g_clear_error(&e);
        }
        sim_result_free(r);
        g_free(p);
    }
    for (guint k = 0; k < n; k++)
        g_free((char *)o[k]);
}

/* The most processors there can be (WL_SF_MAX_PROCS = 64, one bit each
 * of a 64-bit mask) with adaptive regions: every processor has a
 * region, every region a split share, and the image is the serial one;
 * plain traversal has each of the 64 visit every max-set node, 64 times
 * the visits of one processor on the same frame. */
static void test_64_processors(void **state)
{
    (void)state;
    GError *e = NULL;
    const char *const one[] = {"workload.processors=1", NULL};
    SimResult *r1 = run_cfg_out(small, one, 1, NULL, FALSE, &e);
    SimResult *r = run_cfg_set2("workload.processors=64",
                                "workload.regions=adaptive", &e);
    if (!r || !r1)
        fail_msg("%s", e->message);
    assert_true(metric(r, "processors") == 64);
    assert_true(metric(r, "image_matches_serial") == 1);
    assert_true(metric(r, "split_imbalance") >= 1);
    assert_true(metric(r, "traversal_nodes_per_frame") ==
                64 * metric(r1, "traversal_nodes_per_frame"));
    assert_true(metric(r, "traversal_ms") > 0);
    sim_result_free(r);
    sim_result_free(r1);
}

/* The result's frame times are each frame's own duration: frames run
 * back to back from time 0, so they add up to the simulated time, and
 * the mean of those after the first is frame_ms. */
static void test_frame_times(void **state)
{
    (void)state;
    GError *e = NULL;
    SimResult *r = run_cfg(small, NULL, 3, &e);
    if (!r)
        fail_msg("%s", e->message);
    assert_int_equal(r->frame_times->len, 3);
    SimTime sum = 0;
    for (guint f = 0; f < 3; f++) {
        SimTime t = g_array_index(r->frame_times, SimTime, f);
        assert_true(t > 0);
        sum += t;
    }
    assert_true(sum == r->elapsed);
    double mean = sim_time_to_ms(g_array_index(r->frame_times, SimTime, 1) +
                                 g_array_index(r->frame_times, SimTime, 2)) /
                  2;
    assert_true(fabs(metric(r, "frame_ms") - mean) <= 1e-9 * mean);
    sim_result_free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_procs_limits),
        cmocka_unit_test(test_64_processors),
        cmocka_unit_test(test_frame_times),
        cmocka_unit_test(test_chunks_partition),
        cmocka_unit_test(test_migration_and_image),
        cmocka_unit_test(test_check_can_fail),
        cmocka_unit_test(test_minset_equals_maxset),
        cmocka_unit_test(test_workload_metrics),
        cmocka_unit_test(test_frame_log),
        cmocka_unit_test(test_partial_chunking),
        cmocka_unit_test(test_adaptive_split),
        cmocka_unit_test(test_adaptive_predict),
        cmocka_unit_test(test_adaptive_beats_static),
        cmocka_unit_test(test_adaptive_defaults),
        cmocka_unit_test(test_frame_out),
        cmocka_unit_test(test_pull_and_dynamic),
        cmocka_unit_test(test_database_file),
        cmocka_unit_test(test_traversal_counts),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_prerender_same_figures),
        cmocka_unit_test(test_db_set_procs),
        cmocka_unit_test(test_box_screen_exact),
    };
    return cmocka_run_group_tests_name("sortfirst", tests, NULL, NULL);
}
