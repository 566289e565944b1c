/* sf_edit.h — editing the hierarchy under sort-first (seed 000 §1.1
 * operations; §2 "most of the other operations are performed by
 * broadcasting the command to all of the processors"; §3.4.2-§3.4.3
 * max-set operations, deferred to traversal, and garbage collection).
 *
 * Between frames the application edits the database; each frame after
 * the first carries `per_frame[k]` edits of each kind, in this order:
 *
 *   matrix   a random matrix element is rotated by `angle_deg` about y
 *            (every combined matrix below it changes; the chunks move
 *            on the screen and migrate through the next sort);
 *   execute  a random execute is pointed at another structure of the
 *            same height (levels below it, so the network keeps its
 *            size), one that closes no cycle: the max-set subtree under
 *            every instance of the executing structure is replaced;
 *   unpost   a random posted structure is unposted (its max-set tree
 *            goes to garbage collection);
 *   post     the structure unposted last is posted again, else a random
 *            structure not posted (drawn at the identity): a new
 *            max-set tree.
 *
 * A kind with nothing to act on is skipped (not counted).  The editor
 * owns a copy of the database; after the frame's edits it rebuilds the
 * chunk instances (wl_sf_db_reinstance: chunks, and so chunk ids and
 * masters, are kept) and matches the new max-set tree to the old one:
 * a root matches the old root of the same posting (an unposted and
 * re-posted structure is a new tree), a child the old child at the same
 * execute of a matched parent when it executes the same structure.
 * Matched instances keep their bookkeeping (wl_sf_book_remap); the rest
 * are new (master pointers only) or obsolete (collected).
 *
 * Work each frame (WlSfEditFrame): the commands every processor
 * applies to its copy of the hierarchy, and the max-set nodes each
 * processor's skeleton gains and loses (max-set bookkeeping; the
 * min-set keeps no max-set between frames, §3.3).  Pointer work per
 * processor comes from the book (WlSfRemapWork).  Cost per edit frame
 * O(max-set polygons + nodes + chunk instances).
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_EDIT_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_EDIT_H

#include "sim/core/rng.h"
#include "sim/workload/sortfirst/sf_book.h"

typedef enum {
    WL_SF_ED_MATRIX,
    WL_SF_ED_EXECUTE,
    WL_SF_ED_UNPOST,
    WL_SF_ED_POST,
    WL_SF_ED_N
} WlSfEditKind;

/* "matrix", "execute", "unpost", "post" */
extern const char *const wl_sf_edit_names[];

typedef struct {
    uint64_t per_frame[WL_SF_ED_N];
    double angle_deg; /* rotation of a matrix edit */
} WlSfEditSpec;

/* One frame's edit work. */
typedef struct {
    uint64_t commands;        /* edits applied, each processor applies all */
    uint64_t nodes_created;   /* max-set nodes new this frame */
    uint64_t nodes_collected; /* max-set nodes made obsolete */
} WlSfEditFrame;

typedef struct WlSfEdit WlSfEdit;

/* An editor of a copy of db whose chunk database is sf (borrowed, the
 * one the run renders; must outlive the editor); rng borrowed. */
WlSfEdit *wl_sf_edit_new(const SceneDb *db, WlSfDb *sf,
                         const WlSfEditSpec *spec, SimRng *rng);
void wl_sf_edit_free(WlSfEdit *e);
/* TRUE when the spec asks for any edit. */
gboolean wl_sf_edit_any(const WlSfEditSpec *spec);
/* Applies one frame's edits, rebuilds the chunk instances and remaps
 * the book b; the frame's work into *f, each processor's pointer work
 * added to w[p].  Returns the old number of every new instance (-1:
 * new; free with g_free()), or NULL when no edit applied (numbers
 * unchanged). */
gint64 *wl_sf_edit_frame(WlSfEdit *e, WlSfBook *b, WlSfEditFrame *f,
                         WlSfRemapWork *w);
/* The edited database (borrowed). */
const SceneDb *wl_sf_edit_db(const WlSfEdit *e);
/* Edits applied so far, per kind (WL_SF_ED_N entries, borrowed). */
const uint64_t *wl_sf_edit_applied(const WlSfEdit *e);

#endif
