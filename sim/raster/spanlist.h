/* spanlist.h — scanline span lists, sorted by x_min.
 *
 * The first step of the modified scanline z-buffer of Kurç, Aykanat and
 * Özgüç (seed 003, §2): the spans of the projected polygons are put in a
 * list per scanline, sorted by increasing minimum x-intersection.  Here
 * spans are appended in any order (rast_spanlist_sink) and
 * rast_spanlist_sort() orders them once: a counting sort on y, then a
 * sort of each row on (x0, prim, x1, z0).  The key makes the order
 * independent of the drawing order whenever primitive ids are distinct.
 * Cost: O(S + H) plus O(s log s) per row of s spans.
 */
#ifndef PGSIM_RASTER_SPANLIST_H
#define PGSIM_RASTER_SPANLIST_H

#include "sim/raster/scan.h"

typedef struct RastSpanList RastSpanList;

/* Returns a new empty list for a width x height image; free with
 * rast_spanlist_free(). */
RastSpanList *rast_spanlist_new(int width, int height);
void rast_spanlist_free(RastSpanList *sl);
/* Empties the list, keeping its memory. */
void rast_spanlist_clear(RastSpanList *sl);

int rast_spanlist_width(const RastSpanList *sl);
int rast_spanlist_height(const RastSpanList *sl);

/* A sink that appends spans (the counters are not touched). */
RastSpanSink rast_spanlist_sink(RastSpanList *sl);
void rast_spanlist_add(RastSpanList *sl, const RastSpan *s);

/* Sorts every row by x_min; required before rast_spanlist_row(). */
void rast_spanlist_sort(RastSpanList *sl);
gboolean rast_spanlist_sorted(const RastSpanList *sl);

/* The spans of row y in x_min order, *n of them.  Borrowed; valid until
 * the list is next changed.  The list must be sorted. */
const RastSpan *rast_spanlist_row(const RastSpanList *sl, int y, size_t *n);
size_t rast_spanlist_len(const RastSpanList *sl);

#endif
