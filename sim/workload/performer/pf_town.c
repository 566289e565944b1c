/* pf_town.c — the procedural town (see pf_town.h).
 *
 * Placement draws from one sim/core/rng.h stream seeded by (`seed`, 0),
 * the project's only generator, so the town is the same on every
 * platform.  Building is O(size of the town).
 */
#include "sim/workload/performer/pf_town.h"
#include "sim/core/rng.h"

WlPfTownParams wl_pf_town_defaults(void)
{
    return (WlPfTownParams){.blocks = 8,
                            .houses = 6,
                            .trees = 8,
                            .cars = 16,
                            .block = 40,
                            .lod_ranges = {60, 150, 400},
                            .speed = 1.0,
                            .eye_height = 2.0,
                            .fov_deg = 60,
                            .seed = 1};
}

double wl_pf_town_height(double x, double z)
{
    return 2.0 * sin(x / 50.0) * cos(z / 60.0);
}

/* ---- geometry ---------------------------------------------------------- */

static void quad(GArray *v, Vec3 a, Vec3 b, Vec3 c, Vec3 d)
{
    Vec3 t[6] = {a, b, c, a, c, d};
    g_array_append_vals(v, t, 6);
}

/* A box [-sx/2, sx/2] x [0, sy] x [-sz/2, sz/2], each face k x k quads. */
static GArray *box_tris(double sx, double sy, double sz, guint k)
{
    GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
    Vec3 o = vec3(-sx / 2, 0, -sz / 2);
    Vec3 ax[3] = {vec3(sx, 0, 0), vec3(0, sy, 0), vec3(0, 0, sz)};
    for (int f = 0; f < 6; f++) {
        int n = f / 2, a = (n + 1) % 3, b = (n + 2) % 3;
        Vec3 base = f % 2 ? vec3_add(o, ax[n]) : o;
        Vec3 du = vec3_scale(ax[a], 1.0 / k), dv = vec3_scale(ax[b], 1.0 / k);
        for (guint i = 0; i < k; i++)
            for (guint j = 0; j < k; j++) {
                Vec3 p = vec3_add(
                    base, vec3_add(vec3_scale(du, i), vec3_scale(dv, j)));
                quad(v, p, vec3_add(p, du), vec3_add(vec3_add(p, du), dv),
                     vec3_add(p, dv));
            }
    }
    return v;
}

static void add_geoset(WlPfGraph *g, guint node, GArray *tris, guint gstate)
{
    wl_pf_add_geoset(g, node, (Vec3 *)tris->data, tris->len / 3, gstate);
    g_array_free(tris, TRUE);
}

static guint gstate(WlPfGraph *g, guint tex, guint mat, guint modes)
{
    return wl_pf_add_gstate(g, (WlPfGeoState){tex, mat, modes});
}

static void add_terrain(WlPfGraph *g, guint parent, double x0, double z0,
                        double size, guint gs)
{
    guint geode = wl_pf_add_node(g, parent, WL_PF_GEODE);
    GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
    double s = size / 8;
    for (guint i = 0; i < 8; i++)
        for (guint j = 0; j < 8; j++) {
            double x = x0 + i * s, z = z0 + j * s;
            Vec3 p[4] = {
                {x, 0, z}, {x, 0, z + s}, {x + s, 0, z + s}, {x + s, 0, z}};
            for (int c = 0; c < 4; c++)
                p[c].y = wl_pf_town_height(p[c].x, p[c].z);
            quad(v, p[0], p[1], p[2], p[3]);
        }
    add_geoset(g, geode, v, gs);
}

static void add_house(WlPfGraph *g, guint parent, const WlPfTownParams *p,
                      Vec3 at, double yaw, SimRng *rng, guint first_gs)
{
    guint scs = wl_pf_add_node(g, parent, WL_PF_SCS);
    wl_pf_node(g, scs)->callbacks = p->callbacks;
    wl_pf_node(g, scs)->xf = mat4_mul(mat4_translate(at.x, at.y, at.z),
                                      mat4_rotate(vec3(0, 1, 0), yaw));
    guint lod = wl_pf_add_node(g, scs, WL_PF_LOD);
    double r0 = 0;
    g_array_append_val(wl_pf_node(g, lod)->ranges, r0);
    g_array_append_vals(wl_pf_node(g, lod)->ranges, p->lod_ranges, 3);
    double sx = 6 + 6 * sim_rng_uniform(rng),
           sy = 5 + 10 * sim_rng_uniform(rng),
           sz = 6 + 6 * sim_rng_uniform(rng);
    guint gs = first_gs + (guint)sim_rng_below(rng, 6);
    for (guint k = 4; k >= 1; k /= 2) {
        guint geode = wl_pf_add_node(g, lod, WL_PF_GEODE);
        add_geoset(g, geode, box_tris(sx, sy, sz, k), gs);
    }
}

static void add_trees(WlPfGraph *g, guint parent, const WlPfTownParams *p,
                      double x0, double z0, SimRng *rng, guint gs)
{
    guint bb = wl_pf_add_node(g, parent, WL_PF_BILLBOARD);
    wl_pf_node(g, bb)->mask &= ~(guint32)WL_PF_MASK_ISECT;
    for (guint i = 0; i < p->trees; i++) {
        double x = x0 + 2 + (p->block - 4) * sim_rng_uniform(rng);
        double z = z0 + 2 + (p->block - 4) * sim_rng_uniform(rng);
        double y = wl_pf_town_height(x, z);
        GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
        quad(v, vec3(x - 2, y, z), vec3(x + 2, y, z), vec3(x + 2, y + 8, z),
             vec3(x - 2, y + 8, z));
        add_geoset(g, bb, v, gs);
    }
}

static void add_lamps(WlPfGraph *g, guint parent, double x0, double z0,
                      gboolean on, guint gs)
{
    guint sw = wl_pf_add_node(g, parent, WL_PF_SWITCH);
    wl_pf_node(g, sw)->which = on ? WL_PF_SWITCH_ALL : WL_PF_SWITCH_NONE;
    guint geode = wl_pf_add_node(g, sw, WL_PF_GEODE);
    GArray *v = g_array_new(FALSE, FALSE, sizeof(Vec3));
    for (int c = 0; c < 4; c++) {
        double x = x0 + (c & 1 ? 1 : 39), z = z0 + (c & 2 ? 1 : 39);
        GArray *b = box_tris(0.3, 5, 0.3, 1);
        for (guint i = 0; i < b->len; i++) {
            Vec3 q = g_array_index(b, Vec3, i);
            q = vec3_add(q, vec3(x, wl_pf_town_height(x, z), z));
            g_array_append_val(v, q);
        }
        g_array_free(b, TRUE);
    }
    add_geoset(g, geode, v, gs);
}

static void add_block(WlPfTown *t, guint parent, guint bi, guint bj,
                      SimRng *rng, guint gs0)
{
    WlPfGraph *g = t->g;
    const WlPfTownParams *p = &t->p;
    double x0 = bi * p->block, z0 = bj * p->block;
    guint grp = wl_pf_add_node(g, parent, WL_PF_GROUP);
    add_terrain(g, grp, x0, z0, p->block, gs0);
    for (guint h = 0; h < p->houses; h++) {
        double x = x0 + 6 + (p->block - 12) * sim_rng_uniform(rng);
        double z = z0 + 6 + (p->block - 12) * sim_rng_uniform(rng);
        Vec3 at = vec3(x, wl_pf_town_height(x, z), z);
        add_house(g, grp, p, at, 2 * G_PI * sim_rng_uniform(rng), rng, gs0 + 3);
    }
    add_trees(g, grp, p, x0, z0, rng, gs0 + 1);
    add_lamps(g, grp, x0, z0, (bi + bj) % 2 == 0, gs0 + 2);
}

/* The quadtree of groups over blocks [i0, i1) x [j0, j1) under `node`:
 * parent[i * blocks + j] gets the group block (i, j) goes under. */
static void add_quadtree(WlPfTown *t, guint node, guint i0, guint i1,
                         guint j0, guint j1, guint *parent)
{
    if (i1 - i0 <= 1 && j1 - j0 <= 1) {
        parent[i0 * t->p.blocks + j0] = node;
        return;
    }
    guint im = (i0 + i1 + 1) / 2, jm = (j0 + j1 + 1) / 2;
    const guint r[4][4] = {
        {i0, im, j0, jm}, {i0, im, jm, j1}, {im, i1, j0, jm}, {im, i1, jm, j1}};
    for (int q = 0; q < 4; q++)
        if (r[q][0] < r[q][1] && r[q][2] < r[q][3])
            add_quadtree(t, wl_pf_add_node(t->g, node, WL_PF_GROUP), r[q][0],
                         r[q][1], r[q][2], r[q][3], parent);
}

/* The blocks in row order (the placement's draws), each under the root
 * (flat) or its quadtree group (deep). */
static void add_blocks(WlPfTown *t, SimRng *rng, guint gs0)
{
    guint n = t->p.blocks, *parent = g_new(guint, n * n);
    t->blocks_node = t->p.partition
                         ? wl_pf_add_node(t->g, t->g->root, WL_PF_PARTITION)
                         : t->g->root;
    for (guint i = 0; i < n * n; i++)
        parent[i] = t->blocks_node;
    if (t->p.deep)
        add_quadtree(t, t->blocks_node, 0, n, 0, n, parent);
    for (guint i = 0; i < n; i++)
        for (guint j = 0; j < n; j++)
            add_block(t, parent[i * n + j], i, j, rng, gs0);
    g_free(parent);
}

/* ---- cars -------------------------------------------------------------- */

static Mat4 car_matrix(const WlPfTown *t, guint c, guint frame)
{
    const WlPfTownParams *p = &t->p;
    double len = p->blocks * p->block;
    double x = fmod(c * 37.0 + frame * 0.5 * (1 + c % 3), len);
    double z = (c % p->blocks) * p->block + (c % 2 ? 1.5 : -1.5);
    return mat4_translate(x, wl_pf_town_height(x, z), z);
}

static void add_cars(WlPfTown *t, guint gs)
{
    WlPfGraph *g = t->g;
    t->car_group = wl_pf_add_node(g, g->root, WL_PF_GROUP);
    for (guint c = 0; c < t->p.cars; c++) {
        guint dcs = wl_pf_add_node(g, t->car_group, WL_PF_DCS);
        wl_pf_node(g, dcs)->xf = car_matrix(t, c, 0);
        guint geode = wl_pf_add_node(g, dcs, WL_PF_GEODE);
        add_geoset(g, geode, box_tris(4, 1.5, 2, 2), gs);
        g_array_append_val(t->cars, dcs);
    }
}

WlPfTown *wl_pf_town_new(const WlPfTownParams *p)
{
    WlPfTown *t = g_new0(WlPfTown, 1);
    t->p = *p;
    t->g = wl_pf_graph_new();
    t->cars = g_array_new(FALSE, FALSE, sizeof(guint));
    SimRng rng;
    sim_rng_init(&rng, p->seed, 0);
    /* terrain, trees, lamps, six house looks, cars */
    guint gs0 = gstate(t->g, 0, 0, 0);
    gstate(t->g, 1, 1, 1);
    gstate(t->g, 2, 2, 0);
    for (guint i = 0; i < 6; i++)
        gstate(t->g, 3 + i % 3, 3 + i % 2, i % 2);
    gstate(t->g, 6, 5, 0);
    add_blocks(t, &rng, gs0);
    add_cars(t, gs0 + 9);
    wl_pf_update_bounds(t->g, t->g->root);
    if (p->partition)
        wl_pf_partition_build(t->g, t->blocks_node, p->partition);
    return t;
}

void wl_pf_town_free(WlPfTown *t)
{
    if (!t)
        return;
    wl_pf_graph_free(t->g);
    g_array_free(t->cars, TRUE);
    g_free(t);
}

guint wl_pf_town_update(WlPfTown *t, guint frame)
{
    for (guint c = 0; c < t->cars->len; c++)
        wl_pf_node(t->g, g_array_index(t->cars, guint, c))->xf =
            car_matrix(t, c, frame);
    wl_pf_update_bounds(t->g, t->car_group);
    wl_pf_update_bounds_shallow(t->g, t->g->root);
    return t->cars->len;
}

SceneCamera wl_pf_town_camera(const WlPfTown *t, guint frame, double ground)
{
    const WlPfTownParams *p = &t->p;
    double len = p->blocks * p->block;
    double x = fmod(frame * p->speed, len);
    double z = (p->blocks / 2) * p->block;
    SceneCamera c = scene_camera_default();
    c.eye = vec3(x, ground + p->eye_height, z);
    double yaw = 0.4 * sin(frame / 40.0);
    c.target = vec3_add(c.eye, vec3(cos(yaw), -0.05, sin(yaw)));
    c.up = vec3(0, 1, 0);
    c.fov_deg = p->fov_deg;
    c.near = 0.5;
    c.far = 2 * len;
    c.aspect = 1.25;
    return c;
}
