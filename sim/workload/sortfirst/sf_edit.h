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
 *            max-set tree;
 *
 * and the rest of the paper's operations (§1.1, §3.3.1, §3.4.2;
 * sf_edit_struct.c):
 *
 *   create   a new empty structure is created and opened (min-set
 *            only: nothing executes it yet);
 *   add      a primitive is appended to the open structure (a copy of a
 *            random primitive of the database, moved; skipped when no
 *            structure is open);
 *   close    the open structure is closed;
 *   prim_create  a primitive is inserted into a random structure that
 *            holds primitives, after one of them (so it shares their
 *            matrix): a copy of it moved by up to its own extent;
 *   prim_change  a random primitive is scaled about its centroid by
 *            2^u, u uniform in [-1, 1], and moved by up to half its
 *            extent: its chunk's bounding volume grows or shrinks, and
 *            with it the node's volume up the hierarchy (sf_trav.c
 *            takes a node's volume as the union of its subtree's);
 *   prim_delete  a random primitive is deleted (a chunk left empty is
 *            dropped);
 *   color    a random colour element gets a random colour (an attribute
 *            change: the image changes, no chunk or volume does);
 *   execute_add  an execute of a random structure (any height, also
 *            one already executed: "A executed an additional time",
 *            §3.4) is appended to a random structure, one closing no
 *            cycle: the child's whole max-set subtree is replicated;
 *   execute_delete  a random execute is deleted (its subtree is
 *            collected);
 *   delete   a random structure neither posted nor executed is deleted
 *            (§3.4.2: it "only affects the min-set ... you should only
 *            delete non-instanced structures"): one an unpost or an
 *            execute_delete left out of the scene, or one created; its
 *            chunks are dropped.
 *
 * Chunks are re-formed after primitive edits (sf_db_edit.c): a chunk
 * keeps its id, master and copies as long as a primitive of it is left
 * (its box recomputed: it grows or shrinks); a new primitive joins the
 * chunk of its structure with room whose box centre is nearest, else a
 * new chunk (master: its number mod P); a structure with no chunk left
 * is chunked anew by the run's strategy.  Every processor applies the
 * command to its copies (seed 000 §2: commands are broadcast), so a
 * changed chunk is not sent again; a dropped chunk's copies are deleted
 * everywhere.
 *
 * A kind with nothing to act on is skipped (not counted).  The editor
 * owns a copy of the database; after the frame's edits it rebuilds the
 * chunk instances (wl_sf_db_reinstance: chunks, and so chunk ids and
 * masters, are kept) and matches the new max-set tree to the old one:
 * a root matches the old root of the same posting (an unposted and
 * re-posted structure is a new tree), a child the old child made by the
 * same execute element (each element of the editor's copy carries a
 * unique tag) of a matched parent when it executes the same structure.
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
    WL_SF_ED_CREATE,
    WL_SF_ED_ADD,
    WL_SF_ED_CLOSE,
    WL_SF_ED_PRIM_CREATE,
    WL_SF_ED_PRIM_CHANGE,
    WL_SF_ED_PRIM_DELETE,
    WL_SF_ED_COLOR,
    WL_SF_ED_EXEC_ADD,
    WL_SF_ED_EXEC_DELETE,
    WL_SF_ED_DELETE,
    WL_SF_ED_N
} WlSfEditKind;

/* "matrix", "execute", "unpost", "post", "create", "add", "close",
 * "prim_create", "prim_change", "prim_delete", "color", "execute_add",
 * "execute_delete", "delete" */
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
    uint64_t chunks_created;  /* chunks formed by primitive edits */
    uint64_t chunks_dropped;  /* chunks left empty, dropped */
    uint64_t chunks_changed;  /* kept chunks whose primitives changed */
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
