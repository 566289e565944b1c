/* sf_db_edit.h — chunks re-formed after primitive and structure edits
 * (seed 000 §3.3.1: "If primitives within a structure are changed, the
 * bounding volume may need to grow or shrink"; sf_edit.h).
 *
 * The editor tags every element of its copy of the database uniquely;
 * chunks follow their primitives by tag across edits that insert or
 * delete elements (positions shift).  After a frame's edits, for each
 * structure marked dirty:
 *
 *   - each chunk keeps the primitives of it still there (in its order;
 *     a changed primitive keeps its tag and so its chunk), and its id,
 *     master and copies; its box and polygon count are recomputed (the
 *     volume grows or shrinks); a chunk left empty is dropped;
 *   - a primitive in no chunk (new) joins the chunk of its structure
 *     with fewer than N primitives whose box centre is nearest its
 *     centroid, else starts a new chunk (master: its number mod P);
 *   - a structure with primitives but no chunk left (new, or emptied
 *     and refilled) is chunked by d's strategy (sf_db.h).
 *
 * Chunks of clean structures are kept as they are.  Chunk ids are
 * compacted (kept chunks in their old order, then new ones); the map
 * from new to old ids carries the book's chunk state over
 * (wl_sf_book_remap_chunks).  Cost O(chunks + primitives of dirty
 * structures x their chunks).
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_DB_EDIT_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_DB_EDIT_H

#include "sim/workload/sortfirst/sf_book.h"

typedef struct {
    uint64_t created; /* chunks new */
    uint64_t dropped; /* old chunks left without a primitive */
    uint64_t changed; /* kept chunks whose primitives or box changed */
} WlSfRechunk;

/* The tag of every entry of d->prims (parallel to it), read from db, the
 * database d's chunks were formed from.  New GArray of uint64_t. */
GArray *wl_sf_db_prim_tags(const WlSfDb *d, const SceneDb *db);
/* Re-forms the chunks of the structures with dirty[sid] set (dirty has
 * an entry per structure of db; structures new in db must be dirty)
 * from tags (wl_sf_db_prim_tags() before the edits); d->n_structs
 * becomes db's count.  The instances are not rebuilt: call
 * wl_sf_db_reinstance() next.  Returns per new chunk the old chunk it
 * continues, or -1 (g_free). */
gint *wl_sf_db_rechunk(WlSfDb *d, const SceneDb *db, const GArray *tags,
                       const guint8 *dirty, WlSfRechunk *rc);
/* The book's per-chunk state after wl_sf_db_rechunk(): a kept chunk
 * keeps its master, copies and use; a new one is held by its master
 * alone (n_old: chunks before). */
void wl_sf_book_remap_chunks(WlSfBook *b, const gint *old_of_new,
                             guint n_old);

#endif
