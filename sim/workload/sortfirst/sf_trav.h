/* sf_trav.h — §3.5 traversal efficiency of sort-first: empty flags and
 * bounding-volume culling of structure instances, counted (seed 000
 * §3.5: "structures which contain no primitives ... giving the
 * opportunity to skip over such structures during traversal").
 *
 * Each processor traverses the replicated hierarchy every frame; the
 * unit of work counted is a max-set node (a structure instance) whose
 * chunk list the processor scans.  For processor p at the start of a
 * frame (holdings as the sort finds them, this frame's view):
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
 *             each node entered costs one volume test (`volume_tests`);
 *   both      flags and culling together.
 *
 * Chunk boxes not transformed because their node's subtree was culled
 * are counted as `boxes_culled` (p's master and held chunks).  Counts
 * only: the frame's time is not changed.  One pass for all processors
 * (bit masks, P <= 64): O(chunk instances + nodes).
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_TRAV_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_TRAV_H

#include "sim/workload/sortfirst/sf_book.h"

typedef struct {
    uint64_t plain, flags, culled, both; /* nodes scanned */
    uint64_t boxes_culled;               /* chunk boxes skipped */
} WlSfTrav;

/* Adds every processor's counts for the frame whose need[] b holds. */
void wl_sf_trav_count(const WlSfBook *b, WlSfTrav *t);

#endif
