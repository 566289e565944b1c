/* pn_memory.h — what storing pre-tessellated PN levels of detail costs
 * in memory against sending the base mesh and tessellating on the fly
 * (seed 002, slides "Hardware Performance": "models for LOD 0-4 would
 * require 70 times the amount of memory").
 *
 * The counting rule (docs/workloads.md, "PN triangles", "LOD memory"):
 * a model is stored as vertices (vertex_bytes each: position + normal
 * ...) and, for the indexed layouts, three indices per triangle
 * (index_bytes each).  Level L turns each input triangle into (L + 1)^2
 * triangles (pn_triangles.h).  Three layouts:
 *   LIST     independent triangles (Performer's geosets): 3 vertices per
 *            triangle, no indices; level L stores 3 T (L + 1)^2 vertices;
 *   GRIDS    each input triangle's own grid of (L + 2)(L + 3) / 2
 *            points (what scene_pn_tessellate() builds) plus the indices
 *            of its (L + 1)^2 triangles;
 *   INDEXED  one shared vertex per distinct point: V + E L + T L (L - 1)
 *            / 2 vertices (V vertices, E distinct edges, T triangles of
 *            the fan-triangulated mesh, counted by index) plus indices.
 * The LOD store holds levels lo..hi; the PN store holds the base mesh
 * (level 0 in the same layout) plus control_bytes per triangle when the
 * patches are precomputed (0: the control net comes from P and N on the
 * fly, as the paper's hardware does).  The ratio is LOD store / PN store.
 * For a closed mesh LIST and INDEXED give sum (L + 1)^2 (55 for 0..4),
 * GRIDS without indices sum (L + 2)(L + 3) / 6 (18.3 for 0..4).
 * O(polygons) (a hash of the edges for INDEXED).
 */
#ifndef PGSIM_SCENE_PN_MEMORY_H
#define PGSIM_SCENE_PN_MEMORY_H

#include "sim/scene/mesh.h"

typedef enum {
    SCENE_PN_MEM_LIST,
    SCENE_PN_MEM_GRIDS,
    SCENE_PN_MEM_INDEXED
} ScenePnMemLayout;

typedef struct {
    ScenePnMemLayout layout;
    uint64_t vertex_bytes;  /* per stored vertex */
    uint64_t index_bytes;   /* per index (GRIDS, INDEXED) */
    uint64_t control_bytes; /* per input triangle in the PN store */
    guint lo, hi;           /* the stored levels lo..hi */
} ScenePnMemRule;

/* Vertices and bytes of the level-L model of m under rule r's layout. */
uint64_t scene_pn_level_vertices(const SceneMesh *m, guint level,
                                 ScenePnMemLayout layout);
uint64_t scene_pn_level_bytes(const SceneMesh *m, guint level,
                              const ScenePnMemRule *r);
/* The LOD store (levels r->lo..r->hi) and the PN store, in bytes. */
uint64_t scene_pn_lod_store_bytes(const SceneMesh *m, const ScenePnMemRule *r);
uint64_t scene_pn_base_store_bytes(const SceneMesh *m,
                                   const ScenePnMemRule *r);
/* LOD store / PN store: the slides' "70 times the memory" under r. */
double scene_pn_lod_memory_ratio(const SceneMesh *m, const ScenePnMemRule *r);
/* The layouts' names in enum order ("list", "grids", "indexed"), NULL
 * terminated, for cfg_get_enum(). */
extern const char *const scene_pn_mem_layouts[];

#endif
