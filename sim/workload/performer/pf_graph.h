/* pf_graph.h — an IRIS Performer-style scene graph (Rohlf and Helman,
 * SIGGRAPH '94; seed 002, slides "libpr" and "libpf").
 *
 * Nodes live in one array and name their children by index.  Kinds:
 * group; static transform (pfSCS) and dynamic transform (pfDCS), each
 * with a matrix applied to its children; level of detail (pfLOD: child i
 * is drawn when range[i] <= distance * stress < range[i + 1]); switch
 * (one child, all or none); sequence (pfSequence: a precomputed
 * animation, child (frame / seq_frames) mod n is drawn, each child shown
 * seq_frames frames); partition (pfPartition: a group whose children
 * are indexed in a uniform grid of cells over x and z, so that ISECT's
 * vertical segment visits only the children of the cell it crosses;
 * CULL and DRAW treat it as a group); billboard (its geosets are turned about +y
 * to face the eye); geode (geosets).  A geoset is a homogeneous set of
 * triangles (real vertices) with one geostate (texture, material and a
 * mode word: the pfGeoState attributes that lazy state management
 * compares).  Every node has a bounding sphere in its parent's
 * coordinates (its own transform applied) and a traversal mask per
 * traversal (CULL, DRAW, ISECT): a traversal skips a node whose mask
 * does not meet its own.
 *
 * pfFlatten: wl_pf_flatten() applies every static transform to the
 * geometry below it (copying geosets shared with other paths) and turns
 * the SCS into a group, so DRAW no longer pushes, multiplies and pops
 * its matrix; it returns the number of SCS nodes removed.
 *
 * Complexity: bounds O(nodes + vertices); flatten O(nodes + vertices
 * below static transforms).
 */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_GRAPH_H
#define PGSIM_WORKLOAD_PERFORMER_PF_GRAPH_H

#include "sim/scene/vec.h"
#include <glib.h>
#include <stdint.h>

typedef enum {
    WL_PF_GROUP,
    WL_PF_SCS,
    WL_PF_DCS,
    WL_PF_LOD,
    WL_PF_SWITCH,
    WL_PF_BILLBOARD,
    WL_PF_GEODE,
    WL_PF_SEQUENCE,
    WL_PF_PARTITION,
    WL_PF_NKINDS
} WlPfKind;

enum { WL_PF_MASK_CULL = 1, WL_PF_MASK_DRAW = 2, WL_PF_MASK_ISECT = 4 };
enum { WL_PF_SWITCH_ALL = -1, WL_PF_SWITCH_NONE = -2 };
/* Traversal callbacks a node carries (pre- and post-, each traversal) */
enum { WL_PF_CB_CULL = 1, WL_PF_CB_DRAW = 2 };

typedef struct {
    guint texture, material, modes; /* the attributes DRAW compares */
} WlPfGeoState;

typedef struct {
    GArray *verts; /* Vec3, three per triangle */
    guint gstate;  /* index into WlPfGraph.gstates */
    Vec3 center;   /* bounding sphere, geoset coordinates */
    double radius;
} WlPfGeoSet;

typedef struct {
    WlPfKind kind;
    guint32 mask;       /* WL_PF_MASK_* bits this node is in */
    Mat4 xf;            /* SCS / DCS */
    GArray *children;   /* guint node indices */
    GArray *geosets;    /* guint geoset indices (geode, billboard) */
    GArray *ranges;     /* double, LOD: n_children + 1 ranges */
    int which;          /* switch: child index or WL_PF_SWITCH_* */
    Vec3 center;        /* bounding sphere in parent coordinates */
    double radius;      /* < 0: empty */
    gboolean flattened; /* a group that was an SCS before pfFlatten */
    guint32 callbacks;  /* WL_PF_CB_* bits (0: none) */
    guint seq_frames;   /* sequence: frames each child shows (0: 1) */
    /* partition: grid x grid cells of side `cell` from (x0, z0), each a
     * GArray of the child positions whose sphere's square meets it */
    GPtrArray *cells;
    guint grid;
    double x0, z0, cell;
} WlPfNode;

typedef struct {
    GArray *nodes;      /* WlPfNode */
    GPtrArray *geosets; /* WlPfGeoSet *, owned */
    GArray *gstates;    /* WlPfGeoState */
    guint root;
} WlPfGraph;

/* Returns a new graph holding one empty group (the root); free with
 * wl_pf_graph_free(). */
WlPfGraph *wl_pf_graph_new(void);
void wl_pf_graph_free(WlPfGraph *g);
/* Adds a node of `kind` under `parent` (all masks set, identity matrix,
 * switch ALL); returns its index. */
guint wl_pf_add_node(WlPfGraph *g, guint parent, WlPfKind kind);
/* Adds a geostate; returns its index. */
guint wl_pf_add_gstate(WlPfGraph *g, WlPfGeoState gs);
/* Adds a geoset of n triangles (tris: 3 n vertices, copied) to a geode
 * or billboard; returns its index. */
guint wl_pf_add_geoset(WlPfGraph *g, guint node, const Vec3 *tris, guint n,
                       guint gstate);
static inline WlPfNode *wl_pf_node(const WlPfGraph *g, guint i)
{
    return &g_array_index(g->nodes, WlPfNode, i);
}
static inline WlPfGeoSet *wl_pf_geoset(const WlPfGraph *g, guint i)
{
    return g_ptr_array_index(g->geosets, i);
}
static inline guint wl_pf_geoset_tris(const WlPfGeoSet *gs)
{
    return gs->verts->len / 3;
}
static inline guint wl_pf_child(const WlPfNode *n, guint i)
{
    return g_array_index(n->children, guint, i);
}

/* Recomputes the bounding sphere of `node` and everything below it. */
void wl_pf_update_bounds(WlPfGraph *g, guint node);
/* Recomputes node's sphere from its geosets and its children's current
 * spheres (no recursion): after a child moved. */
void wl_pf_update_bounds_shallow(WlPfGraph *g, guint node);
/* The sphere of a transformed by m (centre moved, radius scaled by the
 * largest axis scale of m). */
void wl_pf_sphere_xform(Mat4 m, Vec3 c, double r, Vec3 *oc, double *or_);
/* pfFlatten: returns the number of static transforms removed. */
guint wl_pf_flatten(WlPfGraph *g);
/* pfPartition: indexes `node`'s children (current spheres) in a grid x
 * grid uniform grid over their extent in x and z. */
void wl_pf_partition_build(WlPfGraph *g, guint node, guint grid);
/* Counts nodes of a kind (all nodes, reachable or not). */
guint wl_pf_count_kind(const WlPfGraph *g, WlPfKind kind);

#endif
