/* pphigs_db.c — generators of seed 001's four PPHIGS databases.
 *
 * Shapes (all counts from the spec, i.e. from YAML):
 *   station  one structure: a REPLACE matrix, then polygons in modules,
 *            one colour starting each module; attributes spread evenly.
 *   lobby    the same layout of objects (a colour, then ~7.8 polygons) in
 *            a room; the standard view stands in the middle of the room,
 *            so that most objects behind and beside it are off-screen.
 *   flock    root "flock" executes the Old Well's structures (objects of
 *            a colour and polygons), then for each boid a REPLACE matrix
 *            and an execute of "boid", a primitive structure (§2.3.3) of
 *            colours and polygons.
 *   humans   per figure a tree of structures `levels` deep; each holds a
 *            matrix (REPLACE at a figure's root, CONCATENATE at joints),
 *            a colour, its polygons, then executes of its children.
 * Element tags number primitives 1, 2, 3 ... in creation order.
 * Cost: O(polygons + structures).  Seed 001 §6 and its table.
 */
#include "sim/scene/pphigs_db.h"
#include "sim/core/rng.h"
#include <string.h>

static const char *const kind_names[SCENE_PPHIGS_NKINDS] = {
    "space_station",
    "building_lobby",
    "flock_old_well",
    "two_human_figures",
};

const char *scene_pphigs_kind_name(ScenePphigsKind k)
{
    g_assert(k < SCENE_PPHIGS_NKINDS);
    return kind_names[k];
}

gboolean scene_pphigs_kind_parse(const char *s, ScenePphigsKind *out)
{
    for (int k = 0; k < SCENE_PPHIGS_NKINDS; k++)
        if (strcmp(s, kind_names[k]) == 0) {
            *out = (ScenePphigsKind)k;
            return TRUE;
        }
    return FALSE;
}

typedef struct {
    SceneDb *db;
    SimRng rng;
    guint verts;
    uint64_t next_tag;
} Gen;

/* Item k's share when `total` items are spread over n slots. */
static guint share(guint k, guint total, guint n)
{
    return (guint)(((uint64_t)(k + 1) * total) / n - ((uint64_t)k * total) / n);
}

static double uni(Gen *g, double lo, double hi)
{
    return lo + (hi - lo) * sim_rng_uniform(&g->rng);
}

static Vec3 rnd_in(Gen *g, Vec3 lo, Vec3 hi)
{
    return vec3(uni(g, lo.x, hi.x), uni(g, lo.y, hi.y), uni(g, lo.z, hi.z));
}

void scene_pphigs_plane_basis(Vec3 n, Vec3 *u, Vec3 *v)
{
    Vec3 a = fabs(n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0);
    *u = vec3_norm(vec3_cross(n, a));
    *v = vec3_cross(n, *u);
}

/* A planar regular polygon of radius r about c, randomly oriented. */
static void add_poly(Gen *g, guint sid, Vec3 c, double r)
{
    Vec3 n = vec3_norm(rnd_in(g, vec3(-1, -1, -1), vec3(1, 1, 1))), u, v;
    scene_pphigs_plane_basis(n, &u, &v);
    Vec3 *p = g_new(Vec3, g->verts);
    for (guint i = 0; i < g->verts; i++) {
        double t = 2 * G_PI * i / g->verts;
        p[i] = vec3_add(
            c, vec3_add(vec3_scale(u, r * cos(t)), vec3_scale(v, r * sin(t))));
    }
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, p, g->verts);
    e.tag = g->next_tag++;
    gboolean ok = scene_db_append(g->db, sid, &e, NULL);
    g_assert(ok);
    g_free(p);
}

static void add_el(Gen *g, guint sid, SceneElem e)
{
    gboolean ok = scene_db_append(g->db, sid, &e, NULL);
    g_assert(ok);
}

static void add_color(Gen *g, guint sid)
{
    add_el(
        g, sid,
        scene_elem_color(vec3(uni(g, 0.2, 1), uni(g, 0.2, 1), uni(g, 0.2, 1))));
}

/* `polys` polygons in `groups` objects, each object opened by a colour,
 * centres drawn in [lo, hi]; object radius r.  The first of `attrs`
 * attributes is a REPLACE matrix (the model's placement). */
static void add_objects(Gen *g, guint sid, guint polys, guint attrs, Vec3 lo,
                        Vec3 hi, double r)
{
    add_el(g, sid, scene_elem_matrix(mat4_identity(), SCENE_MAT_REPLACE));
    guint groups = attrs - 1;
    for (guint k = 0; k < groups; k++) {
        add_color(g, sid);
        Vec3 c = rnd_in(g, lo, hi);
        guint n = share(k, polys, groups);
        for (guint i = 0; i < n; i++)
            add_poly(g, sid,
                     vec3_add(c, rnd_in(g, vec3(-r, -r, -r), vec3(r, r, r))),
                     r * 0.5);
    }
}

static gboolean need(gboolean ok, const char *found, const char *expected,
                     GError **err)
{
    if (!ok)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "found %s, expected %s",
                    found, expected);
    return ok;
}

static void gen_station(Gen *g, const ScenePphigsSpec *s)
{
    guint sid = scene_db_add_struct(g->db, "station");
    double h = s->size / 2;
    add_objects(g, sid, s->polygons, s->attributes, vec3(-h, -h / 4, -h / 4),
                vec3(h, h / 4, h / 4), s->size / 40);
    scene_db_post(g->db, sid);
}

static void gen_lobby(Gen *g, const ScenePphigsSpec *s)
{
    guint sid = scene_db_add_struct(g->db, "lobby");
    double h = s->size / 2;
    add_objects(g, sid, s->polygons, s->attributes, vec3(-h, 0, -h),
                vec3(h, h / 3, h), s->size / 60);
    scene_db_post(g->db, sid);
}

/* The Old Well: `well_structs` structures executed by the flock root,
 * together holding well_polygons polygons in well_attributes objects
 * (a colour, then its polygons) on a ring of columns under a dome. */
static void gen_well(Gen *g, const ScenePphigsSpec *s, guint root)
{
    double h = s->size / 2, r = h / 8;
    guint obj = 0;
    for (guint k = 0; k < s->well_structs; k++) {
        char *name = g_strdup_printf("well_%u", k);
        guint w = scene_db_add_struct(g->db, name);
        g_free(name);
        guint ncol = share(k, s->well_attributes, s->well_structs);
        guint npoly = share(k, s->well_polygons, s->well_structs);
        for (guint j = 0; j < MAX(ncol, 1); j++, obj++) {
            if (ncol)
                add_color(g, w);
            double t = 2 * G_PI * obj / MAX(s->well_attributes, 1);
            Vec3 c = vec3(r * cos(t), h / 4 * uni(g, 0, 1), r * sin(t));
            for (guint i = 0; i < share(j, npoly, MAX(ncol, 1)); i++)
                add_poly(
                    g, w,
                    vec3_add(c, rnd_in(g, vec3(-1, -1, -1), vec3(1, 1, 1))),
                    h / 40);
        }
        add_el(g, root, scene_elem_execute(w));
    }
}

static void gen_flock(Gen *g, const ScenePphigsSpec *s)
{
    guint root = scene_db_add_struct(g->db, "flock");
    guint boid = scene_db_add_struct(g->db, "boid");
    scene_db_set_primitive(g->db, boid, TRUE);
    double h = s->size / 2;
    gen_well(g, s, root);
    guint total = s->boid_polygons + s->boid_colors;
    for (guint i = 0; i < total; i++) {
        /* exactly boid_colors colours, spread, the first element one */
        if (share(total - 1 - i, s->boid_colors, total))
            add_color(g, boid);
        else
            add_poly(g, boid, rnd_in(g, vec3(-1, -0.3, -1), vec3(1, 0.3, 1)),
                     0.6);
    }
    for (guint b = 0; b < s->boids; b++) {
        double t = 2 * G_PI * b / s->boids;
        double rad = uni(g, h / 3, h), y = uni(g, 0, h / 2);
        Mat4 m = mat4_mul(mat4_translate(rad * cos(t), y, rad * sin(t)),
                          mat4_rotate(vec3(0, 1, 0), -t));
        add_el(g, root, scene_elem_matrix(m, SCENE_MAT_REPLACE));
        add_el(g, root, scene_elem_execute(boid));
    }
    scene_db_post(g->db, root);
}

/* One figure of n structures: a chain `levels` deep (spine to
 * fingertip), the rest hung round-robin under chain members at depths
 * 1 .. levels-1, so the figure is exactly `levels` deep.  Structure k of
 * the whole database gets share(k) of the polygons. */
static void gen_figure(Gen *g, const ScenePphigsSpec *s, guint f, guint n,
                       guint *k)
{
    guint *ids = g_new(guint, n);
    guint *parent = g_new(guint, n);
    for (guint i = 0; i < n; i++) {
        char *name = g_strdup_printf("fig%u_part%u", f, i);
        ids[i] = scene_db_add_struct(g->db, name);
        g_free(name);
        guint chain = MIN(s->levels, n);
        parent[i] = i == 0 ? 0 : i < chain ? i - 1 : (i - chain) % (chain - 1);
    }
    double seg = s->size / 20;
    for (guint i = 0; i < n; i++) {
        Mat4 m = i == 0 ? mat4_translate(f * s->size / 2, 0, 0)
                        : mat4_mul(mat4_translate(uni(g, -seg, seg), seg, 0),
                                   mat4_rotate(vec3(0, 0, 1), uni(g, -1, 1)));
        add_el(g, ids[i],
               scene_elem_matrix(m, i == 0 ? SCENE_MAT_REPLACE
                                           : SCENE_MAT_CONCAT));
        add_color(g, ids[i]);
        guint np = share((*k)++, s->polygons, s->structures);
        for (guint p = 0; p < np; p++)
            add_poly(g, ids[i],
                     rnd_in(g, vec3(-seg / 4, 0, -seg / 4),
                            vec3(seg / 4, seg, seg / 4)),
                     seg / 8);
    }
    for (guint i = 1; i < n; i++)
        add_el(g, ids[parent[i]], scene_elem_execute(ids[i]));
    scene_db_post(g->db, ids[0]);
    g_free(parent);
    g_free(ids);
}

static void gen_humans(Gen *g, const ScenePphigsSpec *s)
{
    guint k = 0;
    for (guint f = 0; f < s->figures; f++)
        gen_figure(g, s, f, share(f, s->structures, s->figures), &k);
}

static gboolean check_spec(const ScenePphigsSpec *s, GError **err)
{
    if (!need(s->verts >= 3, "a polygon of fewer than 3 vertices", "verts >= 3",
              err))
        return FALSE;
    switch (s->kind) {
    case SCENE_PPHIGS_STATION:
    case SCENE_PPHIGS_LOBBY:
        return need(s->attributes >= 2 && s->attributes <= s->polygons + 1,
                    "an attribute count the polygons cannot carry",
                    "2 <= attributes <= polygons + 1", err);
    case SCENE_PPHIGS_FLOCK:
        return need(s->boid_colors >= 1 && s->well_structs >= 1,
                    "an impossible flock",
                    "boid_colors >= 1, well_structs >= 1", err);
    case SCENE_PPHIGS_HUMANS:
        return need(s->figures >= 1 && s->levels >= 2 &&
                        s->structures >= s->figures * s->levels,
                    "too few structures for the figures' depth",
                    "structures >= figures * levels, levels >= 2", err);
    default:
        return need(FALSE, "an unknown database kind", "one of four", err);
    }
}

/* An order-dependent quad centred at c with half-sides a along u, b along
 * v. */
static void add_odp(Gen *g, guint sid, Vec3 c, Vec3 u, Vec3 v, double a,
                    double b)
{
    Vec3 p[4] = {vec3_add(c, vec3_add(vec3_scale(u, -a), vec3_scale(v, -b))),
                 vec3_add(c, vec3_add(vec3_scale(u, a), vec3_scale(v, -b))),
                 vec3_add(c, vec3_add(vec3_scale(u, a), vec3_scale(v, b))),
                 vec3_add(c, vec3_add(vec3_scale(u, -a), vec3_scale(v, b)))};
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON2D, p, 4);
    e.tag = g->next_tag++;
    add_el(g, sid, e);
}

/* The panel and labels, a quarter of the way from the eye to the target
 * (and beyond the near plane), in the lower left of the view. */
static void gen_overlay(Gen *g, const ScenePphigsSpec *s, const SceneCamera *c)
{
    guint sid = scene_db_add_struct(g->db, "overlay");
    Vec3 f = vec3_sub(c->target, c->eye);
    double d = MAX(vec3_len(f) / 4, c->near * 1.5);
    double h = d * tan(c->fov_deg * G_PI / 360);
    f = vec3_norm(f);
    Vec3 r = vec3_norm(vec3_cross(f, c->up)), up = vec3_cross(r, f);
    Vec3 centre = vec3_add(vec3_add(c->eye, vec3_scale(f, d)),
                           vec3_add(vec3_scale(r, -h / 2), vec3_scale(up, -h / 2)));
    add_color(g, sid);
    add_odp(g, sid, centre, r, up, h * 0.4, h * 0.3);
    for (guint i = 0; i < s->overlays; i++) {
        add_color(g, sid);
        Vec3 at = vec3_add(centre, vec3_add(vec3_scale(r, uni(g, -0.45, 0.45) * h),
                                            vec3_scale(up, uni(g, -0.35, 0.35) * h)));
        add_odp(g, sid, at, r, up, h * uni(g, 0.05, 0.12), h * uni(g, 0.02, 0.05));
    }
    scene_db_post(g->db, sid);
}

SceneCamera scene_pphigs_fit_view(const SceneDb *db)
{
    SceneCamera c = scene_camera_default();
    guint n = scene_db_posted_count(db);
    if (n == 0)
        return c;
    SceneBox b = scene_db_struct_bbox(db, scene_db_posted_at(db, 0));
    for (guint i = 1; i < n; i++)
        b = scene_box_union(b,
                            scene_db_struct_bbox(db, scene_db_posted_at(db, i)));
    if (!scene_box_is_empty(b))
        scene_camera_fit(&c, b, 0.9);
    return c;
}

gboolean scene_pphigs_generate(const ScenePphigsSpec *spec, ScenePphigsDb *out,
                               GError **err)
{
    if (!check_spec(spec, err))
        return FALSE;
    Gen g = {scene_db_new(), {{0}}, spec->verts, 1};
    sim_rng_init(&g.rng, spec->seed, spec->kind);
    if (spec->kind == SCENE_PPHIGS_STATION)
        gen_station(&g, spec);
    else if (spec->kind == SCENE_PPHIGS_LOBBY)
        gen_lobby(&g, spec);
    else if (spec->kind == SCENE_PPHIGS_FLOCK)
        gen_flock(&g, spec);
    else
        gen_humans(&g, spec);
    out->db = g.db;
    out->camera = scene_camera_default();
    if (spec->kind == SCENE_PPHIGS_LOBBY) {
        double h = spec->size / 2;
        out->camera.eye = vec3(0, h / 6, -h);
        out->camera.target = vec3(0, h / 6, h);
        out->camera.fov_deg = spec->fov_deg;
        out->camera.near = spec->size / 1000;
        out->camera.far = spec->size * 4;
    } else {
        out->camera = scene_pphigs_fit_view(g.db);
    }
    if (spec->overlays)
        gen_overlay(&g, spec, &out->camera);
    return TRUE;
}

void scene_pphigs_db_clear(ScenePphigsDb *d)
{
    scene_db_free(d->db);
    d->db = NULL;
}

Scene *scene_pphigs_scene_new(const ScenePphigsSpec *spec, GError **err)
{
    ScenePphigsDb d;
    if (!scene_pphigs_generate(spec, &d, err))
        return NULL;
    Scene *s = scene_new(scene_pphigs_kind_name(spec->kind));
    guint id = scene_add_mesh(s, scene_db_flatten(d.db));
    scene_add_instance(s, id, mat4_identity(), scene_color(1, 1, 1), 0);
    s->camera = d.camera;
    s->two_sided = TRUE;
    scene_set_db(s, d.db);
    return s;
}

typedef struct {
    Mat4 vp;
    uint64_t off, all;
} Offscreen;

/* Corner k (0..7) of the box about sphere e (centre verts[0], radius
 * the distance to verts[1]). */
static Vec3 sphere_corner(const SceneElem *e, guint k)
{
    double r = vec3_len(vec3_sub(e->verts[1], e->verts[0]));
    return vec3_add(e->verts[0], vec3(k & 1 ? r : -r, k & 2 ? r : -r,
                                      k & 4 ? r : -r));
}

gboolean scene_pphigs_prim_offscreen(Mat4 m, const SceneElem *e)
{
    guint mask = e->kind == SCENE_EL_POLYGON2D ? 0x0f : 0x3f;
    gboolean sphere = e->kind == SCENE_EL_SPHERE && e->nverts >= 2;
    guint n = sphere ? 8 : e->nverts;
    for (guint v = 0; v < n && mask; v++) {
        Vec4 q = mat4_apply_point(m, sphere ? sphere_corner(e, v)
                                            : e->verts[v]);
        guint out = (q.x < -q.w) | (q.x > q.w) << 1 | (q.y < -q.w) << 2 |
                    (q.y > q.w) << 3 | (q.z < -q.w) << 4 | (q.z > q.w) << 5;
        mask &= out;
    }
    return mask != 0;
}

static void offscreen_fn(const ScenePrimInst *pi, void *ud)
{
    Offscreen *o = ud;
    o->all++;
    o->off += scene_pphigs_prim_offscreen(mat4_mul(o->vp, pi->matrix), pi->el);
}

double scene_pphigs_offscreen_share(const SceneDb *db, Mat4 vp)
{
    Offscreen o = {vp, 0, 0};
    scene_db_traverse(db, offscreen_fn, &o);
    return o.all ? (double)o.off / (double)o.all : 0.0;
}
