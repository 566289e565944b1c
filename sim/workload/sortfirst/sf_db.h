/* sf_db.h — the sort-first chunk database (seed 000 §3.2, §3.3.1, §4.1).
 *
 * Mueller (seed 000) keeps the structure hierarchy replicated on every
 * processor and migrates only primitives, grouped into chunks of at most
 * N primitives of one structure, each chunk with a 3-D bounding box
 * (§3.2, §3.3.1).  Chunks are formed when the database is loaded, by one
 * of the three strategies of §4.1:
 *
 *   unsorted  every N consecutive primitives of a structure;
 *   partially_sorted  "presort the primitives in the input file by
 *             performing an octree-based sort over each structure's
 *             primitives, then proceed as with the first strategy": the
 *             primitives in the depth-first order of an octree over
 *             their centroids (wl_sf_octree_order; the octree's rule and
 *             why in sf_db.c), then every N;
 *   sorted    a simple 3-D spatial subdivision of the structure's
 *             primitives: split at the median centroid along the longest
 *             axis of the centroids' box (split sizes kept multiples of
 *             N) until a part holds at most N primitives.
 *
 * Every structure's primitives are chunked, reachable or not (the
 * min-set: what is defined); a chunk of an unreachable structure has
 * no instance.  A chunk instance is one chunk under one max-set node of
 * its structure
 * (seed 000 Fig. 6): with the Bronco instanced three times each chunk
 * has three instances.  Mastership is fixed (§3.3.2.1): chunk c is
 * mastered by processor c mod P, which spreads the master set evenly
 * while the database is built.
 *
 * The database also flattens the posted network once (scene_db_flatten:
 * world-space polygons in traversal order, which are also the primitive
 * ids of the renders, so any subset renders the same pixels as the
 * whole), and keeps for every chunk instance the list of its polygons.
 * A structure whose primitives do not share one composite matrix (a
 * matrix element between primitives) is refused: its chunks would need
 * one box per matrix.
 *
 * Memory O(max-set polygons + chunks); building is O(max-set + Σ n log n)
 * over structures.
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_DB_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_DB_H

#include "sim/core/error.h"
#include "sim/scene/structdb.h"

typedef enum {
    WL_SF_CHUNK_SORTED,
    WL_SF_CHUNK_UNSORTED,
    WL_SF_CHUNK_PARTIAL
} WlSfChunking;

/* "sorted", "unsorted", "partially_sorted" */
extern const char *const wl_sf_chunking_names[];

/* The partial sort's octree: a cell holding more centroids than this is
 * split (the point-region octree's rule); a cell this deep is a leaf
 * whatever it holds (its side 2^-21 of the root's: coincident points). */
#define WL_SF_OCTREE_LEAF 1
#define WL_SF_OCTREE_MAX_DEPTH 21

typedef struct {
    guint sid;                 /* structure holding the primitives */
    guint prim_first, n_prims; /* range of WlSfDb.prims (element positions) */
    uint32_t polys;            /* polygons drawn for one instance */
    SceneBox box;              /* in the primitives' own coordinates */
    guint master;              /* fixed master processor */
    guint inst_first, n_inst;  /* range of WlSfDb.insts */
} WlSfChunk;

typedef struct {
    guint chunk;
    guint node;       /* max-set node (scene_db_maxset numbering) */
    guint poly_first; /* range of WlSfDb.inst_polys */
    Mat4 matrix;      /* object -> world of the chunk's primitives */
} WlSfInst;

typedef struct {
    guint procs, granularity;
    WlSfChunking chunking;
    GArray *chunks;     /* WlSfChunk */
    GArray *insts;      /* WlSfInst, grouped by chunk */
    GArray *inst_nodes; /* guint WlSfInst.node of each, packed for the
                         * per-frame sweeps (sf_trav.c) */
    GArray *prims;      /* guint element positions, grouped by chunk */
    GArray *inst_polys; /* uint32_t polygon indices of `flat` */
    SceneMesh *flat;    /* the posted network in world space (owned) */
    uint64_t min_prims; /* primitives stored once (min-set) */
    GArray *nodes;      /* SceneMaxNode: the max-set tree (pre-order) */
    guint n_structs;    /* structures of the database */
    int bv;             /* WlSfBvKind of the chunks' volumes (sf_bv.h);
                         * 0: the axis-aligned `box` alone */
    GArray *bvs;        /* WlSfBv per chunk; NULL for boxes */
    GArray *bv_verts;   /* Vec3: the polytopes' vertices (sf_bv.h) */
} WlSfDb;

/* Builds the chunk database of db's posted network for `procs` masters
 * with at most `granularity` primitives per chunk.  Returns a new
 * database (wl_sf_db_free) or NULL with *err set. */
WlSfDb *wl_sf_db_new(const SceneDb *db, guint procs, guint granularity,
                     WlSfChunking chunking, GError **err);
void wl_sf_db_free(WlSfDb *d);
/* Re-deals the fixed masters for `procs` processors (chunk c to c mod
 * procs, as wl_sf_db_new() deals them); the chunks do not depend on the
 * processor count, so this equals building the database again. */
void wl_sf_db_set_procs(WlSfDb *d, guint procs);
/* Rebuilds the chunk instances, the max-set tree and the flattened
 * network from db after edits that keep every structure's elements
 * (matrix and execute changes, posting); chunks are kept, so chunk ids
 * stay valid.  FALSE with *err (d unchanged but for its instances) on
 * a matrix between one structure's primitives.  O(max-set polygons). */
gboolean wl_sf_db_reinstance(WlSfDb *d, const SceneDb *db, GError **err);
/* Polygons the flattened network draws for one primitive element. */
uint32_t wl_sf_elem_polys(const SceneElem *e);
/* Appends the chunks of structure sid's primitives by d's strategy
 * (masters: chunk number mod P); adds them to min_prims. */
void wl_sf_db_chunk_struct(WlSfDb *d, const SceneDb *db, guint sid);
/* The partial sort: order[0..n) gets the indices of pts in the
 * depth-first order of the octree over them (sf_db.c).  O(n) memory,
 * O(n * WL_SF_OCTREE_MAX_DEPTH) time. */
void wl_sf_octree_order(const Vec3 *pts, guint n, guint *order);

static inline const WlSfChunk *wl_sf_chunk(const WlSfDb *d, guint c)
{
    return &g_array_index(d->chunks, WlSfChunk, c);
}
static inline const WlSfInst *wl_sf_inst(const WlSfDb *d, guint i)
{
    return &g_array_index(d->insts, WlSfInst, i);
}
/* WlSfInst.node of instance i, from the packed copy. */
static inline guint wl_sf_inst_node(const WlSfDb *d, guint i)
{
    return g_array_index(d->inst_nodes, guint, i);
}
static inline guint wl_sf_n_chunks(const WlSfDb *d)
{
    return d->chunks->len;
}
static inline guint wl_sf_n_insts(const WlSfDb *d)
{
    return d->insts->len;
}
/* The polygons of instance i (borrowed; wl_sf_chunk(...)->polys long). */
static inline const uint32_t *wl_sf_inst_polys(const WlSfDb *d, guint i)
{
    return &g_array_index(d->inst_polys, uint32_t,
                          wl_sf_inst(d, i)->poly_first);
}

#endif
