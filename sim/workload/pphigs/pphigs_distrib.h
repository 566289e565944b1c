/* pphigs_distrib.h — distributing a hierarchical display list over graphics
 * processors by primitive (seed 001, Ellsworth, Good, Tebbs 1990).
 *
 * The host keeps the global display list (a SceneDb copy whose element
 * tags are replaced by unique element ids); each GP holds its portion, a
 * SceneDb with the same structure ids whose structures are subsequences
 * (in host order) of the host's, with ODP priority deltas (§4).
 *
 *   SIMPLE  (§2.2) every attribute and execute to every GP, primitives
 *           one at a time to the least-loaded GP.
 *   COMPLEX (§2.3) per-GP attribute states: an attribute is sent to a GP
 *           only when a primitive placed there needs it (w.attr_send:
 *           every pending colour with any primitive, §3.5, or only the
 *           colour of the primitive's type); clusters of up
 *           to c*maxw nominal weight to one GP; concatenate-mode matrices
 *           broadcast with the pending replace-mode matrix; the state is
 *           flushed to every GP before an ordinary execute; primitive
 *           structures broadcast whole, each instance dealt to one GP
 *           like a primitive (§2.3.3).
 *
 *   BY_STRUCTURE (§2.1, rejected by the paper; pgsim's own row) each
 *           primitive and each structure instance whole to the
 *           least-loaded GP (nominal weight of the instance's subtree);
 *           a structure instanced once and heavier than one GP's share
 *           is broken up (its execute to the GPs holding something in
 *           it, its elements dealt the same way); the inherited
 *           attributes by an ancestor skeleton on each GP or by the
 *           host's pre-computed state (w.inherit, pphigs_bystruct.c).  A list whose posted
 *           structures are also executed elsewhere cannot be dealt by
 *           instance (they share one portion per GP) and is dealt by
 *           SIMPLE instead (wl_pphigs_dist_algo() says which).  No
 *           editing or moves: §3's procedure is the by-primitive one.
 *
 * Long triangle strips (§2.3.2, "break up large primitives such as long
 * triangle strips into smaller pieces"): with w.strip_split = k > 0 the
 * host list's strips of more than k triangles are replaced, before
 * dealing, by pieces of at most k triangles (k rounded up to even, so
 * every piece keeps the strip's winding), each dealt on its own; a
 * piece repeats the two vertices it shares with the previous one.
 *
 * Invariant (checked by the tests): at each of its primitives and at
 * each ordinary execute, every GP holds the host's current attribute
 * elements, so the union of the GPs' traversals is the host's traversal,
 * with the same matrices, colours and ODP priorities.
 *
 * Editing (§3): modify and append act at once; insert and delete are two
 * steps: step 1 changes the host (and sends inserted primitives and
 * executes, deletes from GPs at once), step 2 (wl_pphigs_dist_finish)
 * scans backwards from the first edited point until every GP is known
 * current (a primitive of that GP, an ordinary execute, or the start of
 * the structure; O(c maxw/minw n) elements, §3.5) and then walks forward
 * sending the attributes GPs need, past the last edited point until every
 * GP has been checked once.  Deltas are then recomputed (§4).
 *
 * Files: pphigs_distrib.c (dealing, deltas, lifecycle), pphigs_edit.c
 * (§3), pphigs_attrstate.c (§3.4-3.5), pphigs_bystruct.c (§2.1); they
 * share pphigs_dist_internal.h.
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_PPHIGS_DISTRIB_H
#define PGSIM_WORKLOAD_PPHIGS_PPHIGS_DISTRIB_H

#include "sim/scene/structdb.h"

typedef enum {
    WL_PPHIGS_SIMPLE,
    WL_PPHIGS_COMPLEX,
    WL_PPHIGS_BY_STRUCTURE /* §2.1, the paper's rejected alternative */
} WlPphigsAlgo;

/* Distribute-by-structure's two ways of giving a GP the attributes its
 * pieces inherit (§2.1; pphigs_bystruct.c). */
typedef enum {
    WL_PPHIGS_INHERIT_SKELETON,  /* the ancestors' attribute elements */
    WL_PPHIGS_INHERIT_PRECOMPUTE /* the host sends the inherited state */
} WlPphigsInherit;

/* §3.5's choice for complex: each attribute goes with any primitive, "as
 * if each attribute affects all succeeding primitives, regardless of
 * their type" (ALL: the step back is bounded), or only with primitives
 * of the type it affects (BY_KIND: fewer attributes sent, the step back
 * goes on until each type's colour is found or current everywhere). */
typedef enum { WL_PPHIGS_SEND_ALL, WL_PPHIGS_SEND_BY_KIND } WlPphigsAttrSend;

/* Nominal weights (§2.3.4), per element kind; a polygon's weight is
 * w[kind] + w_vertex * nverts.  cluster is the clustering factor c. */
typedef struct {
    double w[SCENE_EL_NKINDS];
    double w_vertex;
    double cluster;
    guint strip_split; /* §2.3.2: strips of more triangles are split into
                          pieces of at most this many; 0: never */
    guint attr_cache;  /* §3.4: attribute states saved every this many
                          dealt elements (complex); 0: no cache */
    WlPphigsInherit inherit; /* by structure: skeleton (0) or precompute */
    WlPphigsAttrSend attr_send; /* complex: all (0) or by kind */
} WlPphigsWeights;

/* Host-to-GP traffic of the distribution and edits so far. */
typedef struct {
    uint64_t elements_sent; /* element copies sent to GPs (inserted or,
                               by modify, replaced) */
    uint64_t sent_to[64];   /* the same per GP */
    uint64_t attrs_sent;    /* of them attribute elements (with
                               precompute's state elements) */
    uint64_t elements_removed;
    uint64_t last_scan;  /* elements examined by the last backward scan */
    uint64_t max_scan;   /* the largest such scan */
    uint64_t total_scan; /* elements examined by all backward scans */
    uint64_t cache_walk; /* host elements walked to place checkpoints of
                            the attribute-state cache (§3.4) */
} WlPphigsTraffic;

typedef struct WlPphigsDist WlPphigsDist;

/* Copies `src` as the host list and distributes it over ngp (1..64) GPs.
 * Returns a new distribution; free with wl_pphigs_dist_free(). */
WlPphigsDist *wl_pphigs_dist_new(const SceneDb *src, guint ngp,
                                 WlPphigsAlgo algo, const WlPphigsWeights *w);
void wl_pphigs_dist_free(WlPphigsDist *d);

guint wl_pphigs_dist_ngp(const WlPphigsDist *d);
/* The algorithm the list was dealt with. */
WlPphigsAlgo wl_pphigs_dist_algo(const WlPphigsDist *d);
/* Borrowed views; never edit them directly. */
const SceneDb *wl_pphigs_dist_host(const WlPphigsDist *d);
const SceneDb *wl_pphigs_dist_gp(const WlPphigsDist *d, guint g);
const WlPphigsTraffic *wl_pphigs_dist_traffic(const WlPphigsDist *d);
/* Nominal weight of one element (a primitive-structure execute weighs
 * its structure's traversal). */
double wl_pphigs_dist_weight(const WlPphigsDist *d, const SceneElem *e);
/* Nominal load of each GP (sum of nominal weights over its portion's
 * traversal, §5.1); `out` has ngp entries. */
void wl_pphigs_dist_loads(const WlPphigsDist *d, double *out);

/* Edits in host coordinates (structure id, element position).  The
 * element's tag is replaced by a fresh element id.  Errors as for
 * scene_db_* (cycles, kind change on modify). */
gboolean wl_pphigs_dist_modify(WlPphigsDist *d, guint sid, guint pos,
                               const SceneElem *e, GError **err);
gboolean wl_pphigs_dist_append(WlPphigsDist *d, guint sid, const SceneElem *e,
                               GError **err);
gboolean wl_pphigs_dist_insert(WlPphigsDist *d, guint sid, guint pos,
                               const SceneElem *e, GError **err);
void wl_pphigs_dist_delete(WlPphigsDist *d, guint sid, guint pos);
/* Step 2 of every pending insert/delete region, then the ODP deltas. */
void wl_pphigs_dist_finish(WlPphigsDist *d);
void wl_pphigs_dist_post(WlPphigsDist *d, guint sid);
void wl_pphigs_dist_unpost(WlPphigsDist *d, guint sid);

/* Moves the primitive at (sid, pos), owned by one GP, to GP `to`, with
 * the attributes it needs there (used by rebalancing, §5).  FALSE when
 * the element is not a dealt primitive. */
gboolean wl_pphigs_dist_move(WlPphigsDist *d, guint sid, guint pos, guint to);
/* The GP owning the dealt element at (sid, pos), or -1 (attributes,
 * ordinary executes, primitive-structure contents). */
gint wl_pphigs_dist_owner(const WlPphigsDist *d, guint sid, guint pos);

#endif
