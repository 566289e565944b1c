/* pphigs_dist_internal.h — shared by the files of the PPHIGS distribution
 * (not public; users include pphigs_distrib.h).
 *
 *   pphigs_distrib.c    bookkeeping, GP copies, dealing (§2.2-2.3), the
 *                       forward walk, ODP deltas (§4), lifecycle, moves
 *   pphigs_attrstate.c  attribute states and the backward scan (§3.4-3.5)
 *   pphigs_edit.c       editing in two steps (§3.1-3.3)
 *   pphigs_bystruct.c   distribute-by-structure (§2.1)
 *
 * Bookkeeping: for every host element a 64-bit mask of the GPs holding a
 * copy; a GP's position of host element i is the number of elements
 * before i whose mask has that GP.  Per structure: nominal load of each
 * GP, the open cluster, and the pending edit region.
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_PPHIGS_DIST_INTERNAL_H
#define PGSIM_WORKLOAD_PPHIGS_PPHIGS_DIST_INTERNAL_H

#include "sim/workload/pphigs/pphigs_distrib.h"

#define NONE (-1)

/* §3.4's attribute states saved every n dealt elements of a structure
 * (pphigs_attrstate.c). */
typedef struct WlPphigsAttrCache WlPphigsAttrCache;

typedef struct {
    GArray *mask;             /* uint64_t per host element */
    double *load;             /* ngp nominal loads of this structure */
    gint cur;                 /* open cluster's GP, NONE */
    double run;               /* nominal weight in the open cluster */
    gint first, last;         /* pending edit region, NONE */
    WlPphigsAttrCache *cache; /* NULL: no cache (simple, primitive
                                 structures, w.attr_cache 0) */
} StructMeta;

struct WlPphigsDist {
    SceneDb *host;
    SceneDb **gp;
    guint ngp;
    WlPphigsAlgo algo;
    WlPphigsWeights w;
    double maxw;     /* largest primitive weight seen */
    GPtrArray *meta; /* StructMeta * per structure */
    double *gload;   /* global nominal load per GP */
    uint64_t next_id;
    WlPphigsTraffic traffic;
    gboolean *broken; /* by structure: per structure, walked element by
                         element (roots and broken-up ones); else NULL */
};

/* Colour slots of an attribute state: fill (polygons, strips, ODPs),
 * line, sphere (structdb.h: a colour per primitive type). */
enum { SLOT_FILL, SLOT_LINE, SLOT_SPHERE, NSLOTS };

/* The slot colour kind k (SCENE_EL_*COLOR) sets. */
static inline guint attr_slot(SceneElemKind k)
{
    return k == SCENE_EL_LINE_COLOR     ? SLOT_LINE
           : k == SCENE_EL_SPHERE_COLOR ? SLOT_SPHERE
                                        : SLOT_FILL;
}

/* The host's current attribute elements known at a point (positions). */
typedef struct {
    gint colour[NSLOTS], replace;
    GArray *concats; /* gint, in host order */
} AttrState;

static inline uint64_t dist_all_mask(const WlPphigsDist *d)
{
    return d->ngp == 64 ? ~(uint64_t)0 : (((uint64_t)1 << d->ngp) - 1);
}

static inline StructMeta *dist_meta(const WlPphigsDist *d, guint sid)
{
    return g_ptr_array_index(d->meta, sid);
}

static inline uint64_t *dist_mask_at(const WlPphigsDist *d, guint sid,
                                     guint pos)
{
    return &g_array_index(dist_meta(d, sid)->mask, uint64_t, pos);
}

static inline const SceneElem *dist_hel(const WlPphigsDist *d, guint sid,
                                        guint pos)
{
    return scene_db_elem(d->host, sid, pos);
}

static inline gboolean dist_is_prim_struct(const WlPphigsDist *d, guint sid)
{
    return d->algo == WL_PPHIGS_COMPLEX && scene_db_is_primitive(d->host, sid);
}

/* Dealt like a primitive: primitives and primitive-structure executes. */
static inline gboolean dist_is_dealt(const WlPphigsDist *d, const SceneElem *e)
{
    return scene_elem_is_prim(e->kind) ||
           (e->kind == SCENE_EL_EXECUTE && dist_is_prim_struct(d, e->child));
}

/* pphigs_distrib.c */
void wl_pphigs_dist_put(WlPphigsDist *d, guint sid, guint pos, guint g);
void wl_pphigs_dist_put_all(WlPphigsDist *d, guint sid, guint pos);
void wl_pphigs_dist_drop(WlPphigsDist *d, guint sid, guint pos, guint g);
guint wl_pphigs_dist_gp_pos(const WlPphigsDist *d, guint sid, guint pos,
                            guint g);
void wl_pphigs_dist_add_load(WlPphigsDist *d, guint sid, guint g, double w);
guint wl_pphigs_dist_choose(WlPphigsDist *d, guint sid, double w);
void wl_pphigs_dist_forward(WlPphigsDist *d, guint sid, guint from, gint last,
                            AttrState *s);
void wl_pphigs_dist_step2(WlPphigsDist *d, guint sid, guint first, gint last);
void wl_pphigs_dist_deltas(WlPphigsDist *d);

/* pphigs_attrstate.c */
void wl_pphigs_attr_init(AttrState *s);
void wl_pphigs_attr_clear(AttrState *s);
void wl_pphigs_attr_step(AttrState *s, const SceneElem *e, gint i);
/* Sends GP g the attributes of s it lacks for element e placed there:
 * every colour (§3.5: "as if each attribute affects all succeeding
 * primitives"), or with w.attr_send by kind only the colour of e's
 * primitive type (an execute, or e NULL: every colour). */
void wl_pphigs_attr_ensure(WlPphigsDist *d, guint sid, const AttrState *s,
                           guint g, const SceneElem *e);
void wl_pphigs_attr_ensure_matrices(WlPphigsDist *d, guint sid,
                                    const AttrState *s);
void wl_pphigs_attr_backward(WlPphigsDist *d, guint sid, guint first,
                             AttrState *s);
/* A cache of structure sid's host list, checkpoints placed (complex,
 * w.attr_cache > 0); free with wl_pphigs_attr_cache_free(). */
WlPphigsAttrCache *wl_pphigs_attr_cache_new(WlPphigsDist *d, guint sid);
void wl_pphigs_attr_cache_free(WlPphigsAttrCache *c);
/* The host list of sid changed at pos: an element inserted (delta +1)
 * or deleted (-1) there; attr: the attribute state after pos changed
 * (checkpoints after pos are dropped), else they shift. */
void wl_pphigs_attr_cache_edit(WlPphigsDist *d, guint sid, guint pos, int delta,
                               gboolean attr);

/* pphigs_bystruct.c: FALSE (nothing dealt) when the list cannot be. */
gboolean wl_pphigs_dist_by_structure(WlPphigsDist *d);
/* Precompute's state elements, once the deltas are final (no-op for the
 * skeleton and the other algorithms). */
void wl_pphigs_dist_by_structure_state(WlPphigsDist *d);

#endif
