/* sf_book.h — min-set and max-set bookkeeping of migrating chunks
 * (seed 000 §3.3, §3.4).
 *
 * Every processor keeps the whole hierarchy; primitives migrate as
 * chunks (sf_db.h).  Push communication with fixed masters (§3.3.2.1):
 *
 * min-set (§3.3)  a processor stores chunk data (the min-set).  For each
 *   of its master chunks it transforms the box of every instance and
 *   bucket-sorts it into regions; the union is the chunk's set of
 *   regions, compared with the master's bit vector of processors holding
 *   a copy; the chunk goes to each new slave, with the first instance in
 *   the slave's region (§3.3.2.3).  For each slave chunk it cull-tests
 *   every instance against its own region and deletes the chunk when no
 *   instance fell in it (decided a frame late, below).  A newly received chunk is cull-tested the same
 *   way when it is rendered.
 * max-set (§3.4)  the min-set copy plus instance pointers (the max-set
 *   skeleton): for each master chunk the master holds every instance
 *   pointer, bucket-sorts each instance and sends an instance pointer
 *   to each processor newly overlapped by that instance, plus the chunk
 *   data when that processor holds no copy (§3.4.4).  A slave tests only
 *   the instances it holds and drops pointers that left its region; its
 *   copy of the chunk is deleted when no pointer refers to it any more
 *   (reference count, §3.4.3), after the frame's arrivals.
 *
 * State is one bit per processor per chunk and per instance (P <= 64):
 * `held_*` are the processors' own copies (changed only by the owner:
 * at its sort, on arrival, at its render), `master_*` the masters' bit
 * vectors.  Both methods render the same chunk instances: those whose
 * box overlaps the region (need).  Invariant after the arrivals of a
 * frame: need[i] bit q => q holds chunk(i) (and, max-set, pointer i).
 *
 * Pull (§3.3.2.2, `migration: pull`; min-set with fixed masters only,
 * as the paper describes it): no bit vectors; every processor
 * transforms the box of every instance of every chunk (held or not) and
 * cull-tests it against its own region, drops slave copies no instance
 * needed last frame, and sends each master a request naming the chunks
 * it needs and lacks; the master answers with the chunks (first instance in the
 * requester's region).
 *
 * Dynamic mastership (§3.3.2.1, `mastership: dynamic`; push): when no
 * instance of a chunk falls in its master's region but some falls in
 * another's, mastership passes, with the copy vector (and, max-set, all
 * instance pointers and their vectors), to the lowest-numbered processor
 * already holding a copy that needs it (else the lowest needing it),
 * and the old master deletes its copy: one copy where the chunk is
 * rendered instead of two.  A chunk that leaves the screen stays with
 * its last master: the off-screen accumulation the paper warns of,
 * unless wl_sf_book_spread() (sf_mastership.c) makes the off-screen
 * masters even after the frame's sorts.
 * The new master takes over on arrival (its next frame's sort).
 *
 * Slave deletion decided on the next frame (§3.3.2.1, push min-set):
 * "one cannot know this until after a complete traversal, one can
 * collect this information during one frame and decide whether or not
 * to delete the chunk during the next frame".  A min-set slave's sort
 * in frame f deletes the copies no instance needed in frame f - 1
 * (`used_prev`), so a copy lives one frame past its last use; the
 * master's copy vector (the regions of f - 1) already leaves it out, so
 * a chunk needed again is sent again.  Pull deletes by the same rule
 * (and asks again for a chunk it deleted but needs).
 *
 * Edits (sf_edit.h) change the max-set; wl_sf_book_remap carries the
 * state of every instance that survives to its new number.  A new
 * instance starts with its master's pointer only (§3.4.3: "places
 * within it pointers to all of its master chunks"); the pointers of an
 * obsolete one are garbage-collected on every processor holding them.
 * A slave copy deleted while its chunk has no instance at all is
 * counted as collected.  The pointers a master sends for instances an
 * edit created are counted as edit bytes (chunk data sent with them is
 * migration: the region needed it).
 *
 * Work is counted, not timed: box transforms of master, slave and newly
 * received chunks (the counts of seed 000 Charts 4 and 5), items sent,
 * received and deleted.  Cost per frame O(P x chunk instances).
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_BOOK_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_BOOK_H

#include "sim/workload/sortfirst/sf_db.h"
#include "sim/workload/sortfirst/sf_regions.h"

typedef enum { WL_SF_MINSET, WL_SF_MAXSET } WlSfBookkeeping;
typedef enum { WL_SF_PUSH, WL_SF_PULL } WlSfMigration;
typedef enum { WL_SF_FIXED, WL_SF_DYNAMIC } WlSfMastership;

extern const char *const wl_sf_bookkeeping_names[]; /* minset, maxset */
extern const char *const wl_sf_migration_names[];   /* push, pull */
extern const char *const wl_sf_mastership_names[];  /* fixed, dynamic */

/* Message sizes in bytes (workload YAML). */
typedef struct {
    uint64_t message;  /* per message (header, end-of-sort marker) */
    uint64_t chunk;    /* per chunk: id, structure, box, first instance */
    uint64_t triangle; /* per polygon of a chunk's data */
    uint64_t instance; /* per instance pointer (max-set) */
    uint64_t cell;     /* per cell of an adaptive work grid */
    uint64_t request;  /* per chunk id in a pull request */
    uint64_t mastership; /* per chunk handed over: id, copy vector */
    uint64_t edit;     /* per edit command (sf_edit.h) */
} WlSfSizes;

/* What one processor sends one other processor in a frame. */
typedef struct {
    guint src, dst;
    GArray *chunks; /* guint: chunk data */
    GArray *insts;  /* guint: max-set instance pointers; min-set: the
                       first instance of each chunk in dst's region */
    GArray *masters; /* guint: chunks whose mastership passes to dst */
    uint64_t polys; /* polygons of the chunks' data */
    uint64_t bytes;
} WlSfBatch;

/* Work of one processor in one frame. */
typedef struct {
    uint64_t master_boxes, slave_boxes, new_boxes; /* box transforms */
    uint64_t sent_chunks, sent_polys, sent_insts, sent_bytes;
    uint64_t recv_chunks, recv_polys, recv_insts;
    uint64_t deleted_chunks;
    uint64_t probe_boxes; /* pull: boxes of chunks not held */
    uint64_t requested;   /* pull: chunks asked for */
    uint64_t handed;      /* dynamic: masterships passed on */
    uint64_t collected;   /* slave copies deleted, chunk without instance */
    uint64_t edit_bytes;  /* pointers sent for instances edits created */
    uint64_t spread;      /* dynamic: off-screen masterships spread */
    uint64_t served;      /* pull: requests this master served */
    uint64_t held_chunks, held_polys; /* after the frame */
} WlSfBookWork;

typedef struct {
    const WlSfDb *db; /* borrowed */
    WlSfRegions regions;
    WlSfBookkeeping bk;
    WlSfSizes sizes;
    WlSfMigration mig;
    WlSfMastership ms;
    guint *master;         /* per chunk: its master now */
    uint64_t *need;        /* per instance: regions overlapped (frame) */
    uint64_t *held_data;   /* per chunk */
    uint64_t *held_inst;   /* per instance (max-set) */
    uint64_t *master_data; /* per chunk: master's copy vector */
    uint64_t *master_inst; /* per instance: master's pointer vector */
    uint64_t *used;        /* per chunk: regions needing it this frame */
    uint64_t *used_prev;   /* per chunk: ... in the previous frame */
    guint8 *fresh;         /* per instance: created by this frame's edits */
    gboolean remapped;     /* edits remapped the instances this frame */
} WlSfBook;

/* Edit work of one processor: max-set pointers created (its new master
 * instances) and garbage-collected (obsolete instances it pointed to). */
typedef struct {
    uint64_t ptr_created, ptr_collected;
} WlSfRemapWork;

/* Initial distribution: each master holds its chunks (and, max-set, all
 * their instance pointers); nobody else holds anything. */
WlSfBook *wl_sf_book_new(const WlSfDb *db, const WlSfRegions *regions,
                         WlSfBookkeeping bk, const WlSfSizes *sizes);
void wl_sf_book_free(WlSfBook *b);
/* Pull or push, fixed or dynamic masters (push and fixed by default);
 * pull needs min-set and fixed masters. */
void wl_sf_book_set_policy(WlSfBook *b, WlSfMigration mig,
                           WlSfMastership ms);
static inline guint wl_sf_book_master(const WlSfBook *b, guint c)
{
    return b->master[c];
}

/* After the database's instances were rebuilt (wl_sf_db_reinstance):
 * old_of_new[i] is new instance i's number before, or -1 (new); n_old
 * the count before.  Adds each processor's pointer work to w[p]
 * (max-set). */
void wl_sf_book_remap(WlSfBook *b, const gint64 *old_of_new, guint n_old,
                      WlSfRemapWork *w);
/* need[] for a frame's view-projection (what the bucket sorts compute). */
void wl_sf_book_need(WlSfBook *b, Mat4 view_proj);
/* Each instance's screen rectangle under view_proj into out[0 .. n_insts). */
void wl_sf_book_screens(const WlSfBook *b, Mat4 view_proj, WlSfScreen *out);
/* wl_sf_book_need() from the instances' screen rectangles
 * (wl_sf_book_screens()). */
void wl_sf_book_need_from(WlSfBook *b, const WlSfScreen *scr);
/* Processor p's sort pass: master bucket sort, slave cull tests,
 * deletions; fills out[q] (an array of P batches, each cleared first)
 * with what p sends q; work into *w. */
void wl_sf_book_sort(WlSfBook *b, guint p, WlSfBatch *out, WlSfBookWork *w);
/* Processor p's pull pass: cull tests of every chunk instance against
 * p's region, deletions; fills out[m] with the requests to master m. */
void wl_sf_book_pull_sort(WlSfBook *b, guint p, WlSfBatch *out,
                          WlSfBookWork *w);
/* A master answers request `req`: reply (reset first) carries the
 * chunks; the master's work into *w. */
void wl_sf_book_serve(WlSfBook *b, const WlSfBatch *req, WlSfBatch *reply,
                      WlSfBookWork *w);
/* A batch arrives at its destination. */
void wl_sf_book_receive(WlSfBook *b, const WlSfBatch *in, WlSfBookWork *w);
/* Processor p after its arrivals: max-set drops unreferenced copies;
 * appends the instances p renders to `render` (guint) and counts the
 * cull tests of newly received min-set chunks (`fresh`: chunks received
 * this frame, may be NULL). */
void wl_sf_book_render_set(WlSfBook *b, guint p, const GArray *fresh,
                           GArray *render, WlSfBookWork *w);
/* Bytes processor p stores: chunk data, pointers, master bit vectors. */
uint64_t wl_sf_book_memory(const WlSfBook *b, guint p);
/* The largest wl_sf_book_memory() over the processors, in one pass
 * over the chunks (O(chunks + instances), not P times that). */
uint64_t wl_sf_book_peak_memory(const WlSfBook *b);
/* TRUE when every instance overlapping a region is held by its
 * processor (the migration invariant); else names the first miss. */
gboolean wl_sf_book_check(const WlSfBook *b, guint *inst, guint *proc);

/* Off-screen master chunks under dynamic mastership (sf_mastership.c):
 * keep (they pile up where they left the screen) | spread (made even
 * among the masters each frame). */
typedef enum { WL_SF_OFF_KEEP, WL_SF_OFF_SPREAD } WlSfOffscreen;
extern const char *const wl_sf_offscreen_names[]; /* keep, spread */
/* After every processor's sort of a frame (push, dynamic): moves
 * off-screen master chunks from processors holding more than their
 * share to those holding the fewest; out[p] are p's P batches of the
 * frame, w[p] its work (sf_mastership.c). */
void wl_sf_book_spread(WlSfBook *b, WlSfBatch *const *out,
                       WlSfBookWork *const *w);

/* An empty batch: no item, 0 polygons, 0 bytes, src = dst = 0. */
void wl_sf_batch_init(WlSfBatch *bt);
/* Frees the arrays and leaves the batch zeroed, so clearing it again
 * (or clearing a zeroed batch) does nothing. */
void wl_sf_batch_clear(WlSfBatch *bt);

#endif
