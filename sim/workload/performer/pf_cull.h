/* pf_cull.h — the CULL, DRAW and ISECT traversals of the Performer
 * scene graph (seed 002, slides "libpf": Traversals, Traversal Control,
 * Performance Optimizations; "libpr": pfGeoState, pfDispList).
 *
 * CULL walks the graph from the root with the composite matrix, skips
 * nodes whose mask lacks WL_PF_MASK_CULL, rejects a node whose world
 * bounding sphere is outside one of the six view-frustum planes (when
 * culling is on), picks one LOD child by eye distance times stress,
 * follows a switch's selection and a sequence's child of the view's
 * frame (only that child is visited and drawn), and appends to a display list: PUSH and
 * POP around each transform and each billboard geoset (the matrix DRAW
 * loads) and GEOSET items; at a group that pfFlatten made of an SCS it
 * counts the PUSH and POP it no longer emits.  It counts its own work and, for
 * a rejected node, the triangles the same selection would have drawn below it.
 *
 * DRAW replays a display list: matrix operations (one per PUSH or POP),
 * geosets, triangles, and pfGeoState changes done lazily (only the
 * attributes that differ from the current state are sent) beside the
 * count an eager push/pop of every attribute would send.
 *
 * Traversal callbacks (slides "libpf": pre- and post-traversal callbacks
 * per traversal type): a node CULL visits and keeps with WL_PF_CB_CULL
 * runs two CULL callbacks; one with WL_PF_CB_DRAW gets a CALLBACK item
 * before and after its contents in the display list, which DRAW runs.
 *
 * ISECT intersects a vertical segment with the graph (masks and
 * bounding spheres prune, then triangles are tested): terrain following.
 * Each traversal is O(nodes visited + triangles tested).
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_CULL_H
#define PGSIM_WORKLOAD_PERFORMER_PF_CULL_H

#include "sim/scene/camera.h"
#include "sim/workload/performer/pf_graph.h"

typedef struct {
    Vec3 eye;
    double planes[6][4]; /* world space, inside: n . p + d >= 0 */
    double stress;       /* >= 1: LOD distances are multiplied by it */
    gboolean cull;       /* view-frustum culling on */
    guint frame;         /* the frame (pfSequence's clock) */
} WlPfView;

enum { WL_PF_DL_PUSH, WL_PF_DL_POP, WL_PF_DL_GEOSET, WL_PF_DL_CALLBACK };
typedef struct {
    guint op;     /* WL_PF_DL_* */
    guint geoset; /* GEOSET items */
} WlPfDlItem;

typedef struct {
    uint64_t nodes_visited, sphere_tests, nodes_culled, lods, billboards;
    uint64_t tris_culled;  /* below culled nodes, by the same selection */
    uint64_t lod_sum;      /* sum of chosen LOD child indices */
    uint64_t matrix_saved; /* PUSH + POP not emitted: flattened SCS */
    uint64_t callbacks;    /* CULL callbacks run (pre + post) */
} WlPfCullStats;

typedef struct {
    uint64_t geosets, tris, matrix_ops;
    uint64_t state_changes, state_naive; /* lazy, eager */
    uint64_t vertices; /* sent (strips: pf_stages.h); 0: 3 per triangle */
    uint64_t callbacks; /* DRAW callbacks run (CALLBACK items) */
} WlPfDrawStats;

typedef struct {
    uint64_t nodes_tested, tris_tested;
    gboolean hit;
    double height; /* highest hit point's y */
} WlPfIsectStats;

/* The frustum of camera c (planes from its view-projection matrix). */
WlPfView wl_pf_view(const SceneCamera *c, double stress, gboolean cull);
/* Appends the frame's display list to dl (WlPfDlItem); adds to *st. */
void wl_pf_cull(const WlPfGraph *g, const WlPfView *v, GArray *dl,
                WlPfCullStats *st);
/* Replays dl; adds to *st. */
void wl_pf_draw(const WlPfGraph *g, const GArray *dl, WlPfDrawStats *st);
/* Intersects the segment x = x, z = z, y in [y0, y1] with the graph. */
void wl_pf_isect(const WlPfGraph *g, double x, double z, double y0, double y1,
                 WlPfIsectStats *st);

#endif
