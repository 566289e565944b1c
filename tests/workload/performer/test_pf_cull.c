/* test_pf_cull.c — the CULL, DRAW and ISECT traversals (pf_cull.c) on
 * small hand-built graphs, every display-list item and every count
 * worked out by hand: a node outside the frustum is culled with the
 * triangles below it counted; LOD picks the child whose range holds the
 * eye distance times stress; a switch draws its selected child; a
 * billboard's geosets are each wrapped in PUSH / POP; masks hide a node
 * from one traversal; DRAW counts lazy state changes against an eager
 * 3 a geoset; ISECT finds the highest hit of a vertical segment,
 * skipping billboards and all LOD children but the finest.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/camera.h"
#include "sim/workload/performer/pf_cull.h"
#include "tests/support.h"

/* A geode with one geoset of k triangles, all within 1 of (x, 0, 0). */
static guint geode_at(WlPfGraph *g, guint parent, WlPfKind kind, double x,
                      guint k, guint gs)
{
    guint n = wl_pf_add_node(g, parent, kind);
    Vec3 t[9];
    for (guint i = 0; i < 3 * k; i++)
        t[i] = vec3(x + (i % 3 == 1 ? 1 : -0.5), i % 3 == 2 ? 0.5 : 0, 0);
    wl_pf_add_geoset(g, n, t, k, gs);
    return n;
}

/* The box |x|, |y|, |z| <= 10 as six inward planes. */
static WlPfView box_view(double stress, gboolean cull)
{
    WlPfView v = {.eye = vec3(0, 0, 0), .stress = stress, .cull = cull};
    for (int p = 0; p < 6; p++) {
        memset(v.planes[p], 0, sizeof v.planes[p]);
        v.planes[p][p / 2] = p % 2 ? -1 : 1;
        v.planes[p][3] = 10;
    }
    return v;
}

typedef struct {
    WlPfGraph *g;
    guint gs[3];
    guint a, l1, s1, bb; /* geosets drawn: a, LOD child 1, switch child 1 */
} Town;

static void town_init(Town *t)
{
    WlPfGraph *g = t->g = wl_pf_graph_new();
    t->gs[0] = wl_pf_add_gstate(g, (WlPfGeoState){1, 1, 1});
    t->gs[1] = wl_pf_add_gstate(g, (WlPfGeoState){1, 2, 1});
    t->gs[2] = wl_pf_add_gstate(g, (WlPfGeoState){2, 2, 2});
    guint r = g->root;
    t->a = geode_at(g, r, WL_PF_GEODE, 0, 1, t->gs[0]);
    guint d = wl_pf_add_node(g, r, WL_PF_DCS); /* moved out of the box */
    wl_pf_node(g, d)->xf = mat4_translate(50, 0, 0);
    geode_at(g, d, WL_PF_GEODE, 0, 2, t->gs[0]);
    geode_at(g, d, WL_PF_GEODE, 0, 1, t->gs[0]);
    guint lod = wl_pf_add_node(g, r, WL_PF_LOD);
    geode_at(g, lod, WL_PF_GEODE, 8, 1, t->gs[0]);
    t->l1 = geode_at(g, lod, WL_PF_GEODE, 8, 1, t->gs[1]);
    const double ranges[3] = {0, 5, 100};
    g_array_append_vals(wl_pf_node(g, lod)->ranges, ranges, 3);
    guint sw = wl_pf_add_node(g, r, WL_PF_SWITCH);
    geode_at(g, sw, WL_PF_GEODE, -3, 1, t->gs[0]);
    t->s1 = geode_at(g, sw, WL_PF_GEODE, -3, 1, t->gs[1]);
    wl_pf_node(g, sw)->which = 1;
    t->bb = geode_at(g, r, WL_PF_BILLBOARD, 2, 1, t->gs[2]);
    Vec3 two[6];
    for (int i = 0; i < 6; i++)
        two[i] = vec3(2 + i % 3, i % 2, 0);
    wl_pf_add_geoset(g, t->bb, two, 2, t->gs[0]);
    guint m = geode_at(g, r, WL_PF_GEODE, 1, 1, t->gs[0]);
    wl_pf_node(g, m)->mask = WL_PF_MASK_ISECT; /* not culled or drawn */
    guint nd = geode_at(g, r, WL_PF_GEODE, 1, 1, t->gs[0]);
    wl_pf_node(g, nd)->mask = WL_PF_MASK_CULL; /* visited, not drawn */
    wl_pf_update_bounds(g, r);
}

/* The geoset index of node n's i-th geoset. */
static guint gset(const Town *t, guint n, guint i)
{
    return g_array_index(wl_pf_node(t->g, n)->geosets, guint, i);
}

static void dl_is(const GArray *dl, const guint (*want)[2], guint n)
{
    assert_int_equal(dl->len, n);
    for (guint i = 0; i < n; i++) {
        const WlPfDlItem *it = &g_array_index(dl, WlPfDlItem, i);
        if (it->op != want[i][0] ||
            (it->op == WL_PF_DL_GEOSET && it->geoset != want[i][1]))
            fail_msg("item %u: op %u geoset %u, expected %u %u", i, it->op,
                     it->geoset, want[i][0], want[i][1]);
    }
}

static void test_cull_and_draw(void **st)
{
    (void)st;
    Town t;
    town_init(&t);
    WlPfView v = box_view(1, TRUE);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfCullStats cs = {0};
    wl_pf_cull(t.g, &v, dl, &cs);
    const guint want[9][2] = {{WL_PF_DL_GEOSET, gset(&t, t.a, 0)},
                              {WL_PF_DL_GEOSET, gset(&t, t.l1, 0)},
                              {WL_PF_DL_GEOSET, gset(&t, t.s1, 0)},
                              {WL_PF_DL_PUSH, 0},
                              {WL_PF_DL_GEOSET, gset(&t, t.bb, 0)},
                              {WL_PF_DL_POP, 0},
                              {WL_PF_DL_PUSH, 0},
                              {WL_PF_DL_GEOSET, gset(&t, t.bb, 1)},
                              {WL_PF_DL_POP, 0}};
    dl_is(dl, want, 9);
    /* root, a, the DCS (culled), the LOD and its child 1, the switch and
     * its child 1, the billboard, the CULL-only geode */
    assert_int_equal(cs.nodes_visited, 9);
    assert_int_equal(cs.sphere_tests, 9);
    assert_int_equal(cs.nodes_culled, 1);
    assert_int_equal(cs.tris_culled, 3);
    assert_int_equal(cs.lods, 1);
    assert_int_equal(cs.lod_sum, 1);
    assert_int_equal(cs.billboards, 2);
    assert_int_equal(cs.matrix_saved, 0);
    /* DRAW: states {1,1,1} (3 from nothing), {1,2,1} (1), {1,2,1} (0),
     * {2,2,2} (2), {1,1,1} (3) */
    WlPfDrawStats ds = {0};
    wl_pf_draw(t.g, dl, &ds);
    assert_int_equal(ds.geosets, 5);
    assert_int_equal(ds.tris, 6);
    assert_int_equal(ds.matrix_ops, 4);
    assert_int_equal(ds.state_changes, 9);
    assert_int_equal(ds.state_naive, 15);
    /* culling off: the DCS is drawn inside its PUSH / POP, nothing tested */
    WlPfView off = box_view(1, FALSE);
    WlPfCullStats c2 = {0};
    g_array_set_size(dl, 0);
    wl_pf_cull(t.g, &off, dl, &c2);
    assert_int_equal(dl->len, 13);
    assert_int_equal(g_array_index(dl, WlPfDlItem, 1).op, WL_PF_DL_PUSH);
    assert_int_equal(g_array_index(dl, WlPfDlItem, 4).op, WL_PF_DL_POP);
    assert_int_equal(c2.sphere_tests, 0);
    assert_int_equal(c2.nodes_culled, 0);
    assert_int_equal(c2.nodes_visited, 11);
    g_array_free(dl, TRUE);
    wl_pf_graph_free(t.g);
}

/* Stress multiplies the LOD distance (the LOD's centre is 8.25 from the
 * eye): x 0.5 is within [0, 5) and picks child 0, x 20 is past 100 and
 * picks none (lod_sum counts the number of children for none). */
static void test_lod_stress(void **st)
{
    (void)st;
    Town t;
    town_init(&t);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfView v = box_view(0.5, TRUE);
    WlPfCullStats cs = {0};
    wl_pf_cull(t.g, &v, dl, &cs);
    assert_int_equal(cs.lod_sum, 0);
    assert_int_equal(dl->len, 9);
    guint lod = wl_pf_child(wl_pf_node(t.g, t.g->root), 2);
    assert_int_equal(g_array_index(dl, WlPfDlItem, 1).geoset,
                     gset(&t, wl_pf_child(wl_pf_node(t.g, lod), 0), 0));
    g_array_set_size(dl, 0);
    WlPfView far = box_view(20, TRUE);
    WlPfCullStats cf = {0};
    wl_pf_cull(t.g, &far, dl, &cf);
    assert_int_equal(cf.lod_sum, 2);
    assert_int_equal(cf.lods, 1);
    assert_int_equal(dl->len, 8);
    assert_int_equal(cf.nodes_visited, 8);
    g_array_free(dl, TRUE);
    wl_pf_graph_free(t.g);
}

/* LOD ranges are half-open, [range[i], range[i + 1]): a LOD whose three
 * children are centred at (4, 0, 0) (its sphere's centre, 4 from the
 * eye) with ranges {r0, r1, r2, r3} picks, at stress s, the child whose
 * range holds 4 s; a distance exactly on a boundary belongs to the
 * farther child, one exactly at the last range to none (lod_sum then
 * counts the 3 children), one below the first range to none too. */
static int lod_pick(const double *ranges, guint nr, double stress)
{
    WlPfGraph *g = wl_pf_graph_new();
    guint gs = wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    guint lod = wl_pf_add_node(g, g->root, WL_PF_LOD);
    guint geo[3];
    for (guint i = 0; i < 3; i++) {
        geo[i] = wl_pf_add_node(g, lod, WL_PF_GEODE);
        const Vec3 t[3] = {vec3(3, 0, 0), vec3(5, 0, 0), vec3(4, 0, 0)};
        wl_pf_add_geoset(g, geo[i], t, 1, gs);
    }
    g_array_append_vals(wl_pf_node(g, lod)->ranges, ranges, nr);
    wl_pf_update_bounds(g, g->root);
    assert_true(wl_pf_node(g, lod)->center.x == 4);
    WlPfView v = box_view(stress, TRUE);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfCullStats cs = {0};
    wl_pf_cull(g, &v, dl, &cs);
    assert_int_equal(cs.lods, 1);
    int pick = -1;
    if (dl->len) {
        assert_int_equal(dl->len, 1);
        guint item = g_array_index(dl, WlPfDlItem, 0).geoset;
        for (guint i = 0; i < 3; i++)
            if (item == g_array_index(wl_pf_node(g, geo[i])->geosets, guint, 0))
                pick = (int)i;
        assert_true(pick >= 0);
        assert_int_equal(cs.lod_sum, pick);
        assert_int_equal(cs.nodes_visited, 3);
    } else {
        assert_int_equal(cs.lod_sum, 3);
        assert_int_equal(cs.nodes_visited, 2);
    }
    g_array_free(dl, TRUE);
    wl_pf_graph_free(g);
    return pick;
}

static void test_lod_boundaries(void **st)
{
    (void)st;
    const double r[5] = {2, 4, 8, 16, 32};
    assert_int_equal(lod_pick(r, 4, 1), 1);     /* 4: on the 0 -> 1 boundary */
    assert_int_equal(lod_pick(r, 4, 0.5), 0);   /* 2: the first range's start */
    assert_int_equal(lod_pick(r, 4, 0.25), -1); /* 1: below every range */
    assert_int_equal(lod_pick(r, 4, 1.5), 1);   /* 6 */
    assert_int_equal(lod_pick(r, 4, 2), 2);     /* 8: on the 1 -> 2 boundary */
    assert_int_equal(lod_pick(r, 4, 3), 2);     /* 12 */
    assert_int_equal(lod_pick(r, 4, 4), -1);    /* 16: the last range's end */
    /* a range past the children's (5 ranges, 3 children): no child 3 */
    assert_int_equal(lod_pick(r, 5, 5), -1); /* 20, in [16, 32) */
    /* one range short (3 ranges): child 2 has no upper bound, never drawn */
    assert_int_equal(lod_pick(r, 3, 1.5), 1);
    assert_int_equal(lod_pick(r, 3, 3), -1);
}

/* The frustum planes of a camera at (1, 2, 3) looking down -z, 90
 * degrees (tan 45 = 1) by aspect 2, near 1, far 10: each unit-normal
 * plane (left, right, bottom, top, near, far) holds the four corners of
 * its face, (1 + 2 x d, 2 + y d, 3 - d) for the face's fixed x = -+1, y
 * = -+1 or d = 1, 10, and has the other corners inside; stress and the
 * culling switch are copied. */
static void test_view_planes(void **st)
{
    (void)st;
    SceneCamera c = scene_camera_default();
    c.eye = vec3(1, 2, 3);
    c.target = vec3(1, 2, -7);
    c.up = vec3(0, 1, 0);
    c.fov_deg = 90;
    c.aspect = 2;
    c.near = 1;
    c.far = 10;
    WlPfView v = wl_pf_view(&c, 1.5, TRUE);
    assert_true(v.stress == 1.5 && v.cull);
    assert_true(v.eye.x == 1 && v.eye.y == 2 && v.eye.z == 3);
    assert_false(wl_pf_view(&c, 1, FALSE).cull);
    for (int p = 0; p < 6; p++) {
        const double *q = v.planes[p];
        assert_true(fabs(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - 1) < 1e-12);
        for (int k = 0; k < 8; k++) {
            double x = k & 1 ? 1 : -1, y = k & 2 ? 1 : -1, d = k & 4 ? 10 : 1;
            Vec3 w = vec3(1 + 2 * x * d, 2 + y * d, 3 - d);
            double dist = q[0] * w.x + q[1] * w.y + q[2] * w.z + q[3];
            double face = p / 2 == 0 ? x : (p / 2 == 1 ? y : (d == 1 ? -1 : 1));
            gboolean on = face == (p % 2 ? 1 : -1);
            if (on ? fabs(dist) > 1e-9 : dist <= 1e-9)
                fail_msg("plane %d corner %d: distance %g", p, k, dist);
        }
    }
}

/* A switch set to none or all. */
static void test_switch(void **st)
{
    (void)st;
    Town t;
    town_init(&t);
    guint sw = wl_pf_child(wl_pf_node(t.g, t.g->root), 3);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfView v = box_view(1, TRUE);
    wl_pf_node(t.g, sw)->which = WL_PF_SWITCH_NONE;
    WlPfCullStats a = {0};
    wl_pf_cull(t.g, &v, dl, &a);
    assert_int_equal(dl->len, 8);
    g_array_set_size(dl, 0);
    wl_pf_node(t.g, sw)->which = WL_PF_SWITCH_ALL;
    WlPfCullStats b = {0};
    wl_pf_cull(t.g, &v, dl, &b);
    assert_int_equal(dl->len, 10);
    assert_int_equal(b.nodes_visited, 10);
    g_array_free(dl, TRUE);
    wl_pf_graph_free(t.g);
}

/* A horizontal triangle at height h over x, z in [0, 4] (x + z <= 4). */
static guint floor_at(WlPfGraph *g, guint parent, WlPfKind kind, double h)
{
    guint n = wl_pf_add_node(g, parent, kind);
    const Vec3 t[3] = {vec3(0, h, 0), vec3(4, h, 0), vec3(0, h, 4)};
    wl_pf_add_geoset(g, n, t, 1, 0);
    return n;
}

static void test_isect(void **st)
{
    (void)st;
    WlPfGraph *g = wl_pf_graph_new();
    wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    guint r = g->root;
    floor_at(g, r, WL_PF_GEODE, 2);
    guint d = wl_pf_add_node(g, r, WL_PF_DCS);
    wl_pf_node(g, d)->xf = mat4_translate(0, 3, 0);
    floor_at(g, d, WL_PF_GEODE, 2); /* at 5 */
    guint hid = floor_at(g, r, WL_PF_GEODE, 9);
    wl_pf_node(g, hid)->mask = WL_PF_MASK_CULL | WL_PF_MASK_DRAW;
    floor_at(g, r, WL_PF_BILLBOARD, 7);
    guint lod = wl_pf_add_node(g, r, WL_PF_LOD);
    floor_at(g, lod, WL_PF_GEODE, 1);
    floor_at(g, lod, WL_PF_GEODE, 8);
    const double ranges[3] = {0, 5, 100};
    g_array_append_vals(wl_pf_node(g, lod)->ranges, ranges, 3);
    guint far = wl_pf_add_node(g, r, WL_PF_DCS);
    wl_pf_node(g, far)->xf = mat4_translate(100, 0, 0);
    floor_at(g, far, WL_PF_GEODE, 6);
    wl_pf_update_bounds(g, r);
    WlPfIsectStats s = {0};
    wl_pf_isect(g, 1, 1, -100, 100, &s);
    assert_true(s.hit && s.height == 5);
    /* root, 2, the DCS and its 5, the billboard, the LOD and its 1, the
     * far DCS (its sphere misses the line) */
    assert_int_equal(s.nodes_tested, 8);
    assert_int_equal(s.tris_tested, 3);
    WlPfIsectStats low = {0};
    wl_pf_isect(g, 1, 1, -100, 4, &low);
    assert_true(low.hit && low.height == 2);
    WlPfIsectStats floor1 = {0};
    wl_pf_isect(g, 1, 1, -100, 1, &floor1); /* a hit exactly at y1 */
    assert_true(floor1.hit && floor1.height == 1);
    WlPfIsectStats at_y0 = {0};
    wl_pf_isect(g, 1, 1, 1, 1.5, &at_y0); /* and one exactly at y0 */
    assert_true(at_y0.hit && at_y0.height == 1);
    WlPfIsectStats miss = {0};
    wl_pf_isect(g, 3.5, 3.5, -100, 100, &miss); /* x + z > 4 */
    assert_false(miss.hit);
    assert_true(miss.tris_tested > 0);
    WlPfIsectStats edge = {0};
    wl_pf_isect(g, 4, 0, -100, 100, &edge); /* a corner counts */
    assert_true(edge.hit && edge.height == 5);
    /* so does a point on each edge (one barycentric weight exactly 0) */
    const double on[3][2] = {{0, 2}, {2, 0}, {2, 2}};
    for (int k = 0; k < 3; k++) {
        WlPfIsectStats e = {0};
        wl_pf_isect(g, on[k][0], on[k][1], -100, 100, &e);
        assert_true(e.hit && e.height == 5);
    }
    wl_pf_graph_free(g);
}

/* ISECT on a triangle in general position, a = (1, 1, 2), b = (5, 3, 1),
 * c = (2, 6, 6), the second of its geoset (after one far away), under an
 * SCS that moves it by (10, 0, 0): a vertical line through the point of
 * barycentric weights (wa, wb, wc) hits at height wa + 3 wb + 6 wc when
 * all three are >= 0, and misses when one is negative. */
static void isect_weights(WlPfGraph *g, double wa, double wb, double wc,
                          gboolean hit)
{
    double x = 10 + wa * 1 + wb * 5 + wc * 2, z = wa * 2 + wb * 1 + wc * 6;
    WlPfIsectStats s = {0};
    wl_pf_isect(g, x, z, -100, 100, &s);
    assert_int_equal(s.nodes_tested, 3);
    assert_int_equal(s.tris_tested, 2);
    if (s.hit != hit || (hit && fabs(s.height - (wa + 3 * wb + 6 * wc)) > 1e-12))
        fail_msg("weights (%g, %g, %g): hit %d at %g", wa, wb, wc, s.hit,
                 s.height);
}

static void test_isect_general_triangle(void **st)
{
    (void)st;
    WlPfGraph *g = wl_pf_graph_new();
    wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    guint scs = wl_pf_add_node(g, g->root, WL_PF_SCS);
    wl_pf_node(g, scs)->xf = mat4_translate(10, 0, 0);
    guint n = wl_pf_add_node(g, scs, WL_PF_GEODE);
    const Vec3 t[6] = {vec3(1, 0, 9), vec3(2, 0, 9), vec3(1, 0, 10),
                       vec3(1, 1, 2), vec3(5, 3, 1), vec3(2, 6, 6)};
    wl_pf_add_geoset(g, n, t, 2, 0);
    wl_pf_update_bounds(g, g->root);
    isect_weights(g, 0.2, 0.3, 0.5, TRUE);
    isect_weights(g, 0.7, 0.1, 0.2, TRUE);
    isect_weights(g, 0.1, 0.8, 0.1, TRUE);
    isect_weights(g, -0.1, 0.6, 0.5, FALSE);
    isect_weights(g, 0.6, -0.1, 0.5, FALSE);
    isect_weights(g, 0.6, 0.5, -0.1, FALSE);
    wl_pf_graph_free(g);
}

/* ISECT prunes by bounding sphere conservatively: a sphere that just
 * touches the segment (its side at the line's distance, its bottom at
 * y1, its top at y0) is still searched.  The triangle (0,2,0) (3,2,0)
 * (0,2,4) has the sphere centre (1.5, 2, 2), radius 2.5 exactly. */
static void test_isect_touching_sphere(void **st)
{
    (void)st;
    WlPfGraph *g = wl_pf_graph_new();
    wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    guint n = wl_pf_add_node(g, g->root, WL_PF_GEODE);
    const Vec3 t[3] = {vec3(0, 2, 0), vec3(3, 2, 0), vec3(0, 2, 4)};
    wl_pf_add_geoset(g, n, t, 1, 0);
    wl_pf_update_bounds(g, g->root);
    assert_true(wl_pf_node(g, n)->radius == 2.5);
    const double q[][4] = {{1, 1, -0.5, -0.5}, /* bottom at y1 */
                           {1, 1, 4.5, 9},     /* top at y0 */
                           {4, 2, -9, 9}};     /* side at the line */
    for (guint i = 0; i < G_N_ELEMENTS(q); i++) {
        WlPfIsectStats s = {0};
        wl_pf_isect(g, q[i][0], q[i][1], q[i][2], q[i][3], &s);
        assert_int_equal(s.nodes_tested, 2);
        assert_int_equal(s.tris_tested, 1);
        assert_false(s.hit);
    }
    /* just past each: pruned at the root */
    const double p[][4] = {
        {1, 1, -0.5, -0.51}, {1, 1, 4.51, 9}, {4.01, 2, -9, 9}};
    for (guint i = 0; i < G_N_ELEMENTS(p); i++) {
        WlPfIsectStats s = {0};
        wl_pf_isect(g, p[i][0], p[i][1], p[i][2], p[i][3], &s);
        assert_int_equal(s.nodes_tested, 1);
        assert_int_equal(s.tris_tested, 0);
    }
    wl_pf_graph_free(g);
}

/* CULL keeps a sphere that touches a frustum plane from outside (the
 * test is conservative): the sphere of radius 2.5 centred 2.5 past the
 * plane x = 10 is drawn, 0.01 further it is culled. */
static void test_cull_touching_plane(void **st)
{
    (void)st;
    for (int k = 0; k < 2; k++) {
        WlPfGraph *g = wl_pf_graph_new();
        wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
        guint d = wl_pf_add_node(g, g->root, WL_PF_DCS);
        wl_pf_node(g, d)->xf = mat4_translate(k ? 11.01 : 11, 0, 0);
        guint n = wl_pf_add_node(g, d, WL_PF_GEODE);
        const Vec3 t[3] = {vec3(0, 2, 0), vec3(3, 2, 0), vec3(0, 2, 4)};
        wl_pf_add_geoset(g, n, t, 1, 0);
        wl_pf_update_bounds(g, g->root);
        WlPfView v = box_view(1, TRUE);
        GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
        WlPfCullStats cs = {0};
        wl_pf_cull(g, &v, dl, &cs);
        assert_int_equal(cs.nodes_culled, k ? 1 : 0);
        assert_int_equal(dl->len, k ? 0 : 3);
        assert_int_equal(cs.tris_culled, k ? 1 : 0);
        g_array_free(dl, TRUE);
        wl_pf_graph_free(g);
    }
}

/* pfFlatten applies each static transform to the geometry below it and
 * turns the SCS into a group (flattened), unless a DCS or billboard is
 * below it (their matrices change); CULL then counts the PUSH and POP
 * each flattened group no longer emits. */
static void test_flatten(void **st)
{
    (void)st;
    WlPfGraph *g = wl_pf_graph_new();
    wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    guint r = g->root;
    guint a = wl_pf_add_node(g, r, WL_PF_SCS);
    wl_pf_node(g, a)->xf = mat4_translate(10, 0, 0);
    guint b = wl_pf_add_node(g, a, WL_PF_SCS);
    wl_pf_node(g, b)->xf = mat4_scale(2, 2, 2);
    guint geo = wl_pf_add_node(g, b, WL_PF_GEODE);
    const Vec3 t[3] = {vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)};
    guint gs = wl_pf_add_geoset(g, geo, t, 1, 0);
    guint c = wl_pf_add_node(g, r, WL_PF_SCS); /* over a DCS: kept */
    wl_pf_node(g, c)->xf = mat4_translate(0, 5, 0);
    guint d = wl_pf_add_node(g, c, WL_PF_DCS);
    guint dg = wl_pf_add_node(g, d, WL_PF_GEODE);
    guint dgs = wl_pf_add_geoset(g, dg, t, 1, 0);
    guint e = wl_pf_add_node(g, r, WL_PF_SCS); /* over a billboard: kept */
    guint bb = wl_pf_add_node(g, e, WL_PF_BILLBOARD);
    wl_pf_add_geoset(g, bb, t, 1, 0);
    wl_pf_update_bounds(g, r);
    assert_int_equal(wl_pf_count_kind(g, WL_PF_SCS), 4);
    assert_int_equal(wl_pf_flatten(g), 2);
    assert_int_equal(wl_pf_count_kind(g, WL_PF_SCS), 2);
    assert_int_equal(wl_pf_count_kind(g, WL_PF_GROUP), 3);
    for (guint k = 0; k < 2; k++) {
        const WlPfNode *n = wl_pf_node(g, k ? b : a);
        assert_int_equal(n->kind, WL_PF_GROUP);
        assert_true(n->flattened);
        assert_true(n->xf.m[0][3] == 0 && n->xf.m[0][0] == 1);
    }
    assert_int_equal(wl_pf_node(g, c)->kind, WL_PF_SCS);
    assert_false(wl_pf_node(g, c)->flattened);
    assert_true(wl_pf_node(g, c)->xf.m[1][3] == 5);
    const WlPfGeoSet *f = wl_pf_geoset(g, gs);
    const Vec3 want[3] = {vec3(12, 0, 0), vec3(10, 2, 0), vec3(10, 0, 2)};
    for (int i = 0; i < 3; i++) {
        Vec3 v = g_array_index(f->verts, Vec3, i);
        assert_true(v.x == want[i].x && v.y == want[i].y && v.z == want[i].z);
    }
    /* the geoset's bound follows its vertices, and the nodes' theirs */
    assert_true(f->center.x == 11 && f->center.y == 1 && f->center.z == 1);
    assert_true(fabs(f->radius - sqrt(3)) < 1e-12);
    assert_true(wl_pf_node(g, a)->center.x == 11);
    /* the geometry under the DCS is untouched */
    assert_true(g_array_index(wl_pf_geoset(g, dgs)->verts, Vec3, 0).x == 1);
    /* CULL: two flattened groups save a PUSH and a POP each; the kept
     * SCS still pushes */
    WlPfView v = box_view(1, FALSE);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfCullStats cs = {0};
    wl_pf_cull(g, &v, dl, &cs);
    assert_int_equal(cs.matrix_saved, 4);
    WlPfDrawStats ds = {0};
    wl_pf_draw(g, dl, &ds);
    /* SCS c and DCS d: 2 PUSH + 2 POP; SCS e: 2, and the billboard's 2 */
    assert_int_equal(ds.matrix_ops, 4 + 2 + 2);
    assert_int_equal(ds.geosets, 3);
    g_array_free(dl, TRUE);
    wl_pf_graph_free(g);
}

/* A geoset of one triangle collapsed to a point has a sphere of radius
 * 0, not an empty one (radius < 0): CULL still visits its geode and
 * draws it, ISECT still tests its triangle (degenerate: no hit). */
static void test_point_geoset(void **state)
{
    (void)state;
    WlPfGraph *g = wl_pf_graph_new();
    guint gs = wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    guint n = wl_pf_add_node(g, g->root, WL_PF_GEODE);
    const Vec3 t[3] = {vec3(1, 2, 1), vec3(1, 2, 1), vec3(1, 2, 1)};
    wl_pf_add_geoset(g, n, t, 1, gs);
    wl_pf_update_bounds(g, g->root);
    assert_true(wl_pf_node(g, n)->radius == 0);
    assert_true(wl_pf_node(g, g->root)->radius == 0);
    WlPfView v = box_view(1, TRUE);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfCullStats cs = {0};
    wl_pf_cull(g, &v, dl, &cs);
    assert_int_equal(cs.nodes_visited, 2);
    assert_int_equal(cs.nodes_culled, 0);
    assert_int_equal(dl->len, 1);
    WlPfIsectStats is = {0};
    wl_pf_isect(g, 1, 1, -100, 100, &is);
    assert_int_equal(is.nodes_tested, 2);
    assert_int_equal(is.tris_tested, 1);
    assert_false(is.hit);
    g_array_free(dl, TRUE);
    wl_pf_graph_free(g);
}

/* A bounding sphere through a transform: the centre moved, the radius
 * times the largest axis scale (3 here, 0.5 for a shrinking one), for
 * radii below 1 too; an empty sphere (radius < 0) stays empty. */
static void test_sphere_xform(void **state)
{
    (void)state;
    Mat4 m = mat4_mul(mat4_translate(1, 2, 3), mat4_scale(2, 3, 1));
    const double r[4] = {0.5, 0, 2, -1}, want[4] = {1.5, 0, 6, -1};
    for (int i = 0; i < 4; i++) {
        Vec3 c;
        double o = NAN;
        wl_pf_sphere_xform(m, vec3(1, 1, 1), r[i], &c, &o);
        assert_true(c.x == 3 && c.y == 5 && c.z == 4);
        if (o != want[i])
            fail_msg("radius %g: %g, expected %g", r[i], o, want[i]);
    }
    /* a shrinking transform shrinks the sphere: largest scale 0.5 */
    Vec3 c;
    double o = NAN;
    wl_pf_sphere_xform(mat4_scale(0.5, 0.25, 0.5), vec3(2, 4, 2), 2, &c, &o);
    assert_true(c.x == 1 && c.y == 1 && c.z == 1 && o == 1);
}

int main(void)
{
    /* a GLib critical (an append to the counting walk's NULL display
     * list, say) fails the suite */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_xform),
        cmocka_unit_test(test_cull_and_draw),
        cmocka_unit_test(test_lod_stress),
        cmocka_unit_test(test_lod_boundaries),
        cmocka_unit_test(test_view_planes),
        cmocka_unit_test(test_switch),
        cmocka_unit_test(test_isect),
        cmocka_unit_test(test_isect_touching_sphere),
        cmocka_unit_test(test_isect_general_triangle),
        cmocka_unit_test(test_cull_touching_plane),
        cmocka_unit_test(test_flatten),
        cmocka_unit_test(test_point_geoset),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
