/* test_pphigs_distrib.c — distribute-by-primitive (seed 001): after the
 * initial distribution and after any edit sequence, the GPs together
 * render exactly what a serial traversal of the host list renders, with
 * the serial ODP priorities; the backward scan is bounded (§3.5).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "tests/scene/mesh_check.h"
#include "sim/core/rng.h"
#include "sim/workload/pphigs/pphigs_distrib.h"
#include "sim/workload/pphigs/pphigs_dist_internal.h"
#include <string.h>

typedef struct {
    uint64_t uid;
    int64_t prio;
    double m[16];
    double c[3];
} Rend;

static void rend_fn(const ScenePrimInst *pi, void *ud)
{
    Rend r;
    memset(&r, 0, sizeof r);
    r.uid = pi->el->tag;
    r.prio = pi->el->kind == SCENE_EL_POLYGON2D ? pi->priority : 0;
    memcpy(r.m, pi->matrix.m, sizeof r.m);
    r.c[0] = pi->color.x, r.c[1] = pi->color.y, r.c[2] = pi->color.z;
    g_array_append_val((GArray *)ud, r);
}

static gint rend_cmp(gconstpointer a, gconstpointer b)
{
    return memcmp(a, b, sizeof(Rend));
}

/* Host rendering == union of GP renderings, as sorted multisets. */
static void assert_same_render(const WlPphigsDist *d)
{
    GArray *h = g_array_new(FALSE, FALSE, sizeof(Rend));
    GArray *u = g_array_new(FALSE, FALSE, sizeof(Rend));
    scene_db_traverse(wl_pphigs_dist_host(d), rend_fn, h);
    for (guint g = 0; g < wl_pphigs_dist_ngp(d); g++)
        scene_db_traverse(wl_pphigs_dist_gp(d, g), rend_fn, u);
    assert_int_equal(h->len, u->len);
    g_array_sort(h, rend_cmp);
    g_array_sort(u, rend_cmp);
    assert_memory_equal(h->data, u->data, h->len * sizeof(Rend));
    g_array_unref(h);
    g_array_unref(u);
}

static const WlPphigsWeights W = {
    .w = {[SCENE_EL_TRIANGLE] = 1,
          [SCENE_EL_POLYGON] = 1,
          [SCENE_EL_TRISTRIP] = 2,
          [SCENE_EL_POLYGON2D] = 1,
          [SCENE_EL_COLOR] = 0.1,
          [SCENE_EL_MATRIX] = 0.3,
          [SCENE_EL_EXECUTE] = 0.2},
    .w_vertex = 0,
    .cluster = 2,
};

static SceneElem rnd_elem(SimRng *r, guint nstruct, guint self, Vec3 *v)
{
    for (int i = 0; i < 3; i++)
        v[i] = vec3(sim_rng_uniform(r), sim_rng_uniform(r), i);
    switch (sim_rng_below(r, 12)) {
    case 0:
    case 1:
        return scene_elem_color(vec3(sim_rng_uniform(r), 0, 1));
    case 8:
        return scene_elem_kind_color(SCENE_EL_LINE_COLOR,
                                     vec3(sim_rng_uniform(r), 1, 0));
    case 9:
        return scene_elem_kind_color(SCENE_EL_SPHERE_COLOR,
                                     vec3(0, sim_rng_uniform(r), 1));
    case 10:
        return scene_elem_prim(SCENE_EL_LINE, v, 2);
    case 11:
        return scene_elem_prim(SCENE_EL_SPHERE, v, 2);
    case 2:
        return scene_elem_matrix(mat4_translate(sim_rng_uniform(r), 1, 0),
                                 SCENE_MAT_REPLACE);
    case 3:
        return scene_elem_matrix(mat4_scale(1 + sim_rng_uniform(r), 1, 1),
                                 SCENE_MAT_CONCAT);
    case 4:
        return scene_elem_prim(SCENE_EL_POLYGON2D, v, 3);
    case 5: {
        guint c = (guint)sim_rng_below(r, nstruct);
        return scene_elem_execute(c > self ? c : (self + 1) % nstruct);
    }
    default:
        return scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    }
}

/* Structures 0..n-1; executes only to higher ids (acyclic); structure
 * n-1 is a primitive structure of a few elements. */
static SceneDb *rnd_db(SimRng *r, guint n, guint len)
{
    SceneDb *db = scene_db_new();
    Vec3 v[3];
    for (guint s = 0; s < n; s++) {
        char name[16];
        g_snprintf(name, sizeof name, "s%u", s);
        scene_db_add_struct(db, name);
    }
    scene_db_set_primitive(db, n - 1, TRUE);
    for (guint s = 0; s < n; s++)
        for (guint i = 0; i < (s == n - 1 ? 4 : len); i++) {
            SceneElem e = rnd_elem(r, n, s, v);
            if (e.kind == SCENE_EL_EXECUTE && (s == n - 1 || e.child <= s))
                e = scene_elem_prim(SCENE_EL_POLYGON2D, v, 3);
            assert_true(scene_db_append(db, s, &e, NULL));
        }
    scene_db_post(db, 0);
    scene_db_post(db, 1);
    return db;
}

static void edit_some(WlPphigsDist *d, SimRng *r, guint nedits)
{
    const SceneDb *h = wl_pphigs_dist_host(d);
    guint n = scene_db_struct_count(h);
    Vec3 v[3];
    for (guint k = 0; k < nedits; k++) {
        guint s = (guint)sim_rng_below(r, n - 1);
        guint len = scene_db_len(h, s);
        SceneElem e = rnd_elem(r, n, s, v);
        if (e.kind == SCENE_EL_EXECUTE && e.child <= s)
            e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        guint op = (guint)sim_rng_below(r, 4);
        if (op == 0 && len > 0) {
            wl_pphigs_dist_delete(d, s, (guint)sim_rng_below(r, len));
        } else if (op == 1 && len > 0) {
            guint p = (guint)sim_rng_below(r, len);
            SceneElem m = *scene_db_elem(h, s, p);
            if (scene_elem_is_color(m.kind))
                m.color.y = sim_rng_uniform(r);
            if (m.kind == SCENE_EL_MATRIX)
                m.matrix.m[0][3] += 1;
            assert_true(wl_pphigs_dist_modify(d, s, p, &m, NULL));
        } else if (op == 2) {
            assert_true(wl_pphigs_dist_append(d, s, &e, NULL));
        } else {
            guint p = (guint)sim_rng_below(r, len + 1);
            assert_true(wl_pphigs_dist_insert(d, s, p, &e, NULL));
        }
        if (sim_rng_below(r, 3) == 0)
            wl_pphigs_dist_finish(d);
    }
    wl_pphigs_dist_finish(d);
}

static void run_random(WlPphigsAlgo algo, WlPphigsAttrSend send)
{
    static const guint gps[] = {1, 3, 4, 16};
    WlPphigsWeights w = W;
    w.attr_send = send;
    for (guint t = 0; t < 4; t++) {
        SimRng r;
        sim_rng_init(&r, 42, t);
        SceneDb *db = rnd_db(&r, 6, 40);
        WlPphigsDist *d = wl_pphigs_dist_new(db, gps[t], algo, &w);
        assert_same_render(d);
        for (int round = 0; round < 6; round++) {
            edit_some(d, &r, 12);
            assert_same_render(d);
        }
        wl_pphigs_dist_unpost(d, 1);
        assert_same_render(d);
        wl_pphigs_dist_post(d, 2);
        assert_same_render(d);
        wl_pphigs_dist_free(d);
        scene_db_free(db);
    }
}

static void test_simple_edits(void **st)
{
    (void)st;
    run_random(WL_PPHIGS_SIMPLE, WL_PPHIGS_SEND_ALL);
}

static void test_complex_edits(void **st)
{
    (void)st;
    run_random(WL_PPHIGS_COMPLEX, WL_PPHIGS_SEND_ALL);
    /* §3.5's alternative: colours only with their primitive type */
    run_random(WL_PPHIGS_COMPLEX, WL_PPHIGS_SEND_BY_KIND);
}

/* Distribute-by-structure (§2.1): on random lists whose posted
 * structures are not executed elsewhere, the GPs' traversals add up to
 * the host's, with either inheritance (the ancestor skeleton, the
 * host's pre-computed state); whole instances go to one GP (an executed
 * structure's primitives are all on the GPs that hold its instance); a
 * list whose posted structure is also executed falls back to SIMPLE. */
static void test_by_structure(void **st)
{
    (void)st;
    static const guint gps[] = {1, 3, 4, 16};
    for (guint t = 0; t < 8; t++) {
        WlPphigsWeights w = W;
        w.inherit = t < 4 ? WL_PPHIGS_INHERIT_SKELETON
                          : WL_PPHIGS_INHERIT_PRECOMPUTE;
        SimRng r;
        sim_rng_init(&r, 7, t % 4);
        SceneDb *db = rnd_db(&r, 6, 40);
        scene_db_unpost(db, 1); /* s1 may be executed by s0 */
        WlPphigsDist *d = wl_pphigs_dist_new(db, gps[t % 4],
                                             WL_PPHIGS_BY_STRUCTURE, &w);
        assert_int_equal(wl_pphigs_dist_algo(d), WL_PPHIGS_BY_STRUCTURE);
        assert_same_render(d);
        wl_pphigs_dist_free(d);
        scene_db_post(db, 1);
        d = wl_pphigs_dist_new(db, gps[t % 4], WL_PPHIGS_BY_STRUCTURE, &w);
        gboolean executed = FALSE; /* is s1 executed anywhere? */
        for (guint s = 0; s < 6; s++)
            for (guint i = 0; i < scene_db_len(db, s); i++)
                executed = executed ||
                           (scene_db_elem(db, s, i)->kind == SCENE_EL_EXECUTE &&
                            scene_db_elem(db, s, i)->child == 1);
        assert_int_equal(wl_pphigs_dist_algo(d), executed
                                                     ? WL_PPHIGS_SIMPLE
                                                     : WL_PPHIGS_BY_STRUCTURE);
        assert_same_render(d);
        wl_pphigs_dist_free(d);
        scene_db_free(db);
    }
}

/* One structure: a colour before every 4th triangle. */
static SceneDb *long_db(guint prims)
{
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "long");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (guint i = 0; i < prims; i++) {
        SceneElem e = i % 4 ? scene_elem_prim(SCENE_EL_TRIANGLE, v, 3)
                            : scene_elem_color(vec3(i, 0, 0));
        assert_true(scene_db_append(db, s, &e, NULL));
    }
    scene_db_post(db, s);
    return db;
}

static void test_scan_bound(void **st)
{
    (void)st;
    SceneDb *db = long_db(4000);
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (guint n = 2; n <= 16; n *= 2) {
        WlPphigsDist *d = wl_pphigs_dist_new(db, n, WL_PPHIGS_COMPLEX, &W);
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(wl_pphigs_dist_insert(d, 0, 3001, &e, NULL));
        wl_pphigs_dist_finish(d);
        /* c (maxw/minw) (n-1) primitives at most, plus one colour per 3
         * primitives and the primitive that completes the set */
        double prims = W.cluster * (n - 1) + 1;
        assert_true(wl_pphigs_dist_traffic(d)->last_scan <=
                    (uint64_t)(prims * 4.0 / 3.0 + 2));
        assert_true(wl_pphigs_dist_traffic(d)->last_scan >= n - 1);
        assert_same_render(d);
        wl_pphigs_dist_free(d);
    }
    scene_db_free(db);
}

/* The step-back bound of §3.4 with unequal weights: triangles (weight
 * 4 with w_vertex 1) and octagons (9), maxw/minw = 2.25;
 * after an insert the backward scan examines at most
 * c (maxw/minw) (n - 1) primitives plus the colours between them. */
static void test_scan_bound_unequal(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint sid = scene_db_add_struct(db, "mixed");
    Vec3 v[8];
    for (int i = 0; i < 8; i++)
        v[i] = vec3(cos(i * G_PI / 4), sin(i * G_PI / 4), 0);
    for (guint i = 0; i < 3000; i++) {
        SceneElem e = i % 4 == 0 ? scene_elem_color(vec3(i, 0, 0))
                      : i % 3    ? scene_elem_prim(SCENE_EL_TRIANGLE, v, 3)
                                 : scene_elem_prim(SCENE_EL_POLYGON, v, 8);
        assert_true(scene_db_append(db, sid, &e, NULL));
    }
    scene_db_post(db, sid);
    WlPphigsWeights w = W;
    w.w_vertex = 1;
    double maxw = w.w[SCENE_EL_POLYGON] + 8 * w.w_vertex;
    double minw = w.w[SCENE_EL_TRIANGLE] + 3 * w.w_vertex;
    assert_true(maxw / minw > 2);
    for (guint n = 2; n <= 16; n *= 2) {
        WlPphigsDist *d = wl_pphigs_dist_new(db, n, WL_PPHIGS_COMPLEX, &w);
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(wl_pphigs_dist_insert(d, 0, 2001, &e, NULL));
        wl_pphigs_dist_finish(d);
        double prims = w.cluster * (maxw / minw) * (n - 1) + 1;
        uint64_t scan = wl_pphigs_dist_traffic(d)->last_scan;
        assert_true(scan <= (uint64_t)(prims * 4.0 / 3.0 + 2));
        assert_true(scan >= n - 1);
        /* the weight ratio matters: beyond the equal-weight bound (62
         * elements against 43 at 16 GPs) */
        if (n == 16)
            assert_true(scan > (w.cluster * (n - 1) + 1) * 4.0 / 3.0 + 2);
        assert_same_render(d);
        wl_pphigs_dist_free(d);
    }
    scene_db_free(db);
}

/* §2.3.2: one 400-triangle strip lands on one GP unless split; split
 * into pieces of 16 (even) triangles it spreads over the GPs, and the
 * GPs still draw the same triangles (pieces repeat shared vertices). */
static void test_strip_split(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint sid = scene_db_add_struct(db, "strip");
    Vec3 v[402];
    for (int i = 0; i < 402; i++)
        v[i] = vec3(i / 2, i % 2, 0);
    SceneElem e = scene_elem_prim(SCENE_EL_TRISTRIP, v, 402);
    assert_true(scene_db_append(db, sid, &e, NULL));
    scene_db_post(db, sid);
    WlPphigsWeights w = W;
    for (int split = 0; split <= 1; split++) {
        w.strip_split = split ? 15 : 0; /* 15 rounds up to 16 */
        WlPphigsDist *d = wl_pphigs_dist_new(db, 4, WL_PPHIGS_COMPLEX, &w);
        const SceneDb *h = wl_pphigs_dist_host(d);
        assert_int_equal(scene_db_len(h, sid), split ? 25 : 1);
        double load[4];
        wl_pphigs_dist_loads(d, load);
        double mx = MAX(MAX(load[0], load[1]), MAX(load[2], load[3]));
        double sum = load[0] + load[1] + load[2] + load[3];
        if (split)
            assert_true(mx < 0.3 * sum);
        else
            assert_true(mx == sum);
        wl_pphigs_dist_free(d);
    }
    scene_db_free(db);
}

/* §2.3.2: the complex algorithm fills a cluster of exactly c * maxw
 * weight before it opens the next (unit triangles, c = 3: runs of 3). */
static void test_cluster_runs(void **st)
{
    (void)st;
    SceneDb *db = long_db(400);
    WlPphigsWeights wc = W;
    wc.cluster = 3;
    WlPphigsDist *d = wl_pphigs_dist_new(db, 4, WL_PPHIGS_COMPLEX, &wc);
    gint cur = -1;
    guint run = 0, runs = 0;
    for (guint i = 1; i < 400; i++) {
        if (i % 4 == 0)
            continue; /* a colour */
        gint o = wl_pphigs_dist_owner(d, 0, i);
        if (o != cur && cur >= 0) {
            assert_int_equal(run, 3);
            runs++;
            run = 0;
        }
        cur = o;
        run++;
    }
    assert_int_equal(runs, 300 / 3 - 1);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

static void test_attribute_copies(void **st)
{
    (void)st;
    SceneDb *db = long_db(400);
    WlPphigsDist *s = wl_pphigs_dist_new(db, 4, WL_PPHIGS_SIMPLE, &W);
    WlPphigsWeights wc = W;
    wc.cluster = 6;
    WlPphigsDist *c = wl_pphigs_dist_new(db, 4, WL_PPHIGS_COMPLEX, &wc);
    guint simple = 0, complex = 0, prims = 0;
    for (guint g = 0; g < 4; g++) {
        simple += mesh_check_count_kind(wl_pphigs_dist_gp(s, g), 0, SCENE_EL_COLOR);
        complex += mesh_check_count_kind(wl_pphigs_dist_gp(c, g), 0, SCENE_EL_COLOR);
        prims += mesh_check_count_kind(wl_pphigs_dist_gp(c, g), 0, SCENE_EL_TRIANGLE);
    }
    assert_int_equal(simple, 4 * 100); /* every colour on every GP */
    assert_true(complex < 2 * 100);    /* mostly on one or two GPs */
    assert_int_equal(prims, 300);
    double load[4];
    wl_pphigs_dist_loads(c, load);
    double mean = (load[0] + load[1] + load[2] + load[3]) / 4;
    for (guint g = 0; g < 4; g++) /* balanced within 5 % */
        assert_true(fabs(load[g] - mean) < 0.05 * mean);
    wl_pphigs_dist_free(s);
    wl_pphigs_dist_free(c);
    scene_db_free(db);
}

static void test_primitive_structure(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    guint top = scene_db_add_struct(db, "flock");
    guint boid = scene_db_add_struct(db, "boid");
    scene_db_set_primitive(db, boid, TRUE);
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (int i = 0; i < 5; i++) {
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        SceneElem c = scene_elem_color(vec3(i, 0, 0));
        assert_true(scene_db_append(db, boid, i < 4 ? &c : &e, NULL));
        assert_true(scene_db_append(db, boid, &e, NULL));
    }
    for (int b = 0; b < 40; b++) {
        SceneElem m =
            scene_elem_matrix(mat4_translate(b, 0, 0), SCENE_MAT_REPLACE);
        SceneElem x = scene_elem_execute(boid);
        assert_true(scene_db_append(db, top, &m, NULL));
        assert_true(scene_db_append(db, top, &x, NULL));
    }
    scene_db_post(db, top);
    WlPphigsDist *d = wl_pphigs_dist_new(db, 4, WL_PPHIGS_COMPLEX, &W);
    guint execs = 0;
    for (guint g = 0; g < 4; g++) {
        const SceneDb *p = wl_pphigs_dist_gp(d, g);
        assert_int_equal(scene_db_len(p, boid), 10); /* broadcast whole */
        guint e = mesh_check_count_kind(p, top, SCENE_EL_EXECUTE);
        assert_int_equal(e, 10); /* instances dealt evenly */
        execs += e;
    }
    assert_int_equal(execs, 40);
    assert_same_render(d);
    wl_pphigs_dist_free(d);
    scene_db_free(db);
}

/* ---- §3.4: the attribute-state cache --------------------------------- */

/* GP g of a and of b hold the same list (same traversal, in order). */
static void assert_same_gps(const WlPphigsDist *a, const WlPphigsDist *b)
{
    for (guint g = 0; g < wl_pphigs_dist_ngp(a); g++) {
        GArray *x = g_array_new(FALSE, FALSE, sizeof(Rend));
        GArray *y = g_array_new(FALSE, FALSE, sizeof(Rend));
        scene_db_traverse(wl_pphigs_dist_gp(a, g), rend_fn, x);
        scene_db_traverse(wl_pphigs_dist_gp(b, g), rend_fn, y);
        assert_int_equal(x->len, y->len);
        assert_memory_equal(x->data, y->data, x->len * sizeof(Rend));
        g_array_unref(x);
        g_array_unref(y);
    }
}

/* With a cache every 1, 2 or 5 dealt elements, the same random edits
 * leave every GP with the same list as without it (the cache changes
 * where the scan stops, not what is sent), and the scans examine no
 * more elements. */
static void test_attr_cache_same(void **st)
{
    (void)st;
    static const guint gps[] = {3, 4, 16}, every[] = {1, 2, 5};
    for (guint t = 0; t < 3; t++) {
        SimRng r0, r1;
        sim_rng_init(&r0, 11, t);
        SceneDb *db = rnd_db(&r0, 6, 60);
        r1 = r0;
        WlPphigsWeights wc = W;
        wc.attr_cache = every[t];
        WlPphigsDist *a = wl_pphigs_dist_new(db, gps[t], WL_PPHIGS_COMPLEX, &W);
        WlPphigsDist *b = wl_pphigs_dist_new(db, gps[t], WL_PPHIGS_COMPLEX, &wc);
        for (int round = 0; round < 6; round++) {
            edit_some(a, &r0, 12);
            edit_some(b, &r1, 12);
            assert_same_render(b);
            assert_same_gps(a, b);
        }
        const WlPphigsTraffic *ta = wl_pphigs_dist_traffic(a);
        const WlPphigsTraffic *tb = wl_pphigs_dist_traffic(b);
        assert_int_equal(ta->elements_sent, tb->elements_sent);
        assert_true(tb->total_scan < ta->total_scan);
        assert_int_equal(ta->cache_walk, 0);
        assert_true(tb->cache_walk > 0);
        wl_pphigs_dist_free(a);
        wl_pphigs_dist_free(b);
        scene_db_free(db);
    }
}

/* One structure: colour A, 40 triangles, colour B, 60 triangles. */
static SceneDb *two_colour_db(void)
{
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "two");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (guint i = 0; i < 102; i++) {
        SceneElem e = i == 0 || i == 41
                          ? scene_elem_color(vec3(i, 1, 0))
                          : scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(scene_db_append(db, s, &e, NULL));
    }
    scene_db_post(db, s);
    return db;
}

/* Deleting colour B (before the checkpoints after it) must drop them:
 * their state names B's position, which now holds a triangle of some
 * GP; a triangle inserted after them would take that triangle along to
 * its GP as if it were the colour (a second copy, a wrong colour). */
static void test_attr_cache_invalidated(void **st)
{
    (void)st;
    SceneDb *db = two_colour_db();
    Vec3 v[3] = {vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0)};
    WlPphigsWeights wc = W;
    wc.attr_cache = 2;
    for (guint at = 50; at <= 90; at += 10) {
        WlPphigsDist *d = wl_pphigs_dist_new(db, 16, WL_PPHIGS_COMPLEX, &wc);
        wl_pphigs_dist_delete(d, 0, 41);
        wl_pphigs_dist_finish(d);
        assert_same_render(d);
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(wl_pphigs_dist_insert(d, 0, at, &e, NULL));
        wl_pphigs_dist_finish(d);
        assert_true(wl_pphigs_dist_traffic(d)->last_scan <= 4);
        assert_same_render(d);
        wl_pphigs_dist_free(d);
    }
    scene_db_free(db);
}

/* The step-back cost: on a long list at 16 GPs a cache every 2 dealt
 * elements stops the scan at the checkpoint behind the insert, instead
 * of after a primitive of each of the 16 GPs (§3.5's bound). */
static void test_attr_cache_scan(void **st)
{
    (void)st;
    SceneDb *db = long_db(4000);
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    uint64_t scan[2];
    for (guint every = 0; every <= 2; every += 2) {
        WlPphigsWeights wc = W;
        wc.attr_cache = every;
        WlPphigsDist *d = wl_pphigs_dist_new(db, 16, WL_PPHIGS_COMPLEX, &wc);
        SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(wl_pphigs_dist_insert(d, 0, 3001, &e, NULL));
        wl_pphigs_dist_finish(d);
        scan[every / 2] = wl_pphigs_dist_traffic(d)->last_scan;
        assert_same_render(d);
        wl_pphigs_dist_free(d);
    }
    assert_true(scan[0] >= 15);           /* a primitive of each other GP */
    assert_true(scan[1] <= 2 * 4 / 3 + 2); /* 2 triangles and a colour */
    scene_db_free(db);
}

/* One structure: replace matrix M1, 2 triangles, matrix M2 (`mode`),
 * 60 triangles: most GPs hold M1 only if M2 concatenates. */
static SceneDb *two_matrix_db(SceneMatMode mode)
{
    SceneDb *db = scene_db_new();
    guint s = scene_db_add_struct(db, "two");
    Vec3 v[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    for (guint i = 0; i < 64; i++) {
        SceneElem e =
            i == 0   ? scene_elem_matrix(mat4_translate(1, 0, 0),
                                         SCENE_MAT_REPLACE)
            : i == 3 ? scene_elem_matrix(mat4_scale(2, 3, 1), mode)
                      : scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
        assert_true(scene_db_append(db, s, &e, NULL));
    }
    scene_db_post(db, s);
    return db;
}

/* M2 changing mode (replace -> concatenate and back) changes the state
 * after it, so the checkpoints after it must go: a triangle inserted
 * after them then gets M1 and M2 (or M2 alone) as the host draws it,
 * and the GPs hold what they hold without a cache. */
static void test_attr_cache_mode_change(void **st)
{
    (void)st;
    Vec3 v[3] = {vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0)};
    for (int from = 0; from < 2; from++) {
        SceneMatMode m0 = from ? SCENE_MAT_CONCAT : SCENE_MAT_REPLACE;
        SceneMatMode m1 = from ? SCENE_MAT_REPLACE : SCENE_MAT_CONCAT;
        SceneDb *db = two_matrix_db(m0);
        for (guint at = 20; at <= 60; at += 20) {
            WlPphigsWeights wc = W;
            wc.attr_cache = 2;
            WlPphigsDist *a = wl_pphigs_dist_new(db, 16, WL_PPHIGS_COMPLEX, &W);
            WlPphigsDist *b = wl_pphigs_dist_new(db, 16, WL_PPHIGS_COMPLEX, &wc);
            SceneElem m = scene_elem_matrix(mat4_scale(2, 3, 1), m1);
            SceneElem e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
            for (int k = 0; k < 2; k++) {
                WlPphigsDist *d = k ? b : a;
                assert_true(wl_pphigs_dist_modify(d, 0, 3, &m, NULL));
                wl_pphigs_dist_finish(d);
                const SceneDb *h = wl_pphigs_dist_host(d);
                assert_int_equal(scene_db_len(h, 0), 64); /* in place */
                assert_int_equal(scene_db_elem(h, 0, 3)->mode, m1);
                assert_int_equal(scene_db_elem(h, 0, 4)->kind,
                                 SCENE_EL_TRIANGLE);
                assert_true(wl_pphigs_dist_insert(d, 0, at, &e, NULL));
                wl_pphigs_dist_finish(d);
                assert_same_render(d);
            }
            assert_same_gps(a, b);
            wl_pphigs_dist_free(a);
            wl_pphigs_dist_free(b);
        }
        scene_db_free(db);
    }
}

/* The distribution and its attribute cache free functions take NULL. */
static void test_free_null(void **st)
{
    (void)st;
    wl_pphigs_dist_free(NULL);
    wl_pphigs_attr_cache_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_null),
        cmocka_unit_test(test_simple_edits),
        cmocka_unit_test(test_complex_edits),
        cmocka_unit_test(test_by_structure),
        cmocka_unit_test(test_attr_cache_mode_change),
        cmocka_unit_test(test_scan_bound),
        cmocka_unit_test(test_scan_bound_unequal),
        cmocka_unit_test(test_strip_split),
        cmocka_unit_test(test_cluster_runs),
        cmocka_unit_test(test_attribute_copies),
        cmocka_unit_test(test_primitive_structure),
        cmocka_unit_test(test_attr_cache_same),
        cmocka_unit_test(test_attr_cache_invalidated),
        cmocka_unit_test(test_attr_cache_scan),
    };
    return cmocka_run_group_tests_name("pphigs_distrib", tests, NULL, NULL);
}
