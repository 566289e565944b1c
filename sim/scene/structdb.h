/* structdb.h — the hierarchical structure database (PHIGS-like).
 *
 * A SceneDb holds numbered structures (ids 0, 1, 2 ... never reused while
 * the db lives); each is an ordered list of elements:
 *   primitives  triangle, polygon, triangle strip, 2-D order-dependent
 *               polygon (ODP; drawn in traversal order, seed 001 §4),
 *               line (2 vertices), sphere (centre and a point of its
 *               surface: the radius is their distance after the matrix);
 *   attributes  a colour per primitive type, as PHIGS has (seed 001
 *               §2.3.1: the state holds "the colors ... for each type of
 *               primitive"): fill colour (polygons, strips, ODPs), line
 *               colour, sphere colour; matrix in REPLACE or CONCATENATE
 *               mode;
 *   executes    of another structure (instancing).
 * Posted structures are the traversal roots, in posting order.  Edits are
 * modify (same kind only), append, insert and delete (seed 001 §3); an
 * execute that would close a cycle is rejected with a GError, so the
 * network (the min-set view, seed 000 §3.3) is always a DAG.
 *
 * Inherited state (PHIGS): a structure starts with the caller's colours and
 * composite matrix G and a local matrix L = I.  REPLACE sets L = M,
 * CONCATENATE sets L = L M; primitives use G L.  Nothing a child sets is
 * seen by its parent after the execute returns.
 *
 * Priorities of ODPs: the traversal keeps one counter.  Before an element,
 * counter += elem.delta, and an ODP's priority is the counter after that;
 * after a structure's last element, counter += end_delta.  Elements made
 * by the constructors below have delta 1 for ODPs and 0 otherwise and
 * structures end_delta 0, which numbers ODPs serially (1, 2, 3 ...).  A
 * distributed portion stores other deltas (seed 001 §4, Figure 4): the
 * pphigs workload keeps one SceneDb per graphics processor.
 *
 * Each element carries a caller tag (uint64) copied through edits and
 * reported by the traversal: it identifies a primitive across copies.
 *
 * Complexity: append O(1) amortised; insert/delete O(n) in the
 * structure's length; the cycle check O(structures + executes);
 * traversal O(size of the max-set); bounding boxes O(min-set) with a
 * per-structure cache invalidated by edits.
 */
#ifndef PGSIM_SCENE_STRUCTDB_H
#define PGSIM_SCENE_STRUCTDB_H

#include "sim/core/error.h"
#include "sim/scene/mesh.h"
#include <stdint.h>

typedef enum {
    SCENE_EL_TRIANGLE,
    SCENE_EL_POLYGON,
    SCENE_EL_TRISTRIP,
    SCENE_EL_POLYGON2D, /* order-dependent (ODP) */
    SCENE_EL_LINE,      /* a segment: verts[0], verts[1] */
    SCENE_EL_SPHERE,    /* centre verts[0], a surface point verts[1] */
    SCENE_EL_COLOR,     /* fill colour: polygons, strips, ODPs */
    SCENE_EL_MATRIX,
    SCENE_EL_EXECUTE,
    SCENE_EL_LINE_COLOR,   /* colour of lines */
    SCENE_EL_SPHERE_COLOR, /* colour of spheres */
    SCENE_EL_NKINDS
} SceneElemKind;

typedef enum { SCENE_MAT_REPLACE, SCENE_MAT_CONCAT } SceneMatMode;

typedef struct {
    SceneElemKind kind;
    uint64_t tag;      /* caller's identity, copied with the element */
    int64_t delta;     /* priority advance before this element (above) */
    guint nverts;      /* primitives: vertex count */
    Vec3 *verts;       /* primitives: owned by the db once added */
    Vec3 color;        /* SCENE_EL_COLOR: r, g, b */
    Mat4 matrix;       /* SCENE_EL_MATRIX */
    SceneMatMode mode; /* SCENE_EL_MATRIX */
    guint child;       /* SCENE_EL_EXECUTE: structure id */
} SceneElem;

typedef struct SceneDb SceneDb;

/* Element constructors: plain values; `verts` is borrowed (the db copies
 * it when the element is added).  Tags start at 0; set e.tag yourself. */
SceneElem scene_elem_prim(SceneElemKind kind, const Vec3 *verts, guint nverts);
SceneElem scene_elem_color(Vec3 rgb);
/* A colour attribute of kind SCENE_EL_COLOR, _LINE_COLOR or
 * _SPHERE_COLOR. */
SceneElem scene_elem_kind_color(SceneElemKind kind, Vec3 rgb);
/* The colour attribute kind that colours primitive kind k. */
SceneElemKind scene_elem_color_of(SceneElemKind k);
/* TRUE for the three colour kinds. */
gboolean scene_elem_is_color(SceneElemKind k);
SceneElem scene_elem_matrix(Mat4 m, SceneMatMode mode);
SceneElem scene_elem_execute(guint child);
gboolean scene_elem_is_prim(SceneElemKind k);
gboolean scene_elem_is_attr(SceneElemKind k);
const char *scene_elem_kind_name(SceneElemKind k);

/* Returns a new empty database; free with scene_db_free(). */
SceneDb *scene_db_new(void);
void scene_db_free(SceneDb *db);
/* Deep copy (elements, posting, deltas, primitive-structure flags). */
SceneDb *scene_db_copy(const SceneDb *db);

/* Adds an empty structure; returns its id.  `name` is copied. */
guint scene_db_add_struct(SceneDb *db, const char *name);
guint scene_db_struct_count(const SceneDb *db);
const char *scene_db_struct_name(const SceneDb *db, guint sid);
/* Looks a structure up by name; FALSE if absent. */
gboolean scene_db_find(const SceneDb *db, const char *name, guint *sid);
guint scene_db_len(const SceneDb *db, guint sid);
/* Borrowed; valid until the next edit of that structure. */
const SceneElem *scene_db_elem(const SceneDb *db, guint sid, guint pos);
int64_t scene_db_end_delta(const SceneDb *db, guint sid);
void scene_db_set_end_delta(SceneDb *db, guint sid, int64_t d);
void scene_db_set_delta(SceneDb *db, guint sid, guint pos, int64_t d);
/* Sets element (sid, pos)'s caller tag (an identity, not an edit). */
void scene_db_set_tag(SceneDb *db, guint sid, guint pos, uint64_t tag);
/* User designation of primitive structures (seed 001 §2.3.3). */
void scene_db_set_primitive(SceneDb *db, guint sid, gboolean on);
gboolean scene_db_is_primitive(const SceneDb *db, guint sid);

/* Edits.  pos must be in range (pos <= len for insert).  An execute of an
 * unknown structure or one closing a cycle fails with SIM_ERROR_INPUT
 * ("found execute of 'b' in 'a' closing the cycle a -> b -> a, expected
 * an acyclic structure network").  modify keeps the element's kind. */
gboolean scene_db_append(SceneDb *db, guint sid, const SceneElem *e,
                         GError **err);
gboolean scene_db_insert(SceneDb *db, guint sid, guint pos, const SceneElem *e,
                         GError **err);
gboolean scene_db_modify(SceneDb *db, guint sid, guint pos, const SceneElem *e,
                         GError **err);
void scene_db_delete(SceneDb *db, guint sid, guint pos);

/* Posting: roots of the traversal, in posting order; posting twice is a
 * no-op, unposting a structure that is not posted returns FALSE. */
void scene_db_post(SceneDb *db, guint sid);
gboolean scene_db_unpost(SceneDb *db, guint sid);
gboolean scene_db_is_posted(const SceneDb *db, guint sid);
guint scene_db_posted_count(const SceneDb *db);
guint scene_db_posted_at(const SceneDb *db, guint i);

/* Traversal.  One call per primitive instance with the state it inherits;
 * `path` is the execute chain (structure ids, root first).  Borrowed. */
typedef struct {
    guint sid;           /* structure holding the primitive */
    guint pos;           /* its position there */
    const SceneElem *el; /* the primitive */
    Mat4 matrix;         /* composite G L */
    Vec3 color;          /* inherited colour of the primitive's type
                            (default 1, 1, 1) */
    int64_t priority;    /* ODP priority (meaningful for ODPs) */
    guint depth;         /* 1 for a posted structure's own elements */
    guint instance;      /* max-set node (scene_db_maxset numbering) */
} ScenePrimInst;

typedef void (*ScenePrimFn)(const ScenePrimInst *pi, void *ud);
/* Traverses every posted structure in posting order. */
void scene_db_traverse(const SceneDb *db, ScenePrimFn fn, void *ud);
/* Traverses one structure as a root with the given inherited state
 * (`color` for every primitive type); *priority is the counter,
 * updated. */
void scene_db_traverse_from(const SceneDb *db, guint sid, Mat4 g, Vec3 color,
                            int64_t *priority, ScenePrimFn fn, void *ud);

/* The posted network as one world-space mesh, in traversal order: each
 * triangle, polygon and ODP becomes a polygon, each strip of n vertices
 * n - 2 triangles (alternate ones reversed, so the strip keeps one
 * winding); colour = inherited colour, tag = structure id.  A new mesh,
 * free with scene_mesh_free().  O(max-set). */
SceneMesh *scene_db_flatten(const SceneDb *db);

/* Max-set view (seed 000 §3.4): the instance tree, one node per structure
 * instance reached from the posted roots, in traversal (pre-)order. */
typedef struct {
    guint sid;
    gint parent; /* node index, -1 for a posted root */
    guint depth; /* 1 for roots */
    Mat4 matrix; /* composite matrix at the instance's entry */
} SceneMaxNode;
/* Returns a new GArray of SceneMaxNode; free with g_array_unref(). */
GArray *scene_db_maxset(const SceneDb *db);

/* Min-set view (seed 000 §3.3): the DAG.  Distinct children of a
 * structure in first-execute order (new GArray of guint), and the
 * number of executes of `child` in `sid`. */
GArray *scene_db_children(const SceneDb *db, guint sid);
guint scene_db_execute_count(const SceneDb *db, guint sid, guint child);
/* The network's shape, found without expanding it: roots are the
 * posted structures and every structure nothing executes (an edit may
 * post any of them); counts are doubles, since shared executes multiply
 * (each of 40 levels executing the next twice makes 2^40 instances).
 * Iterative (Kahn's topological order), O(structures + executes). */
typedef struct {
    guint depth;       /* levels of the longest execute chain (1: none) */
    guint deepest;     /* the structure at its end */
    double instances;  /* max-set structure instances */
    double elements;   /* max-set element instances */
} SceneDbShape;
void scene_db_shape(const SceneDb *db, SceneDbShape *out);
/* Execute chains a database may hold (scene_db_load refuses deeper
 * ones): the traversals recurse once per level. */
#define SCENE_DB_DEPTH_MAX 256
/* Levels of nesting below and including sid (a leaf structure has 1). */
guint scene_db_height(const SceneDb *db, guint sid);

/* Bounding boxes in the structure's own coordinates (children through
 * their execute-time matrices, conservatively by box corners). */
SceneBox scene_db_struct_bbox(const SceneDb *db, guint sid);
/* Boxes of consecutive chunks of up to n primitives (seed 000 §3.3.1),
 * each in the structure's coordinates; new GArray of SceneBox. */
GArray *scene_db_chunk_bboxes(const SceneDb *db, guint sid, guint n);

/* Statistics of the posted network, counted the way seed 001's table
 * counts them: primitives and attributes per instance (max-set),
 * structures reachable from posted roots (min-set), depth in levels. */
typedef struct {
    guint structures;        /* reachable, min-set */
    guint depth;             /* levels (1: no executes) */
    uint64_t primitives;     /* max-set primitive instances */
    uint64_t attributes;     /* max-set attribute instances */
    uint64_t executes;       /* max-set execute instances */
    uint64_t min_primitives; /* primitives stored (min-set) */
    uint64_t instances;      /* max-set structure instances */
} SceneDbStats;
void scene_db_stats(const SceneDb *db, SceneDbStats *st);

#endif
