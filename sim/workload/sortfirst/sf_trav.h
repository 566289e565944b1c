/* sf_trav.h — §3.5 traversal efficiency of sort-first: empty flags and
 * bounding-volume culling of structure instances, counted and priced
 * (seed 000 §3.5: "structures which contain no primitives ... giving
 * the opportunity to skip over such structures during traversal").
 *
 * Each processor traverses the replicated hierarchy every frame; the
 * unit of work is a max-set node (a structure instance) whose chunk list
 * the processor scans.  For processor p at the start of a frame
 * (holdings as the sort finds them, this frame's view):
 *
 *   plain     every node: N nodes;
 *   flags     min-set: per-structure empty flags, a node is scanned
 *             only when p masters or holds a chunk of its structure;
 *             max-set: hierarchical flags, a node's subtree is entered
 *             only when p masters a chunk or holds an instance pointer
 *             somewhere in it;
 *   culled    bounding-volume culling: a node's subtree is skipped when
 *             no chunk instance in it overlaps any region (the node's
 *             volume taken as the union of its subtree's chunk boxes);
 *             each node entered (a root, or a child of a node whose
 *             volume passed, and under max-set flags one whose flag is
 *             set) costs one volume test;
 *   flags_culled  both.
 *
 * All four counts are reported whatever the run uses; the run's mode
 * (WlSfTravMode) gives each processor's priced work (WlSfTravProc):
 * nodes scanned (node_visit each, sf_frame.h), volume tests (a box: 8
 * vertex transforms) and the chunk boxes its sort does not transform
 * because their node was culled (its master boxes and slave boxes, as
 * sf_book.c counts them: min-set every instance of a held chunk,
 * max-set each held pointer).  One pass for all processors (bit masks,
 * P <= 64): O(chunk instances + nodes x P).
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_TRAV_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_TRAV_H

#include "sim/workload/sortfirst/sf_book.h"

typedef enum {
    WL_SF_TRAV_PLAIN,
    WL_SF_TRAV_FLAGS,
    WL_SF_TRAV_CULLED,
    WL_SF_TRAV_BOTH
} WlSfTravMode;

/* "plain", "flags", "culled", "flags_culled" */
extern const char *const wl_sf_trav_names[];

typedef struct {
    uint64_t plain, flags, culled, both; /* nodes scanned, all processors */
    uint64_t boxes_culled; /* chunk boxes skipped (culling modes) */
    uint64_t tests;        /* volume tests in the run's mode */
} WlSfTrav;

/* One processor's traversal work in the run's mode. */
typedef struct {
    uint64_t nodes;         /* structure instances scanned */
    uint64_t tests;         /* bounding-volume tests */
    uint64_t master_culled; /* master chunk boxes not transformed */
    uint64_t slave_culled;  /* slave chunk boxes not transformed */
} WlSfTravProc;

/* Adds every processor's counts for the frame whose need[] b holds; per
 * (P entries, cleared first; may be NULL) gets mode's work of each. */
void wl_sf_trav_count(const WlSfBook *b, WlSfTravMode mode, WlSfTrav *t,
                      WlSfTravProc *per);

#endif
