/* pphigs_db.h — generators of the four PPHIGS test databases of seed 001
 * (Ellsworth, Good, Tebbs 1990, §6 and its table): space station,
 * building lobby, flock of boids about the Old Well, two articulated
 * human figures.
 *
 * The originals are not available; each generator builds a structure
 * network with the published shape (structures, hierarchy depth,
 * polygons per structure, polygon/attribute ratio, the lobby's off-screen
 * share) from parameters that live in YAML (configs/pphigs/databases.yaml;
 * the published statistics are in configs/papers/ellsworth90/published.yaml and a
 * test compares the two).  Geometry is synthetic but spatially coherent
 * in list order, as the paper assumes (§2.2).  Deterministic for a seed.
 */
#ifndef PGSIM_SCENE_PPHIGS_DB_H
#define PGSIM_SCENE_PPHIGS_DB_H

#include "sim/scene/scene.h"

typedef enum {
    SCENE_PPHIGS_STATION,
    SCENE_PPHIGS_LOBBY,
    SCENE_PPHIGS_FLOCK,
    SCENE_PPHIGS_HUMANS,
    SCENE_PPHIGS_NKINDS
} ScenePphigsKind;

/* Generator parameters; which fields a kind reads is said per field. */
typedef struct {
    ScenePphigsKind kind;
    uint64_t seed;
    guint polygons;        /* station, lobby: polygons; humans: total */
    guint attributes;      /* station, lobby: attribute elements */
    guint verts;           /* vertices per polygon (all kinds) */
    double size;           /* extent of the model (world units) */
    double fov_deg;        /* lobby: the standard view's vertical fov */
    guint boids;           /* flock: boid instances */
    guint boid_polygons;   /* flock: polygons in the boid structure */
    guint boid_colors;     /* flock: colours in the boid structure */
    guint well_structs;    /* flock: structures of the Old Well */
    guint well_polygons;   /* flock: polygons of the Old Well, in total */
    guint well_attributes; /* flock: colours of the Old Well, in total */
    guint figures;         /* humans: figures */
    guint structures;      /* humans: structures over all figures */
    guint levels;          /* humans: hierarchy depth (levels) */
    guint overlays;        /* any kind: 2-D labels over a panel, 0: none */
} ScenePphigsSpec;

typedef struct {
    SceneDb *db;        /* owned */
    SceneCamera camera; /* the database's standard view */
} ScenePphigsDb;

/* "space_station", "building_lobby", "flock_old_well",
 * "two_human_figures"; the row names of seed 001's table. */
const char *scene_pphigs_kind_name(ScenePphigsKind k);
gboolean scene_pphigs_kind_parse(const char *s, ScenePphigsKind *out);

/* Builds the database; FALSE with *err (SIM_ERROR_INPUT) when the spec
 * cannot be met (e.g. more attributes than polygons allow).  With
 * overlays > 0 a last posted structure "overlay" holds order-dependent
 * primitives (seed 001 §4): a panel, then `overlays` labels, each after
 * its colour, on a plane between the eye and the model; labels overlap
 * the panel and each other, so their order is visible. */
gboolean scene_pphigs_generate(const ScenePphigsSpec *spec, ScenePphigsDb *out,
                               GError **err);
void scene_pphigs_db_clear(ScenePphigsDb *d);
/* The standard view of a database whose generator has no view of its
 * own (and of a user's structure database file): the default camera
 * fitted to the posted structures' bounds (the default camera when
 * they hold no primitive). */
SceneCamera scene_pphigs_fit_view(const SceneDb *db);

/* The database as a renderable scene named after its kind: the posted
 * network flattened into one mesh (scene_db_flatten()), the standard
 * view as camera, two-sided (the generators' polygons face every way),
 * and s->db holding the database.  NULL with *err as above. */
Scene *scene_pphigs_scene_new(const ScenePphigsSpec *spec, GError **err);

/* The in-plane axes the generators draw a polygon of unit normal n on:
 * u = n x a normalised, a the x axis unless |n.x| >= 0.9 (then the y
 * axis, so that a is never near n), and v = n x u. */
void scene_pphigs_plane_basis(Vec3 n, Vec3 *u, Vec3 *v);

/* TRUE when the primitive lies wholly outside one clip plane of `mvp`
 * (-w <= x, y, z <= w): trivially rejected, off-screen (a sphere: the
 * box about it).  An
 * order-dependent (2-D) primitive is tested against x and y only: it is
 * drawn by priority, whatever its depth. */
gboolean scene_pphigs_prim_offscreen(Mat4 mvp, const SceneElem *e);

/* Share of the max-set polygons that lie wholly outside the view
 * frustum of `vp` (projection * view). */
double scene_pphigs_offscreen_share(const SceneDb *db, Mat4 vp);

#endif
