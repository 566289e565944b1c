/* test_pf_town.c — the procedural town (pf_town.c) node by node against
 * its description: per block a group of the terrain (8 x 8 quads on the
 * height field 2 sin(x / 50) cos(z / 60)), the houses (an SCS over a LOD
 * of three boxes, 4 x 4, 2 x 2 and 1 x 1 quads a face, ranges 0 and
 * lod_ranges), a billboard of trees (4 m wide, 8 m tall quads standing
 * on the terrain, 2 m or more inside the block, hidden from ISECT) and a
 * switch of four lamp posts (on in every other block); then a group of
 * cars (a DCS over a 2 x 2-quad box each, in their lanes).  The camera
 * drives down the middle street; APP moves every car.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/core/rng.h"
#include "sim/workload/performer/pf_town.h"

static WlPfTown *small_town(void)
{
    WlPfTownParams p = wl_pf_town_defaults();
    p.blocks = 2;
    p.houses = 2;
    p.trees = 3;
    p.cars = 3;
    return wl_pf_town_new(&p);
}

static const WlPfNode *child(const WlPfTown *t, const WlPfNode *n, guint i)
{
    assert_true(i < n->children->len);
    return wl_pf_node(t->g, wl_pf_child(n, i));
}

static const WlPfGeoSet *only_geoset(const WlPfTown *t, const WlPfNode *n)
{
    assert_int_equal(n->geosets->len, 1);
    return wl_pf_geoset(t->g, g_array_index(n->geosets, guint, 0));
}

static Vec3 vtx(const WlPfGeoSet *gs, guint i)
{
    return g_array_index(gs->verts, Vec3, i);
}

/* The box of a geoset's vertices. */
static void bbox(const WlPfGeoSet *gs, Vec3 *lo, Vec3 *hi)
{
    *lo = vec3(INFINITY, INFINITY, INFINITY);
    *hi = vec3(-INFINITY, -INFINITY, -INFINITY);
    for (guint i = 0; i < gs->verts->len; i++) {
        Vec3 v = vtx(gs, i);
        *lo = vec3(fmin(lo->x, v.x), fmin(lo->y, v.y), fmin(lo->z, v.z));
        *hi = vec3(fmax(hi->x, v.x), fmax(hi->y, v.y), fmax(hi->z, v.z));
    }
}

static void near(double a, double b)
{
    if (fabs(a - b) > 1e-9)
        fail_msg("%.12f, expected %.12f", a, b);
}

static void test_height(void **st)
{
    (void)st;
    near(wl_pf_town_height(0, 0), 0);
    near(wl_pf_town_height(25 * G_PI, 0), 2);
    near(wl_pf_town_height(25 * G_PI, 60 * G_PI), -2);
    near(wl_pf_town_height(10, 20), 2 * sin(0.2) * cos(20.0 / 60));
}

static void check_terrain(const WlPfTown *t, const WlPfNode *n, double x0,
                          double z0)
{
    assert_int_equal(n->kind, WL_PF_GEODE);
    const WlPfGeoSet *gs = only_geoset(t, n);
    assert_int_equal(wl_pf_geoset_tris(gs), 128);
    assert_int_equal(gs->gstate, 0);
    Vec3 lo, hi;
    bbox(gs, &lo, &hi);
    near(lo.x, x0), near(hi.x, x0 + 40), near(lo.z, z0), near(hi.z, z0 + 40);
    for (guint i = 0; i < gs->verts->len; i++) {
        Vec3 v = vtx(gs, i);
        near(v.y, wl_pf_town_height(v.x, v.z));
        near(fmod(v.x - x0, 5), 0); /* the 5 m grid */
        near(fmod(v.z - z0, 5), 0);
    }
    /* the first quad: (x0, z0) (x0, z0 + 5) (x0 + 5, z0 + 5) */
    near(vtx(gs, 0).x, x0), near(vtx(gs, 1).z, z0 + 5);
    near(vtx(gs, 2).x, x0 + 5), near(vtx(gs, 5).x, x0 + 5);
    near(vtx(gs, 5).z, z0);
}

static void check_house(const WlPfTown *t, const WlPfNode *scs, double x0,
                        double z0)
{
    assert_int_equal(scs->kind, WL_PF_SCS);
    double x = scs->xf.m[0][3], z = scs->xf.m[2][3];
    assert_true(x >= x0 + 6 && x <= x0 + 34 && z >= z0 + 6 && z <= z0 + 34);
    near(scs->xf.m[1][3], wl_pf_town_height(x, z));
    const WlPfNode *lod = child(t, scs, 0);
    assert_int_equal(lod->kind, WL_PF_LOD);
    assert_int_equal(lod->ranges->len, 4);
    const double r[4] = {0, 60, 150, 400};
    for (guint i = 0; i < 4; i++)
        assert_true(g_array_index(lod->ranges, double, i) == r[i]);
    assert_int_equal(lod->children->len, 3);
    Vec3 lo0, hi0;
    for (guint i = 0; i < 3; i++) {
        const WlPfGeoSet *gs = only_geoset(t, child(t, lod, i));
        guint k = 4 >> i;
        assert_int_equal(wl_pf_geoset_tris(gs), 12 * k * k);
        assert_true(gs->gstate >= 3 && gs->gstate < 9);
        Vec3 lo, hi;
        bbox(gs, &lo, &hi);
        near(lo.y, 0);
        near(lo.x, -hi.x), near(lo.z, -hi.z);
        assert_true(hi.x >= 3 && hi.x <= 6 && hi.y >= 5 && hi.y <= 15);
        if (i == 0)
            lo0 = lo, hi0 = hi;
        near(hi.x, hi0.x), near(hi.y, hi0.y), near(lo.z, lo0.z);
    }
}

static void check_trees(const WlPfTown *t, const WlPfNode *bb, double x0,
                        double z0)
{
    assert_int_equal(bb->kind, WL_PF_BILLBOARD);
    assert_int_equal(bb->mask, WL_PF_MASK_CULL | WL_PF_MASK_DRAW);
    assert_int_equal(bb->geosets->len, 3);
    for (guint i = 0; i < 3; i++) {
        const WlPfGeoSet *gs =
            wl_pf_geoset(t->g, g_array_index(bb->geosets, guint, i));
        assert_int_equal(wl_pf_geoset_tris(gs), 2);
        assert_int_equal(gs->gstate, 1);
        Vec3 lo, hi;
        bbox(gs, &lo, &hi);
        near(hi.x - lo.x, 4);
        near(hi.y - lo.y, 8);
        near(hi.z, lo.z);
        double x = (lo.x + hi.x) / 2;
        near(lo.y, wl_pf_town_height(x, lo.z));
        /* the quad (x-2, y) (x+2, y) (x+2, y+8) (x-2, y+8) as two
         * triangles a b c, a c d */
        const double qx[6] = {-2, 2, 2, -2, 2, -2}, qy[6] = {0, 0, 8, 0, 8, 8};
        for (guint k = 0; k < 6; k++) {
            near(vtx(gs, k).x, x + qx[k]);
            near(vtx(gs, k).y, lo.y + qy[k]);
        }
        assert_true(x >= x0 + 2 && x <= x0 + 38);
        assert_true(lo.z >= z0 + 2 && lo.z <= z0 + 38);
    }
}

static void check_lamps(const WlPfTown *t, const WlPfNode *sw, double x0,
                        double z0, gboolean on)
{
    assert_int_equal(sw->kind, WL_PF_SWITCH);
    assert_int_equal(sw->which, on ? WL_PF_SWITCH_ALL : WL_PF_SWITCH_NONE);
    const WlPfGeoSet *gs = only_geoset(t, child(t, sw, 0));
    assert_int_equal(wl_pf_geoset_tris(gs), 4 * 12);
    assert_int_equal(gs->gstate, 2);
    for (guint c = 0; c < 4; c++) {
        Vec3 lo = vec3(INFINITY, INFINITY, INFINITY),
             hi = vec3(-1e9, -1e9, -1e9);
        for (guint i = 36 * c; i < 36 * (c + 1); i++) {
            Vec3 v = vtx(gs, i);
            lo = vec3(fmin(lo.x, v.x), fmin(lo.y, v.y), fmin(lo.z, v.z));
            hi = vec3(fmax(hi.x, v.x), fmax(hi.y, v.y), fmax(hi.z, v.z));
        }
        double x = x0 + (c & 1 ? 1 : 39), z = z0 + (c & 2 ? 1 : 39);
        near(lo.x, x - 0.15), near(hi.x, x + 0.15);
        near(lo.z, z - 0.15), near(hi.z, z + 0.15);
        near(lo.y, wl_pf_town_height(x, z));
        near(hi.y - lo.y, 5);
    }
}

static void test_blocks(void **st)
{
    (void)st;
    WlPfTown *t = small_town();
    const WlPfNode *root = wl_pf_node(t->g, t->g->root);
    assert_int_equal(root->children->len, 4 + 1);
    assert_int_equal(t->g->gstates->len, 10);
    /* terrain, trees, lamps, six house looks, cars */
    const guint gst[10][3] = {{0, 0, 0}, {1, 1, 1}, {2, 2, 0}, {3, 3, 0},
                              {4, 4, 1}, {5, 3, 0}, {3, 4, 1}, {4, 3, 0},
                              {5, 4, 1}, {6, 5, 0}};
    for (guint i = 0; i < 10; i++) {
        const WlPfGeoState *x = &g_array_index(t->g->gstates, WlPfGeoState, i);
        if (x->texture != gst[i][0] || x->material != gst[i][1] ||
            x->modes != gst[i][2])
            fail_msg("geostate %u: %u %u %u", i, x->texture, x->material,
                     x->modes);
    }
    const WlPfGeoState *g5 = &g_array_index(t->g->gstates, WlPfGeoState, 5);
    assert_true(g5->texture == 5 && g5->material == 3 && g5->modes == 0);
    const WlPfGeoState *g9 = &g_array_index(t->g->gstates, WlPfGeoState, 9);
    assert_true(g9->texture == 6 && g9->material == 5 && g9->modes == 0);
    const WlPfGeoState *g4 = &g_array_index(t->g->gstates, WlPfGeoState, 4);
    assert_true(g4->texture == 4 && g4->material == 4 && g4->modes == 1);
    for (guint bi = 0; bi < 2; bi++)
        for (guint bj = 0; bj < 2; bj++) {
            const WlPfNode *b = child(t, root, 2 * bi + bj);
            double x0 = 40.0 * bi, z0 = 40.0 * bj;
            assert_int_equal(b->kind, WL_PF_GROUP);
            assert_int_equal(b->children->len, 1 + 2 + 1 + 1);
            check_terrain(t, child(t, b, 0), x0, z0);
            check_house(t, child(t, b, 1), x0, z0);
            check_house(t, child(t, b, 2), x0, z0);
            check_trees(t, child(t, b, 3), x0, z0);
            check_lamps(t, child(t, b, 4), x0, z0, (bi + bj) % 2 == 0);
        }
    assert_int_equal(wl_pf_count_kind(t->g, WL_PF_SCS), 8);
    assert_int_equal(wl_pf_count_kind(t->g, WL_PF_DCS), 3);
    wl_pf_town_free(t);
}

/* splitmix64 (Steele, Lea and Flood 2014), the town's placement stream,
 * written out again here so that every drawn value can be predicted. */
/* Every placement from the seed, in drawing order: per block, per
 * house x = x0 + 6 + (block - 12) u, z likewise, yaw 2 pi u, size 6 + 6
 * u by 5 + 10 u by 6 + 6 u, look 3 + (a draw below 6); then per tree x =
 * x0 + 2 + (block - 4) u, z likewise; u from one sim/core/rng.h stream
 * (seed, 0). */
static void test_placement_from_seed(void **st)
{
    (void)st;
    WlPfTownParams p = wl_pf_town_defaults();
    p.blocks = 2, p.houses = 2, p.trees = 3, p.cars = 0, p.seed = 77;
    p.block = 50;
    WlPfTown *t = wl_pf_town_new(&p);
    SimRng r;
    sim_rng_init(&r, 77, 0);
    SimRng *rng = &r;
    const WlPfNode *root = wl_pf_node(t->g, t->g->root);
    for (guint bi = 0; bi < 2; bi++)
        for (guint bj = 0; bj < 2; bj++) {
            const WlPfNode *b = child(t, root, 2 * bi + bj);
            double x0 = 50.0 * bi, z0 = 50.0 * bj;
            for (guint h = 0; h < 2; h++) {
                double x = x0 + 6 + 38 * sim_rng_uniform(rng);
                double z = z0 + 6 + 38 * sim_rng_uniform(rng);
                double yaw = 2 * G_PI * sim_rng_uniform(rng);
                double sx = 6 + 6 * sim_rng_uniform(rng),
                       sy = 5 + 10 * sim_rng_uniform(rng);
                double sz = 6 + 6 * sim_rng_uniform(rng);
                guint look = 3 + (guint)sim_rng_below(rng, 6);
                const WlPfNode *scs = child(t, b, 1 + h);
                Mat4 want =
                    mat4_mul(mat4_translate(x, wl_pf_town_height(x, z), z),
                             mat4_rotate(vec3(0, 1, 0), yaw));
                for (int i = 0; i < 4; i++)
                    for (int j = 0; j < 4; j++)
                        near(scs->xf.m[i][j], want.m[i][j]);
                const WlPfGeoSet *gs =
                    only_geoset(t, child(t, child(t, scs, 0), 2));
                Vec3 lo, hi;
                bbox(gs, &lo, &hi);
                near(hi.x, sx / 2), near(hi.y, sy), near(hi.z, sz / 2);
                assert_int_equal(gs->gstate, look);
            }
            const WlPfNode *bb = child(t, b, 3);
            for (guint k = 0; k < 3; k++) {
                double x = x0 + 2 + 46 * sim_rng_uniform(rng);
                double z = z0 + 2 + 46 * sim_rng_uniform(rng);
                const WlPfGeoSet *gs =
                    wl_pf_geoset(t->g, g_array_index(bb->geosets, guint, k));
                near(vtx(gs, 0).x, x - 2), near(vtx(gs, 0).z, z);
                near(vtx(gs, 0).y, wl_pf_town_height(x, z));
            }
        }
    wl_pf_town_free(t);
}

/* Each box has its six faces: of a house's 12 k^2 triangles, 2 k^2 lie
 * in each face plane of its box. */
static void test_box_faces(void **st)
{
    (void)st;
    WlPfTown *t = small_town();
    const WlPfNode *lod =
        child(t, child(t, wl_pf_node(t->g, t->g->root), 0), 1);
    lod = child(t, lod, 0);
    for (guint i = 0; i < 3; i++) {
        const WlPfGeoSet *gs = only_geoset(t, child(t, lod, i));
        guint k = 4 >> i;
        Vec3 lo, hi;
        bbox(gs, &lo, &hi);
        const double bound[3][2] = {{lo.x, hi.x}, {lo.y, hi.y}, {lo.z, hi.z}};
        for (int a = 0; a < 3; a++)
            for (int side = 0; side < 2; side++) {
                guint in = 0;
                for (guint tr = 0; tr < wl_pf_geoset_tris(gs); tr++) {
                    gboolean all = TRUE;
                    for (guint v = 0; v < 3; v++) {
                        Vec3 q = vtx(gs, 3 * tr + v);
                        double c = a == 0 ? q.x : (a == 1 ? q.y : q.z);
                        all &= fabs(c - bound[a][side]) < 1e-9;
                    }
                    in += all;
                }
                if (in != 2 * k * k)
                    fail_msg("LOD %u axis %d side %d: %u triangles, "
                             "expected %u",
                             i, a, side, in, 2 * k * k);
            }
    }
    wl_pf_town_free(t);
}

/* Car c at frame f: x = (37 c + 0.5 f (1 + c mod 3)) mod 80, in lane
 * z = (c mod 2 blocks) x 40 +- 1.5, on the terrain. */
static void car_is(const WlPfTown *t, guint c, guint f)
{
    const WlPfNode *d = wl_pf_node(t->g, g_array_index(t->cars, guint, c));
    double x = fmod(c * 37.0 + f * 0.5 * (1 + c % 3), 80);
    double z = (c % 2) * 40.0 + (c % 2 ? 1.5 : -1.5);
    near(d->xf.m[0][3], x);
    near(d->xf.m[2][3], z);
    near(d->xf.m[1][3], wl_pf_town_height(x, z));
    near(d->xf.m[0][0], 1);
}

static void test_cars(void **st)
{
    (void)st;
    WlPfTown *t = small_town();
    const WlPfNode *root = wl_pf_node(t->g, t->g->root);
    const WlPfNode *cars = child(t, root, 4);
    assert_int_equal(wl_pf_child(root, 4), t->car_group);
    assert_int_equal(cars->children->len, 3);
    for (guint c = 0; c < 3; c++) {
        assert_int_equal(wl_pf_child(cars, c),
                         g_array_index(t->cars, guint, c));
        const WlPfNode *d = child(t, cars, c);
        const WlPfGeoSet *gs = only_geoset(t, child(t, d, 0));
        assert_int_equal(wl_pf_geoset_tris(gs), 48);
        assert_int_equal(gs->gstate, 9);
        Vec3 lo, hi;
        bbox(gs, &lo, &hi);
        near(lo.x, -2), near(hi.x, 2), near(lo.y, 0), near(hi.y, 1.5);
        near(lo.z, -1), near(hi.z, 1);
        car_is(t, c, 0);
    }
    assert_int_equal(wl_pf_town_update(t, 7), 3);
    for (guint c = 0; c < 3; c++)
        car_is(t, c, 7);
    /* the bounds follow: the cars' group holds car 1 where it went */
    const WlPfNode *d1 = child(t, cars, 1);
    Vec3 dc = vec3_sub(d1->center, cars->center);
    assert_true(vec3_len(dc) + d1->radius <= cars->radius + 1e-9);
    near(d1->center.x, fmod(37 + 7 * 0.5 * 2, 80));
    wl_pf_town_free(t);
}

/* Houses face any way: their turns about +y cover the whole circle
 * (sin of the yaw of both signs, in the default town). */
static void test_house_yaws(void **st)
{
    (void)st;
    WlPfTownParams p = wl_pf_town_defaults();
    WlPfTown *t = wl_pf_town_new(&p);
    guint pos = 0, neg = 0, houses = 0;
    for (guint i = 0; i < t->g->nodes->len; i++) {
        const WlPfNode *n = wl_pf_node(t->g, i);
        if (n->kind != WL_PF_SCS)
            continue;
        houses++;
        double c = n->xf.m[0][0], s = n->xf.m[0][2];
        near(c * c + s * s, 1);
        pos += s > 0.5, neg += s < -0.5;
    }
    assert_int_equal(houses, 8 * 8 * 6);
    assert_true(pos > 50 && neg > 50);
    wl_pf_town_free(t);
}

static void test_camera(void **st)
{
    (void)st;
    WlPfTown *t = small_town();
    for (guint f = 0; f < 200; f += 70) {
        SceneCamera c = wl_pf_town_camera(t, f, 3);
        near(c.eye.x, fmod(f * 1.0, 80));
        near(c.eye.y, 3 + 2);
        near(c.eye.z, 40);
        double yaw = 0.4 * sin(f / 40.0);
        near(c.target.x - c.eye.x, cos(yaw));
        near(c.target.y - c.eye.y, -0.05);
        near(c.target.z - c.eye.z, sin(yaw));
        near(c.up.y, 1);
        near(c.fov_deg, 60);
        near(c.near, 0.5);
        near(c.far, 160);
        near(c.aspect, 1.25);
    }
    wl_pf_town_free(t);
}

/* The defaults docs/workloads.md gives for `town` (performer). */
static void test_defaults(void **st)
{
    (void)st;
    WlPfTownParams p = wl_pf_town_defaults();
    assert_int_equal(p.blocks, 8);
    assert_int_equal(p.houses, 6);
    assert_int_equal(p.trees, 8);
    assert_int_equal(p.cars, 16);
    assert_true(p.block == 40);
    assert_true(p.lod_ranges[0] == 60 && p.lod_ranges[1] == 150 &&
                p.lod_ranges[2] == 400);
    assert_true(p.speed == 1 && p.eye_height == 2 && p.fov_deg == 60);
    assert_int_equal(p.seed, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_height),
        cmocka_unit_test(test_blocks),
        cmocka_unit_test(test_cars),
        cmocka_unit_test(test_camera),
        cmocka_unit_test(test_house_yaws),
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_placement_from_seed),
        cmocka_unit_test(test_box_faces),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
