/* scene_cfg.c — scenes from a YAML `scene:` section.
 *
 * Implements scene_cfg.h: a small table of generators, each reading its
 * parameters with the typed cfg getters (sim/core/cfg.h) and calling the
 * generator's C API; then the common view / camera / path / background
 * keys.  O(size of the section) plus the generator's cost.
 */
#include "sim/scene/scene_cfg.h"

#include "sim/core/inputs.h"
#include "sim/scene/isosurface.h"
#include "sim/scene/march.h"
#include "sim/scene/nurbs.h"
#include "sim/scene/obj.h"
#include "sim/scene/ply.h"
#include "sim/scene/pn_triangles.h"
#include "sim/scene/pphigs_db.h"
#include "sim/scene/scene_limits.h"
#include "sim/scene/teapots.h"
#include "sim/scene/vehicle.h"

#include <string.h>

typedef Scene *(*GenFn)(const CfgNode *sec, GError **err);

/* ---- small readers ----------------------------------------------------- */

/* One element of an [x, y, z] list within [lo, hi]. */
static gboolean get_elem(const CfgNode *e, double lo, double hi, double *v,
                         GError **err)
{
    const char *s = cfg_scalar(e);
    char *end = NULL;
    *v = s ? g_ascii_strtod(s, &end) : 0;
    if (s && *s && !*end && isfinite(*v) && *v >= lo && *v <= hi)
        return TRUE;
    char *f = g_strdup_printf("'%s'", s ? s : "a non-scalar");
    char *x = g_strdup_printf("a number in [%g, %g]", lo, hi);
    cfg_error(err, e, f, x);
    g_free(f);
    g_free(x);
    return FALSE;
}

/* map[key] as [x, y, z], each in [lo, hi]; absent leaves *out. */
static gboolean get_triple(const CfgNode *map, const char *key, double lo,
                           double hi, Vec3 *out, GError **err)
{
    const CfgNode *n = cfg_get(map, key);
    if (!n)
        return TRUE;
    if (cfg_kind(n) != CFG_SEQ || cfg_seq_len(n) != 3) {
        cfg_error(err, n, "not a list of 3", "[x, y, z]");
        return FALSE;
    }
    double v[3];
    for (guint i = 0; i < 3; i++)
        if (!get_elem(cfg_seq_at(n, i), lo, hi, &v[i], err))
            return FALSE;
    *out = vec3(v[0], v[1], v[2]);
    return TRUE;
}

/* A position or direction: each coordinate within +-SCENE_COORD_MAX. */
static gboolean get_vec3(const CfgNode *map, const char *key, Vec3 *out,
                         GError **err)
{
    return get_triple(map, key, -SCENE_COORD_MAX, SCENE_COORD_MAX, out, err);
}

static gboolean get_color(const CfgNode *map, const char *key, SceneColor *out,
                          GError **err)
{
    Vec3 v = {out->r, out->g, out->b};
    if (!get_triple(map, key, SCENE_COLOR_MIN, SCENE_COLOR_MAX, &v, err))
        return FALSE;
    *out = scene_color((float)v.x, (float)v.y, (float)v.z);
    return TRUE;
}

static gboolean get_guint(const CfgNode *map, const char *key, guint64 min,
                          guint64 max, guint *out, GError **err)
{
    uint64_t v = *out;
    if (!cfg_get_count(map, key, FALSE, min, max, &v, err))
        return FALSE;
    *out = (guint)v;
    return TRUE;
}

/* "file:line:col" of map[key] (or of the map); free with g_free(). */
static char *where(const CfgNode *map, const char *key)
{
    const CfgNode *at = cfg_get(map, key);
    if (!at)
        at = map;
    return g_strdup_printf("%s:%d:%d", cfg_file(at), cfg_line(at), cfg_col(at));
}

static gboolean want_map(const CfgNode *n, const char *what, GError **err)
{
    if (cfg_kind(n) == CFG_MAP)
        return TRUE;
    cfg_error(err, n, "a non-map", what);
    return FALSE;
}

/* ---- generators -------------------------------------------------------- */

static const char *const layouts[] = {"spread", "depth", NULL};
static const char *const arrangements[] = {"1", "2", NULL};

static gboolean get_placements(const CfgNode *sec, SceneTeapotsParams *p,
                               GArray *out, GError **err)
{
    const CfgNode *n = cfg_get(sec, "placements");
    if (!n)
        return TRUE;
    if (cfg_kind(n) != CFG_SEQ || cfg_seq_len(n) == 0) {
        cfg_error(err, n, "not a list", "a list of {at, yaw, scale}");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(n); i++) {
        const CfgNode *e = cfg_seq_at(n, i);
        SceneTeapotPlacement pl = {{0, 0, 0}, 0, 1};
        if (!want_map(e, "a map {at, yaw, scale}", err) ||
            !get_vec3(e, "at", &pl.at, err) ||
            !cfg_get_double(e, "yaw", FALSE, -360, 360, &pl.yaw_deg, err) ||
            !cfg_get_double(e, "scale", FALSE, 1e-6, 1e6, &pl.scale, err))
            return FALSE;
        g_array_append_val(out, pl);
    }
    p->placements = (SceneTeapotPlacement *)out->data;
    p->n_placements = p->count = out->len;
    return TRUE;
}

static gboolean get_layout(const CfgNode *sec, SceneTeapotsParams *p,
                           GError **err)
{
    int layout = p->layout;
    if (cfg_get(sec, "arrangement")) {
        if (!cfg_get_enum(sec, "arrangement", TRUE, arrangements, &layout, err))
            return FALSE;
    } else if (!cfg_get_enum(sec, "layout", FALSE, layouts, &layout, err)) {
        return FALSE;
    }
    p->layout = (SceneTeapotLayout)layout;
    return TRUE;
}

static Scene *gen_teapots(const CfgNode *sec, GError **err)
{
    SceneTeapotsParams p = scene_teapots_defaults();
    uint64_t polys = p.polygons_per_teapot;
    const char *count_key = cfg_get(sec, "teapots") ? "teapots" : "count";
    GArray *pl = g_array_new(FALSE, FALSE, sizeof(SceneTeapotPlacement));
    Scene *s = NULL;
    if (get_guint(sec, count_key, 1, SCENE_TEAPOTS_MAX, &p.count, err) &&
        cfg_get_count(sec, "polygons_per_teapot", FALSE, 1, 1u << 26, &polys,
                      err) &&
        get_layout(sec, &p, err) &&
        cfg_get_double(sec, "spacing", FALSE, 0, 1e3, &p.spacing, err) &&
        cfg_get_double(sec, "shift", FALSE, -1e3, 1e3, &p.shift, err) &&
        cfg_get_double(sec, "yaw_step", FALSE, -360, 360, &p.yaw_step, err) &&
        cfg_get_double(sec, "yaw", FALSE, -360, 360, &p.yaw, err) &&
        get_guint(sec, "columns", 1, 4096, &p.columns, err) &&
        cfg_get_double(sec, "across", FALSE, 0, 1e3, &p.across, err) &&
        get_color(sec, "color", &p.color, err) &&
        cfg_get_bool(sec, "vary_color", FALSE, &p.vary_color, err) &&
        get_placements(sec, &p, pl, err)) {
        p.polygons_per_teapot = polys;
        char *what = where(sec, "polygons_per_teapot");
        s = scene_teapots_new(&p, what, err);
        g_free(what);
    }
    g_array_free(pl, TRUE);
    return s;
}

/* `instancing`: how many copies execute one vehicle tree (vehicle.h):
 * none (1), moderate (3, seed 000's Bronco), heavy (all copies) or a
 * count of 1 .. instances. */
static gboolean get_instancing(const CfgNode *sec, SceneVehicleParams *p,
                               GError **err)
{
    static const char *const words[] = {"none", "moderate", "heavy", NULL};
    static const guint of_word[] = {1, 3, 0};
    const CfgNode *n = cfg_get(sec, "instancing");
    const char *v = n ? cfg_scalar(n) : NULL;
    uint64_t k = 0;
    if (!n)
        return TRUE;
    for (guint i = 0; v && words[i]; i++)
        if (!strcmp(v, words[i])) {
            p->instancing = MIN(of_word[i], p->instances);
            return TRUE;
        }
    if (v && g_ascii_string_to_unsigned(v, 10, 1, p->instances, &k, NULL)) {
        p->instancing = (guint)k;
        return TRUE;
    }
    char *want = g_strdup_printf("none | moderate | heavy or a count of copies "
                                 "per vehicle tree, 1 .. instances (%u)",
                                 p->instances);
    cfg_error(err, n, v ? v : "a non-scalar", want);
    g_free(want);
    return FALSE;
}

static Scene *gen_vehicle(const CfgNode *sec, GError **err)
{
    SceneVehicleParams p = scene_vehicle_defaults();
    uint64_t tris = p.triangles;
    if (!get_guint(sec, "structures", 10, 1u << 24, &p.structures, err) ||
        !cfg_get_count(sec, "triangles", FALSE, 8, 1u << 28, &tris, err) ||
        !get_guint(sec, "instances", 1, 1024, &p.instances, err) ||
        !cfg_get_double(sec, "circle_radius", FALSE, 0, 1e6, &p.circle_radius,
                        err) ||
        !cfg_get_double(sec, "camera_radius", FALSE, 0, 1e6, &p.camera_radius,
                        err) ||
        !cfg_get_double(sec, "camera_height", FALSE, -1e6, 1e6,
                        &p.camera_height, err) ||
        !cfg_get_double(sec, "fov", FALSE, 1, 170, &p.fov_deg, err) ||
        !cfg_get_double(sec, "degrees_per_frame", FALSE, -360, 360,
                        &p.degrees_per_frame, err) ||
        !get_guint(sec, "frames", 1, 1u << 24, &p.frames, err) ||
        !get_instancing(sec, &p, err))
        return NULL;
    p.triangles = tris;
    char *what = where(sec, "triangles");
    Scene *s = scene_vehicle_new(&p, what, err);
    g_free(what);
    return s;
}

static const char *const fields[] = {"gyroid", "metaballs", NULL};

static Scene *gen_isosurface(const CfgNode *sec, GError **err)
{
    SceneIsoParams p = scene_iso_defaults();
    int field = p.field;
    uint64_t seed = p.seed;
    if (!cfg_get_enum(sec, "field", FALSE, fields, &field, err) ||
        !get_guint(sec, "grid", 2, SCENE_ISO_GRID_MAX, &p.grid, err) ||
        !cfg_get_double(sec, "iso", FALSE, -1e6, 1e6, &p.iso, err) ||
        !cfg_get_double(sec, "periods", FALSE, 0, 1e3, &p.periods, err) ||
        !get_guint(sec, "balls", 1, 4096, &p.balls, err) ||
        !cfg_get_count(sec, "seed", FALSE, 0, UINT64_MAX, &seed, err) ||
        !get_color(sec, "color", &p.color, err))
        return NULL;
    p.field = (SceneFieldKind)field;
    p.seed = seed;
    char *what = where(sec, "grid");
    gboolean ok = scene_iso_check(&p, what, err);
    g_free(what);
    return ok ? scene_iso_new(&p) : NULL;
}

static Scene *gen_nurbs(const CfgNode *sec, GError **err)
{
    SceneNurbsParams p = scene_nurbs_defaults();
    uint64_t seed = p.seed;
    if (!get_guint(sec, "patches_u", 1, 256, &p.patches_u, err) ||
        !get_guint(sec, "patches_v", 1, 256, &p.patches_v, err) ||
        !get_guint(sec, "tess", 1, 256, &p.tess, err) ||
        !get_guint(sec, "bumps", 0, 64, &p.bumps, err) ||
        !cfg_get_double(sec, "amplitude", FALSE, 0, 0.9, &p.amplitude, err) ||
        !cfg_get_count(sec, "seed", FALSE, 0, UINT64_MAX, &seed, err) ||
        !get_color(sec, "color", &p.color, err))
        return NULL;
    p.seed = seed;
    return scene_nurbs_new(&p);
}

static Scene *gen_march(const CfgNode *sec, GError **err)
{
    SceneMarchParams p = scene_march_defaults();
    uint64_t seed = p.iso.seed;
    int field = p.iso.field;
    if (!cfg_get_enum(sec, "field", FALSE, fields, &field, err) ||
        !cfg_get_double(sec, "periods", FALSE, 0, 1e3, &p.iso.periods, err) ||
        !cfg_get_double(sec, "fill", FALSE, 0.05, 1, &p.fill, err) ||
        !get_guint(sec, "grid", 2, 1024, &p.iso.grid, err) ||
        !get_guint(sec, "cell", 1, 1024, &p.cell, err) ||
        !cfg_get_double(sec, "iso", FALSE, -1e6, 1e6, &p.iso.iso, err) ||
        !get_guint(sec, "balls", 1, 4096, &p.iso.balls, err) ||
        !cfg_get_count(sec, "seed", FALSE, 0, UINT64_MAX, &seed, err) ||
        !get_color(sec, "color", &p.iso.color, err))
        return NULL;
    p.iso.seed = seed;
    p.iso.field = (SceneFieldKind)field;
    if (p.iso.grid % p.cell != 0) {
        cfg_error(err, cfg_get(sec, "cell") ? cfg_get(sec, "cell") : sec,
                  "a cell size that does not divide the grid",
                  "a cell size dividing grid (64 / 16 in igehy98)");
        return NULL;
    }
    return scene_march_new(&p);
}

static Scene *gen_large_polygons(const CfgNode *sec, GError **err)
{
    SceneBigPolyParams p = scene_bigpoly_defaults();
    uint64_t seed = p.seed;
    if (!get_guint(sec, "count", 1, 1u << 26, &p.count, err) ||
        !get_guint(sec, "max_sides", 3, 16, &p.max_sides, err) ||
        !cfg_get_double(sec, "huge_fraction", FALSE, 0, 1, &p.huge_fraction,
                        err) ||
        !cfg_get_double(sec, "min_size", FALSE, 0, 10, &p.min_size, err) ||
        !cfg_get_double(sec, "max_size", FALSE, 0, 10, &p.max_size, err) ||
        !cfg_get_count(sec, "seed", FALSE, 0, UINT64_MAX, &seed, err))
        return NULL;
    p.seed = seed;
    if (p.max_size < p.min_size) {
        cfg_error(err, cfg_get(sec, "max_size"), "max_size < min_size",
                  "max_size >= min_size");
        return NULL;
    }
    char *what = where(sec, "count");
    gboolean ok = scene_bigpoly_check(&p, what, err);
    g_free(what);
    return ok ? scene_bigpoly_new(&p) : NULL;
}

/* The PPHIGS databases (seed 001): the keys each kind reads, all
 * required (numbers from configs/scenes/, matching configs/pphigs/
 * databases.yaml), then `seed` (default 1) and `verts` (default 4). */
static const char *const pphigs_keys[SCENE_PPHIGS_NKINDS][8] = {
    {"polygons", "attributes", NULL},
    {"polygons", "attributes", NULL},
    {"boids", "boid_polygons", "boid_colors", "well_structs", "well_polygons",
     "well_attributes", NULL},
    {"figures", "structures", "polygons", "levels", NULL},
};

static guint *pphigs_field(ScenePphigsSpec *p, const char *key)
{
#define F(k)                                                                   \
    {                                                                          \
#k, G_STRUCT_OFFSET(ScenePphigsSpec, k)                                \
    }
    static const struct {
        const char *key;
        gsize off;
    } fields[] = {F(polygons),      F(attributes),      F(boids),
                  F(boid_polygons), F(boid_colors),     F(well_structs),
                  F(well_polygons), F(well_attributes), F(figures),
                  F(structures),    F(levels)};
#undef F
    for (guint i = 0; i < G_N_ELEMENTS(fields); i++)
        if (!strcmp(fields[i].key, key))
            return &G_STRUCT_MEMBER(guint, p, fields[i].off);
    g_assert_not_reached();
}

static Scene *gen_pphigs(const CfgNode *sec, ScenePphigsKind kind, GError **err)
{
    ScenePphigsSpec p = {.kind = kind, .seed = 1, .verts = 4, .fov_deg = 45};
    if (!cfg_get_count(sec, "seed", FALSE, 0, UINT64_MAX, &p.seed, err) ||
        !get_guint(sec, "verts", 3, 64, &p.verts, err) ||
        !cfg_get_double(sec, "size", TRUE, 1e-6, 1e9, &p.size, err) ||
        (kind == SCENE_PPHIGS_LOBBY &&
         !cfg_get_double(sec, "fov_deg", TRUE, 1, 170, &p.fov_deg, err)))
        return NULL;
    for (guint i = 0; pphigs_keys[kind][i]; i++) {
        const char *k = pphigs_keys[kind][i];
        uint64_t v = 0;
        if (!cfg_get_count(sec, k, TRUE, 0, 1u << 24, &v, err))
            return NULL;
        *pphigs_field(&p, k) = (guint)v;
    }
    GError *e = NULL;
    Scene *s = scene_pphigs_scene_new(&p, &e);
    if (!s) {
        char *at = where(sec, "generator");
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "%s: %s", at, e->message);
        g_free(at);
        g_error_free(e);
    }
    return s;
}

static Scene *gen_station(const CfgNode *sec, GError **err)
{
    return gen_pphigs(sec, SCENE_PPHIGS_STATION, err);
}
static Scene *gen_lobby(const CfgNode *sec, GError **err)
{
    return gen_pphigs(sec, SCENE_PPHIGS_LOBBY, err);
}
static Scene *gen_flock(const CfgNode *sec, GError **err)
{
    return gen_pphigs(sec, SCENE_PPHIGS_FLOCK, err);
}
static Scene *gen_humans(const CfgNode *sec, GError **err)
{
    return gen_pphigs(sec, SCENE_PPHIGS_HUMANS, err);
}

static const char *const gen_names[] = {
    "teapots",        "vehicle",           "isosurface",
    "large_polygons", "space_station",     "building_lobby",
    "flock_old_well", "two_human_figures", "nurbs",
    "march",          NULL};
static const GenFn gen_fns[] = {gen_teapots,        gen_vehicle, gen_isosurface,
                                gen_large_polygons, gen_station, gen_lobby,
                                gen_flock,          gen_humans,  gen_nurbs,
                                gen_march};

const char *const *scene_generator_names(void)
{
    return gen_names;
}

/* ---- files ------------------------------------------------------------- */

Scene *scene_from_file(const char *path, GError **err)
{
    SceneMesh *m = NULL;
    char *lower = g_ascii_strdown(path, -1);
    if (g_str_has_suffix(lower, ".obj"))
        m = scene_obj_load(path, err);
    else if (g_str_has_suffix(lower, ".ply"))
        m = scene_ply_load(path, err);
    else
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: found an unknown extension, expected .obj or .ply"
                    " (or a .yaml scene file)",
                    path);
    g_free(lower);
    if (m && m->start->len < 2) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s:0:0: found a model without faces, expected at least"
                    " one polygon (an OBJ 'f' line or a PLY face)",
                    path);
        scene_mesh_free(m);
        m = NULL;
    }
    if (!m)
        return NULL;
    Scene *s = scene_new(path);
    guint id = scene_add_mesh(s, m);
    scene_add_instance(s, id, mat4_identity(), scene_color(1, 1, 1), 0);
    SceneView v = scene_view_default();
    scene_apply_view(s, &v);
    return s;
}

static Scene *load_file(const CfgNode *sec, GError **err)
{
    const char *file = NULL;
    if (!cfg_get_str(sec, "file", TRUE, &file, err))
        return NULL;
    char *dir = g_path_get_dirname(cfg_file(sec));
    char *path = g_path_is_absolute(file) || !strcmp(dir, ".")
                     ? g_strdup(file)
                     : g_build_filename(dir, file, NULL);
    GError *e = NULL;
    Scene *s = scene_from_file(path, &e);
    if (e && e->domain == SIM_ERROR && e->code == SIM_ERROR_IO) {
        const CfgNode *at = cfg_get(sec, "file");
        g_prefix_error(&e, "%s:%d:%d: file: ", cfg_file(at), cfg_line(at),
                       cfg_col(at));
    }
    if (e)
        g_propagate_error(err, e);
    g_free(path);
    g_free(dir);
    return s;
}

/* ---- view, camera, path ------------------------------------------------ */

static const char *const projections[] = {"perspective", "orthographic", NULL};

static const char *const fits[] = {"sphere", "box", "vertices", NULL};

static gboolean apply_view(Scene *s, const CfgNode *n, GError **err)
{
    SceneView v = scene_view_default();
    int proj = v.proj, fit = 0;
    if (!want_map(n, "a map {azimuth, elevation, fov, fill ...}", err) ||
        !cfg_get_double(n, "azimuth", FALSE, -360, 360, &v.azimuth_deg, err) ||
        !cfg_get_double(n, "elevation", FALSE, -90, 90, &v.elevation_deg,
                        err) ||
        !cfg_get_double(n, "fov", FALSE, 1, 170, &v.fov_deg, err) ||
        !cfg_get_double(n, "fill", FALSE, 0.01, SCENE_FILL_MAX, &v.fill,
                        err) ||
        !cfg_get_double(n, "aspect", FALSE, 1e-3, 1e3, &v.aspect, err) ||
        !cfg_get_enum(n, "projection", FALSE, projections, &proj, err) ||
        !cfg_get_enum(n, "fit", FALSE, fits, &fit, err))
        return FALSE;
    v.proj = (SceneProjection)proj;
    v.fit_box = fit == 1;
    v.fit_vertices = fit == 2;
    scene_apply_view(s, &v);
    return TRUE;
}

static gboolean read_camera(const CfgNode *n, SceneCamera *c, GError **err)
{
    int proj = c->proj;
    if (!want_map(n, "a camera map {eye, target, up, fov ...}", err) ||
        !get_vec3(n, "eye", &c->eye, err) ||
        !get_vec3(n, "target", &c->target, err) ||
        !get_vec3(n, "up", &c->up, err) ||
        !cfg_get_double(n, "fov", FALSE, 1, 170, &c->fov_deg, err) ||
        !cfg_get_double(n, "height", FALSE, 1e-9, 1e12, &c->height, err) ||
        !cfg_get_double(n, "near", FALSE, 1e-9, 1e12, &c->near, err) ||
        !cfg_get_double(n, "far", FALSE, 1e-9, 1e12, &c->far, err) ||
        !cfg_get_double(n, "aspect", FALSE, 1e-3, 1e3, &c->aspect, err) ||
        !cfg_get_enum(n, "projection", FALSE, projections, &proj, err))
        return FALSE;
    c->proj = (SceneProjection)proj;
    Vec3 d = vec3_sub(c->target, c->eye);
    if (c->far <= c->near || vec3_len(d) == 0 ||
        vec3_len(vec3_cross(d, c->up)) == 0) {
        cfg_error(err, n,
                  "a degenerate camera (near >= far, eye = target "
                  "or up along the view direction)",
                  "a valid camera");
        return FALSE;
    }
    return TRUE;
}

static const char *const path_kinds[] = {"fixed", "orbit", "keyframes", NULL};
static const char *const interps[] = {"linear", "catmull_rom", NULL};

static SceneCameraPath *read_orbit(const CfgNode *n, const SceneCamera *c,
                                   guint frames, GError **err)
{
    Vec3 center = c->target, axis = vec3(0, 1, 0);
    double start = 0, step = 360.0 / frames;
    if (!get_vec3(n, "center", &center, err) ||
        !get_vec3(n, "axis", &axis, err) ||
        !cfg_get_double(n, "start", FALSE, -360, 360, &start, err) ||
        !cfg_get_double(n, "degrees_per_frame", FALSE, -360, 360, &step, err))
        return NULL;
    if (vec3_len(axis) == 0) {
        cfg_error(err, cfg_get(n, "axis"), "a zero axis", "a non-zero axis");
        return NULL;
    }
    return scene_path_new_orbit(c, center, axis, start, step, frames);
}

/* Reads one key into p; unset fields default to *prev (the previous
 * key, or the scene camera for the first); *last is the previous frame. */
static gboolean read_key(const CfgNode *k, SceneCameraPath *p,
                         SceneCamera *prev, double *last, GError **err)
{
    SceneCamera kc = *prev;
    double frame = 0;
    if (!want_map(k, "a key map", err) ||
        !cfg_get_double(k, "frame", TRUE, 0, 1e9, &frame, err) ||
        !read_camera(k, &kc, err))
        return FALSE;
    if (scene_path_n_keys(p) > 0 && frame <= *last) {
        cfg_error(err, cfg_get(k, "frame"),
                  "a frame not after the previous key's", "increasing frames");
        return FALSE;
    }
    scene_path_add_key(p, frame, &kc);
    *prev = kc;
    *last = frame;
    return TRUE;
}

static SceneCameraPath *read_keys(const CfgNode *n, const SceneCamera *c,
                                  GError **err)
{
    int interp = 0;
    const CfgNode *keys = cfg_get(n, "keys");
    if (!cfg_get_enum(n, "interp", FALSE, interps, &interp, err))
        return NULL;
    if (!keys || cfg_kind(keys) != CFG_SEQ || cfg_seq_len(keys) == 0) {
        cfg_error(err, keys ? keys : n, "no list of keys",
                  "keys: [{frame, eye, target ...}, ...]");
        return NULL;
    }
    SceneCameraPath *p = scene_path_new_keyframes((SceneInterp)interp);
    SceneCamera prev = *c;
    double last = 0;
    for (guint i = 0; i < cfg_seq_len(keys); i++)
        if (!read_key(cfg_seq_at(keys, i), p, &prev, &last, err)) {
            scene_path_free(p);
            return NULL;
        }
    return p;
}

static gboolean apply_path(Scene *s, const CfgNode *n, GError **err)
{
    int kind = 0;
    guint frames = s->path ? scene_path_n_frames(s->path) : 1;
    if (!want_map(n, "a path map {kind ...}", err) ||
        !cfg_get_enum(n, "kind", TRUE, path_kinds, &kind, err) ||
        !get_guint(n, "frames", 1, 1u << 24, &frames, err))
        return FALSE;
    SceneCameraPath *p = NULL;
    if (kind == SCENE_PATH_FIXED)
        p = scene_path_new_fixed(&s->camera, frames);
    else if (kind == SCENE_PATH_ORBIT)
        p = read_orbit(n, &s->camera, frames, err);
    else if ((p = read_keys(n, &s->camera, err)) && cfg_get(n, "frames") &&
             frames > scene_path_n_frames(p))
        scene_path_set_n_frames(p, frames);
    if (!p)
        return FALSE;
    scene_set_path(s, p);
    s->camera = scene_path_camera(p, 0);
    return TRUE;
}

/* A generator's own path (the vehicle's orbit) follows a camera set by
 * `view` or `camera`: frame 0 shows what the section asked for. */
static gboolean rebase_path(Scene *s, const CfgNode *at, GError **err)
{
    if (!s->path)
        return TRUE;
    if (scene_path_kind(s->path) == SCENE_PATH_KEYFRAMES) {
        cfg_error(err, at, "a camera for a keyframed scene",
                  "a path: section with the keys");
        return FALSE;
    }
    scene_path_set_base(s->path, &s->camera);
    return TRUE;
}

static const char *const pn_normals[] = {"linear", "quadratic", NULL};

/* pn_triangles: {level: L, normals: linear | quadratic} replaces every
 * mesh by its curved PN tessellation (sim/scene/pn_triangles.h). */
static gboolean apply_pn(Scene *s, const CfgNode *n, GError **err)
{
    ScenePnParams p = {.level = 1, .normals = SCENE_PN_LINEAR};
    int normals = p.normals;
    if (!want_map(n, "a map {level: L, normals: linear | quadratic}", err) ||
        !get_guint(n, "level", 0, 64, &p.level, err) ||
        !cfg_get_enum(n, "normals", FALSE, pn_normals, &normals, err))
        return FALSE;
    p.normals = (ScenePnNormals)normals;
    scene_pn_apply(s, &p);
    return TRUE;
}

static gboolean apply_common(Scene *s, const CfgNode *sec, GError **err)
{
    const CfgNode *n, *cam = NULL;
    if ((n = cfg_get(sec, "pn_triangles")) && !apply_pn(s, n, err))
        return FALSE;
    if ((n = cfg_get(sec, "view")) && !apply_view(s, n, err))
        return FALSE;
    if ((cam = cfg_get(sec, "camera")) && !read_camera(cam, &s->camera, err))
        return FALSE;
    if ((n = cfg_get(sec, "path")) && !apply_path(s, n, err))
        return FALSE;
    if (!n && (cam || (cam = cfg_get(sec, "view"))) &&
        !rebase_path(s, cam, err))
        return FALSE;
    return get_color(sec, "background", &s->background, err) &&
           cfg_get_bool(sec, "two_sided", FALSE, &s->two_sided, err);
}

Scene *scene_from_cfg(const CfgNode *sec, GError **err)
{
    int gen = 0;
    Scene *s;
    if (!sec || !want_map(sec, "a scene map {generator | file ...}", err))
        return NULL;
    if (cfg_get(sec, "file") && !cfg_get(sec, "generator"))
        s = load_file(sec, err);
    else if (cfg_get_enum(sec, "generator", TRUE, gen_names, &gen, err))
        s = gen_fns[gen](sec, err);
    else
        return NULL;
    if (s && (!apply_common(s, sec, err) || !cfg_check_unused(sec, err))) {
        scene_free(s);
        s = NULL;
    }
    return s;
}

/* ---- scene files ------------------------------------------------------- */

/* Top-level sections of a run config (sim/run/run.c) that a scene
 * file reader skips; a plain scene file has only `scene:`. */
static const char *const run_sections[] = {
    "schema_version", "machine", "workload", "run", "sweep", NULL};

static Scene *scene_from_yaml(const char *path, GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return NULL;
    sim_inputs_note_file("scene", path);
    Scene *s = NULL;
    const CfgNode *sec = NULL;
    if (cfg_kind(root) != CFG_MAP)
        cfg_error(err, root, "a non-map", "a map with a scene: section");
    else if (!(sec = cfg_get(root, "scene")))
        cfg_error(err, root, "no key 'scene'",
                  "a scene: section (docs/scenes.md)");
    if (sec && cfg_get(root, "schema_version"))
        for (guint i = 0; run_sections[i]; i++)
            if (cfg_get(root, run_sections[i]))
                cfg_mark_read(cfg_get(root, run_sections[i]));
    if (sec && (s = scene_from_cfg(sec, err)) && !cfg_check_unused(root, err)) {
        scene_free(s);
        s = NULL;
    }
    cfg_free(root);
    return s;
}

Scene *scene_load(const char *path, GError **err)
{
    char *lower = g_ascii_strdown(path, -1);
    gboolean yaml =
        g_str_has_suffix(lower, ".yaml") || g_str_has_suffix(lower, ".yml");
    g_free(lower);
    if (yaml)
        return scene_from_yaml(path, err);
    return scene_from_file(path, err);
}
