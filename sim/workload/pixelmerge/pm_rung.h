/* pm_rung.h — the image fidelity ladder of sort-last compositing: the
 * schemes of pm_composite.h run on images held at three rungs, so that
 * compositing scales with the active pixels, not with processes x image
 * size (issue 35, point 2):
 *
 *   pixels  real pixels (pm_composite.h: depth, colour, the operator);
 *   runs    active spans without values: each process holds the sorted
 *           maximal runs [s, e) of linear indices it covers; a composite
 *           is their union.  The messages, their bytes and the work are
 *           those of the pixel rung exactly (an active set, its runs and
 *           its bounding box are all a message's size depends on);
 *   counts  rectangles and coverage only: each process holds a few
 *           screen rectangles, each with how many active pixels it holds
 *           (spread evenly over it); a piece of a rectangle keeps its
 *           share; a composite merges rectangles that intersect into
 *           their bounding box, the overlap counted once at the product of
 *           the two coverages (independent placement).  Runs are
 *           estimated as one per rectangle row.  Its error against the
 *           pixel rung is measured (pgsim bench composite).
 *
 * The plan, the groups, the shares and who sends what to whom are those
 * of pm_composite.h (a message per non-empty overlap of a piece and a
 * share); only what a message holds is measured on the rung's image.
 * The result is a WlPmMerge without image or held pixels (steps and
 * totals only), for pm_replay.h.
 * Cost: O(runs x stages + P x stages) for runs, O(rectangles x stages +
 * P x stages) for counts, plus, for direct send, O(P^2).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_RUNG_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_RUNG_H

#include "sim/workload/pixelmerge/pm_composite.h"

typedef enum { WL_PM_RUNG_PIXELS, WL_PM_RUNG_RUNS, WL_PM_RUNG_COUNTS } WlPmRung;

/* NULL-terminated names, indexed by WlPmRung: "pixels", "runs",
 * "counts". */
extern const char *const wl_pm_rung_names[];

/* One run of active pixels: linear indices [s, e). */
typedef struct {
    uint64_t s, e;
} WlPmRun;

/* One rectangle x0..x1, y0..y1 (inclusive) holding `active` pixels. */
typedef struct {
    guint x0, y0, x1, y1;
    double active;
} WlPmCover;

/* A process's image at the runs or counts rung: WlPmRun (sorted,
 * disjoint, not adjacent) or WlPmCover elements. */
typedef struct {
    WlPmRung rung;
    guint width, height;
    GArray *el;
} WlPmRungImage;

/* A new empty image (rung runs or counts); free with
 * wl_pm_rung_image_free(). */
WlPmRungImage *wl_pm_rung_image_new(WlPmRung rung, guint width, guint height);
void wl_pm_rung_image_free(WlPmRungImage *im);
/* Appends a span of row y, x0..x1 inclusive, rows in nondecreasing order
 * (runs: coalesced with the previous run when adjacent). */
void wl_pm_rung_add_span(WlPmRungImage *im, guint y, guint x0, guint x1);
/* Appends a rectangle holding `active` pixels (counts). */
void wl_pm_rung_add_rect(WlPmRungImage *im, const WlPmCover *r);
/* The image of an active pixel array at a rung (runs or counts: one
 * rectangle, its bounding box, holding its pixels). */
WlPmRungImage *wl_pm_rung_from_wpa(WlPmRung rung, const WlPmWpa *w);
/* Active pixels held (counts: rounded). */
uint64_t wl_pm_rung_image_active(const WlPmRungImage *im);

/* Runs `scheme` on images[n_procs] (borrowed, one rung, one size) as
 * pm_composite.h does (c's radices, bounding_rect, rle, order; the
 * operator does not matter).  Returns a new merge holding steps and
 * totals (image and held NULL); free with wl_pm_rung_merge_free().
 * *stages (may be NULL) gets the plan's stage count. */
WlPmMerge *wl_pm_rung_run(WlPmScheme scheme, const WlPmCompose *c,
                          WlPmRungImage *const *images, guint n_procs,
                          const WlPmFormat *fmt, guint *stages);
void wl_pm_rung_merge_free(WlPmMerge *m);

/* Locations of the linear range [a, b) inside box x0..x1, y0..y1
 * (inclusive) of a screen `width` wide: O(1). */
uint64_t wl_pm_box_locations(guint width, uint64_t a, uint64_t b,
                             const guint *box);

#endif
